//! The motions of a move: rigid motions with uniform scaling and Hicks–Henne bumps, read from
//! a motion file (`[[motion]]` tables) or built value by value; checked against the case
//! (values, loop names) and applied to its loops (none crossing itself or another, walls
//! inside the far field), the moved curves fitted — all before any meshing.

use boundary1d::BoundaryNodes;
use geom_curve::{ClosedCurve, Point2, loops};
use mesh_model::{LayeredMesh, Role};
use mesh_move::motion::{IDENTITY, Mat2, resolve_motions};
use mesh_move::{
    BoundaryLoop, BoundaryMotion, HicksHenne, LoopMotion, Motion, RigidMotion, Surface, move_loops,
};
use serde::Deserialize;

use crate::case::Case;
use crate::error::{Context, Result, bail, ensure, input_error};
use crate::pipeline;
use crate::source::from_toml;

/// The case with its loops moved, their curves refitted, and each loop's linear part (scale ·
/// rotation; the identity for a loop that stays or is only bumped).
pub struct MovedGeometry {
    /// The case with its loops' points moved.
    pub case: Case,
    /// The moved loops' curves.
    pub curves: Vec<ClosedCurve>,
    /// Each loop's linear part.
    linear: Vec<Mat2>,
    /// Each loop's turn, radians in [−π, π].
    turn: Vec<f64>,
}

/// The motions checked against the case (values, names) and the moved loops checked (none
/// crossing itself or another, walls inside the far field), then the moved curves fitted —
/// all before any meshing.
pub fn moved_geometry(case: &Case, motions: &[LoopMotion]) -> Result<MovedGeometry> {
    let bad = |e: mesh_move::MoveError| input_error!("bad motion: {e}");
    let loops: Vec<BoundaryLoop> = case
        .loops
        .iter()
        .map(|l| BoundaryLoop {
            name: l.name.clone(),
            role: l.role,
            points: l.points.clone(),
        })
        .collect();
    let moved = move_loops(&loops, motions).map_err(bad)?;
    let names: Vec<(&str, Role)> = loops.iter().map(|l| (l.name.as_str(), l.role)).collect();
    let resolved = resolve_motions(&names, motions).map_err(bad)?;
    let linear = resolved
        .iter()
        .map(|m| m.map_or(IDENTITY, Motion::linear))
        .collect();
    let turn = resolved
        .iter()
        .map(|m| m.map_or(0.0, Motion::turn_rad))
        .collect();
    let mut moved_case = case.clone();
    for (input, l) in moved_case.loops.iter_mut().zip(moved) {
        let ccw = |p: &[[f64; 2]]| {
            let pts: Vec<Point2<f64>> = p.iter().map(|q| Point2::new(q[0], q[1])).collect();
            loops::is_counter_clockwise(&pts)
        };
        ensure!(
            ccw(&input.points) == ccw(&l.points),
            "bad motion: loop '{}' is turned inside out by its bumps",
            input.name
        );
        input.points = l.points;
    }
    let curves = pipeline::curves(&moved_case).map_err(|e| e.context("bad motion"))?;
    Ok(MovedGeometry {
        case: moved_case,
        curves,
        linear,
        turn,
    })
}

/// Where every boundary node goes: on its loop's moved curve at its parameter `t` (the
/// boundary nodes of loop `l` are the mesh nodes after those of loops `0..l`).
pub fn boundary_targets(
    moved: &MovedGeometry,
    nodes: &[BoundaryNodes],
    layered: &LayeredMesh,
) -> Result<BoundaryMotion> {
    let mut out = BoundaryMotion {
        nodes: Vec::new(),
        targets: Vec::new(),
        linear: Vec::new(),
        turn: Vec::new(),
    };
    let loops = moved.curves.iter().zip(nodes);
    for (((curve, bn), linear), turn) in loops.zip(&moved.linear).zip(&moved.turn) {
        for &t in &bn.t {
            let p = curve.point(t);
            out.nodes.push(out.nodes.len() as u32);
            out.targets.push([p.x, p.y]);
            out.linear.push(*linear);
            out.turn.push(*turn);
        }
    }
    ensure!(
        out.nodes.len() <= layered.mesh.nodes.len(),
        "the layered mesh has fewer nodes than the boundary"
    );
    Ok(out)
}

/// `motions` at the fraction `s` of their amplitude (0: none, 1: all): each rotation angle,
/// translation and bump amplitude times `s`, each scale factor to the power `s`, the centres
/// as they are; the steps of a motion sequence.
pub fn scaled(motions: &[LoopMotion], s: f64) -> Vec<LoopMotion> {
    motions
        .iter()
        .map(|m| {
            let mut m = m.clone();
            if let Some(r) = m.motion.rigid.as_mut() {
                r.scale = r.scale.powf(s);
                r.rotate_deg *= s;
                r.translate = [r.translate[0] * s, r.translate[1] * s];
            }
            m.motion.bumps.iter_mut().for_each(|b| b.amplitude *= s);
            m
        })
        .collect()
}

/// The rigid motion of the values given (the others at the identity's), `None` when none is.
pub fn rigid(
    scale: Option<f64>,
    rotate_deg: Option<f64>,
    about: Option<[f64; 2]>,
    translate: Option<[f64; 2]>,
) -> Option<RigidMotion> {
    let given = scale.is_some() || rotate_deg.is_some() || about.is_some() || translate.is_some();
    given.then(|| RigidMotion {
        scale: scale.unwrap_or(1.0),
        rotate_deg: rotate_deg.unwrap_or(0.0),
        about: about.unwrap_or([0.0, 0.0]),
        translate: translate.unwrap_or([0.0, 0.0]),
    })
}

/// The wall of a case with one wall (the loop a motion moves when none is named).
pub fn default_loop(case: &Case) -> Result<String> {
    let walls: Vec<&str> = case
        .loops
        .iter()
        .filter(|l| l.role == Role::Wall)
        .map(|l| l.name.as_str())
        .collect();
    match walls.as_slice() {
        [one] => Ok((*one).to_string()),
        _ => bail!(
            "--loop NAME is needed: case '{}' has {} wall loops ({})",
            case.name,
            walls.len(),
            walls.join(", ")
        ),
    }
}

/// `POSITION,AMPLITUDE[,WIDTH][,upper|lower]`.
pub fn parse_bump(text: &str) -> Result<HicksHenne> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    ensure!(
        (2..=4).contains(&parts.len()),
        "give POSITION,AMPLITUDE[,WIDTH][,upper|lower]"
    );
    let num = |v: &str, what: &str| {
        v.parse::<f64>()
            .map_err(|_| input_error!("{what} {v:?} is not a number"))
    };
    let mut bump = HicksHenne::new(
        num(parts[0], "position")?,
        num(parts[1], "amplitude")?,
        Surface::Upper,
    );
    for (i, part) in parts.iter().enumerate().skip(2) {
        match *part {
            "upper" => bump.surface = Surface::Upper,
            "lower" => bump.surface = Surface::Lower,
            v if i == 2 => bump.width = num(v, "width")?,
            v => bail!("the surface is upper or lower, got {v:?}"),
        }
    }
    Ok(bump)
}

/// The motion file: `[[motion]]` tables (see the README).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MotionFile {
    motion: Vec<LoopMotionSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoopMotionSpec {
    #[serde(rename = "loop")]
    loop_name: String,
    scale: Option<f64>,
    rotate_deg: Option<f64>,
    about: Option<[f64; 2]>,
    translate: Option<[f64; 2]>,
    #[serde(default)]
    bump: Vec<BumpSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BumpSpec {
    position: f64,
    amplitude: f64,
    width: Option<f64>,
    surface: Option<SurfaceSpec>,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum SurfaceSpec {
    Upper,
    Lower,
}

/// The motions of the motion file at `path`.
pub fn load_file(path: &std::path::Path) -> Result<Vec<LoopMotion>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read motion file {}", path.display()))?;
    parse_str(&text, &path.display().to_string())
}

/// The motions of a motion file's TOML `text`; errors name `origin` (the file).
pub fn parse_str(text: &str, origin: &str) -> Result<Vec<LoopMotion>> {
    let file: MotionFile = from_toml(text, origin)?;
    ensure!(!file.motion.is_empty(), "{origin}: no [[motion]] table");
    Ok(file
        .motion
        .into_iter()
        .map(|m| {
            let rigid = rigid(m.scale, m.rotate_deg, m.about, m.translate);
            let bumps = m
                .bump
                .iter()
                .map(|b| {
                    let surface = match b.surface {
                        Some(SurfaceSpec::Lower) => Surface::Lower,
                        _ => Surface::Upper,
                    };
                    let bump = HicksHenne::new(b.position, b.amplitude, surface);
                    // the width exponent defaults in one place, `HicksHenne::new`
                    HicksHenne {
                        width: b.width.unwrap_or(bump.width),
                        ..bump
                    }
                })
                .collect();
            LoopMotion {
                loop_name: m.loop_name,
                motion: Motion { rigid, bumps },
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_move::Surface;

    #[test]
    fn bump_syntax() {
        let b = parse_bump("0.3,0.01").unwrap();
        assert_eq!((b.position, b.amplitude, b.width), (0.3, 0.01, 3.0));
        assert_eq!(b.surface, Surface::Upper);
        let b = parse_bump("0.3, -0.01, 2, lower").unwrap();
        assert_eq!((b.width, b.surface), (2.0, Surface::Lower));
        assert_eq!(
            parse_bump("0.5,0.01,lower").unwrap().surface,
            Surface::Lower
        );
        assert!(parse_bump("0.5").is_err());
        assert!(parse_bump("0.5,0.01,side").is_err());
        assert!(parse_bump("0.5,0.01,2,3").is_err());
    }
}
