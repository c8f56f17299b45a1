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
         deviation {:.2}°, cell axis {:.2}°, shrinks {} ({} nodes), converged {}, \
         thickness {:.4}",
        mesh.nodes.len(),
        mesh.cell_count(),
        seconds,
        m.min_volume,
        m.edge_deviation_deg,
        m.cell_axis_deg,
        grown.stats.shrinks,
        grown.stats.shrunk_nodes,
        grown.stats.converged,
        between / surface.area(),
    );
    grown
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
    Measures {
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
