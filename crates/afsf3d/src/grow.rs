//! The layer loop: ideal steps, two spring balances, checks, and the cells appended to the
//! polyhedral mesh.

use geom_surface::Surface;
use mesh_model::Role;
use mesh_model::poly::{CellFace, PolyMesh};
use springfield::{
    AngleSpring3d, ExtrusionSpring, NeighbourSpring3d, SpringField3d, SpringSet3d, TensionSpring,
    solve_model,
};

use crate::check::shrink_until_valid;
use crate::front::{Topo, ideal_steps};
use crate::{GrowError, GrowStats, Grown3d, LayerParams};

/// Grows `params.layers` layers from the wall surface `surface` (see the crate's doc).
pub fn grow_layers(surface: &Surface, params: &LayerParams) -> Result<Grown3d, GrowError> {
    check_params(params)?;
    surface.check()?;
    if let Some(facet) = (0..surface.facets.len()).find(|&f| surface.role(f) != Role::Wall) {
        return Err(GrowError::NotWall { facet });
    }
    let topo = Topo::new(surface);
    let n = surface.nodes.len();
    let mut mesh = PolyMesh::new();
    mesh.nodes = surface.nodes.clone();
    let mut bottom_faces: Vec<u32> = surface
        .facets
        .iter()
        .map(|f| mesh.push_face(f.nodes()))
        .collect();
    let mut columns: Vec<Vec<u32>> = (0..n as u32).map(|i| vec![i]).collect();
    let mut front = surface.clone();
    let mut stats = GrowStats {
        converged: true,
        ..GrowStats::default()
    };
    let spacing = topo
        .edges
        .iter()
        .map(|e| {
            geom_predicates::vector::dist(
                surface.nodes[e.nodes[0] as usize],
                surface.nodes[e.nodes[1] as usize],
            )
        })
        .sum::<f64>()
        / topo.edges.len() as f64;
    let mut thickness = 0.0;
    for layer in 0..params.layers {
        let height = params.first_height * params.growth.powi(layer as i32);
        thickness += height;
        let rounds = smoothing_rounds(params.smoothing, thickness, spacing);
        let (dir, len) = ideal_steps(&front, &topo, height, rounds);
        let mut children = balance(&front.nodes, &topo, &dir, &len, params, layer, &mut stats)?;
        shrink_until_valid(
            &front.nodes,
            &mut children,
            &front.facets,
            params.max_shrinks,
            layer,
            &mut stats,
        )?;
        let base = mesh.nodes.len() as u32;
        mesh.nodes.extend_from_slice(&children);
        let level: Vec<u32> = columns.iter().map(|c| *c.last().expect("a node")).collect();
        bottom_faces = push_cells(
            &mut mesh,
            surface,
            &topo,
            &level,
            base,
            &bottom_faces,
            layer,
        );
        for (i, c) in columns.iter_mut().enumerate() {
            c.push(base + i as u32);
        }
        front.nodes = children;
    }
    Ok(Grown3d {
        mesh,
        columns,
        front,
        stats,
    })
}

/// The rounds of direction smoothing of a layer whose top is `thickness` off the wall:
/// `smoothing × 2·thickness / spacing`, rounded up, at most `smoothing` — none near the
/// wall, where the layers are thin and must stay normal to it, all of them once the layers
/// are half as thick as the wall's mean edge `spacing`, where a concave front would fold.
fn smoothing_rounds(smoothing: usize, thickness: f64, spacing: f64) -> usize {
    let ramp = (2.0 * thickness / spacing).min(1.0);
    (smoothing as f64 * ramp).ceil() as usize
}

fn check_params(p: &LayerParams) -> Result<(), GrowError> {
    let bad = |what: &str| Err(GrowError::Params(what.to_string()));
    if !(p.first_height.is_finite() && p.first_height > 0.0) {
        return bad("first_height must be positive and finite");
    }
    if !(p.growth.is_finite() && p.growth >= 1.0) {
        return bad("growth must be at least 1");
    }
    if !(p.springs.tension_ratio > 0.0 && p.springs.tension_ratio <= 1.0) {
        return bad("tension_ratio must be in (0, 1]");
    }
    p.solver
        .check()
        .map_err(|e| GrowError::Params(e.to_string()))
}

/// The children of the front nodes `x`, balanced: placed at their ideal steps, balanced by
/// the extrusion, neighbour and angle springs, then again with the tension springs (ideal
/// length `tension_ratio` × the length after the first balance). Only the children move.
fn balance(
    x: &[[f64; 3]],
    topo: &Topo,
    dir: &[[f64; 3]],
    len: &[f64],
    params: &LayerParams,
    layer: usize,
    stats: &mut GrowStats,
) -> Result<Vec<[f64; 3]>, GrowError> {
    let n = x.len();
    let mut p: Vec<[f64; 3]> = x.to_vec();
    p.extend((0..n).map(|i| std::array::from_fn(|d| x[i][d] + len[i] * dir[i][d])));
    let movable: Vec<bool> = (0..2 * n).map(|i| i >= n).collect();
    let scale: Vec<f64> = (0..2 * n).map(|i| len[i % n]).collect();
    let up = n as u32;
    let mut set = SpringSet3d::default();
    for i in 0..n {
        let k = i as u32;
        set.extrusion.push(ExtrusionSpring {
            lower: k,
            upper: k + up,
            ideal_length: len[i],
            lower_share: 0.0,
        });
        set.angle.push(AngleSpring3d {
            parent: k,
            child: k + up,
            direction: dir[i],
        });
    }
    let edge_length = |e: [u32; 2]| (len[e[0] as usize] + len[e[1] as usize]) / 2.0;
    for e in &topo.edges {
        set.neighbour.push(NeighbourSpring3d {
            edge: e.nodes.map(|v| v + up),
            far1: e.far[0].map(|v| v + up),
            far2: e.far[1].map(|v| v + up),
            extrusion_length: edge_length(e.nodes),
        });
    }
    let solve = |p: &mut Vec<[f64; 3]>, set: &SpringSet3d, stats: &mut GrowStats| {
        let model = SpringField3d::new(set, &params.springs);
        let out = solve_model(p, &scale, &movable, &model, &params.solver)
            .map_err(|source| GrowError::Spring { layer, source })?;
        stats.converged &= out.converged;
        Ok::<(), GrowError>(())
    };
    solve(&mut p, &set, stats)?;
    let longest = topo.longest_edge(&p[n..]);
    for e in &topo.edges {
        let [a, b] = e.nodes.map(|v| v as usize);
        let length = geom_predicates::vector::dist(p[n + a], p[n + b]);
        let l_charac = longest[a].max(longest[b]);
        set.tension.push(TensionSpring::new(
            e.nodes.map(|v| v + up),
            length,
            edge_length(e.nodes),
            l_charac,
            &params.springs,
        ));
    }
    solve(&mut p, &set, stats)?;
    Ok(p.split_off(n))
}

/// Appends the cells of one layer: the children (mesh nodes `base + i`) over the front nodes
/// `level` (mesh nodes), one cell per facet with its faces in the contract's order (bottom,
/// top, sides along the bottom's edges); each side face is stored once, as
/// (a, b, b', a') for the edge a → b of its first facet. Returns the top faces.
fn push_cells(
    mesh: &mut PolyMesh,
    surface: &Surface,
    topo: &Topo,
    level: &[u32],
    base: u32,
    bottom_faces: &[u32],
    layer: usize,
) -> Vec<u32> {
    let top_faces: Vec<u32> = surface
        .facets
        .iter()
        .map(|f| {
            let k: Vec<u32> = f.nodes().iter().map(|&v| base + v).collect();
            mesh.push_face(&k)
        })
        .collect();
    let side_faces: Vec<u32> = topo
        .edges
        .iter()
        .map(|e| {
            let [a, b] = e.nodes;
            mesh.push_face(&[level[a as usize], level[b as usize], base + b, base + a])
        })
        .collect();
    let mut faces = Vec::with_capacity(6);
    for (f, facet) in surface.facets.iter().enumerate() {
        faces.clear();
        faces.push(CellFace {
            face: bottom_faces[f],
            reversed: true,
        });
        faces.push(CellFace {
            face: top_faces[f],
            reversed: false,
        });
        for (&v, &e) in facet.nodes().iter().zip(&topo.facet_edges[f]) {
            faces.push(CellFace {
                face: side_faces[e as usize],
                reversed: topo.edges[e as usize].nodes[0] != v,
            });
        }
        mesh.push_cell(&faces, layer as u32, f as u32);
    }
    top_faces
}
