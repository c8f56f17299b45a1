//! What the movers' integration tests share: one rigid motion applied to every loop, and how
//! far a moved mesh is from that rigid motion of the original.

use mesh_model::Mesh;
use mesh_move::{LoopMotion, Motion, RigidMotion};

/// `rigid` for each of the loops `names`.
pub fn every_loop(names: &[&str], rigid: RigidMotion) -> Vec<LoopMotion> {
    names
        .iter()
        .map(|n| LoopMotion {
            loop_name: n.to_string(),
            motion: Motion::rigid(rigid),
        })
        .collect()
}

/// The largest distance of a node of `after` from `rigid` applied to its place in `before`.
pub fn rigid_error(before: &Mesh, after: &Mesh, rigid: &RigidMotion) -> f64 {
    (0..before.nodes.len() as u32)
        .map(|k| {
            let (want, got) = (rigid.apply(before.xy(k)), after.xy(k));
            (want[0] - got[0]).hypot(want[1] - got[1])
        })
        .fold(0.0, f64::max)
}
