//! 3D surfaces from files and their boundary groups, through the command as `main` runs it:
//! each named solid of an ASCII STL is a group of its own in the `.msh`, `.vtu` and `.su2`
//! (unnamed solids `wall`, `wall_2`; a binary STL's bodies likewise), each physical surface of an
//! input `.msh` (facets in none: `wall`), the built-in wing's tips apart from its side; and
//! the surfaces refused with exit 1 and one line: a body inside another, a degenerate facet,
//! an extension no reader knows.

use std::fmt::Write as _;
use std::path::Path;

use curvemesh_cli::exit::{self, Exit};
use end_to_end::{Outcome, assert_one_line_naming, cli, s, xtask_ok};
use geom_surface::Surface;
use mesh_model::Role;

/// A sphere of radius `r` about `centre` (an icosphere refined once): its triangles, facing
/// out.
fn sphere(r: f64, centre: [f64; 3]) -> Vec<[[f64; 3]; 3]> {
    let s = Surface::sphere(r, 1);
    s.facets
        .iter()
        .map(|f| {
            let p = |i: usize| {
                let q = s.nodes[f.0[i] as usize];
                std::array::from_fn(|d| q[d] + centre[d])
            };
            [p(0), p(1), p(2)]
        })
        .collect()
}

/// An ASCII STL of `solids`: a name (`""`: none) and its triangles each.
fn ascii_stl(solids: &[(&str, Vec<[[f64; 3]; 3]>)]) -> String {
    let mut text = String::new();
    for (name, tris) in solids {
        writeln!(text, "solid {name}").unwrap();
        for t in tris {
            text.push_str("  facet normal 0 0 0\n    outer loop\n");
            for p in t {
                writeln!(text, "      vertex {:?} {:?} {:?}", p[0], p[1], p[2]).unwrap();
            }
            text.push_str("    endloop\n  endfacet\n");
        }
        writeln!(text, "endsolid {name}").unwrap();
    }
    text
}

/// A binary STL of `tris`.
fn binary_stl(tris: &[[[f64; 3]; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        b.extend([0u8; 12]);
        t.iter()
            .flatten()
            .for_each(|x| b.extend((*x as f32).to_le_bytes()));
        b.extend([0u8; 2]);
    }
    b
}

/// A 3D case over `[surface] surface` with two thin layers, written in `dir`.
fn case(dir: &Path, surface: &str) -> String {
    let text = format!(
        "name = \"body\"\ndimension = 3\n\n[surface]\n{surface}\n\n\
         [layers]\nfirst_height = 0.01\ngrowth = 1.2\nmax_layers = 2\n\n[cut]\ncells = \"mixed\"\n"
    );
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    s(&path).to_string()
}

/// The groups of a meshed case: the `.msh`'s physical names, the `.su2`'s markers, the
/// `.vtu`'s `boundary_group:` arrays, and the wall facets of each group in the `.msh`.
struct Groups {
    physical: Vec<String>,
    markers: Vec<String>,
    vtu: Vec<String>,
    walls: Vec<(String, usize)>,
}

fn mesh_groups(dir: &Path, case: &str) -> Groups {
    let (msh, su2, vtu) = (dir.join("m.msh"), dir.join("m.su2"), dir.join("m.vtu"));
    let args = [
        "mesh",
        case,
        "--quiet",
        "--out",
        s(&msh),
        "--out",
        s(&su2),
        "--out",
        s(&vtu),
    ];
    assert_eq!(xtask_ok(&args), Outcome::Valid);
    let text = std::fs::read_to_string(&msh).unwrap();
    let start = text.find("$PhysicalNames\n").unwrap();
    let physical = text[start..]
        .lines()
        .skip(2)
        .take_while(|l| !l.starts_with('$'))
        .map(|l| l.splitn(3, ' ').nth(2).unwrap().trim_matches('"').into())
        .collect();
    let markers = std::fs::read_to_string(&su2)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("MARKER_TAG= ").map(String::from))
        .collect();
    let vtu = std::fs::read_to_string(&vtu).unwrap();
    let vtu = vtu
        .split("Name=\"boundary_group:")
        .skip(1)
        .map(|t| t.split('"').next().unwrap().into())
        .collect();
    let back = mesh_io::read_msh(&msh).unwrap();
    let walls = (0..back.patches.len())
        .filter(|&p| back.patches[p].role == Role::Wall)
        .map(|p| {
            (
                back.patches[p].name.clone(),
                back.patch_facets(p as u32).count(),
            )
        })
        .collect();
    Groups {
        physical,
        markers,
        vtu,
        walls,
    }
}

/// The exit of `cargo xtask mesh CASE --out DIR/x.msh` that must fail: status 1 and one
/// line naming `words`, no file written.
fn refused(dir: &Path, case: &str, words: &[&str]) -> String {
    let out = dir.join("x.msh");
    let end = exit::of_run(&curvemesh_cli::run(cli(&[
        "mesh",
        case,
        "--quiet",
        "--out",
        s(&out),
    ])));
    let Exit { code, stderr } = end;
    let line = stderr.expect("a line on stderr");
    assert_eq!(code, 1, "{line}");
    assert_one_line_naming(&line, words);
    assert!(!out.exists(), "{line}");
    line
}

#[test]
fn each_named_solid_of_an_ascii_stl_is_a_group() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stl = ascii_stl(&[
        ("left body", sphere(0.5, [-1.0, 0.0, 0.0])),
        ("right", sphere(0.5, [1.0, 0.0, 0.0])),
    ]);
    std::fs::write(d.join("two.stl"), stl).unwrap();
    let g = mesh_groups(d, &case(d, "file = \"two.stl\""));
    assert_eq!(g.physical, ["fluid", "left_body", "right", "outer"]);
    assert_eq!(g.markers, ["left_body", "right", "outer"]);
    assert_eq!(g.vtu, ["left_body", "right", "outer"]);
    let walls = [("left_body".to_string(), 80), ("right".to_string(), 80)];
    assert_eq!(g.walls, walls);
}

#[test]
fn unnamed_solids_are_walls_and_a_binary_stls_bodies_are_walls_too() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (a, b) = (sphere(0.5, [0.0; 3]), sphere(0.3, [0.0, 2.0, 0.0]));
    std::fs::write(
        d.join("u.stl"),
        ascii_stl(&[("", a.clone()), ("", b.clone())]),
    )
    .unwrap();
    let g = mesh_groups(d, &case(d, "file = \"u.stl\""));
    assert_eq!(g.markers, ["wall", "wall_2", "outer"]);
    let both: Vec<_> = a.iter().chain(&b).copied().collect();
    std::fs::write(d.join("b.stl"), binary_stl(&both)).unwrap();
    let g = mesh_groups(d, &case(d, "file = \"b.stl\""));
    // a binary STL names no solid: its two closed bodies are two groups all the same
    let walls = [("wall".to_string(), 80), ("wall_2".to_string(), 80)];
    assert_eq!(g.walls, walls);
}

/// A `.msh` surface of the triangles `tris`, triangle `i` in physical group `group[i]` (0:
/// none) of `names`, an entity per group.
fn msh_surface(tris: &[[[f64; 3]; 3]], group: &[usize], names: &[&str]) -> String {
    let mut t = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    writeln!(t, "$PhysicalNames\n{}", names.len()).unwrap();
    for (i, n) in names.iter().enumerate() {
        writeln!(t, "2 {} \"{n}\"", i + 1).unwrap();
    }
    writeln!(t, "$EndPhysicalNames\n$Entities\n0 0 {} 0", names.len() + 1).unwrap();
    for e in 0..=names.len() {
        let tags = if e == 0 { "0".into() } else { format!("1 {e}") };
        writeln!(t, "{} -9 -9 -9 9 9 9 {tags} 0", e + 1).unwrap();
    }
    let n = 3 * tris.len();
    writeln!(t, "$EndEntities\n$Nodes\n1 {n} 1 {n}\n2 1 0 {n}").unwrap();
    (1..=n).for_each(|i| writeln!(t, "{i}").unwrap());
    for p in tris.iter().flatten() {
        writeln!(t, "{:?} {:?} {:?}", p[0], p[1], p[2]).unwrap();
    }
    let blocks = names.len() + 1;
    writeln!(
        t,
        "$EndNodes\n$Elements\n{blocks} {} 1 {}",
        tris.len(),
        tris.len()
    )
    .unwrap();
    for e in 0..blocks {
        let mine: Vec<usize> = (0..tris.len()).filter(|&i| group[i] == e).collect();
        writeln!(t, "2 {} 2 {}", e + 1, mine.len()).unwrap();
        for i in mine {
            writeln!(t, "{} {} {} {}", i + 1, 3 * i + 1, 3 * i + 2, 3 * i + 3).unwrap();
        }
    }
    t + "$EndElements\n"
}

#[test]
fn each_physical_surface_of_a_msh_is_a_group_and_the_rest_wall() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let tris = sphere(0.5, [0.0; 3]);
    // the upper half in `top`, a quarter of the rest in `patch 2`, the others in none
    let group: Vec<usize> = (0..tris.len())
        .map(|i| match tris[i].iter().map(|p| p[2]).sum::<f64>() {
            z if z > 0.0 => 1,
            _ if i % 4 == 0 => 2,
            _ => 0,
        })
        .collect();
    let text = msh_surface(&tris, &group, &["top", "patch 2"]);
    std::fs::write(d.join("body.msh"), text).unwrap();
    let g = mesh_groups(d, &case(d, "file = \"body.msh\""));
    // the groups in the order of their first triangle, each with all its triangles
    let mut order: Vec<usize> = Vec::new();
    group.iter().for_each(|&k| {
        if !order.contains(&k) {
            order.push(k);
        }
    });
    let name = |k: usize| ["wall", "top", "patch_2"][k].to_string();
    let count = |k| group.iter().filter(|&&g| g == k).count();
    let want: Vec<(String, usize)> = order.iter().map(|&k| (name(k), count(k))).collect();
    assert_eq!(g.walls, want);
    assert_eq!(g.markers.len(), 4);
    assert!(
        g.markers.contains(&"patch_2".to_string()),
        "{:?}",
        g.markers
    );
}

#[test]
fn the_wings_tips_are_groups_apart_from_its_side() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let surface = "wing = \"naca0012\"\nspan = 0.5\nfirst_height = 1e-2";
    let g = mesh_groups(d, &case(d, surface));
    assert_eq!(g.markers, ["wall", "tip-root", "tip-far", "outer"]);
    assert_eq!(
        g.physical,
        ["fluid", "wall", "tip-root", "tip-far", "outer"]
    );
    // the two caps alike, and far fewer facets than the side
    let (side, root, far) = (g.walls[0].1, g.walls[1].1, g.walls[2].1);
    assert!(root == far && 0 < root && root < side, "{:?}", g.walls);
}

#[test]
fn a_bad_span_step_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (keys, words) in [
        (
            "wing = \"naca0012\"\nspan_step = -0.1",
            &["span_step", "positive"][..],
        ),
        (
            "wing = \"naca0012\"\nspan = 2.0\nspan_step = 1e-6",
            &["span_step", "more than 10000"],
        ),
        (
            "builtin = \"sphere\"\nspan_step = 0.1",
            &["span_step applies to a wing only"],
        ),
    ] {
        refused(d, &case(d, keys), words);
    }
}

#[test]
fn a_sphere_inside_a_sphere_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stl = ascii_stl(&[
        ("shell", sphere(1.0, [0.0; 3])),
        ("inner", sphere(0.4, [0.1, 0.0, 0.0])),
    ]);
    std::fs::write(d.join("nested.stl"), stl).unwrap();
    refused(
        d,
        &case(d, "file = \"nested.stl\""),
        &[
            "nested.stl",
            "body 2 (group \"inner\", facet 80) lies inside body 1 (group \"shell\", facet 0)",
        ],
    );
}

#[test]
fn a_degenerate_facet_is_refused_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut tris = sphere(0.5, [0.0; 3]);
    // facet 3 a sliver: three corners on one line (exactly: the coordinates are binary)
    tris[2] = [[0.0; 3], [0.25, 0.0, 0.0], [0.5, 0.0, 0.0]];
    std::fs::write(d.join("flat.stl"), ascii_stl(&[("body", tris)])).unwrap();
    let line = refused(
        d,
        &case(d, "file = \"flat.stl\""),
        &["flat.stl:16: facet 3 (line 16): degenerate (zero area)"],
    );
    assert!(line.contains("on one line"), "{line}");
}

#[test]
fn an_unknown_surface_extension_names_the_formats_that_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("body.obj"), "v 0 0 0\n").unwrap();
    refused(
        d,
        &case(d, "file = \"body.obj\""),
        &["body.obj", "expected .stl or .msh"],
    );
}
