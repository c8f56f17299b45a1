//! The case file (TOML, `../shared/design/interface.md`): its schema, the checks of its values,
//! and turning each `[[loop]]` into the points of a closed loop. Built-in cases use the same
//! schema; their data files are embedded (see [`crate::builtin`]).

use std::collections::BTreeMap;
use std::path::Path;

use crate::error::{Context, Result, bail, ensure, input_error};
use afsf2d::AfsfParams;
use boundary1d::SpacingParams;
use mesh_model::Role;
use serde::Deserialize;
use vector_adding::CurvingParams;

use crate::builtin;
use crate::placement::{Frame, Placement};
use crate::policy::{curving_of, spacing_of};
use crate::source::{FileSource, from_toml};

/// A parsed and checked case.
#[derive(Debug, Clone)]
pub struct Case {
    /// The case's name (from the file, else the file stem).
    pub name: String,
    /// `merge_walls = true`: every wall loop in one boundary group `wall` (else one group per
    /// wall loop, named after it).
    pub merge_walls: bool,
    /// The loops, points in the order given (orientation is fixed later).
    pub loops: Vec<LoopInput>,
    /// `[boundary]`: the spacing of the boundary nodes. Its `first_height` and `max_bulge`
    /// are not the case's: the pipeline sets them from `[layers]`
    /// ([`crate::pipeline::spacing_params`]).
    pub boundary: SpacingParams,
    /// `[layers]`, and `inside` (mesh the inside of the single wall loop instead of the
    /// region between the loops): the mesher's parameters.
    pub layers: AfsfParams,
    /// `[curving] order`: 1 (linear), 2 or 3; `--order` overrides it.
    pub order: u8,
    /// `[curving]`: the curving's parameters (its `order` and `triangles` are set per run,
    /// [`crate::pipeline::curving_params`]).
    pub curving: CurvingParams,
    /// `[views]`: named rectangles `x0, y0, x1, y1` for pictures (`--png FILE@NAME`).
    pub views: BTreeMap<String, [f64; 4]>,
    /// `aoa`, `farfield` and `[layers] yplus`, `re`, when given (the report echoes them).
    pub placement: Placement,
}

/// One closed boundary loop, read and transformed.
#[derive(Debug, Clone)]
pub struct LoopInput {
    /// A name for people: the loop's `name`, else its file stem, else its role.
    pub name: String,
    /// Wall or far field.
    pub role: Role,
    /// The loop's points after scale, rotation and translation.
    pub points: Vec<[f64; 2]>,
    /// Where the points came from, for messages.
    pub origin: String,
    /// The boundary group of the loop in the mesh files (`name_groups`).
    pub group: String,
    /// This loop's largest boundary segment, overriding `[boundary] max_spacing`.
    pub max_spacing: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    name: Option<String>,
    /// 2 (the default) for this schema; 3 is read by [`crate::case3d`].
    dimension: Option<u8>,
    #[serde(default)]
    inside: bool,
    #[serde(default)]
    merge_walls: bool,
    /// The angle of attack in degrees, nose up, about the walls' quarter chord.
    aoa: Option<f64>,
    /// A far-field circle of this radius in chords about the walls' quarter chord, instead
    /// of a farfield loop.
    farfield: Option<f64>,
    #[serde(rename = "loop", default)]
    loops: Vec<LoopSpec>,
    #[serde(default)]
    boundary: BoundaryKeys,
    #[serde(default)]
    layers: LayerKeys,
    #[serde(default)]
    curving: CurvingKeys,
    #[serde(default)]
    views: BTreeMap<String, Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoopSpec {
    role: RoleSpec,
    name: Option<String>,
    file: Option<String>,
    naca: Option<String>,
    /// Points per side of a generated NACA section.
    naca_points: Option<usize>,
    /// Read as lists of any length, so that a point of three numbers is refused, not cut.
    points: Option<Vec<Vec<f64>>>,
    circle: Option<CircleSpec>,
    #[serde(default = "one")]
    scale: f64,
    #[serde(default)]
    rotate_deg: f64,
    #[serde(default)]
    translate: Option<Vec<f64>>,
    /// This loop's largest boundary segment (overrides `[boundary] max_spacing`).
    max_spacing: Option<f64>,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum RoleSpec {
    Wall,
    Farfield,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct CircleSpec {
    center: Vec<f64>,
    radius: f64,
    /// Points that define the circle as geometry (not the mesh spacing).
    #[serde(default = "circle_points_default")]
    points: usize,
}

// The sections list the keys a case file gives of each crate's parameters, under the names of
// `../shared/design/interface.md`. Their defaults and ranges are the crates' own
// (`SpacingParams`, `AfsfParams`, `CurvingParams`: `Default` and their checks): a key left
// out keeps the crate's default.

/// `[boundary]`: keys of `boundary1d::SpacingParams` (method.md §2).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoundaryKeys {
    growth: Option<f64>,
    refine_angle_deg: Option<f64>,
    max_spacing: Option<f64>,
    medial_axis: Option<bool>,
}

/// `[layers]`: keys of `afsf2d::AfsfParams` (method.md §3), and of `afsf3d::LayerParams` in 3D.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LayerKeys {
    pub(crate) first_height: Option<f64>,
    pub(crate) growth: Option<f64>,
    pub(crate) max_layers: Option<u32>,
    /// The target y⁺ of the first layer, instead of `first_height` (with `re`).
    pub(crate) yplus: Option<f64>,
    /// The Reynolds number based on the walls' chord, for `yplus` (default 1e6).
    pub(crate) re: Option<f64>,
}

/// `[curving]`: the order, and keys of `vector_adding::CurvingParams` (method.md §4).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct CurvingKeys {
    order: Option<u8>,
    min_curved_layers: Option<u32>,
    /// `CurvingParams::stop_min_scaled_jacobian`.
    stop_scaled_jacobian: Option<f64>,
    strategy: Option<vector_adding::Strategy>,
}

/// `field` set to `value` when the case gives it.
fn set<T>(field: &mut T, value: Option<T>) {
    if let Some(v) = value {
        *field = v;
    }
}

impl CaseFile {
    /// The crates' parameters with the keys the file gives.
    fn params(&self) -> (SpacingParams, AfsfParams, u8, CurvingParams) {
        let (b, l, c) = (&self.boundary, &self.layers, &self.curving);
        let mut boundary = SpacingParams::default();
        set(&mut boundary.growth, b.growth);
        set(&mut boundary.refine_angle_deg, b.refine_angle_deg);
        set(&mut boundary.max_spacing, b.max_spacing);
        set(&mut boundary.medial_axis, b.medial_axis);
        let mut layers = AfsfParams {
            inside: self.inside,
            ..AfsfParams::default()
        };
        set(&mut layers.first_height, l.first_height);
        set(&mut layers.growth, l.growth);
        set(&mut layers.max_layers, l.max_layers);
        let mut curving = CurvingParams::default();
        set(&mut curving.min_curved_layers, c.min_curved_layers);
        set(
            &mut curving.stop_min_scaled_jacobian,
            c.stop_scaled_jacobian,
        );
        set(&mut curving.strategy, c.strategy);
        (boundary, layers, c.order.unwrap_or(3), curving)
    }
}

fn one() -> f64 {
    1.0
}

fn circle_points_default() -> usize {
    256
}

/// The highest polynomial order of a run (`[curving] order` and `--order`: 1 is the linear
/// mesh).
pub const MAX_ORDER: u8 = 3;

/// The most points a generated loop (`circle = { points = N }`, `naca_points`) may have:
/// checked before they are made.
pub const MAX_GENERATED_POINTS: usize = 1_000_000;

/// `values` as exactly `N` numbers, or an error naming `what` and `form` (`[x, y]`).
fn exactly<const N: usize>(values: &[f64], what: &str, form: &str) -> Result<[f64; N]> {
    <[f64; N]>::try_from(values).map_err(|_| {
        input_error!(
            "{what} has {} numbers {values:?}: give {N}, {form}",
            values.len()
        )
    })
}

impl Case {
    /// A case of `loops` (their boundary groups named here, as for a case file) with every
    /// parameter at the case file's default, the views none.
    pub fn new(name: &str, mut loops: Vec<LoopInput>, inside: bool, merge_walls: bool) -> Case {
        let file = CaseFile {
            inside,
            ..CaseFile::default()
        };
        let (boundary, layers, order, curving) = file.params();
        name_groups(&mut loops, merge_walls);
        Case {
            name: name.to_string(),
            merge_walls,
            loops,
            boundary,
            layers,
            order,
            curving,
            views: BTreeMap::new(),
            placement: Placement::default(),
        }
    }

    /// The order of a run that asks for `asked` (`None`: the case's own), checked.
    pub fn order_of(&self, asked: Option<u8>) -> Result<u8> {
        let order = asked.unwrap_or(self.order);
        ensure!(
            (1..=MAX_ORDER).contains(&order),
            "order {order}: must be 1, 2 or 3"
        );
        Ok(order)
    }

    /// The case's name made safe for file names ([`crate::source::file_stem_of`]): the
    /// default outputs are `out/STEM.msh` and `out/STEM.json`.
    pub fn file_stem(&self) -> String {
        crate::source::file_stem_of(&self.name)
    }
}

/// Parses a case from TOML text without touching the disk: a loop's `file` names a built-in
/// data file (for the fuzz target and tests). The case is named `case` unless it says.
pub fn parse_case_str(text: &str) -> Result<Case> {
    parse(text, "case", FileSource::Builtin, "case")
}

pub(crate) fn parse(
    text: &str,
    origin: &str,
    files: FileSource<'_>,
    default_name: &str,
) -> Result<Case> {
    let file: CaseFile = from_toml(text, origin)?;
    if let Some(d) = file.dimension.filter(|&d| d != 2) {
        bail!("{origin}: dimension = {d}: must be 2 or 3");
    }
    let (boundary, mut layers, order, curving) = file.params();
    let (yplus, re) = (file.layers.yplus, file.layers.re);
    let derived = yplus.is_some() || re.is_some();
    if derived {
        check_yplus(origin, &file.layers)?;
    } else {
        check_params(origin, &boundary, &layers, order, &curving)?;
    }
    ensure!(
        !file.loops.is_empty(),
        "{origin}: no [[loop]]: a case needs at least one boundary loop"
    );
    let walls = file
        .loops
        .iter()
        .filter(|l| matches!(l.role, RoleSpec::Wall))
        .count();
    let farfields = file.loops.len() - walls;
    if file.inside {
        ensure!(
            walls == 1 && farfields == 0,
            "{origin}: inside = true needs exactly one wall loop and no farfield loop \
             (found {walls} wall and {farfields} farfield)"
        );
        ensure!(
            file.farfield.is_none(),
            "{origin}: farfield = {}: inside = true meshes the inside of the wall, with no far \
             field",
            file.farfield.unwrap_or_default()
        );
    } else if file.farfield.is_some() {
        ensure!(
            farfields == 0,
            "{origin}: farfield = {} makes the far-field circle: give it or a farfield loop, not \
             both",
            file.farfield.unwrap_or_default()
        );
    } else {
        ensure!(
            farfields == 1,
            "{origin}: a case needs exactly one farfield loop around the walls (found {farfields}); \
             or set inside = true to mesh the inside of a single wall loop"
        );
    }
    let mut views = BTreeMap::new();
    for (name, rect) in &file.views {
        let what = format!("{origin}: [views] {name}");
        views.insert(name.clone(), exactly::<4>(rect, &what, "x0, y0, x1, y1")?);
    }
    let mut loops = Vec::with_capacity(file.loops.len());
    for (i, spec) in file.loops.iter().enumerate() {
        let what = format!("{origin}: loop {}", i + 1);
        loops.push(read_loop(spec, &files, &what)?);
    }
    let placement = place(origin, &file, &mut loops, &mut layers)?;
    if derived {
        check_params(origin, &boundary, &layers, order, &curving)?;
    }
    name_groups(&mut loops, file.merge_walls);
    Ok(Case {
        name: file
            .name
            .clone()
            .unwrap_or_else(|| default_name.to_string()),
        merge_walls: file.merge_walls,
        loops,
        boundary,
        layers,
        order,
        curving,
        views,
        placement,
    })
}

/// `[layers] yplus` and `re` checked: they set the first layer instead of `first_height`.
fn check_yplus(origin: &str, l: &LayerKeys) -> Result<()> {
    ensure!(
        l.first_height.is_none(),
        "{origin}: [layers] first_height and yplus/re both set the first layer: give one"
    );
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if let Some(y) = l.yplus {
        ensure!(
            positive(y),
            "{origin}: [layers] yplus = {y}: must be positive"
        );
    }
    if let Some(re) = l.re {
        ensure!(
            positive(re) && re >= 1e3,
            "{origin}: [layers] re = {re}: give a Reynolds number of at least 1e3"
        );
    }
    Ok(())
}

/// The case file's placement of its walls, as airfoil files are placed
/// ([`crate::placement`]): `aoa` turns every wall about the walls' quarter chord, `farfield`
/// adds a far-field circle of that many chords about it, `[layers] yplus` and `re` set the
/// first layer's height from the walls' chord.
fn place(
    origin: &str,
    file: &CaseFile,
    loops: &mut Vec<LoopInput>,
    layers: &mut AfsfParams,
) -> Result<Placement> {
    let (yplus, re) = (file.layers.yplus, file.layers.re);
    if file.aoa.is_none() && file.farfield.is_none() && yplus.is_none() && re.is_none() {
        return Ok(Placement::default());
    }
    let walls = loops.iter().filter(|l| l.role == Role::Wall);
    let frame = Frame::of(walls.map(|l| &l.points[..]))
        .with_context(|| format!("{origin}: the walls have no extent in x (no chord)"))?;
    let mut placement = Placement {
        chord: Some(frame.chord),
        ..Placement::default()
    };
    if let Some(aoa) = file.aoa {
        ensure!(
            aoa.is_finite() && aoa.abs() <= 90.0,
            "{origin}: aoa = {aoa}: give degrees in [-90, 90]"
        );
        for l in loops.iter_mut().filter(|l| l.role == Role::Wall) {
            frame.pitch(&mut l.points, aoa);
        }
        placement.aoa_deg = Some(aoa);
    }
    if let Some(r) = file.farfield {
        ensure!(
            r.is_finite() && r >= 2.0,
            "{origin}: farfield = {r}: give a radius of at least 2 chords"
        );
        loops.push(LoopInput {
            name: "farfield".into(),
            role: Role::Farfield,
            points: frame.farfield(r).context("far field")?,
            origin: format!("circle of radius {r} chords"),
            group: String::new(),
            max_spacing: None,
        });
        placement.farfield_chords = Some(r);
    }
    if yplus.is_some() || re.is_some() {
        let (y, r) = (yplus.unwrap_or(1.0), re.unwrap_or(1e6));
        layers.first_height = crate::placement::first_height(y, r, frame.chord);
        placement.yplus = Some(y);
        placement.re = Some(r);
    }
    Ok(placement)
}

/// Names the boundary group of every loop, as solvers will see it (PyFR and SU2 take it as a
/// boundary name, so it is an identifier: `A-Z a-z 0-9 _`, not starting with a digit): the
/// far field is `farfield`; a wall is named after its loop (`slat`, other characters become
/// `_`), made unique with `_2`, `_3`... and never `farfield` or `fluid`; with `merge_walls`
/// every wall is `wall`.
pub(crate) fn name_groups(loops: &mut [LoopInput], merge_walls: bool) {
    let mut taken: Vec<String> = vec!["farfield".into(), "fluid".into()];
    for l in loops.iter_mut() {
        l.group = match l.role {
            Role::Farfield => "farfield".into(),
            Role::Wall if merge_walls => "wall".into(),
            Role::Wall => wall_group_name(&l.name, &mut taken),
        };
    }
}

/// The boundary group of a wall named `name` (2D loops, 3D surface groups): an identifier
/// (`A-Z a-z 0-9 _`, other characters become `_`; `wall_` in front of an empty name or one
/// starting with a digit) unlike every name in `taken` (case ignored, `_2`, `_3`... added),
/// which it joins. `taken` starts with `farfield` and `fluid`.
pub(crate) fn wall_group_name(name: &str, taken: &mut Vec<String>) -> String {
    let mut base: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if base.is_empty() || base.starts_with(|c: char| c.is_ascii_digit()) {
        base.insert_str(0, "wall_");
    }
    let mut name = base.clone();
    let mut k = 2;
    while taken.iter().any(|t| t.eq_ignore_ascii_case(&name)) {
        name = format!("{base}_{k}");
        k += 1;
    }
    taken.push(name.clone());
    name
}

/// Checks the parameters by the crates' own checks (what the pipeline will hand them), each
/// fault named by its section and key; the order's range and `min_curved_layers` against
/// `max_layers` are the case's own rules.
fn check_params(
    origin: &str,
    boundary: &SpacingParams,
    layers: &AfsfParams,
    order: u8,
    curving: &CurvingParams,
) -> Result<()> {
    let fault = |section: &str, name: &str, value: f64, rule: &str| {
        input_error!("{origin}: [{section}] {name} = {value}: {rule}")
    };
    match layers.check() {
        Err(afsf2d::AfsfError::BadParameter {
            name,
            value,
            expected,
        }) => return Err(fault("layers", name, value, &format!("must be {expected}"))),
        Err(e) => bail!("{origin}: [layers]: {e}"),
        Ok(()) => {}
    }
    match spacing_of(boundary, layers).validate() {
        Err(boundary1d::Boundary1dError::InvalidParameter {
            name,
            value,
            reason,
        }) => return Err(fault("boundary", name, value, reason)),
        Err(e) => bail!("{origin}: [boundary]: {e}"),
        Ok(()) => {}
    }
    ensure!(
        (1..=MAX_ORDER).contains(&order),
        "{origin}: [curving] order = {order}: must be 1, 2 or 3"
    );
    // checked as the pipeline runs it at order 3 (`--order` may ask for 3 whatever the case)
    match curving_of(curving, 3, false).check() {
        Err(vector_adding::CurvingError::BadParameter { name, value, rule }) => {
            let key = match name {
                "stop_min_scaled_jacobian" => "stop_scaled_jacobian",
                other => other,
            };
            return Err(fault("curving", key, value, rule));
        }
        Err(e) => bail!("{origin}: [curving]: {e}"),
        Ok(()) => {}
    }
    ensure!(
        curving.min_curved_layers <= layers.max_layers,
        "{origin}: [curving] min_curved_layers = {}: must be at most [layers] max_layers = {}",
        curving.min_curved_layers,
        layers.max_layers
    );
    Ok(())
}

/// A loop's points as given (before scale, rotation and translation) by its one source — a
/// coordinate file, NACA digits, a list of points or a circle — with where they came from
/// and the file's stem (the loop's default name).
fn loop_points(
    spec: &LoopSpec,
    files: &FileSource<'_>,
    what: &str,
) -> Result<(Vec<geom_curve::Point2<f64>>, String, Option<String>)> {
    if let Some(name) = &spec.file {
        let (text, shown) = match files {
            FileSource::Dir(dir) => {
                let path = dir.join(name);
                let text = std::fs::read_to_string(&path)
                    .with_context(|| format!("{what}: cannot read {}", path.display()))?;
                (text, path.display().to_string())
            }
            FileSource::Builtin => match builtin::data_file(name) {
                Some(text) => (text.to_string(), format!("built-in {name}")),
                None => bail!("{what}: built-in data file {name} does not exist"),
            },
        };
        let points = geom_curve::selig::parse(&text).with_context(|| shown.clone())?;
        let stem = Path::new(name)
            .file_stem()
            .and_then(|s| s.to_str())
            .map(str::to_string);
        Ok((points, shown, stem))
    } else if let Some(digits) = &spec.naca {
        let n = spec.naca_points.unwrap_or(101);
        ensure!(
            n <= MAX_GENERATED_POINTS,
            "{what}: naca_points = {n}: at most {MAX_GENERATED_POINTS}"
        );
        let points =
            geom_curve::naca::naca4(digits, n, true).with_context(|| format!("{what}: naca"))?;
        Ok((
            points,
            format!("NACA {digits}"),
            Some(format!("naca{digits}")),
        ))
    } else if let Some(points) = &spec.points {
        let pts = points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let [x, y] = exactly::<2>(p, &format!("{what}: point {}", i + 1), "[x, y]")?;
                Ok(geom_curve::Point2::new(x, y))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok((pts, format!("{what} points"), None))
    } else if let Some(c) = &spec.circle {
        // the radius's range is geom-curve's (`circle_points`), named in its error
        ensure!(
            (8..=MAX_GENERATED_POINTS).contains(&c.points),
            "{what}: circle points = {}: give 8 to {MAX_GENERATED_POINTS}",
            c.points
        );
        let [cx, cy] = exactly::<2>(&c.center, &format!("{what}: circle center"), "[x, y]")?;
        let centre = geom_curve::Point2::new(cx, cy);
        let pts = geom_curve::circle_points(centre, c.radius, c.points)
            .with_context(|| format!("{what}: circle"))?;
        Ok((pts, format!("circle of radius {}", c.radius), None))
    } else {
        bail!("{what}: give one of file, naca, points or circle")
    }
}

fn read_loop(spec: &LoopSpec, files: &FileSource<'_>, what: &str) -> Result<LoopInput> {
    let sources = [
        spec.file.is_some(),
        spec.naca.is_some(),
        spec.points.is_some(),
        spec.circle.is_some(),
    ];
    let given = sources.iter().filter(|&&s| s).count();
    ensure!(
        given == 1,
        "{what}: give exactly one of file, naca, points or circle (found {given})"
    );
    ensure!(
        spec.scale.is_finite() && spec.scale > 0.0,
        "{what}: scale = {}: must be positive",
        spec.scale
    );
    let translate = match &spec.translate {
        Some(t) => exactly::<2>(t, &format!("{what}: translate"), "[dx, dy]")?,
        None => [0.0, 0.0],
    };
    ensure!(
        spec.rotate_deg.is_finite() && translate.iter().all(|v| v.is_finite()),
        "{what}: rotate_deg and translate must be finite numbers"
    );
    if let Some(cap) = spec.max_spacing {
        ensure!(
            cap.is_finite() && cap > 0.0,
            "{what}: max_spacing = {cap}: must be positive"
        );
    }
    let role = match spec.role {
        RoleSpec::Wall => Role::Wall,
        RoleSpec::Farfield => Role::Farfield,
    };
    let (raw, origin, stem) = loop_points(spec, files, what)?;
    let (s, (sin, cos)) = (spec.scale, spec.rotate_deg.to_radians().sin_cos());
    let points = raw
        .iter()
        .map(|p| {
            let (x, y) = (p.x * s, p.y * s);
            [
                x * cos - y * sin + translate[0],
                x * sin + y * cos + translate[1],
            ]
        })
        .collect();
    let name = spec
        .name
        .clone()
        .or(stem)
        .unwrap_or_else(|| role.name().to_string());
    Ok(LoopInput {
        name,
        role,
        points,
        origin,
        group: String::new(),
        max_spacing: spec.max_spacing,
    })
}
