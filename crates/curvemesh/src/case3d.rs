//! The 3D case file (`dimension = 3`): the wall surface (`[surface]`: a built-in sphere, cube
//! or step, a `.stl` / `.msh` file relative to the case file, or the finite wing of a 2D case),
//! the layers (`[layers]`, as
//! in 2D), the cut into standard cells (`[cut] cells = "tets" | "mixed"`) and the order
//! (`[curving] order = 1`, `2` or `3`: P2 or P3 cells curved onto the true wall). Unknown keys are errors,
//! as in 2D; every value is checked here, each fault named by its section and key.

use std::path::PathBuf;

use crate::error::{Result, bail, ensure};
use serde::Deserialize;

use crate::source::{FileSource, from_toml};
use mesh_model::Role;

/// A parsed and checked 3D case.
#[derive(Debug, Clone)]
pub struct Case3d {
    /// The case's name (from the file, else the file stem).
    pub name: String,
    /// Where the case came from, for messages.
    pub origin: String,
    /// The bodies (`[surface]`, or one `[[surface]]` table each), in order.
    pub bodies: Vec<Body>,
    /// `[farfield]`: the outer boundary, the space between it and the layers filled with
    /// tetrahedra (`None`: the domain is the layers' shell, its outer boundary `outer`).
    pub farfield: Option<Farfield>,
    /// `[layers]`: first height, growth, number of layers (the other settings the crate's).
    pub layers: afsf3d::LayerParams,
    /// `[layers] min_coverage`: the least fraction of wall nodes whose columns take every
    /// layer (where a column cannot take its next layer it stops and the rest grow on);
    /// below it the run fails with one line naming where and why (default
    /// [`MIN_COVERAGE`]).
    pub min_coverage: f64,
    /// `[cut] cells`.
    pub cells: CutCells,
    /// `[cut] max_lean_deg`: in the mixed cut, a layer cell with an extrusion edge leaning
    /// more than this off its front's normal (table 6's angle) is cut into tetrahedra and
    /// pyramids, not kept as a prism or hexahedron (default [`MAX_LEAN_DEG`]; 180 keeps all).
    pub max_lean_deg: f64,
    /// `[cut] min_corner_sj`: in the mixed cut, a layer cell that would be kept as a prism or
    /// hexahedron with a corner scaled Jacobian below this is cut into tetrahedra and
    /// pyramids instead (default [`MIN_CORNER_SJ`]; 0 keeps every such cell).
    pub min_corner_sj: f64,
    /// `[curving] order` (1 to 3).
    pub order: u8,
}

/// One body of a 3D case: where its surface comes from, where it is moved to, its name.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// The surface.
    pub source: SurfaceSource,
    /// `translate = [x, y, z]`: the body moved by this (default none).
    pub translate: [f64; 3],
    /// `name`: the boundary group of the body's `wall` patch (its other patches, a wing's
    /// tips, get it as a prefix); default `wall`, then `wall_2`, … for later bodies.
    pub name: Option<String>,
}

/// `[farfield]`: the domain's outer boundary and its triangles' size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Farfield {
    /// `box = { min, max }` or `sphere = { center, radius }`.
    pub shape: geom_surface::FarfieldShape,
    /// `max_size`: the far field's triangles' edge length, the fill's largest (default a
    /// tenth of the shape's extent).
    pub max_size: f64,
}

/// Where a body's surface comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceSource {
    /// `builtin = "sphere"`: `geom_surface::Surface::sphere(radius, refinement)`.
    Sphere {
        /// `radius` (default 1).
        radius: f64,
        /// `refinement` (default 3: 1280 triangles).
        refinement: u32,
    },
    /// `builtin = "cube"`: `Surface::cube(size, divisions, triangles)`.
    Cube {
        /// `size` (default 1).
        size: f64,
        /// `divisions` per edge (default 8).
        divisions: usize,
        /// `triangles` (default false: quads).
        triangles: bool,
    },
    /// `builtin = "step"`: `Surface::step(refinement)`.
    Step {
        /// `refinement` (default 1: quads of 0.1).
        refinement: usize,
    },
    /// `file = "body.stl"` (or `.msh`), resolved against the case file's folder.
    File(PathBuf),
    /// `wing = "naca0012"`: the finite wing of a 2D case (a built-in case's name, or a case
    /// file relative to this one), [`crate::wing::wing_surface`].
    Wing {
        /// The 2D case: a built-in name or a path.
        case: String,
        /// `span` (default 2, chords of the section).
        span: f64,
        /// `span_step`: the largest step between span stations (`None`: the section's
        /// longest edge).
        span_step: Option<f64>,
        /// `first_height`: the surface's first height — the section's spacing at corners, the span
        /// grading from each tip — in place of the 2D case's `[layers] first_height` (the
        /// dissertation's "surface" height of tables 5–7; `None`: the 2D case's).
        first_height: Option<f64>,
        /// `triangles` (default true: the side's and caps' quads split, as the tetrahedral
        /// cut of the dissertation's wing takes them).
        triangles: bool,
        /// `cap` (default `"fill"`: isotropic triangles; `"layers"`: the 2D mesher's layers
        /// inside the section), [`crate::wing::CapMesh`].
        cap: crate::wing::CapMesh,
        /// `element`: of a 2D case with several wall loops, the one (by its name) extruded
        /// (`None`: the case's only wall loop).
        element: Option<String>,
    },
}

/// What the layer cells are cut into.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CutCells {
    /// Tetrahedra only (`topo_cut::cut_to_tets`).
    Tets,
    /// Prisms and hexahedra kept, the rest tetrahedra and pyramids (`topo_cut::cut_to_mixed`).
    Mixed,
    /// Prisms kept, hexahedra halved into prisms, the rest tetrahedra: no pyramid, for solvers
    /// that take none (`topo_cut::cut_to_prisms`).
    Prisms,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile3d {
    name: Option<String>,
    #[allow(dead_code)] // read by the probe in `case`; listed so that it is a known key
    dimension: u8,
    /// a table (`[surface]`) or an array of tables (`[[surface]]`), read in [`body_keys`]
    surface: Option<toml::Value>,
    farfield: Option<FarfieldKeys>,
    #[serde(default)]
    layers: LayerKeys3d,
    #[serde(default)]
    cut: CutKeys,
    #[serde(default)]
    curving: CurvingKeys3d,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct SurfaceKeys {
    builtin: Option<String>,
    file: Option<String>,
    wing: Option<String>,
    span: Option<f64>,
    span_step: Option<f64>,
    first_height: Option<f64>,
    radius: Option<f64>,
    refinement: Option<u32>,
    size: Option<f64>,
    divisions: Option<usize>,
    triangles: Option<bool>,
    cap: Option<crate::wing::CapMesh>,
    element: Option<String>,
    translate: Option<[f64; 3]>,
    name: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FarfieldKeys {
    #[serde(rename = "box")]
    box_: Option<BoxKeys>,
    sphere: Option<SphereKeys>,
    max_size: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoxKeys {
    min: [f64; 3],
    max: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SphereKeys {
    center: [f64; 3],
    radius: f64,
}

/// `[layers]` of a 3D case: the 2D keys, `max_aspect`, `stand_off` and `smoothing`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct LayerKeys3d {
    first_height: Option<f64>,
    growth: Option<f64>,
    max_layers: Option<u32>,
    /// [`afsf3d::LayerParams::max_aspect`]; default 0 (no limit), or
    /// [`QUAD_WING_MAX_ASPECT`] for a wing with a quad side.
    max_aspect: Option<f64>,
    /// [`afsf3d::LayerParams::merge_rows`]; default 0 (each edge merged by itself), or
    /// [`QUAD_WING_MERGE_ROWS`] for a wing with a quad side.
    merge_rows: Option<f64>,
    /// [`afsf3d::LayerParams::stand_off`]: the smallest cosine wanted between a node's
    /// direction and each facet's normal around it; default 0 (none turned).
    stand_off: Option<f64>,
    /// [`afsf3d::LayerParams::smoothing`]: rounds of direction smoothing; default 8.
    /// (signed, so that a negative count is refused by name, not by the TOML reader)
    smoothing: Option<i64>,
    /// [`Case3d::min_coverage`]; default [`MIN_COVERAGE`].
    min_coverage: Option<f64>,
    /// [`afsf3d::LayerParams::fan_threshold_deg`]: a convex edge turning by more than this
    /// grows a fan of columns; default 120, 0 none.
    fan_threshold_deg: Option<f64>,
    /// [`afsf3d::LayerParams::fan_max_angle_deg`]: the widest piece of a fan; default 60.
    fan_max_angle_deg: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct CutKeys {
    cells: Option<CutCells>,
    max_lean_deg: Option<f64>,
    min_corner_sj: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct CurvingKeys3d {
    order: Option<u8>,
}

/// A wing with a quad side: each layer at most this many times the front's mean edge high
/// ([`afsf3d::LayerParams::max_aspect`], from layer 9 on for the built-in section): the 45
/// layers grow (without a limit the growth fails in layer 28, with 2 in layer 27) and their
/// corners keep a scaled Jacobian above 0.2 (0.206; 0.0145 with 1, 0.148 with 0.35, 0.1975
/// with 0.25; 0.2006 with [`QUAD_WING_MERGE_ROWS`]; `docs/3d.md`).
pub const QUAD_WING_MAX_ASPECT: f64 = 0.26;

/// The default `[cut] max_lean_deg`: the mixed mesh's prisms and hexahedra keep their side
/// edges within table 6's 30° of the wall normal (the bar); the few layer cells over
/// an edge leaning more (merged children over parents far apart) are cut instead.
pub const MAX_LEAN_DEG: f64 = 30.0;

/// A wing with a quad side: merges carried along its rows of quads up to this ratio
/// ([`afsf3d::LayerParams::merge_rows`]): at the finer cases (first heights 1e-4) the
/// trailing edge's thin quads merge one side where the layers reach their 0.00084 width, and
/// the 1° triangles left fail layer 16 (case 2) or keep a corner scaled Jacobian of 0.016
/// (case 3); carried along the rows, cases 2 and 3 grow their 45 layers (0.65: the corners
/// 0.028 / 0.022; 1.3: case 2 fails in layer 40; `docs/3d.md`).
pub const QUAD_WING_MERGE_ROWS: f64 = 1.0;

/// The default `[cut] min_corner_sj`: the mixed mesh's prisms and hexahedra keep a corner
/// scaled Jacobian of 0.2 at least (the bar on wings); the few layer cells under it
/// (the step's, squeezed at its concave edges down to 0.175; cells beside stopped columns;
/// prisms over a surface's thin triangles) are cut into tetrahedra and pyramids.
pub const MIN_CORNER_SJ: f64 = 0.2;

/// The default `[layers] min_coverage`: nine wall nodes in ten keep every layer.
pub const MIN_COVERAGE: f64 = 0.9;

/// The most rounds of direction smoothing a 3D case may ask for.
pub const MAX_SMOOTHING: u32 = 100;

/// The most layers a 3D case may ask for.
pub const MAX_LAYERS_3D: u32 = 1000;

/// The most refinements of the built-in sphere (20·4⁷ = 327 680 triangles).
pub const MAX_SPHERE_REFINEMENT: u32 = 7;

/// The most divisions per edge of the built-in cube, and refinements of the step.
pub const MAX_VOXEL_DIVISIONS: usize = 200;

/// Parses a 3D case from TOML `text` (its `dimension` is 3); `files` resolves a surface file.
pub(crate) fn parse(
    text: &str,
    origin: &str,
    files: &FileSource<'_>,
    default_name: &str,
) -> Result<Case3d> {
    let file: CaseFile3d = from_toml(text, origin)?;
    let Some(keys) = file.surface else {
        bail!(
            "{origin}: no [surface]: a 3D case needs builtin = \"sphere\" | \"cube\" | \"step\" or file = \"body.stl\""
        );
    };
    let bodies = body_keys(keys, origin)?
        .iter()
        .enumerate()
        .map(|(i, k)| body(k, i, files, origin))
        .collect::<Result<Vec<_>>>()?;
    let farfield = file.farfield.map(|f| farfield(&f, origin)).transpose()?;
    let mut layers = afsf3d::LayerParams::default();
    let l = &file.layers;
    let at = format!("{origin}: [layers]");
    layers.first_height = positive(l.first_height, layers.first_height, &at, "first_height")?;
    if let Some(g) = l.growth {
        ensure!(
            g.is_finite() && (1.0..=10.0).contains(&g),
            "{origin}: [layers] growth = {g}: must be 1 to 10"
        );
        layers.growth = g;
    }
    if let Some(n) = l.max_layers {
        ensure!(
            (1..=MAX_LAYERS_3D).contains(&n),
            "{origin}: [layers] max_layers = {n}: must be 1 to {MAX_LAYERS_3D}"
        );
        layers.layers = n as usize;
    }
    // a wing's quad side meets its caps on a rim where the plain angle weights feed back
    layers.patch_normals = bodies.iter().any(|b| {
        matches!(
            b.source,
            SurfaceSource::Wing {
                triangles: false,
                ..
            }
        )
    });
    // and its far layers, geometric, outrun the front's coarsening near the far tip
    if layers.patch_normals {
        layers.max_aspect = QUAD_WING_MAX_ASPECT;
        // and its thin quads merge one side only unless carried along their rows
        layers.merge_rows = QUAD_WING_MERGE_ROWS;
    }
    if let Some(a) = l.max_aspect {
        ensure!(
            a.is_finite() && a >= 0.0,
            "{origin}: [layers] max_aspect = {a}: must be 0 (no limit) or positive"
        );
        layers.max_aspect = a;
    }
    if let Some(r) = l.merge_rows {
        ensure!(
            r.is_finite() && (0.0..=10.0).contains(&r),
            "{origin}: [layers] merge_rows = {r}: must be 0 (off) to 10"
        );
        layers.merge_rows = r;
    }
    if let Some(c) = l.stand_off {
        ensure!(
            c.is_finite() && (0.0..1.0).contains(&c),
            "{origin}: [layers] stand_off = {c}: must be 0 (none turned) up to below 1 (a cosine)"
        );
        layers.stand_off = c;
    }
    if let Some(n) = l.smoothing {
        ensure!(
            (0..=i64::from(MAX_SMOOTHING)).contains(&n),
            "{origin}: [layers] smoothing = {n}: must be 0 to {MAX_SMOOTHING} rounds"
        );
        layers.smoothing = n as usize;
    }
    if let Some(t) = l.fan_threshold_deg {
        ensure!(
            t.is_finite() && (t == 0.0 || (30.0..180.0).contains(&t)),
            "{origin}: [layers] fan_threshold_deg = {t}: must be 0 (no fans) or 30 up to below 180 (degrees)"
        );
        layers.fan_threshold_deg = t;
    }
    if let Some(a) = l.fan_max_angle_deg {
        ensure!(
            a.is_finite() && (20.0..=90.0).contains(&a),
            "{origin}: [layers] fan_max_angle_deg = {a}: must be 20 to 90 (degrees)"
        );
        layers.fan_max_angle_deg = a;
    }
    let min_coverage = l.min_coverage.unwrap_or(MIN_COVERAGE);
    ensure!(
        (0.0..=1.0).contains(&min_coverage),
        "{origin}: [layers] min_coverage = {min_coverage}: must be 0 to 1 (a fraction of the wall nodes)"
    );
    let max_lean_deg = file.cut.max_lean_deg.unwrap_or(MAX_LEAN_DEG);
    ensure!(
        max_lean_deg.is_finite() && max_lean_deg > 0.0 && max_lean_deg <= 180.0,
        "{origin}: [cut] max_lean_deg = {max_lean_deg}: must be above 0 and at most 180 (degrees)"
    );
    let min_corner_sj = file.cut.min_corner_sj.unwrap_or(MIN_CORNER_SJ);
    ensure!(
        (0.0..1.0).contains(&min_corner_sj),
        "{origin}: [cut] min_corner_sj = {min_corner_sj}: must be at least 0 and below 1"
    );
    let order = file.curving.order.unwrap_or(1);
    check_order(order, &format!("{origin}: [curving] order = {order}"))?;
    let cells = file.cut.cells.unwrap_or(CutCells::Mixed);
    // the fronts' facets kept in shape for the prisms the mixed cut keeps (`afsf3d`'s
    // `shape`); a tetrahedral cut is judged by its dihedral angles, which the reshaped fronts
    // do not lower, and the extruded 30P30N's fill could not recover its reshaped fronts
    layers.reshape = cells != CutCells::Tets;
    Ok(Case3d {
        name: file.name.unwrap_or_else(|| default_name.to_string()),
        origin: origin.to_string(),
        bodies,
        farfield,
        layers,
        min_coverage,
        cells,
        max_lean_deg,
        min_corner_sj,
        order,
    })
}

/// `value` (or `default` when not given), refused with one line naming `at` and `key` unless
/// finite and positive.
fn positive(value: Option<f64>, default: f64, at: &str, key: &str) -> Result<f64> {
    let v = value.unwrap_or(default);
    ensure!(
        v.is_finite() && v > 0.0,
        "{at} {key} = {v}: must be positive"
    );
    Ok(v)
}

/// Refuses any order but 1, 2 and 3, naming `what` (the key or the flag).
pub fn check_order(order: u8, what: &str) -> Result<()> {
    match order {
        1..=3 => Ok(()),
        _ => bail!("{what}: must be 1, 2 or 3"),
    }
}

/// The most span steps `span_step` may make.
const MAX_SPAN_STATIONS: usize = 10_000;

/// A wing's surface keys: the 2D case it is made from, its span, the surface's first height,
/// whether the side is triangulated, how the tips are closed; a sphere's, cube's or step's key
/// is refused.
fn wing_source(
    k: &SurfaceKeys,
    name: &str,
    files: &FileSource<'_>,
    at: &str,
) -> Result<SurfaceSource> {
    ensure!(
        k.builtin.is_none() && k.file.is_none(),
        "{at}: give one of builtin, file or wing"
    );
    let case = match files {
        _ if crate::builtin::case_text(name).is_some() => name.to_string(),
        FileSource::Dir(dir) => dir.join(name).display().to_string(),
        FileSource::Builtin => bail!("{at}: wing = {name:?}: not a built-in case"),
    };
    let span = positive(k.span, 2.0, at, "span")?;
    let span_step = k
        .span_step
        .map(|h| positive(Some(h), h, at, "span_step"))
        .transpose()?;
    if let Some(step) = span_step
        && span / step > MAX_SPAN_STATIONS as f64
    {
        bail!(
            "{at}: span_step = {step} cuts the span {span} into more than {MAX_SPAN_STATIONS} steps"
        );
    }
    let first_height = k
        .first_height
        .map(|h| positive(Some(h), h, at, "first_height"))
        .transpose()?;
    let triangles = k.triangles.unwrap_or(true);
    let given = [
        ("radius", k.radius.is_some()),
        ("refinement", k.refinement.is_some()),
        ("size", k.size.is_some()),
        ("divisions", k.divisions.is_some()),
    ];
    if let Some((key, _)) = given.iter().find(|(_, g)| *g) {
        bail!("{at}: {key} does not apply to a wing");
    }
    Ok(SurfaceSource::Wing {
        case,
        span,
        span_step,
        first_height,
        triangles,
        cap: k.cap.unwrap_or_default(),
        element: k.element.clone(),
    })
}

/// A built-in surface's keys (sphere, cube or step) and the keys it takes.
fn builtin_source(
    k: &SurfaceKeys,
    builtin: &str,
    at: &str,
) -> Result<(SurfaceSource, &'static [&'static str])> {
    Ok(match builtin {
        "sphere" => {
            let radius = positive(k.radius, 1.0, at, "radius")?;
            let refinement = k.refinement.unwrap_or(3);
            ensure!(
                refinement <= MAX_SPHERE_REFINEMENT,
                "{at} refinement = {refinement}: must be 0 to {MAX_SPHERE_REFINEMENT}"
            );
            (
                SurfaceSource::Sphere { radius, refinement },
                &["radius", "refinement"],
            )
        }
        "cube" => {
            let size = positive(k.size, 1.0, at, "size")?;
            let divisions = k.divisions.unwrap_or(8);
            ensure!(
                (1..=MAX_VOXEL_DIVISIONS).contains(&divisions),
                "{at} divisions = {divisions}: must be 1 to {MAX_VOXEL_DIVISIONS}"
            );
            let triangles = k.triangles.unwrap_or(false);
            (
                SurfaceSource::Cube {
                    size,
                    divisions,
                    triangles,
                },
                &["size", "divisions", "triangles"],
            )
        }
        "step" => {
            let refinement = k.refinement.unwrap_or(1) as usize;
            ensure!(
                (1..=MAX_VOXEL_DIVISIONS / 10).contains(&refinement),
                "{at} refinement = {refinement}: must be 1 to {}",
                MAX_VOXEL_DIVISIONS / 10
            );
            (SurfaceSource::Step { refinement }, &["refinement"])
        }
        other => bail!("{at} builtin = {other:?}: must be \"sphere\", \"cube\" or \"step\""),
    })
}

/// The `surface` value: one table (`[surface]`) or several (`[[surface]]`), each read as
/// [`SurfaceKeys`].
fn body_keys(value: toml::Value, origin: &str) -> Result<Vec<SurfaceKeys>> {
    let tables = match value {
        toml::Value::Array(tables) => tables,
        table @ toml::Value::Table(_) => vec![table],
        _ => bail!("{origin}: surface must be a table ([surface]) or tables ([[surface]])"),
    };
    ensure!(
        !tables.is_empty(),
        "{origin}: no [surface]: a 3D case needs at least one body"
    );
    let several = tables.len() > 1;
    tables
        .into_iter()
        .enumerate()
        .map(|(i, t)| {
            t.try_into::<SurfaceKeys>().map_err(|e| {
                let at = if several {
                    format!("[[surface]] {}", i + 1)
                } else {
                    "[surface]".into()
                };
                crate::error::input_error!("{origin}: {at}: {}", e.message().trim())
            })
        })
        .collect()
}

/// Body `i`'s keys checked: its surface, where it moves, its name.
fn body(k: &SurfaceKeys, i: usize, files: &FileSource<'_>, origin: &str) -> Result<Body> {
    let at = format!("{origin}: [surface]");
    let at = if i > 0 { format!("{at} {}", i + 1) } else { at };
    let translate = k.translate.unwrap_or([0.0; 3]);
    ensure!(
        translate.iter().all(|x| x.is_finite()),
        "{at}: translate = {translate:?}: must be finite numbers"
    );
    if let Some(name) = &k.name {
        let ok = !name.is_empty()
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !name.starts_with(|c: char| c.is_ascii_digit());
        ensure!(
            ok,
            "{at}: name = {name:?}: must be letters, digits and '_', not starting with a digit (a boundary group's name)"
        );
        let taken = [Role::Farfield.name(), "fluid", "outer"];
        ensure!(
            !taken.iter().any(|t| name.eq_ignore_ascii_case(t)),
            "{at}: name = {name:?}: the name of another group"
        );
    }
    Ok(Body {
        source: surface_source(k, files, &at)?,
        translate,
        name: k.name.clone(),
    })
}

/// `[farfield]`'s keys checked: one shape, valid, a size that makes at most
/// [`geom_surface::MAX_FARFIELD_TRIANGLES`] triangles.
fn farfield(k: &FarfieldKeys, origin: &str) -> Result<Farfield> {
    use geom_surface::FarfieldShape;
    let at = format!("{origin}: [farfield]");
    let shape = match (&k.box_, &k.sphere) {
        (Some(b), None) => FarfieldShape::Box {
            min: b.min,
            max: b.max,
        },
        (None, Some(s)) => FarfieldShape::Sphere {
            center: s.center,
            radius: s.radius,
        },
        _ => bail!(
            "{at}: give box = {{ min = [x, y, z], max = [x, y, z] }} or sphere = {{ center = [x, y, z], radius = R }}"
        ),
    };
    if let Some(problem) = shape.problem() {
        bail!("{at}: {problem}");
    }
    let extent = shape.extent();
    let max_size = positive(k.max_size, extent / 10.0, &at, "max_size")?;
    // a sphere's area 4πr², a box's six faces at most 6 e²: two triangles per size²
    let too_many =
        2.0 * 6.0 * (extent / max_size).powi(2) > geom_surface::MAX_FARFIELD_TRIANGLES as f64;
    ensure!(
        !too_many,
        "{at} max_size = {max_size}: too small for a far field {extent} across (at most {} triangles; at least {:.3e})",
        geom_surface::MAX_FARFIELD_TRIANGLES,
        extent * (12.0 / geom_surface::MAX_FARFIELD_TRIANGLES as f64).sqrt()
    );
    Ok(Farfield { shape, max_size })
}

fn surface_source(k: &SurfaceKeys, files: &FileSource<'_>, at: &str) -> Result<SurfaceSource> {
    let at = at.to_string();
    // the keys each source takes; any other key given is refused
    if let Some(name) = &k.wing {
        return wing_source(k, name, files, &at);
    }
    let wing_only = [
        ("element", k.element.is_some()),
        ("span", k.span.is_some()),
        ("span_step", k.span_step.is_some()),
        ("first_height", k.first_height.is_some()),
        ("cap", k.cap.is_some()),
    ];
    if let Some((key, _)) = wing_only.iter().find(|(_, g)| *g) {
        bail!("{at}: {key} applies to a wing only");
    }
    let (source, allowed): (SurfaceSource, &[&str]) = match (&k.builtin, &k.file) {
        (Some(_), Some(_)) => bail!("{at}: give builtin or file, not both"),
        (None, None) => {
            bail!(
                "{at}: give builtin = \"sphere\" | \"cube\" | \"step\", file = \"body.stl\" or wing = \"naca0012\""
            )
        }
        (None, Some(name)) => {
            let path = match files {
                FileSource::Dir(dir) => dir.join(name),
                FileSource::Builtin => {
                    bail!("{at}: file = {name:?}: a built-in case names no file")
                }
            };
            (SurfaceSource::File(path), &[])
        }
        (Some(b), None) => builtin_source(k, b, &at)?,
    };
    let given = [
        ("radius", k.radius.is_some()),
        ("refinement", k.refinement.is_some()),
        ("size", k.size.is_some()),
        ("divisions", k.divisions.is_some()),
        ("triangles", k.triangles.is_some()),
    ];
    if let Some((key, _)) = given.iter().find(|(key, g)| *g && !allowed.contains(key)) {
        bail!("{at}: {key} does not apply to this surface");
    }
    Ok(source)
}
