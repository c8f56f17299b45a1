//! `cargo xtask mesh` on 3D cases (`dimension = 3`), run through the binary: the built-in
//! surfaces (at a small refinement and few layers, written here as case files, so the test
//! stays fast in debug builds) to `.msh`, `.vtu`, a slice picture and the report; an STL torus
//! written by the test meshed end to end; order 2 on the sphere and the wing (every cell
//! certified, the volume closer to the true one than at P1, the wing's wall nodes on the
//! true wing); open and inverted STL files, order 3 and flags of 2D runs refused with exit 1,
//! one line and no file left behind.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Output};

const XTASK: &str = env!("CARGO_BIN_EXE_xtask");

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(XTASK)
        .arg("mesh")
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Every file below `dir` (relative names, sorted).
fn files(dir: &Path) -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    out.sort();
    out
}

fn case(dir: &Path, name: &str, surface: &str, layers: &str, cut: &str) -> String {
    case_cut(dir, name, surface, layers, &format!("cells = \"{cut}\""))
}

/// [`case`] with the `[cut]` section's lines as given.
fn case_cut(dir: &Path, name: &str, surface: &str, layers: &str, cut: &str) -> String {
    let text = format!(
        "name = \"{name}\"\ndimension = 3\n\n[surface]\n{surface}\n\n[layers]\n{layers}\n\n[cut]\n{cut}\n"
    );
    let file = format!("{name}.toml");
    std::fs::write(dir.join(&file), text).unwrap();
    file
}

/// Meshes case `file` at P2 in `dir` (its report only), which must succeed, and reads the
/// report.
fn p2_report(dir: &Path, file: &str) -> serde_json::Value {
    let o = run(
        dir,
        &[file, "--order", "2", "--report", "r.json", "--quiet"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    serde_json::from_slice(&std::fs::read(dir.join("r.json")).unwrap()).unwrap()
}

/// Runs a case to `.msh`, `.vtu`, a slice picture and the report; checks the report.
fn mesh_case(dir: &Path, file: &str, stem: &str, layers: u64) -> serde_json::Value {
    let (msh, vtu, png, json) = (
        format!("{stem}.msh"),
        format!("{stem}.vtu"),
        format!("{stem}.png"),
        format!("{stem}.json"),
    );
    let o = run(
        dir,
        &[
            file, "--out", &msh, "--out", &vtu, "--report", &json, "--png", &png, "--quiet",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{file}: {}", stderr(&o));
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join(&json)).unwrap()).unwrap();
    assert_eq!(r["dimension"], 3, "{r}");
    assert_eq!(r["layers"], layers, "{r}");
    assert_eq!(r["coverage"], 1.0, "{r}");
    assert!(r["problems"].as_array().unwrap().is_empty(), "{r}");
    assert!(
        r["volume_check"]["relative_difference"].as_f64().unwrap() <= 1e-9,
        "{r}"
    );
    let q = &r["quality"];
    assert!(q["max_dihedral_deg"].as_f64().unwrap() < 180.0, "{r}");
    // tables 5-7, and table 6 over the prisms' and hexahedra's side edges when there are any
    let layered = r["cells"]["prism"].as_u64().unwrap() + r["cells"]["hex"].as_u64().unwrap() > 0;
    let hs = q["histograms"].as_array().unwrap();
    assert_eq!(hs.len(), if layered { 4 } else { 3 }, "{r}");
    if layered {
        let (all, sides) = (&hs[1]["counts"], &hs[3]["counts"]);
        let n = |h: &serde_json::Value| -> u64 {
            h.as_array()
                .unwrap()
                .iter()
                .map(|c| c.as_u64().unwrap())
                .sum()
        };
        assert!(n(sides) > 0 && n(sides) <= n(all), "{r}");
    }
    // prisms and hexahedra: their smallest corner scaled Jacobian, positive and at most 1
    if layered {
        let sj = q["min_corner_scaled_jacobian"]["value"].as_f64().unwrap();
        assert!(sj > 0.0 && sj <= 1.0, "{r}");
    }
    for key in [
        "surface", "check", "grow", "cut", "validate", "write", "total",
    ] {
        assert!(r["timings_s"][key].is_number(), "{key}: {r}");
    }
    // a group per wall patch (`wall` on the built-ins, the solid's name on an STL) and `outer`
    // (the last front of a near-body mesh)
    let groups = r["boundary_groups"].as_object().unwrap();
    assert!(groups.len() >= 2 && groups.contains_key("outer"), "{r}");
    assert!(groups.values().all(|n| n.as_u64().unwrap() > 0), "{r}");
    // the .msh reads back as the same mesh, with the group fluid and those of the report
    let back = mesh_io::read_msh(&dir.join(&msh)).unwrap();
    let cells: u64 = ["tet", "pyramid", "prism", "hex"]
        .iter()
        .map(|k| r["cells"][k].as_u64().unwrap())
        .sum();
    assert_eq!(back.cells.len() as u64, cells);
    let text = std::fs::read_to_string(dir.join(&msh)).unwrap();
    for group in groups.keys().map(String::as_str).chain(["fluid"]) {
        let quoted = format!("\"{group}\"");
        assert!(text.contains(&quoted), "{group} missing in {msh}");
    }
    assert!(
        std::fs::read(dir.join(&png))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
    assert!(std::fs::metadata(dir.join(&vtu)).unwrap().len() > 0);
    r
}

#[test]
fn built_in_surfaces_are_meshed_end_to_end() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let layers = "first_height = 0.01\ngrowth = 1.2\nmax_layers = 3";
    let sphere = case(
        d,
        "sphere",
        "builtin = \"sphere\"\nrefinement = 1",
        layers,
        "mixed",
    );
    let r = mesh_case(d, &sphere, "sphere", 3);
    assert_eq!(r["cells"]["prism"], 3 * 80, "{r}");
    let cube = case(
        d,
        "cube",
        "builtin = \"cube\"\ndivisions = 2",
        layers,
        "tets",
    );
    let r = mesh_case(d, &cube, "cube", 3);
    assert_eq!(r["cells"]["hex"], 0, "{r}");
    assert!(r["cells"]["tet"].as_u64().unwrap() > 0, "{r}");
    let step = case(
        d,
        "step",
        "builtin = \"step\"",
        "first_height = 2e-3\ngrowth = 1.2\nmax_layers = 2",
        "mixed",
    );
    mesh_case(d, &step, "step", 2);
    // a slice along x, coloured by layer, zoomed on the wall
    let o = run(
        d,
        &[
            &sphere,
            "--out",
            "x.msh",
            "--png",
            "x.png@-0.2,0.8,0.2,1.1",
            "--slice",
            "x=0.01",
            "--colour",
            "layer",
            "--quiet",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// An ASCII STL torus (major radius 1, minor 0.3), facets counter-clockwise seen from outside
/// (or inside when `inverted`); `open` leaves one facet out.
fn torus_stl(inverted: bool, open: bool) -> String {
    let (n, m) = (24, 12);
    let at = |i: usize, j: usize| {
        let (u, v) = (
            std::f64::consts::TAU * (i % n) as f64 / n as f64,
            std::f64::consts::TAU * (j % m) as f64 / m as f64,
        );
        let r = 1.0 + 0.3 * v.cos();
        [r * u.cos(), r * u.sin(), 0.3 * v.sin()]
    };
    let mut s = String::from("solid torus\n");
    let mut facet = |t: [[f64; 3]; 3]| {
        let t = if inverted { [t[0], t[2], t[1]] } else { t };
        s.push_str(" facet normal 0 0 0\n  outer loop\n");
        for p in t {
            let _ = writeln!(s, "   vertex {} {} {}", p[0], p[1], p[2]);
        }
        s.push_str("  endloop\n endfacet\n");
    };
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if !(open && i == 0 && j == 0) {
                facet([a, b, c]);
            }
            facet([a, c, d]);
        }
    }
    s.push_str("endsolid torus\n");
    s
}

#[test]
fn an_stl_torus_is_meshed_and_bad_stl_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let layers = "first_height = 0.01\ngrowth = 1.2\nmax_layers = 2";
    std::fs::write(d.join("torus.stl"), torus_stl(false, false)).unwrap();
    let torus = case(d, "torus", "file = \"torus.stl\"", layers, "mixed");
    let r = mesh_case(d, &torus, "torus", 2);
    assert_eq!(r["cells"]["prism"], 2 * 24 * 12 * 2, "{r}");
    // the STL's solid names its wall group
    assert_eq!(r["boundary_groups"]["torus"], 2 * 24 * 12, "{r}");

    let bad = tempfile::tempdir().unwrap();
    let b = bad.path();
    for (name, stl, says) in [
        ("open", torus_stl(false, true), "not closed"),
        ("inverted", torus_stl(true, false), "inverted"),
    ] {
        std::fs::write(b.join(format!("{name}.stl")), stl).unwrap();
        let file = case(b, name, &format!("file = \"{name}.stl\""), layers, "mixed");
        let before = files(b);
        let o = run(
            b,
            &[
                &file,
                "--out",
                "out/x.msh",
                "--report",
                "out/x.json",
                "--png",
                "p.png",
            ],
        );
        assert_eq!(o.status.code(), Some(1), "{name}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert!(
            e.contains(says) && e.contains(&format!("{name}.stl")),
            "{e}"
        );
        assert_eq!(files(b), before, "{name}: a file was left behind");
    }
}

#[test]
fn what_3d_does_not_do_yet_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let layers = "max_layers = 2";
    let sphere = case(
        d,
        "s",
        "builtin = \"sphere\"\nrefinement = 1",
        layers,
        "mixed",
    );
    let before = files(d);
    for (args, says) in [
        (
            vec![sphere.as_str(), "--triangles"],
            "--triangles applies to 2D",
        ),
        (
            vec![sphere.as_str(), "--png", "a.png", "--slice", "w=1"],
            "x=C, y=C or z=C",
        ),
        (
            vec!["naca0012", "--slice", "z=0", "--png", "a.png"],
            "applies to 3D cases",
        ),
    ] {
        let o = run(d, &args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert!(e.contains(says), "{args:?}: {e}");
    }
    let bad_key = std::fs::read_to_string(d.join(&sphere))
        .unwrap()
        .replace("[cut]", "[cut]\nfoo = 1");
    std::fs::write(d.join("k.toml"), bad_key).unwrap();
    let o = run(d, &["k.toml"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("foo"), "{}", stderr(&o));
    std::fs::remove_file(d.join("k.toml")).unwrap();
    assert_eq!(files(d), before);
    // the list names the 3D cases
    let list = String::from_utf8_lossy(&run(d, &["--list"]).stdout).into_owned();
    for name in ["sphere", "cube", "step"] {
        assert!(list.lines().any(|l| l.starts_with(name)), "{list}");
    }
}

/// `[layers] max_aspect` holds the layers' heights (the report says so, the front stays
/// nearer the wall than without it); a negative or non-finite value is refused by name.
#[test]
fn a_layer_height_limit_from_the_case_file_holds_the_heights() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let surface = "builtin = \"sphere\"\nrefinement = 1";
    let layers = "first_height = 0.05\ngrowth = 1.3\nmax_layers = 6";
    let free = case(d, "free", surface, layers, "mixed");
    let held = case(
        d,
        "held",
        surface,
        &format!("{layers}\nmax_aspect = 0.1"),
        "mixed",
    );
    let volume = |r: &serde_json::Value| r["volume"].as_f64().unwrap();
    let notes = |r: &serde_json::Value| r["notes"].to_string();
    let r_free = mesh_case(d, &free, "free", 6);
    let r_held = mesh_case(d, &held, "held", 6);
    assert!(!notes(&r_free).contains("held to"), "{}", notes(&r_free));
    assert!(notes(&r_held).contains("held to 0.1"), "{}", notes(&r_held));
    assert!(
        volume(&r_held) < 0.8 * volume(&r_free),
        "{} {}",
        volume(&r_held),
        volume(&r_free)
    );
    // each bad value of the 3D layer keys is refused in one line naming the key
    let bad_values = [
        ("max_aspect", "-1.0"),
        ("max_aspect", "nan"),
        ("max_aspect", "inf"),
        ("stand_off", "-0.1"),
        ("stand_off", "1.0"),
        ("stand_off", "nan"),
        ("smoothing", "101"),
        ("smoothing", "-1"),
        ("merge_rows", "-0.5"),
        ("merge_rows", "nan"),
    ];
    for (key, bad) in bad_values {
        let text = std::fs::read_to_string(d.join(&held))
            .unwrap()
            .replace("max_aspect = 0.1", &format!("{key} = {bad}"));
        std::fs::write(d.join("bad.toml"), text).unwrap();
        let o = run(d, &["bad.toml"]);
        assert_eq!(o.status.code(), Some(1), "{key} = {bad}");
        let e = stderr(&o);
        assert_eq!(e.trim().lines().count(), 1, "{key} = {bad}: {e}");
        assert!(
            e.contains(&format!("[layers] {key}")) || e.contains(key),
            "{key} = {bad}: {e}"
        );
    }
}

/// `[cut] max_lean_deg`: the mixed cut keeps no prism whose side edge leans more than that
/// off its front's normal (table 6 over the kept layers stays under it), cutting those cells
/// into tetrahedra and pyramids; 180 keeps every prism; a bad value is refused by name.
#[test]
fn the_mixed_cut_keeps_no_prism_leaning_over_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let surface = "builtin = \"sphere\"\nrefinement = 2";
    let layers = "first_height = 0.01\ngrowth = 1.2\nmax_layers = 4";
    let plain = case(d, "plain", surface, layers, "mixed");
    let with_limit = |name: &str, limit: &str| {
        let file = case(d, name, surface, layers, "mixed");
        let text = std::fs::read_to_string(d.join(&file)).unwrap();
        let text = text.replace("\"mixed\"", &format!("\"mixed\"\nmax_lean_deg = {limit}"));
        std::fs::write(d.join(&file), text).unwrap();
        file
    };
    let (lean, all) = (with_limit("lean", "0.3"), with_limit("all", "180"));
    let r_plain = mesh_case(d, &plain, "plain", 4);
    let r_lean = mesh_case(d, &lean, "lean", 4);
    mesh_case(d, &all, "all", 4);
    let read = |f: &str| std::fs::read(d.join(f)).unwrap();
    assert!(
        read("all.msh") == read("plain.msh"),
        "180 keeps every prism"
    );
    let cells = |r: &serde_json::Value, k: &str| r["cells"][k].as_u64().unwrap();
    let hs = |r: &serde_json::Value| r["quality"]["histograms"].as_array().unwrap().clone();
    // the plain cut (the default limit, 30 degrees): every cell a prism, some side edges
    // over 0.3 degrees
    assert_eq!(
        cells(&r_plain, "tet") + cells(&r_plain, "pyramid"),
        0,
        "{r_plain}"
    );
    assert!(
        hs(&r_plain)[3]["max_deg"].as_f64().unwrap() > 0.3,
        "{r_plain}"
    );
    // the limit at 0.3 degrees: those cells cut, the prisms left within it
    assert!(cells(&r_lean, "tet") > 0, "{r_lean}");
    assert!(
        cells(&r_lean, "prism") < cells(&r_plain, "prism"),
        "{r_lean}"
    );
    if let Some(h) = hs(&r_lean).get(3) {
        assert!(h["max_deg"].as_f64().unwrap() <= 0.3, "{r_lean}");
    }
    for bad in ["0.0", "-5.0", "181.0", "nan"] {
        let text = std::fs::read_to_string(d.join(&lean))
            .unwrap()
            .replace("max_lean_deg = 0.3", &format!("max_lean_deg = {bad}"));
        std::fs::write(d.join("bad.toml"), text).unwrap();
        let o = run(d, &["bad.toml"]);
        assert_eq!(o.status.code(), Some(1), "max_lean_deg = {bad}");
        let e = stderr(&o);
        assert_eq!(e.trim().lines().count(), 1, "{bad}: {e}");
        assert!(e.contains("[cut] max_lean_deg"), "{bad}: {e}");
    }
}

/// The `naca0012` wing (surface and layers from 1e-3, growth 1.3) with the `[surface]` keys
/// `surface`, `layers` layers and the cut `cut`, meshed by [`mesh_case`].
fn mesh_wing(d: &Path, surface: &str, layers: u64, cut: &str) -> serde_json::Value {
    let wing = case(
        d,
        "wing",
        &format!("wing = \"naca0012\"\nfirst_height = 1e-3\n{surface}"),
        &format!("first_height = 1e-3\ngrowth = 1.3\nmax_layers = {layers}"),
        cut,
    );
    mesh_case(d, &wing, "wing", layers)
}

#[test]
fn the_wing_of_a_2d_case_is_meshed_and_bad_wing_keys_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let r = mesh_wing(d, "span = 1.0", 3, "tets");
    assert!(r["cells"]["tet"].as_u64().unwrap() > 0, "{r}");
    let before = files(d);
    for (surface, says) in [
        ("wing = \"naca0012\"\nspan = -1.0", "span"),
        ("wing = \"nothing-here\"", "nothing-here"),
        ("wing = \"naca0012\"\nradius = 2.0", "radius"),
        ("builtin = \"sphere\"\nspan = 2.0", "span"),
        ("builtin = \"sphere\"\nfirst_height = 1e-3", "first_height"),
        ("wing = \"naca0012\"\nfirst_height = 0.0", "first_height"),
        ("wing = \"sphere\"", "sphere"),
        ("wing = \"naca0012\"\ncap = \"round\"", "`fill` or `layers`"),
        ("builtin = \"sphere\"\ncap = \"fill\"", "cap"),
    ] {
        let bad = case(d, "bad", surface, "max_layers = 2", "tets");
        let o = run(d, &[&bad, "--quiet"]);
        assert_eq!(o.status.code(), Some(1), "{surface}: {}", stderr(&o));
        let err = stderr(&o);
        assert_eq!(err.trim().lines().count(), 1, "{surface}: {err}");
        assert!(err.contains(says), "{surface}: {err}");
        std::fs::remove_file(d.join(&bad)).unwrap();
        assert_eq!(files(d), before);
    }
}

/// The wing's mixed mesh over a quad side and the isotropic caps (the default): in its first
/// layers every prism and hexahedron corner has a scaled Jacobian of at least 0.2 (issue 13's
/// bar at the tips and the trailing edge; 0.0063 at the caps and 0.0054 at the trailing edge
/// before, with the caps' own 2D layers and a triangulated side).
#[test]
fn the_wing_mixed_over_quads_has_corner_sj_above_0_2_at_tips_and_trailing_edge() {
    let tmp = tempfile::tempdir().unwrap();
    let r = mesh_wing(tmp.path(), "span = 2.0\ntriangles = false", 2, "mixed");
    let sj = &r["quality"]["min_corner_scaled_jacobian"];
    assert!(sj["value"].as_f64().unwrap() >= 0.2, "{sj}");
    for patch in ["wall", "tip-root", "tip-far"] {
        assert!(sj["by_wall_patch"][patch].as_f64().unwrap() >= 0.2, "{sj}");
    }
}

/// The wing's tip caps over a quad side keep a corner scaled Jacobian of 0.2 in the layers
/// where the cap's cells across the trailing edge's thin strip are stretched most (layers
/// 3–4: 0.178 before the strip's triangles were paired into quads, `docs/3d.md`).
#[test]
fn the_wing_caps_over_a_quad_side_keep_corner_sj_above_0_2_in_five_layers() {
    let tmp = tempfile::tempdir().unwrap();
    let r = mesh_wing(tmp.path(), "span = 2.0\ntriangles = false", 5, "mixed");
    let sj = &r["quality"]["min_corner_scaled_jacobian"];
    for patch in ["wall", "tip-root", "tip-far"] {
        assert!(sj["by_wall_patch"][patch].as_f64().unwrap() >= 0.2, "{sj}");
    }
}

/// The wing with quads on its side grows past the layers where it failed (11, before each
/// wall patch's normal was weighted alike and a layer still invalid dropped the merges of
/// its failing cells; 28, before its layers' heights were held to a quarter of the front's
/// mean edge, `docs/3d.md`): 30 layers, every column full, the mixed cut conforming with the
/// volume kept, its tets under 160°, every prism and hexahedron corner at a scaled Jacobian
/// of 0.2 over every wall patch, and the report saying where the heights were held.
#[test]
fn the_wing_with_quads_on_its_side_grows_30_layers() {
    let tmp = tempfile::tempdir().unwrap();
    let r = mesh_wing(tmp.path(), "span = 2.0\ntriangles = false", 30, "mixed");
    let max = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
    assert!(max <= 160.0, "max dihedral {max}");
    let sj = &r["quality"]["min_corner_scaled_jacobian"];
    for patch in ["wall", "tip-root", "tip-far"] {
        assert!(sj["by_wall_patch"][patch].as_f64().unwrap() >= 0.2, "{sj}");
    }
    let notes = r["notes"].as_array().unwrap();
    let held = notes
        .iter()
        .filter_map(|n| n.as_str())
        .find(|n| n.starts_with("layer heights held to 0.26"));
    assert!(held.is_some(), "{r}");
}

/// The quad-side wing at the dissertation's finer cases 2 and 3 (the surface's spacing and
/// the first layer 1e-4, growth 1.4; then the first layer 1e-5), 17 layers: where the
/// layers reach the trailing edge's 0.00084 width its thin quads merge, and merged one
/// side only (the pairs taken edge by edge, not along their rows) they left 1° triangles:
/// case 2 failed in layer 16 (an inverted cell at the trailing edge next to the root tip),
/// case 3 kept a prism corner of 0.016 there (`docs/3d.md`). Now both grow, every column
/// full, the tets under 150° and every prism and hexahedron corner at 0.2 over every patch;
/// with the rows off (`merge_rows = 0`) case 2's trailing-edge columns stop early.
#[test]
fn the_finer_quad_wings_merge_their_trailing_edge_along_its_rows() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let wing = "wing = \"naca0012\"\nfirst_height = 1e-4\nspan = 2.0\ntriangles = false";
    let off = case(
        d,
        "off",
        wing,
        "first_height = 1e-4\ngrowth = 1.4\nmax_layers = 17\nmerge_rows = 0",
        "mixed",
    );
    // with the rows off, columns at the trailing edge cannot take their next layers: they
    // stop there and the rest grow on (the whole run failed in layer 16 before columns
    // could stop)
    let o = run(d, &[&off, "--quiet", "--report", "off.json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("off.json")).unwrap()).unwrap();
    let columns = &r["columns"];
    assert!(
        columns["full"].as_u64() < columns["wall_nodes"].as_u64(),
        "{columns}"
    );
    let x = columns["first_stopped"][0]["at"][0].as_f64().unwrap();
    assert!(
        x > 0.99,
        "the first stopped column is not at the trailing edge: {columns}"
    );
    for (n, first) in [(2, "1e-4"), (3, "1e-5")] {
        let file = case(
            d,
            &format!("quad{n}"),
            wing,
            &format!("first_height = {first}\ngrowth = 1.4\nmax_layers = 17"),
            "mixed",
        );
        let r = mesh_case(d, &file, &format!("quad{n}"), 17);
        let max = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
        assert!(max <= 150.0, "case {n}: max dihedral {max}");
        let sj = &r["quality"]["min_corner_scaled_jacobian"];
        for patch in ["wall", "tip-root", "tip-far"] {
            assert!(
                sj["by_wall_patch"][patch].as_f64().unwrap() >= 0.2,
                "case {n}: {sj}"
            );
        }
    }
}

/// The built-in step (15 layers) cut into tetrahedra keeps every dihedral angle under 160°
/// (issue 13's bar; 163.4° before the cut was refined cell by cell).
#[test]
fn the_step_cut_into_tets_stays_under_160_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let step = case(
        d,
        "step",
        "builtin = \"step\"",
        "first_height = 2e-3\ngrowth = 1.2\nmax_layers = 15",
        "tets",
    );
    let r = mesh_case(d, &step, "step", 15);
    let max = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
    assert!(max <= 160.0, "max dihedral {max}: {r}");
}

/// The step (15 layers of the geometric stack, mixed cells) with the cut key
/// `[cut] min_corner_sj = 0.5` (an override: the default is 0.2) meets issue 13's two bars for
/// the layer cells it keeps, at first heights of 1e-3, 2e-3 and 3e-3: the smallest corner
/// scaled Jacobian of its prisms and hexahedra above 0.5 (0.345, 0.175 and 0.008 without the
/// key) and every side edge of them within 30° of the wall's normal (table 6 over the kept
/// cells), with every wall node's full stack, the squeezed cells by the tower's foot cut into
/// tetrahedra and pyramids under 150° and the report saying how many.
#[test]
fn the_step_keeps_its_corners_above_one_half_and_its_edges_within_30_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // the built-in case sets no expert key (the default is 0.2); 0.5 is asked for here
    let builtin = include_str!("../../../fixtures/cases/step.toml");
    assert!(!builtin.contains("min_corner_sj"), "{builtin}");
    for first in ["1e-3", "2e-3", "3e-3"] {
        let layers = format!("first_height = {first}\ngrowth = 1.2\nmax_layers = 15");
        let step = case_cut(
            d,
            "step",
            "builtin = \"step\"",
            &layers,
            "cells = \"mixed\"\nmin_corner_sj = 0.5",
        );
        let r = mesh_case(d, &step, "step", 15);
        let q = &r["quality"];
        let sj = q["min_corner_scaled_jacobian"]["value"].as_f64().unwrap();
        assert!(sj >= 0.5, "first height {first}: corner SJ {sj}: {r}");
        let kept = &q["histograms"][3];
        assert_eq!(kept["name"], "layer extrusion edge deviation", "{r}");
        assert_eq!(kept["counts"][3], 0, "first height {first}: {r}");
        assert!(kept["max_deg"].as_f64().unwrap() <= 30.0, "{r}");
        let max = q["max_dihedral_deg"].as_f64().unwrap();
        assert!(
            max <= 150.0,
            "first height {first}: max dihedral {max}: {r}"
        );
        assert!(
            r["notes"]
                .to_string()
                .contains("corner scaled Jacobian below 0.5"),
            "{r}"
        );
        // the geometric stack, not held: no note of held heights
        assert!(
            !r["notes"].to_string().contains("layer heights held"),
            "{r}"
        );
    }
    // without the key, the 2e-3 step keeps squeezed hexahedra
    let layers = "first_height = 2e-3\ngrowth = 1.2\nmax_layers = 15";
    let plain = case(d, "plain", "builtin = \"step\"", layers, "mixed");
    let r = mesh_case(d, &plain, "plain", 15);
    let sj = r["quality"]["min_corner_scaled_jacobian"]["value"]
        .as_f64()
        .unwrap();
    assert!(sj < 0.5, "{r}");
    // bad values are refused by name
    for bad in ["-0.1", "1.0", "nan"] {
        let k = case_cut(
            d,
            "k",
            "builtin = \"step\"",
            "max_layers = 2",
            &format!("cells = \"mixed\"\nmin_corner_sj = {bad}"),
        );
        let o = run(d, &[&k, "--out", "k.msh"]);
        assert_eq!(o.status.code(), Some(1), "{bad}");
        assert!(stderr(&o).contains("[cut] min_corner_sj"), "{}", stderr(&o));
        std::fs::remove_file(d.join(&k)).unwrap();
    }
}

/// A step whose layers are too thick for its concave edges (its height limit taken off)
/// fails in one line that names the layer, the wall facet and where that facet is, exits 1
/// and writes nothing.
#[test]
fn a_layer_that_cannot_grow_is_named_with_its_place() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let step = case(
        d,
        "step",
        "builtin = \"step\"",
        "first_height = 8e-3\ngrowth = 1.2\nmax_layers = 15\nmax_aspect = 0",
        "mixed",
    );
    let o = run(d, &[&step, "--out", "step.msh", "--report", "r.json"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert_eq!(e.trim().lines().count(), 1, "{e}");
    // the columns that cannot grow stop; so many do here that the coverage falls below
    // [layers] min_coverage, and the line says where the first stopped and why
    assert!(
        e.contains("is below [layers] min_coverage") && e.contains("at (0.3000, 0.3000, "),
        "{e}"
    );
    assert_eq!(files(d), vec![step]);
}

/// Runs `file` at `order` to a `.msh` and the report; returns the report.
fn at_order(dir: &Path, file: &str, order: &str) -> serde_json::Value {
    let (msh, json) = (format!("p{order}.msh"), format!("p{order}.json"));
    let o = run(
        dir,
        &[
            file, "--order", order, "--out", &msh, "--report", &json, "--quiet",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{file} P{order}: {}", stderr(&o));
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join(&json)).unwrap()).unwrap();
    assert!(r["problems"].as_array().unwrap().is_empty(), "{r}");
    assert_eq!(r["order"], order.parse::<u64>().unwrap(), "{r}");
    r
}

/// The certified figures of a P2 report: every cell valid, decided, with a positive bound.
fn assert_certified(r: &serde_json::Value) {
    let q = &r["quality"];
    assert_eq!(q["invalid_cells"], 0, "{r}");
    assert_eq!(q["certified"], true, "{r}");
    assert!(q["min_scaled_jacobian"].as_f64().unwrap() > 0.0, "{r}");
    assert!(
        r["volume_check"]["relative_difference"].as_f64().unwrap() <= 1e-9,
        "{r}"
    );
}

#[test]
fn the_sphere_at_p2_is_certified_and_closer_to_the_true_volume() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for cut in ["mixed", "tets"] {
        let file = case(
            d,
            cut,
            "builtin = \"sphere\"\nrefinement = 2",
            "first_height = 0.03\ngrowth = 1.2\nmax_layers = 3",
            cut,
        );
        let p1 = at_order(d, &file, "1");
        let p2 = at_order(d, &file, "2");
        assert_certified(&p2);
        assert_eq!(p1["cells"], p2["cells"], "{p2}");
        // each order against the true shell under its own outer front (the front may curve
        // where the cells below it need it): the volume the front's facets enclose, minus
        // the true ball; P1's wall is the icosphere, P2's is on the sphere
        let ball = 4.0 / 3.0 * std::f64::consts::PI;
        let error = |r: &serde_json::Value, msh: &str| {
            let shell = front_volume(&d.join(msh)) - ball;
            (r["volume"].as_f64().unwrap() - shell).abs() / shell
        };
        let (e1, e2) = (error(&p1, "p1.msh"), error(&p2, "p2.msh"));
        assert!(
            e2 < 0.1 * e1,
            "{cut}: relative volume error P1 {e1:e}, P2 {e2:e}"
        );
        assert!(p2["notes"].to_string().contains("true sphere"), "{p2}");
        assert!(p2["curved_edge_fraction"].as_f64().unwrap() > 0.0, "{p2}");
    }
}

#[test]
fn the_wing_at_p2_has_its_side_nodes_on_the_true_wing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let span = 1.0;
    let file = case(
        d,
        "wing2",
        &format!("wing = \"naca0012\"\nspan = {span}"),
        "first_height = 2e-3\ngrowth = 1.3\nmax_layers = 2",
        "tets",
    );
    // thin cells at the tips' rims (the caps' 2D layers under the first 3D layer) may be
    // left invalid by the curving: then the run fails validation (exit 2) naming them, and
    // is never a success
    let o = run(
        d,
        &[
            &file, "--order", "2", "--out", "p2.msh", "--report", "p2.json", "--quiet",
        ],
    );
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("p2.json")).unwrap()).unwrap();
    let invalid = r["quality"]["invalid_cells"].as_u64().unwrap();
    match o.status.code() {
        Some(0) => assert_certified(&r),
        Some(2) => {
            assert!(invalid > 0, "{r}");
            assert!(stderr(&o).contains("invalid by the certified Jacobian check"));
        }
        c => panic!("exit {c:?}: {}", stderr(&o)),
    }
    assert!(r["notes"].to_string().contains("true wing"), "{r}");
    let mesh = mesh_io::read_msh(&d.join("p2.msh")).unwrap();
    assert_eq!(mesh.order, 2);
    let section = curvemesh::load::load_2d("naca0012").unwrap();
    let (_, shape) = curvemesh::wing::wing_surface(&section, span, true).unwrap();
    let (mut side, mut cap) = (0, 0);
    for (f, facet) in mesh.boundary.iter().enumerate() {
        let patch = &mesh.patches[mesh.boundary_patch[f] as usize];
        if patch.role != mesh_model::Role::Wall {
            continue;
        }
        let corners = facet.corners();
        let z: Vec<f64> = corners.iter().map(|&n| mesh.nodes[n as usize][2]).collect();
        let on_cap = z.iter().all(|&z| z == 0.0) || z.iter().all(|&z| z == span);
        for &n in &facet.nodes[corners.len()..] {
            let p = mesh.nodes[n as usize];
            if on_cap {
                // the tip caps are flat
                assert!(p[2] == 0.0 || p[2] == span, "{p:?}");
                cap += 1;
            } else {
                let (_, _, dist) = shape
                    .curve
                    .0
                    .closest_point(geom_curve::Point2::new(p[0], p[1]));
                assert!(dist < 1e-9, "side node {n} at {p:?} off the wing by {dist}");
                side += 1;
            }
        }
    }
    assert!(side > 0 && cap > 0, "{side} {cap}");
}

/// The wing with quads on its side cut into mixed cells at P2, its first layer thick enough for
/// pyramids with an edge on the wall: those pyramids are curved onto the true wing (refused
/// before the 14-node pyramid was certified) and every cell is certified.
#[test]
fn the_mixed_wing_at_p2_is_certified_with_curved_pyramids() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let file = case(
        d,
        "wingmix",
        "wing = \"naca0012\"\nfirst_height = 1e-3\nspan = 1.0\ntriangles = false",
        "first_height = 0.02\ngrowth = 1.3\nmax_layers = 3",
        "mixed",
    );
    let r = at_order(d, &file, "2");
    assert_certified(&r);
    let mesh = mesh_io::read_msh(&d.join("p2.msh")).unwrap();
    let pyramid14 = mesh_model::CellType::new(mesh_model::Shape::Pyramid, 2);
    let curved = mesh
        .cells
        .iter()
        .filter(|c| c.ty == pyramid14)
        .filter(|c| {
            let x = |k: usize| mesh.nodes[c.nodes[k] as usize];
            mesh_model::Shape::Pyramid
                .edges()
                .iter()
                .enumerate()
                .any(|(k, e)| {
                    (0..3).any(|i| (x(5 + k)[i] - 0.5 * (x(e[0])[i] + x(e[1])[i])).abs() > 1e-9)
                })
        })
        .count();
    assert!(curved > 100, "{curved} curved pyramids");
}

/// The volume the outer front (the `farfield` facets) of the mesh in `msh` encloses, along
/// the facets' curved shape.
fn front_volume(msh: &Path) -> f64 {
    let mut mesh = mesh_io::read_msh(msh).unwrap();
    let all = std::mem::take(&mut mesh.boundary);
    for (f, facet) in all.iter().enumerate() {
        let patch = &mesh.patches[mesh.boundary_patch[f] as usize];
        if patch.role == mesh_model::Role::Farfield {
            mesh.boundary.push(facet.ty, facet.nodes);
        }
    }
    jacobian_check::enclosed_volume(&mesh).unwrap()
}

/// The built-in wing (case 1 of tables 5–7, 45 layers, tets) keeps every dihedral angle
/// under 150°, issue 13's aim (its bar is 160°; 179.7° before the growth's repair of
/// capped cells, `afsf3d::repair`, 154.6° before `topo-cut`'s first refining pass went two
/// levels deep, 151.7° before its third pass, four levels deep over the cells still over
/// 150°), with every wall node's full column, and almost every extrusion
/// edge within table 6's 30° of its front's normal (7 over 30°; 139 before merged children
/// leaning over 30° were stood upright, `afsf3d`'s `upright`). Cases 2 and 3 (152.3°,
/// 153.2°) take too long for a debug test; `docs/3d.md` gives their commands.
#[test]
fn the_built_in_wing_cut_into_tets_stays_under_150_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let r = mesh_case(dir.path(), "wing", "wing", 45);
    let max = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
    assert!(max <= 150.0, "max dihedral {max}");
    let table6 = r["quality"]["histograms"]
        .as_array()
        .unwrap()
        .iter()
        .find(|h| h["name"] == "extrusion edge deviation")
        .unwrap();
    assert_eq!(
        table6["upper_edges_deg"][2].as_f64(),
        Some(30.0),
        "{table6}"
    );
    let over_30 = table6["counts"][3].as_u64().unwrap();
    assert!(
        over_30 <= 15,
        "{over_30} extrusion edges over 30°: {table6}"
    );
}

/// The built-in wing (case 1, 45 layers) cut into mixed cells keeps its tetrahedra under
/// 150°, the aim: `topo-cut`'s mixed refining may keep a side between two cut cells
/// whole (157.0° before, one tetrahedron over 150°; cases 2 and 3: 154.4° and 163.3° before,
/// 150.0° now, `docs/3d.md`).
#[test]
fn the_built_in_wing_cut_into_mixed_cells_stays_under_150_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let file = case(
        d,
        "wingmix45",
        "wing = \"naca0012\"\nspan = 2.0\nfirst_height = 1e-3\ntriangles = true",
        "first_height = 1e-3\ngrowth = 1.3\nmax_layers = 45",
        "mixed",
    );
    let r = mesh_case(d, &file, "wingmix45", 45);
    let max = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
    assert!(max <= 150.0, "max dihedral {max}");
    assert!(r["cells"]["pyramid"].as_u64().unwrap() > 0, "{r}");
}

/// The wing's case 2 (surface and layers from 1e-4, growth 1.4) cut mixed, 8 layers over a
/// span of 0.5, at P2: every cell certified. Before pyramids were curved above the wall and
/// the 3D curving had its repair of the tip rims, 83 cells were invalid and the run failed.
#[test]
fn the_mixed_wing_of_case_2_is_certified_at_p2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let wing = case(
        d,
        "wing2",
        "wing = \"naca0012\"\nspan = 0.5\nfirst_height = 1e-4",
        "first_height = 1e-4\ngrowth = 1.4\nmax_layers = 8",
        "mixed",
    );
    let r = p2_report(d, &wing);
    let q = &r["quality"];
    assert_eq!(q["invalid_cells"], 0, "{r}");
    assert_eq!(q["certified"], true, "{r}");
    assert!(r["cells"]["pyramid"].as_u64().unwrap() > 0, "{r}");
    let note = r["notes"][0].as_str().unwrap();
    assert!(note.contains("mended by the repair (0 not)"), "{note}");
    assert!(
        !note.contains("; 0 cells the marching left invalid"),
        "{note}"
    );
}

/// The same triangulated wing of case 2 with `[cut] min_corner_sj = 0.2`: its sliver prisms
/// (over the side's thin triangles at the trailing edge, corner scaled Jacobians down to
/// 0.0006 at the wall) are cut, every prism kept has its corners at 0.2 or more on every wall
/// patch, the tetrahedra stay under 150°, and at P2 every cell is certified.
#[test]
fn the_mixed_wing_cuts_its_sliver_prisms_below_the_corner_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let surface = "wing = \"naca0012\"\nspan = 0.5\nfirst_height = 1e-4";
    let layers = "first_height = 1e-4\ngrowth = 1.4\nmax_layers = 8";
    let wing = case_cut(
        d,
        "wing2",
        surface,
        layers,
        "cells = \"mixed\"\nmin_corner_sj = 0.2",
    );
    let r = p2_report(d, &wing);
    let q = &r["quality"];
    assert_eq!(q["certified"], true, "{r}");
    assert!(q["max_dihedral_deg"].as_f64().unwrap() <= 150.0, "{r}");
    let sj = &q["min_corner_scaled_jacobian"];
    for patch in ["wall", "tip-root", "tip-far"] {
        assert!(sj["by_wall_patch"][patch].as_f64().unwrap() >= 0.2, "{sj}");
    }
    assert!(r["cells"]["prism"].as_u64().unwrap() > 0, "{r}");
    assert!(
        r["notes"]
            .to_string()
            .contains("corner scaled Jacobian below 0.2"),
        "{r}"
    );
}

/// The wing's case 2 cut mixed with only 4 layers (prisms at the tip rims one layer under the
/// front) at P2: every cell certified. The single-cell repair left 2 cells invalid there
/// (each choice for one broke its thin neighbour); the repair now mends such a neighbour in
/// turn (a chain of two).
#[test]
fn the_mixed_wing_of_case_2_at_four_layers_is_certified_at_p2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let wing = case(
        d,
        "wing4",
        "wing = \"naca0012\"\nspan = 0.5\nfirst_height = 1e-4",
        "first_height = 1e-4\ngrowth = 1.4\nmax_layers = 4",
        "mixed",
    );
    let r = p2_report(d, &wing);
    assert_eq!(r["quality"]["certified"], true, "{r}");
    assert_eq!(r["quality"]["invalid_cells"], 0, "{r}");
    let note = r["notes"][0].as_str().unwrap();
    assert!(note.contains("mended by the repair (0 not)"), "{note}");
}
