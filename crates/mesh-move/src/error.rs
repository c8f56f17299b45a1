//! The crate's one error type: every message is one line that names the loop, value, node or
//! cell at fault.

/// Everything that can go wrong when checking a motion or moving a mesh.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MoveError {
    /// A motion parameter is NaN or infinite.
    #[error("{what} must be a finite number, got {value}")]
    NotFinite {
        /// The parameter (`scale`, `rotate_deg`, `about.x`, `bump amplitude`, ...).
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A scale factor that is zero or negative (a negative one would mirror the loop).
    #[error("scale must be positive, got {scale}")]
    BadScale {
        /// The scale factor.
        scale: f64,
    },
    /// A bump position outside the open interval (0, 1) of the chord.
    #[error(
        "bump position must be strictly between 0 and 1 (a fraction of the chord), got {position}"
    )]
    BumpPosition {
        /// The position.
        position: f64,
    },
    /// A bump width exponent that is zero or negative.
    #[error("bump width exponent must be positive, got {width}")]
    BumpWidth {
        /// The width exponent.
        width: f64,
    },
    /// A bump amplitude larger than the limit, in chords.
    #[error("bump amplitude {amplitude} is too large: at most ±{max} chords")]
    BumpAmplitude {
        /// The amplitude in chords.
        amplitude: f64,
        /// The largest magnitude accepted ([`crate::motion::MAX_BUMP_AMPLITUDE`]).
        max: f64,
    },
    /// A Hicks–Henne bump asked of a loop that is not a wall.
    #[error("loop {name}: Hicks-Henne bumps apply to wall loops only")]
    BumpOnFarfield {
        /// The loop.
        name: String,
    },
    /// A loop that has no usable chord (fewer than 3 distinct points).
    #[error("loop {name}: no chord for a bump (fewer than 3 distinct points)")]
    NoChord {
        /// The loop.
        name: String,
    },
    /// A fault in the motion of one loop.
    #[error("loop {name}: {source}")]
    InLoop {
        /// The loop.
        name: String,
        /// What is wrong with its motion.
        source: Box<MoveError>,
    },
    /// A motion names a loop that does not exist.
    #[error("no loop named {name:?} (loops: {known})")]
    UnknownLoop {
        /// The name asked for.
        name: String,
        /// The names there are, comma-separated.
        known: String,
    },
    /// A motion names a loop whose name several loops share.
    #[error("loop name {name:?} is ambiguous: {count} loops have it")]
    AmbiguousLoop {
        /// The name.
        name: String,
        /// How many loops have it.
        count: usize,
    },
    /// Two motions for the same loop.
    #[error("loop {name} is given two motions; combine them into one")]
    MovedTwice {
        /// The loop.
        name: String,
    },
    /// A moved loop crosses itself (a bump too large for the section).
    #[error("moved loop {name} crosses itself near ({x}, {y})")]
    SelfCrossing {
        /// The loop.
        name: String,
        /// x of a common point.
        x: f64,
        /// y of a common point.
        y: f64,
    },
    /// Two moved loops cross or touch.
    #[error("moved loops {a} and {b} cross near ({x}, {y})")]
    LoopsCross {
        /// The first loop.
        a: String,
        /// The second loop.
        b: String,
        /// x of a common point.
        x: f64,
        /// y of a common point.
        y: f64,
    },
    /// A moved wall that has left the far field.
    #[error("moved wall {wall} lies outside the far field {farfield}")]
    OutsideFarfield {
        /// The wall loop.
        wall: String,
        /// The far-field loop.
        farfield: String,
    },
    /// A moved wall that lies inside another wall.
    #[error("moved wall {inner} lies inside wall {outer}")]
    InsideWall {
        /// The inner wall.
        inner: String,
        /// The outer wall.
        outer: String,
    },
    /// The movers take linear 2D meshes.
    #[error("the mesh must be linear and 2D (got order {order}, {dim}D)")]
    NotLinear2d {
        /// The mesh's order.
        order: u8,
        /// The mesh's dimension.
        dim: u8,
    },
    /// A patch whose facets do not chain into one closed loop.
    #[error("patch {name}: its boundary facets do not form one closed loop (at node {node})")]
    BrokenPatch {
        /// The patch.
        name: String,
        /// The node where the chain breaks.
        node: u32,
    },
    /// A boundary node that the boundary motion does not place.
    #[error("boundary node {node} has no target in the boundary motion")]
    MissingBoundaryNode {
        /// The node.
        node: u32,
    },
    /// A boundary motion whose arrays differ in length or that names a node twice or out of range.
    #[error("boundary motion: {what}")]
    BadBoundaryMotion {
        /// What is wrong.
        what: String,
    },
    /// A mover parameter out of range.
    #[error("{what} must be positive and finite, got {value}")]
    BadParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// The RBF interpolation system could not be solved.
    #[error("the RBF system of {size} boundary nodes is singular (two boundary nodes coincide?)")]
    SingularSystem {
        /// Its size.
        size: usize,
    },
    /// A mover that needs the mesh's layers called without them.
    #[error("the spring mover needs the mesh's layers: call move_layered with a LayeredMesh")]
    NeedsLayering,
    /// The mesh's layering does not fit the mesh.
    #[error("the mesh's layering is broken: {what}")]
    BadLayering {
        /// What is wrong.
        what: String,
    },
    /// Bad spring or solver parameters, or a failed spring solve.
    #[error("springs: {what}")]
    Springs {
        /// What went wrong.
        what: String,
    },
    /// Two meshes compared that do not share their topology.
    #[error("the meshes differ in topology: {what}")]
    TopologyMismatch {
        /// What differs.
        what: String,
    },
}

impl MoveError {
    /// This error, attributed to loop `name`.
    pub(crate) fn in_loop(self, name: &str) -> MoveError {
        MoveError::InLoop {
            name: name.to_string(),
            source: Box::new(self),
        }
    }
}
