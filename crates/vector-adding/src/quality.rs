//! The figure of merit every decision of the curving compares: a certificate's
//! scaled-Jacobian lower bound, 0 when the cell is not proved valid.

use jacobian_check::Certificate;

/// A certificate's scaled-Jacobian lower bound, 0 when not proved valid.
pub(crate) fn quality(c: &Certificate) -> f64 {
    c.scaled_jacobian_lower_bound().unwrap_or(0.0)
}
