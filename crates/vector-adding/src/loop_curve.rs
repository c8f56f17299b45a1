//! The input of the 2D curving for one boundary loop: its curve and where its nodes lie on
//! it ([`LoopCurve`]), read by the boundary placement and the entry points.

use geom_curve::ClosedCurve;

/// The curve of one boundary loop and the parameters of its nodes, as `boundary1d` placed
/// them: node `k` of the loop is at `curve.point(t[k])`.
#[derive(Debug, Clone, Copy)]
pub struct LoopCurve<'a> {
    /// The loop's curve.
    pub curve: &'a ClosedCurve,
    /// The curve parameter of each of its boundary nodes, in node order.
    pub t: &'a [f64],
}
