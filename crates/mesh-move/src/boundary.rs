//! The boundary of a linear 2D mesh as loops of nodes (one per patch), and the motion of its
//! boundary nodes that the movers follow: each node's target and the linear part (rotation
//! and scale) of its body's motion.

use std::collections::HashMap;

use mesh_model::{Dim, Mesh};

use crate::MoveError;
use crate::motion::{
    BoundaryLoop, IDENTITY, LoopMotion, Mat2, check_loops, moved_points, resolve_motions,
};

/// Where every boundary node of a mesh goes.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryMotion {
    /// The boundary nodes (each once).
    pub nodes: Vec<u32>,
    /// The new position of each.
    pub targets: Vec<[f64; 2]>,
    /// The linear part (`scale · rotation`) of the motion of each node's body; the identity
    /// for fixed loops and bumps.
    pub linear: Vec<Mat2>,
    /// The turn of each node's body, radians in [−π, π] ([`crate::RigidMotion::turn_rad`]);
    /// 0 for fixed loops and bumps.
    pub turn: Vec<f64>,
}

impl BoundaryMotion {
    /// The motion that keeps every boundary node of `mesh` where it is.
    ///
    /// # Errors
    /// [`MoveError::NotLinear2d`] for a high-order or 3D mesh.
    pub fn fixed(mesh: &Mesh) -> Result<BoundaryMotion, MoveError> {
        check_linear_2d(mesh)?;
        let mut nodes: Vec<u32> = mesh.boundary.flat_nodes().to_vec();
        nodes.sort_unstable();
        nodes.dedup();
        let targets = nodes.iter().map(|&k| mesh.xy(k)).collect();
        let linear = vec![IDENTITY; nodes.len()];
        let turn = vec![0.0; nodes.len()];
        Ok(BoundaryMotion {
            nodes,
            targets,
            linear,
            turn,
        })
    }
}

pub(crate) fn check_linear_2d(mesh: &Mesh) -> Result<(), MoveError> {
    if mesh.order != 1 || mesh.dim != Dim::Two {
        return Err(MoveError::NotLinear2d {
            order: mesh.order,
            dim: mesh.dim.as_u8(),
        });
    }
    Ok(())
}

/// The nodes of patch `patch` in loop order (facet `a → b` puts `b` after `a`).
///
/// # Errors
/// [`MoveError::BrokenPatch`] when its facets do not chain into one closed loop.
pub fn patch_loop(mesh: &Mesh, patch: u32) -> Result<Vec<u32>, MoveError> {
    let name = || mesh.patches[patch as usize].name.clone();
    let mut next: HashMap<u32, u32> = HashMap::new();
    for f in mesh.patch_facets(patch) {
        let facet = mesh.boundary.get(f);
        let k = facet.corners();
        if next.insert(k[0], k[1]).is_some() {
            return Err(MoveError::BrokenPatch {
                name: name(),
                node: k[0],
            });
        }
    }
    let Some(&start) = next.keys().min() else {
        return Ok(Vec::new());
    };
    let mut out = vec![start];
    let mut at = start;
    loop {
        let Some(&b) = next.get(&at) else {
            return Err(MoveError::BrokenPatch {
                name: name(),
                node: at,
            });
        };
        if b == start {
            break;
        }
        if out.len() == next.len() {
            return Err(MoveError::BrokenPatch {
                name: name(),
                node: b,
            });
        }
        out.push(b);
        at = b;
    }
    if out.len() != next.len() {
        return Err(MoveError::BrokenPatch {
            name: name(),
            node: start,
        });
    }
    Ok(out)
}

/// The boundary loops of `mesh`, one per patch, with the patches' names and roles.
///
/// # Errors
/// [`MoveError::NotLinear2d`], [`MoveError::BrokenPatch`].
pub fn mesh_loops(mesh: &Mesh) -> Result<Vec<(Vec<u32>, BoundaryLoop)>, MoveError> {
    check_linear_2d(mesh)?;
    (0..mesh.patches.len() as u32)
        .map(|p| {
            let nodes = patch_loop(mesh, p)?;
            let patch = &mesh.patches[p as usize];
            let points = nodes.iter().map(|&k| mesh.xy(k)).collect();
            Ok((
                nodes,
                BoundaryLoop {
                    name: patch.name.clone(),
                    role: patch.role,
                    points,
                },
            ))
        })
        .collect()
}

/// The boundary nodes of `mesh` moved by `motions` (loops named by their patches; the others
/// stay). Each patch's nodes are moved as a loop by [`crate::Motion::apply`] (the bumps'
/// chord is that of the node loop), then the moved loops are checked by [`check_loops`]
/// before any node moves.
///
/// # Errors
/// [`MoveError::NotLinear2d`], [`MoveError::BrokenPatch`], the motion faults of
/// [`resolve_motions`], [`MoveError::NoChord`] and the loop faults of [`check_loops`].
pub fn boundary_motion(mesh: &Mesh, motions: &[LoopMotion]) -> Result<BoundaryMotion, MoveError> {
    let loops = mesh_loops(mesh)?;
    let names: Vec<(&str, mesh_model::Role)> = loops
        .iter()
        .map(|(_, l)| (l.name.as_str(), l.role))
        .collect();
    let resolved = resolve_motions(&names, motions)?;
    let mut moved = Vec::with_capacity(loops.len());
    let mut out = BoundaryMotion {
        nodes: Vec::new(),
        targets: Vec::new(),
        linear: Vec::new(),
        turn: Vec::new(),
    };
    for ((nodes, l), m) in loops.iter().zip(&resolved) {
        let points = moved_points(l, *m)?;
        let linear = m.map_or(IDENTITY, |m| m.linear());
        out.nodes.extend_from_slice(nodes);
        out.targets.extend_from_slice(&points);
        out.linear.extend(std::iter::repeat_n(linear, nodes.len()));
        let turn = m.map_or(0.0, |m| m.turn_rad());
        out.turn.extend(std::iter::repeat_n(turn, nodes.len()));
        moved.push(BoundaryLoop {
            points,
            ..l.clone()
        });
    }
    check_loops(&moved)?;
    Ok(out)
}
