//! Sliver removal (stage 4; a stub until then).

use crate::FillOptions;
use crate::insert::FaceSet;
use crate::mesh::Mesh;
use crate::region::Side;

/// Improves the worst dihedral angles of the inside tets.
pub(crate) fn improve(
    _mesh: &mut Mesh,
    _side: &mut Vec<Side>,
    _faces: &FaceSet,
    _first_free: usize,
    _options: &FillOptions,
) {
}
