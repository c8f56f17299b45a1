//! The spring mover on the real NACA0012 mesh of the built-in case (far field of radius 20):
//! the pitch about the quarter chord at 10°, 30°, 60° and 90° in one step with no inverted
//! cell and the first layer kept, beside IDW and RBF; the identity to the bit; a rigid motion
//! of every loop carried rigidly; and the 30P30N flap deflection.

use crate::common;

use std::time::Instant;

use mesh_model::LayeredMesh;
use mesh_move::{
    BoundaryMotion, Comparison, Fill, IdwParams, Kernel, LoopMotion, Method, Motion, MoveStats,
    RbfParams, RigidMotion, SpringMoveParams, Strategy, boundary_motion, compare, move_layered,
};

fn naca() -> &'static LayeredMesh {
    common::naca_layered()
}

fn springs(strategy: Strategy, fill: Fill) -> Method {
    Method::Springs(SpringMoveParams {
        strategy,
        fill,
        ..SpringMoveParams::default()
    })
}

fn methods() -> Vec<(&'static str, Method)> {
    vec![
        ("springs", Method::Springs(SpringMoveParams::default())),
        (
            "springs, IDW fill",
            springs(Strategy::AllTogether, Fill::Idw),
        ),
        ("IDW", Method::Idw(IdwParams::default())),
        ("RBF Wendland C2", Method::Rbf(RbfParams::default())),
        (
            "RBF thin-plate",
            Method::Rbf(RbfParams {
                kernel: Kernel::ThinPlateSpline,
                support_radius: None,
            }),
        ),
    ]
}

/// The NACA0012 wall turned nose up by `deg` degrees about the quarter chord.
fn pitch(deg: f64) -> Vec<LoopMotion> {
    vec![LoopMotion {
        loop_name: "naca0012".into(),
        motion: Motion::rigid(RigidMotion::rotation(-deg, [0.25, 0.0])),
    }]
}

fn run(
    mesh: &LayeredMesh,
    motions: &[LoopMotion],
    method: &Method,
) -> (Comparison, MoveStats, f64) {
    let boundary = boundary_motion(&mesh.mesh, motions).expect("a valid motion");
    let t = Instant::now();
    let m = move_layered(mesh, &boundary, method).expect("moves");
    let secs = t.elapsed().as_secs_f64();
    let c = compare(&mesh.mesh, &m.mesh).expect("same topology");
    assert_eq!(c.inverted_cells, m.stats.inverted_cells);
    (c, m.stats, secs)
}

const HEADER: &str = "| motion, mover | worst-cell ratio | inverted cells | min scaled Jacobian after | first-layer height drift | wall-normal angle drift (°) | spring iterations (converged, residual), fill kept | time (s) |\n|---|---|---|---|---|---|---|---|";

fn row(label: &str, c: &Comparison, s: &MoveStats, secs: f64) -> String {
    let fl = c.first_layer.unwrap_or_default();
    let sp = s.springs.map_or("–".to_string(), |p| {
        let newton = p.newton.map_or(String::new(), |n| {
            format!(
                ", Newton {} ({}, {:.0e})",
                n.iterations,
                if n.converged { "yes" } else { "no" },
                n.residual
            )
        });
        format!(
            "{} ({}, {:.1e}), fill {:?}{newton}",
            p.iterations,
            if p.converged { "yes" } else { "no" },
            p.residual,
            p.fill
        )
    });
    format!(
        "| {label} | {:.3} | {} | {:.3} | {:.2e} | {:.2} | {sp} | {secs:.2} |",
        c.worst_cell_ratio, c.inverted_cells, c.min_after, fl.height, fl.angle_deg
    )
}

#[test]
fn springs_pitch_the_naca0012_up_to_90_degrees_keeping_the_first_layer() {
    println!(
        "NACA0012 (far field radius 20), wall pitched nose up about the quarter chord, one step:\n{HEADER}"
    );
    // a bar for the worst-cell ratio above the best generic method measured on such a mesh,
    // a global thin-plate RBF, which keeps 0.95 / 0.85 / 0.70 / 0.51 (the balance keeps
    // 0.99 / 0.94 / 0.84 / 0.74)
    for (deg, bar) in [(10.0, 0.95), (30.0, 0.9), (60.0, 0.8), (90.0, 0.7)] {
        for (name, method) in methods() {
            let (c, s, secs) = run(naca(), &pitch(deg), &method);
            println!("{}", row(&format!("{deg}°, {name}"), &c, &s, secs));
            if name == "springs" {
                assert!(c.worst_cell_ratio >= bar, "{deg}°: {c:?}");
            }
            if name.starts_with("springs") && !name.ends_with("IDW fill") {
                assert_eq!(c.inverted_cells, 0, "{name} {deg}°: {c:?}");
                let fl = c.first_layer.expect("walls");
                assert!(fl.height < 0.01, "{name} {deg}°: {fl:?}");
                assert!(fl.angle_deg < 5.0, "{name} {deg}°: {fl:?}");
            }
        }
    }
}

#[test]
fn the_identity_motion_moves_no_node_with_springs() {
    let mesh = naca();
    let fixed = BoundaryMotion::fixed(&mesh.mesh).unwrap();
    for (name, method) in methods() {
        let after = move_layered(mesh, &fixed, &method).unwrap();
        assert_eq!(after.mesh.nodes, mesh.mesh.nodes, "{name}");
        assert_eq!(after.stats.largest_displacement, 0.0, "{name}");
    }
}

#[test]
fn a_rigid_motion_of_every_loop_moves_every_node_rigidly_with_springs() {
    let mesh = naca();
    let rigid = common::turn_and_shift(1.0);
    let motions = common::every_loop(&["naca0012", "farfield"], rigid);
    let size = mesh_move::movers::bounding_box_diagonal(&mesh.mesh);
    for (name, method) in methods()
        .into_iter()
        .filter(|(n, _)| n.starts_with("springs"))
    {
        let boundary = boundary_motion(&mesh.mesh, &motions).unwrap();
        let after = move_layered(mesh, &boundary, &method).unwrap().mesh;
        let worst = common::rigid_error(&mesh.mesh, &after, &rigid);
        assert!(worst <= 1e-9 * size, "{name}: {worst:e} (size {size})");
    }
}

#[test]
fn the_spring_mover_needs_the_layers_and_checks_them() {
    let mesh = naca();
    let fixed = BoundaryMotion::fixed(&mesh.mesh).unwrap();
    let method = springs(Strategy::AllTogether, Fill::Screw);
    let e = mesh_move::move_mesh(&mesh.mesh, &fixed, &method)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "the spring mover needs the mesh's layers: call move_layered with a LayeredMesh"
    );
    let mut broken = mesh.clone();
    broken.layering.node_layer.pop();
    let e = move_layered(&broken, &fixed, &method)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("the mesh's layering is broken: node_layer has"),
        "{e}"
    );
    let bad = Method::Springs(SpringMoveParams {
        core_aspect: 0.0,
        ..SpringMoveParams::default()
    });
    let e = move_layered(mesh, &fixed, &bad).unwrap_err().to_string();
    assert_eq!(e, "core aspect must be positive and finite, got 0");
    let mut p = SpringMoveParams::default();
    p.springs.c_percent = 2.0;
    let e = move_layered(mesh, &fixed, &Method::Springs(p))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("springs: ") && e.contains("c_percent") && !e.contains('\n'),
        "{e}"
    );
}

#[test]
fn springs_deflect_the_30p30n_flap() {
    let case = test_cases::real_case("30p30n");
    let mesh = test_cases::grow(&case).output.layered;
    let hinge = common::leading_edge(&case, "flap");
    println!(
        "30P30N (first height 5e-6, far field radius 20), flap deflected about its leading edge, one step:\n{HEADER}"
    );
    for deg in [10.0, -10.0] {
        let motions = vec![LoopMotion {
            loop_name: "flap".into(),
            motion: Motion::rigid(RigidMotion::rotation(-deg, hinge)),
        }];
        for (name, method) in methods() {
            let (c, s, secs) = run(&mesh, &motions, &method);
            println!(
                "{}",
                row(&format!("flap {deg:+}° (down > 0), {name}"), &c, &s, secs)
            );
            if name.starts_with("springs") && !name.ends_with("IDW fill") {
                assert_eq!(c.inverted_cells, 0, "{name} {deg}°: {c:?}");
                // the jump springs spread the squeeze of the flap's gap (0.864 and 0.867
                // without them: 0.890 and 0.885); the quadrilaterals' own jump springs trade
                // some skew for an even Jacobian (issue 43's sj: 0.875 → 0.906): 0.845 and
                // 0.825 (the thin-plate RBF's: 0.833 and 0.797)
                assert!(c.worst_cell_ratio > 0.81, "{name} {deg}°: {c:?}");
            }
        }
    }
}

#[test]
fn springs_follow_hicks_henne_bumps_keeping_the_first_layer() {
    let morph = common::eight_bumps("naca0012");
    let (c, s, _) = run(naca(), &morph, &springs(Strategy::AllTogether, Fill::Screw));
    println!("8 bumps of 1 % chord: {c:?} {s:?}");
    assert_eq!(c.inverted_cells, 0);
    let fl = c.first_layer.expect("walls");
    assert!(fl.height < 0.01 && fl.angle_deg < 5.0, "{fl:?}");
    assert!(c.worst_cell_ratio > 0.5, "{c:?}");
    assert!(s.springs.is_some_and(|p| p.converged), "{s:?}");
}

/// The shortest corner-to-corner edge of each cell of `mesh`.
fn shortest_edges(mesh: &mesh_model::Mesh) -> Vec<f64> {
    mesh.cells
        .iter()
        .map(|c| {
            let k = c.corners();
            (0..k.len())
                .map(|i| {
                    let (p, q) = (mesh.xy(k[i]), mesh.xy(k[(i + 1) % k.len()]));
                    (q[0] - p[0]).hypot(q[1] - p[1])
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

#[test]
fn springs_keep_the_layers_heights_where_bumps_shrink_the_wall() {
    // near the leading edge an inward bump shrinks the wall under the layers; holding only
    // the first three layers' heights, the thin cells above kept their aspect and lost 15 %
    // of their height with the wall's width (issue 43's edge measure 0.846, IDW 0.952); with
    // the thin cells' extrusion edges held too the worst is 0.943 at P3, here at order 1
    let morph = common::eight_bumps("naca0012");
    let boundary = boundary_motion(&naca().mesh, &morph).expect("a valid motion");
    let moved = move_layered(
        naca(),
        &boundary,
        &Method::Springs(SpringMoveParams::default()),
    )
    .expect("moves");
    let (before, after) = (shortest_edges(&naca().mesh), shortest_edges(&moved.mesh));
    let worst = before
        .iter()
        .zip(&after)
        .map(|(b, a)| a / b)
        .fold(f64::INFINITY, f64::min);
    println!("8 bumps: the worst shortest-edge ratio {worst:.4}");
    assert!(worst > 0.93, "{worst}");
}

#[test]
fn springs_keep_the_first_layer_of_a_scaled_body() {
    // NACA0012 ×1.5 about its quarter chord and carried five chords upstream: the walls
    // stretch under the layers, whose heights stay (at the blunt trailing edge's corners the
    // fans' children were pulled 13° sideways when the springs kept the original spacing)
    let grow = vec![LoopMotion {
        loop_name: "naca0012".into(),
        motion: Motion::rigid(RigidMotion {
            scale: 1.5,
            rotate_deg: 0.0,
            about: [0.25, 0.0],
            translate: [-5.0, 0.0],
        }),
    }];
    let (c, s, _) = run(naca(), &grow, &springs(Strategy::AllTogether, Fill::Screw));
    println!("×1.5 and 5 chords left: {c:?} {s:?}");
    assert_eq!(c.inverted_cells, 0);
    let fl = c.first_layer.expect("walls");
    // within the 1 % and 5° of every motion: 0.52 % and 2.5° (6.6° at the blunt trailing
    // edge's corner fans before the corner springs held the first layer's angles)
    assert!(fl.height < 0.01 && fl.angle_deg < 5.0, "{fl:?}");
    // 0.867 (0.742 when the shifted Newton steps stopped unconverged)
    assert!(c.worst_cell_ratio > 0.8, "{c:?}");
    // the Newton balance converges: its shifted steps crept here, and after 20 steps the
    // convex Hessian takes over (`springfield::newton`)
    let newton = s.springs.and_then(|p| p.newton).expect("the balance ran");
    assert!(newton.converged && newton.convex > 0, "{newton:?}");
}
