//! Columns that stop (issue 47): where a column cannot take its next layer — a slot's two
//! sides growing into each other (the fronts cross), the step at half its spacing with the
//! issue's heights (a cell stays inverted at the tower's foot) — those columns stop and the
//! rest grow on. The layers stay a valid polyhedral mesh whose volumes balance the volume
//! between the wall and the final front, the final front passes its surface check, both cuts
//! of `topo-cut` are valid with the volume kept and the layering record checked, and the
//! columns record where and why they stopped, their neighbours stepping down gradually.

use afsf3d::{Grown3d, LayerParams, StopWhy, grow_layers};
use geom_surface::Surface;
use mesh_model::{Layering, Mesh, Shape, validate};

/// Grows `params` from `surface` and checks the layers: valid, volumes balanced, the final
/// front a valid surface, each column's length its layers (`stops` where short), the stopped
/// columns' neighbours at most one layer deeper per edge near where they stopped.
fn grow_and_check(name: &str, surface: &Surface, params: &LayerParams) -> Grown3d {
    let grown = grow_layers(surface, params).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mesh = &grown.mesh;
    let problems = mesh.validate();
    assert!(problems.is_empty(), "{name}: {}", problems[0]);
    let cells: f64 = (0..mesh.cell_count()).map(|c| mesh.cell_volume(c)).sum();
    let min = (0..mesh.cell_count())
        .map(|c| mesh.cell_volume(c))
        .fold(f64::INFINITY, f64::min);
    assert!(min > 0.0, "{name}: a cell of volume {min}");
    grown
        .front
        .check()
        .unwrap_or_else(|e| panic!("{name}: final front: {e}"));
    let between = grown.front.enclosed_volume() - surface.enclosed_volume();
    assert!(
        (cells - between).abs() <= 1e-9 * between,
        "{name}: cells {cells} vs between {between}"
    );
    for (v, (column, stop)) in grown.columns.iter().zip(&grown.stops).enumerate() {
        match stop {
            None => assert_eq!(column.len(), params.layers + 1, "{name}: column {v}"),
            Some(s) => assert_eq!(column.len(), s.layer + 1, "{name}: column {v}"),
        }
    }
    let stopped = grown.stops.iter().filter(|s| s.is_some()).count();
    assert_eq!(stopped, grown.stats.stopped_columns, "{name}");
    eprintln!(
        "{name}: {} cells, coverage {:.4} ({stopped} columns stopped: {:?}), merges {}, shrinks {}",
        mesh.cell_count(),
        grown.coverage(),
        grown.stops.iter().flatten().map(|s| (s.layer, s.why)).min(),
        grown.stats.merges,
        grown.stats.shrinks,
    );
    grown
}

/// Both cuts of `topo-cut`: valid (conforming, every corner Jacobian positive), every cell's
/// volume positive, summing to the volume inside the cut mesh's boundary (the wall and the
/// final front as the cut splits its quadrilaterals), the layering record checked. Returns the
/// tetrahedral cut.
pub(crate) fn cut_and_check(name: &str, grown: &Grown3d) -> Mesh {
    let mut tets = None;
    let cuts = [
        ("tets", topo_cut::cut_to_tets(&grown.mesh)),
        ("mixed", topo_cut::cut_to_mixed(&grown.mesh)),
    ];
    for (kind, cut) in cuts {
        let mesh = cut.unwrap_or_else(|e| panic!("{name} {kind}: {e}"));
        let problems = validate(&mesh);
        assert!(problems.is_empty(), "{name} {kind}: {}", problems[0]);
        let volumes: Vec<f64> = (0..mesh.cells.len())
            .map(|i| mesh_model::measure3d::cell_volume(&mesh, i))
            .collect();
        assert!(volumes.iter().all(|&v| v > 0.0), "{name} {kind}");
        let sum: f64 = volumes.iter().sum();
        let inside: f64 = mesh
            .boundary
            .iter()
            .map(|f| geom_surface::facet_volume6(&mesh.nodes, f.corners(), [0.0; 3]))
            .sum::<f64>()
            / 6.0;
        assert!(
            (sum - inside).abs() <= 1e-9 * inside,
            "{name} {kind}: {sum} vs {inside}"
        );
        let layering = Layering::new(
            &mesh,
            grown.node_layer.clone(),
            grown.node_parents.clone(),
            mesh.cells.len(),
        );
        assert_eq!(layering.check(&mesh), None, "{name} {kind}");
        eprintln!(
            "{name} {kind}: {} cells ({} pyramids, {} tets), max dihedral {:.1}°",
            mesh.cells.len(),
            mesh.count(Shape::Pyramid),
            mesh.count(Shape::Tet),
            topo_cut::max_dihedral_deg(&mesh)
        );
        tets.get_or_insert(mesh);
    }
    tets.expect("the tetrahedral cut")
}

/// A block with a slot 0.1 wide through it: the slot's two sides grow towards each other.
fn slot() -> Surface {
    Surface::voxels([5, 3, 3], 0.1, |[i, _, k]| k == 0 || i != 2, "slot")
}

#[test]
fn a_slots_sides_stop_where_they_meet_and_the_rest_grows_on() {
    // thicker than half the slot by layer 5
    let params = LayerParams {
        first_height: 1e-2,
        growth: 1.2,
        layers: 10,
        ..LayerParams::default()
    };
    let surface = slot();
    let grown = grow_and_check("slot", &surface, &params);
    let stops: Vec<_> = grown.stops.iter().flatten().collect();
    assert!(!stops.is_empty());
    assert!(stops.iter().any(|s| s.why == StopWhy::FrontsCross));
    // the first stop where the sides meet: the layers' tops 0.05 apart by layer 4 or 5,
    // shrunk until layer 7
    let first = stops.iter().map(|s| s.layer).min().unwrap();
    assert!((4..=8).contains(&first), "first stop in layer {first}");
    // every column that stopped for crossing fronts stands in the slot (x 0.2 to 0.3) or on
    // its rim's faces next to it (the layers, 0.17 thick, reach over the rim)
    for (v, s) in grown.stops.iter().enumerate() {
        if s.is_some_and(|s| s.why == StopWhy::FrontsCross) {
            let x = surface.nodes[v][0];
            assert!((0.1..=0.4).contains(&x), "node {v} at x = {x}");
        }
    }
    // the outside of the block grows every layer
    assert!(grown.coverage() > 0.5, "{}", grown.coverage());
    cut_and_check("slot", &grown);
}

#[test]
fn the_step_at_half_its_spacing_stops_columns_at_the_towers_foot() {
    // the heights at quads of 0.05: an inverted cell at the tower's foot in layer 12
    // stopped the whole growth before columns could stop
    let params = LayerParams {
        first_height: 2e-3,
        growth: 1.2,
        layers: 15,
        ..LayerParams::default()
    };
    let grown = grow_and_check("step, quads of 0.05", &Surface::step(2), &params);
    assert!(grown.coverage() > 0.95, "{}", grown.coverage());
    cut_and_check("step, quads of 0.05", &grown);
}

/// With `stop_gap`, the slot's sides stop before they meet: the columns facing across it
/// stop for that reason, none because the fronts crossed, and the gap between the last
/// fronts stays open (every node of one side's top keeps off the other side's).
#[test]
fn with_stop_gap_a_slots_sides_stop_before_they_meet() {
    let params = LayerParams {
        first_height: 1e-2,
        growth: 1.2,
        layers: 10,
        stop_gap: 3.0,
        ..LayerParams::default()
    };
    let surface = slot();
    let grown = grow_and_check("slot", &surface, &params);
    let stops: Vec<_> = grown.stops.iter().flatten().collect();
    assert!(stops.iter().any(|s| s.why == StopWhy::FrontsNear));
    assert!(!stops.iter().any(|s| s.why == StopWhy::FrontsCross));
    // in the slot's upper part (x from 0.2 to 0.3, away from its ends and its floor, where
    // the sides and the floor merge as at any concave edge), the two sides' last nodes
    let front = &grown.front;
    let inside =
        |p: [f64; 3]| (0.2..=0.3).contains(&p[0]) && (0.08..0.22).contains(&p[1]) && p[2] > 0.22;
    let (mut left, mut right) = (f64::NEG_INFINITY, f64::INFINITY);
    for p in front.nodes.iter().copied().filter(|&p| inside(p)) {
        if p[0] < 0.25 {
            left = left.max(p[0]);
        } else {
            right = right.min(p[0]);
        }
    }
    assert!(right - left > 0.02, "the slot's fronts {left} and {right}");
    assert!(grown.coverage() > 0.5, "{}", grown.coverage());
    // the tetrahedral cut, and the mixed cut as the pipeline makes it (prisms and hexahedra
    // with a corner scaled Jacobian under 0.2 cut too: beside the stopped columns the plain
    // mixed cut would keep a hexahedron inverted at a corner)
    let low = topo_cut::quality::low_corner_cells(&grown.mesh, 0.2);
    for (kind, cut) in [
        ("tets", topo_cut::cut_to_tets(&grown.mesh)),
        ("mixed", topo_cut::cut_to_mixed_cutting(&grown.mesh, &low)),
    ] {
        let mesh = cut.unwrap_or_else(|e| panic!("slot {kind}: {e}"));
        let problems = validate(&mesh);
        assert!(problems.is_empty(), "slot {kind}: {}", problems[0]);
    }
}
