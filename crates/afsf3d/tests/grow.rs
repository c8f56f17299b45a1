//! The must-show properties of the layer growth on the sphere, the cube and the step: a valid
//! polyhedral mesh, cell volumes summing to the volume between the surface and the final
//! front (integrated independently over the two closed surfaces), every wall node keeping
//! its full column (coverage 100 %), the first layer's extrusion edges within 30° of the
//! wall normal.

use afsf3d::{Grown3d, LayerParams, grow_layers};
use geom_surface::{Surface, angle_between, fan_normal};

struct Measures {
    min_volume: f64,
    /// Largest angle between a first-layer extrusion edge and its node's wall normal (deg).
    edge_deviation_deg: f64,
    /// Largest angle between a first-layer cell's axis (bottom centroid to top centroid) and
    /// its wall facet's normal (deg).
    cell_axis_deg: f64,
    /// Largest angle, over every layer, between an extrusion edge and the angle-weighted
    /// normal of the front it grew from (deg).
    worst_deviation_deg: f64,
    /// Largest corner angle of the final front's facets (deg).
    front_max_angle_deg: f64,
}

fn grow_and_check(name: &str, surface: &Surface, params: &LayerParams) -> Grown3d {
    let start = std::time::Instant::now();
    let grown = grow_layers(surface, params).unwrap_or_else(|e| panic!("{name}: {e}"));
    let seconds = start.elapsed().as_secs_f64();
    let mesh = &grown.mesh;
    let problems = mesh.validate();
    assert!(problems.is_empty(), "{name}: {}", problems[0]);
    assert_eq!(mesh.cell_count(), params.layers * surface.facets.len());

    // coverage: every wall node keeps its full column
    let full = grown
        .columns
        .iter()
        .filter(|c| c.len() == params.layers + 1)
        .count();
    assert_eq!(
        full,
        surface.nodes.len(),
        "{name}: coverage {full}/{}",
        surface.nodes.len()
    );

    // volumes: the cells against the divergence theorem over the wall and the final front
    let cells: f64 = (0..mesh.cell_count()).map(|c| mesh.cell_volume(c)).sum();
    grown
        .front
        .check()
        .unwrap_or_else(|e| panic!("{name}: final front: {e}"));
    let between = grown.front.enclosed_volume() - surface.enclosed_volume();
    assert!(
        (cells - between).abs() <= 1e-9 * between,
        "{name}: cells {cells} vs between {between}"
    );

    let m = measures(surface, &grown);
    assert!(m.min_volume > 0.0);
    assert!(
        m.edge_deviation_deg <= 30.0,
        "{name}: {}",
        m.edge_deviation_deg
    );
    eprintln!(
        "{name}: {} nodes, {} cells, {:.3} s, min volume {:.3e}, first-layer extrusion edge \
         deviation {:.2}° (all layers {:.2}°), cell axis {:.2}°, front max angle {:.1}°, shrinks {} ({} nodes), converged {}, \
         mean thickness {:.4}",
        mesh.nodes.len(),
        mesh.cell_count(),
        seconds,
        m.min_volume,
        m.edge_deviation_deg,
        m.worst_deviation_deg,
        m.cell_axis_deg,
        m.front_max_angle_deg,
        grown.stats.shrinks,
        grown.stats.shrunk_nodes,
        grown.stats.converged,
        mean_thickness(surface, &grown),
    );
    grown
}

/// The mean distance from a wall node to the top of its column.
fn mean_thickness(surface: &Surface, grown: &Grown3d) -> f64 {
    let top = |c: &Vec<u32>| grown.mesh.nodes[*c.last().expect("a node") as usize];
    grown
        .columns
        .iter()
        .enumerate()
        .map(|(i, c)| geom_predicates::vector::dist(surface.nodes[i], top(c)))
        .sum::<f64>()
        / surface.nodes.len() as f64
}

fn measures(surface: &Surface, grown: &Grown3d) -> Measures {
    let mesh = &grown.mesh;
    let min_volume = (0..mesh.cell_count())
        .map(|c| mesh.cell_volume(c))
        .fold(f64::INFINITY, f64::min);
    let normals = surface.node_normals();
    let deg = 180.0 / std::f64::consts::PI;
    let edge_deviation_deg = grown
        .columns
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let step =
                geom_predicates::vector::sub(mesh.nodes[c[1] as usize], mesh.nodes[c[0] as usize]);
            angle_between(step, normals[i]) * deg
        })
        .fold(0.0, f64::max);
    let centroid = |k: &[u32], level: usize| -> [f64; 3] {
        let mut s = [0.0; 3];
        for &v in k {
            let p = mesh.nodes[grown.columns[v as usize][level] as usize];
            (0..3).for_each(|d| s[d] += p[d] / k.len() as f64);
        }
        s
    };
    let cell_axis_deg = surface
        .facets
        .iter()
        .map(|f| {
            let axis = geom_predicates::vector::sub(centroid(f.nodes(), 1), centroid(f.nodes(), 0));
            angle_between(axis, fan_normal(&surface.nodes, f.nodes())) * deg
        })
        .fold(0.0, f64::max);
    let levels = grown.columns[0].len();
    let level = |k: usize| -> Vec<[f64; 3]> {
        grown
            .columns
            .iter()
            .map(|c| mesh.nodes[c[k] as usize])
            .collect()
    };
    let mut worst_deviation_deg = 0.0f64;
    for k in 0..levels - 1 {
        let front = Surface {
            nodes: level(k),
            ..surface.clone()
        };
        let (below, above) = (front.nodes.clone(), level(k + 1));
        for (i, n) in front.node_normals().iter().enumerate() {
            let step = geom_predicates::vector::sub(above[i], below[i]);
            worst_deviation_deg = worst_deviation_deg.max(angle_between(step, *n) * deg);
        }
    }
    let top = &grown.front;
    let front_max_angle_deg = top
        .facets
        .iter()
        .flat_map(|f| {
            let k = f.nodes();
            (0..k.len()).map(move |i| {
                let p = |j: usize| top.nodes[k[(i + j) % k.len()] as usize];
                let a = geom_predicates::vector::sub(p(k.len() - 1), p(0));
                let b = geom_predicates::vector::sub(p(1), p(0));
                angle_between(a, b) * deg
            })
        })
        .fold(0.0, f64::max);
    Measures {
        worst_deviation_deg,
        front_max_angle_deg,
        min_volume,
        edge_deviation_deg,
        cell_axis_deg,
    }
}

#[test]
fn the_sphere_keeps_30_full_layers() {
    let params = LayerParams {
        layers: 30,
        ..LayerParams::default()
    };
    grow_and_check("sphere", &Surface::sphere(1.0, 3), &params);
}

#[test]
fn the_cube_keeps_30_full_layers_at_its_sharp_edges_and_corners() {
    let params = LayerParams {
        layers: 30,
        ..LayerParams::default()
    };
    grow_and_check("cube quads", &Surface::cube(1.0, 8, false), &params);
    grow_and_check("cube triangles", &Surface::cube(1.0, 8, true), &params);
}

#[test]
fn the_step_keeps_15_full_layers_in_its_concave_edges() {
    let params = LayerParams {
        first_height: 2e-3,
        growth: 1.2,
        layers: 15,
        ..LayerParams::default()
    };
    grow_and_check("step", &Surface::step(1), &params);
}

#[test]
fn bad_input_is_an_error() {
    let mut open = Surface::cube(1.0, 2, true);
    open.facets.pop();
    open.facet_patch.pop();
    let e = grow_layers(&open, &LayerParams::default()).unwrap_err();
    assert!(e.to_string().contains("not closed"), "{e}");
    let bad = LayerParams {
        growth: 0.5,
        ..LayerParams::default()
    };
    assert!(grow_layers(&Surface::sphere(1.0, 1), &bad).is_err());
}

#[test]
fn each_cell_follows_the_face_contract_with_topo_cut() {
    let surface = Surface::cube(1.0, 2, false);
    let params = LayerParams {
        layers: 3,
        ..LayerParams::default()
    };
    let grown = grow_layers(&surface, &params).unwrap();
    let mesh = &grown.mesh;
    for c in 0..mesh.cell_count() {
        let (layer, pipe) = (mesh.cell_layer[c] as usize, mesh.cell_pipe[c] as usize);
        assert_eq!(c, layer * surface.facets.len() + pipe);
        let wall = surface.facets[pipe].nodes();
        let at =
            |k: usize| -> Vec<u32> { wall.iter().map(|&v| grown.columns[v as usize][k]).collect() };
        let faces = mesh.cell(c);
        assert_eq!(faces.len(), 2 + wall.len());
        // face 0: the bottom, stored as the front sees it, turned towards the wall
        assert_eq!(mesh.face(faces[0].face as usize), at(layer).as_slice());
        assert!(faces[0].reversed);
        assert_eq!(mesh.face(faces[1].face as usize), at(layer + 1).as_slice());
        assert!(!faces[1].reversed);
        // the sides, along the bottom's edges a → b, outward as (a, b, b', a')
        let (lo, hi) = (at(layer), at(layer + 1));
        for i in 0..wall.len() {
            let j = (i + 1) % wall.len();
            let mut side = mesh.face(faces[2 + i].face as usize).to_vec();
            if faces[2 + i].reversed {
                side.reverse();
            }
            let start = side.iter().position(|&v| v == lo[i]).unwrap();
            side.rotate_left(start);
            assert_eq!(side, vec![lo[i], lo[j], hi[j], hi[i]]);
        }
    }
}
