//! Test code only — the one dev-only kit the crates' integration tests and benches share:
//! the geometry fixtures of `fixtures/geometry` ([`fixtures`]), loop generators and their
//! proptest strategies ([`shapes`]), layered 3D polyhedral meshes ([`layered`]), the property checks every mesh must pass ([`checks`]), SU2's orientation tests of a 3D cell ([`su2`]),
//! and [`assert_near!`].
//!
//! Dev-only: a `[dev-dependencies]` entry, never published. It depends on `mesh-model`,
//! `geom-curve` and `jacobian-check`, so the *unit* tests of those crates cannot use it (that
//! would be a second copy of the crate); their integration tests (`tests/*.rs`) can. The
//! built-in cases run through the tool's stages are `test-cases`'.

pub mod checks;
pub mod fixtures;
pub mod layered;
pub mod shapes;
pub mod su2;

/// Asserts that two numbers differ by at most `tol`, naming both and the difference:
/// `assert_near!(a, b, 1e-12)` or `assert_near!(a, b, 1e-12, "at {i}")`.
#[macro_export]
macro_rules! assert_near {
    ($a:expr, $b:expr, $tol:expr $(,)?) => {
        $crate::assert_near!($a, $b, $tol, "")
    };
    ($a:expr, $b:expr, $tol:expr, $($msg:tt)+) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        assert!(
            (a - b).abs() <= tol,
            "{} = {a:e} and {} = {b:e} differ by {:e} > {tol:e} {}",
            stringify!($a),
            stringify!($b),
            (a - b).abs(),
            format!($($msg)+)
        );
    }};
}

#[cfg(test)]
mod tests {
    #[test]
    fn assert_near_passes_within_and_names_the_gap_beyond() {
        assert_near!(1.0, 1.0 + 1e-13, 1e-12);
        let caught = std::panic::catch_unwind(|| assert_near!(1.0, 1.1, 1e-3, "case {}", 7));
        let message = *caught.unwrap_err().downcast::<String>().unwrap();
        assert!(
            message.contains("differ by") && message.contains("case 7"),
            "{message}"
        );
    }
}
