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
//!   with the flat-plate skin-friction estimate at x = c ([`crate::placement`]), or is given
//!   (`--first-height`); `--growth` and `--layers` set the layers as the case file's keys do.

use std::collections::BTreeMap;
use std::path::Path;

use crate::error::{Context, Result, bail, ensure};
use mesh_model::Role;

use crate::case::{Case, LoopInput};
use crate::placement::{Frame, Placement};

pub use crate::placement::first_height;

/// Whether `spec` names an airfoil coordinate file rather than a case: a `.dat` file, or a
/// `.txt` file (as airfoil sites often serve them), read as Selig or Lednicer.
pub fn is_coordinate_file(spec: &str) -> bool {
    Path::new(spec)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dat") || e.eq_ignore_ascii_case("txt"))
}

/// The airfoil options with their defaults applied.
struct Defaulted {
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
    /// The first layer's height, instead of the one of `yplus` and `re`.
    pub first_height: Option<f64>,
    /// The ratio of one layer's height to the one below (default: the case file's, 1.3).
    pub growth: Option<f64>,
    /// The most layers grown from any boundary (default: the case file's).
    pub layers: Option<u32>,
}

/// The case of airfoil files `files` with the options `args`.
pub fn case(files: &[String], args: &AirfoilOptions) -> Result<Case> {
    let a = Defaulted {
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
    ensure!(
        args.first_height.is_none() || (args.yplus.is_none() && args.re.is_none()),
        "--first-height sets the first layer: give it or --yplus/--re, not both"
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
    let frame = Frame::of(loops.iter().map(|l| &l.points[..]))
        .with_context(|| format!("{}: the airfoil has no extent in x", files.join(", ")))?;
    let chord = frame.chord;
    for l in &mut loops {
        frame.pitch(&mut l.points, a.aoa);
    }
    let circle = frame.farfield(a.farfield).context("far field")?;
    loops.push(LoopInput {
        name: "farfield".into(),
        role: Role::Farfield,
        points: circle,
        origin: format!("circle of radius {} chords", a.farfield),
        group: String::new(),
        max_spacing: None,
    });
    let name = loops[..files.len()]
        .iter()
        .map(|l| l.name.as_str())
        .collect::<Vec<_>>()
        .join("+");
    let (x_min, y_le) = (frame.x_min, frame.y_le);
    let mut views = BTreeMap::new();
    let h = 0.02 * chord;
    views.insert(
        "le".to_string(),
        [x_min - h, y_le - h, x_min + 2.0 * h, y_le + h],
    );
    // the trailing edge: the rightmost wall point
    let walls = loops.iter().filter(|l| l.role == Role::Wall);
    let te = walls
        .flat_map(|l| l.points.iter())
        .fold(
            [f64::NEG_INFINITY, 0.0],
            |a, p| if p[0] > a[0] { *p } else { a },
        );
    views.insert(
        "te".to_string(),
        [te[0] - 2.0 * h, te[1] - h, te[0] + h, te[1] + h],
    );
    let mut case = Case::new(&name, loops, false, a.merge_walls);
    case.boundary.max_spacing = chord;
    case.layers.first_height = match args.first_height {
        Some(h) => {
            ensure!(positive(h), "--first-height {h}: must be positive");
            h
        }
        None => first_height(a.yplus, a.re, chord),
    };
    if let Some(g) = args.growth {
        case.layers.growth = g;
    }
    if let Some(n) = args.layers {
        case.layers.max_layers = n;
    }
    check_layers(&case.layers)?;
    case.placement = Placement {
        aoa_deg: Some(a.aoa),
        yplus: args.first_height.is_none().then_some(a.yplus),
        re: args.first_height.is_none().then_some(a.re),
        farfield_chords: Some(a.farfield),
        chord: Some(chord),
    };
    case.views = views;
    Ok(case)
}

/// The layers of a case of airfoil files checked as a case file's are, the faults named by
/// their flags.
fn check_layers(layers: &afsf2d::AfsfParams) -> Result<()> {
    match layers.check() {
        Err(afsf2d::AfsfError::BadParameter {
            name,
            value,
            expected,
        }) => {
            let flag = match name {
                "first_height" => "--first-height",
                "growth" => "--growth",
                "max_layers" => "--layers",
                other => other,
            };
            bail!("{flag} {value}: must be {expected}")
        }
        Err(e) => bail!("the layers: {e}"),
        Ok(()) => Ok(()),
    }
}
