//! The NACA0012 wing of a 2D case (`xtask::wing`) through the 3D stages: layers grown by
//! `afsf3d` with every wall node's column full, the layer cells exact in volume, and both
//! cuts of `topo-cut` conforming and positive with the volume kept. The dissertation's
//! cases at full size are measured by the example `wing3d` (`docs/3d.md`).

use afsf3d::{LayerParams, grow_layers};
use mesh_model::{Mesh, validate};

fn tet_volume(mesh: &Mesh) -> f64 {
    mesh.cells
        .iter()
        .map(|c| {
            let k = c.corners();
            let p = |i: usize| mesh.nodes[k[i] as usize];
            let sub = geom_predicates::vector::sub;
            let (a, b, d) = (sub(p(1), p(0)), sub(p(2), p(0)), sub(p(3), p(0)));
            geom_predicates::vector::dot(geom_predicates::vector::cross3(a, b), d) / 6.0
        })
        .sum()
}

/// The NACA0012 wing of span 0.5 (surface and layers from 1e-3, growth 1.3) and `layers`
/// layers grown from it.
fn wing(triangles: bool, layers: usize) -> (geom_surface::Surface, afsf3d::Grown3d) {
    let mut case = curvemesh::load::load_2d("naca0012").unwrap();
    case.layers.first_height = 1e-3;
    let (wall, _) = curvemesh::wing::wing_surface(&case, 0.5, triangles).unwrap();
    let params = LayerParams {
        first_height: 1e-3,
        growth: 1.3,
        layers,
        ..LayerParams::default()
    };
    let grown = grow_layers(&wall, &params).unwrap();
    (wall, grown)
}

#[test]
fn a_naca0012_wing_grows_full_columns_and_cuts_into_valid_cells() {
    let (wall, grown) = wing(true, 4);
    assert!(
        grown.columns.iter().all(|c| c.len() == 5),
        "a column was cut off"
    );
    assert!(grown.mesh.validate().is_empty());
    let between = grown.front.enclosed_volume() - wall.enclosed_volume();
    let cells: f64 = (0..grown.mesh.cell_count())
        .map(|c| grown.mesh.cell_volume(c))
        .sum();
    assert!(
        (cells - between).abs() < 1e-9 * between,
        "{cells} vs {between}"
    );
    let tets = topo_cut::cut_to_tets(&grown.mesh).unwrap();
    assert!(validate(&tets).is_empty(), "{:?}", validate(&tets).first());
    assert!((tet_volume(&tets) - cells).abs() < 1e-9 * cells);
    let mixed = topo_cut::cut_to_mixed(&grown.mesh).unwrap();
    assert!(
        validate(&mixed).is_empty(),
        "{:?}",
        validate(&mixed).first()
    );
    assert_eq!(mixed.count(mesh_model::Shape::Prism), 4 * wall.facets.len());
}

/// With the quads kept (hexahedra on the side, prisms over the caps' triangles) the cells at
/// the blunt trailing edge keep an edge-normalised corner scaled Jacobian above the issue's
/// 0.2 for the first layers (measured 0.444 at 3 layers, span 2; `docs/3d.md` has the
/// values at 10–23 layers). The caps are left out: their thinnest 2D cells bound it at the
/// sine of their corner angles (0.045) before any growth.
#[test]
fn the_trailing_edge_cells_of_a_wing_with_quads_stay_above_the_bar() {
    let (wall, grown) = wing(false, 3);
    let mixed = topo_cut::cut_to_mixed(&grown.mesh).unwrap();
    let x_te = wall.nodes.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    let side = wall.patches.iter().position(|p| p.name == "wall").unwrap() as u32;
    let mut worst = f64::INFINITY;
    for i in 0..mixed.cells.len() {
        let Some(q) = mesh_model::measure3d::min_corner_scaled_jacobian(&mixed, i) else {
            continue;
        };
        let k = mixed.cells.get(i).corners();
        let at_te = k.iter().any(|&v| mixed.nodes[v as usize][0] > x_te - 0.01);
        if at_te && wall.facet_patch[mixed.cell_pipe[i] as usize] == side {
            worst = worst.min(q);
        }
    }
    assert!(
        worst > 0.4,
        "trailing edge: min corner scaled Jacobian {worst}"
    );
}

#[test]
fn a_sharp_trailing_edge_grows_fans_and_every_column_of_a_thick_stack() {
    // the NACA 0012 with its sharp trailing edge (a 16° wedge), span 2, its span stations
    // graded from 1e-3 at the tips, 45 layers from 1e-3 at growth 1.3: the trailing edge's
    // nodes grow fans; next to its ends at the tips, where the first layer is as high as the
    // span step, unbalanced fans fold the tip's first cells, and one column stopped in the
    // first layer stopped every column of the thick stack (the fans' copies are balanced then)
    let text = "[[loop]]\nrole = \"wall\"\nnaca = \"0012\"\n\n[[loop]]\nrole = \"farfield\"\n\
                circle = { center = [0.5, 0.0], radius = 20.0 }\n\n[layers]\nfirst_height = 1e-3\n";
    let curvemesh::load::AnyCase::Two(case) = curvemesh::load::parse_str(text).unwrap() else {
        panic!("a 2D case");
    };
    let (wall, _) = curvemesh::wing::wing_surface(&case, 2.0, true).unwrap();
    let params = LayerParams {
        first_height: 1e-3,
        growth: 1.3,
        layers: 45,
        ..LayerParams::default()
    };
    let grown = grow_layers(&wall, &params).unwrap();
    assert!(grown.stats.fanned_nodes > 40, "{:?}", grown.stats);
    assert_eq!(grown.stats.unfanned_nodes, 0);
    assert_eq!(grown.coverage(), 1.0, "{:?}", grown.stats);
    assert!(grown.mesh.validate().is_empty());
}
