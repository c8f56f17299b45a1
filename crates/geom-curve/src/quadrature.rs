//! Adaptive Gauss–Legendre quadrature of a scalar function on an interval, used for arc
//! lengths. Owns the rule's nodes and weights and the bisection strategy, nothing else.

/// Nodes on [-1, 1] of the 8-point Gauss–Legendre rule (positive half; the rule is symmetric).
const NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// Weights matching [`NODES`].
const WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// The 8-point Gauss–Legendre estimate of ∫ f on [a, b].
pub(crate) fn gauss_legendre_8(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    let mut sum = 0.0;
    for (node, weight) in NODES.iter().zip(WEIGHTS) {
        sum += weight * (f(mid - half * node) + f(mid + half * node));
    }
    sum * half
}

/// Most intervals [`integrate_adaptive`] evaluates (each costs 16 evaluations of `f`): the
/// quadrature is bounded whatever the integrand, so NaN, infinite or rough integrands cost at
/// most this and never hang the caller.
pub(crate) const MAX_INTERVALS: usize = 2048;
/// Deepest bisection: an interval is never shorter than 2^-40 of the whole.
const MAX_DEPTH: u32 = 40;

/// ∫ f on [a, b] by 8-point Gauss–Legendre, halving intervals until the two halves agree with
/// the whole within `rel_tol` times the magnitude of the integral (scaled by the interval's
/// share of [a, b]), or within a few rounding errors of the interval's own estimate, whichever
/// is larger. Scale-free: multiplying `f` by any factor changes nothing but the result's
/// scale. Bounded: at most [`MAX_INTERVALS`] intervals and a depth of 40; past those the best
/// estimate so far is returned. A non-finite estimate is returned at once.
pub(crate) fn integrate_adaptive(f: &impl Fn(f64) -> f64, a: f64, b: f64, rel_tol: f64) -> f64 {
    let whole = gauss_legendre_8(f, a, b);
    if !whole.is_finite() || a == b {
        return whole;
    }
    let tolerance = rel_tol * whole.abs();
    let width = b - a;
    // (a, b, estimate, depth); depth-first, left to right, so the sum is deterministic
    let mut stack = vec![(a, b, whole, 0u32)];
    let mut intervals = 1usize;
    let mut total = 0.0;
    while let Some((lo, hi, estimate, depth)) = stack.pop() {
        let mid = 0.5 * (lo + hi);
        let left = gauss_legendre_8(f, lo, mid);
        let right = gauss_legendre_8(f, mid, hi);
        intervals += 2;
        let halves = left + right;
        let share = ((hi - lo) / width).abs();
        let allowed = (tolerance * share).max(4.0 * f64::EPSILON * halves.abs());
        let settled = (halves - estimate).abs() <= allowed;
        if settled
            || !halves.is_finite()
            || depth >= MAX_DEPTH
            || intervals + 2 * stack.len() >= MAX_INTERVALS
            || mid == lo
            || mid == hi
        {
            total += halves;
            continue;
        }
        stack.push((mid, hi, right, depth + 1));
        stack.push((lo, mid, left, depth + 1));
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_polynomials_and_smooth_functions() {
        let poly = |x: f64| 15.0 * x.powi(14) + 1.0;
        let value = integrate_adaptive(&poly, 0.0, 1.0, 1e-14);
        assert!((value - 2.0).abs() < 1e-13);
        let sqrt = |x: f64| x.sqrt();
        let value = integrate_adaptive(&sqrt, 0.0, 1.0, 1e-12);
        assert!((value - 2.0 / 3.0).abs() < 1e-10);
        let reversed = integrate_adaptive(&sqrt, 1.0, 0.0, 1e-12);
        assert!((reversed + 2.0 / 3.0).abs() < 1e-10);
        let weights: f64 = 2.0 * WEIGHTS.iter().sum::<f64>();
        assert!((weights - 2.0).abs() < 1e-15);
    }

    /// D4 (issue 15): the arc length hung at scales 1e-100 and 1e150 (NaN or infinite
    /// integrands never met the absolute tolerance and bisected 2^30 times).
    #[test]
    fn is_scale_free_and_bounded() {
        let sqrt = |x: f64| x.sqrt();
        for scale in [1e-200, 1e-100, 1.0, 1e100, 1e200] {
            let scaled = |x: f64| scale * sqrt(x);
            let value = integrate_adaptive(&scaled, 0.0, 1.0, 1e-12);
            assert!((value / scale - 2.0 / 3.0).abs() < 1e-10, "scale {scale}");
        }
        let calls = std::cell::Cell::new(0usize);
        let nasty = |x: f64| {
            calls.set(calls.get() + 1);
            if x < 0.3 {
                f64::NAN
            } else {
                (1e6 * x).sin().abs()
            }
        };
        let _ = integrate_adaptive(&nasty, 0.0, 1.0, 1e-15);
        assert!(
            calls.get() <= 16 * (MAX_INTERVALS + 2),
            "{} calls",
            calls.get()
        );
        let rough = |x: f64| (1e6 * x).sin().abs();
        calls.set(0);
        let value = integrate_adaptive(&rough, 0.0, 1.0, 1e-15);
        assert!(value.is_finite());
    }
}
