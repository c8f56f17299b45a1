//! The worst tetrahedra of a cut mesh mended by moving nodes: what no cut can mend. Where
//! columns stop early (issue 47) the step down to them is closed by pyramids and tetrahedra
//! over front facets that lean steeply, and where two fronts face each other across a gap the
//! fill's tetrahedra join points of both; a cell whose own shape is flat cuts badly whatever
//! its apex and diagonals. Moving one of its nodes a fraction of an edge mends it.
//!
//! Two passes of up to [`SWEEPS`] sweeps: the tetrahedra over [`BAR_DEG`] first, then those
//! over the target. Each sweep visits the free nodes of the bad tetrahedra, worst tetrahedron
//! first, and moves each by a compass search (± each axis, from a quarter of its shortest
//! edge, halving [`HALVINGS`] times, never farther than half that edge from where it
//! started) to lower the largest dihedral angle of the tetrahedra around it. A move is kept
//! only when it lowers that angle (or keeps it and lowers the tetrahedra's summed excess over
//! the target with no more of them over it: a node between two bad tetrahedra mends one
//! while another node mends the other), every cell around stays positive (each corner's
//! tetrahedron by the exact `orient3d`), the prisms and hexahedra around keep their
//! smallest corner scaled Jacobian at [`SJ_FLOOR`] or at what it was, if lower, and the node
//! stays at least half the shorter of its own and each neighbour's shortest edge (in the mesh
//! as it came) from that neighbour: a needle's largest dihedral angle is small, so the angles
//! alone let two nodes close in on each other, sweep after sweep, until they met. Each node
//! has its [`Freedom`]: the caller fixes some (a wall, a far field) and lets others slide only
//! across an edge (the first layer's nodes across their extrusion edges, so that the first
//! layer keeps its height, leaning at most [`MAX_LEAN_DEG`]); a mesh without a tetrahedron
//! over the target is left to the bit.

use geom_predicates::vector::{cross3, dist, dot};
use mesh_model::measure3d::min_corner_scaled_jacobian;
use mesh_model::{Mesh, Shape};

use crate::cone::Piece;
use crate::improve::piece_quality;

/// The bar (degrees) over which a tetrahedron is mended first, and may be mended at the cost
/// of pushing others over the target (by [`BAR_GAIN_DEG`] at least): the issues' bar on
/// every tetrahedron.
pub const BAR_DEG: f64 = 160.0;

/// How much (degrees) a move that pushes more tetrahedra over the target must lower a worst
/// angle over [`BAR_DEG`]: near-flat tetrahedra that no move mends (fronts 0.005 apart
/// across a gap, facets 0.08 long) otherwise trade hundredths of a degree for neighbours
/// pushed over (on the extruded 30P30N at its default span stations, 1 644 over 160° left
/// against 550).
const BAR_GAIN_DEG: f64 = 2.0;

/// How many times the compass step halves.
const HALVINGS: usize = 5;

/// How many sweeps over the tetrahedra still over the target.
const SWEEPS: usize = 8;

/// A move may lower the smallest corner scaled Jacobian of the prisms and hexahedra around
/// a node to this, or to its value before the move if that is lower: the bar for a
/// wing's prisms.
pub const SJ_FLOOR: f64 = 0.2;

/// How far a node sliding across an edge may lean it (degrees).
pub const MAX_LEAN_DEG: f64 = 15.0;

/// How a node may move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Freedom {
    /// Anywhere (within half its shortest edge).
    Free,
    /// Not at all.
    Fixed,
    /// Only across this edge vector (from the edge's other end to the node), leaning it at
    /// most [`MAX_LEAN_DEG`].
    Across([f64; 3]),
}

/// What the smoothing did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Smoothed {
    /// The nodes moved (a node moved in several sweeps counts once a sweep).
    pub moves: usize,
    /// The largest dihedral angle of the tetrahedra before and after, degrees.
    pub before_deg: f64,
    /// See `before_deg`.
    pub after_deg: f64,
    /// The tetrahedra over the target before and after.
    pub over_before: usize,
    /// See `over_before`.
    pub over_after: usize,
}

/// The cells around some nodes (compressed rows): only the nodes a sweep visits, so that a
/// mesh of millions of cells pays for the few hundred nodes it moves.
struct Stars {
    /// Each node's row, `u32::MAX` for the nodes left out.
    row: Vec<u32>,
    start: Vec<u32>,
    cells: Vec<u32>,
}

impl Stars {
    /// The stars of `nodes` (distinct) in `mesh`.
    fn of_nodes(mesh: &Mesh, nodes: &[u32]) -> Stars {
        let mut row = vec![u32::MAX; mesh.nodes.len()];
        for (r, &v) in nodes.iter().enumerate() {
            row[v as usize] = r as u32;
        }
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (i, c) in mesh.cells.iter().enumerate() {
            for &v in c.corners() {
                if row[v as usize] != u32::MAX {
                    pairs.push((row[v as usize], i as u32));
                }
            }
        }
        pairs.sort_unstable();
        let mut start = vec![0u32; nodes.len() + 1];
        pairs.iter().for_each(|&(r, _)| start[r as usize + 1] += 1);
        for r in 0..nodes.len() {
            start[r + 1] += start[r];
        }
        Stars {
            row,
            start,
            cells: pairs.into_iter().map(|(_, c)| c).collect(),
        }
    }

    fn of(&self, v: u32) -> &[u32] {
        let r = self.row[v as usize] as usize;
        &self.cells[self.start[r] as usize..self.start[r + 1] as usize]
    }
}

/// The largest dihedral angle of `mesh`'s tetrahedra and those over `target` (with their
/// angles).
fn scan(mesh: &Mesh, target: f64) -> (f64, Vec<(f64, usize)>) {
    let mut worst = 0.0f64;
    let mut bad = Vec::new();
    for i in 0..mesh.cells.len() {
        if mesh.cells.get(i).ty.shape == Shape::Tet {
            let q = cell_quality(mesh, i);
            worst = worst.max(q);
            if q > target {
                bad.push((q, i));
            }
        }
    }
    (worst, bad)
}

/// Each node's shortest edge (over the edges of the cells around it; infinite for a node in
/// no cell).
fn shortest_edges(mesh: &Mesh) -> Vec<f64> {
    let mut scale = vec![f64::INFINITY; mesh.nodes.len()];
    for c in mesh.cells.iter() {
        let k = c.corners();
        for [i, j] in c.ty.shape.edges() {
            let (a, b) = (k[*i] as usize, k[*j] as usize);
            let d = dist(mesh.nodes[a], mesh.nodes[b]);
            scale[a] = scale[a].min(d);
            scale[b] = scale[b].min(d);
        }
    }
    scale
}

/// Lowers the largest dihedral angle of `mesh`'s linear tetrahedra over `target_deg` by
/// moving its nodes as `freedom` lets them (see the module's doc).
pub fn smooth_worst_tets(mesh: &mut Mesh, freedom: &[Freedom], target_deg: f64) -> Smoothed {
    let (before, bad) = scan(mesh, target_deg);
    let mut out = Smoothed {
        before_deg: before,
        after_deg: before,
        over_before: bad.len(),
        over_after: bad.len(),
        moves: 0,
    };
    if bad.is_empty() {
        return out;
    }
    let scale = shortest_edges(mesh);
    let freedom = (freedom, scale.as_slice());
    // those over the bar first, each move free to push others over the target; then those
    // over the target, no move pushing more over it (see `Star::better`)
    if target_deg < BAR_DEG {
        let over_bar = bad.iter().copied().filter(|b| b.0 > BAR_DEG).collect();
        out.moves += sweeps(mesh, freedom, BAR_DEG, over_bar);
        let (_, bad) = scan(mesh, target_deg);
        out.moves += sweeps(mesh, freedom, target_deg, bad);
    } else {
        out.moves += sweeps(mesh, freedom, target_deg, bad);
    }
    let (after, bad) = scan(mesh, target_deg);
    (out.after_deg, out.over_after) = (after, bad.len());
    out
}

/// Up to [`SWEEPS`] sweeps over the tetrahedra over `target` (`bad`, with their angles);
/// the node moves made.
fn sweeps(
    mesh: &mut Mesh,
    (freedom, scale): (&[Freedom], &[f64]),
    target: f64,
    mut bad: Vec<(f64, usize)>,
) -> usize {
    let mut moves = 0;
    for _ in 0..SWEEPS {
        if bad.is_empty() {
            break;
        }
        // the movable nodes of the bad tetrahedra, worst tetrahedron first
        bad.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut seen = vec![false; mesh.nodes.len()];
        let mut nodes = Vec::new();
        for &(_, i) in &bad {
            for &v in mesh.cells.get(i).corners() {
                if freedom[v as usize] != Freedom::Fixed && !seen[v as usize] {
                    seen[v as usize] = true;
                    nodes.push(v);
                }
            }
        }
        let stars = Stars::of_nodes(mesh, &nodes);
        let mut moved = Vec::new();
        for &v in &nodes {
            if move_node(mesh, (stars.of(v), v, freedom[v as usize]), target, scale) {
                moved.push(v);
            }
        }
        moves += moved.len();
        if moved.is_empty() {
            break;
        }
        // the bad tetrahedra now: the old ones and any around a moved node
        let mut now: Vec<usize> = bad.iter().map(|b| b.1).collect();
        for &v in &moved {
            now.extend(stars.of(v).iter().map(|&c| c as usize));
        }
        now.sort_unstable();
        now.dedup();
        bad = now
            .into_iter()
            .filter(|&i| mesh.cells.get(i).ty.shape == Shape::Tet)
            .map(|i| (cell_quality(mesh, i), i))
            .filter(|b| b.0 > target)
            .collect();
    }
    moves
}

/// The largest dihedral angle of cell `i` if a tetrahedron, 0 for another positive cell,
/// `improve::INVERTED` for a cell with a corner that is not positive (`piece_quality`).
fn cell_quality(mesh: &Mesh, i: usize) -> f64 {
    let c = mesh.cells.get(i);
    let mut k = [0u32; 8];
    k[..c.corners().len()].copy_from_slice(c.corners());
    let piece: Piece = (c.ty.shape, k);
    piece_quality(&mesh.nodes, &piece)
}

/// The quality of the cells `star` around a node, for a target of `target` degrees: the
/// largest [`cell_quality`] (a cell that is not positive puts it out of reach of any move),
/// the tetrahedra's excess over the target summed (so that a move may mend one of several bad
/// tetrahedra around the node) and how many are over it, and the smallest corner scaled
/// Jacobian of its prisms and hexahedra.
fn star_quality(mesh: &Mesh, star: &[u32], target: f64) -> (Star, f64) {
    let mut worst = 0.0f64;
    let mut excess = 0.0;
    let mut over = 0;
    let mut sj = 1.0f64;
    for &c in star {
        let c = c as usize;
        let q = cell_quality(mesh, c);
        worst = worst.max(q);
        excess += (q - target).max(0.0);
        over += usize::from(q > target);
        if let Some(s) = min_corner_scaled_jacobian(mesh, c) {
            sj = sj.min(s);
        }
    }
    (
        Star {
            worst,
            excess,
            over,
        },
        sj,
    )
}

/// The tetrahedra around a node: their largest dihedral angle, their summed excess over the
/// target and how many are over it.
#[derive(Debug, Clone, Copy)]
struct Star {
    worst: f64,
    excess: f64,
    over: usize,
}

impl Star {
    /// Whether `self` is better than `than`: a lower worst angle with no more tetrahedra
    /// over the target (any number where the worst was over [`BAR_DEG`] and falls by
    /// [`BAR_GAIN_DEG`]), or the same worst
    /// angle and a lower excess with no more over the target. Else lowering a tetrahedron
    /// just over the target pushes others over it: the step's tetrahedral cut went from 112
    /// over 150° to 183.
    fn better(&self, than: &Star) -> bool {
        let no_more = self.over <= than.over;
        (self.worst < than.worst - 1e-9
            && (no_more || (than.worst > BAR_DEG && self.worst < than.worst - BAR_GAIN_DEG)))
            || (self.worst <= than.worst && no_more && self.excess < than.excess - 1e-9)
    }
}

/// The compass search of node `v` (moving as `freedom` lets it) over the cells `star`
/// around it; whether it moved.
fn move_node(
    mesh: &mut Mesh,
    (star, v, freedom): (&[u32], u32, Freedom),
    target: f64,
    scale: &[f64],
) -> bool {
    if freedom == Freedom::Fixed {
        return false;
    }
    let start = mesh.nodes[v as usize];
    // the nodes around, each kept at least half the shorter of its and `v`'s original
    // shortest edge away: the angles alone would let two nodes close in on each other
    // (a needle's largest dihedral angle is small) until they meet
    let mut near: Vec<(u32, f64)> = star
        .iter()
        .flat_map(|&c| mesh.cells.get(c as usize).corners())
        .filter(|&&w| w != v)
        .map(|&w| (w, 0.5 * scale[v as usize].min(scale[w as usize])))
        .collect();
    near.sort_unstable_by_key(|n| n.0);
    near.dedup_by_key(|n| n.0);
    let apart = |mesh: &Mesh, p: [f64; 3]| {
        near.iter()
            .all(|&(w, floor)| dist(p, mesh.nodes[w as usize]) >= floor)
    };
    let shortest = near
        .iter()
        .map(|&(w, _)| dist(start, mesh.nodes[w as usize]))
        .fold(f64::INFINITY, f64::min);
    if !(shortest.is_finite() && shortest > 0.0) {
        return false;
    }
    let (moves, reach) = match freedom {
        Freedom::Fixed => return false,
        Freedom::Free => (
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].to_vec(),
            0.5 * shortest,
        ),
        Freedom::Across(e) => {
            let len = dot(e, e).sqrt();
            if len.is_nan() || len <= 0.0 {
                return false;
            }
            let lean = len * MAX_LEAN_DEG.to_radians().tan();
            (across(e).to_vec(), lean.min(0.5 * shortest))
        }
    };
    let (mut best, sj_before) = star_quality(mesh, star, target);
    let floor = sj_before.min(SJ_FLOOR);
    let mut at = start;
    let mut step = 0.25 * shortest;
    for _ in 0..HALVINGS {
        let mut improved = true;
        while improved {
            improved = false;
            for m in &moves {
                for sign in [1.0, -1.0] {
                    let p = std::array::from_fn(|d| at[d] + sign * step * m[d]);
                    if dist(p, start) > reach || !apart(mesh, p) {
                        continue;
                    }
                    mesh.nodes[v as usize] = p;
                    let (q, sj) = star_quality(mesh, star, target);
                    if q.better(&best) && sj >= floor {
                        best = q;
                        at = p;
                        improved = true;
                    }
                }
            }
        }
        step *= 0.5;
    }
    mesh.nodes[v as usize] = at;
    at != start
}

/// Two unit vectors across `e` (non-zero), square to it and to each other.
fn across(e: [f64; 3]) -> [[f64; 3]; 2] {
    let unit = |v: [f64; 3]| {
        let l = dot(v, v).sqrt();
        v.map(|x| x / l)
    };
    let e = unit(e);
    let other = if e[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t1 = unit(cross3(e, other));
    [t1, cross3(e, t1)]
}
