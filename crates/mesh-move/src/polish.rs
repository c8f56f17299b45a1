//! The local polish of the spring mover's filled region, after the fill: node by node
//! pattern searches over the free corners of the cells the fill spoiled most. Two passes:
//! first the worst cells by the ratio of scaled Jacobians (moved over original), then the
//! cells opened past [`ANGLE_ABOVE`] (the largest angle of a triangle, or of a quad cut on its
//! shorter diagonal) further than they were. Neither makes a node's worst ratio fall below
//! the mesh's worst after the first, so nothing inverts, and a rigid motion stays exact.
//! The polish is a choice per node, so its result is not a smooth function of the boundary;
//! the smooth mover skips it.

use mesh_model::measure::corners_max_angle_deg;

use crate::quality::scaled_jacobian;

/// Ratios under this are polished; above it a cell counts as kept.
const POLISH_BELOW: f64 = 0.99;

/// A cell's largest angle (degrees) above this and above its original is relieved: the
/// dissertation's bound is 150°, and a margin keeps the curving's small changes below it.
const ANGLE_ABOVE: f64 = 125.0;

/// The cells of the filled region around each free node, their original scaled Jacobians and
/// largest angles.
struct Local<'a> {
    cells: &'a [Vec<u32>],
    node_cells: Vec<Vec<usize>>,
    before: Vec<f64>,
    /// Per cell, the angle above which it is relieved: max(ANGLE_ABOVE, its original).
    angle_limit: Vec<f64>,
}

impl<'a> Local<'a> {
    fn new(old: &[[f64; 2]], cells: &'a [Vec<u32>], free: &[bool]) -> Local<'a> {
        let mut node_cells: Vec<Vec<usize>> = vec![Vec::new(); old.len()];
        for (c, k) in cells.iter().enumerate() {
            for &n in k.iter().filter(|&&n| free[n as usize]) {
                node_cells[n as usize].push(c);
            }
        }
        let mut local = Local {
            cells,
            node_cells,
            before: Vec::new(),
            angle_limit: Vec::new(),
        };
        local.before = (0..cells.len()).map(|c| local.sj(old, c)).collect();
        local.angle_limit = (0..cells.len())
            .map(|c| local.angle(old, c).max(ANGLE_ABOVE))
            .collect();
        local
    }

    fn corners(&self, x: &[[f64; 2]], c: usize) -> ([[f64; 2]; 4], usize) {
        let mut p = [[0.0; 2]; 4];
        for (q, &n) in p.iter_mut().zip(&self.cells[c]) {
            *q = x[n as usize];
        }
        (p, self.cells[c].len().min(4))
    }

    fn sj(&self, x: &[[f64; 2]], c: usize) -> f64 {
        let (p, n) = self.corners(x, c);
        scaled_jacobian(&p[..n])
    }

    fn angle(&self, x: &[[f64; 2]], c: usize) -> f64 {
        let (p, n) = self.corners(x, c);
        corners_max_angle_deg(&p[..n])
    }

    fn ratio(&self, x: &[[f64; 2]], c: usize) -> f64 {
        let b = self.before[c];
        if b > 0.0 { self.sj(x, c) / b } else { 1.0 }
    }

    /// How far cell `c` is opened past its limit (0 when not).
    fn excess(&self, x: &[[f64; 2]], c: usize) -> f64 {
        (self.angle(x, c) - self.angle_limit[c]).max(0.0)
    }

    fn worst_ratio_at(&self, x: &[[f64; 2]], n: u32) -> f64 {
        self.node_cells[n as usize]
            .iter()
            .map(|&c| self.ratio(x, c))
            .fold(f64::INFINITY, f64::min)
    }

    fn worst_excess_at(&self, x: &[[f64; 2]], n: u32) -> f64 {
        self.node_cells[n as usize]
            .iter()
            .map(|&c| self.excess(x, c))
            .fold(0.0, f64::max)
    }

    /// Node `n` tried at eight directions and four step lengths (0.3 to 0.01 of its shortest
    /// edge), moved to the place of the highest `score` if that beats its own by 1e-9
    /// (`score` None: not allowed). True if it moved.
    fn search(
        &self,
        x: &mut [[f64; 2]],
        n: u32,
        score: impl Fn(&[[f64; 2]]) -> Option<f64>,
    ) -> bool {
        let start = x[n as usize];
        let Some(own) = score(x) else {
            return false;
        };
        let mut best = (own, start);
        let shortest = self.node_cells[n as usize]
            .iter()
            .flat_map(|&c| self.cells[c].iter())
            .filter(|&&m| m != n)
            .map(|&m| {
                let q = x[m as usize];
                (q[0] - start[0]).hypot(q[1] - start[1])
            })
            .fold(f64::INFINITY, f64::min);
        for step in [0.3, 0.1, 0.03, 0.01].map(|f| f * shortest) {
            for d in 0..8 {
                let a = d as f64 * std::f64::consts::FRAC_PI_4;
                x[n as usize] = [start[0] + step * a.cos(), start[1] + step * a.sin()];
                match score(x) {
                    Some(q) if q > best.0 + 1e-9 => best = (q, x[n as usize]),
                    _ => {}
                }
            }
        }
        x[n as usize] = best.1;
        best.1 != start
    }

    /// The free corners of the cells picked by `pick`, sorted.
    fn corners_of(&self, free: &[bool], pick: impl Fn(usize) -> bool) -> Vec<u32> {
        let mut nodes: Vec<u32> = (0..self.cells.len())
            .filter(|&c| pick(c))
            .flat_map(|c| self.cells[c].iter().copied())
            .filter(|&n| free[n as usize])
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

/// The polish of the filled region `cells` (free nodes `free` may move) from `old` to `x`:
/// up to `passes` passes of each kind. Returns the node moves made.
pub(crate) fn polish(
    old: &[[f64; 2]],
    x: &mut [[f64; 2]],
    cells: &[Vec<u32>],
    free: &[bool],
    passes: usize,
) -> usize {
    let local = Local::new(old, cells, free);
    worst_cells(&local, x, free, passes) + open_angles(&local, x, free, passes)
}

/// Passes over the free corners of the worst cells (ratio within 0.05 of the worst), each
/// moved to the best place for the smallest ratio of its cells. Cells at 0.99 or above are
/// left as they are.
fn worst_cells(local: &Local, x: &mut [[f64; 2]], free: &[bool], passes: usize) -> usize {
    let mut moves = 0;
    for _ in 0..passes {
        let ratios: Vec<f64> = (0..local.cells.len()).map(|c| local.ratio(x, c)).collect();
        let worst = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        if worst >= POLISH_BELOW {
            break;
        }
        let limit = (worst + 0.05).min(POLISH_BELOW);
        let mut moved = 0;
        for n in local.corners_of(free, |c| ratios[c] < limit) {
            moved += usize::from(local.search(x, n, |x| Some(local.worst_ratio_at(x, n))));
        }
        moves += moved;
        if moved == 0 {
            break;
        }
    }
    moves
}

/// Passes over the free corners of the cells opened past their angle limit, each moved to
/// lessen the largest excess of its cells while its worst ratio stays at or above both the
/// mesh's worst and its own.
fn open_angles(local: &Local, x: &mut [[f64; 2]], free: &[bool], passes: usize) -> usize {
    let worst = (0..local.cells.len())
        .map(|c| local.ratio(x, c))
        .fold(f64::INFINITY, f64::min);
    let mut moves = 0;
    for _ in 0..passes {
        let nodes = local.corners_of(free, |c| local.excess(x, c) > 0.0);
        let mut moved = 0;
        for n in nodes {
            let floor = worst.min(local.worst_ratio_at(x, n));
            let score = |x: &[[f64; 2]]| {
                let r = local.worst_ratio_at(x, n);
                (r >= floor && r > 0.0).then(|| -local.worst_excess_at(x, n))
            };
            moved += usize::from(local.search(x, n, score));
        }
        moves += moved;
        if moved == 0 {
            break;
        }
    }
    moves
}
