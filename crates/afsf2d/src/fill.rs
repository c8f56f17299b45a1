//! Filling the region left between the closed fronts: a constrained Delaunay triangulation
//! (`spade`) of the front nodes with every front edge as a constraint, keeping the triangles
//! on the left of the fronts (flood fill that never crosses a constraint), refined inside,
//! then improved by largest-angle edge flips and Steiner smoothing. Front edges are never
//! split, so the fill conforms to the layered cells edge for edge.
//!
//! Where a fill triangle stays too obtuse, the layered cells around it are peeled into the
//! region ([`fill_with_peeling`]); the region is filled whole once, and after each peel only
//! the cavity around what changed is filled again ([`refill_cavity`]; whole again if that
//! fails).
//!
//! It owns nothing else: the fronts are kept simple and disjoint by `grow`, which is what
//! makes this triangulation exact.

use spade::handles::FixedFaceHandle;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

use geom_predicates::vector::dist;
use geom_predicates::{orient2d, polygon_area};
use mesh_model::topology::Edges;
use mesh_model::{NONE, Shape};
use spade::{AngleLimit, RefinementParameters};

use crate::error::AfsfError;
use crate::geom::P2;
use crate::grow::Cell;

mod flips;
mod smooth;
use flips::flip_min_max_angle;
use smooth::smooth_steiner;

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

/// The constrained triangulation of the fill, with its vertex handles.
type Cdt = ConstrainedDelaunayTriangulation<Vertex>;
type VertexHandle = spade::handles::FixedVertexHandle;
type InnerFace = FixedFaceHandle<spade::handles::InnerTag>;

/// Triangles (node indices, counter-clockwise) covering the region on the left of the
/// directed edges `directed` (the region's whole boundary), with the nodes `free` inserted
/// inside it, and the positions of the nodes added inside it (numbered from `pos.len()` on).
/// With `min_angle_deg` > 0 the triangulation is refined (Ruppert/Chew, boundary edges never
/// split) toward that smallest angle, which also bounds the largest angle.
///
/// The flips and the smoothing work on the fill's own nodes ([`Local`]), numbered in the
/// order of their indices: the same arithmetic in the same order on a few compact arrays
/// instead of lookups across every node of the mesh.
pub(crate) fn fill_region(
    directed_edges: &[(u32, u32)],
    free: &[u32],
    pos: &[P2],
    min_angle_deg: f64,
) -> Result<(Vec<[u32; 3]>, Vec<P2>), AfsfError> {
    let (mut local, constraints) = triangulate(directed_edges, free, pos, min_angle_deg)?;
    local.improve(&constraints);
    Ok(local.into_global(pos.len()))
}

/// The refined constrained triangulation of [`fill_region`] before its flips and smoothing,
/// in local numbers, with the front edges in local numbers (lower end first, sorted).
fn triangulate(
    directed_edges: &[(u32, u32)],
    free: &[u32],
    pos: &[P2],
    min_angle_deg: f64,
) -> Result<(Local, Vec<(u32, u32)>), AfsfError> {
    let mut cdt: Cdt = ConstrainedDelaunayTriangulation::new();
    let handle_of = insert_nodes(&mut cdt, directed_edges, free, pos)?;
    let directed = add_front_edges(&mut cdt, directed_edges, &handle_of)?;
    if min_angle_deg > 0.0 {
        let extra = 8 * cdt.num_vertices() + 64;
        cdt.refine(
            RefinementParameters::<f64>::new()
                .exclude_outer_faces(true)
                .keep_constraint_edges()
                .with_angle_limit(AngleLimit::from_deg(min_angle_deg))
                .with_max_additional_vertices(extra),
        );
    }
    let faces = faces_inside(&cdt, directed)?;
    let local = Local::new(&cdt, &faces);
    let mut constraints: Vec<(u32, u32)> = directed_edges
        .iter()
        .map(|&(a, b)| {
            let (a, b) = (local.of_node(&handle_of, a), local.of_node(&handle_of, b));
            if a < b { (a, b) } else { (b, a) }
        })
        .collect();
    constraints.sort_unstable();
    Ok((local, constraints))
}

/// Inserts the ends of the front edges, then the free nodes, once each; two nodes at one
/// place are an error.
fn insert_nodes(
    cdt: &mut Cdt,
    directed_edges: &[(u32, u32)],
    free: &[u32],
    pos: &[P2],
) -> Result<Vec<Option<VertexHandle>>, AfsfError> {
    // by node (every front and free node indexes `pos`)
    let mut handle_of: Vec<Option<VertexHandle>> = vec![None; pos.len()];
    let nodes = directed_edges
        .iter()
        .flat_map(|&(a, b)| [a, b])
        .chain(free.iter().copied());
    for g in nodes {
        if handle_of[g as usize].is_some() {
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
        handle_of[g as usize] = Some(h);
    }
    Ok(handle_of)
}

/// Makes every front edge a constraint edge; a front edge crossing another or passing through
/// a node is an error. Returns the edges as vertex-handle pairs.
fn add_front_edges(
    cdt: &mut Cdt,
    directed_edges: &[(u32, u32)],
    handle_of: &[Option<VertexHandle>],
) -> Result<Vec<(VertexHandle, VertexHandle)>, AfsfError> {
    let mut directed = Vec::with_capacity(directed_edges.len());
    for &(ga, gb) in directed_edges {
        let handle = |g: u32| {
            handle_of[g as usize]
                .ok_or_else(|| AfsfError::Fill(format!("front node {g} was not inserted")))
        };
        let (a, b) = (handle(ga)?, handle(gb)?);
        if !cdt.can_add_constraint(a, b) {
            return Err(AfsfError::Fill(format!(
                "front edge {ga}-{gb} crosses another front edge"
            )));
        }
        cdt.add_constraint(a, b);
        if !cdt.exists_constraint(a, b) {
            return Err(AfsfError::Fill(format!(
                "front edge {ga}-{gb} passes through a front node"
            )));
        }
        directed.push((a, b));
    }
    Ok(directed)
}

/// The faces on the left of the front edges, by a flood fill that stops at constraint edges;
/// in the order of their handles (deterministic).
fn faces_inside(
    cdt: &Cdt,
    directed: Vec<(VertexHandle, VertexHandle)>,
) -> Result<Vec<InnerFace>, AfsfError> {
    let mut inside = vec![false; cdt.num_all_faces()];
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
        if std::mem::replace(&mut inside[f.index()], true) {
            continue;
        }
        for e in cdt.face(f).adjacent_edges() {
            if cdt.is_constraint_edge(e.as_undirected().fix()) {
                continue;
            }
            match e.rev().face().as_inner() {
                Some(g) => {
                    if !inside[g.fix().index()] {
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
    // in the order of their handles
    let faces = cdt
        .inner_faces()
        .map(|f| f.fix())
        .filter(|f| inside[f.index()])
        .collect();
    Ok(faces)
}

/// The fill triangles in a numbering of their own: the mesh nodes inserted (`front`, by
/// increasing index) first, then the vertices the refinement added, in order of first use
/// by the faces. The map is increasing on the mesh nodes and puts the added vertices after
/// them, as their final indices (from `pos.len()` on) do: every order by node index is
/// the same in either numbering.
#[derive(Clone)]
struct Local {
    /// The mesh node of each local node below `front.len()`, increasing.
    front: Vec<u32>,
    /// The local number of each vertex of the triangulation (by handle index).
    of_vertex: Vec<u32>,
    /// The positions of the local nodes: the mesh nodes', then the added ones'.
    pts: Vec<P2>,
    /// The triangles of the faces, counter-clockwise, in local numbers.
    tris: Vec<[u32; 3]>,
}

impl Local {
    fn new(cdt: &Cdt, faces: &[InnerFace]) -> Self {
        let mut front: Vec<(u32, usize)> = cdt
            .vertices()
            .filter(|v| v.data().node != NONE)
            .map(|v| (v.data().node, v.fix().index()))
            .collect();
        front.sort_unstable();
        let mut of_vertex = vec![NONE; cdt.num_vertices()];
        let mut pts = Vec::with_capacity(cdt.num_vertices());
        for (l, &(_, h)) in front.iter().enumerate() {
            of_vertex[h] = l as u32;
            let p = cdt
                .vertex(spade::handles::FixedVertexHandle::from_index(h))
                .position();
            pts.push([p.x, p.y]);
        }
        let tris: Vec<[u32; 3]> = faces
            .iter()
            .map(|&f| {
                cdt.face(f).vertices().map(|h| {
                    let slot = &mut of_vertex[h.fix().index()];
                    if *slot == NONE {
                        let p = h.position();
                        pts.push([p.x, p.y]);
                        *slot = (pts.len() - 1) as u32;
                    }
                    *slot
                })
            })
            .collect();
        Local {
            front: front.into_iter().map(|(g, _)| g).collect(),
            of_vertex,
            pts,
            tris,
        }
    }

    /// The local number of mesh node `g` (inserted).
    fn of_node(&self, handle_of: &[Option<VertexHandle>], g: u32) -> u32 {
        handle_of[g as usize].map_or(NONE, |h| self.of_vertex[h.index()])
    }

    /// Flips, smooths the added nodes, flips again (`constraints`: the front edges, lower
    /// end first, sorted).
    fn improve(&mut self, constraints: &[(u32, u32)]) {
        let front = self.front.len();
        flip_min_max_angle(&mut self.tris, &self.pts, constraints);
        smooth_steiner(&self.tris, &mut self.pts, front);
        flip_min_max_angle(&mut self.tris, &self.pts, constraints);
    }

    /// The triangles in mesh numbers, the added nodes numbered from `n0` on in local order,
    /// and the added nodes' positions.
    fn into_global(self, n0: usize) -> (Vec<[u32; 3]>, Vec<P2>) {
        let m = self.front.len();
        let front = &self.front;
        let tris = self
            .tris
            .iter()
            .map(|t| {
                t.map(|l| {
                    let l = l as usize;
                    if l < m { front[l] } else { (n0 + l - m) as u32 }
                })
            })
            .collect();
        let mut pts = self.pts;
        (tris, pts.split_off(m))
    }
}

/// The fill triangles, the added nodes and the cells peeled (their indices, in the order
/// they were peeled).
pub(crate) type PeeledFill = (Vec<[u32; 3]>, Vec<P2>, Vec<u32>);

/// Only cells whose longest edge is at most this many times their shortest are peeled:
/// peeling a boundary-layer cell would lay bare the side of its neighbours' stack of thin
/// cells, whose short edges no triangle can meet with good angles.
const PEEL_MAX_EDGE_RATIO: f64 = 4.0;

fn edge_ratio(c: &Cell, pos: &[P2]) -> f64 {
    let k = c.corners();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..k.len() {
        let l = dist(pos[k[i] as usize], pos[k[(i + 1) % k.len()] as usize]);
        lo = lo.min(l);
        hi = hi.max(l);
    }
    hi / lo
}

/// Fills the region left between the layered cells and, while some fill triangle has an
/// angle of `angles.peel_max_angle_deg` or more, peels the layered cells (not the first
/// layer) that touch those triangles into the region and fills again, at most
/// `angles.rounds` times: a coarse cell
/// whose corner pinches the region between fronts of very different sizes thus becomes room
/// for well-shaped triangles. Peeled cells get `len` 0; their nodes are kept (inside the
/// region, as triangulation vertices, when no remaining cell uses them). `facets` are the
/// boundary facets with the domain on their left, `fronts` the final fronts' edges
/// ([`Region::new`]). Returns the triangles, the added nodes
/// (numbered from `pos.len()` on) and the cells peeled, with what `beside` gave: it reads the
/// cells as they are before any peel, beside the first fill (on another thread of the pool
/// when there is one; before it otherwise).
///
/// The first round fills the whole region; a later round fills again only the cavity around
/// what it changed ([`refill_cavity`]), or the whole region when that fails.
pub(crate) fn fill_with_peeling<R: Send>(
    cells: &mut [Cell],
    facets: &[(u32, u32)],
    fronts: &[(u32, u32, u32)],
    pos: &[P2],
    angles: FillAngles,
    beside: impl FnOnce(&[Cell]) -> R + Send,
) -> Result<(PeeledFill, R), AfsfError> {
    peel_rounds(cells, facets, fronts, pos, angles, refill_cavity, beside)
        .map(|(fill, _, aside)| (fill, aside))
}

/// A fill of the region: its triangles (counter-clockwise, in mesh numbers; the added nodes
/// from `pos.len()` on), the added nodes' positions, and the first triangle this round made
/// (the triangles before it were checked in an earlier round).
struct Fill {
    tris: Vec<[u32; 3]>,
    steiner: Vec<P2>,
    new_from: usize,
}

impl Fill {
    /// Where node `g` is: a mesh node (of `pos`), or an added node of this fill after them.
    fn at(&self, pos: &[P2], g: u32) -> P2 {
        match (g as usize).checked_sub(pos.len()) {
            None => pos[g as usize],
            Some(k) => self.steiner[k],
        }
    }
}

/// What a peel round changed: the corners of the bad triangles (added nodes among them) and
/// the cells it peeled, each with its number of corners (their `len` is 0 by now).
struct Change<'a> {
    bad: &'a [u32],
    peeled: &'a [(u32, u8)],
}

/// A fill again after a peel round, from the last one: [`refill_cavity`], or a stand-in in
/// the tests.
type Refill = fn(&Fill, &Change<'_>, &[Cell], &Region, &[P2], f64) -> Result<Fill, AfsfError>;

/// How the rounds after the first were filled: around what changed, or whole (after the
/// fill around what changed failed).
#[derive(Debug, Default, Clone, Copy, PartialEq)]
struct Refills {
    local: u32,
    whole: u32,
}

/// [`fill_with_peeling`] with the fill of a later round given (`refill`; the whole region is
/// filled again when it fails).
fn peel_rounds<R: Send>(
    cells: &mut [Cell],
    facets: &[(u32, u32)],
    fronts: &[(u32, u32, u32)],
    pos: &[P2],
    angles: FillAngles,
    refill: Refill,
    beside: impl FnOnce(&[Cell]) -> R + Send,
) -> Result<(PeeledFill, Refills, R), AfsfError> {
    let mut region = Region::new(cells, facets, fronts);
    let mut incidence: Option<CellsOfNode> = None;
    let max_angle_deg = angles.peel_max_angle_deg;
    let limit = crate::quality::AngleLimit::new(max_angle_deg);
    let mut peeled: Vec<u32> = Vec::new();
    let mut refills = Refills::default();
    let whole = |region: &Region, cells: &[Cell], peeled: &[u32]| {
        let directed = region.directed(cells);
        let free: Vec<u32> = peeled
            .iter()
            .flat_map(|&c| cells[c as usize].nodes)
            .filter(|&g| g != NONE && region.unused(g))
            .collect();
        let (tris, steiner) = fill_region(&directed, &free, pos, angles.min_angle_deg)?;
        Ok::<_, AfsfError>(Fill {
            tris,
            steiner,
            new_from: 0,
        })
    };
    let (mut fill, aside) = if rayon::current_num_threads() > 1 {
        // what a peel round needs, and `beside`, run on the other thread while the first
        // fill runs
        let start: &[Cell] = cells;
        let (filled, (of_node, aside)) = rayon::join(
            || whole(&region, start, &peeled),
            || {
                rayon::join(
                    || (angles.rounds > 0).then(|| CellsOfNode::new(start, pos.len())),
                    || beside(start),
                )
            },
        );
        incidence = of_node;
        (filled?, aside)
    } else {
        let aside = beside(cells);
        (whole(&region, cells, &peeled)?, aside)
    };
    let mut round = 0;
    loop {
        let done = |fill: Fill, peeled: Vec<u32>, aside: R| {
            Ok(((fill.tris, fill.steiner, peeled), refills, aside))
        };
        if round == angles.rounds {
            return done(fill, peeled, aside);
        }
        round += 1;
        // (the triangles kept from the last round were not bad there, and are where they were)
        let bad = bad_corners(&fill, pos, limit, max_angle_deg);
        if bad.is_empty() {
            return done(fill, peeled, aside);
        }
        let bad_nodes: Vec<u32> = bad
            .iter()
            .copied()
            .filter(|&g| (g as usize) < pos.len())
            .collect();
        // (built before the first peel: it lists the cells alive at the start)
        let of_node = incidence.get_or_insert_with(|| CellsOfNode::new(cells, pos.len()));
        let mut now: Vec<(u32, u8)> = Vec::new();
        for ci in of_node.peelable(&bad_nodes, cells, pos) {
            let c = &mut cells[ci as usize];
            now.push((ci, c.len));
            peeled.push(ci);
            c.len = 0;
        }
        if now.is_empty() {
            return done(fill, peeled, aside);
        }
        region.peel(cells, &now, of_node);
        let change = Change {
            bad: &bad,
            peeled: &now,
        };
        fill = match refill(&fill, &change, cells, &region, pos, angles.min_angle_deg) {
            Ok(local) => {
                refills.local += 1;
                local
            }
            Err(_) => {
                refills.whole += 1;
                whole(&region, cells, &peeled)?
            }
        };
    }
}

/// The corners of the new triangles of `fill` with an angle of `max_angle_deg` or more
/// (added nodes among them), sorted, once each.
fn bad_corners(
    fill: &Fill,
    pos: &[P2],
    limit: crate::quality::AngleLimit,
    max_angle_deg: f64,
) -> Vec<u32> {
    use rayon::prelude::*;
    let at = |g: u32| fill.at(pos, g);
    // (the cosines clear nearly every triangle; the angle decides the others)
    let bad = |a, b, c| {
        !limit.triangle_below(a, b, c)
            && crate::quality::max_triangle_angle_deg(a, b, c) >= max_angle_deg
    };
    let mut corners: Vec<u32> = fill.tris[fill.new_from..]
        .par_iter()
        .filter(|t| bad(at(t[0]), at(t[1]), at(t[2])))
        .flat_map_iter(|t| t.iter().copied())
        .collect();
    corners.sort_unstable();
    corners.dedup();
    corners
}

/// The fill of a peel round around what it changed: the last round's triangles with a corner
/// at a node of a bad triangle or of a peeled cell and the
/// peeled cells make a cavity, whose boundary (the sides met once) is filled anew by
/// [`fill_region`] with the mesh nodes inside it as free nodes; the added nodes inside it are
/// dropped (the refinement places its own, and moves them: kept ones would be held fixed)
/// and the others renumbered in order. The other triangles stay as they are, and the
/// cavity's boundary is never split, so the fill still conforms. The cavity is filled in a
/// compact numbering of its own nodes, increasing as their mesh numbers are. Fails (the
/// caller then fills the whole region) when the cavity's sides are met twice the same way, a
/// node inside it is still a corner of a layered cell, the triangulation fails, or its
/// triangles do not cover the cavity exactly with positive triangles using every node.
fn refill_cavity(
    prev: &Fill,
    change: &Change<'_>,
    cells: &[Cell],
    region: &Region,
    pos: &[P2],
    min_angle_deg: f64,
) -> Result<Fill, AfsfError> {
    let n = pos.len();
    let at = |g: u32| prev.at(pos, g);
    let peeled_corners = |&(c, len): &(u32, u8)| &cells[c as usize].nodes[..len as usize];
    let mut seeds: Vec<u32> = change.bad.to_vec();
    seeds.extend(change.peeled.iter().flat_map(peeled_corners));
    seeds.sort_unstable();
    seeds.dedup();
    // (one ring of triangles more makes the built-in meshes' worst fill angles worse:
    // docs/afsf.md, "Hole filling")
    let in_cavity: Vec<bool> = prev
        .tris
        .iter()
        .map(|t| t.iter().any(|g| seeds.binary_search(g).is_ok()))
        .collect();
    let elements: Vec<&[u32]> = (prev.tris.iter().zip(&in_cavity))
        .filter(|&(_, &inside)| inside)
        .map(|(t, _)| &t[..])
        .chain(change.peeled.iter().map(peeled_corners))
        .collect();
    let boundary = cavity_boundary(&elements)?;
    let mut on_boundary: Vec<u32> = boundary.iter().flat_map(|&(a, b)| [a, b]).collect();
    on_boundary.sort_unstable();
    on_boundary.dedup();
    // the mesh nodes inside the cavity: nodes of peeled cells no layered cell keeps
    let mut free: Vec<u32> = elements.iter().flat_map(|k| k.iter().copied()).collect();
    free.sort_unstable();
    free.dedup();
    free.retain(|&g| (g as usize) < n && on_boundary.binary_search(&g).is_err());
    if let Some(g) = free.iter().find(|&&g| !region.unused(g)) {
        return Err(AfsfError::Fill(format!(
            "node {g} inside the cavity is a corner of a layered cell"
        )));
    }
    // the cavity's own numbering: its boundary and free nodes, increasing
    let mut ids: Vec<u32> = on_boundary.iter().chain(&free).copied().collect();
    ids.sort_unstable();
    let local = |g: &u32| ids.binary_search(g).map_or(NONE, |l| l as u32);
    let edges: Vec<(u32, u32)> = boundary.iter().map(|(a, b)| (local(a), local(b))).collect();
    let local_free: Vec<u32> = free.iter().map(local).collect();
    let local_pos: Vec<P2> = ids.iter().map(|&g| at(g)).collect();
    let (tris, added) = fill_region(&edges, &local_free, &local_pos, min_angle_deg)?;
    let cavity_area: f64 = elements
        .iter()
        .map(|k| polygon_area(k.iter().map(|&g| at(g))))
        .sum();
    check_cavity_fill(&tris, &local_pos, &added, cavity_area)?;
    Ok(splice(prev, &in_cavity, &ids, &tris, added, n))
}

/// The sides of the counter-clockwise `elements` that no element has the other way, with the
/// elements on their left, sorted; an error when a side is met twice the same way (the
/// elements overlap) or none is left.
fn cavity_boundary(elements: &[&[u32]]) -> Result<Vec<(u32, u32)>, AfsfError> {
    let mut sides: Vec<(u32, u32)> = elements
        .iter()
        .flat_map(|k| (0..k.len()).map(|j| (k[j], k[(j + 1) % k.len()])))
        .collect();
    sides.sort_unstable();
    if sides.windows(2).any(|w| w[0] == w[1]) {
        return Err(AfsfError::Fill(
            "two elements of the cavity share a side the same way".into(),
        ));
    }
    let boundary: Vec<(u32, u32)> = sides
        .iter()
        .copied()
        .filter(|&(a, b)| sides.binary_search(&(b, a)).is_err())
        .collect();
    if boundary.is_empty() {
        return Err(AfsfError::Fill("the cavity has no boundary".into()));
    }
    Ok(boundary)
}

/// Relative tolerance of the cavity fill's area against the cavity's.
const CAVITY_AREA_TOLERANCE: f64 = 1e-9;

/// Checks a cavity's fill (local numbers: the `pts.len()` cavity nodes, then the `added`
/// ones): every triangle positive, every cavity node used, the area that of the cavity.
fn check_cavity_fill(
    tris: &[[u32; 3]],
    pts: &[P2],
    added: &[P2],
    cavity_area: f64,
) -> Result<(), AfsfError> {
    let m = pts.len();
    let at = |l: u32| {
        if (l as usize) < m {
            pts[l as usize]
        } else {
            added[l as usize - m]
        }
    };
    let mut used = vec![false; m];
    let mut area = 0.0;
    for t in tris {
        let c = t.map(at);
        let twice = orient2d(c[0], c[1], c[2]);
        if twice <= 0.0 {
            return Err(AfsfError::Fill("a cavity triangle is not positive".into()));
        }
        area += 0.5 * twice;
        for &l in t.iter().filter(|&&l| (l as usize) < m) {
            used[l as usize] = true;
        }
    }
    if used.contains(&false) {
        return Err(AfsfError::Fill("a cavity node is left out".into()));
    }
    let off = (area - cavity_area).abs();
    if off.is_nan() || off > CAVITY_AREA_TOLERANCE * cavity_area.abs() {
        return Err(AfsfError::Fill(format!(
            "the cavity's fill covers {area}, the cavity {cavity_area}"
        )));
    }
    Ok(())
}

/// The last round's fill with the triangles in the cavity replaced by `tris` (in the cavity's
/// numbering: node `l` is `ids[l]`, then the `added` nodes): the kept triangles in their
/// order, then the new ones; the added nodes the kept triangles use in their order, then the
/// new ones.
fn splice(
    prev: &Fill,
    in_cavity: &[bool],
    ids: &[u32],
    tris: &[[u32; 3]],
    added: Vec<P2>,
    n: usize,
) -> Fill {
    let mut keep = vec![false; prev.steiner.len()];
    for (t, _) in prev.tris.iter().zip(in_cavity).filter(|&(_, &c)| !c) {
        for &g in t.iter().filter(|&&g| g as usize >= n) {
            keep[g as usize - n] = true;
        }
    }
    let mut steiner = Vec::with_capacity(prev.steiner.len() + added.len());
    let mut new_id = vec![NONE; prev.steiner.len()];
    for (s, &p) in prev.steiner.iter().enumerate() {
        if keep[s] {
            new_id[s] = (n + steiner.len()) as u32;
            steiner.push(p);
        }
    }
    let renumber = |g: u32| {
        if (g as usize) < n {
            g
        } else {
            new_id[g as usize - n]
        }
    };
    let mut out: Vec<[u32; 3]> = Vec::with_capacity(prev.tris.len() + tris.len());
    out.extend(
        (prev.tris.iter().zip(in_cavity))
            .filter(|&(_, &c)| !c)
            .map(|(t, _)| t.map(renumber)),
    );
    let new_from = out.len();
    let (m, base) = (ids.len(), n + steiner.len());
    out.extend(tris.iter().map(|t| {
        t.map(|l| {
            let l = l as usize;
            if l < m {
                renumber(ids[l])
            } else {
                (base + l - m) as u32
            }
        })
    }));
    steiner.extend(added);
    Fill {
        tris: out,
        steiner,
        new_from,
    }
}

/// The fill's angle parameters: the refinement's smallest angle, and the peel rounds
/// (at most `rounds`, while a triangle has an angle of `peel_max_angle_deg` or more).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FillAngles {
    pub min_angle_deg: f64,
    pub peel_max_angle_deg: f64,
    pub rounds: u32,
}

/// The cells alive at the start of the fill by corner node: what a peel round needs to
/// find the cells around the nodes of its bad triangles, and the cells beside those it
/// peels, without counting the edges of every layered cell.
struct CellsOfNode {
    /// `cells[start[g]..start[g + 1]]` are the cells with corner `g`, increasing (a cell
    /// with `g` twice among its corners is listed twice).
    start: Vec<u32>,
    cells: Vec<u32>,
}

impl CellsOfNode {
    fn new(cells: &[Cell], n_nodes: usize) -> Self {
        let mut start = vec![0u32; n_nodes + 1];
        for c in cells {
            for &g in c.corners() {
                start[g as usize + 1] += 1;
            }
        }
        for g in 0..n_nodes {
            start[g + 1] += start[g];
        }
        let mut next = start.clone();
        let mut of_node = vec![0u32; start[n_nodes] as usize];
        for (ci, c) in cells.iter().enumerate() {
            for &g in c.corners() {
                of_node[next[g as usize] as usize] = ci as u32;
                next[g as usize] += 1;
            }
        }
        CellsOfNode {
            start,
            cells: of_node,
        }
    }

    /// The cells listed with corner `g`.
    fn of(&self, g: u32) -> &[u32] {
        &self.cells[self.start[g as usize] as usize..self.start[g as usize + 1] as usize]
    }

    /// The cells a peel round may take with a corner among `nodes`, increasing, once each:
    /// alive, above the first layer, edge ratio at most [`PEEL_MAX_EDGE_RATIO`].
    fn peelable(&self, nodes: &[u32], cells: &[Cell], pos: &[P2]) -> Vec<u32> {
        let mut found: Vec<u32> = Vec::new();
        for &g in nodes {
            found.extend(self.of(g));
        }
        found.sort_unstable();
        found.dedup();
        found.retain(|&ci| {
            let c = &cells[ci as usize];
            c.len > 0 && c.layer != 0 && edge_ratio(c, pos) <= PEEL_MAX_EDGE_RATIO
        });
        found
    }

    /// The alive cells with the edge `{a, b}` as a side, with that side's index (a cell
    /// with it twice, twice).
    fn sides(&self, cells: &[Cell], a: u32, b: u32) -> Vec<(u32, u32)> {
        let mut found = Vec::new();
        let list = self.of(a);
        for (i, &d) in list.iter().enumerate() {
            if i > 0 && list[i - 1] == d {
                continue; // a cell listed twice is looked at once
            }
            let k = cells[d as usize].corners();
            for j in 0..k.len() {
                let (p, q) = (k[j], k[(j + 1) % k.len()]);
                if (p, q) == (a, b) || (p, q) == (b, a) {
                    found.push((d, j as u32));
                }
            }
        }
        found
    }
}

/// The boundary of the region left to the fill, kept up to date as cells are peeled. At the
/// start it is read off the final fronts (each front edge knows its cell); a peel round then
/// looks only at the sides of the cells it peels, and at the cells beside them
/// ([`CellsOfNode`]), instead of counting the edges of every layered cell again.
struct Region {
    /// The cell sides on the region's boundary (in one alive cell, no facet on them), as
    /// (cell, side: corners `j` and `j + 1`), sorted.
    open: Vec<(u32, u32)>,
    /// The boundary facets, domain on their left.
    facets: Vec<(u32, u32)>,
    /// The facets by their nodes (lower first), with their index, sorted.
    facet_keys: Vec<((u32, u32), u32)>,
    /// Whether each facet has no alive cell on it (a front edge).
    bare: Vec<bool>,
    /// The nodes of peeled cells that no alive cell has as a corner, sorted.
    unused: Vec<u32>,
}

/// The open cell sides of a region, sorted, and whether each facet is bare.
type OpenAndBare = (Vec<(u32, u32)>, Vec<bool>);

fn cell_shape(c: &Cell) -> Shape {
    if c.len == 3 { Shape::Tri } else { Shape::Quad }
}

/// The open sides and the bare facets of the alive cells, counted from their edge table.
fn open_and_bare_by_table(cells: &[Cell], facets: &[(u32, u32)]) -> OpenAndBare {
    let live: Vec<u32> = (0..cells.len() as u32)
        .filter(|&c| cells[c as usize].len > 0)
        .collect();
    let facet_nodes: Vec<[u32; 2]> = facets.iter().map(|&(a, b)| [a, b]).collect();
    let edges = Edges::build(
        live.iter().map(|&c| {
            let c = &cells[c as usize];
            (cell_shape(c), c.corners())
        }),
        facet_nodes.iter().map(|f| &f[..]),
    );
    let mut open = Vec::new();
    for (i, &c) in live.iter().enumerate() {
        for (j, &e) in edges.of_cell(i).iter().enumerate() {
            if edges.cells(e).len() == 1 && !edges.is_boundary(e) {
                open.push((c, j as u32));
            }
        }
    }
    let bare = facets
        .iter()
        .map(|&(a, b)| {
            edges
                .find(&[a, b])
                .is_none_or(|e| edges.cells(e).is_empty())
        })
        .collect();
    (open, bare)
}

impl Region {
    /// The region of the cells alive in `cells`, whose fronts are the directed edges
    /// `fronts` (`(a, b, cell)`: the region on the left, the cell on the right or `NONE` on a
    /// bare facet). When the fronts do not match the cells edge for edge, the boundary is
    /// counted from the edge table instead.
    fn new(cells: &[Cell], facets: &[(u32, u32)], fronts: &[(u32, u32, u32)]) -> Self {
        let (open, bare) = match open_from_fronts(cells, facets, fronts) {
            Some(found) => {
                if cfg!(debug_assertions) {
                    let counted = open_and_bare_by_table(cells, facets);
                    assert_eq!(found.0, counted.0, "the fronts' open edges");
                    assert_eq!(found.1, counted.1, "the fronts' bare facets");
                }
                found
            }
            None => open_and_bare_by_table(cells, facets),
        };
        let mut facet_keys: Vec<((u32, u32), u32)> = facets
            .iter()
            .enumerate()
            .map(|(f, &(a, b))| ((a.min(b), a.max(b)), f as u32))
            .collect();
        facet_keys.sort_unstable();
        Region {
            open,
            facets: facets.to_vec(),
            facet_keys,
            bare,
            unused: Vec::new(),
        }
    }

    /// Whether node `g` is a node of a peeled cell that no alive cell has as a corner.
    fn unused(&self, g: u32) -> bool {
        self.unused.binary_search(&g).is_ok()
    }

    /// The region's boundary as directed edges with the region on their left: the open cell
    /// sides reversed, in cell order, then the facets no alive cell stands on.
    fn directed(&self, cells: &[Cell]) -> Vec<(u32, u32)> {
        let mut directed: Vec<(u32, u32)> = self
            .open
            .iter()
            .map(|&(c, j)| {
                let k = cells[c as usize].corners();
                let j = j as usize;
                (k[(j + 1) % k.len()], k[j])
            })
            .collect();
        directed.extend(
            (0..self.facets.len())
                .filter(|&f| self.bare[f])
                .map(|f| self.facets[f]),
        );
        directed
    }

    /// Takes the cells `peeled` (cell, its number of corners; alive until now, their `len`
    /// already 0) out of the region's walls: the sides they shared with one alive cell open,
    /// the facets under them are laid bare, and their nodes no alive cell keeps are unused.
    /// `of_node` lists the cells alive before any peel.
    fn peel(&mut self, cells: &[Cell], peeled: &[(u32, u8)], of_node: &CellsOfNode) {
        self.open.retain(|&(c, _)| cells[c as usize].len > 0);
        for &(c, len) in peeled {
            let nodes = &cells[c as usize].nodes;
            let k = &nodes[..len as usize];
            for j in 0..k.len() {
                let (a, b) = (k[j], k[(j + 1) % k.len()]);
                let sides = of_node.sides(cells, a, b);
                let key = (a.min(b), a.max(b));
                let from = self.facet_keys.partition_point(|f| f.0 < key);
                let on = self.facet_keys[from..]
                    .iter()
                    .take_while(|f| f.0 == key)
                    .map(|f| f.1 as usize);
                let mut facet = false;
                for f in on {
                    facet = true;
                    self.bare[f] = sides.is_empty();
                }
                if sides.len() == 1 && !facet {
                    self.open.push(sides[0]);
                }
            }
            for &g in nodes.iter().filter(|&&g| g != NONE) {
                let kept = of_node.of(g).iter().any(|&d| cells[d as usize].len > 0);
                if !kept {
                    self.unused.push(g);
                }
            }
        }
        self.open.sort_unstable();
        self.open.dedup();
        self.unused.sort_unstable();
        self.unused.dedup();
    }
}

/// The open cell sides (sorted) and the bare facets, from the fronts: every front edge with
/// a cell is a side of that alive cell, met once; every front edge without one is a facet,
/// met once; else `None`.
fn open_from_fronts(
    cells: &[Cell],
    facets: &[(u32, u32)],
    fronts: &[(u32, u32, u32)],
) -> Option<OpenAndBare> {
    let mut open = Vec::with_capacity(fronts.len());
    let mut bare_edges = Vec::new();
    for &(a, b, c) in fronts {
        if c == NONE {
            bare_edges.push((a, b));
            continue;
        }
        let cell = cells.get(c as usize)?;
        let k = cell.corners();
        // the cell is on the right of the front edge: its side (b, a)
        let j = (0..k.len()).find(|&j| k[j] == b && k[(j + 1) % k.len()] == a)?;
        open.push((c, j as u32));
    }
    open.sort_unstable();
    if open.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    bare_edges.sort_unstable();
    let bare: Vec<bool> = facets
        .iter()
        .map(|f| bare_edges.binary_search(f).is_ok())
        .collect();
    let n_bare = bare.iter().filter(|&&b| b).count();
    if n_bare != bare_edges.len() || bare_edges.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    Some((open, bare))
}

#[cfg(test)]
mod tests {
    use super::*;
    use flips::FLIP_SWEEPS;
    use smooth::SMOOTHING_SWEEPS;

    /// The region's boundary counted from scratch, as every peel round did before `Region`.
    fn directed_from_scratch(cells: &[Cell], facets: &[(u32, u32)]) -> Vec<(u32, u32)> {
        let live: Vec<&Cell> = cells.iter().filter(|c| c.len > 0).collect();
        let facet_nodes: Vec<[u32; 2]> = facets.iter().map(|&(a, b)| [a, b]).collect();
        let shape = |c: &Cell| if c.len == 3 { Shape::Tri } else { Shape::Quad };
        let edges = Edges::build(
            live.iter().map(|c| (shape(c), c.corners())),
            facet_nodes.iter().map(|f| &f[..]),
        );
        let mut directed = Vec::new();
        for (i, c) in live.iter().enumerate() {
            let k = c.corners();
            for (j, &e) in edges.of_cell(i).iter().enumerate() {
                if edges.cells(e).len() == 1 && !edges.is_boundary(e) {
                    directed.push((k[(j + 1) % k.len()], k[j]));
                }
            }
        }
        for &(a, b) in facets {
            if edges
                .find(&[a, b])
                .is_none_or(|e| edges.cells(e).is_empty())
            {
                directed.push((a, b));
            }
        }
        directed
    }

    /// The largest angle of a triangle, infinite when it is not positive.
    fn naive_worst(c: [P2; 3]) -> f64 {
        if orient2d(c[0], c[1], c[2]) <= 0.0 {
            return f64::INFINITY;
        }
        crate::quality::max_triangle_angle_deg(c[0], c[1], c[2])
    }

    /// The flips as specified, in mesh numbers, measuring every pair each sweep (no pair
    /// kept from the last sweep, no cosines, no table of owners but a map).
    pub(super) fn naive_flips(
        tris: &mut [[u32; 3]],
        at: &dyn Fn(u32) -> P2,
        constraints: &[(u32, u32)],
    ) {
        let worst = |t: [u32; 3]| naive_worst(t.map(at));
        for _ in 0..FLIP_SWEEPS {
            let mut owner = std::collections::BTreeMap::new();
            for (t, tri) in tris.iter().enumerate() {
                for i in 0..3 {
                    owner.insert((tri[i], tri[(i + 1) % 3]), (t, (i + 2) % 3));
                }
            }
            let mut flipped = vec![false; tris.len()];
            let mut flips = 0;
            for (&(a, b), &(t1, c1)) in owner.iter().filter(|(e, _)| e.0 < e.1) {
                let Some(&(t2, c2)) = owner.get(&(b, a)) else {
                    continue;
                };
                if constraints.contains(&(a, b)) || flipped[t1] || flipped[t2] {
                    continue;
                }
                let (c, d) = (tris[t1][c1], tris[t2][c2]);
                let before = worst(tris[t1]).max(worst(tris[t2]));
                let (n1, n2) = ([c, a, d], [d, b, c]);
                if worst(n1).max(worst(n2)) < before - 1e-6 {
                    tris[t1] = n1;
                    tris[t2] = n2;
                    flipped[t1] = true;
                    flipped[t2] = true;
                    flips += 1;
                }
            }
            if flips == 0 {
                break;
            }
        }
    }

    /// The smoothing as specified, in mesh numbers (added node `s` is `n0 + s`): every node
    /// tried in every sweep, every angle measured.
    fn naive_smoothing(tris: &[[u32; 3]], pos: &[P2], steiner: &mut [P2]) {
        let n0 = pos.len();
        for _ in 0..SMOOTHING_SWEEPS {
            for s in 0..steiner.len() {
                let g = (n0 + s) as u32;
                let at = |v: u32, p: P2, steiner: &[P2]| {
                    if v == g {
                        p
                    } else if (v as usize) < n0 {
                        pos[v as usize]
                    } else {
                        steiner[v as usize - n0]
                    }
                };
                let own: Vec<[u32; 3]> = tris.iter().copied().filter(|t| t.contains(&g)).collect();
                if own.is_empty() {
                    continue;
                }
                let old = steiner[s];
                let (mut sx, mut sy, mut k) = (0.0, 0.0, 0.0);
                for t in &own {
                    for &v in t.iter().filter(|&&v| v != g) {
                        let q = at(v, old, steiner);
                        sx += q[0];
                        sy += q[1];
                        k += 1.0;
                    }
                }
                let centroid = [sx / k, sy / k];
                let figures = own
                    .iter()
                    .map(|t| naive_worst(t.map(|v| at(v, old, steiner))));
                let before = figures.fold(0.0f64, |w, f| {
                    if w == f64::INFINITY || f == f64::INFINITY {
                        f64::INFINITY
                    } else {
                        w.max(f)
                    }
                });
                for f in [1.0, 0.5, 0.25] {
                    let p = [
                        old[0] + f * (centroid[0] - old[0]),
                        old[1] + f * (centroid[1] - old[1]),
                    ];
                    let better = own.iter().all(|t| {
                        let c = t.map(|v| at(v, p, steiner));
                        let angle = crate::quality::max_triangle_angle_deg(c[0], c[1], c[2]);
                        orient2d(c[0], c[1], c[2]) > 0.0 && (angle < before || angle.is_nan())
                    });
                    if better && 0.0 < before {
                        steiner[s] = p;
                        break;
                    }
                }
            }
        }
    }

    /// `n` points around an ellipse of radius `r` (its height `squash` × its width),
    /// counter-clockwise, each moved along the ellipse by up to 0.3 of its step and out by up
    /// to `radial` × `r`.
    pub(super) fn jittered_ring(
        n: usize,
        r: f64,
        (radial, squash): (f64, f64),
        rng: &mut testkit::layered::Rng,
    ) -> Vec<P2> {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * (i as f64 + 0.3 * rng.unit()) / n as f64;
                let r = r * (1.0 + radial * rng.unit());
                [r * a.cos(), squash * r * a.sin()]
            })
            .collect()
    }

    /// The refined fill of an annulus of `outer` and `inner` jittered nodes before its flips
    /// and smoothing, in its own numbering, with its front edges (lower end first, sorted).
    pub(super) fn refined_annulus(
        outer: usize,
        inner: usize,
        rng: &mut testkit::layered::Rng,
    ) -> (Local, Vec<(u32, u32)>) {
        let mut points = jittered_ring(outer, 10.0, (0.3, 0.7), rng);
        let mut hole = jittered_ring(inner, 3.0, (0.3, 0.7), rng);
        hole.reverse(); // clockwise: the region on the left of its edges
        points.extend(hole);
        let ring = |from: usize, len: usize| {
            (0..len).map(move |i| ((from + i) as u32, (from + (i + 1) % len) as u32))
        };
        let directed: Vec<(u32, u32)> = ring(0, outer).chain(ring(outer, inner)).collect();
        triangulate(&directed, &[], &points, 30.0).unwrap()
    }

    /// The flips and smoothing on the fill's own numbering give the triangles and added
    /// nodes of flipping and smoothing as specified in the mesh's numbering, to the last
    /// bit: annuli whose nodes have shuffled indices among unrelated nodes (so that no order
    /// of insertion or of position stands in for the order of the indices).
    #[test]
    fn the_local_flips_and_smoothing_are_those_of_the_mesh_numbering() {
        let mut rng = testkit::layered::Rng(28);
        for case in 0..4 {
            let (outer, inner) = (60 + 60 * case, 40 + 30 * case);
            let mut points = jittered_ring(outer, 10.0, (0.3, 0.7), &mut rng);
            let mut hole = jittered_ring(inner, 3.0, (0.3, 0.7), &mut rng);
            hole.reverse(); // clockwise: the region on the left of its edges
            points.extend(hole);
            // a few free nodes in the region
            points.extend((0..3).map(|i| [6.0 + i as f64 * 0.2, 0.1 * i as f64]));
            let n = points.len();
            // node k of the region is mesh node `id[k]` among 4n nodes
            let mut id: Vec<u32> = (0..4 * n as u32).collect();
            rng.shuffle(&mut id);
            id.truncate(n);
            let mut pos: Vec<P2> = (0..4 * n).map(|i| [1e3 + i as f64, -7.0]).collect();
            for (k, &g) in id.iter().enumerate() {
                pos[g as usize] = points[k];
            }
            let loop_edges =
                |from: usize, len: usize| (0..len).map(move |i| (from + i, from + (i + 1) % len));
            let directed: Vec<(u32, u32)> = loop_edges(0, outer)
                .chain(loop_edges(outer, inner))
                .map(|(a, b)| (id[a], id[b]))
                .collect();
            let free: Vec<u32> = id[outer + inner..].to_vec();
            let (local, constraints) = triangulate(&directed, &free, &pos, 30.0).unwrap();
            assert!(
                local.pts.len() > local.front.len() + 100,
                "the refinement adds nodes"
            );
            let (mut want, mut steiner) = local.clone().into_global(pos.len());
            let mut sorted: Vec<(u32, u32)> = directed
                .iter()
                .map(|&(a, b)| (a.min(b), a.max(b)))
                .collect();
            sorted.sort_unstable();
            {
                let at = |g: u32| {
                    let g = g as usize;
                    if g < pos.len() {
                        pos[g]
                    } else {
                        steiner[g - pos.len()]
                    }
                };
                naive_flips(&mut want, &at, &sorted);
            }
            naive_smoothing(&want, &pos, &mut steiner);
            let at = |g: u32| {
                let g = g as usize;
                if g < pos.len() {
                    pos[g]
                } else {
                    steiner[g - pos.len()]
                }
            };
            naive_flips(&mut want, &at, &sorted);
            let mut local = local;
            local.improve(&constraints);
            let (got, got_steiner) = local.into_global(pos.len());
            assert_eq!(got, want, "case {case}: the triangles");
            let bits = |p: &[P2]| p.iter().map(|q| q.map(f64::to_bits)).collect::<Vec<_>>();
            assert_eq!(
                bits(&got_steiner),
                bits(&steiner),
                "case {case}: the added nodes"
            );
        }
    }

    #[test]
    fn the_kept_boundary_equals_the_boundary_counted_from_scratch_after_each_peel() {
        // an 8 × 8 grid of nodes: quads, every third cut into two triangles; the bottom row's
        // edges are facets (the domain above them), as a wall under the first layer
        let n = 8u32;
        let at = |i: u32, j: u32| j * n + i;
        let mut cells = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                let cell = |nodes: [u32; 4], len| Cell {
                    nodes,
                    len,
                    layer: j,
                    pipe: 0,
                    origin: [0; 3],
                };
                if (i + j) % 3 == 0 {
                    cells.push(cell([q[0], q[1], q[2], NONE], 3));
                    cells.push(cell([q[0], q[2], q[3], NONE], 3));
                } else {
                    cells.push(cell(q, 4));
                }
            }
        }
        let facets: Vec<(u32, u32)> = (0..n - 1).map(|i| (at(i, 0), at(i + 1, 0))).collect();
        // the fronts: every open cell side reversed with its cell, the bare facets without
        let mut fronts = Vec::new();
        for (ci, c) in cells.iter().enumerate() {
            let k = c.corners();
            for j in 0..k.len() {
                let (a, b) = (k[j], k[(j + 1) % k.len()]);
                let shared = cells.iter().enumerate().any(|(di, d)| {
                    let m = d.corners();
                    di != ci && (0..m.len()).any(|i| m[i] == b && m[(i + 1) % m.len()] == a)
                });
                if !shared && !facets.contains(&(a, b)) {
                    fronts.push((b, a, ci as u32));
                }
            }
        }
        fronts.reverse(); // any order
        // a front edge on no cell side: the boundary is counted from the edge table instead
        let wrong = [(at(0, 0), at(7, 7), 3)];
        let n_nodes = (n * n) as usize;
        assert!(open_from_fronts(&cells, &facets, &fronts).is_some());
        assert!(open_from_fronts(&cells, &facets, &wrong).is_none());
        let mut regions = [
            Region::new(&cells, &facets, &fronts),
            Region::new(&cells, &facets, &wrong),
        ];
        for region in &regions {
            assert_eq!(
                region.directed(&cells),
                directed_from_scratch(&cells, &facets)
            );
        }
        // (before any peel: the cells alive at the start)
        let of_node = CellsOfNode::new(&cells, n_nodes);
        let mut seed = 12345u64;
        let mut gone: Vec<u32> = Vec::new();
        for _round in 0..6 {
            let mut now = Vec::new();
            for (ci, c) in cells.iter_mut().enumerate() {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                if c.len > 0 && (seed >> 33) % 5 == 1 {
                    now.push((ci as u32, c.len));
                    gone.push(ci as u32);
                    c.len = 0;
                }
            }
            for region in &mut regions {
                region.peel(&cells, &now, &of_node);
                assert_eq!(
                    region.directed(&cells),
                    directed_from_scratch(&cells, &facets)
                );
                // the nodes of the cells peeled so far: unused exactly when no alive cell has
                // them
                for &c in &gone {
                    for g in cells[c as usize].nodes.into_iter().filter(|&g| g != NONE) {
                        let used = cells.iter().any(|c| c.corners().contains(&g));
                        assert_eq!(!region.unused(g), used, "node {g}");
                    }
                }
            }
        }
        assert!(
            cells.iter().any(|c| c.len > 0),
            "some cells are left to test"
        );
    }

    /// A 10 × 9 grid of cells over unit columns, layer `j` in row `j`, the domain's boundary
    /// its facets; row 4 is 0.15 high (its cells too thin to peel) and its cells 3 to 6 are
    /// missing: a thin slot whose top nodes sit half a column off its bottom ones, so that
    /// its triangles can only be flat and the fill peels the cells above and below it. The
    /// cells, facets, fronts and node positions.
    type Grid = (Vec<Cell>, Vec<(u32, u32)>, Vec<(u32, u32, u32)>, Vec<P2>);

    fn slotted_grid() -> Grid {
        let (nx, ny) = (10u32, 9u32);
        let ys: Vec<f64> = (0..=ny)
            .map(|j| if j <= 4 { j as f64 } else { j as f64 - 0.85 })
            .collect();
        let at = |i: u32, j: u32| j * (nx + 1) + i;
        let pos: Vec<P2> = (0..=ny)
            .flat_map(|j| (0..=nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let shift = if j == 5 && (4..=6).contains(&i) {
                    0.5
                } else {
                    0.0
                };
                [i as f64 + shift, ys[j as usize]]
            })
            .collect();
        let mut cells = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                if j == 4 && (3..7).contains(&i) {
                    continue;
                }
                cells.push(Cell {
                    nodes: [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                    len: 4,
                    layer: j,
                    pipe: 0,
                    origin: [0; 3],
                });
            }
        }
        // the grid's outline, counter-clockwise
        let mut outline: Vec<u32> = (0..nx).map(|i| at(i, 0)).collect();
        outline.extend((0..ny).map(|j| at(nx, j)));
        outline.extend((1..=nx).rev().map(|i| at(i, ny)));
        outline.extend((1..=ny).rev().map(|j| at(0, j)));
        let facets: Vec<(u32, u32)> = (0..outline.len())
            .map(|k| (outline[k], outline[(k + 1) % outline.len()]))
            .collect();
        // the slot's fronts: its cells' open sides, reversed
        let mut fronts = Vec::new();
        for (ci, c) in cells.iter().enumerate() {
            let k = c.corners();
            for j in 0..4 {
                let (a, b) = (k[j], k[(j + 1) % 4]);
                let shared = cells
                    .iter()
                    .any(|d| (0..4).any(|i| d.nodes[i] == b && d.nodes[(i + 1) % 4] == a));
                if !shared && !facets.contains(&(a, b)) {
                    fronts.push((b, a, ci as u32));
                }
            }
        }
        (cells, facets, fronts, pos)
    }

    /// Twice the signed area of a polygon.
    fn twice_area(p: &[P2]) -> f64 {
        (0..p.len())
            .map(|i| {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum()
    }

    /// The layered cells left and the fill cover the domain (area `domain`) exactly and
    /// conform: every fill triangle positive, every edge in two cells or in one cell and a
    /// facet, every added node and every node of a peeled cell used.
    fn assert_covers(cells: &[Cell], facets: &[(u32, u32)], fill: &PeeledFill, pos: &[P2]) {
        let (tris, steiner, peeled) = fill;
        let all: Vec<P2> = pos.iter().chain(steiner).copied().collect();
        let corners = |k: &[u32]| k.iter().map(|&g| all[g as usize]).collect::<Vec<P2>>();
        let live: Vec<&[u32]> = cells
            .iter()
            .filter(|c| c.len > 0)
            .map(|c| c.corners())
            .collect();
        assert_eq!(cells.len() - live.len(), peeled.len());
        for t in tris {
            let c = corners(t);
            assert!(orient2d(c[0], c[1], c[2]) > 0.0, "triangle {t:?}");
        }
        let covered: f64 = live
            .iter()
            .copied()
            .chain(tris.iter().map(|t| &t[..]))
            .map(|k| twice_area(&corners(k)))
            .sum();
        let outline: Vec<P2> = facets.iter().map(|&(a, _)| pos[a as usize]).collect();
        let domain = twice_area(&outline);
        assert!(
            (covered - domain).abs() < 1e-12 * domain,
            "{covered} vs {domain}"
        );
        let shape = |k: &[u32]| {
            if k.len() == 3 {
                Shape::Tri
            } else {
                Shape::Quad
            }
        };
        let facet_nodes: Vec<[u32; 2]> = facets.iter().map(|&(a, b)| [a, b]).collect();
        let elements: Vec<&[u32]> = live
            .iter()
            .copied()
            .chain(tris.iter().map(|t| &t[..]))
            .collect();
        let edges = Edges::build(
            elements.iter().map(|&k| (shape(k), k)),
            facet_nodes.iter().map(|f| &f[..]),
        );
        for e in 0..edges.len() as u32 {
            let uses = edges.cells(e).len() + usize::from(edges.is_boundary(e));
            assert_eq!(uses, 2, "edge {:?}", edges.nodes(e));
        }
        let mut used = vec![false; all.len()];
        for k in &elements {
            for &g in k.iter() {
                used[g as usize] = true;
            }
        }
        assert!(used.iter().all(|&u| u), "every node is a corner");
    }

    const SLOT_ANGLES: FillAngles = FillAngles {
        min_angle_deg: 30.0,
        peel_max_angle_deg: 120.0,
        rounds: 16,
    };

    /// A peel round fills only the cavity around what it changed, and the result covers the
    /// region exactly and conforms; the cavity's triangles are fewer than the region's.
    #[test]
    fn a_peel_round_fills_again_around_what_it_changed() {
        let (mut cells, facets, fronts, pos) = slotted_grid();
        let live = |cells: &[Cell]| cells.iter().filter(|c| c.len > 0).count();
        let at_start = live(&cells);
        let (fill, refills, seen) = peel_rounds(
            &mut cells,
            &facets,
            &fronts,
            &pos,
            SLOT_ANGLES,
            refill_cavity,
            live,
        )
        .unwrap();
        assert!(!fill.2.is_empty(), "the slot peels");
        // what runs beside the first fill reads the cells before any peel
        assert_eq!(seen, at_start);
        assert_eq!(live(&cells), at_start - fill.2.len());
        assert!(refills.local > 0 && refills.whole == 0, "{refills:?}");
        assert_covers(&cells, &facets, &fill, &pos);
        // no triangle is left with an angle of 120° or more where a round could peel more
        let (tris, steiner, _) = &fill;
        let at = |g: u32| {
            if (g as usize) < pos.len() {
                pos[g as usize]
            } else {
                steiner[g as usize - pos.len()]
            }
        };
        let worst = tris
            .iter()
            .map(|t| crate::quality::max_triangle_angle_deg(at(t[0]), at(t[1]), at(t[2])))
            .fold(0.0f64, f64::max);
        assert!(worst < 120.0, "worst fill angle {worst}");
    }

    /// When the fill around what changed fails, the round fills the whole region again, as
    /// every round did before: the same cells peeled, the region covered.
    #[test]
    fn a_failed_cavity_fill_falls_back_to_the_whole_region() {
        fn refuse(
            _: &Fill,
            _: &Change<'_>,
            _: &[Cell],
            _: &Region,
            _: &[P2],
            _: f64,
        ) -> Result<Fill, AfsfError> {
            Err(AfsfError::Fill("refused".into()))
        }
        let (mut cells, facets, fronts, pos) = slotted_grid();
        let (fill, refills, ()) = peel_rounds(
            &mut cells,
            &facets,
            &fronts,
            &pos,
            SLOT_ANGLES,
            refuse,
            |_| (),
        )
        .unwrap();
        assert!(!fill.2.is_empty(), "the slot peels");
        assert!(refills.local == 0 && refills.whole > 0, "{refills:?}");
        assert_covers(&cells, &facets, &fill, &pos);
    }

    /// The cavity fill refuses a cavity whose inside holds a node a layered cell still has,
    /// and one whose elements overlap (a side met twice the same way).
    #[test]
    fn the_cavity_fill_refuses_what_it_cannot_fill() {
        let (mut cells, facets, fronts, pos) = slotted_grid();
        let region = Region::new(&cells, &facets, &fronts);
        let directed = region.directed(&cells);
        let (tris, steiner) = fill_region(&directed, &[], &pos, 30.0).unwrap();
        let prev = Fill {
            tris,
            steiner,
            new_from: 0,
        };
        // the four cells around node (5, 6), "peeled" without the region knowing: that
        // node, inside the cavity, is still a node of the layered cells
        let around: Vec<usize> = (0..cells.len())
            .filter(|&c| cells[c].nodes.contains(&(6 * 11 + 5)))
            .collect();
        assert_eq!(around.len(), 4);
        let peeled: Vec<(u32, u8)> = around.iter().map(|&c| (c as u32, 4)).collect();
        for &c in &around {
            cells[c].len = 0;
        }
        let change = Change {
            bad: &[],
            peeled: &peeled,
        };
        let got = refill_cavity(&prev, &change, &cells, &region, &pos, 30.0);
        assert!(got.is_err());
        // a layered cell taken into the cavity twice overlaps itself
        let twice = [peeled[0], peeled[0]];
        let change = Change {
            bad: &[],
            peeled: &twice,
        };
        let got = refill_cavity(&prev, &change, &cells, &region, &pos, 30.0);
        assert!(got.is_err());
    }
}
