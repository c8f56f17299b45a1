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

/// ∫ f on [a, b] by 8-point Gauss–Legendre, halving intervals until the halves agree with the
/// whole within `abs_tol` (scaled by the interval's share), to a depth of 30.
pub(crate) fn integrate_adaptive(f: &impl Fn(f64) -> f64, a: f64, b: f64, abs_tol: f64) -> f64 {
    let whole = gauss_legendre_8(f, a, b);
    refine(f, a, b, whole, abs_tol, 30)
}

fn refine(f: &impl Fn(f64) -> f64, a: f64, b: f64, whole: f64, abs_tol: f64, depth: u32) -> f64 {
    let mid = 0.5 * (a + b);
    let left = gauss_legendre_8(f, a, mid);
    let right = gauss_legendre_8(f, mid, b);
    let halves = left + right;
    if depth == 0 || (halves - whole).abs() <= abs_tol {
        return halves;
    }
    refine(f, a, mid, left, 0.5 * abs_tol, depth - 1)
        + refine(f, mid, b, right, 0.5 * abs_tol, depth - 1)
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
        let weights: f64 = 2.0 * WEIGHTS.iter().sum::<f64>();
        assert!((weights - 2.0).abs() < 1e-15);
    }
}
