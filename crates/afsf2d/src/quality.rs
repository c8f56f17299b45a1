//! Triangles on demand and the obtuse-angle quality figure of the dissertation (Tables 1, 3,
//! 4): cut each quad along its shorter diagonal, then count triangles by their largest angle.
//! It owns these two functions on a linear 2D [`Mesh`], and the mesher's test of a triangle
//! against a largest-angle limit by cosines ([`AngleLimit`]).

use mesh_model::measure::split_quad_shorter_diagonal;
use mesh_model::{CellType, Mesh, Shape};

use crate::geom::P2;

/// Lower bounds (degrees) of the histogram bins: `[95, 105)`, `[105, 115)`, `[115, 125)`,
/// `[125, 135)`, `[135, 180]`.
pub const ANGLE_BINS_DEG: [f64; 5] = [95.0, 105.0, 115.0, 125.0, 135.0];

/// Largest-angle figures of the triangles of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AngleStats {
    /// Number of triangles (after cutting quads).
    pub triangles: usize,
    /// Largest angle of any triangle (degrees).
    pub max_angle_deg: f64,
    /// Triangles whose largest angle lies in each bin of [`ANGLE_BINS_DEG`].
    pub histogram: [usize; 5],
}

/// The same mesh with every linear quad cut into two triangles along its shorter diagonal;
/// both triangles keep the quad's layer and pipe. Nodes, facets and patches are unchanged.
pub fn cut_quads_shorter_diagonal(mesh: &Mesh) -> Mesh {
    let mut out = Mesh {
        cells: mesh_model::Cells::with_capacity(mesh.cells.len() * 2, 3),
        cell_layer: Vec::with_capacity(mesh.cell_layer.len() * 2),
        cell_pipe: Vec::with_capacity(mesh.cell_pipe.len() * 2),
        ..mesh.clone()
    };
    let tri = CellType::new(Shape::Tri, 1);
    for (i, c) in mesh.cells.iter().enumerate() {
        let pieces: Vec<[u32; 3]> = if c.ty == CellType::new(Shape::Quad, 1) {
            split_quad_shorter_diagonal(mesh, c.corners()).to_vec()
        } else {
            out.cells.push(c.ty, c.nodes);
            if let Some(&l) = mesh.cell_layer.get(i) {
                out.cell_layer.push(l);
            }
            if let Some(&p) = mesh.cell_pipe.get(i) {
                out.cell_pipe.push(p);
            }
            continue;
        };
        for t in pieces {
            out.cells.push(tri, &t);
            if let Some(&l) = mesh.cell_layer.get(i) {
                out.cell_layer.push(l);
            }
            if let Some(&p) = mesh.cell_pipe.get(i) {
                out.cell_pipe.push(p);
            }
        }
    }
    out
}

pub use mesh_model::measure::triangle_max_angle_deg as max_triangle_angle_deg;

/// A largest-angle limit, with its cosine, for [`AngleLimit::triangle_below`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct AngleLimit {
    deg: f64,
    cos: f64,
}

/// How far from the limit's cosine a corner's cosine must lie for the comparison of cosines to
/// decide: far above the rounding of either way of measuring the angle (~1e-15).
const COS_MARGIN: f64 = 1e-12;

impl AngleLimit {
    pub(crate) fn new(deg: f64) -> Self {
        AngleLimit {
            deg,
            cos: deg.to_radians().cos(),
        }
    }

    /// Exactly `max_triangle_angle_deg(a, b, c) < limit`, decided from the corners' cosines
    /// (no `atan2`) unless a corner lies within a hair of the limit or a side has no length,
    /// where the angles themselves decide.
    pub(crate) fn triangle_below(&self, a: P2, b: P2, c: P2) -> bool {
        let corners = [a, b, c];
        // each side's length once (a side's square is the same bits either way round); the
        // side from corner i to i + 1 is `side[i]`, the third measured only at corner 1
        let length = |p: P2, q: P2| {
            let u = [q[0] - p[0], q[1] - p[1]];
            (u[0] * u[0] + u[1] * u[1]).sqrt()
        };
        let mut side = [length(a, b), f64::NAN, length(c, a)];
        let mut all_below = true;
        for i in 0..3 {
            let (p, q, r) = (corners[i], corners[(i + 1) % 3], corners[(i + 2) % 3]);
            if i == 1 {
                side[1] = length(b, c);
            }
            let u = [q[0] - p[0], q[1] - p[1]];
            let v = [r[0] - p[0], r[1] - p[1]];
            // |u| |v|: the sides from p to q and from r to p
            let cos = (u[0] * v[0] + u[1] * v[1]) / (side[i] * side[(i + 2) % 3]);
            if cos < self.cos - COS_MARGIN {
                return false; // this corner's angle is above the limit
            }
            // NaN (a side without length) is not above the limit's cosine either
            all_below &= cos > self.cos + COS_MARGIN;
        }
        all_below || max_triangle_angle_deg(a, b, c) < self.deg
    }
}

/// Counts the triangles of the linear mesh under `mesh` by largest angle: the corners of every
/// cell, whatever its order, with quads cut along their shorter diagonal. So the figure of one
/// linear mesh is the same whether it is read at order 1, 2 or 3, cut or not.
///
/// Each triangle is binned by the cosine of its largest angle against the bins' cosines
/// (no `atan2`); one within a hair of a bin's edge, or whose sides are too short, too long or
/// not finite to square, is measured by [`max_triangle_angle_deg`] instead. The largest angle
/// is measured only for the triangles whose cosine comes within that hair of the least seen
/// so far (a superset of the worst ones), so the figures are those of measuring every
/// triangle, to the last bit. The cells are counted in parallel (rayon); sums and maxima do
/// not depend on how the work is split.
pub fn max_angle_histogram(mesh: &Mesh) -> AngleStats {
    use rayon::prelude::*;
    (0..mesh.cells.len())
        .into_par_iter()
        .with_min_len(1 << 12)
        .fold(Tally::default, |mut tally, i| {
            let c = mesh.cells.get(i);
            let k = c.corners();
            let mut count = |t: [u32; 3]| tally.add(mesh.xy(t[0]), mesh.xy(t[1]), mesh.xy(t[2]));
            match c.ty.shape {
                Shape::Tri => count([k[0], k[1], k[2]]),
                Shape::Quad => split_quad_shorter_diagonal(mesh, k)
                    .into_iter()
                    .for_each(&mut count),
                _ => {}
            }
            tally
        })
        .reduce(Tally::default, Tally::merge)
        .stats
}

/// The cosines of the bins' lower bounds ([`ANGLE_BINS_DEG`]).
fn bin_cosines() -> [f64; 5] {
    ANGLE_BINS_DEG.map(|d| d.to_radians().cos())
}

/// The figures of part of the triangles, and the least cosine of a largest angle seen.
#[derive(Debug, Clone, Copy)]
struct Tally {
    stats: AngleStats,
    least_cos: f64,
    bins_cos: [f64; 5],
}

impl Default for Tally {
    fn default() -> Self {
        Tally {
            stats: AngleStats::default(),
            least_cos: f64::INFINITY,
            bins_cos: bin_cosines(),
        }
    }
}

impl Tally {
    fn add(&mut self, a: P2, b: P2, c: P2) {
        self.stats.triangles += 1;
        let Some(cos) = largest_angle_cos(a, b, c) else {
            let angle = max_triangle_angle_deg(a, b, c);
            self.count_angle(angle);
            return;
        };
        let near_edge = self
            .bins_cos
            .iter()
            .any(|&edge| (cos - edge).abs() <= COS_MARGIN);
        let mut angle = None;
        let mut exact = || *angle.get_or_insert_with(|| max_triangle_angle_deg(a, b, c));
        if near_edge {
            let a = exact();
            self.bin(a);
        } else if let Some(bin) = self.bins_cos.iter().rposition(|&edge| cos < edge) {
            self.stats.histogram[bin] += 1;
        }
        self.least_cos = self.least_cos.min(cos);
        if cos <= self.least_cos + COS_MARGIN {
            let a = exact();
            self.stats.max_angle_deg = self.stats.max_angle_deg.max(a);
        }
    }

    /// Counts a triangle measured by its angle.
    fn count_angle(&mut self, angle: f64) {
        self.stats.max_angle_deg = self.stats.max_angle_deg.max(angle);
        self.bin(angle);
    }

    fn bin(&mut self, angle: f64) {
        if let Some(bin) = ANGLE_BINS_DEG.iter().rposition(|&lo| angle >= lo) {
            self.stats.histogram[bin] += 1;
        }
    }

    fn merge(mut self, other: Tally) -> Tally {
        self.stats.triangles += other.stats.triangles;
        self.stats.max_angle_deg = self.stats.max_angle_deg.max(other.stats.max_angle_deg);
        for (h, o) in self.stats.histogram.iter_mut().zip(other.stats.histogram) {
            *h += o;
        }
        self.least_cos = self.least_cos.min(other.least_cos);
        self
    }
}

/// The cosine of the largest angle of triangle `a b c` (to the rounding), or `None` when a
/// side is too short, too long or not finite to square soundly. As in
/// [`max_triangle_angle_deg`], only the corners opposite a side within `SIDE_MARGIN` of the
/// longest are measured (the largest angle, at least 60°, is among them).
fn largest_angle_cos(a: P2, b: P2, c: P2) -> Option<f64> {
    const SIDE_MARGIN: f64 = 1e-6;
    let corners = [a, b, c];
    let sq = |p: P2, q: P2| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
    // the squared side opposite each corner
    let opposite = [sq(b, c), sq(c, a), sq(a, b)];
    if !opposite
        .iter()
        .all(|&s| s.is_normal() && s > 1e-200 && s < 1e200)
    {
        return None;
    }
    let longest = opposite[0].max(opposite[1]).max(opposite[2]);
    let mut least = f64::INFINITY;
    for (i, &side) in opposite.iter().enumerate() {
        if side < longest * (1.0 - SIDE_MARGIN) {
            continue;
        }
        let (p, q, r) = (corners[i], corners[(i + 1) % 3], corners[(i + 2) % 3]);
        let u = [q[0] - p[0], q[1] - p[1]];
        let v = [r[0] - p[0], r[1] - p[1]];
        let (uu, vv) = (u[0] * u[0] + u[1] * u[1], v[0] * v[0] + v[1] * v[1]);
        least = least.min((u[0] * v[0] + u[1] * v[1]) / (uu.sqrt() * vv.sqrt()));
    }
    Some(least)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::Dim;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn the_cosine_test_answers_as_the_angles_do(
            a in prop::array::uniform2(-1.0f64..1.0),
            b in prop::array::uniform2(-1.0f64..1.0),
            c in prop::array::uniform2(-1.0f64..1.0),
            limit in 60.0f64..180.0,
            scale in prop_oneof![Just(1.0), Just(1e-7), Just(1e5)],
        ) {
            let [a, b, c] = [a, b, c].map(|p| [p[0] * scale, p[1] * scale]);
            let want = max_triangle_angle_deg(a, b, c) < limit;
            prop_assert_eq!(AngleLimit::new(limit).triangle_below(a, b, c), want);
            // at its own largest angle, a hair above and below: the angles decide
            let worst = max_triangle_angle_deg(a, b, c);
            // (neighbouring doubles: `worst` is positive)
            let (up, down) = (f64::from_bits(worst.to_bits() + 1), f64::from_bits(worst.to_bits() - 1));
            for l in [worst, up, down] {
                let want = max_triangle_angle_deg(a, b, c) < l;
                prop_assert_eq!(AngleLimit::new(l).triangle_below(a, b, c), want);
            }
        }
    }

    /// The histogram as it was counted before the cosines: every triangle measured.
    fn every_triangle(mesh: &Mesh) -> AngleStats {
        let mut stats = AngleStats::default();
        let mut count = |t: [u32; 3]| {
            let a = max_triangle_angle_deg(mesh.xy(t[0]), mesh.xy(t[1]), mesh.xy(t[2]));
            stats.triangles += 1;
            stats.max_angle_deg = stats.max_angle_deg.max(a);
            if let Some(bin) = ANGLE_BINS_DEG.iter().rposition(|&lo| a >= lo) {
                stats.histogram[bin] += 1;
            }
        };
        for c in mesh.cells.iter() {
            let k = c.corners();
            match c.ty.shape {
                Shape::Tri => count([k[0], k[1], k[2]]),
                _ => split_quad_shorter_diagonal(mesh, k)
                    .into_iter()
                    .for_each(&mut count),
            }
        }
        stats
    }

    proptest! {
        #[test]
        fn the_histogram_is_that_of_measuring_every_triangle(
            points in prop::collection::vec(prop::array::uniform2(-1.0f64..1.0), 3..60),
            cells in prop::collection::vec((any::<u32>(), any::<u32>(), any::<u32>(), any::<u32>(), any::<bool>()), 1..300),
            scale in prop_oneof![Just(1.0), Just(1e-7), Just(1e5), Just(1e-170)],
            on_edge in any::<bool>(),
        ) {
            let mut m = Mesh::new(Dim::Two, 1);
            m.nodes = points.iter().map(|p| [p[0] * scale, p[1] * scale, 0.0]).collect();
            if on_edge {
                // a triangle whose largest angle is a bin's edge, to the rounding
                let a = 105f64.to_radians();
                m.nodes.extend([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [a.cos(), a.sin(), 0.0]]);
            }
            let n = m.nodes.len() as u32;
            for &(a, b, c, d, quad) in &cells {
                if quad {
                    m.cells.push(CellType::new(Shape::Quad, 1), &[a % n, b % n, c % n, d % n]);
                } else {
                    m.cells.push(CellType::new(Shape::Tri, 1), &[a % n, b % n, c % n]);
                }
            }
            if on_edge {
                m.cells.push(CellType::new(Shape::Tri, 1), &[n - 3, n - 2, n - 1]);
            }
            let (new, old) = (max_angle_histogram(&m), every_triangle(&m));
            prop_assert_eq!(new.triangles, old.triangles);
            prop_assert_eq!(new.histogram, old.histogram);
            prop_assert_eq!(new.max_angle_deg.to_bits(), old.max_angle_deg.to_bits());
        }
    }

    #[test]
    fn degenerate_triangles_are_never_below_a_limit() {
        let limit = AngleLimit::new(179.0);
        assert!(!limit.triangle_below([0.0, 0.0], [0.0, 0.0], [1.0, 0.0]));
        assert!(!limit.triangle_below([0.0, 0.0], [1.0, 0.0], [2.0, 0.0]));
        assert!(limit.triangle_below([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]));
    }

    #[test]
    fn a_skewed_quad_is_cut_on_its_shorter_diagonal_and_binned() {
        let mut m = Mesh::new(Dim::Two, 1);
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        m.cells.push(CellType::new(Shape::Quad, 1), &[0, 1, 2, 3]);
        m.cell_layer.push(4);
        m.cell_pipe.push(7);
        let t = cut_quads_shorter_diagonal(&m);
        assert_eq!(t.count(Shape::Tri), 2);
        assert_eq!(t.cell_layer, vec![4, 4]);
        assert_eq!(t.cell_pipe, vec![7, 7]);
        // the short diagonal is 1-3 (length sqrt 2), not 0-2 (sqrt 10)
        assert!(
            t.cells
                .iter()
                .all(|c| c.corners().contains(&1) && c.corners().contains(&3))
        );
        assert!((t.linear_area() - m.linear_area()).abs() < 1e-15);
        let s = max_angle_histogram(&m);
        assert_eq!(s.triangles, 2);
        // triangles 0-1-3 and 1-2-3 are right isosceles triangles
        assert!((s.max_angle_deg - 90.0).abs() < 1e-9, "{s:?}");
        assert_eq!(s.histogram, [0; 5]);
        let mut obtuse = Mesh::new(Dim::Two, 1);
        obtuse.nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [-0.5, 0.75f64.sqrt(), 0.0],
        ];
        obtuse.cells.push(CellType::new(Shape::Tri, 1), &[0, 1, 2]);
        let s = max_angle_histogram(&obtuse);
        assert!((s.max_angle_deg - 120.0).abs() < 1e-9, "{s:?}");
        assert_eq!(s.histogram, [0, 0, 1, 0, 0]);
    }

    #[test]
    fn a_curved_quad_counts_by_its_corners_as_its_linear_quad() {
        let mut lin = Mesh::new(Dim::Two, 1);
        lin.nodes = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        lin.cells.push(CellType::new(Shape::Quad, 1), &[0, 1, 2, 3]);
        let mut p2 = lin.clone();
        p2.order = 2;
        p2.cells = mesh_model::Cells::with_capacity(1, 9);
        // mid-edge and centre nodes anywhere: only the corners count
        for _ in 0..5 {
            p2.nodes.push([0.7, 0.3, 0.0]);
        }
        p2.cells
            .push(CellType::new(Shape::Quad, 2), &[0, 1, 2, 3, 4, 5, 6, 7, 8]);
        assert_eq!(max_angle_histogram(&p2), max_angle_histogram(&lin));
        assert_eq!(max_angle_histogram(&p2).triangles, 2);
    }

    #[test]
    fn equilateral_triangles_fall_in_no_bin() {
        let a = max_triangle_angle_deg([0.0, 0.0], [1.0, 0.0], [0.5, 3f64.sqrt() / 2.0]);
        assert!((a - 60.0).abs() < 1e-9);
    }
}
