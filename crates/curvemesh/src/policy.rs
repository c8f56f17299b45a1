//! The tool's parameter policies, shared by the case checks and the pipeline: the boundary
//! spacing that `[layers]` implies, and `[curving]` at the order asked for.

use afsf2d::AfsfParams;
use boundary1d::SpacingParams;
use vector_adding::CurvingParams;

/// The spacing of the boundary nodes given by `[boundary]` with what `[layers]` sets: the
/// spacing at sharp corners is the first layer's height, and a segment's bulge is at most
/// half the height of a full stack of layers (so that the curving can carry it up).
pub fn spacing_of(boundary: &SpacingParams, layers: &AfsfParams) -> SpacingParams {
    SpacingParams {
        first_height: layers.first_height,
        max_bulge: 0.5 * stack_height(layers),
        ..*boundary
    }
}

/// The height of a full stack of layers: `h₁·(Gⁿ − 1)/(G − 1)`.
fn stack_height(layers: &AfsfParams) -> f64 {
    let (h, g) = (layers.first_height, layers.growth);
    let n = f64::from(layers.max_layers);
    if g > 1.0 {
        h * (g.powf(n) - 1.0) / (g - 1.0)
    } else {
        h * n
    }
}

/// `[curving]` at an order, quads cut or not.
pub fn curving_of(curving: &CurvingParams, order: u8, triangles: bool) -> CurvingParams {
    CurvingParams {
        order,
        triangles,
        ..*curving
    }
}
