//! `curvemesh mesh A.dat [B.dat ...]`: a case made from airfoil coordinate files (`.dat` or
//! `.txt`, Selig or Lednicer, told apart by `geom_curve::selig::parse`) with the defaults of the built-in
//! cases. Each file is a wall loop named after its file stem, placed by its own coordinates
//! (a multi-element airfoil is several files in one frame). Then:
//!
//! - the reference chord `c` is the x-extent of all elements together, the quarter-chord
//!   point is `(x_min + c/4, y of the leftmost point)`;
//! - `--aoa DEG` rotates every element about the quarter-chord point, positive nose up
//!   (clockwise in x-right, y-up axes);
//! - the far field is a circle of radius `--farfield R` chords about the quarter-chord point;
//! - the first layer height comes from a target y⁺ and Reynolds number (based on the chord)
//!   with the flat-plate skin-friction estimate at x = c: `Cf = 0.026 / Re^(1/7)` (Schlichting,
//!   White), `u_τ = U √(Cf/2)`, `y = y⁺ ν / u_τ` with `ν = U c / Re`, so `y = y⁺ c / (Re √(Cf/2))`.

use std::collections::BTreeMap;
use std::path::Path;

use crate::error::{Context, Result, ensure};
use mesh_model::Role;

use crate::case::{Case, LoopInput};

/// Points on the far-field circle (its geometry, not its mesh spacing).
const FARFIELD_POINTS: usize = 256;

/// Whether `spec` names an airfoil coordinate file rather than a case: a `.dat` file, or a
/// `.txt` file (as airfoil sites often serve them), read as Selig or Lednicer.
pub fn is_coordinate_file(spec: &str) -> bool {
    Path::new(spec)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dat") || e.eq_ignore_ascii_case("txt"))
}

/// The first layer height for a target y⁺ at Reynolds number `re` (based on `chord`), by the
/// flat-plate estimate of the module doc.
pub fn first_height(yplus: f64, re: f64, chord: f64) -> f64 {
    let cf = 0.026 / re.powf(1.0 / 7.0);
    yplus * chord / (re * (0.5 * cf).sqrt())
}

/// The airfoil options with their defaults applied.
struct Placement {
    aoa: f64,
    farfield: f64,
    yplus: f64,
    re: f64,
    merge_walls: bool,
}

/// How airfoil files are placed and meshed (`cargo xtask mesh FILE.dat --aoa ...`); `None`
/// takes the default named on each field.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AirfoilOptions {
    /// Angle of attack in degrees, in [-90, 90] (default 0).
    pub aoa: Option<f64>,
    /// Far-field radius in chords, at least 2 (default 30).
    pub farfield: Option<f64>,
    /// Target y+ of the first layer (default 1).
    pub yplus: Option<f64>,
    /// Reynolds number based on the chord, at least 1e3 (default 1e6).
    pub re: Option<f64>,
    /// The walls as one group `wall`.
    pub merge_walls: bool,
}

/// The case of airfoil files `files` with the options `args`.
pub fn case(files: &[String], args: &AirfoilOptions) -> Result<Case> {
    let a = Placement {
        aoa: args.aoa.unwrap_or(0.0),
        farfield: args.farfield.unwrap_or(30.0),
        yplus: args.yplus.unwrap_or(1.0),
        re: args.re.unwrap_or(1e6),
        merge_walls: args.merge_walls,
    };
    let positive = |v: f64| v.is_finite() && v > 0.0;
    ensure!(
        a.aoa.is_finite() && a.aoa.abs() <= 90.0,
        "--aoa {}: give degrees in [-90, 90]",
        a.aoa
    );
    ensure!(
        positive(a.farfield) && a.farfield >= 2.0,
        "--farfield {}: give a radius of at least 2 chords",
        a.farfield
    );
    ensure!(positive(a.yplus), "--yplus {}: must be positive", a.yplus);
    ensure!(
        positive(a.re) && a.re >= 1e3,
        "--re {}: give a Reynolds number of at least 1e3",
        a.re
    );
    let mut loops = Vec::with_capacity(files.len() + 1);
    for f in files {
        let path = Path::new(f);
        let text = std::fs::read_to_string(path).with_context(|| format!("cannot read {f}"))?;
        let points = geom_curve::selig::parse(&text).with_context(|| f.clone())?;
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("wall");
        loops.push(LoopInput {
            name: name.to_string(),
            role: Role::Wall,
            points: points.iter().map(|p| [p.x, p.y]).collect(),
            origin: f.clone(),
            group: String::new(),
            max_spacing: None,
        });
    }
    let all = || loops.iter().flat_map(|l| l.points.iter());
    let x_min = all().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    let x_max = all().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
    let chord = x_max - x_min;
    ensure!(
        positive(chord),
        "{}: the airfoil has no extent in x",
        files.join(", ")
    );
    let y_le = all().find(|p| p[0] == x_min).map_or(0.0, |p| p[1]);
    let centre = [x_min + 0.25 * chord, y_le];
    // nose up: clockwise
    let (sin, cos) = (-a.aoa.to_radians()).sin_cos();
    for l in &mut loops {
        for p in &mut l.points {
            let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
            *p = [
                centre[0] + dx * cos - dy * sin,
                centre[1] + dx * sin + dy * cos,
            ];
        }
    }
    let circle = geom_curve::circle_points(
        geom_curve::Point2::new(centre[0], centre[1]),
        a.farfield * chord,
        FARFIELD_POINTS,
    )
    .context("far field")?;
    loops.push(LoopInput {
        name: "farfield".into(),
        role: Role::Farfield,
        points: circle.iter().map(|p| [p.x, p.y]).collect(),
        origin: format!("circle of radius {} chords", a.farfield),
        group: String::new(),
        max_spacing: None,
    });
    let name = loops[..files.len()]
        .iter()
        .map(|l| l.name.as_str())
        .collect::<Vec<_>>()
        .join("+");
    let mut views = BTreeMap::new();
    let h = 0.02 * chord;
    views.insert(
        "le".to_string(),
        [x_min - h, y_le - h, x_min + 2.0 * h, y_le + h],
    );
    let mut case = Case::new(&name, loops, false, a.merge_walls);
    case.boundary.max_spacing = chord;
    case.layers.first_height = first_height(a.yplus, a.re, chord);
    case.views = views;
    Ok(case)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_height_is_the_flat_plate_estimate() {
        // Re 6e6, y+ 1: Cf = 0.026 / 6e6^(1/7) = 0.002799, u_tau = 0.03741, y = 1 / (6e6 u_tau)
        let y = first_height(1.0, 6e6, 1.0);
        assert!((y - 4.455e-6).abs() < 0.005e-6, "{y}");
        // linear in y+ and in the chord
        assert!((first_height(30.0, 6e6, 2.0) - 60.0 * y).abs() < 1e-15);
    }
}
