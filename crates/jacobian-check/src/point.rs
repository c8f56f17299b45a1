//! The point type of the reference coordinates, shared by every module that evaluates a
//! cell: the shape functions, the Jacobian, the Bernstein regions and the pyramid's collapsed
//! coordinates. A leaf; public as `lagrange::RefPoint`.

/// A point in reference coordinates (unused coordinates are 0).
pub type RefPoint = [f64; 3];
