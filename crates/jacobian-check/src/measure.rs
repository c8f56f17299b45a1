//! The reference cells' measures (area in 2D, volume in 3D, in Gmsh's reference
//! coordinates) and the measure of a cell from its determinant's Bernstein coefficients:
//! the one rule [`cell_volume`](crate::cell_volume) and the whole-mesh check's measure share.
//! A leaf.

use mesh_model::Shape;

/// The measure of a shape's reference cell in Gmsh's reference coordinates: its area in 2D,
/// its volume in 3D.
fn reference_measure(shape: Shape) -> f64 {
    match shape {
        Shape::Tri => 0.5,
        Shape::Quad => 4.0, // [−1, 1]²
        Shape::Tet => 1.0 / 6.0,
        Shape::Prism => 1.0, // the unit triangle (½) × [−1, 1]
        Shape::Hex => 8.0,
        Shape::Pyramid => 4.0 / 3.0,
        Shape::Line => 0.0,
    }
}

/// The integral of the Jacobian determinant over a cell of shape `shape` from its Bernstein
/// coefficients `c` on the whole reference cell (triangle, quadrilateral, tetrahedron, prism,
/// hexahedron, or the linear pyramid's base square): their mean times the reference measure,
/// since every Bernstein polynomial of a degree has the same integral over the simplex, the
/// box and the prism (and the linear pyramid's determinant, a biquadratic f(ξ, η) along the
/// rays from the apex, integrates to ∫∫ f dξ dη / 3, the mean of its coefficients times 4/3).
/// Not for the high-order pyramids' coefficients, which live on its collapsed box.
pub(crate) fn measure_from_coefficients(shape: Shape, c: &[f64]) -> f64 {
    c.iter().sum::<f64>() / c.len() as f64 * reference_measure(shape)
}
