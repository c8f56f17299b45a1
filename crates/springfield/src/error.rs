//! The crate's one error type: what can be wrong with the input of a spring solve.

use thiserror::Error;

/// Why a spring solve could not run.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SpringError {
    /// The per-node arrays (positions, scales, movable flags) do not have the same length.
    /// Fix: give one scale and one flag per node.
    #[error(
        "per-node arrays differ in length: {positions} positions, {scales} scales, {movable} movable flags"
    )]
    LengthMismatch {
        /// Number of positions.
        positions: usize,
        /// Number of scales.
        scales: usize,
        /// Number of movable flags.
        movable: usize,
    },
    /// A movable node has a length scale that is not a positive finite number.
    /// Fix: give every movable node its characteristic length (e.g. its ideal extrusion length).
    #[error("node {node} has length scale {scale}, which is not positive and finite")]
    BadScale {
        /// The node.
        node: usize,
        /// Its scale.
        scale: f64,
    },
    /// A parameter is out of its range (named in the message).
    /// Fix: use a value in the documented range.
    #[error("parameter `{name}` = {value} is out of range: {expected}")]
    BadParameter {
        /// The parameter's name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it should be.
        expected: &'static str,
    },
    /// The force assembly produced a NaN or infinite force or stiffness, usually because two
    /// linked nodes coincide. Fix: the caller's springs link coincident nodes.
    #[error("non-finite force or stiffness at node {node} in iteration {iteration}")]
    NonFiniteForce {
        /// The node.
        node: usize,
        /// The iteration.
        iteration: usize,
    },
    /// The Newton solve or its linearisation failed (named in the message): a start that is
    /// inverted, a stiffness that is not positive definite, the sparse factorisation.
    /// Fix: start from an admissible (uninverted) configuration.
    #[error("{0}")]
    Solver(String),
}
