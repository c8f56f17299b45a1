//! Refinement (stage 3; a stub until then).

use crate::error::FillError;
use crate::insert::FaceSet;
use crate::mesh::Mesh;
use crate::region::Side;
use crate::{FillInput, FillOptions};

/// Refines the inside tets; the number of points added.
pub(crate) fn refine(
    _mesh: &mut Mesh,
    _side: &mut Vec<Side>,
    _faces: &FaceSet,
    _input: &FillInput,
    _options: &FillOptions,
) -> Result<usize, FillError> {
    Ok(0)
}
