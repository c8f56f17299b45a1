//! The per-cell quality figure that [`crate::ColourBy::MaxAngle`] colours by: the largest
//! interior angle, measured on the cell's corners (the straight-sided cell underneath a curved
//! one). It owns that measure only; Jacobians are the caller's (see
//! [`crate::ColourBy::ScaledJacobian`]).

use mesh_model::Mesh;

pub use mesh_model::measure::triangle_max_angle_deg;

/// Largest interior angle of each cell of a 2D mesh, degrees, from its corners: a triangle's
/// own; a quad is cut along its shorter diagonal and the larger of the two triangles' values
/// is kept (the convention of the report's `obtuse_hist`).
///
/// # Panics
/// If a cell names a node that does not exist (the drawing functions check this first).
pub fn max_angle_deg(mesh: &Mesh) -> Vec<f64> {
    (0..mesh.cells.len())
        .map(|i| mesh_model::measure::cell_max_angle_deg(mesh, i))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::{CellType, Dim, Shape};
    use proptest::prelude::*;

    #[test]
    fn right_isoceles_triangle_has_ninety_degrees() {
        let a = triangle_max_angle_deg([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]);
        assert!((a - 90.0).abs() < 1e-12, "{a}");
    }

    #[test]
    fn a_triangle_with_a_repeated_corner_is_the_worst() {
        assert_eq!(
            triangle_max_angle_deg([0.0, 0.0], [0.0, 0.0], [1.0, 1.0]),
            180.0
        );
    }

    #[test]
    fn a_square_cut_along_a_diagonal_gives_ninety_and_a_rhombus_its_obtuse_angle() {
        let mut m = Mesh::new(Dim::Two, 1);
        // A unit square, and a rhombus with 60° and 120° corners.
        let s = 3f64.sqrt() / 2.0;
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [10.0, 0.0, 0.0],
            [11.0, 0.0, 0.0],
            [11.5, s, 0.0],
            [10.5, s, 0.0],
        ];
        let quad = CellType::new(Shape::Quad, 1);
        m.cells.push(quad, &[0, 1, 2, 3]);
        m.cells.push(quad, &[4, 5, 6, 7]);
        let a = max_angle_deg(&m);
        assert!((a[0] - 90.0).abs() < 1e-9, "{a:?}");
        // The shorter diagonal joins the 120° corners, leaving two equilateral triangles.
        assert!((a[1] - 60.0).abs() < 1e-9, "{a:?}");
    }

    proptest! {
        #[test]
        fn a_triangle_s_largest_angle_lies_between_sixty_and_one_eighty(
            a in prop::array::uniform2(-10.0f64..10.0),
            b in prop::array::uniform2(-10.0f64..10.0),
            c in prop::array::uniform2(-10.0f64..10.0),
        ) {
            let m = triangle_max_angle_deg(a, b, c);
            prop_assert!((60.0 - 1e-9..=180.0 + 1e-9).contains(&m), "{m}");
            // Invariant under relabelling of the corners.
            let m2 = triangle_max_angle_deg(c, a, b);
            prop_assert!((m - m2).abs() < 1e-9);
        }
    }
}
