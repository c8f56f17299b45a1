//! Gauss–Legendre rules on [−1, 1]: the one quadrature behind the area rules, the enclosed
//! volume and the curved high-order pyramids' volume rule. A leaf.

/// Gauss–Legendre nodes and weights on [−1, 1] with `m` points (Newton on the Legendre
/// recurrence, from the Chebyshev guesses).
pub(crate) fn gauss_legendre(m: usize) -> Vec<(f64, f64)> {
    (0..m)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (m as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=m {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                let pm = if m == 1 { x } else { p1 };
                let pm1 = if m == 1 { 1.0 } else { p0 };
                dp = m as f64 * (x * pm - pm1) / (x * x - 1.0);
                let dx = pm / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_its_degree_exactly() {
        for m in 1..=5 {
            let g = gauss_legendre(m);
            for d in 0..2 * m {
                let exact = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d as f64 + 1.0)
                };
                let got: f64 = g.iter().map(|(x, w)| w * x.powi(d as i32)).sum();
                assert!((got - exact).abs() < 1e-14, "m={m} d={d}: {got} vs {exact}");
            }
        }
    }
}
