//! Curving a moved mesh with a previous run's decisions (`curve_mesh_keeping`, `replay`) and
//! the derivative of that curving (`tangent`), on the built-in NACA 0012 case at P3: a replay
//! of a run's own decisions is that run to the last bit; a slight motion changes no
//! decision; a motion that would leave a kept stop invalid changes it and stays valid; the
//! tangent matches central finite differences.

use geom_curve::ClosedCurve;
use mesh_model::{LayeredMesh, Mesh};
use test_cases::{Grown, grow, real_case};
use vector_adding::stats::CurvingStats;
use vector_adding::{
    Carry, CurvingParams, DecisionChange, Decisions, EdgeRule, LoopCurve, boundary_points,
    curve_mesh_keeping, curve_mesh_owned, replay, tangent,
};

fn naca() -> Grown {
    grow(&real_case("naca0012"))
}

fn loops<'a>(g: &'a Grown, curves: &'a [ClosedCurve]) -> Vec<LoopCurve<'a>> {
    curves
        .iter()
        .zip(&g.nodes)
        .map(|(curve, n)| LoopCurve { curve, t: &n.t })
        .collect()
}

fn bits(mesh: &Mesh) -> Vec<u64> {
    mesh.nodes
        .iter()
        .flat_map(|v| v.iter().map(|x| x.to_bits()))
        .collect()
}

fn assert_identical(a: &Mesh, b: &Mesh, what: &str) {
    assert!(bits(a) == bits(b), "{what}: nodes differ");
    assert!(a == b, "{what}: meshes differ");
}

fn assert_valid(mesh: &Mesh, what: &str) {
    let v = jacobian_check::check_mesh(mesh, &Default::default()).unwrap();
    assert!(
        v.invalid_cells.is_empty() && v.undecided.is_empty(),
        "{what}: {} invalid, {} undecided",
        v.invalid_cells.len(),
        v.undecided.len()
    );
}

/// The pipes of a curving kept from another are reported as that one's (no repair on the
/// NACA 0012: nothing bent after its marching), curved some layers deep.
fn assert_same_pipes(kept: &CurvingStats, curved: &CurvingStats, what: &str) {
    assert!(curved.deepest_curved_layer > 1, "{what}: {curved:?}");
    assert_eq!(curved.repaired_cells, 0, "{what}");
    let pipes = |s: &CurvingStats| {
        let (d, st) = (s.deepest_curved_layer, s.stops);
        (d, st, s.reduced_tops, s.handed_to_fill, s.curved_edges)
    };
    assert_eq!(pipes(kept), pipes(curved), "{what}");
}

#[test]
fn a_replay_of_its_own_decisions_is_the_same_mesh() {
    let g = naca();
    let layered = &g.output.layered;
    for triangles in [false, true] {
        let params = g.curving_params(3, triangles);
        let what = format!("triangles={triangles}");
        let curved = g.curve(&params).unwrap();
        let on = loops(&g, &g.curves);
        let (kept, changes) = curve_mesh_keeping(layered, &on, &params, &curved.decisions).unwrap();
        assert!(changes.is_empty(), "{what}: {changes:?}");
        assert_identical(&kept.mesh, &curved.mesh, &what);
        assert_eq!(kept.decisions, curved.decisions);
        assert_same_pipes(&kept.stats, &curved.stats, &what);
        let boundary = boundary_points(layered, &on, 3).unwrap();
        let replayed = replay(layered, &curved.decisions, &boundary).unwrap();
        assert_identical(&replayed, &curved.mesh, &what);
    }
}

#[test]
fn a_curving_of_a_linear_mesh_it_keeps_is_the_same_to_the_last_bit() {
    // `curve_mesh_owned` lets the linear nodes and layers go before the assembly and moves
    // the per-cell records: nothing of the result may change
    let g = naca();
    for (order, triangles) in [(2, false), (3, false), (3, true)] {
        let params = g.curving_params(order, triangles);
        let what = format!("P{order} triangles={triangles}");
        let curved = g.curve(&params).unwrap();
        let on = loops(&g, &g.curves);
        let owned = curve_mesh_owned(g.output.layered.clone(), &on, &params).unwrap();
        assert_identical(&owned.mesh, &curved.mesh, &what);
        assert_eq!(owned.decisions, curved.decisions, "{what}");
        assert_eq!(owned.stats.edges, curved.stats.edges, "{what}");
        assert!(owned.decisions.rules.not_straight().count() < owned.decisions.rules.len() / 4);
    }
}

#[test]
fn decisions_of_another_topology_or_order_are_refused() {
    let g = naca();
    let params = g.curving_params(3, false);
    let curved = g.curve(&params).unwrap();
    let on = loops(&g, &g.curves);
    let p2 = CurvingParams { order: 2, ..params };
    let e = curve_mesh_keeping(&g.output.layered, &on, &p2, &curved.decisions).unwrap_err();
    assert!(e.to_string().contains("another order"), "{e}");
    let mut fewer = curved.decisions.clone();
    fewer.edges.pop();
    let e = curve_mesh_keeping(&g.output.layered, &on, &params, &fewer).unwrap_err();
    assert!(e.to_string().contains("edges"), "{e}");
    // a rule naming no edge, or a loop of carried edges: named, never a panic
    let mut bad = curved.decisions.clone();
    let [a, b] = bad.edges[0];
    let carry = |source, source_from| Carry {
        source,
        source_from,
        from: a,
        reversed: false,
        fraction: 1.0,
    };
    bad.rules
        .set(0, EdgeRule::Carried(carry(u32::MAX, u32::MAX)));
    let e = curve_mesh_keeping(&g.output.layered, &on, &params, &bad).unwrap_err();
    assert!(e.to_string().contains("carried from"), "{e}");
    bad.rules.set(0, EdgeRule::Carried(carry(0, b)));
    let boundary = boundary_points(&g.output.layered, &on, 3).unwrap();
    let e = replay(&g.output.layered, &bad, &boundary).unwrap_err();
    assert!(e.to_string().contains("loop"), "{e}");
    let e = tangent(&g.output.layered, &curved.decisions, &[], &boundary).unwrap_err();
    assert!(e.to_string().contains("node derivatives"), "{e}");
    let short = &boundary[1..];
    let e = replay(&g.output.layered, &curved.decisions, short).unwrap_err();
    assert!(e.to_string().contains("boundary high-order points"), "{e}");
}

/// `g`'s loops rotated by `angle` about the quarter chord, their curves refitted, and the
/// layered mesh moved with them (boundary nodes on the new curves at their parameters,
/// the others rotated, then moved by `field`).
fn rotated(
    g: &Grown,
    angle: f64,
    field: impl Fn([f64; 2]) -> [f64; 2],
) -> (Vec<ClosedCurve>, LayeredMesh) {
    let turn = |x: [f64; 2]| rotate(x, angle);
    let mut case = g.case.clone();
    for l in &mut case.loops {
        l.points.iter_mut().for_each(|x| *x = turn(*x));
    }
    let curves = test_cases::boundary(&case).0;
    let mut layered = g.output.layered.clone();
    let on_boundary: usize = g.nodes.iter().map(|n| n.t.len()).sum();
    let mut k = 0;
    for (curve, n) in curves.iter().zip(&g.nodes) {
        for &t in &n.t {
            let c = curve.point(t);
            layered.mesh.nodes[k] = [c.x, c.y, 0.0];
            k += 1;
        }
    }
    for v in &mut layered.mesh.nodes[on_boundary..] {
        let x = turn([v[0], v[1]]);
        let d = field(x);
        *v = [x[0] + d[0], x[1] + d[1], 0.0];
    }
    (curves, layered)
}

/// `x` rotated by `angle` about the quarter chord.
fn rotate(x: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    let (dx, dy) = (x[0] - 0.25, x[1]);
    [0.25 + c * dx - s * dy, s * dx + c * dy]
}

#[test]
fn a_slight_motion_changes_no_decision() {
    let g = naca();
    let first = g.case.layers.first_height;
    // a smooth field far smaller than the first layer, on the interior nodes
    let field = |x: [f64; 2]| {
        let a = 0.05 * first;
        [
            a * (3.0 * x[0] + 1.0).sin() * (2.0 * x[1]).cos(),
            a * x[0].cos() * (3.0 * x[1] + 2.0).sin(),
        ]
    };
    for triangles in [false, true] {
        let params = g.curving_params(3, triangles);
        let curved = g.curve(&params).unwrap();
        let (curves, moved) = rotated(&g, 0.5f64.to_radians(), field);
        let on = loops(&g, &curves);
        let (kept, changes) = curve_mesh_keeping(&moved, &on, &params, &curved.decisions).unwrap();
        assert!(changes.is_empty(), "triangles={triangles}: {changes:?}");
        assert_valid(&kept.mesh, "slight motion");
        assert_ne!(bits(&kept.mesh), bits(&curved.mesh));
        assert_same_pipes(&kept.stats, &curved.stats, "slight motion");
    }
}

/// A stop of `d` (a layered quadrilateral whose bottom edge is curved and top straight),
/// bulging into its cell: (cell, bottom ends, top ends listed above them, bulge / height).
fn stops(g: &Grown, curved: &Mesh, d: &Decisions) -> Vec<(usize, [u32; 2], [u32; 2], f64)> {
    let mesh = &g.output.layered.mesh;
    let layer = &g.output.layered.layering.node_layer;
    let mut out = Vec::new();
    for (ci, cell) in mesh
        .cells
        .iter()
        .enumerate()
        .take(g.output.layered.layering.layered_cells)
    {
        let k = cell.corners();
        if k.len() != 4 || mesh.cell_layer[ci] == 0 {
            continue;
        }
        let l = mesh.cell_layer[ci];
        let Some(j) =
            (0..4).find(|&j| layer[k[j] as usize] == l && layer[k[(j + 1) % 4] as usize] == l)
        else {
            continue;
        };
        let (b0, b1, t1, t0) = (k[j], k[(j + 1) % 4], k[(j + 2) % 4], k[(j + 3) % 4]);
        let carried = matches!(d.rule(b0, b1), Some(EdgeRule::Carried(_)));
        if !carried || d.rule(t0, t1) != Some(&EdgeRule::Straight) {
            continue;
        }
        // the bottom's middle high-order node against its chord's middle
        let bulge = bulge_of(curved, b0, b1);
        let (xb0, xt0) = (mesh.xy(b0), mesh.xy(t0));
        let up = [xt0[0] - xb0[0], xt0[1] - xb0[1]];
        let height = up[0].hypot(up[1]);
        let into = bulge[0] * up[0] + bulge[1] * up[1];
        if into > 0.0 {
            out.push((ci, [b0, b1], [t0, t1], into / height / height));
        }
    }
    out
}

/// The deviation from its chord of the first high-order node of edge a–b in `curved`.
fn bulge_of(curved: &Mesh, a: u32, b: u32) -> [f64; 2] {
    for cell in curved.cells.iter() {
        let k = cell.corners();
        let n = k.len();
        for j in 0..n {
            if (k[j], k[(j + 1) % n]) == (a, b) || (k[j], k[(j + 1) % n]) == (b, a) {
                let q = cell.ty.order as usize - 1;
                let first = cell.nodes[n + j * q];
                let s = if k[j] == a { 1.0 / 3.0 } else { 2.0 / 3.0 };
                let (xa, xb, x) = (curved.xy(a), curved.xy(b), curved.xy(first));
                let l = [xa[0] + s * (xb[0] - xa[0]), xa[1] + s * (xb[1] - xa[1])];
                return [x[0] - l[0], x[1] - l[1]];
            }
        }
    }
    panic!("no edge {a}-{b}")
}

#[test]
fn a_motion_that_breaks_a_kept_stop_changes_it_and_stays_valid() {
    let g = naca();
    for triangles in [false, true] {
        let params = g.curving_params(3, triangles);
        let curved = g.curve(&params).unwrap();
        let mut candidates = stops(&g, &curved.mesh, &curved.decisions);
        candidates.sort_by(|a, b| b.3.total_cmp(&a.3));
        let &(ci, [b0, b1], [t0, t1], _) = candidates.first().expect("a stop cell");
        // squash the stop cell to a third of its bottom's bulge
        let mut moved = g.output.layered.clone();
        let bulge = bulge_of(&curved.mesh, b0, b1);
        let bulge = bulge[0].hypot(bulge[1]);
        for (b, t) in [(b0, t0), (b1, t1)] {
            let (xb, xt) = (moved.mesh.xy(b), moved.mesh.xy(t));
            let f = 0.3 * bulge / (xt[0] - xb[0]).hypot(xt[1] - xb[1]);
            moved.mesh.nodes[t as usize] = [
                xb[0] + f * (xt[0] - xb[0]),
                xb[1] + f * (xt[1] - xb[1]),
                0.0,
            ];
        }
        let on = loops(&g, &g.curves);
        let (kept, changes) = curve_mesh_keeping(&moved, &on, &params, &curved.decisions).unwrap();
        let what = format!("triangles={triangles}, cell {ci}");
        let top = [t0.min(t1), t0.max(t1)];
        assert!(
            changes.iter().any(|c| matches!(c, DecisionChange::Edge { corners, old: EdgeRule::Straight, new: EdgeRule::Carried(_) } if *corners == top)),
            "{what}: {changes:?}"
        );
        eprintln!("{what}: {} changes: {changes:?}", changes.len());
        assert_valid(&kept.mesh, &what);
        assert_eq!(kept.stats.unrepaired_cells, 0);
        // decisions away from the squashed cell are kept
        assert!(
            changes.len() < curved.decisions.rules.len() / 100,
            "{what}: {} changes",
            changes.len()
        );
    }
}

/// The curved mesh's nodes as a flat vector.
fn flat(nodes: impl Iterator<Item = [f64; 2]>) -> Vec<f64> {
    nodes.flat_map(|v| v.into_iter()).collect()
}

/// The tangent of the curving by `decisions` when every node and boundary point `x` of
/// `layered` moves by `field(x)`, flattened.
fn tangent_along(
    layered: &LayeredMesh,
    decisions: &Decisions,
    boundary: &[[f64; 2]],
    field: impl Fn([f64; 2]) -> [f64; 2],
) -> (Vec<[f64; 2]>, Vec<[f64; 2]>, Vec<f64>) {
    let nodes = layered.mesh.nodes.iter();
    let d_nodes: Vec<[f64; 2]> = nodes.map(|v| field([v[0], v[1]])).collect();
    let d_boundary: Vec<[f64; 2]> = boundary.iter().map(|&x| field(x)).collect();
    let analytic = tangent(layered, decisions, &d_nodes, &d_boundary).unwrap();
    (d_nodes, d_boundary, flat(analytic.into_iter()))
}

/// The central difference `(plus − minus) / 2 eps`.
fn central(plus: &[f64], minus: &[f64], eps: f64) -> Vec<f64> {
    let pairs = plus.iter().zip(minus);
    pairs.map(|(p, m)| (p - m) / (2.0 * eps)).collect()
}

fn relative_gap(a: &[f64], b: &[f64]) -> f64 {
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let gap: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&gap) / norm(b)
}

#[test]
fn the_tangent_matches_central_differences_of_the_replay() {
    let g = naca();
    let layered = &g.output.layered;
    let field = |x: [f64; 2]| {
        [
            (2.0 * x[0]).sin() * (0.3 * x[1]).cos() + 0.1 * x[1],
            (1.5 * x[1] + 0.5).sin() * x[0].cos(),
        ]
    };
    for triangles in [false, true] {
        let params = g.curving_params(3, triangles);
        let curved = g.curve(&params).unwrap();
        let d = &curved.decisions;
        let boundary = boundary_points(layered, &loops(&g, &g.curves), 3).unwrap();
        let (d_nodes, d_boundary, analytic) = tangent_along(layered, d, &boundary, field);
        let at = |eps: f64| {
            let mut moved = layered.clone();
            for (v, dv) in moved.mesh.nodes.iter_mut().zip(&d_nodes) {
                *v = [v[0] + eps * dv[0], v[1] + eps * dv[1], 0.0];
            }
            let b: Vec<[f64; 2]> = boundary
                .iter()
                .zip(&d_boundary)
                .map(|(x, dx)| [x[0] + eps * dx[0], x[1] + eps * dx[1]])
                .collect();
            flat(
                replay(&moved, d, &b)
                    .unwrap()
                    .nodes
                    .iter()
                    .map(|v| [v[0], v[1]]),
            )
        };
        let eps = 1e-6;
        let (plus, minus) = (at(eps), at(-eps));
        let gap = relative_gap(&central(&plus, &minus, eps), &analytic);
        eprintln!("replay, triangles={triangles}: relative gap {gap:e}");
        assert!(gap < 1e-7, "triangles={triangles}: {gap:e}");
    }
}

#[test]
fn the_tangent_matches_central_differences_of_keeping_under_a_rotation() {
    let g = naca();
    let alpha = 10f64.to_radians();
    let params = g.curving_params(3, false);
    // the decisions of the mesh rotated by alpha, kept for alpha ± eps
    let (curves, at_alpha) = rotated(&g, alpha, |_| [0.0; 2]);
    let on = loops(&g, &curves);
    let base = vector_adding::curve_mesh(&at_alpha, &on, &params).unwrap();
    let boundary = boundary_points(&at_alpha, &on, 3).unwrap();
    // d/dα of a rotation about the quarter chord: the point turned a quarter turn more
    let spin = |x: [f64; 2]| [-x[1], x[0] - 0.25];
    let (_, _, analytic) = tangent_along(&at_alpha, &base.decisions, &boundary, spin);
    let at = |angle: f64| {
        let (curves, moved) = rotated(&g, angle, |_| [0.0; 2]);
        let on = loops(&g, &curves);
        let (kept, changes) = curve_mesh_keeping(&moved, &on, &params, &base.decisions).unwrap();
        assert!(changes.is_empty(), "{changes:?}");
        flat(kept.mesh.nodes.iter().map(|v| [v[0], v[1]]))
    };
    let eps = 1e-5;
    let (plus, minus) = (at(alpha + eps), at(alpha - eps));
    let gap = relative_gap(&central(&plus, &minus, eps), &analytic);
    eprintln!("rotation: relative gap {gap:e}");
    assert!(gap < 1e-7, "{gap:e}");
}
