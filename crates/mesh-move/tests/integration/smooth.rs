//! The smooth mover is a smooth function of the boundary, and its sensitivities are its
//! derivatives: on the NACA0012 mesh of the built-in case, for a bump amplitude and for a
//! rotation angle about 30°, central finite differences of the moved mesh (all nodes, 2-norm)
//! agree across ε = 1e-4, 1e-5, 1e-7 to 1e-5 relative, and with the sensitivities from the
//! linearised balance (the implicit function theorem, no finite difference) to 1e-6. (At
//! ε = 1e-3, a fifth of the bump's amplitude, the central difference's own O(ε²) error is
//! 2e-5: curvature of the map, not noise; the dissertation's mover failed at ε = 1e-10.)

#[allow(dead_code)] // shared by the test files; this one uses the mesh only
use crate::common;

use mesh_model::LayeredMesh;
use mesh_move::{
    HicksHenne, LoopMotion, Method, Motion, RigidMotion, ShapeField, SpringMoveParams, Surface,
    boundary_motion, move_layered,
};

fn naca() -> &'static LayeredMesh {
    common::naca_layered()
}

/// Every node of the mesh moved by the smooth mover for `motions`.
fn moved(motions: &[LoopMotion]) -> Vec<[f64; 2]> {
    let mesh = naca();
    let boundary = boundary_motion(&mesh.mesh, motions).expect("a valid motion");
    let m = move_layered(
        mesh,
        &boundary,
        &Method::Springs(SpringMoveParams::default()),
    )
    .expect("moves");
    assert_eq!(m.stats.inverted_cells, 0);
    let newton = m
        .stats
        .springs
        .and_then(|s| s.newton)
        .expect("the balance ran");
    assert!(newton.converged, "{newton:?}");
    (0..m.mesh.nodes.len() as u32)
        .map(|k| m.mesh.xy(k))
        .collect()
}

fn difference(plus: &[[f64; 2]], minus: &[[f64; 2]], scale: f64) -> Vec<[f64; 2]> {
    plus.iter()
        .zip(minus)
        .map(|(p, m)| [(p[0] - m[0]) / scale, (p[1] - m[1]) / scale])
        .collect()
}

fn norm(v: &[[f64; 2]]) -> f64 {
    v.iter()
        .map(|d| d[0] * d[0] + d[1] * d[1])
        .sum::<f64>()
        .sqrt()
}

fn relative(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    norm(&difference(a, b, 1.0)) / norm(b)
}

/// The derivative by the linearised balance at the moved mesh of `motion(α)`.
fn sensitivity(motion: &dyn Fn(f64) -> Vec<LoopMotion>, alpha: f64) -> Vec<[f64; 2]> {
    let mesh = naca();
    let x = moved(&motion(alpha));
    // the boundary nodes' derivative: their motion is explicit (the motion applied to the
    // nodes), differenced with a step far below the mover's
    let h = 1e-6;
    let target = |a: f64| boundary_motion(&mesh.mesh, &motion(a)).unwrap();
    let (p, m) = (target(alpha + h), target(alpha - h));
    let mut d_boundary = vec![[0.0; 2]; x.len()];
    let mut fixed = vec![false; x.len()];
    for ((&k, tp), tm) in p.nodes.iter().zip(&p.targets).zip(&m.targets) {
        d_boundary[k as usize] = [(tp[0] - tm[0]) / (2.0 * h), (tp[1] - tm[1]) / (2.0 * h)];
        fixed[k as usize] = true;
    }
    let field = ShapeField::of(mesh, SpringMoveParams::default().shape).unwrap();
    field.linearise(&x, &fixed).unwrap().respond(&d_boundary)
}

fn check(label: &str, motion: &dyn Fn(f64) -> Vec<LoopMotion>, alpha: f64) {
    let fd: Vec<Vec<[f64; 2]>> = [1e-4, 1e-5, 1e-7]
        .iter()
        .map(|&e| {
            difference(
                &moved(&motion(alpha + e)),
                &moved(&motion(alpha - e)),
                2.0 * e,
            )
        })
        .collect();
    let exact = sensitivity(motion, alpha);
    let across = [relative(&fd[0], &fd[1]), relative(&fd[2], &fd[1])];
    let against = relative(&exact, &fd[1]);
    println!(
        "{label}: |dX/dα| {:.4e}; finite differences across ε {:.1e} {:.1e}; sensitivities against ε = 1e-5: {against:.1e}",
        norm(&fd[1]),
        across[0],
        across[1]
    );
    assert!(across.iter().all(|&r| r < 1e-5), "{label}: {across:?}");
    assert!(against < 1e-6, "{label}: {against:e}");
}

#[test]
fn a_bump_amplitude_moves_the_mesh_smoothly_and_its_sensitivity_is_the_derivative() {
    let bumps = |a: f64| {
        vec![LoopMotion {
            loop_name: "naca0012".into(),
            motion: Motion {
                rigid: None,
                bumps: vec![
                    HicksHenne::new(0.3, a, Surface::Upper),
                    HicksHenne::new(0.6, -0.004, Surface::Lower),
                ],
            },
        }]
    };
    check("bump amplitude at 0.005", &bumps, 0.005);
}

#[test]
fn a_rotation_angle_moves_the_mesh_smoothly_and_its_sensitivity_is_the_derivative() {
    let pitch = |deg: f64| {
        vec![LoopMotion {
            loop_name: "naca0012".into(),
            motion: Motion::rigid(RigidMotion::rotation(-deg, [0.25, 0.0])),
        }]
    };
    check("pitch angle at 30° (per degree)", &pitch, 30.0);
}
