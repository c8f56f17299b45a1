//! The geometry curve of the dissertation (§3.1.2): a closed C2 piecewise quintic Hermite curve
//! through the loop's points, with C0 breaks at sharp corners.
//!
//! Segment `i` joins point `i` to point `i + 1` (the last one closes the loop). Each segment
//! matches position, first and second derivative at both ends (six conditions, the text's
//! "6-degree" curve). The derivatives at a point are those of the Lagrange polynomial through
//! the point and `k` neighbours on each side, the abscissae being cumulative chord lengths.
//! Since both segments meeting at a point use the same derivatives (with respect to the chord
//! length parameter), the curve is C2 there. At a corner the stencils stop: a point next to a
//! corner uses a one-sided stencil that ends at the corner, and the corner itself gets two
//! one-sided sets of derivatives, so the curve is only C0 there.
//!
//! The global parameter is `t ∈ [0, n)`: segment `i` is `t ∈ [i, i + 1)`, with local
//! parameter `u = t − i`; `t = i` is input point `i`. Values of `t` outside `[0, n)` wrap
//! around. Derivatives [`ClosedCurve::d1`] and [`ClosedCurve::d2`] are with respect to `t`; the
//! chord-length parameter `s = s_i + h_i·u` (with `h_i` the chord of segment `i`) is the one in
//! which the curve is C2, so `d1(t)/h_i` and `d2(t)/h_i²` are continuous at smooth points while
//! `d1(t)` itself jumps by the ratio of neighbouring chords. Tangent and curvature are
//! continuous at every non-corner point.
//!
//! Owns the fitted curve and its queries (evaluation, arc length and its inverse, closest
//! point). Does not decide spacing (that is `boundary1d`) and does not reorient loops (see
//! [`crate::loops::make_counter_clockwise`]).

use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};

use crate::CurveError;
use crate::loops::{LoopCheckParams, validate_loop};
use crate::quadrature::integrate_adaptive;

/// Relative accuracy of the arc lengths (against the length being measured).
const ARC_LENGTH_REL_TOL: f64 = 1e-15;

/// How the curve is fitted through the points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CurveParams {
    /// A point is a corner (C0 break) when the angle ∠ABC between the chords to its two
    /// neighbours is smaller than this, in degrees; 180 means a straight continuation.
    /// Default 140°, i.e. a change of direction of more than 40° between consecutive chords.
    ///
    /// Why 140°: on resolved smooth curves consecutive chords turn by a few degrees; the
    /// sharpest smooth points of the reference airfoils (leading edges of NACA 0012, RAE 2822,
    /// 30P30N) turn by at most 22° (angle ≥ 158°), while their real corners (sharp and blunt
    /// trailing edges, the slat cusp, the main-element cove) turn by at least 60°
    /// (angle ≤ 120°). 140° sits between the two with a margin on both sides. A circle needs
    /// at least 10 points not to be taken as a polygon of corners.
    pub corner_angle_deg: f64,
    /// A point is also a corner (a "kink") when its change of direction, 180° − ∠ABC, is at
    /// least this many degrees **and** more than [`Self::kink_turn_ratio`] times that of
    /// both neighbours. Default 15°. This catches moderate corners in well-resolved outlines
    /// (for example tips where two arcs meet at 27°) that the absolute test misses, while a
    /// smooth leading edge, whose neighbours turn almost as much, stays smooth.
    pub kink_min_turn_deg: f64,
    /// See [`Self::kink_min_turn_deg`]. Dimensionless, default 3.
    pub kink_turn_ratio: f64,
    /// Neighbours on each side of a point in the Lagrange stencil that gives its derivatives
    /// (`k`; the polynomial has degree 2k). Default 2 (quartic). Range 1..=8.
    pub lagrange_half_width: usize,
    /// Checks run on the points before fitting.
    pub loop_checks: LoopCheckParams,
}

impl Default for CurveParams {
    fn default() -> Self {
        Self {
            corner_angle_deg: 140.0,
            kink_min_turn_deg: 15.0,
            kink_turn_ratio: 3.0,
            lagrange_half_width: 2,
            loop_checks: LoopCheckParams::default(),
        }
    }
}

/// One quintic segment, `u ∈ [0, 1]`, stored in power form `Σ c_j u^j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HermiteSegment {
    coefficients: [Vector2<f64>; 6],
    chord_length: f64,
    box_min: Point2<f64>,
    box_max: Point2<f64>,
}

impl HermiteSegment {
    /// The quintic matching position `p`, first derivative `m` and second derivative `a` (all
    /// with respect to `u`) at both ends.
    fn from_end_conditions(
        p0: Point2<f64>,
        m0: Vector2<f64>,
        a0: Vector2<f64>,
        p1: Point2<f64>,
        m1: Vector2<f64>,
        a1: Vector2<f64>,
    ) -> Self {
        let c0 = p0.coords;
        let c1 = m0;
        let c2 = 0.5 * a0;
        let delta = p1.coords - c0 - c1 - c2;
        let delta_d1 = m1 - m0 - a0;
        let delta_d2 = a1 - a0;
        let c3 = 10.0 * delta - 4.0 * delta_d1 + 0.5 * delta_d2;
        let c4 = -15.0 * delta + 7.0 * delta_d1 - delta_d2;
        let c5 = 6.0 * delta - 3.0 * delta_d1 + 0.5 * delta_d2;
        let coefficients = [c0, c1, c2, c3, c4, c5];
        // Bernstein control points bound the segment: b_j = Σ_{i≤j} C(j,i)/C(5,i) c_i.
        let binomial_5 = [1.0, 5.0, 10.0, 10.0, 5.0, 1.0];
        let mut box_min = p0;
        let mut box_max = p0;
        for j in 0..6 {
            let mut control = Vector2::zeros();
            let mut binomial_j = 1.0;
            for (i, c) in coefficients.iter().enumerate().take(j + 1) {
                control += c * (binomial_j / binomial_5[i]);
                binomial_j = binomial_j * (j - i) as f64 / (i + 1) as f64;
            }
            box_min = box_min.inf(&Point2::from(control));
            box_max = box_max.sup(&Point2::from(control));
        }
        Self {
            coefficients,
            chord_length: (p1 - p0).norm(),
            box_min,
            box_max,
        }
    }

    /// Position at local parameter `u`.
    pub fn point(&self, u: f64) -> Point2<f64> {
        let c = &self.coefficients;
        Point2::from(c[0] + u * (c[1] + u * (c[2] + u * (c[3] + u * (c[4] + u * c[5])))))
    }

    /// First derivative with respect to `u`.
    pub fn d1(&self, u: f64) -> Vector2<f64> {
        let c = &self.coefficients;
        c[1] + u * (2.0 * c[2] + u * (3.0 * c[3] + u * (4.0 * c[4] + u * 5.0 * c[5])))
    }

    /// Second derivative with respect to `u`.
    pub fn d2(&self, u: f64) -> Vector2<f64> {
        let c = &self.coefficients;
        2.0 * c[2] + u * (6.0 * c[3] + u * (12.0 * c[4] + u * 20.0 * c[5]))
    }

    /// Length of the straight chord between the segment's end points (the `h` that scales
    /// derivatives between `u` and the chord-length parameter).
    pub fn chord_length(&self) -> f64 {
        self.chord_length
    }

    /// An axis-aligned box containing the whole segment (from its Bézier control points):
    /// `(min corner, max corner)`.
    pub fn bounding_box(&self) -> (Point2<f64>, Point2<f64>) {
        (self.box_min, self.box_max)
    }

    /// Arc length between local parameters `u0 ≤ u1` (negative if `u1 < u0`).
    fn arc_length(&self, u0: f64, u1: f64) -> f64 {
        let speed = |u: f64| self.d1(u).norm();
        integrate_adaptive(&speed, u0, u1, ARC_LENGTH_REL_TOL)
    }

    /// Lower bound of the distance from `p` to the segment (distance to its box).
    fn distance_lower_bound(&self, p: Point2<f64>) -> f64 {
        let below = self.box_min - p;
        let above = p - self.box_max;
        Vector2::new(below.x.max(above.x).max(0.0), below.y.max(above.y).max(0.0)).norm()
    }

    /// The closest point of the segment to `p`: (u, point, distance). Samples 17 points, then
    /// narrows the best bracket by golden-section search and polishes with Newton steps that
    /// are kept only when they bring the point closer.
    fn closest_point(&self, p: Point2<f64>) -> (f64, Point2<f64>, f64) {
        const SAMPLES: usize = 16;
        let distance = |u: f64| (self.point(u) - p).norm();
        let mut best_u = 0.0;
        let mut best_d = distance(0.0);
        for j in 1..=SAMPLES {
            let u = j as f64 / SAMPLES as f64;
            let d = distance(u);
            if d < best_d {
                best_u = u;
                best_d = d;
            }
        }
        let step = 1.0 / SAMPLES as f64;
        let (mut lo, mut hi) = ((best_u - step).max(0.0), (best_u + step).min(1.0));
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let mut x1 = hi - ratio * (hi - lo);
        let mut x2 = lo + ratio * (hi - lo);
        let (mut f1, mut f2) = (distance(x1), distance(x2));
        while hi - lo > 1e-7 {
            if f1 < f2 {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - ratio * (hi - lo);
                f1 = distance(x1);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + ratio * (hi - lo);
                f2 = distance(x2);
            }
        }
        let mut u = 0.5 * (lo + hi);
        let mut d = distance(u);
        for _ in 0..8 {
            let offset = self.point(u) - p;
            let d1 = self.d1(u);
            let slope = offset.dot(&d1);
            let curvature_term = d1.norm_squared() + offset.dot(&self.d2(u));
            if curvature_term <= 0.0 {
                break;
            }
            let next = (u - slope / curvature_term).clamp(0.0, 1.0);
            let next_d = distance(next);
            if next_d > d || next == u {
                break;
            }
            u = next;
            d = next_d;
        }
        if d < best_d {
            (u, self.point(u), d)
        } else {
            (best_u, self.point(best_u), best_d)
        }
    }
}

/// First and second derivatives with respect to the chord-length parameter on each side of a
/// point (equal on both sides except at corners).
#[derive(Debug, Clone, Copy)]
struct PointDerivatives {
    before: (Vector2<f64>, Vector2<f64>),
    after: (Vector2<f64>, Vector2<f64>),
}

/// A closed C2 piecewise quintic Hermite curve with C0 corners (see the module docs).
#[derive(Debug, Clone)]
pub struct ClosedCurve {
    points: Vec<Point2<f64>>,
    corners: Vec<usize>,
    is_corner: Vec<bool>,
    segments: Vec<HermiteSegment>,
    /// Arc length from `t = 0` to `t = i`, `i = 0..=n`.
    cumulative_lengths: Vec<f64>,
}

impl ClosedCurve {
    /// Fits the curve through `points` (a closed loop, first point not repeated).
    ///
    /// # Errors
    /// Any fault of [`validate_loop`] under `params.loop_checks`;
    /// [`CurveError::SplineCrossesItself`] when the fitted curve crosses itself although the
    /// polygon does not; and
    /// [`CurveError::InvalidParameter`] when `corner_angle_deg` is not in (0, 180],
    /// `kink_min_turn_deg` is negative, `kink_turn_ratio` is below 1 or `lagrange_half_width`
    /// is not in 1..=8.
    pub fn new(points: &[Point2<f64>], params: &CurveParams) -> Result<Self, CurveError> {
        if !(params.corner_angle_deg > 0.0 && params.corner_angle_deg <= 180.0) {
            return Err(CurveError::InvalidParameter {
                name: "corner_angle_deg",
                value: params.corner_angle_deg,
                reason: "must be in (0, 180] degrees",
            });
        }
        if !(params.kink_min_turn_deg >= 0.0 && params.kink_turn_ratio >= 1.0) {
            return Err(CurveError::InvalidParameter {
                name: "kink_min_turn_deg / kink_turn_ratio",
                value: params.kink_min_turn_deg.min(params.kink_turn_ratio),
                reason: "the angle must be >= 0 degrees and the ratio >= 1",
            });
        }
        if !(1..=8).contains(&params.lagrange_half_width) {
            return Err(CurveError::InvalidParameter {
                name: "lagrange_half_width",
                value: params.lagrange_half_width as f64,
                reason: "must be in 1..=8",
            });
        }
        validate_loop(points, &params.loop_checks)?;
        let n = points.len();
        let chords: Vec<f64> = (0..n)
            .map(|i| (points[(i + 1) % n] - points[i]).norm())
            .collect();
        // change of direction at each point, degrees in [0, 180]
        let turn_deg: Vec<f64> = (0..n)
            .map(|i| {
                let before = points[i] - points[(i + n - 1) % n];
                let after = points[(i + 1) % n] - points[i];
                before
                    .perp(&after)
                    .abs()
                    .atan2(before.dot(&after))
                    .to_degrees()
            })
            .collect();
        let is_corner: Vec<bool> = (0..n)
            .map(|i| {
                let neighbours = turn_deg[(i + n - 1) % n].max(turn_deg[(i + 1) % n]);
                180.0 - turn_deg[i] < params.corner_angle_deg
                    || (turn_deg[i] >= params.kink_min_turn_deg
                        && turn_deg[i] > params.kink_turn_ratio * neighbours)
            })
            .collect();
        let corners: Vec<usize> = (0..n).filter(|&i| is_corner[i]).collect();
        let stencils = Stencils {
            points,
            chords: &chords,
            is_corner: &is_corner,
            has_corners: !corners.is_empty(),
            half_width: params.lagrange_half_width,
        };
        let derivatives: Vec<PointDerivatives> = (0..n).map(|i| stencils.derivatives(i)).collect();
        let segments: Vec<HermiteSegment> = (0..n)
            .map(|i| {
                let j = (i + 1) % n;
                let h = chords[i];
                let (d1_start, d2_start) = derivatives[i].after;
                let (d1_end, d2_end) = derivatives[j].before;
                HermiteSegment::from_end_conditions(
                    points[i],
                    h * d1_start,
                    h * h * d2_start,
                    points[j],
                    h * d1_end,
                    h * h * d2_end,
                )
            })
            .collect();
        check_spline_simple(&segments)?;
        let mut cumulative_lengths = Vec::with_capacity(n + 1);
        cumulative_lengths.push(0.0);
        let mut total = 0.0;
        for segment in &segments {
            total += segment.arc_length(0.0, 1.0);
            cumulative_lengths.push(total);
        }
        Ok(Self {
            points: points.to_vec(),
            corners,
            is_corner,
            segments,
            cumulative_lengths,
        })
    }

    /// The curve as a polygon: `per_segment` points on each segment at equal steps of its
    /// local parameter, starting with the segment's first input point (`n·per_segment`
    /// points, `per_segment ≥ 1`; point `k` is at `t = k / per_segment`).
    pub fn sampled_polyline(&self, per_segment: usize) -> Vec<Point2<f64>> {
        sample_segments(&self.segments, per_segment)
    }

    /// The points the curve interpolates (`point(i as f64)` is `input_points()[i]`).
    pub fn input_points(&self) -> &[Point2<f64>] {
        &self.points
    }

    /// Indices of the input points that are corners (C0 breaks), increasing.
    pub fn corners(&self) -> &[usize] {
        &self.corners
    }

    /// Whether input point `i` is a corner (false for out-of-range `i`).
    pub fn is_corner(&self, i: usize) -> bool {
        self.is_corner.get(i).copied().unwrap_or(false)
    }

    /// The segments, segment `i` joining point `i` to point `i + 1`.
    pub fn segments(&self) -> &[HermiteSegment] {
        &self.segments
    }

    /// Number of segments `n` (= number of input points), the period of the parameter `t`.
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// Position at parameter `t`.
    pub fn point(&self, t: f64) -> Point2<f64> {
        let (i, u) = self.locate(t);
        self.segments[i].point(u)
    }

    /// First derivative with respect to `t` (from the segment `t` falls in: at `t = i`,
    /// segment `i`).
    pub fn d1(&self, t: f64) -> Vector2<f64> {
        let (i, u) = self.locate(t);
        self.segments[i].d1(u)
    }

    /// Second derivative with respect to `t`.
    pub fn d2(&self, t: f64) -> Vector2<f64> {
        let (i, u) = self.locate(t);
        self.segments[i].d2(u)
    }

    /// Unit tangent, in the direction of increasing `t`.
    pub fn tangent(&self, t: f64) -> Vector2<f64> {
        self.d1(t).normalize()
    }

    /// Signed curvature (1/length): positive where the curve turns left as `t` increases.
    pub fn curvature(&self, t: f64) -> f64 {
        let (i, u) = self.locate(t);
        let d1 = self.segments[i].d1(u);
        let d2 = self.segments[i].d2(u);
        d1.perp(&d2) / d1.norm().powi(3)
    }

    /// Arc length travelled from `t0` to `t1` in the direction of increasing `t` (negative
    /// when `t1 < t0`); each full turn of `t` adds [`Self::total_length`].
    pub fn arc_length(&self, t0: f64, t1: f64) -> f64 {
        self.arc_length_from_origin(t1) - self.arc_length_from_origin(t0)
    }

    /// Length of the whole closed curve.
    pub fn total_length(&self) -> f64 {
        self.cumulative_lengths[self.segments.len()]
    }

    /// Arc length from `t = 0` to each input point, `n + 1` values, the last being
    /// [`Self::total_length`].
    pub fn cumulative_lengths(&self) -> &[f64] {
        &self.cumulative_lengths
    }

    /// The parameter `t ∈ [0, n)` at arc length `s` from `t = 0`; `s` wraps modulo the total
    /// length. Newton's method on the arc-length integral, safeguarded by bisection.
    pub fn t_at_arc_length(&self, s: f64) -> f64 {
        let total = self.total_length();
        let n = self.segments.len();
        let s = s.rem_euclid(total);
        if !s.is_finite() {
            return f64::NAN;
        }
        let i = self
            .cumulative_lengths
            .partition_point(|&c| c <= s)
            .saturating_sub(1)
            .min(n - 1);
        let segment = &self.segments[i];
        let target = s - self.cumulative_lengths[i];
        let segment_length = self.cumulative_lengths[i + 1] - self.cumulative_lengths[i];
        let tolerance = 4.0 * f64::EPSILON * total;
        let (mut lo, mut hi) = (0.0, 1.0);
        let mut u = 0.0;
        let mut length = 0.0;
        let mut next = (target / segment_length).clamp(0.0, 1.0);
        for _ in 0..60 {
            length += segment.arc_length(u, next);
            u = next;
            let error = length - target;
            if error.abs() <= tolerance {
                break;
            }
            if error > 0.0 {
                hi = u;
            } else {
                lo = u;
            }
            let newton = u - error / segment.d1(u).norm();
            next = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if next == u {
                break;
            }
        }
        i as f64 + u
    }

    /// The point of the curve closest to `p`: `(t, point, distance)`. Exact up to the local
    /// search tolerance wherever `p` is: segments are visited in order of the distance to
    /// their bounding boxes and skipped once that bound exceeds the best distance found.
    pub fn closest_point(&self, p: Point2<f64>) -> (f64, Point2<f64>, f64) {
        let mut best = (0.0, self.points[0], (self.points[0] - p).norm());
        for (i, q) in self.points.iter().enumerate() {
            let d = (q - p).norm();
            if d < best.2 {
                best = (i as f64, *q, d);
            }
        }
        let mut candidates: Vec<(f64, usize)> = self
            .segments
            .iter()
            .enumerate()
            .map(|(i, segment)| (segment.distance_lower_bound(p), i))
            .filter(|&(bound, _)| bound <= best.2)
            .collect();
        candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (bound, i) in candidates {
            if bound > best.2 {
                break;
            }
            let (u, q, d) = self.segments[i].closest_point(p);
            if d < best.2 {
                best = (i as f64 + u, q, d);
            }
        }
        best
    }

    /// Segment index and local parameter of `t`.
    fn locate(&self, t: f64) -> (usize, f64) {
        let n = self.segments.len();
        let wrapped = t.rem_euclid(n as f64);
        let floor = wrapped.floor();
        let i = if floor.is_finite() {
            (floor as usize).min(n - 1)
        } else {
            0
        };
        (i, wrapped - i as f64)
    }

    /// Arc length from `t = 0` to `t`, counting full turns.
    fn arc_length_from_origin(&self, t: f64) -> f64 {
        let n = self.segments.len() as f64;
        let turns = (t / n).floor();
        let (i, u) = self.locate(t);
        let within = if u == 0.0 {
            0.0
        } else {
            self.segments[i].arc_length(0.0, u)
        };
        turns * self.total_length() + self.cumulative_lengths[i] + within
    }
}

/// Samples per segment of the self-crossing check of the spline.
const CROSSING_SAMPLES: usize = 8;

fn sample_segments(segments: &[HermiteSegment], per_segment: usize) -> Vec<Point2<f64>> {
    let per_segment = per_segment.max(1);
    let mut out = Vec::with_capacity(segments.len() * per_segment);
    for segment in segments {
        out.push(segment.point(0.0));
        for j in 1..per_segment {
            out.push(segment.point(j as f64 / per_segment as f64));
        }
    }
    out
}

/// The spline must not cross itself where the polygon through its points does not: checked
/// on the polygon through [`CROSSING_SAMPLES`] points per segment (exact predicates).
fn check_spline_simple(segments: &[HermiteSegment]) -> Result<(), CurveError> {
    let n = segments.len();
    let samples = sample_segments(segments, CROSSING_SAMPLES);
    let Some(crossing) = crate::loops::find_self_intersection(&samples) else {
        return Ok(());
    };
    let piece = |edge: usize| {
        let i = edge / CROSSING_SAMPLES;
        (i, (i + 1) % n)
    };
    let (from_a, to_a) = piece(crossing.edge_a);
    let (from_b, to_b) = piece(crossing.edge_b);
    Err(CurveError::SplineCrossesItself {
        from_a,
        to_a,
        from_b,
        to_b,
        x: crossing.point.x,
        y: crossing.point.y,
    })
}

/// The data needed to build the Lagrange stencil of each point.
struct Stencils<'a> {
    points: &'a [Point2<f64>],
    chords: &'a [f64],
    is_corner: &'a [bool],
    has_corners: bool,
    half_width: usize,
}

impl Stencils<'_> {
    /// Walks from point `i` in direction `forward` for at most `max_steps` points, stopping
    /// after the first corner met. Returns (point index, signed chord-length abscissa).
    fn walk(&self, i: usize, forward: bool, max_steps: usize) -> Vec<(usize, f64)> {
        let n = self.points.len();
        let mut out = Vec::with_capacity(max_steps);
        let mut index = i;
        let mut abscissa = 0.0;
        for _ in 0..max_steps {
            if forward {
                abscissa += self.chords[index];
                index = (index + 1) % n;
            } else {
                index = (index + n - 1) % n;
                abscissa -= self.chords[index];
            }
            out.push((index, abscissa));
            if self.is_corner[index] {
                break;
            }
        }
        out
    }

    fn derivatives(&self, i: usize) -> PointDerivatives {
        let k = self.half_width;
        if self.is_corner[i] {
            let before = self.walk(i, false, 2 * k);
            let after = self.walk(i, true, 2 * k);
            return PointDerivatives {
                before: self.lagrange(i, &before, &[]),
                after: self.lagrange(i, &[], &after),
            };
        }
        let (before, after) = if self.has_corners {
            let mut before = self.walk(i, false, 2 * k);
            let mut after = self.walk(i, true, 2 * k);
            let mut n_before = before.len().min(k);
            let mut n_after = after.len().min(k);
            if n_before < k {
                n_after = after.len().min(2 * k - n_before);
            }
            if n_after < k {
                n_before = before.len().min(2 * k - n_after);
            }
            before.truncate(n_before);
            after.truncate(n_after);
            (before, after)
        } else {
            let k = k.min((self.points.len() - 1) / 2);
            (self.walk(i, false, k), self.walk(i, true, k))
        };
        let both = self.lagrange(i, &before, &after);
        PointDerivatives {
            before: both,
            after: both,
        }
    }

    /// First and second derivatives at point `i` of the Lagrange polynomial through `i` and
    /// the given neighbours.
    fn lagrange(
        &self,
        i: usize,
        before: &[(usize, f64)],
        after: &[(usize, f64)],
    ) -> (Vector2<f64>, Vector2<f64>) {
        let mut nodes = Vec::with_capacity(1 + before.len() + after.len());
        nodes.push((i, 0.0));
        nodes.extend_from_slice(before);
        nodes.extend_from_slice(after);
        // Weights on abscissae scaled to [-1, 1], so that the products of up to 16 chord
        // lengths in Fornberg's recursion neither underflow nor overflow at any scale.
        let scale = nodes.iter().map(|&(_, x)| x.abs()).fold(0.0, f64::max);
        let abscissae: Vec<f64> = nodes.iter().map(|&(_, x)| x / scale).collect();
        let weights = fornberg_weights(&abscissae);
        let origin = self.points[i];
        let mut d1 = Vector2::zeros();
        let mut d2 = Vector2::zeros();
        for (&(index, _), w) in nodes.iter().zip(&weights) {
            let offset = (self.points[index] - origin) / scale;
            d1 += w[1] * offset;
            d2 += w[2] * offset;
        }
        (d1, d2 / scale)
    }
}

/// Weights of the 0th, 1st and 2nd derivative at 0 of the polynomial interpolating values at
/// the distinct abscissae `x` (Fornberg, "Generation of finite difference formulas on
/// arbitrarily spaced grids", Math. Comp. 51, 1988).
fn fornberg_weights(x: &[f64]) -> Vec<[f64; 3]> {
    let m = x.len();
    let mut c = vec![[0.0; 3]; m];
    c[0][0] = 1.0;
    let mut c1 = 1.0;
    let mut c4 = x[0];
    for i in 1..m {
        let order = i.min(2);
        let mut c2 = 1.0;
        let c5 = c4;
        c4 = x[i];
        for j in 0..i {
            let c3 = x[i] - x[j];
            c2 *= c3;
            if j == i - 1 {
                for k in (1..=order).rev() {
                    c[i][k] = c1 * (k as f64 * c[i - 1][k - 1] - c5 * c[i - 1][k]) / c2;
                }
                c[i][0] = -c1 * c5 * c[i - 1][0] / c2;
            }
            for k in (1..=order).rev() {
                c[j][k] = (c4 * c[j][k] - k as f64 * c[j][k - 1]) / c3;
            }
            c[j][0] = c4 * c[j][0] / c3;
        }
        c1 = c2;
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fornberg_reproduces_central_differences() {
        let w = fornberg_weights(&[0.0, -1.0, 1.0]);
        let expected = [[1.0, 0.0, -2.0], [0.0, -0.5, 1.0], [0.0, 0.5, 1.0]];
        for (got, want) in w.iter().zip(expected) {
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() < 1e-14, "{w:?}");
            }
        }
    }

    #[test]
    fn fornberg_is_exact_for_polynomials_on_uneven_nodes() {
        let x = [0.0, -0.3, -0.7, 0.2, 0.9];
        let w = fornberg_weights(&x);
        // f = 1 + 2x − 3x² + x³ − 0.5x⁴: f'(0) = 2, f''(0) = −6
        let f = |x: f64| 1.0 + 2.0 * x - 3.0 * x * x + x * x * x - 0.5 * x.powi(4);
        let d1: f64 = x.iter().zip(&w).map(|(&xi, wi)| wi[1] * f(xi)).sum();
        let d2: f64 = x.iter().zip(&w).map(|(&xi, wi)| wi[2] * f(xi)).sum();
        assert!((d1 - 2.0).abs() < 1e-12);
        assert!((d2 + 6.0).abs() < 1e-11);
    }

    #[test]
    fn segment_matches_its_end_conditions() {
        let p0 = Point2::new(0.1, 0.2);
        let p1 = Point2::new(1.0, -0.4);
        let m0 = Vector2::new(0.3, 1.0);
        let m1 = Vector2::new(-0.2, 0.5);
        let a0 = Vector2::new(2.0, -1.0);
        let a1 = Vector2::new(0.0, 3.0);
        let s = HermiteSegment::from_end_conditions(p0, m0, a0, p1, m1, a1);
        assert!((s.point(0.0) - p0).norm() < 1e-15);
        assert!((s.point(1.0) - p1).norm() < 1e-14);
        assert!((s.d1(0.0) - m0).norm() < 1e-14);
        assert!((s.d1(1.0) - m1).norm() < 1e-13);
        assert!((s.d2(0.0) - a0).norm() < 1e-14);
        assert!((s.d2(1.0) - a1).norm() < 1e-12);
        let (lo, hi) = s.bounding_box();
        for j in 0..=100 {
            let p = s.point(f64::from(j) / 100.0);
            assert!(p.x >= lo.x - 1e-15 && p.y >= lo.y - 1e-15);
            assert!(p.x <= hi.x + 1e-15 && p.y <= hi.y + 1e-15);
        }
    }
}
