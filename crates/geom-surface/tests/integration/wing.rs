//! Property tests of the wing's span stations.

use geom_surface::wing::span_stations;
use proptest::prelude::*;

proptest! {
    #[test]
    fn stations_are_monotone_symmetric_and_graded(
        span in 0.01f64..20.0,
        first in 1e-6f64..0.1,
        growth in 1.0f64..1.6,
        max_ratio in 1.0f64..200.0,
    ) {
        let max_step = first * max_ratio;
        let z = span_stations(span, first, growth, max_step);
        prop_assert!(z.len() >= 2);
        prop_assert_eq!(z[0], 0.0);
        prop_assert_eq!(*z.last().unwrap(), span);
        let n = z.len() - 1;
        for k in 0..=n {
            prop_assert!((z[k] + z[n - k] - span).abs() <= 1e-12 * span, "not symmetric at {}", k);
        }
        let steps: Vec<f64> = z.windows(2).map(|w| w[1] - w[0]).collect();
        for (k, s) in steps.iter().enumerate() {
            prop_assert!(*s > 0.0, "step {} is {}", k, s);
            prop_assert!(*s <= max_step * (1.0 + 1e-9), "step {} is {} > {}", k, s, max_step);
        }
        for w in steps.windows(2) {
            let r = (w[1] / w[0]).max(w[0] / w[1]);
            prop_assert!(r <= growth * (1.0 + 1e-9), "ratio {} > {}", r, growth);
        }
        // room for the grading to the largest step and a few largest steps: the first step
        // is the first height
        let graded: f64 = (0..)
            .map(|k| first * growth.powi(k))
            .take_while(|&s| s <= max_step)
            .take(10_000)
            .sum();
        if growth > 1.05 && span >= 2.0 * graded + 25.0 * max_step {
            prop_assert!((steps[0] - first).abs() <= 1e-12 * first);
        }
    }
}
