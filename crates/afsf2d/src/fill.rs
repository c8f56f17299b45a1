//! Filling the region left between the closed fronts: a constrained Delaunay triangulation
//! (`spade`) of the front nodes with every front edge as a constraint, keeping the triangles
//! on the left of the fronts (flood fill that never crosses a constraint). No node is added,
//! so the fill conforms to the layered cells edge for edge.
//!
//! It owns nothing else: the fronts are kept simple and disjoint by `grow`, which is what
//! makes this triangulation exact.

use std::collections::HashMap;

use spade::handles::FixedFaceHandle;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

use mesh_model::NONE;
use spade::{AngleLimit, RefinementParameters};

use crate::error::AfsfError;
use crate::geom::P2;
use crate::grow::Loop;

#[derive(Debug, Clone, Copy)]
struct Vertex {
    position: Point2<f64>,
    node: u32,
}

impl From<Point2<f64>> for Vertex {
    fn from(position: Point2<f64>) -> Self {
        Vertex {
            position,
            node: NONE,
        }
    }
}

impl HasPosition for Vertex {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// Triangles (node indices, counter-clockwise) covering the region on the left of the fronts,
/// and the positions of the nodes added inside it (numbered from `pos.len()` on). With
/// `min_angle_deg` > 0 the triangulation is refined (Ruppert/Chew, front edges never split)
/// toward that smallest angle, which also bounds the largest angle.
pub(crate) fn fill_fronts(
    loops: &[Loop],
    pos: &[P2],
    min_angle_deg: f64,
) -> Result<(Vec<[u32; 3]>, Vec<P2>), AfsfError> {
    let mut cdt: ConstrainedDelaunayTriangulation<Vertex> = ConstrainedDelaunayTriangulation::new();
    let mut handle_of: HashMap<u32, spade::handles::FixedVertexHandle> = HashMap::new();
    for l in loops {
        for &g in &l.items {
            if handle_of.contains_key(&g) {
                continue;
            }
            let p = pos[g as usize];
            let h = cdt
                .insert(Vertex {
                    position: Point2::new(p[0], p[1]),
                    node: g,
                })
                .map_err(|e| AfsfError::Fill(format!("node {g} at {p:?}: {e:?}")))?;
            if cdt.vertex(h).data().node != g {
                return Err(AfsfError::Fill(format!(
                    "front nodes {g} and {} coincide",
                    cdt.vertex(h).data().node
                )));
            }
            handle_of.insert(g, h);
        }
    }
    let mut directed = Vec::new();
    for l in loops {
        let k = l.items.len();
        for i in 0..k {
            let (a, b) = (handle_of[&l.items[i]], handle_of[&l.items[(i + 1) % k]]);
            if !cdt.can_add_constraint(a, b) {
                return Err(AfsfError::Fill(format!(
                    "front edge {}-{} crosses another front edge",
                    l.items[i],
                    l.items[(i + 1) % k]
                )));
            }
            cdt.add_constraint(a, b);
            if !cdt.exists_constraint(a, b) {
                return Err(AfsfError::Fill(format!(
                    "front edge {}-{} passes through a front node",
                    l.items[i],
                    l.items[(i + 1) % k]
                )));
            }
            directed.push((a, b));
        }
    }
    if min_angle_deg > 0.0 {
        let extra = 2 * cdt.num_vertices() + 16;
        cdt.refine(
            RefinementParameters::<f64>::new()
                .exclude_outer_faces(true)
                .keep_constraint_edges()
                .with_angle_limit(AngleLimit::from_deg(min_angle_deg))
                .with_max_additional_vertices(extra),
        );
    }
    // flood fill from the left of every front edge
    let mut inside: HashMap<FixedFaceHandle<spade::handles::InnerTag>, ()> = HashMap::new();
    let mut stack = Vec::new();
    for (a, b) in directed {
        let e = cdt.get_edge_from_neighbors(a, b).ok_or_else(|| {
            AfsfError::Fill("a front edge is missing from the triangulation".into())
        })?;
        if let Some(f) = e.face().as_inner() {
            stack.push(f.fix());
        }
    }
    while let Some(f) = stack.pop() {
        if inside.insert(f, ()).is_some() {
            continue;
        }
        for e in cdt.face(f).adjacent_edges() {
            if cdt.is_constraint_edge(e.as_undirected().fix()) {
                continue;
            }
            match e.rev().face().as_inner() {
                Some(g) => {
                    if !inside.contains_key(&g.fix()) {
                        stack.push(g.fix());
                    }
                }
                None => {
                    return Err(AfsfError::Fill(
                        "the region between the fronts leaks to the outside".into(),
                    ));
                }
            }
        }
    }
    let mut faces: Vec<_> = inside.keys().copied().collect();
    faces.sort_unstable_by_key(|f| f.index());
    let mut added: HashMap<spade::handles::FixedVertexHandle, u32> = HashMap::new();
    let mut steiner = Vec::new();
    let tris = faces
        .iter()
        .map(|&f| {
            let v = cdt.face(f).vertices();
            v.map(|h| {
                let node = h.data().node;
                if node != NONE {
                    return node;
                }
                *added.entry(h.fix()).or_insert_with(|| {
                    let p = h.position();
                    steiner.push([p.x, p.y]);
                    (pos.len() + steiner.len() - 1) as u32
                })
            })
        })
        .collect();
    Ok((tris, steiner))
}
