//! Filling the region left between the closed fronts: a constrained Delaunay triangulation
//! (`spade`) of the front nodes with every front edge as a constraint, keeping the triangles
//! on the left of the fronts (flood fill that never crosses a constraint), refined inside,
//! then improved by largest-angle edge flips and Steiner smoothing. Front edges are never
//! split, so the fill conforms to the layered cells edge for edge.
//!
//! It owns nothing else: the fronts are kept simple and disjoint by `grow`, which is what
//! makes this triangulation exact.

use spade::handles::FixedFaceHandle;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

use geom_predicates::orient2d;
use geom_predicates::vector::dist;
use mesh_model::topology::Edges;
use mesh_model::{NONE, Shape};
use spade::{AngleLimit, RefinementParameters};

use crate::error::AfsfError;
use crate::geom::P2;
use crate::grow::Cell;

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
pub(crate) fn fill_region(
    directed_edges: &[(u32, u32)],
    free: &[u32],
    pos: &[P2],
    min_angle_deg: f64,
) -> Result<(Vec<[u32; 3]>, Vec<P2>), AfsfError> {
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
    let (mut tris, mut steiner) = triangles_of(&cdt, &faces, pos);
    let mut constraints: Vec<(u32, u32)> = directed_edges
        .iter()
        .map(|&(a, b)| if a < b { (a, b) } else { (b, a) })
        .collect();
    constraints.sort_unstable();
    flip_min_max_angle(&mut tris, pos, &steiner, &constraints);
    smooth_steiner(&tris, pos, &mut steiner);
    flip_min_max_angle(&mut tris, pos, &steiner, &constraints);
    Ok((tris, steiner))
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

/// The triangles of `faces` as node indices; the vertices the refinement added become new
/// nodes, numbered from `pos.len()` in order of first use, with their positions.
fn triangles_of(cdt: &Cdt, faces: &[InnerFace], pos: &[P2]) -> (Vec<[u32; 3]>, Vec<P2>) {
    let mut added: Vec<u32> = vec![NONE; cdt.num_vertices()];
    let mut steiner = Vec::new();
    let tris: Vec<[u32; 3]> = faces
        .iter()
        .map(|&f| {
            let v = cdt.face(f).vertices();
            v.map(|h| {
                let node = h.data().node;
                if node != NONE {
                    return node;
                }
                let slot = &mut added[h.fix().index()];
                if *slot == NONE {
                    let p = h.position();
                    steiner.push([p.x, p.y]);
                    *slot = (pos.len() + steiner.len() - 1) as u32;
                }
                *slot
            })
        })
        .collect();
    (tris, steiner)
}

/// Sweeps of the largest-angle edge flips.
const FLIP_SWEEPS: usize = 16;

/// Flips the diagonal of two fill triangles that share an edge which is not a front edge,
/// whenever the other diagonal lowers the larger of their largest angles: the constrained
/// Delaunay triangulation maximises the smallest angle, which is not the figure a solver
/// needs, and next to long front edges it keeps flat triangles whose other diagonal is
/// fine. Both new triangles must be positive (the pair forms a convex quadrilateral).
fn flip_min_max_angle(
    tris: &mut [[u32; 3]],
    pos: &[P2],
    steiner: &[P2],
    constraints: &[(u32, u32)],
) {
    let n0 = pos.len();
    let at = |g: u32| {
        if (g as usize) < n0 {
            pos[g as usize]
        } else {
            steiner[g as usize - n0]
        }
    };
    let worst = |t: [u32; 3]| {
        let (a, b, c) = (at(t[0]), at(t[1]), at(t[2]));
        if orient2d(a, b, c) <= 0.0 {
            return f64::INFINITY;
        }
        crate::quality::max_triangle_angle_deg(a, b, c)
    };
    // each triangle's figure, kept up to date through the flips (the nodes do not move here)
    let mut figure: Vec<f64> = {
        use rayon::prelude::*;
        tris.par_iter().map(|&t| worst(t)).collect()
    };
    // `kept[3 t + c]`: the other triangle of the edge opposite corner `c` of `t` when that pair
    // was tried in the last sweep and not flipped; a pair tried again unchanged (neither
    // triangle flipped since) would again not flip, so it is skipped
    let mut kept = vec![NONE; 3 * tris.len()];
    let mut flipped = vec![false; tris.len()];
    for _ in 0..FLIP_SWEEPS {
        let owner = Owners::new(tris);
        let before_sweep = std::mem::replace(&mut flipped, vec![false; tris.len()]);
        let tried = std::mem::replace(&mut kept, vec![NONE; 3 * tris.len()]);
        let mut flips = 0;
        // in a fixed order: the same input makes the same mesh
        for &((a, b), (t1, c1)) in &owner.by_edge {
            if a >= b {
                continue;
            }
            // a pair tried in the last sweep, neither triangle flipped since: `t2` still owns
            // (b, a) when every directed edge has one owner
            let t2 = tried[3 * t1 + c1];
            if owner.unique && t2 != NONE && !before_sweep[t1] && !before_sweep[t2 as usize] {
                if !flipped[t1] && !flipped[t2 as usize] {
                    kept[3 * t1 + c1] = t2;
                }
                continue;
            }
            if constraints.binary_search(&(a, b)).is_ok() {
                continue;
            }
            let Some((t2, c2)) = owner.get((b, a)) else {
                continue;
            };
            if flipped[t1] || flipped[t2] {
                continue;
            }
            let (c, d) = (tris[t1][c1], tris[t2][c2]);
            // t1 = (a, b, c), t2 = (b, a, d), both counter-clockwise
            let before = figure[t1].max(figure[t2]);
            let (n1, n2) = ([c, a, d], [d, b, c]);
            // the second triangle is measured only when the first leaves the flip possible
            let w1 = worst(n1);
            let w2 = if w1 >= before - 1e-6 {
                f64::INFINITY
            } else {
                worst(n2)
            };
            if w1.max(w2) < before - 1e-6 {
                tris[t1] = n1;
                tris[t2] = n2;
                figure[t1] = w1;
                figure[t2] = w2;
                flipped[t1] = true;
                flipped[t2] = true;
                flips += 1;
            } else {
                kept[3 * t1 + c1] = t2 as u32;
            }
        }
        if flips == 0 {
            break;
        }
    }
}

/// The triangle and the opposite corner of each directed edge (`tri[i] -> tri[i+1]`,
/// opposite corner `i+2`), sorted by edge: a directed edge met twice keeps its last triangle.
struct Owners {
    by_edge: Vec<((u32, u32), (usize, usize))>,
    /// Whether no directed edge was met twice.
    unique: bool,
}

impl Owners {
    fn new(tris: &[[u32; 3]]) -> Self {
        use rayon::prelude::*;
        // (edge, position 3 t + i): the keys are distinct, so sorting them orders equal edges
        // by position, as a stable sort by edge alone did (the parallel merge sort, like the
        // sequential one, runs in near-linear time over the runs of a triangulation's edges)
        let mut owner: Vec<(u32, u32, u32)> = tris
            .par_iter()
            .enumerate()
            .flat_map_iter(|(t, tri)| {
                (0..3).map(move |i| (tri[i], tri[(i + 1) % 3], (3 * t + i) as u32))
            })
            .collect();
        owner.par_sort();
        let mut kept: Vec<((u32, u32), (usize, usize))> = Vec::with_capacity(owner.len());
        for (a, b, at) in owner {
            let o = ((a, b), (at as usize / 3, (at as usize % 3 + 2) % 3));
            match kept.last_mut() {
                // among equal edges the last position is kept
                Some(last) if last.0 == o.0 => *last = o,
                _ => kept.push(o),
            }
        }
        Owners {
            unique: kept.len() == 3 * tris.len(),
            by_edge: kept,
        }
    }

    fn get(&self, edge: (u32, u32)) -> Option<(usize, usize)> {
        let i = self.by_edge.binary_search_by_key(&edge, |&(k, _)| k).ok()?;
        Some(self.by_edge[i].1)
    }
}

/// Sweeps of the Steiner-node smoothing.
const SMOOTHING_SWEEPS: usize = 6;

/// Moves each added node toward the centroid of its triangles' other corners when that
/// lowers the largest angle of its triangles (and keeps them positive): the refinement
/// leaves obtuse triangles where it may not split a front edge, and these moves mend most
/// of them. Front nodes never move.
fn smooth_steiner(tris: &[[u32; 3]], pos: &[P2], steiner: &mut [P2]) {
    if steiner.is_empty() {
        return;
    }
    let n0 = pos.len();
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); steiner.len()];
    for (t, tri) in tris.iter().enumerate() {
        for &g in tri {
            if g as usize >= n0 {
                incident[g as usize - n0].push(t as u32);
            }
        }
    }
    let at = |g: u32, steiner: &[P2]| {
        if (g as usize) < n0 {
            pos[g as usize]
        } else {
            steiner[g as usize - n0]
        }
    };
    let corners = |s: usize, t: u32, p: P2, steiner: &[P2]| {
        let g = (n0 + s) as u32;
        tris[t as usize].map(|v| if v == g { p } else { at(v, steiner) })
    };
    // the largest angle of each triangle where its corners are (infinite when it is not
    // positive), kept until one of its corners moves: `None` when not measured since
    let mut figure: Vec<Option<f64>> = vec![None; tris.len()];
    // the largest angle of node `s`'s triangles where they are (infinite when one is not
    // positive), from the kept figures
    let worst = |s: usize, steiner: &[P2], figure: &mut [Option<f64>]| -> f64 {
        let mut w = 0.0f64;
        for &t in &incident[s] {
            let f = *figure[t as usize].get_or_insert_with(|| {
                let c = tris[t as usize].map(|v| at(v, steiner));
                if orient2d(c[0], c[1], c[2]) <= 0.0 {
                    f64::INFINITY
                } else {
                    crate::quality::max_triangle_angle_deg(c[0], c[1], c[2])
                }
            });
            if f == f64::INFINITY {
                return f64::INFINITY;
            }
            w = w.max(f);
        }
        w
    };
    // exactly "the largest angle of `s`'s triangles with `s` at `p` < before", the angles mostly compared by their cosines
    let improves = |s: usize, p: P2, steiner: &[P2], before: f64| -> bool {
        let limit = crate::quality::AngleLimit::new(before);
        for &t in &incident[s] {
            let c = corners(s, t, p, steiner);
            if orient2d(c[0], c[1], c[2]) <= 0.0 {
                return false;
            }
            // (a NaN angle is passed over by the maximum in `worst`)
            if !limit.triangle_below(c[0], c[1], c[2])
                && !crate::quality::max_triangle_angle_deg(c[0], c[1], c[2]).is_nan()
            {
                return false;
            }
        }
        0.0 < before
    };
    // a node tried and left where it was is tried again only once one of its neighbours
    // moved (else it would stay again): `moved[v]` counts the moves up to v's last one,
    // `settled[s]` the moves before s was last left (plus one; 0: not settled)
    let (mut moves, mut moved, mut settled) =
        (0u64, vec![0u64; steiner.len()], vec![0u64; steiner.len()]);
    for _ in 0..SMOOTHING_SWEEPS {
        for s in 0..steiner.len() {
            let g = (n0 + s) as u32;
            if settled[s] != 0 {
                let still = incident[s].iter().all(|&t| {
                    tris[t as usize].iter().all(|&v| {
                        (v as usize) < n0 || v == g || moved[v as usize - n0] < settled[s]
                    })
                });
                if still {
                    continue;
                }
            }
            let (mut sx, mut sy, mut k) = (0.0, 0.0, 0.0);
            for &t in &incident[s] {
                for &v in &tris[t as usize] {
                    if v != g {
                        let q = at(v, steiner);
                        sx += q[0];
                        sy += q[1];
                        k += 1.0;
                    }
                }
            }
            if k == 0.0 {
                continue;
            }
            let old = steiner[s];
            let centroid = [sx / k, sy / k];
            let before = worst(s, steiner, &mut figure);
            settled[s] = moves + 1;
            for f in [1.0, 0.5, 0.25] {
                let p = [
                    old[0] + f * (centroid[0] - old[0]),
                    old[1] + f * (centroid[1] - old[1]),
                ];
                if improves(s, p, steiner, before) {
                    steiner[s] = p;
                    for &t in &incident[s] {
                        figure[t as usize] = None;
                    }
                    moves += 1;
                    moved[s] = moves;
                    settled[s] = 0;
                    break;
                }
            }
        }
    }
}

/// The fill triangles, the added nodes and the number of cells peeled.
pub(crate) type PeeledFill = (Vec<[u32; 3]>, Vec<P2>, usize);

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
/// angle of `max_angle_deg` or more, peels the layered cells (not the first layer) that touch
/// those triangles into the region and fills again, at most `rounds` times: a coarse cell
/// whose corner pinches the region between fronts of very different sizes thus becomes room
/// for well-shaped triangles. Peeled cells get `len` 0; their nodes are kept (inside the
/// region, as triangulation vertices, when no remaining cell uses them). `facets` are the
/// boundary facets with the domain on their left. Returns the triangles, the added nodes
/// (numbered from `pos.len()` on) and the number of cells peeled.
pub(crate) fn fill_with_peeling(
    cells: &mut [Cell],
    facets: &[(u32, u32)],
    pos: &[P2],
    min_angle_deg: f64,
    max_angle_deg: f64,
    rounds: u32,
) -> Result<PeeledFill, AfsfError> {
    let mut region = Region::new(cells, facets, pos.len());
    let peelable = Peelable::new(cells, pos);
    let limit = crate::quality::AngleLimit::new(max_angle_deg);
    let mut peeled: Vec<u32> = Vec::new();
    let mut round = 0;
    loop {
        let directed = region.directed(cells);
        let free: Vec<u32> = peeled
            .iter()
            .flat_map(|&c| cells[c as usize].nodes)
            .filter(|&g| g != mesh_model::NONE && region.node_uses[g as usize] == 0)
            .collect();
        let (tris, steiner) = fill_region(&directed, &free, pos, min_angle_deg)?;
        if round == rounds {
            return Ok((tris, steiner, peeled.len()));
        }
        round += 1;
        let at = |g: u32| {
            if (g as usize) < pos.len() {
                pos[g as usize]
            } else {
                steiner[g as usize - pos.len()]
            }
        };
        // (the cosines clear nearly every triangle; the angle decides the others)
        let bad = |a, b, c| {
            !limit.triangle_below(a, b, c)
                && crate::quality::max_triangle_angle_deg(a, b, c) >= max_angle_deg
        };
        let bad_nodes: Vec<u32> = tris
            .iter()
            .filter(|t| bad(at(t[0]), at(t[1]), at(t[2])))
            .flat_map(|t| t.iter().copied().filter(|&g| (g as usize) < pos.len()))
            .collect();
        if bad_nodes.is_empty() {
            return Ok((tris, steiner, peeled.len()));
        }
        let before = peeled.len();
        for ci in peelable.touching(&bad_nodes) {
            let c = &mut cells[ci as usize];
            if c.len == 0 {
                continue;
            }
            peeled.push(ci);
            c.len = 0;
        }
        if peeled.len() == before {
            return Ok((tris, steiner, peeled.len()));
        }
        region.peel(cells, &peeled[before..]);
    }
}

/// The cells a peel round may take (alive at the start, above the first layer, edge ratio at
/// most [`PEEL_MAX_EDGE_RATIO`]), by corner node: a round looks only at the cells around the
/// nodes of its bad triangles instead of every cell.
struct Peelable {
    /// `cells[start[g]..start[g + 1]]` are the peelable cells with corner `g`, increasing.
    start: Vec<u32>,
    cells: Vec<u32>,
}

impl Peelable {
    fn new(cells: &[Cell], pos: &[P2]) -> Self {
        let ok = |c: &Cell| c.len > 0 && c.layer != 0 && edge_ratio(c, pos) <= PEEL_MAX_EDGE_RATIO;
        let mut start = vec![0u32; pos.len() + 1];
        for c in cells.iter().filter(|c| ok(c)) {
            for &g in c.corners() {
                start[g as usize + 1] += 1;
            }
        }
        for g in 0..pos.len() {
            start[g + 1] += start[g];
        }
        let mut fill = start.clone();
        let mut of_node = vec![0u32; start[pos.len()] as usize];
        for (ci, c) in cells.iter().enumerate().filter(|(_, c)| ok(c)) {
            for &g in c.corners() {
                of_node[fill[g as usize] as usize] = ci as u32;
                fill[g as usize] += 1;
            }
        }
        Peelable {
            start,
            cells: of_node,
        }
    }

    /// The peelable cells with a corner among `nodes`, increasing, once each.
    fn touching(&self, nodes: &[u32]) -> Vec<u32> {
        let mut found: Vec<u32> = Vec::new();
        for &g in nodes {
            let g = g as usize;
            found.extend(&self.cells[self.start[g] as usize..self.start[g + 1] as usize]);
        }
        found.sort_unstable();
        found.dedup();
        found
    }
}

/// The boundary of the region left to the fill, kept up to date as cells are peeled: the
/// edges of the cells alive at the start are counted once (by `mesh_model::topology`), then
/// each peel round only updates the counts of the peeled cells' edges and corners, instead of
/// counting the edges of every layered cell again.
struct Region {
    /// The cells alive at the start, by index; their position in this list is their index in
    /// `edges`.
    live: Vec<u32>,
    /// Position in `live` of each cell (`NONE` for a cell not alive at the start).
    position: Vec<u32>,
    /// The edges of the cells in `live`, with the boundary facets on theirs.
    edges: Edges,
    /// Whether each cell of `live` is still alive (not peeled).
    alive: Vec<bool>,
    /// Cells still alive on each edge.
    edge_uses: Vec<u32>,
    /// Cells still alive with each node as a corner.
    node_uses: Vec<u32>,
    /// The cell edges on the region's boundary (alive in one cell, no facet on it), as
    /// (position in `live`, local edge), sorted.
    open: Vec<(u32, u32)>,
    /// The edge of each boundary facet (`NONE` when no cell has it).
    facet_edge: Vec<u32>,
    /// The boundary facets, domain on their left.
    facets: Vec<(u32, u32)>,
}

impl Region {
    fn new(cells: &[Cell], facets: &[(u32, u32)], n_nodes: usize) -> Self {
        let facet_nodes: Vec<[u32; 2]> = facets.iter().map(|&(a, b)| [a, b]).collect();
        let live: Vec<u32> = (0..cells.len() as u32)
            .filter(|&c| cells[c as usize].len > 0)
            .collect();
        let mut position = vec![NONE; cells.len()];
        for (i, &c) in live.iter().enumerate() {
            position[c as usize] = i as u32;
        }
        let shape = |c: &Cell| if c.len == 3 { Shape::Tri } else { Shape::Quad };
        let edges = Edges::build(
            live.iter().map(|&c| {
                let c = &cells[c as usize];
                (shape(c), c.corners())
            }),
            facet_nodes.iter().map(|f| &f[..]),
        );
        let edge_uses: Vec<u32> = (0..edges.len() as u32)
            .map(|e| edges.cells(e).len() as u32)
            .collect();
        let mut node_uses = vec![0u32; n_nodes];
        let mut open = Vec::new();
        for (i, &c) in live.iter().enumerate() {
            for &g in cells[c as usize].corners() {
                node_uses[g as usize] += 1;
            }
            for (j, &e) in edges.of_cell(i).iter().enumerate() {
                if edge_uses[e as usize] == 1 && !edges.is_boundary(e) {
                    open.push((i as u32, j as u32));
                }
            }
        }
        let facet_edge = facets
            .iter()
            .map(|&(a, b)| edges.find(&[a, b]).unwrap_or(NONE))
            .collect();
        Region {
            alive: vec![true; live.len()],
            live,
            position,
            edges,
            edge_uses,
            node_uses,
            open,
            facet_edge,
            facets: facets.to_vec(),
        }
    }

    /// The region's boundary as directed edges with the region on their left: the open cell
    /// edges reversed, in cell order, then the facets no alive cell stands on.
    fn directed(&self, cells: &[Cell]) -> Vec<(u32, u32)> {
        let mut directed: Vec<(u32, u32)> = self
            .open
            .iter()
            .map(|&(i, j)| {
                let k = cells[self.live[i as usize] as usize].corners();
                let j = j as usize;
                (k[(j + 1) % k.len()], k[j])
            })
            .collect();
        directed.extend(
            self.facets
                .iter()
                .zip(&self.facet_edge)
                .filter(|&(_, &e)| e == NONE || self.edge_uses[e as usize] == 0)
                .map(|(&f, _)| f),
        );
        directed
    }

    /// Takes the cells `peeled` (alive until now, their `len` already 0) out of the region's
    /// walls: the edges they shared with alive cells open.
    fn peel(&mut self, cells: &[Cell], peeled: &[u32]) {
        let mut touched = Vec::new();
        for &c in peeled {
            let i = self.position[c as usize] as usize;
            self.alive[i] = false;
            let of_cell = self.edges.of_cell(i);
            for &g in &cells[c as usize].nodes[..of_cell.len()] {
                self.node_uses[g as usize] -= 1;
            }
            for &e in of_cell {
                self.edge_uses[e as usize] -= 1;
                touched.push(e);
            }
        }
        let alive = &self.alive;
        self.open.retain(|&(i, _)| alive[i as usize]);
        for e in touched {
            if self.edge_uses[e as usize] != 1 || self.edges.is_boundary(e) {
                continue;
            }
            let open = self
                .edges
                .cells(e)
                .iter()
                .filter(|u| alive[u.cell as usize]);
            self.open.extend(open.map(|u| (u.cell, u32::from(u.local))));
        }
        self.open.sort_unstable();
        self.open.dedup();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// The edge owners by the parallel sort on (edge, position) are those of a stable sort by
    /// edge, where a directed edge met twice keeps its last triangle.
    #[test]
    fn the_edge_owners_are_those_of_a_stable_sort() {
        let mut rng = testkit::layered::Rng(5);
        let mut node = || rng.below(40) as u32;
        // random triangles over few nodes: many directed edges are met twice or more
        let tris: Vec<[u32; 3]> = (0..3000).map(|_| [node(), node(), node()]).collect();
        let mut owner: Vec<((u32, u32), (usize, usize))> = tris
            .iter()
            .enumerate()
            .flat_map(|(t, tri)| {
                (0..3).map(move |i| ((tri[i], tri[(i + 1) % 3]), (t, (i + 2) % 3)))
            })
            .collect();
        owner.sort_by_key(|&(k, _)| k);
        let mut kept: Vec<((u32, u32), (usize, usize))> = Vec::new();
        for o in owner {
            match kept.last_mut() {
                Some(last) if last.0 == o.0 => *last = o,
                _ => kept.push(o),
            }
        }
        let owners = Owners::new(&tris);
        assert!(!owners.unique);
        assert_eq!(owners.by_edge, kept);
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
        let mut region = Region::new(&cells, &facets, (n * n) as usize);
        assert_eq!(
            region.directed(&cells),
            directed_from_scratch(&cells, &facets)
        );
        let mut seed = 12345u64;
        for _round in 0..6 {
            let mut peeled = Vec::new();
            for (ci, c) in cells.iter_mut().enumerate() {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                if c.len > 0 && (seed >> 33) % 5 == 1 {
                    c.len = 0;
                    peeled.push(ci as u32);
                }
            }
            region.peel(&cells, &peeled);
            assert_eq!(
                region.directed(&cells),
                directed_from_scratch(&cells, &facets)
            );
            for g in 0..n * n {
                let used = cells.iter().any(|c| c.corners().contains(&g));
                assert_eq!(region.node_uses[g as usize] > 0, used, "node {g}");
            }
        }
        assert!(
            cells.iter().any(|c| c.len > 0),
            "some cells are left to test"
        );
    }
}
