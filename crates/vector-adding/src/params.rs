//! The knobs of the curving: order, how many layers at least stay curved next to walls, which
//! vector strategy, and when a pipe may stop.

use serde::{Deserialize, Serialize};

use crate::error::CurvingError;

/// How the high-order nodes of a cell's top edge (and of the diagonal of a cut quadrilateral)
/// follow from the curved edge below it.
///
/// Both strategies give the same top edge: the node at fraction `s` of the bottom edge moves
/// by `(1 − s)·V_left + s·V_right`, V being the two extrusion edges, which amounts to laying
/// the bottom edge's deviation from its chord onto the top chord. They differ only on the
/// diagonal of a quadrilateral cut into two triangles, when that diagonal cannot stay
/// straight.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Strategy {
    /// The diagonal follows the quadrilateral's own map (the blend of its bottom and top
    /// edges), so both triangles share the quadrilateral's parametrisation (the
    /// dissertation's straighter trace).
    #[default]
    TwoVector,
    /// The diagonal follows the map of the lower triangle alone: bottom edge plus one
    /// extrusion vector (the dissertation's first strategy, with its zig-zag trace).
    OneVector,
}

/// Parameters of [`crate::curve_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CurvingParams {
    /// Polynomial order of the output, 2 or 3.
    pub order: u8,
    /// Next to walls, the number of cell layers that keep a curved bottom edge at least
    /// (the boundary edge counts as the first): a pipe never stops below it unless the cells
    /// would be invalid. Far-field pipes stop as soon as a straight top is valid. Default 2.
    pub min_curved_layers: u32,
    /// Vector strategy. Default [`Strategy::TwoVector`].
    pub strategy: Strategy,
    /// A pipe stops (the cell gets a straight top edge) when the cell with a straight top
    /// is certified valid with a scaled Jacobian of at least this, in (0, 1]. Default 0.5: the
    /// stop cell, the least good of its pipe, keeps at least half its largest Jacobian.
    pub stop_min_scaled_jacobian: f64,
    /// Cut every quadrilateral into two triangles along its shorter diagonal (kept straight
    /// where both triangles are valid with it straight, with a scaled Jacobian of at least
    /// `stop_min_scaled_jacobian`). Default false.
    pub triangles: bool,
    /// The certified check used for every decision (default: subdivision depth 4; a cell
    /// left undecided counts as not valid, so a shallow depth only curves more).
    #[serde(skip)]
    pub certify: jacobian_check::CertifyParams,
}

impl Default for CurvingParams {
    fn default() -> Self {
        CurvingParams {
            order: 3,
            min_curved_layers: 2,
            strategy: Strategy::TwoVector,
            stop_min_scaled_jacobian: 0.5,
            triangles: false,
            certify: jacobian_check::CertifyParams {
                max_depth: 4,
                ..jacobian_check::CertifyParams::default()
            },
        }
    }
}

impl CurvingParams {
    /// Checks every parameter's range.
    ///
    /// # Errors
    /// [`CurvingError::BadParameter`] naming the first parameter out of range.
    pub fn check(&self) -> Result<(), CurvingError> {
        if !(2..=3).contains(&self.order) {
            return Err(CurvingError::BadParameter {
                name: "order",
                value: self.order as f64,
                rule: "must be 2 or 3",
            });
        }
        if self.min_curved_layers > 1000 {
            return Err(CurvingError::BadParameter {
                name: "min_curved_layers",
                value: self.min_curved_layers as f64,
                rule: "must be at most 1000",
            });
        }
        let q = self.stop_min_scaled_jacobian;
        if !(q > 0.0 && q <= 1.0) {
            return Err(CurvingError::BadParameter {
                name: "stop_min_scaled_jacobian",
                value: q,
                rule: "must lie in (0, 1]",
            });
        }
        Ok(())
    }
}
