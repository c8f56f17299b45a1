//! Colours: the perceptual colour map, the fixed colours of the picture (edges, boundary
//! roles, no-value grey), the per-cell colours of each [`ColourBy`] choice and the legend that
//! explains them. It owns no layout and no drawing.

use mesh_model::{Mesh, NONE, Role};

use crate::error::DrawError;
use crate::params::ColourBy;
use crate::quality::max_angle_deg;

/// An sRGB colour, 8 bits a channel.
pub(crate) type Rgb = [u8; 3];

/// Background.
pub(crate) const WHITE: Rgb = [255, 255, 255];
/// Mesh edges.
pub(crate) const EDGE: Rgb = [48, 48, 48];
/// Text, ticks, frames of the legend and scale bar.
pub(crate) const INK: Rgb = [25, 25, 25];
/// Plot-area frame.
pub(crate) const FRAME: Rgb = [150, 150, 150];
/// Cells with no value (the fill in the layer colouring, NaN).
pub(crate) const NO_VALUE: Rgb = [200, 200, 200];
/// Cells of layers grown from the far field, in the layer colouring (which counts the walls'
/// layers).
pub(crate) const FARFIELD_LAYERS: Rgb = [188, 204, 230];
/// Cells whose scaled Jacobian is negative (inverted).
pub(crate) const INVERTED: Rgb = [215, 25, 28];

/// The stroke colour of a boundary loop of the given role.
pub(crate) fn role_colour(role: Role) -> Rgb {
    match role {
        Role::Wall => [0, 0, 0],
        Role::Farfield => [20, 50, 140],
    }
}

/// matplotlib's viridis map (public domain, CC0) sampled at 17 evenly spaced points.
const VIRIDIS: [Rgb; 17] = [
    [68, 1, 84],
    [72, 24, 106],
    [71, 45, 123],
    [66, 64, 134],
    [59, 82, 139],
    [51, 99, 141],
    [44, 114, 142],
    [38, 130, 142],
    [33, 145, 140],
    [31, 160, 136],
    [40, 174, 128],
    [63, 188, 115],
    [94, 201, 98],
    [132, 212, 75],
    [173, 220, 48],
    [216, 226, 25],
    [253, 231, 37],
];

/// How much of white is mixed into the map's colours for cell fills: the darkest viridis
/// colours would otherwise hide the dark edges drawn over them.
const FILL_LIGHTEN: f64 = 0.22;

/// Mixes `fraction` of white into `c`.
pub(crate) fn lighten(c: Rgb, fraction: f64) -> Rgb {
    c.map(|v| (v as f64 + (255.0 - v as f64) * fraction).round() as u8)
}

/// The map's colour at `t` in [0, 1] (clamped), as used for cell fills.
pub(crate) fn map_colour(t: f64) -> Rgb {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mixed = [0, 1, 2].map(|k| (a[k] as f64 + (b[k] as f64 - a[k] as f64) * f).round() as u8);
    lighten(mixed, FILL_LIGHTEN)
}

/// How the legend's bar is painted, bottom (minimum) to top.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum BarPaint {
    /// A smooth gradient through these stops (fraction along the bar, colour).
    Gradient(Vec<(f64, Rgb)>),
    /// Equal blocks, bottom to top.
    Blocks(Vec<Rgb>),
}

/// A tick of the legend bar.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tick {
    /// Position along the bar, 0 at the bottom, 1 at the top.
    pub frac: f64,
    /// Its label.
    pub label: String,
    /// Labels of major ticks are placed first; others only where they do not collide.
    pub major: bool,
}

/// What the legend shows.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Legend {
    /// The heading above the bar.
    pub title: String,
    /// The bar.
    pub bar: BarPaint,
    /// Ticks along the bar.
    pub ticks: Vec<Tick>,
    /// Extra colour keys below the bar (far field, fill, inverted, NaN).
    pub swatches: Vec<(Rgb, String)>,
}

/// The fill colour of every cell (`None`: not filled) and the legend that explains them.
pub(crate) struct CellColours {
    /// One entry per cell, or empty when cells are not filled.
    pub per_cell: Vec<Option<Rgb>>,
    /// The legend, when cells are coloured.
    pub legend: Option<Legend>,
}

/// Colours the cells of `mesh` as `by` asks; its last `fill_cells` cells are its filled
/// region (for the layer colouring).
pub(crate) fn cell_colours(
    mesh: &Mesh,
    by: &ColourBy,
    fill_cells: usize,
) -> Result<CellColours, DrawError> {
    let n = mesh.cells.len();
    let check_len = |what, len| {
        if len == n {
            Ok(())
        } else {
            Err(DrawError::LengthMismatch {
                what,
                len,
                expected: n,
                per: "cell",
            })
        }
    };
    match by {
        ColourBy::None => Ok(CellColours {
            per_cell: Vec::new(),
            legend: None,
        }),
        ColourBy::Layer => {
            check_len(
                "mesh.cell_layer (needed to colour by layer)",
                mesh.cell_layer.len(),
            )?;
            Ok(layer_colours(mesh, n.saturating_sub(fill_cells)))
        }
        ColourBy::MaxAngle => {
            // the scale fits the data (whole 5° steps within 60–180°), and small angles, the
            // good ones, take the light end of the map, as a high scaled Jacobian does
            let values = max_angle_deg(mesh);
            let (lo, hi) = angle_range(&values);
            let ticks = nice_ticks(lo, hi, 5)
                .into_iter()
                .map(|t| Tick {
                    label: format!("{}°", t.label),
                    ..t
                })
                .collect();
            Ok(continuous(&values, lo, hi, "max angle", ticks, None, true))
        }
        ColourBy::ScaledJacobian(values) => {
            check_len("the scaled-Jacobian values", values.len())?;
            let ticks = nice_ticks(0.0, 1.0, 5);
            Ok(continuous(
                values,
                0.0,
                1.0,
                "scaled jacobian",
                ticks,
                Some((INVERTED, "< 0 (inverted)")),
                false,
            ))
        }
        ColourBy::Categories {
            values,
            names,
            label,
        } => {
            check_len("the cell categories", values.len())?;
            Ok(category_colours(values, names, label))
        }
        ColourBy::CellValues { values, label } => {
            check_len("the cell values", values.len())?;
            let (lo, hi) = finite_range(values);
            let ticks = nice_ticks(lo, hi, 5);
            Ok(continuous(values, lo, hi, label, ticks, None, false))
        }
    }
}

/// The angle scale of `values` (degrees): their range out to whole 5° steps, within
/// [60, 180], at least 10° wide.
fn angle_range(values: &[f64]) -> (f64, f64) {
    let (lo, hi) = finite_range(values);
    let lo = ((lo / 5.0).floor() * 5.0).clamp(60.0, 170.0);
    let hi = ((hi / 5.0).ceil() * 5.0).clamp(lo + 10.0, 180.0);
    (lo, hi)
}

/// Range of the finite values, widened when they are all equal; [0, 1] when there is none.
fn finite_range(values: &[f64]) -> (f64, f64) {
    let (lo, hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        (0.0, 1.0)
    } else if lo == hi {
        let pad = if lo == 0.0 { 0.5 } else { 0.01 * lo.abs() };
        (lo - pad, hi + pad)
    } else {
        (lo, hi)
    }
}

/// Colours values on `[lo, hi]`; NaN in grey, and values below `lo` in `below.0` when given
/// (otherwise clamped). The map runs dark to light from `lo` to `hi`, or light to dark when
/// `high_is_bad`: light is always the good end.
fn continuous(
    values: &[f64],
    lo: f64,
    hi: f64,
    title: &str,
    ticks: Vec<Tick>,
    below: Option<(Rgb, &str)>,
    high_is_bad: bool,
) -> CellColours {
    let map = |t: f64| map_colour(if high_is_bad { 1.0 - t } else { t });
    let mut any_nan = false;
    let mut any_below = false;
    let per_cell = values
        .iter()
        .map(|&v| {
            Some(if v.is_nan() {
                any_nan = true;
                NO_VALUE
            } else if let (true, Some((c, _))) = (v < lo, below) {
                any_below = true;
                c
            } else {
                map(((v - lo) / (hi - lo)).clamp(0.0, 1.0))
            })
        })
        .collect();
    let stops = (0..=16)
        .map(|i| {
            let t = i as f64 / 16.0;
            (t, map(t))
        })
        .collect();
    let mut swatches = Vec::new();
    if let (Some((c, label)), true) = (below, any_below) {
        swatches.push((c, label.to_string()));
    }
    if any_nan {
        swatches.push((NO_VALUE, "no value".to_string()));
    }
    CellColours {
        per_cell,
        legend: Some(Legend {
            title: title.to_string(),
            bar: BarPaint::Gradient(stops),
            ticks,
            swatches,
        }),
    }
}

/// One colour per category, spread over the map; a value without a name in grey.
fn category_colours(values: &[u32], names: &[String], label: &str) -> CellColours {
    let n = names.len();
    let colour = |i: usize| map_colour(i as f64 / n.saturating_sub(1).max(1) as f64);
    let per_cell = values
        .iter()
        .map(|&v| {
            Some(if (v as usize) < n {
                colour(v as usize)
            } else {
                NO_VALUE
            })
        })
        .collect();
    let ticks = names
        .iter()
        .enumerate()
        .map(|(i, name)| Tick {
            frac: (i as f64 + 0.5) / n.max(1) as f64,
            label: name.clone(),
            major: true,
        })
        .collect();
    CellColours {
        per_cell,
        legend: Some(Legend {
            title: label.to_string(),
            bar: BarPaint::Blocks((0..n).map(colour).collect()),
            ticks,
            swatches: Vec::new(),
        }),
    }
}

/// Where a cell stands in the layer colouring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LayerOf {
    /// In layer `n` (1 = on the boundary) grown from a wall, or from a boundary of unknown
    /// role when the mesh has no pipes.
    Wall(u32),
    /// In a layer grown from the far field.
    Farfield,
    /// In the filled region, or in no layer.
    Fill,
}

/// Each cell's place in the layer colouring: a cell from `fill_from` on, or with no layer,
/// is the fill; the others are in layer `cell_layer + 1` of the boundary their pipe starts
/// at (`cell_pipe`, a boundary facet, gives its role); without pipes every layered cell
/// counts as a wall's.
fn layers_of(mesh: &Mesh, fill_from: usize) -> Vec<LayerOf> {
    let piped = mesh.cell_pipe.len() == mesh.cell_layer.len();
    let role = |pipe: u32| {
        let patch = mesh.boundary_patch.get(pipe as usize)?;
        mesh.patches.get(*patch as usize).map(|p| p.role)
    };
    let cell = |(i, &layer): (usize, &u32)| {
        if i >= fill_from || layer == NONE {
            return LayerOf::Fill;
        }
        if !piped {
            return LayerOf::Wall(layer + 1);
        }
        match role(mesh.cell_pipe[i]) {
            Some(Role::Wall) => LayerOf::Wall(layer + 1),
            Some(Role::Farfield) => LayerOf::Farfield,
            None => LayerOf::Fill,
        }
    };
    mesh.cell_layer.iter().enumerate().map(cell).collect()
}

/// Layer colours, counted from the walls: the map from layer 1 (on the wall) to the
/// outermost wall layer, odd layers lighter; the layers grown from the far field in one
/// light blue, the fill in grey, each with its swatch. Cells from `fill_from` on are the
/// fill.
fn layer_colours(mesh: &Mesh, fill_from: usize) -> CellColours {
    let places = layers_of(mesh, fill_from);
    let max_layer = places
        .iter()
        .filter_map(|p| match p {
            LayerOf::Wall(l) => Some(*l),
            _ => None,
        })
        .max()
        .unwrap_or(1);
    let colour = |layer: u32| {
        let c = map_colour((layer - 1) as f64 / (max_layer - 1).max(1) as f64);
        if layer.is_multiple_of(2) {
            lighten(c, 0.3)
        } else {
            c
        }
    };
    let per_cell = places
        .iter()
        .map(|p| {
            Some(match *p {
                LayerOf::Wall(l) => colour(l),
                LayerOf::Farfield => FARFIELD_LAYERS,
                LayerOf::Fill => NO_VALUE,
            })
        })
        .collect();
    let count = max_layer as usize;
    let bar = if count <= 200 {
        BarPaint::Blocks((1..=max_layer).map(colour).collect())
    } else {
        BarPaint::Gradient(
            (0..=16)
                .map(|i| (i as f64 / 16.0, map_colour(i as f64 / 16.0)))
                .collect(),
        )
    };
    let step = nice_step(max_layer as f64 / 6.0).max(1.0) as u32;
    let ticks = (1..=max_layer)
        .filter(|l| l % step == 0 || *l == 1 || *l == max_layer)
        .map(|l| Tick {
            frac: (l as f64 - 0.5) / count as f64,
            label: l.to_string(),
            major: l == 1 || l == max_layer,
        })
        .collect();
    let mut swatches = Vec::new();
    if places.contains(&LayerOf::Farfield) {
        swatches.push((FARFIELD_LAYERS, FARFIELD_SWATCH.to_string()));
    }
    if places.contains(&LayerOf::Fill) {
        swatches.push((NO_VALUE, FILL_SWATCH.to_string()));
    }
    CellColours {
        per_cell,
        legend: Some(Legend {
            title: LAYER_TITLE.to_string(),
            bar,
            ticks,
            swatches,
        }),
    }
}

/// The layer legend's heading: the layers are counted from the walls, the first is 1.
pub(crate) const LAYER_TITLE: &str = "layer from wall";
/// The layer legend's swatches.
pub(crate) const FARFIELD_SWATCH: &str = "far field";
pub(crate) const FILL_SWATCH: &str = "fill";

/// The "nice" number (1, 2 or 5 × 10^k) nearest below-or-at `x` (x > 0); 0 for x <= 0.
pub(crate) fn nice_step(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 || !x.is_finite() {
        return 0.0;
    }
    let decade = 10f64.powf(x.log10().floor());
    let m = x / decade;
    let nice = if m >= 5.0 {
        5.0
    } else if m >= 2.0 {
        2.0
    } else {
        1.0
    };
    nice * decade
}

/// Ticks over `[lo, hi]`: both ends (major, labelled with more digits) and about `count` nice
/// round values between.
pub(crate) fn nice_ticks(lo: f64, hi: f64, count: usize) -> Vec<Tick> {
    let span = hi - lo;
    let step = nice_step(span / count as f64);
    let mut ticks = vec![
        Tick {
            frac: 0.0,
            label: format_number(lo, step / 10.0),
            major: true,
        },
        Tick {
            frac: 1.0,
            label: format_number(hi, step / 10.0),
            major: true,
        },
    ];
    if step > 0.0 {
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        for k in first..=last.min(first + 4 * count as i64) {
            let v = k as f64 * step;
            let frac = (v - lo) / span;
            if frac > 1e-9 && frac < 1.0 - 1e-9 {
                ticks.push(Tick {
                    frac,
                    label: format_number(v, step),
                    major: false,
                });
            }
        }
    }
    ticks
}

/// `v` written with as many digits as a resolution of `step` needs; exponent form for very
/// large or very small magnitudes. Trailing zeros of the fraction are dropped.
pub(crate) fn format_number(v: f64, step: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let magnitude = v.abs().log10().floor();
    let resolution = if step > 0.0 && step.is_finite() {
        step.abs().log10().floor()
    } else {
        magnitude - 3.0
    };
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        let digits = (magnitude - resolution).clamp(0.0, 4.0) as usize;
        let s = format!("{v:.digits$e}");
        // Trim zeros in the mantissa: "1.50e-5" -> "1.5e-5".
        if let Some((mantissa, exponent)) = s.split_once('e') {
            let mantissa = if mantissa.contains('.') {
                mantissa.trim_end_matches('0').trim_end_matches('.')
            } else {
                mantissa
            };
            return format!("{mantissa}e{exponent}");
        }
        return s;
    }
    let decimals = (-resolution).clamp(0.0, 8.0) as usize;
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" { "0".into() } else { s }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(nice_step(7.3), 5.0);
        assert_eq!(nice_step(0.031), 0.02);
        assert_eq!(nice_step(1.0), 1.0);
        assert_eq!(nice_step(0.0), 0.0);
    }

    #[test]
    fn numbers_are_written_with_the_digits_their_step_needs() {
        assert_eq!(format_number(0.25, 0.05), "0.25");
        assert_eq!(format_number(3.0, 1.0), "3");
        assert_eq!(format_number(1.5e-5, 1e-6), "1.5e-5");
        assert_eq!(format_number(-0.0001, 1.0), "-1e-4");
        assert_eq!(format_number(250000.0, 50000.0), "2.5e5");
        assert_eq!(format_number(0.0, 1.0), "0");
    }

    #[test]
    fn the_map_runs_from_dark_to_light() {
        let lum = |c: Rgb| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64;
        let mut prev = lum(map_colour(0.0));
        for i in 1..=50 {
            let l = lum(map_colour(i as f64 / 50.0));
            assert!(l > prev, "luminance not increasing at {i}");
            prev = l;
        }
    }

    /// Cells with the layers and pipes `afsf2d` gives them (no shapes: the colouring reads
    /// only the records): facet 0 on a wall, facet 1 on the far field.
    fn layered(cell_layer: Vec<u32>, cell_pipe: Vec<u32>) -> Mesh {
        let mut mesh = Mesh::new(mesh_model::Dim::Two, 1);
        mesh.cell_layer = cell_layer;
        mesh.cell_pipe = cell_pipe;
        mesh.boundary_patch = vec![0, 1];
        for (name, role) in [("wall", Role::Wall), ("farfield", Role::Farfield)] {
            mesh.patches.push(mesh_model::Patch {
                name: name.into(),
                role,
            });
        }
        mesh
    }

    #[test]
    fn layers_count_from_the_walls_only_and_the_far_field_and_fill_are_told_apart() {
        // three wall layers (0-based 0, 1, 2), two far-field layers, a cell of no layer, then
        // two fill triangles that borrowed a wall layer and a far-field one
        let mesh = layered(
            vec![0, 1, 2, 0, 1, NONE, 2, 1],
            vec![0, 0, 0, 1, 1, NONE, 0, 1],
        );
        let places = layers_of(&mesh, 6);
        use LayerOf::*;
        let expected = [
            Wall(1),
            Wall(2),
            Wall(3),
            Farfield,
            Farfield,
            Fill,
            Fill,
            Fill,
        ];
        assert_eq!(places, expected);
        let c = layer_colours(&mesh, 6);
        let per_cell: Vec<Rgb> = c.per_cell.iter().map(|c| c.unwrap()).collect();
        // the wall's first layer is the map's start, its last the map's end
        assert_eq!(per_cell[0], map_colour(0.0));
        assert_eq!(per_cell[2], map_colour(1.0));
        assert!(per_cell[3..5].iter().all(|&c| c == FARFIELD_LAYERS));
        assert!(per_cell[5..].iter().all(|&c| c == NO_VALUE));
        assert!(
            per_cell[..3]
                .iter()
                .all(|c| ![FARFIELD_LAYERS, NO_VALUE].contains(c))
        );
        let legend = c.legend.unwrap();
        assert_eq!(legend.title, "layer from wall");
        let labels: Vec<&str> = legend.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["1", "2", "3"]);
        assert_eq!(legend.bar, BarPaint::Blocks(per_cell[..3].to_vec()));
        let swatches: Vec<&str> = legend.swatches.iter().map(|s| s.1.as_str()).collect();
        assert_eq!(swatches, ["far field", "fill"]);
    }

    #[test]
    fn without_pipes_every_layered_cell_counts_from_its_wall() {
        let mesh = layered(vec![0, 1, NONE], Vec::new());
        assert_eq!(
            layers_of(&mesh, 3),
            [LayerOf::Wall(1), LayerOf::Wall(2), LayerOf::Fill]
        );
        let legend = layer_colours(&mesh, 3).legend.unwrap();
        let swatches: Vec<&str> = legend.swatches.iter().map(|s| s.1.as_str()).collect();
        assert_eq!(swatches, ["fill"]);
    }

    #[test]
    fn ticks_lie_inside_the_bar_and_include_both_ends() {
        let t = nice_ticks(-0.37, 2.9, 5);
        assert!(t.iter().all(|t| (0.0..=1.0).contains(&t.frac)));
        assert_eq!(t.iter().filter(|t| t.major).count(), 2);
        assert!(t.iter().any(|t| t.label == "1"), "{t:?}");
    }
}
