//! Exact orientation predicates (Shewchuk's adaptive arithmetic from the `robust` crate): the
//! sign is always right for the given coordinates; the magnitude is an approximation of the
//! determinant.

use robust::{Coord, Coord3D};

/// The sign of an exact predicate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sign {
    /// Below zero: clockwise in 2D; see [`orient3d`] for 3D.
    Negative,
    /// Exactly zero: collinear (2D) or coplanar (3D).
    Zero,
    /// Above zero: counter-clockwise in 2D; see [`orient3d`] for 3D.
    Positive,
}

impl Sign {
    /// The sign of `value` (NaN counts as zero).
    #[inline]
    pub fn of(value: f64) -> Self {
        if value > 0.0 {
            Sign::Positive
        } else if value < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    /// The opposite sign.
    #[inline]
    pub fn reversed(self) -> Self {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
}

#[inline]
fn c2(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

#[inline]
fn c3(p: [f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// Twice the signed area of triangle `a b c`, exact in sign: positive when `a → b → c` turns
/// left (counter-clockwise), negative when it turns right, exactly 0 when collinear.
#[inline]
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    robust::orient2d(c2(a), c2(b), c2(c))
}

/// The sign of [`orient2d`].
#[inline]
pub fn orient2d_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Sign {
    Sign::of(orient2d(a, b, c))
}

/// Six times the signed volume of tetrahedron `a b c d` with the sign of
/// `(a - d) · ((b - d) × (c - d))`, exact in sign: positive when `d` lies below the plane
/// through `a b c` ("below": `a b c` appear counter-clockwise seen from above), negative above,
/// exactly 0 when the four points are coplanar. So the tetrahedron `(0,0,0) (1,0,0) (0,1,0)
/// (0,0,1)` gives a negative value (`d` above the counter-clockwise base).
#[inline]
pub fn orient3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// The sign of [`orient3d`].
#[inline]
pub fn orient3d_sign(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Sign {
    Sign::of(orient3d(a, b, c, d))
}

/// Whether `e` lies inside the sphere through `a b c d`, exact in sign: positive inside,
/// negative outside, exactly 0 when the five points are co-spherical — for `a b c d`
/// positively oriented ([`orient3d`] > 0); the sign flips for a negatively oriented
/// tetrahedron. The magnitude approximates the 5×5 lifted determinant.
#[inline]
pub fn insphere(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))
}

/// The sign of [`insphere`].
#[inline]
pub fn insphere_sign(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> Sign {
    Sign::of(insphere(a, b, c, d, e))
}
