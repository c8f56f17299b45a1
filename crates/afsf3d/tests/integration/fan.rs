//! Fans at a sharp trailing edge (`afsf3d`'s `fan`): a closed wedge of 11.4° grows a fan of
//! columns along its trailing edge, both `topo-cut` cuts of its layers are valid (conforming,
//! every cell positive, the volumes balanced, the layering record checked), and the
//! tetrahedra at the edge stay under 160°, where one column along the bisector puts them
//! past 170°.

use afsf3d::{Grown3d, LayerParams, grow_layers};
use geom_surface::{Facet, Surface};
use mesh_model::measure3d::tet_max_dihedral_deg;
use mesh_model::{Mesh, Shape};

/// A closed wedge: the triangle (0, ±0.1), (1, 0) in the x-z plane (its trailing edge at
/// x = 1) extruded along y over `stations` stations 0.25 apart, its sides quads (or each
/// split in two triangles), its ends capped.
fn wedge(stations: usize, triangles: bool) -> Surface {
    let section = [[1.0, 0.0], [0.0, 0.1], [0.0, -0.1]];
    let mut nodes = Vec::new();
    for s in 0..stations {
        for p in section {
            nodes.push([p[0], 0.25 * s as f64, p[1]]);
        }
    }
    let at = |s: usize, i: usize| (3 * s + i % 3) as u32;
    let mut facets = Vec::new();
    for s in 0..stations - 1 {
        for i in 0..3 {
            let k = [at(s, i), at(s + 1, i), at(s + 1, i + 1), at(s, i + 1)];
            if triangles {
                facets.push(Facet::tri(k[0], k[1], k[2]));
                facets.push(Facet::tri(k[0], k[2], k[3]));
            } else {
                facets.push(Facet::quad(k[0], k[1], k[2], k[3]));
            }
        }
    }
    let l = stations - 1;
    facets.push(Facet::tri(at(0, 0), at(0, 1), at(0, 2)));
    facets.push(Facet::tri(at(l, 0), at(l, 2), at(l, 1)));
    let mut surface = Surface::single_patch(nodes, facets, "wall");
    if surface.enclosed_volume() < 0.0 {
        for f in &mut surface.facets {
            let m = f.nodes().len();
            f.0[..m].reverse();
        }
    }
    surface.check().expect("a closed wedge");
    surface
}

/// The layers of `grown`, a valid polyhedral mesh, cut both ways and checked
/// (`stop::cut_and_check`); the tetrahedral cut.
fn cut_and_check(name: &str, grown: &Grown3d) -> Mesh {
    let problems = grown.mesh.validate();
    assert!(problems.is_empty(), "{name}: {problems:?}");
    crate::stop::cut_and_check(name, grown)
}

/// The largest dihedral angle of the tetrahedra of `mesh` with a corner at the trailing edge
/// (within 0.02 of it), away from the wedge's ends (where the edge's chain ends unfanned).
fn trailing_edge_dihedral(mesh: &Mesh) -> f64 {
    let at_edge = |p: [f64; 3]| (p[0] - 1.0).hypot(p[2]) < 0.02 && (0.4..1.6).contains(&p[1]);
    (0..mesh.cells.len())
        .filter(|&c| mesh.cells.get(c).ty.shape == Shape::Tet)
        .filter(|&c| {
            let k = mesh.cells.get(c).corners();
            k.iter().any(|&v| at_edge(mesh.nodes[v as usize]))
        })
        .map(|c| tet_max_dihedral_deg(mesh, c))
        .fold(0.0, f64::max)
}

#[test]
fn a_sharp_trailing_edge_grows_a_fan_and_its_tetrahedra_stay_under_160() {
    for triangles in [false, true] {
        let surface = wedge(9, triangles);
        let params = LayerParams {
            first_height: 2e-3,
            growth: 1.2,
            layers: 6,
            ..LayerParams::default()
        };
        let name = if triangles {
            "wedge, triangles"
        } else {
            "wedge, quads"
        };
        let grown = grow_layers(&surface, &params).unwrap();
        // the seven inner nodes of the trailing edge, three pieces each (a turn of 168.6°)
        assert_eq!(grown.stats.fanned_nodes, 7, "{name}");
        assert_eq!(grown.fan_columns.len(), 7 * 3, "{name}");
        assert_eq!(grown.coverage(), 1.0, "{name}");
        assert!(
            grown.fan_columns.iter().all(|(_, c)| c.len() == 7),
            "{name}"
        );
        let fanned = trailing_edge_dihedral(&cut_and_check(name, &grown));
        let plain = LayerParams {
            fan_threshold_deg: 0.0,
            ..params
        };
        let grown = grow_layers(&surface, &plain).unwrap();
        assert_eq!((grown.stats.fanned_nodes, grown.fan_columns.len()), (0, 0));
        let bisector = trailing_edge_dihedral(&cut_and_check(name, &grown));
        eprintln!(
            "{name}: trailing edge's tetrahedra {fanned:.1}° with fans, {bisector:.1}° without"
        );
        assert!(fanned < 160.0, "{name}: {fanned}");
        assert!(bisector > 170.0, "{name}: {bisector}");
    }
}
