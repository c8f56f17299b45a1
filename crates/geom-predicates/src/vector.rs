//! Small vector operations on `[f64; D]` points, written so that every crate rounds the same
//! way (`dot` sums the products in axis order; `dist` is the square root of that sum).

/// `a - b`.
#[inline]
pub fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| a[k] - b[k])
}

/// `a + b`.
#[inline]
pub fn add<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| a[k] + b[k])
}

/// `a + t (b - a)`, computed as `a + t·(b - a)` per axis.
#[inline]
pub fn lerp<const D: usize>(a: [f64; D], b: [f64; D], t: f64) -> [f64; D] {
    std::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
}

/// The dot product, summed in axis order.
#[inline]
pub fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    let mut s = a[0] * b[0];
    for k in 1..D {
        s += a[k] * b[k];
    }
    s
}

/// The Euclidean distance `|a - b|`.
#[inline]
pub fn dist<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// The 2D cross product (perp-dot) `a.x b.y - a.y b.x`, not exact: use
/// [`crate::orient2d`] for a sign that must be right.
#[inline]
pub fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The 3D cross product `a × b`.
#[inline]
pub fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
