//! How SU2 reads the orientation of a 3D cell: the corner tetrahedra its reader
//! (`CPhysicalGeometry::Check_IntElem_Orientation`) wants positive in a cell of each VTK type,
//! else it re-orients the cell. A `.su2` writer's cells must pass every one.

/// Six times the signed volume of the tetrahedron `a b c d`, positive when `a b c` turn
/// counter-clockwise seen from `d`'s side (the right-hand rule: `(b-a) × (c-a) · (d-a)`).
pub fn tet6(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    // `orient3d` is positive with `d` below the counter-clockwise base: the opposite sign
    -geom_predicates::orient3d(a, b, c, d)
}

/// The corner tetrahedra (local node indices) SU2 wants positive in a cell of VTK type
/// `vtk_type`: tetrahedron 10, pyramid 14, prism 13, hexahedron 12.
///
/// # Panics
/// On any other type.
pub fn orientation_tests(vtk_type: u8) -> &'static [[usize; 4]] {
    match vtk_type {
        10 => &[[0, 1, 2, 3]],
        14 => &[[0, 1, 2, 4], [2, 3, 0, 4]],
        13 => &[[0, 2, 1, 3], [3, 4, 5, 2]],
        12 => &[[0, 1, 2, 5], [0, 2, 3, 7], [4, 6, 5, 1], [4, 7, 6, 3]],
        _ => panic!("not a 3D VTK cell: {vtk_type}"),
    }
}

/// Whether SU2 keeps a cell of VTK type `vtk_type` with `corners` (in the file's order) as
/// written: every one of its [`orientation_tests`] positive.
pub fn kept_as_written(vtk_type: u8, corners: &[[f64; 3]]) -> bool {
    orientation_tests(vtk_type)
        .iter()
        .all(|t| tet6(corners[t[0]], corners[t[1]], corners[t[2]], corners[t[3]]) > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_right_handed_tetrahedron_is_positive() {
        let x = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        assert_eq!(tet6(x[0], x[1], x[2], x[3]), 1.0);
        assert!(kept_as_written(10, &x));
        assert!(!kept_as_written(10, &[x[0], x[2], x[1], x[3]]));
    }
}
