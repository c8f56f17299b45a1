//! The movers on the real NACA0012 mesh of the built-in case (far field of radius 20): valid
//! cells after rotations of the wall, exact identity, exact rigid motion of every loop, the
//! worst-cell ratio table, and a 30P30N flap deflection.

use crate::common;

use mesh_model::Mesh;
use mesh_move::{
    BoundaryMotion, Comparison, IdwParams, Kernel, LoopMotion, Method, Motion, MoveStats,
    RbfParams, RigidMotion, boundary_motion, compare, move_mesh,
};

fn naca() -> &'static Mesh {
    &common::naca_layered().mesh
}

const METHODS: [(&str, Method); 3] = [
    ("IDW", Method::Idw(IdwParams { exponent: 3.0 })),
    (
        "RBF Wendland C2",
        Method::Rbf(RbfParams {
            kernel: Kernel::WendlandC2,
            support_radius: None,
        }),
    ),
    (
        "RBF thin-plate",
        Method::Rbf(RbfParams {
            kernel: Kernel::ThinPlateSpline,
            support_radius: None,
        }),
    ),
];

/// Wendland C2 with a support radius of a few chords instead of the domain's diameter.
const LOCAL_WENDLAND: [(&str, Method); 3] = [
    ("RBF Wendland C2, R = 0.5", wendland(0.5)),
    ("RBF Wendland C2, R = 2", wendland(2.0)),
    ("RBF Wendland C2, R = 5", wendland(5.0)),
];

const fn wendland(r: f64) -> Method {
    Method::Rbf(RbfParams {
        kernel: Kernel::WendlandC2,
        support_radius: Some(r),
    })
}

/// The NACA0012 wall turned nose up by `deg` degrees about the quarter chord.
fn pitch(deg: f64) -> Vec<LoopMotion> {
    vec![LoopMotion {
        loop_name: "naca0012".into(),
        motion: Motion::rigid(RigidMotion::rotation(-deg, [0.25, 0.0])),
    }]
}

fn moved(mesh: &Mesh, motions: &[LoopMotion], method: &Method) -> (Mesh, Comparison) {
    let (m, c, _) = moved_with_stats(mesh, motions, method);
    (m, c)
}

fn moved_with_stats(
    mesh: &Mesh,
    motions: &[LoopMotion],
    method: &Method,
) -> (Mesh, Comparison, MoveStats) {
    let boundary = boundary_motion(mesh, motions).expect("a valid motion");
    let m = move_mesh(mesh, &boundary, method).expect("moves");
    let c = compare(mesh, &m.mesh).expect("same topology");
    (m.mesh, c, m.stats)
}

#[test]
fn pitching_the_naca0012_by_10_and_30_degrees_inverts_no_cell() {
    for deg in [10.0, 30.0] {
        for (name, method) in &METHODS[..2] {
            let (_, c) = moved(naca(), &pitch(deg), method);
            assert_eq!(c.inverted_cells, 0, "{name} {deg}°: {c:?}");
            assert!(c.min_after > 0.0, "{name} {deg}°: {c:?}");
        }
    }
}

#[test]
fn the_identity_motion_moves_no_node_at_all() {
    let mesh = naca();
    let identity = vec![LoopMotion {
        loop_name: "naca0012".into(),
        motion: Motion::rigid(RigidMotion::IDENTITY),
    }];
    for motions in [vec![], identity] {
        for (name, method) in &METHODS {
            let (after, c) = moved(mesh, &motions, method);
            assert_eq!(after.nodes, mesh.nodes, "{name}");
            assert_eq!(c.worst_cell_ratio, 1.0, "{name}");
        }
    }
    // the same through a hand-made boundary motion that keeps every node
    let fixed = BoundaryMotion::fixed(mesh).unwrap();
    for (name, method) in &METHODS {
        let after = move_mesh(mesh, &fixed, method).unwrap().mesh;
        assert_eq!(after.nodes, mesh.nodes, "{name}");
    }
}

#[test]
fn a_rigid_motion_of_every_loop_moves_every_node_rigidly() {
    let mesh = naca();
    let rigid = common::turn_and_shift(1.5);
    let motions = common::every_loop(&["naca0012", "farfield"], rigid);
    let size = mesh_move::movers::bounding_box_diagonal(mesh);
    for (name, method) in &METHODS {
        let (after, c) = moved(mesh, &motions, method);
        let worst = common::rigid_error(mesh, &after, &rigid);
        assert!(worst <= 1e-12 * size, "{name}: {worst:e} (size {size})");
        assert_eq!(c.inverted_cells, 0, "{name}");
        assert!((c.worst_cell_ratio - 1.0).abs() < 1e-6, "{name}: {c:?}");
    }
}

fn row(label: &str, c: &Comparison, s: &MoveStats) -> String {
    let fl = c.first_layer.unwrap_or_default();
    format!(
        "| {label} | {:.3} | {} | {:.3} | {:.2e} | {:.2} | {:.1e} |",
        c.worst_cell_ratio,
        c.inverted_cells,
        c.min_after,
        fl.height,
        fl.angle_deg,
        s.interpolation_residual
    )
}

const HEADER: &str = "| motion, mover | worst-cell ratio | inverted cells | min scaled Jacobian after | first-layer height drift | wall-normal angle drift (°) | RBF boundary residual |\n|---|---|---|---|---|---|---|";

#[test]
fn worst_cell_ratio_table_of_the_naca0012_pitch() {
    println!(
        "NACA0012 (far field radius 20), wall pitched nose up about the quarter chord, one step:\n{HEADER}"
    );
    for deg in [10.0, 30.0, 60.0, 90.0] {
        for (name, method) in METHODS.iter().chain(&LOCAL_WENDLAND) {
            let (_, c, s) = moved_with_stats(naca(), &pitch(deg), method);
            println!("{}", row(&format!("{deg}°, {name}"), &c, &s));
        }
    }
}

#[test]
fn worst_cell_ratio_table_of_the_30p30n_flap_deflection() {
    let case = test_cases::real_case("30p30n");
    let mesh = test_cases::grow(&case).output.layered.mesh;
    let hinge = common::leading_edge(&case, "flap");
    println!(
        "30P30N (first height 5e-6, far field radius 20), flap deflected about its leading edge ({:.4}, {:.4}), one step:\n{HEADER}",
        hinge[0], hinge[1]
    );
    for deg in [10.0, -10.0] {
        let motions = vec![LoopMotion {
            loop_name: "flap".into(),
            motion: Motion::rigid(RigidMotion::rotation(-deg, hinge)),
        }];
        for (name, method) in METHODS.iter().chain(&LOCAL_WENDLAND) {
            let (_, c, s) = moved_with_stats(&mesh, &motions, method);
            assert_eq!(c.inverted_cells, s.inverted_cells);
            if deg == 10.0 && name == &"IDW" {
                println!(
                    "({} boundary nodes, {} others)",
                    s.boundary_nodes, s.interior_nodes
                );
            }
            println!(
                "{}",
                row(&format!("flap {deg:+}° (down > 0), {name}"), &c, &s)
            );
        }
    }
}

#[test]
fn hicks_henne_bumps_on_the_naca0012_mesh_move_the_wall_nodes_and_invert_no_cell() {
    let mesh = naca();
    let morph = common::eight_bumps("naca0012");
    for (name, method) in &METHODS {
        let (_, c, s) = moved_with_stats(mesh, &morph, method);
        assert_eq!(c.inverted_cells, 0, "{name}");
        assert!(s.largest_boundary_displacement > 0.005, "{name}: {s:?}");
        assert!(s.largest_boundary_displacement <= 0.04, "{name}: {s:?}");
        assert!(c.worst_cell_ratio > 0.5, "{name}: {c:?}");
    }
}

#[test]
fn the_movers_refuse_what_they_cannot_move_in_one_line() {
    let mesh = naca();
    let mut p2 = mesh.clone();
    p2.order = 2;
    let fixed = BoundaryMotion::fixed(mesh).unwrap();
    let idw = Method::Idw(IdwParams::default());
    let e = move_mesh(&p2, &fixed, &idw).unwrap_err().to_string();
    assert_eq!(e, "the mesh must be linear and 2D (got order 2, 2D)");
    let mut short = fixed.clone();
    let lost = short.nodes.pop().unwrap();
    short.targets.pop();
    short.linear.pop();
    short.turn.pop();
    let e = move_mesh(mesh, &short, &idw).unwrap_err().to_string();
    assert_eq!(
        e,
        format!("boundary node {lost} has no target in the boundary motion")
    );
    let mut nan = fixed.clone();
    nan.targets[3][1] = f64::NAN;
    let e = move_mesh(mesh, &nan, &idw).unwrap_err().to_string();
    assert!(e.starts_with("boundary motion: node "), "{e}");
    let e = move_mesh(mesh, &fixed, &Method::Idw(IdwParams { exponent: -1.0 }))
        .unwrap_err()
        .to_string();
    assert_eq!(e, "IDW exponent must be positive and finite, got -1");
    let e = move_mesh(mesh, &fixed, &wendland(0.0))
        .unwrap_err()
        .to_string();
    assert_eq!(e, "RBF support radius must be positive and finite, got 0");
}
