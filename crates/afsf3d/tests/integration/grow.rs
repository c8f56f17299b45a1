//! The must-show properties of the layer growth on the sphere, the cube and the step (at two
//! spacings, the finer one merging children): a valid polyhedral mesh, cell volumes summing
//! to the volume between the surface and the final front (integrated independently over the
//! two closed surfaces), every wall node's column reaching the last layer (coverage 100 %,
//! merged or not), the first layer's extrusion edges within 30° of the wall normal; where
//! children merge, the cells cut by `topo-cut` into tetrahedra and into mixed cells, every
//! one positive, their volumes summing to the volume inside the cut mesh's boundary, and
//! the layering record checked on the cut mesh.

use afsf3d::{Grown3d, LayerParams, grow_layers};
use geom_surface::{Facet, Surface, angle_between, fan_normal};
use mesh_model::measure3d::corner_determinants;
use mesh_model::{Layering, Mesh, NONE, Shape, validate};

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
    if grown.stats.merges == 0 {
        assert_eq!(mesh.cell_count(), params.layers * surface.facets.len());
    }
    let (covered, merged) = coverage(&grown, params.layers);
    assert_eq!(covered, surface.nodes.len(), "{name}: coverage");

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
         mean thickness {:.4}, coverage {covered}/{} ({} full unmerged, {merged} merged columns), \
         merges {} by layer {:?}",
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
        surface.nodes.len(),
        covered - merged,
        grown.stats.merges,
        grown.layer_merges,
    );
    grown
}

/// The columns reaching the last layer, and how many of them hold a merged child.
fn coverage(grown: &Grown3d, layers: usize) -> (usize, usize) {
    let reaches = |c: &Vec<u32>| {
        c.len() == layers + 1
            && grown.node_layer[*c.last().expect("a node") as usize] as usize == layers
    };
    let merged = |c: &Vec<u32>| c.iter().any(|&v| grown.node_parents[v as usize][1] != NONE);
    let covered = grown.columns.iter().filter(|c| reaches(c)).count();
    let merged = grown
        .columns
        .iter()
        .filter(|c| reaches(c) && merged(c))
        .count();
    (covered, merged)
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

/// For each layer, the front it grew from (the bottoms of its cells, over all the mesh's
/// nodes) and the child of each of its nodes.
#[allow(clippy::type_complexity)]
fn fronts(grown: &Grown3d) -> Vec<(Surface, std::collections::HashMap<u32, u32>)> {
    let mesh = &grown.mesh;
    let layers = grown.layer_merges.len();
    let mut out: Vec<(Surface, std::collections::HashMap<u32, u32>)> = (0..layers)
        .map(|_| {
            let s = Surface::single_patch(mesh.nodes.clone(), Vec::new(), "front");
            (s, std::collections::HashMap::new())
        })
        .collect();
    for c in 0..mesh.cell_count() {
        let k = mesh.face(mesh.cell(c)[0].face as usize);
        let facet = Facet([
            k[0],
            k[1],
            k[2],
            k.get(3).copied().unwrap_or(geom_surface::NO_NODE),
        ]);
        let layer = mesh.cell_layer[c] as usize;
        out[layer].0.facets.push(facet);
        out[layer].0.facet_patch.push(0);
    }
    for (v, p) in grown.node_parents.iter().enumerate() {
        for &parent in p.iter().filter(|&&q| q != NONE) {
            out[grown.node_layer[v] as usize - 1]
                .1
                .insert(parent, v as u32);
        }
    }
    out
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
    let mut worst_deviation_deg = 0.0f64;
    for (layer, (front, child)) in fronts(grown).iter().enumerate() {
        for (v, n) in front.node_normals().iter().enumerate() {
            let Some(&c) = child.get(&(v as u32)) else {
                continue;
            };
            if grown.node_layer[v] as usize == layer {
                let step = geom_predicates::vector::sub(mesh.nodes[c as usize], mesh.nodes[v]);
                worst_deviation_deg = worst_deviation_deg.max(angle_between(step, *n) * deg);
            }
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

/// The smallest edge-normalised corner scaled Jacobian
/// (`mesh_model::measure3d::corner_determinants`) of the cells of layers `layers` (from 0)
/// whose columns did not merge there, each cell read off its wall facet's columns.
fn min_corner_sj(surface: &Surface, grown: &Grown3d, layers: std::ops::Range<usize>) -> f64 {
    let x = &grown.mesh.nodes;
    let mut worst = f64::INFINITY;
    let mut p = Vec::with_capacity(8);
    for k in layers {
        for f in &surface.facets {
            let level = |l: usize| f.nodes().iter().map(move |&v| grown.columns[v as usize][l]);
            let top: Vec<u32> = level(k + 1).collect();
            if (0..top.len()).any(|i| top[i] == top[(i + 1) % top.len()]) {
                continue; // merged: not a prism or hexahedron
            }
            p.clear();
            p.extend(level(k).chain(level(k + 1)).map(|v| x[v as usize]));
            worst = corner_determinants(&p, true)
                .into_iter()
                .fold(worst, f64::min);
        }
    }
    worst
}

#[test]
fn the_sphere_keeps_30_full_layers() {
    let params = LayerParams {
        layers: 30,
        ..LayerParams::default()
    };
    let sphere = Surface::sphere(1.0, 3);
    let grown = grow_and_check("sphere", &sphere, &params);
    // the bar: every prism corner's scaled Jacobian above 0.5 (measured 0.795)
    let sj = min_corner_sj(&sphere, &grown, 0..30);
    assert!(sj > 0.79, "sphere: min corner scaled Jacobian {sj}");
}

#[test]
fn the_cube_keeps_30_full_layers_at_its_sharp_edges_and_corners() {
    let params = LayerParams {
        layers: 30,
        ..LayerParams::default()
    };
    let cube = Surface::cube(1.0, 8, false);
    let grown = grow_and_check("cube quads", &cube, &params);
    // 1/√3 at the corners: the corner node's direction stands off each face at 1/√3
    let sj = min_corner_sj(&cube, &grown, 0..30);
    assert!(sj > 0.57, "cube quads: min corner scaled Jacobian {sj}");
    // (triangles: 0.31, prisms over the right triangles' 45° corners at the cube's corners)
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
    let step = Surface::step(1);
    let grown = grow_and_check("step", &step, &params);
    // the tower's foot corners: the angle-weighted normal stands off the tower's sides at
    // 1/√11 ≈ 0.30 (0.34 after the smoothing)
    let sj = min_corner_sj(&step, &grown, 0..12);
    assert!(
        sj > 0.34,
        "step: min corner scaled Jacobian {sj} in layers 0-11"
    );
    // turned to stand off every facet at 0.55 (`stand_off`): 0.535 in the first layer, above
    // 0.5 up to layer 11 (thickness 0.079); the last three layers, as thick as the wall's
    // spacing, squeeze the cells over the block's top diagonally off each foot corner
    // (docs/3d.md): 0.40, 0.21, 0.08
    let turned = LayerParams {
        stand_off: 0.55,
        ..params
    };
    let grown = grow_and_check("step, stand-off 0.55", &step, &turned);
    let sj = min_corner_sj(&step, &grown, 0..12);
    assert!(
        sj > 0.5,
        "step: min corner scaled Jacobian {sj} in layers 0-11"
    );
    let first = min_corner_sj(&step, &grown, 0..1);
    assert!(
        first > 0.53,
        "step: first layer's min corner scaled Jacobian {first}"
    );
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

/// The volume of a linear cell of `mesh`: the cone from its first corner over its faces
/// (turned outward), each fanned from its centroid as `PolyMesh::cell_volume` does.
fn cell_volume(mesh: &Mesh, shape: Shape, k: &[u32]) -> f64 {
    let o = mesh.nodes[k[0] as usize];
    let six: f64 = shape
        .faces()
        .iter()
        .map(|f| {
            let face: Vec<u32> = f.iter().map(|&j| k[j]).collect();
            geom_surface::facet_volume6(&mesh.nodes, &face, o)
        })
        .sum();
    six / 6.0
}

/// Every cell, merged or not, in the contract's order: face 0 the bottom, face 1 the top
/// when it has three nodes or more (fewer than the bottom where children merged), then one
/// side per bottom edge a → b, turned outward as (a, b, b', a') or (a, b, m) where the two
/// children merged; every top node a child (by `node_parents`) of a bottom node.
fn merged_cells_follow_the_contract(name: &str, grown: &Grown3d) {
    let mesh = &grown.mesh;
    let (mut merged, mut topless) = (0, 0);
    for c in 0..mesh.cell_count() {
        let faces = mesh.cell(c);
        let bottom = mesh.face(faces[0].face as usize);
        assert!(faces[0].reversed, "{name}: cell {c}");
        let m = bottom.len();
        let has_top = faces.len() == m + 2;
        assert!(has_top || faces.len() == m + 1, "{name}: cell {c}");
        let child_of = |v: u32, p: u32| grown.node_parents[v as usize].contains(&p);
        if has_top {
            let top = mesh.face(faces[1].face as usize);
            assert!(top.iter().all(|&t| bottom.iter().any(|&b| child_of(t, b))));
            merged += usize::from(top.len() < m);
        } else {
            topless += 1;
        }
        for i in 0..m {
            let f = &faces[1 + usize::from(has_top) + i];
            let mut side = mesh.face(f.face as usize).to_vec();
            if f.reversed {
                side.reverse();
            }
            let at = side
                .iter()
                .position(|&v| v == bottom[i])
                .expect("the edge's start");
            side.rotate_left(at);
            assert_eq!(side[1], bottom[(i + 1) % m], "{name}: cell {c} side {i}");
            assert!(side.len() == 4 || (side.len() == 3 && child_of(side[2], side[0])));
        }
    }
    eprintln!("{name}: {merged} cells under a smaller top, {topless} under an edge");
    assert!(merged + topless > 0, "{name}: no merged cell");
}

/// The layers cut by `topo-cut` into tetrahedra and into mixed cells: each cut valid
/// (conforming, every corner Jacobian positive), every cell's volume positive, the volumes
/// summing to the volume inside the cut mesh's boundary (the wall and the final front) to
/// 1e-9, and the layering record (the grown nodes' layers and parents with the cut cells'
/// layers and pipes) passing its check.
fn cut_and_check(name: &str, grown: &Grown3d) {
    merged_cells_follow_the_contract(name, grown);
    let cuts = [
        ("tets", topo_cut::cut_to_tets(&grown.mesh)),
        ("mixed", topo_cut::cut_to_mixed(&grown.mesh)),
    ];
    for (kind, cut) in cuts {
        let mesh = cut.unwrap_or_else(|e| panic!("{name} {kind}: {e}"));
        let problems = validate(&mesh);
        assert!(problems.is_empty(), "{name} {kind}: {}", problems[0]);
        let (mut sum, mut min) = (0.0, f64::INFINITY);
        let mut count = [0usize; 4];
        for c in mesh.cells.iter() {
            let v = cell_volume(&mesh, c.ty.shape, c.corners());
            sum += v;
            min = min.min(v);
            count[[Shape::Tet, Shape::Pyramid, Shape::Prism, Shape::Hex]
                .iter()
                .position(|&s| s == c.ty.shape)
                .expect("a standard cell")] += 1;
        }
        let inside: f64 = mesh
            .boundary
            .iter()
            .map(|f| geom_surface::facet_volume6(&mesh.nodes, f.corners(), [0.0; 3]))
            .sum::<f64>()
            / 6.0;
        assert!(min > 0.0, "{name} {kind}: a cell of volume {min}");
        assert!(
            (sum - inside).abs() <= 1e-9 * inside,
            "{name} {kind}: cells {sum} vs inside {inside}"
        );
        let layering = Layering::new(
            &mesh,
            grown.node_layer.clone(),
            grown.node_parents.clone(),
            mesh.cells.len(),
        );
        assert_eq!(layering.check(&mesh), None, "{name} {kind}");
        eprintln!(
            "{name} {kind}: {} cells (tet {}, pyramid {}, prism {}, hex {}), min volume {min:.3e}, \
             max dihedral {:.1}°",
            mesh.cells.len(),
            count[0],
            count[1],
            count[2],
            count[3],
            topo_cut::max_dihedral_deg(&mesh),
        );
    }
}

#[test]
fn the_step_merges_children_where_its_front_shrinks_and_keeps_15_layers() {
    // thicker layers than the case (3e-3): the front over the concave edges and
    // corners shrinks below Coe_shrink in layer 13
    let params = LayerParams {
        first_height: 3e-3,
        growth: 1.2,
        layers: 15,
        ..LayerParams::default()
    };
    let grown = grow_and_check("step, first height 3e-3", &Surface::step(1), &params);
    assert!(grown.stats.merges > 0);
    cut_and_check("step, first height 3e-3", &grown);
    // half the spacing, first height 1e-3: merges in layer 14
    let params = LayerParams {
        first_height: 1e-3,
        ..params
    };
    let grown = grow_and_check("step, quads of 0.05", &Surface::step(2), &params);
    assert!(grown.stats.merges > 0);
    cut_and_check("step, quads of 0.05", &grown);
}

#[test]
fn the_step_squeezed_merges_stay_cells_topo_cut_cuts() {
    // `squeeze` 0.5: squeezed cells round the concave edges merge from layer 10 on (the
    // layers thicker than half the wall's spacing); the merged cells are cut into valid
    // tetrahedra and mixed cells, the layering record checks, every column is full (at 3e-3
    // nine columns stop at the tower's foot instead: docs/afsf3d.md)
    for first_height in [2e-3, 1e-3] {
        let params = LayerParams {
            first_height,
            growth: 1.2,
            layers: 15,
            squeeze: 0.5,
            ..LayerParams::default()
        };
        let name = format!("step, squeeze 0.5, first height {first_height}");
        let grown = grow_and_check(&name, &Surface::step(1), &params);
        assert!(grown.stats.merges > 0, "{name}");
        cut_and_check(&name, &grown);
    }
}

/// A block with a slot 0.1 wide through it: the slot's two sides grow towards each other.
fn slot() -> Surface {
    Surface::voxels([5, 3, 3], 0.1, |[i, _, k]| k == 0 || i != 2, "slot")
}

#[test]
fn a_slot_thinner_than_its_layers_keeps_every_column() {
    // (thicker than half the slot, its sides' columns stop where they meet: the module stop)
    let thin = LayerParams {
        first_height: 1e-3,
        growth: 1.2,
        layers: 10,
        ..LayerParams::default()
    };
    grow_and_check("slot, thin layers", &slot(), &thin);
}

/// Before a volume fill the layers stop where they turn isotropic (`stop_aspect`) and under
/// `max_thickness`: fewer layers, the next one higher than the wall's edges, the stack under
/// the limit, every column complete. (On a sphere the front's edges grow with the stack, and
/// at growth 1.2 over edges of 0.26 the layers never turn isotropic: the cube's flat faces do.)
#[test]
fn growth_stops_where_the_layers_turn_isotropic_or_too_thick() {
    let cube = Surface::cube(1.0, 8, false);
    let iso = LayerParams {
        layers: 40,
        stop_aspect: 1.0,
        ..LayerParams::default()
    };
    let grown = grow_layers(&cube, &iso).unwrap();
    let n = grown.layer_heights.len();
    assert!(
        (5..40).contains(&n),
        "{n} layers: {:?}",
        grown.layer_heights
    );
    let next = iso.first_height * iso.growth.powi(n as i32);
    assert!(next > 0.125, "stopped early: next layer {next}");
    assert!(grown.columns.iter().all(|c| c.len() == n + 1));
    let sphere = Surface::sphere(1.0, 2);
    let thin = LayerParams {
        layers: 40,
        max_thickness: 0.05,
        ..LayerParams::default()
    };
    let grown = grow_layers(&sphere, &thin).unwrap();
    let thickness: f64 = grown.layer_heights.iter().sum();
    assert!(
        thickness <= 0.05 && thickness > 0.05 / 1.2 - 1e-3,
        "{thickness}"
    );
}
