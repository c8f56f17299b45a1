//! Node placement: from the graded spacing field of a loop to nodes on its curve.
//!
//! Between consecutive corners (or around the whole loop when it has none) the nodes sit at
//! equal steps `q` of `φ(s) = ∫ ds/h(s)`. Why that keeps every promise:
//! the field `h` is `β = g − 1` Lipschitz in arc length, hence `ln h` is `β`-Lipschitz in `φ`
//! (`d ln h/dφ = dh/ds`). A segment covering `φ ∈ [φ_k, φ_k + q]` has length
//! `∫ h dφ ≤ h_min·(e^{βq} − 1)/β`, with `h_min` the least `h` over the segment; and two
//! segments meeting at a node where `h = h_n` have lengths in
//! `[h_n·(1 − e^{−βq})/β, h_n·(e^{βq} − 1)/β]`, so their ratio is at most `e^{βq}`. With
//! `q = ln(g)/β` both bounds are tight: no segment exceeds the field over its span, no ratio
//! exceeds `g`. The node count of a stretch is `N = ⌈Φ/q⌉`; to keep the step exactly `q`
//! everywhere (so that ratios hold across corners too), the stretch's field is clipped to
//! `min(h, λ)` with `λ` chosen so that `∫ ds/min(h, λ) = N·q`: only the largest spacings
//! shrink, and the clipped field is still `β`-Lipschitz. When a very short stretch would need
//! `λ` below its corner spacing, that corner spacing is lowered to `λ` and the loop redone.

use geom_curve::{ClosedCurve, Point2};

use crate::spacing::{LoopSpacing, graded_field, interpolation_cap};
use crate::{Boundary1dError, BoundaryNodes, NodePlacement, SpacingParams};

/// Safety factor on the step: keeps the proven bounds strict under rounding.
const STEP_MARGIN: f64 = 1.0 - 1e-7;
/// Corner-spacing adjustments allowed before giving up.
const MAX_ADJUSTMENTS: usize = 64;

/// A stretch of the field where `h` is linear: from arc position `s0` over `length`, going
/// from `start` to `end`.
#[derive(Debug, Clone, Copy)]
struct Piece {
    s0: f64,
    length: f64,
    start: f64,
    end: f64,
}

impl Piece {
    /// The part of the piece where `min(h, λ)` is linear, in one or two sub-pieces.
    fn clipped(self, lambda: f64) -> [Option<Piece>; 2] {
        let (a, b) = (self.start, self.end);
        if a <= lambda && b <= lambda {
            return [Some(self), None];
        }
        if a >= lambda && b >= lambda {
            return [
                Some(Piece {
                    start: lambda,
                    end: lambda,
                    ..self
                }),
                None,
            ];
        }
        let split = self.length * (lambda - a) / (b - a);
        let first = Piece {
            s0: self.s0,
            length: split,
            start: a.min(lambda),
            end: lambda,
        };
        let second = Piece {
            s0: self.s0 + split,
            length: self.length - split,
            start: lambda,
            end: b.min(lambda),
        };
        [Some(first), Some(second)]
    }

    /// `∫ ds/h` over the piece: `length·ln(end/start)/(end − start)`.
    fn phi(&self) -> f64 {
        let ratio = (self.end - self.start) / self.start;
        if ratio.abs() < 1e-8 {
            self.length / self.start * (1.0 - 0.5 * ratio)
        } else if ratio > -0.5 {
            self.length / self.start * ratio.ln_1p() / ratio
        } else {
            // `1 + ratio` would round away an `end` far below `start` (ln_1p(−1) = −∞)
            self.length * (self.end / self.start).ln() / (self.end - self.start)
        }
    }

    /// Distance from the piece's start at which `∫ ds/h` reaches `phi`.
    fn offset_at_phi(&self, phi: f64) -> f64 {
        let slope = (self.end - self.start) / self.length;
        let x = slope * phi;
        let offset = if x.abs() < 1e-9 {
            self.start * phi * (1.0 + 0.5 * x)
        } else {
            self.start * x.exp_m1() / slope
        };
        offset.clamp(0.0, self.length)
    }
}

/// One stretch between corners (or the whole loop): its pieces in order of arc position
/// (unwrapped, may run past the loop's length) and the geometry point it starts at.
struct Stretch {
    start_point: usize,
    pieces: Vec<Piece>,
}

impl Stretch {
    fn length(&self) -> f64 {
        self.pieces.iter().map(|p| p.length).sum()
    }

    fn max_spacing(&self) -> f64 {
        self.pieces
            .iter()
            .map(|p| p.start.max(p.end))
            .fold(0.0, f64::max)
    }

    /// `Φ(λ) = ∫ ds/min(h, λ)` and `dΦ/dλ`.
    fn phi(&self, lambda: f64) -> (f64, f64) {
        let mut phi = 0.0;
        let mut above = 0.0;
        for piece in &self.pieces {
            for sub in piece.clipped(lambda).into_iter().flatten() {
                phi += sub.phi();
                if sub.start >= lambda && sub.end >= lambda {
                    above += sub.length;
                }
            }
        }
        (phi, -above / (lambda * lambda))
    }

    /// The clip level `λ` with `Φ(λ) = target`, or infinity when the unclipped field already
    /// gives at least `target`. Safeguarded Newton iteration (Φ is convex and decreasing).
    fn clip_level(&self, target: f64) -> f64 {
        let (phi_unclipped, _) = self.phi(f64::INFINITY);
        if phi_unclipped >= target * (1.0 - 1e-13) {
            return f64::INFINITY;
        }
        let mut lo = self.length() / target;
        let mut hi = self.max_spacing();
        let mut lambda = hi;
        for _ in 0..200 {
            let (phi, slope) = self.phi(lambda);
            let error = phi - target;
            if error.abs() <= 1e-13 * target {
                break;
            }
            if error > 0.0 {
                lo = lambda;
            } else {
                hi = lambda;
            }
            let newton = lambda - error / slope;
            lambda = if slope < 0.0 && newton > lo && newton < hi {
                newton
            } else {
                (lo * hi).sqrt()
            };
        }
        lambda
    }

    /// Arc positions of the nodes at `φ = k·Φ/N`, `k = 1..N`, under the clip `λ`.
    fn interior_nodes(&self, lambda: f64, count: usize) -> Vec<f64> {
        let sub_pieces: Vec<Piece> = self
            .pieces
            .iter()
            .flat_map(|p| p.clipped(lambda).into_iter().flatten())
            .collect();
        let total: f64 = sub_pieces.iter().map(Piece::phi).sum();
        let step = total / count as f64;
        let mut nodes = Vec::with_capacity(count.saturating_sub(1));
        let mut accumulated = 0.0;
        let mut k = 1;
        for piece in &sub_pieces {
            let phi = piece.phi();
            while k < count && (k as f64) * step <= accumulated + phi {
                let local = (k as f64) * step - accumulated;
                nodes.push(piece.s0 + piece.offset_at_phi(local));
                k += 1;
            }
            accumulated += phi;
        }
        // rounding may leave the last targets just past the accumulated total
        let end = self.pieces.last().map_or(0.0, |p| p.s0 + p.length);
        while nodes.len() < count - 1 {
            nodes.push(end);
        }
        nodes
    }
}

/// The pieces of the field on geometry segment `i` (from point `i` to `i + 1`), where `h` is
/// the lower envelope of the interpolated cap and the two cones from the end points.
fn segment_pieces(
    spacing: &LoopSpacing,
    slope: f64,
    max_spacing: f64,
    i: usize,
    s0: f64,
    out: &mut Vec<Piece>,
) {
    let n = spacing.cap.len();
    let j = (i + 1) % n;
    let length = spacing.arc_positions[i + 1] - spacing.arc_positions[i];
    let cap0 = interpolation_cap(spacing, i, j, max_spacing);
    let cap1 = interpolation_cap(spacing, j, i, max_spacing);
    let (h0, h1) = (spacing.graded[i], spacing.graded[j]);
    let cap_slope = (cap1 - cap0) / length;
    let field = |x: f64| {
        (cap0 + cap_slope * x)
            .min(h0 + slope * x)
            .min(h1 + slope * (length - x))
    };
    let mut cuts = [0.0, length, 0.0, 0.0, 0.0];
    let mut count = 2;
    let mut add = |x: f64| {
        if x > 0.0 && x < length {
            cuts[count] = x;
            count += 1;
        }
    };
    if cap_slope != slope {
        add((h0 - cap0) / (cap_slope - slope));
    }
    if cap_slope != -slope {
        add((h1 + slope * length - cap0) / (cap_slope + slope));
    }
    add((h1 - h0 + slope * length) / (2.0 * slope));
    let cuts = &mut cuts[..count];
    cuts.sort_by(f64::total_cmp);
    for pair in cuts.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b > a {
            out.push(Piece {
                s0: s0 + a,
                length: b - a,
                start: field(a),
                end: field(b),
            });
        }
    }
}

/// Splits the loop into stretches: corner to corner, or the whole loop from its smallest
/// spacing when it has no corners.
fn stretches(spacing: &LoopSpacing, slope: f64, max_spacing: f64) -> Vec<Stretch> {
    let n = spacing.cap.len();
    let corners: Vec<usize> = (0..n).filter(|&i| spacing.is_corner[i]).collect();
    let bounds: Vec<(usize, usize)> = if corners.is_empty() {
        let start = (0..n)
            .min_by(|&a, &b| spacing.graded[a].total_cmp(&spacing.graded[b]))
            .unwrap_or(0);
        vec![(start, n)]
    } else {
        (0..corners.len())
            .map(|k| {
                let from = corners[k];
                let to = corners[(k + 1) % corners.len()];
                let count = if corners.len() == 1 {
                    n
                } else {
                    (to + n - from) % n
                };
                (from, count)
            })
            .collect()
    };
    bounds
        .into_iter()
        .map(|(start_point, segment_count)| {
            let mut pieces = Vec::with_capacity(3 * segment_count);
            let mut s0 = spacing.arc_positions[start_point];
            for r in 0..segment_count {
                let i = (start_point + r) % n;
                segment_pieces(spacing, slope, max_spacing, i, s0, &mut pieces);
                s0 += spacing.arc_positions[i + 1] - spacing.arc_positions[i];
            }
            Stretch {
                start_point,
                pieces,
            }
        })
        .collect()
}

/// The nodes of one loop before they are placed: the spacing after the corner adjustments,
/// its stretches and each stretch's clip level and node count.
pub(crate) struct NodePlan {
    spacing: LoopSpacing,
    stretches: Vec<Stretch>,
    plan: Vec<(f64, usize)>,
}

impl NodePlan {
    /// Nodes the loop will have.
    pub(crate) fn node_count(&self) -> usize {
        self.plan.iter().map(|&(_, count)| count).sum()
    }
}

/// Plans the nodes of one loop: node counts per stretch, without allocating per node.
///
/// # Errors
/// [`Boundary1dError::TooManyNodes`] as soon as the loop alone would exceed `node_limit`
/// (checked before any per-node allocation); [`Boundary1dError::CornerSpacingDidNotSettle`].
pub(crate) fn plan_nodes(
    mut spacing: LoopSpacing,
    params: &SpacingParams,
    loop_index: usize,
    node_limit: usize,
) -> Result<NodePlan, Boundary1dError> {
    let slope = params.growth - 1.0;
    let step = params.growth.ln() / slope * STEP_MARGIN;
    for _ in 0..MAX_ADJUSTMENTS {
        let stretches = stretches(&spacing, slope, params.max_spacing);
        let mut plan = Vec::with_capacity(stretches.len());
        let mut adjusted = false;
        let mut estimate = 0.0;
        for (k, stretch) in stretches.iter().enumerate() {
            let (phi, _) = stretch.phi(f64::INFINITY);
            let count = ((phi / step) * (1.0 - 1e-12)).ceil().max(1.0);
            estimate += count;
            // a field that is not finite is refused like a huge one
            if estimate.is_nan() || estimate > node_limit as f64 {
                return Err(Boundary1dError::TooManyNodes {
                    loop_index,
                    estimate,
                    limit: node_limit,
                });
            }
            let count = count as usize;
            let lambda = stretch.clip_level(count as f64 * step);
            if spacing.is_corner[stretch.start_point] {
                let end_point = stretches[(k + 1) % stretches.len()].start_point;
                for corner in [stretch.start_point, end_point] {
                    if lambda < spacing.graded[corner] * (1.0 - 1e-12) {
                        // lower by at least 2 % so that the adjustments end quickly
                        spacing.cap[corner] = lambda.min(0.98 * spacing.graded[corner]);
                        adjusted = true;
                    }
                }
            }
            plan.push((lambda, count));
        }
        if adjusted {
            spacing.graded = graded_field(&spacing.cap, &spacing.arc_positions, slope);
            continue;
        }
        return Ok(NodePlan {
            spacing,
            stretches,
            plan,
        });
    }
    Err(Boundary1dError::CornerSpacingDidNotSettle {
        loop_index,
        iterations: MAX_ADJUSTMENTS,
    })
}

/// Places the planned nodes of one loop on its curve (or polygon).
pub(crate) fn place_nodes(
    curve: &ClosedCurve,
    planned: &NodePlan,
    params: &SpacingParams,
) -> BoundaryNodes {
    let spacing = &planned.spacing;
    let mut arc_nodes: Vec<(f64, bool)> = Vec::with_capacity(planned.node_count());
    for (stretch, &(lambda, count)) in planned.stretches.iter().zip(&planned.plan) {
        let start = stretch.start_point;
        arc_nodes.push((spacing.arc_positions[start], spacing.is_corner[start]));
        for s in stretch.interior_nodes(lambda, count) {
            arc_nodes.push((s, false));
        }
    }
    to_boundary_nodes(curve, spacing, params, &arc_nodes, spacing.cap.len())
}

/// Turns arc positions into curve parameters and points, in increasing `t` from `t = 0`.
fn to_boundary_nodes(
    curve: &ClosedCurve,
    spacing: &LoopSpacing,
    params: &SpacingParams,
    arc_nodes: &[(f64, bool)],
    n: usize,
) -> BoundaryNodes {
    let total = spacing.arc_positions[n];
    let points_in = curve.input_points();
    let mut nodes: Vec<(f64, Point2<f64>, bool)> = arc_nodes
        .iter()
        .map(|&(s, is_corner)| {
            let s = s.rem_euclid(total);
            // geometry points (corners and stretch starts) keep their exact parameter
            let exact = spacing
                .arc_positions
                .binary_search_by(|probe| probe.total_cmp(&s))
                .ok()
                .filter(|&i| i < n);
            if let Some(i) = exact {
                return (i as f64, points_in[i], is_corner);
            }
            match params.placement {
                NodePlacement::OnCurve => {
                    let t = curve.t_at_arc_length(s);
                    (t, curve.point(t), is_corner)
                }
                NodePlacement::OnPolyline => {
                    let i = spacing
                        .arc_positions
                        .partition_point(|&p| p <= s)
                        .saturating_sub(1)
                        .min(n - 1);
                    let fraction = ((s - spacing.arc_positions[i])
                        / (spacing.arc_positions[i + 1] - spacing.arc_positions[i]))
                        .clamp(0.0, 1.0);
                    let a = points_in[i];
                    let b = points_in[(i + 1) % n];
                    (i as f64 + fraction, a + (b - a) * fraction, is_corner)
                }
            }
        })
        .collect();
    let first = nodes
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.0.total_cmp(&b.1.0))
        .map_or(0, |(k, _)| k);
    nodes.rotate_left(first);
    BoundaryNodes {
        t: nodes.iter().map(|node| node.0).collect(),
        points: nodes.iter().map(|node| node.1).collect(),
        is_corner: nodes.iter().map(|node| node.2).collect(),
    }
}
