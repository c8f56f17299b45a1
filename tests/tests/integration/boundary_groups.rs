//! One boundary group per body: every wall loop is its own physical group in the `.msh` and
//! its own marker in the `.su2`, named after the loop, beside `farfield`; `merge_walls = true`
//! makes them one `wall`.

use std::path::Path;

use end_to_end::{Outcome, read_json, s, xtask_ok};
use mesh_model::Role;

fn mesh(case: &str, dir: &Path) -> (String, String, mesh_model::Mesh) {
    let (msh, su2) = (dir.join("m.msh"), dir.join("m.su2"));
    let args = [
        "mesh",
        case,
        "--quiet",
        "--order",
        "2",
        "--out",
        s(&msh),
        "--out",
        s(&su2),
    ];
    let outcome = xtask_ok(&args);
    assert_eq!(outcome, Outcome::Valid);
    (
        std::fs::read_to_string(&msh).unwrap(),
        std::fs::read_to_string(&su2).unwrap(),
        mesh_io::read_msh(&msh).unwrap(),
    )
}

fn physical_names(msh: &str) -> Vec<String> {
    let start = msh.find("$PhysicalNames\n").unwrap();
    msh[start..]
        .lines()
        .skip(2)
        .take_while(|l| !l.starts_with('$'))
        .map(|l| {
            l.splitn(3, ' ')
                .nth(2)
                .unwrap()
                .trim_matches('"')
                .to_string()
        })
        .collect()
}

fn markers(su2: &str) -> Vec<&str> {
    su2.lines()
        .filter_map(|l| l.strip_prefix("MARKER_TAG= "))
        .collect()
}

#[test]
fn every_body_is_a_group_of_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let (msh, su2, back) = mesh("two-element", dir.path());
    assert_eq!(physical_names(&msh), ["fluid", "main", "flap", "farfield"]);
    assert_eq!(markers(&su2), ["main", "flap", "farfield"]);
    let patches: Vec<(&str, Role)> = back
        .patches
        .iter()
        .map(|p| (p.name.as_str(), p.role))
        .collect();
    assert_eq!(
        patches,
        [
            ("main", Role::Wall),
            ("flap", Role::Wall),
            ("farfield", Role::Farfield)
        ]
    );
}

#[test]
fn merge_walls_makes_one_wall_group() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("two.toml");
    std::fs::write(
        &case,
        "merge_walls = true\n\
         [[loop]]\nrole = \"wall\"\nname = \"a b\"\nnaca = \"0012\"\n\
         [[loop]]\nrole = \"wall\"\nnaca = \"0012\"\ntranslate = [0.0, 0.5]\n\
         [[loop]]\nrole = \"farfield\"\ncircle = { center = [0.5, 0.0], radius = 20.0 }\n\
         [layers]\nfirst_height = 1e-3\nmax_layers = 10\n",
    )
    .unwrap();
    let (msh, su2, _) = mesh(case.to_str().unwrap(), dir.path());
    assert_eq!(physical_names(&msh), ["fluid", "wall", "farfield"]);
    assert_eq!(markers(&su2), ["wall", "farfield"]);
    // without the key: identifiers, made unique
    let text = std::fs::read_to_string(&case).unwrap();
    std::fs::write(&case, text.replace("merge_walls = true\n", "")).unwrap();
    let (msh, su2, _) = mesh(case.to_str().unwrap(), dir.path());
    assert_eq!(
        physical_names(&msh),
        ["fluid", "a_b", "naca0012", "farfield"]
    );
    assert_eq!(markers(&su2), ["a_b", "naca0012", "farfield"]);
}

#[test]
fn the_vtu_carries_the_boundary_facets_with_their_group() {
    let dir = tempfile::tempdir().unwrap();
    let (vtu, json) = (dir.path().join("m.vtu"), dir.path().join("m.json"));
    let args = ["mesh", "two-element", "--quiet", "--order", "3"];
    let outputs = ["--out", s(&vtu), "--report", s(&json)];
    assert_eq!(xtask_ok(&[&args[..], &outputs].concat()), Outcome::Valid);
    let text = std::fs::read_to_string(&vtu).unwrap();
    let report = read_json(&json);
    // the group names, as numeric field data (meshio reads no string array): one Int64 array
    // `boundary_group:NAME` per group, holding the group's index, in index order
    let mut names = Vec::new();
    for (k, piece) in text.split(r#"Name="boundary_group:"#).skip(1).enumerate() {
        let (name, rest) = piece.split_once('"').unwrap();
        let index = &rest[rest.find('>').unwrap() + 1..rest.find("</DataArray>").unwrap()];
        assert_eq!(index.trim().parse::<usize>().unwrap(), k, "{name}");
        names.push(name.to_string());
    }
    assert_eq!(names, ["main", "flap", "farfield"]);
    assert!(!text.contains(r#"type="String""#));
    let start = text.find(r#"Name="boundary_group""#).unwrap();
    let block = &text[text[start..].find('>').unwrap() + start + 1..];
    let block = &block[..block.find("</DataArray>").unwrap()];
    let group: Vec<i64> = block
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    let cells =
        report["cells"]["tri"].as_u64().unwrap() + report["cells"]["quad"].as_u64().unwrap();
    assert_eq!(group.iter().filter(|&&g| g == -1).count() as u64, cells);
    for (k, name) in names.iter().enumerate() {
        let n = group.iter().filter(|&&g| g == k as i64).count() as u64;
        assert_eq!(
            n,
            report["boundary_groups"][name].as_u64().unwrap(),
            "{name}"
        );
    }
}
