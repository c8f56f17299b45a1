//! Property tests of the curving on random geometries and parameters: an ellipse (or a
//! circle) as a wall inside a far-field circle, or meshed inside, curved at order 2 or 3 with
//! 1–4 curved layers, mixed or cut into triangles, by either strategy. The output is always
//! certified valid, conforming, with its boundary nodes on the curves and the area of its
//! cells equal to the area its curved boundary encloses. Bad parameters are named errors,
//! never panics.

use crate::common;

use std::sync::OnceLock;

use common::{check_curved, curved_layers_above_walls};
use geom_curve::{Point2, circle_points};
use mesh_model::Role;
use proptest::prelude::*;
use test_cases::Grown;
use vector_adding::{CurvingError, CurvingParams, Strategy as VectorStrategy};

/// A random domain: an ellipse, rotated and shifted, inside a far-field circle, or alone and
/// meshed inside.
#[derive(Debug, Clone, Copy)]
struct Domain {
    semi_axes: [f64; 2],
    rotate_deg: f64,
    centre: [f64; 2],
    /// Radius of the far field; None: the ellipse is meshed inside.
    farfield: Option<f64>,
    max_spacing: f64,
    first_height: f64,
    growth: f64,
}

fn ellipse(d: &Domain) -> Vec<Point2<f64>> {
    let (s, c) = d.rotate_deg.to_radians().sin_cos();
    (0..256)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 256.0;
            let (x, y) = (d.semi_axes[0] * a.cos(), d.semi_axes[1] * a.sin());
            Point2::new(x * c - y * s + d.centre[0], x * s + y * c + d.centre[1])
        })
        .collect()
}

/// The domain grown by the tool's own stages (`test-cases`).
fn grow(d: &Domain) -> Grown {
    let xy = |p: Vec<Point2<f64>>| p.iter().map(|q| [q.x, q.y]).collect::<Vec<_>>();
    let mut loops = vec![("wall".to_string(), Role::Wall, xy(ellipse(d)))];
    if let Some(r) = d.farfield {
        let far = circle_points(Point2::new(0.0, 0.0), r, 256).unwrap();
        loops.push(("farfield".to_string(), Role::Farfield, xy(far)));
    }
    let mut case = test_cases::case_of("ellipse", loops, d.farfield.is_none());
    case.boundary.max_spacing = d.max_spacing;
    case.layers.max_layers = 30;
    test_cases::grow(&test_cases::with_layers(&case, d.first_height, d.growth))
}

fn domains() -> impl Strategy<Value = Domain> {
    (
        0.3f64..1.5,
        0.2f64..1.0,
        0.0f64..180.0,
        (-0.5f64..0.5, -0.5f64..0.5),
        prop::option::weighted(0.7, 3.0f64..6.0),
        0.08f64..0.4,
        1e-3f64..2e-2,
        1.2f64..1.45,
    )
        .prop_map(
            |(a, ratio, rotate_deg, (x, y), farfield, max_spacing, first_height, growth)| Domain {
                semi_axes: [a, a * ratio],
                rotate_deg,
                centre: [x, y],
                farfield,
                max_spacing,
                first_height,
                growth,
            },
        )
}

fn curving_params() -> impl Strategy<Value = CurvingParams> {
    (2u8..=3, 1u32..=4, any::<bool>(), any::<bool>()).prop_map(
        |(order, min_curved_layers, triangles, one_vector)| CurvingParams {
            order,
            min_curved_layers,
            triangles,
            strategy: if one_vector {
                VectorStrategy::OneVector
            } else {
                VectorStrategy::TwoVector
            },
            ..CurvingParams::default()
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn curved_meshes_are_valid_conforming_and_exact(d in domains(), params in curving_params()) {
        let g = grow(&d);
        let what = format!("{d:?} {params:?}");
        let curved = g.curve(&params)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        let c = check_curved(&what, &curved, &g.curves, params.order);
        prop_assert!(c.fraction > 0.0 && c.fraction < 0.5, "{}: {}", what, c.fraction);
        let layers = curved_layers_above_walls(&g.output, &curved.mesh, params.min_curved_layers);
        prop_assert!(layers.curved_walls > 0, "{}", what);
        prop_assert!(layers.early.is_empty(), "{}: {:?}", what, layers.early);
        replayed_and_linear(&g, &curved, params.order, &what);
    }
}

/// A replay of the run's own decisions is its mesh to the last bit, and the tangent is
/// linear in the node and boundary derivatives.
fn replayed_and_linear(g: &Grown, curved: &vector_adding::Curved, order: u8, what: &str) {
    let layered = &g.output.layered;
    let loops: Vec<vector_adding::LoopCurve<'_>> = (g.curves.iter().zip(&g.nodes))
        .map(|(curve, n)| vector_adding::LoopCurve { curve, t: &n.t })
        .collect();
    let boundary = vector_adding::boundary_points(layered, &loops, order).unwrap();
    let replayed = vector_adding::replay(layered, &curved.decisions, &boundary).unwrap();
    assert!(replayed == curved.mesh, "{what}: the replay differs");
    let field = |k: f64| move |x: &[f64]| [(k * x[0]).sin() + x[1], (k * x[1]).cos() * x[0]];
    let tangent = |f: &dyn Fn(&[f64]) -> [f64; 2]| {
        let d_nodes: Vec<[f64; 2]> = layered.mesh.nodes.iter().map(|v| f(v)).collect();
        let d_boundary: Vec<[f64; 2]> = boundary.iter().map(|v| f(v)).collect();
        vector_adding::tangent(layered, &curved.decisions, &d_nodes, &d_boundary).unwrap()
    };
    let (f1, f2) = (field(1.3), field(-2.1));
    let sum = tangent(&|x| {
        let (a, b) = (f1(x), f2(x));
        [a[0] + 2.0 * b[0], a[1] + 2.0 * b[1]]
    });
    let (t1, t2) = (tangent(&f1), tangent(&f2));
    for ((s, a), b) in sum.iter().zip(&t1).zip(&t2) {
        for d in 0..2 {
            let want = a[d] + 2.0 * b[d];
            assert!(
                (s[d] - want).abs() <= 1e-9 * (1.0 + want.abs()),
                "{what}: {s:?}"
            );
        }
    }
}

/// Found by the property test above (its seed is in `props.proptest-regressions`): a wall
/// that is nearly a circle (radius ≈ 1.05), boundary segments of ≈ 0.22 (so a sagitta of
/// ≈ 0.006) under a first layer of 0.001 growing by 1.2. Straight tops stay invalid up to
/// layer ≈ 10, but some pipes end at layer 6–7 where the layers meet the filled region; the
/// cell's top is then straight and the cell inverted, and the repair cannot bend that top
/// because the fill triangle across it is a needle whose height above the top edge is below
/// the deviation. `curve_mesh` used to report `unrepaired_cells: 3` and leave 3
/// quadrilaterals invalid (cells 511, 522 and 584 at P2, mixed); now such pipes bend the edge
/// they share with the fill triangle (17 of the 20 here), and the repair mends the others by
/// bending the fill triangle in turn.
#[test]
fn a_thin_first_layer_under_coarse_wall_edges_is_valid() {
    let d = Domain {
        semi_axes: [1.0843635934657856, 1.0115962504495868],
        rotate_deg: 0.0,
        centre: [0.0, 0.16057336830555355],
        farfield: Some(3.0),
        max_spacing: 0.3784027530094376,
        first_height: 0.001,
        growth: 1.2,
    };
    let g = grow(&d);
    let params = CurvingParams {
        order: 2,
        min_curved_layers: 1,
        ..CurvingParams::default()
    };
    let curved = g.curve(&params).unwrap();
    assert_eq!(curved.stats.unrepaired_cells, 0, "{:?}", curved.stats);
    // most pipes that end in the filled region hand their deviation to the fill triangles
    // rather than end in inverted cells; the repair mends the rest
    assert!(curved.stats.handed_to_fill > 0, "{:?}", curved.stats);
    check_curved("near circle, thin first layer", &curved, &g.curves, 2);
}

/// A small grown annulus, made once, for the parameter checks.
fn small() -> &'static Grown {
    static GROWN: OnceLock<Grown> = OnceLock::new();
    GROWN.get_or_init(|| {
        grow(&Domain {
            semi_axes: [1.0, 1.0],
            rotate_deg: 0.0,
            centre: [0.0, 0.0],
            farfield: Some(3.0),
            max_spacing: 0.5,
            first_height: 0.02,
            growth: 1.3,
        })
    })
}

/// The name of the parameter a curving run rejected, or None if it ran.
fn rejected(params: &CurvingParams) -> Option<&'static str> {
    let g = small();
    match g.curve(params) {
        Ok(_) => None,
        Err(CurvingError::BadParameter { name, .. }) => Some(name),
        Err(e) => panic!("{params:?}: not a parameter error: {e}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn a_bad_order_is_named(order in any::<u8>().prop_filter("bad", |o| !(2..=3).contains(o)),
                            base in curving_params()) {
        let params = CurvingParams { order, ..base };
        prop_assert_eq!(rejected(&params), Some("order"));
    }

    #[test]
    fn a_bad_stop_threshold_is_named(
        q in prop_oneof![
            -10.0f64..=0.0,
            (1.0f64..10.0).prop_filter("above 1", |q| *q > 1.0),
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(-0.0),
        ],
        base in curving_params(),
    ) {
        let params = CurvingParams { stop_min_scaled_jacobian: q, ..base };
        prop_assert_eq!(rejected(&params), Some("stop_min_scaled_jacobian"));
    }
}

#[test]
fn orders_one_and_four_are_refused_and_two_and_three_run() {
    for (order, want) in [(1, Some("order")), (4, Some("order")), (2, None), (3, None)] {
        let params = CurvingParams {
            order,
            ..CurvingParams::default()
        };
        assert_eq!(rejected(&params), want, "order {order}");
    }
    for q in [1e-9, 1.0] {
        let params = CurvingParams {
            stop_min_scaled_jacobian: q,
            ..CurvingParams::default()
        };
        assert_eq!(rejected(&params), None, "stop threshold {q}");
    }
}

#[test]
fn a_cell_naming_a_missing_node_is_refused_not_panicked_on() {
    // before the curving used mesh_model's structural checks, the edge table indexed by
    // the bad node and panicked
    let mut g = small().clone();
    let n = g.output.layered.mesh.nodes.len() as u32;
    g.output.layered.mesh.cells.nodes_mut(0)[1] = n + 7;
    let e = g.curve(&CurvingParams::default()).unwrap_err();
    assert!(
        matches!(
            e,
            CurvingError::InvalidMesh(mesh_model::Problem::NodeOutOfRange { cell: 0, .. })
        ),
        "{e}"
    );
    assert!(e.to_string().contains(&format!("node {}", n + 7)), "{e}");
}

/// A mesh with a fault of its own and a layering that does not fit it: the mesh's fault is
/// told (the two checks run side by side; the layering's is safe on a broken mesh).
#[test]
fn a_fault_of_the_mesh_is_told_before_one_of_its_layering() {
    let mut g = small().clone();
    let n = g.output.layered.mesh.nodes.len() as u32;
    g.output.layered.mesh.cells.nodes_mut(0)[1] = n + 7;
    g.output.layered.layering.node_layer.pop();
    let e = g.curve(&CurvingParams::default()).unwrap_err();
    assert!(matches!(e, CurvingError::InvalidMesh(_)), "{e}");
    // and alone, the layering's fault is named
    let mut g = small().clone();
    g.output.layered.layering.node_layer.pop();
    let e = g.curve(&CurvingParams::default()).unwrap_err();
    assert!(matches!(e, CurvingError::BadLayers(_)), "{e}");
}

/// The layering is checked as a whole (`Layering::check`) before any curving: a record that
/// does not fit its mesh is a named error, never a panic.
#[test]
fn a_layering_that_does_not_fit_its_mesh_is_named() {
    let layering_error = |edit: &dyn Fn(&mut mesh_model::Layering)| {
        let mut g = small().clone();
        edit(&mut g.output.layered.layering);
        match g.curve(&CurvingParams::default()) {
            Err(CurvingError::BadLayers(why)) => why,
            other => panic!("{other:?}"),
        }
    };
    assert!(
        layering_error(&|l| {
            l.node_layer.pop();
        })
        .contains("node_layer")
    );
    assert!(layering_error(&|l| l.layered_cells = usize::MAX).contains("layered cells"));
    let wrong_parent = layering_error(&|l| {
        let child = l.node_layer.iter().position(|&k| k == 2).unwrap();
        l.node_parents[child][1] = 0; // a wall node two layers below
    });
    assert!(wrong_parent.contains("not one below"), "{wrong_parent}");
}
