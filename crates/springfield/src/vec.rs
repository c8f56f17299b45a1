//! Tiny fixed-size vector helpers on `[f64; D]`, so that the solver and the extrusion spring
//! are written once for 2D and 3D.

#[inline]
pub(crate) fn sub<const D: usize>(a: &[f64; D], b: &[f64; D]) -> [f64; D] {
    std::array::from_fn(|i| a[i] - b[i])
}

#[inline]
pub(crate) fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}
