//! Fans at a sharp trailing edge (`afsf3d`'s `fan`): a closed wedge of 11.4° grows a fan of
//! columns along its trailing edge, its two ends fanned over the end caps' rims too, both
//! `topo-cut` cuts of its layers are valid (conforming, every cell positive, the volumes
//! balanced, the layering record checked), and the tetrahedra at the edge stay under 160°,
//! where one column along the bisector puts them past 170°.

use afsf3d::{Grown3d, LayerParams, grow_layers};
use geom_surface::{Facet, Surface};
use mesh_model::measure3d::tet_max_dihedral_deg;
use mesh_model::{Mesh, Shape};

/// A closed wedge: the triangle (0, ±0.1), (1, 0) in the x-z plane (its trailing edge at
/// x = 1), its upper and lower sides each with a node at mid-chord, extruded along y over
/// `stations` stations 0.25 apart, its sides quads (or each split in two triangles), its ends
/// capped by three triangles (so that the trailing edge's end has a rim edge to a node on the
/// rim, not to a corner).
fn wedge(stations: usize, triangles: bool) -> Surface {
    let section = [
        [1.0, 0.0],
        [0.5, 0.05],
        [0.0, 0.1],
        [0.0, -0.1],
        [0.5, -0.05],
    ];
    let m = section.len();
    let mut nodes = Vec::new();
    for s in 0..stations {
        for p in section {
            nodes.push([p[0], 0.25 * s as f64, p[1]]);
        }
    }
    let at = |s: usize, i: usize| (m * s + i % m) as u32;
    let mut facets = Vec::new();
    for s in 0..stations - 1 {
        for i in 0..m {
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
    for [a, b, c] in [[0, 1, 4], [1, 2, 4], [2, 3, 4]] {
        facets.push(Facet::tri(at(0, a), at(0, b), at(0, c)));
        facets.push(Facet::tri(at(l, a), at(l, c), at(l, b)));
    }
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
/// (within 0.02 of it), away from the wedge's ends (where the cut alone leaves tetrahedra
/// over 170° whether the ends are fanned or not: 172.2° and 174.9°).
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
        // the nine nodes of the trailing edge, three pieces each (a turn of 168.6°): the seven
        // inner ones and the two ends (fanned over their caps' rims)
        assert_eq!(grown.stats.fanned_nodes, 9, "{name}");
        assert_eq!(grown.fan_columns.len(), 9 * 3, "{name}");
        // the column at each rim edge's far end (mid-chord, half a chord from the trailing
        // edge's end: the fan's thin cells along the rim fold there in the second layer) and
        // the ends' fans stop early; every other column keeps its six layers
        let (x, y) = (&surface.nodes, 0.25 * 8.0);
        let at_end = |v: u32| {
            let p = x[grown.columns[v as usize][0] as usize];
            p[1] == 0.0 || p[1] == y
        };
        for (v, stop) in grown.stops.iter().enumerate() {
            assert!(stop.is_none() || at_end(v as u32), "{name}: {v} {stop:?}");
        }
        assert!(grown.coverage() > 0.95, "{name}: {}", grown.coverage());
        assert!(
            grown
                .fan_columns
                .iter()
                .all(|(v, c)| c.len() == 7 || at_end(*v)),
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
