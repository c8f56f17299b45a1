//! The design variables of a motion and the mesh sensitivities of `cargo xtask move
//! --sensitivities`: for each variable, the derivative of every node of the written mesh.
//!
//! The boundary's derivative comes from its explicit map (the motion applied to the loop's
//! points, the C2 curve refitted, each boundary node at its parameter `t`, the boundary
//! high-order nodes on the curve), differenced centrally with a step of 10⁻⁵ of the
//! variable's size — cheap, and accurate to about 10⁻¹⁰. The other linear nodes' derivative
//! is the response of the smooth mover's linearised balance (`mesh_move::Sensitivity`), and
//! the high-order nodes' is the curving's tangent with its decisions fixed
//! (`vector_adding::tangent`): neither is a finite difference of the mesh.

use crate::error::{Result, input_error};
use boundary1d::BoundaryNodes;
use mesh_model::LayeredMesh;
use mesh_move::{LoopMotion, Sensitivity};
use vector_adding::Decisions;

use super::motion::{boundary_targets, moved_geometry};
use crate::case::Case;
use crate::pipeline;

/// Which value of a loop's motion.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Rotate,
    TranslateX,
    TranslateY,
    Scale,
    Bump(usize),
}

/// One design variable: a value of one loop's motion.
#[derive(Debug, Clone)]
pub(crate) struct Variable {
    /// `loop.rotate_deg`, `loop.translate_x`, `loop.translate_y`, `loop.scale`,
    /// `loop.bump<i>` (the i-th bump's amplitude, from 1).
    pub name: String,
    motion: usize,
    kind: Kind,
}

impl Variable {
    fn value<'m>(&self, motions: &'m mut [LoopMotion]) -> Option<&'m mut f64> {
        let m = &mut motions[self.motion].motion;
        match self.kind {
            Kind::Rotate => m.rigid.as_mut().map(|r| &mut r.rotate_deg),
            Kind::TranslateX => m.rigid.as_mut().map(|r| &mut r.translate[0]),
            Kind::TranslateY => m.rigid.as_mut().map(|r| &mut r.translate[1]),
            Kind::Scale => m.rigid.as_mut().map(|r| &mut r.scale),
            Kind::Bump(i) => m.bumps.get_mut(i).map(|b| &mut b.amplitude),
        }
    }

    /// `motions` with this variable changed by `delta`.
    fn shifted(&self, motions: &[LoopMotion], delta: f64) -> Vec<LoopMotion> {
        let mut out = motions.to_vec();
        if let Some(v) = self.value(&mut out) {
            *v += delta;
        }
        out
    }
}

/// The design variables of `motions`: every rigid motion's four values, every bump's
/// amplitude.
pub(crate) fn variables(motions: &[LoopMotion]) -> Vec<Variable> {
    let mut out = Vec::new();
    for (i, lm) in motions.iter().enumerate() {
        let name = |what: &str| format!("{}.{what}", lm.loop_name);
        if lm.motion.rigid.is_some() {
            for (what, kind) in [
                ("rotate_deg", Kind::Rotate),
                ("translate_x", Kind::TranslateX),
                ("translate_y", Kind::TranslateY),
                ("scale", Kind::Scale),
            ] {
                out.push(Variable {
                    name: name(what),
                    motion: i,
                    kind,
                });
            }
        }
        for b in 0..lm.motion.bumps.len() {
            out.push(Variable {
                name: name(&format!("bump{}", b + 1)),
                motion: i,
                kind: Kind::Bump(b),
            });
        }
    }
    out
}

/// What the sensitivities are taken at.
pub(crate) struct At<'a> {
    pub case: &'a Case,
    pub motions: &'a [LoopMotion],
    pub nodes: &'a [BoundaryNodes],
    /// The moved linear mesh with its layers.
    pub moved: &'a LayeredMesh,
    /// The balance linearised there.
    pub balance: &'a Sensitivity,
    /// The curving's decisions and order, when the mesh is curved.
    pub curving: Option<(&'a Decisions, u8)>,
}

/// The derivative of every node of the written mesh for each variable.
pub(crate) fn sensitivities(
    at: &At<'_>,
    variables: &[Variable],
) -> Result<Vec<(String, Vec<[f64; 2]>)>> {
    let n = at.moved.mesh.nodes.len();
    let mut out = Vec::new();
    for var in variables {
        let mut probe = at.motions.to_vec();
        let size = var.value(&mut probe).map_or(1.0, |v| v.abs().max(1.0));
        let h = 1e-5 * size;
        let mut sides = Vec::new();
        for delta in [h, -h] {
            let geometry = moved_geometry(at.case, &var.shifted(at.motions, delta))?;
            let targets = boundary_targets(&geometry, at.nodes, at.moved)?;
            let points = match at.curving {
                Some((_, order)) => {
                    // the boundary nodes where this side of the difference puts them
                    let mut there = at.moved.clone();
                    for (&k, p) in targets.nodes.iter().zip(&targets.targets) {
                        there.mesh.nodes[k as usize] = [p[0], p[1], 0.0];
                    }
                    let loops = pipeline::loop_curves(&geometry.curves, at.nodes);
                    vector_adding::boundary_points(&there, &loops, order)
                        .map_err(|e| input_error!("sensitivities: {e}"))?
                }
                None => Vec::new(),
            };
            sides.push((targets, points));
        }
        let central =
            |p: &[f64; 2], m: &[f64; 2]| [(p[0] - m[0]) / (2.0 * h), (p[1] - m[1]) / (2.0 * h)];
        let mut d_boundary = vec![[0.0; 2]; n];
        for ((&k, p), m) in sides[0]
            .0
            .nodes
            .iter()
            .zip(&sides[0].0.targets)
            .zip(&sides[1].0.targets)
        {
            d_boundary[k as usize] = central(p, m);
        }
        let d_nodes = at.balance.respond(&d_boundary);
        let column = match at.curving {
            Some((decisions, _)) => {
                let d_points: Vec<[f64; 2]> = sides[0]
                    .1
                    .iter()
                    .zip(&sides[1].1)
                    .map(|(p, m)| central(p, m))
                    .collect();
                vector_adding::tangent(at.moved, decisions, &d_nodes, &d_points)
                    .map_err(|e| input_error!("sensitivities: {e}"))?
            }
            None => d_nodes,
        };
        out.push((var.name.clone(), column));
    }
    Ok(out)
}
