//! Every built-in case runs at every order, writes every format, and what it writes reads back
//! as the same boundary mesh the report describes.

use std::collections::HashMap;

use curvemesh::builtin;
use end_to_end::{Outcome, mesh, xtask_ok as run};
use mesh_model::{Role, Shape};

#[test]
fn every_builtin_case_at_every_order_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    for name in builtin::names() {
        for order in ["1", "2", "3"] {
            let msh = dir.path().join(format!("{name}-p{order}.msh"));
            let vtu = dir.path().join(format!("{name}-p{order}.vtu"));
            let su2 = dir.path().join(format!("{name}-p{order}.su2"));
            let json = dir.path().join(format!("{name}-p{order}.json"));
            let outcome = mesh(
                name,
                order,
                &[
                    "--out",
                    msh.to_str().unwrap(),
                    "--out",
                    vtu.to_str().unwrap(),
                    "--out",
                    su2.to_str().unwrap(),
                    "--report",
                    json.to_str().unwrap(),
                ],
            );
            assert_eq!(outcome.unwrap(), Outcome::Valid, "{name} P{order}");
            assert!(vtu.exists() && su2.exists());

            let report: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
            let mesh = mesh_io::read_msh(&msh).unwrap();
            assert_eq!(report["case"], name);
            assert_eq!(report["order"].as_u64(), Some(u64::from(mesh.order)));
            assert_eq!(
                report["nodes"].as_u64(),
                Some(mesh.nodes.len() as u64),
                "{name}"
            );
            assert!(report["timings_s"]["total"].as_f64().unwrap() > 0.0);

            // Every loop is closed: each corner node of a patch's facets is used twice.
            let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
            for (f, &patch) in mesh.boundary.iter().zip(&mesh.boundary_patch) {
                assert_eq!(f.ty.shape, Shape::Line);
                assert_eq!(f.ty.order, mesh.order);
                for &n in f.corners() {
                    *uses.entry((patch, n)).or_default() += 1;
                }
            }
            assert!(uses.values().all(|&u| u == 2), "{name}: every loop closed");
            // The cells are conforming, positive, and cover the domain exactly: their areas
            // sum to the area enclosed by the boundary facets (domain on their left).
            let problems = mesh_model::validate(&mesh);
            assert!(
                problems.is_empty(),
                "{name}: {:?}",
                &problems[..problems.len().min(5)]
            );
            let enclosed = jacobian_check::enclosed_area(&mesh).unwrap();
            let area = jacobian_check::integrate_area(&mesh).unwrap();
            assert!(
                (area - enclosed).abs() <= 1e-9 * enclosed,
                "{name} P{order}: cells {area} vs boundary {enclosed}"
            );
            let reported = report["area"].as_f64().unwrap();
            assert!(
                (reported - area).abs() <= 1e-9 * area,
                "{name}: report area {reported}"
            );
            // curving moves the boundary by far less than a cell: the area barely changes
            let linear = mesh.linear_area();
            assert!(
                (area - linear).abs() <= 1e-3 * linear,
                "{name} P{order}: curved area {area} vs linear {linear}"
            );
            if order != "1" {
                assert_eq!(
                    report["quality"]["invalid_cells"].as_u64(),
                    Some(0),
                    "{name}"
                );
                assert_eq!(report["quality"]["certified"].as_bool(), Some(true));
                let f = report["curved_edge_fraction"].as_f64().unwrap();
                assert!(f > 0.0 && f < 0.5, "{name} P{order}: curved fraction {f}");
            }
            let walls = mesh.patches.iter().filter(|p| p.role == Role::Wall).count();
            assert!(walls >= 1, "{name}: has a wall");
            assert_eq!(
                report["loops"].as_array().unwrap().len(),
                mesh.patches.len()
            );
        }
    }
}

#[test]
fn list_prints_and_succeeds() {
    assert_eq!(run(&["mesh", "--list"]), Outcome::Valid);
    assert!(builtin::names().len() >= 4);
}

#[test]
fn a_loop_can_have_its_own_max_spacing() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("caps.toml");
    std::fs::write(
        &case,
        "[[loop]]\nrole = \"wall\"\nnaca = \"0012\"\nmax_spacing = 0.02\n\n[[loop]]\n\
         role = \"farfield\"\ncircle = { center = [0.5, 0.0], radius = 20.0 }\n\n\
         [boundary]\nmax_spacing = 2.0\n",
    )
    .unwrap();
    let json = dir.path().join("caps.json");
    let msh = dir.path().join("caps.msh");
    let case_s = case.to_str().unwrap();
    let (msh_s, json_s) = (msh.to_str().unwrap(), json.to_str().unwrap());
    let outcome = mesh(case_s, "1", &["--out", msh_s, "--report", json_s]);
    assert_eq!(outcome.unwrap(), Outcome::Valid);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let loops = report["loops"].as_array().unwrap();
    let wall_max = loops[0]["spacing_max"].as_f64().unwrap();
    let far_max = loops[1]["spacing_max"].as_f64().unwrap();
    assert!(wall_max <= 0.02 * (1.0 + 1e-6), "wall spacing {wall_max}");
    assert!(
        far_max > 0.5 && far_max <= 2.0 * (1.0 + 1e-6),
        "farfield spacing {far_max}"
    );
}
