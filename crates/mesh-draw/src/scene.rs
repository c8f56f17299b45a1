//! The picture as a list of device-independent pieces (pixel coordinates): cell fills grouped
//! by colour, the unique mesh edges, the boundary loops by role, and the marks around them
//! (frame, legend, scale bar, title), laid out for the requested size. Both back-ends (PNG
//! and SVG) draw a scene; neither decides anything about what is shown.

use std::collections::HashMap;

use mesh_model::topology::Edges;
use mesh_model::{CellRef, Mesh, Role};

use crate::check::check_mesh;
use crate::colour::{
    BarPaint, EDGE, FARFIELD_SWATCH, FILL_SWATCH, FRAME, INK, LAYER_TITLE, Legend, Rgb, WHITE,
    cell_colours, format_number, nice_step, role_colour,
};
use crate::error::DrawError;
use crate::font::{text_rows, text_width};
use crate::frame::{Curve, Frame, PxRect};
use crate::params::{DrawParams, View, mesh_view};

/// Which back-end a scene is for: the SVG leaves out edges shorter than a pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Target {
    /// Raster: every visible edge.
    Png,
    /// Vector: edges shorter than a pixel are left out to keep the file small.
    Svg,
}

/// Cells of one colour: closed outlines, stored flat.
#[derive(Debug, Clone)]
pub(crate) struct FillGroup {
    /// Fill colour.
    pub colour: Rgb,
    /// The outlines' curves, one outline after another.
    pub curves: Vec<Curve>,
    /// The end (exclusive index in `curves`) of each outline.
    pub outline_ends: Vec<u32>,
}

/// Open curves stroked alike. A curve that starts where the previous one ended continues it.
#[derive(Debug, Clone)]
pub(crate) struct StrokeGroup {
    /// A name for the SVG (`edges`, `wall`, `farfield`).
    pub name: &'static str,
    /// Stroke colour.
    pub colour: Rgb,
    /// Stroke opacity, 0 to 1.
    pub opacity: f64,
    /// Stroke width, pixels.
    pub width_px: f64,
    /// The curves.
    pub curves: Vec<Curve>,
}

/// Horizontal placement of a text relative to its anchor point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Anchor {
    /// The text starts at the point.
    Start,
    /// The text is centred on the point.
    Middle,
}

/// A mark drawn over the mesh.
#[derive(Debug, Clone)]
pub(crate) enum Mark {
    /// A filled rectangle.
    Rect {
        /// Where.
        rect: PxRect,
        /// Fill colour.
        fill: Rgb,
        /// Fill opacity, 0 to 1.
        opacity: f64,
    },
    /// A rectangle's outline.
    Outline {
        /// Where.
        rect: PxRect,
        /// Stroke colour.
        colour: Rgb,
        /// Stroke width, pixels.
        width_px: f64,
    },
    /// The legend's colour bar, minimum at the bottom.
    Bar {
        /// Where.
        rect: PxRect,
        /// Its paint.
        paint: BarPaint,
    },
    /// An open polyline.
    Polyline {
        /// Its points, pixels.
        points: Vec<[f64; 2]>,
        /// Stroke colour.
        colour: Rgb,
        /// Stroke width, pixels.
        width_px: f64,
    },
    /// One line of text.
    Text {
        /// The text.
        text: String,
        /// Anchor x, pixels.
        x: f64,
        /// Baseline y, pixels.
        y_baseline: f64,
        /// Cap height, pixels.
        cap_px: f64,
        /// Placement relative to `x`.
        anchor: Anchor,
        /// Colour.
        colour: Rgb,
    },
}

/// Everything to draw, in pixels.
#[derive(Debug, Clone)]
pub(crate) struct Scene {
    /// Picture width, pixels.
    pub width_px: u32,
    /// Picture height, pixels.
    pub height_px: u32,
    /// Where the mesh is drawn; the mesh is clipped to it.
    pub plot: PxRect,
    /// Cell fills, one group per colour.
    pub fills: Vec<FillGroup>,
    /// The unique edges of the visible cells.
    pub edges: StrokeGroup,
    /// The boundary loops, one group per role.
    pub boundaries: Vec<StrokeGroup>,
    /// Marks over the mesh, drawn in order.
    pub marks: Vec<Mark>,
}

/// Smallest and largest picture side, pixels.
const SIZE_RANGE: std::ops::RangeInclusive<u32> = 16..=16384;

/// Builds the scene of `mesh` drawn as `params` asks.
pub(crate) fn build_scene(
    mesh: &Mesh,
    params: &DrawParams,
    target: Target,
) -> Result<Scene, DrawError> {
    if !SIZE_RANGE.contains(&params.width_px) || !SIZE_RANGE.contains(&params.height_px) {
        return Err(DrawError::InvalidSize {
            width_px: params.width_px,
            height_px: params.height_px,
        });
    }
    check_mesh(mesh)?;
    let view = match params.view {
        Some(v) => {
            v.check()?;
            v
        }
        None => mesh_view(mesh, 0.04)?,
    };
    let colours = cell_colours(mesh, &params.colour, params.fill_cells)?;
    let legend = if params.show_legend {
        colours.legend.as_ref()
    } else {
        None
    };
    let mut layout = Layout::new(params, legend, false);
    let mut frame = Frame::new(&view, layout.plot)?;
    let mut visible = visible_cells(mesh, &frame.cull_view());
    // the wall line no thicker than the first layer in view, so that the layers show
    let mut first_px = first_layer_px(mesh, &frame, &visible);
    // First layers below a pixel are said so in a band of its own above the plot, never over
    // the cells. The band leaves the plot no larger, so they stay below a pixel in it.
    if first_px.is_some_and(|h| h < 1.0) {
        let with_note = Layout::new(params, legend, true);
        if with_note.note_baseline.is_some() {
            layout = with_note;
            frame = Frame::new(&view, layout.plot)?;
            visible = visible_cells(mesh, &frame.cull_view());
            first_px = first_layer_px(mesh, &frame, &visible);
        }
    }
    let fills = if colours.per_cell.is_empty() {
        Vec::new()
    } else {
        fill_groups(mesh, &frame, &visible, &colours.per_cell)
    };
    let edges = StrokeGroup {
        name: "edges",
        colour: EDGE,
        opacity: if fills.is_empty() { 1.0 } else { 0.8 },
        width_px: 0.8,
        curves: unique_edges(mesh, &frame, &visible, target),
    };
    let bold = (params.width_px.min(params.height_px) as f64 / 400.0).clamp(2.0, 3.0);
    let wall_px = first_px.map_or(bold, |h| bold.min(h).max(MIN_WALL_PX));
    let boundaries = boundary_groups(mesh, &frame, bold, wall_px);

    let mut marks = vec![Mark::Outline {
        rect: layout.plot,
        colour: FRAME,
        width_px: 1.0,
    }];
    if params.show_scale_bar {
        marks.extend(scale_bar(&frame, layout.cap_px));
    }
    if let (Some(h), Some(y_baseline)) = (first_px.filter(|&h| h < 1.0), layout.note_baseline) {
        marks.push(Mark::Text {
            text: below_a_pixel(
                h,
                params.width_px as f64 - 2.0 * layout.margin,
                layout.cap_px,
            ),
            x: 0.5 * (layout.plot.x0 + layout.plot.x1),
            y_baseline,
            cap_px: layout.cap_px,
            anchor: Anchor::Middle,
            colour: INK,
        });
    }
    if let (Some(legend), Some(rect)) = (legend, layout.legend) {
        marks.extend(legend_marks(legend, rect, layout.cap_px));
    }
    if let Some(title) = &params.title {
        marks.push(Mark::Text {
            text: title.clone(),
            x: 0.5 * params.width_px as f64,
            y_baseline: layout.title_baseline,
            cap_px: layout.title_cap_px,
            anchor: Anchor::Middle,
            colour: INK,
        });
    }
    Ok(Scene {
        width_px: params.width_px,
        height_px: params.height_px,
        plot: layout.plot,
        fills,
        edges,
        boundaries,
        marks,
    })
}

/// Where things go in the picture.
struct Layout {
    /// Cap height of the legend and scale-bar text, pixels.
    cap_px: f64,
    /// The picture's margin, pixels.
    margin: f64,
    /// Cap height of the title, pixels.
    title_cap_px: f64,
    /// Baseline of the title, pixels.
    title_baseline: f64,
    /// Baseline of the note on the first layers, in its band between the title and the plot
    /// (`None`: no band, or no room for one).
    note_baseline: Option<f64>,
    /// The mesh's rectangle.
    plot: PxRect,
    /// The legend's column, when there is a legend.
    legend: Option<PxRect>,
}

/// The space above and below the note's line in its band, cap heights.
const NOTE_GAP: f64 = 0.3;

impl Layout {
    /// The layout of the picture `params` asks for, with a band for the note on the first
    /// layers above the plot when `note` (and the picture has room for it).
    fn new(params: &DrawParams, legend: Option<&Legend>, note: bool) -> Layout {
        let (w, h) = (params.width_px as f64, params.height_px as f64);
        let cap_px = (w.min(h) / 70.0).clamp(7.0, 18.0);
        let title_cap_px = 1.25 * cap_px;
        let margin = if w.min(h) < 120.0 { 2.0 } else { cap_px };
        let title_band = if params.title.is_some() {
            title_cap_px * 2.2
        } else {
            0.0
        };
        let title_baseline = margin + title_cap_px * 1.3;
        // the note's band: a line of text at `cap_px`, from its tallest glyph to its
        // descenders, with a gap above and below (clear of the title and the plot's frame)
        let (above, below) = text_rows(0.0, cap_px);
        let gap = NOTE_GAP * cap_px;
        let note_band = if note { below - above + 2.0 * gap } else { 0.0 };
        let mut note_baseline = note.then_some(margin + title_band + gap - above);
        let mut plot = PxRect {
            x0: margin,
            y0: margin + title_band + note_band,
            x1: w - margin,
            y1: h - margin,
        };
        let mut legend_rect = None;
        // The legend's column has one width whatever it holds (or when there is no legend to
        // show), so that a view lands on the same pixels in every colouring.
        if params.show_legend {
            let width = legend
                .map_or(0.0, |l| legend_width(l, cap_px))
                .max(column_width(cap_px));
            if plot.width() - width - margin >= 0.5 * w {
                legend_rect = Some(PxRect {
                    x0: w - margin - width,
                    y0: plot.y0,
                    x1: w - margin,
                    y1: plot.y1,
                });
                plot.x1 -= width + margin;
            }
        }
        if plot.width() < 8.0 || plot.height() < 8.0 {
            plot = PxRect {
                x0: 0.0,
                y0: 0.0,
                x1: w,
                y1: h,
            };
            // no room for a band beside the plot: the note is left out
            note_baseline = None;
        }
        // Whole pixels: the plot's frame stays crisp and the margins tile exactly.
        let plot = PxRect {
            x0: plot.x0.round(),
            y0: plot.y0.round(),
            x1: plot.x1.round(),
            y1: plot.y1.round(),
        };
        Layout {
            cap_px,
            margin,
            title_cap_px,
            title_baseline,
            note_baseline,
            plot,
            legend: legend_rect,
        }
    }
}

/// Sizes of the legend's parts, in cap heights.
const BAR_WIDTH: f64 = 1.6;
const TICK_LENGTH: f64 = 0.5;
const LABEL_GAP: f64 = 0.45;
const SWATCH_ROW: f64 = 2.2;

/// Width of the legend column for the legends this crate makes (angles, scaled Jacobian,
/// layers, values), pixels: the width of the widest of their usual labels.
fn column_width(cap: f64) -> f64 {
    let text = |s: &str| text_width(s, cap);
    let bar = cap * (BAR_WIDTH + TICK_LENGTH + LABEL_GAP) + text("-0.000125");
    let swatches = ["< 0 (inverted)", FARFIELD_SWATCH, FILL_SWATCH];
    let swatch = cap * (BAR_WIDTH + LABEL_GAP) + swatches.map(text).into_iter().fold(0.0, f64::max);
    let headings = text("scaled jacobian").max(text(LAYER_TITLE));
    bar.max(swatch).max(headings).ceil() + 1.0
}

/// Width of the legend column, pixels.
fn legend_width(legend: &Legend, cap: f64) -> f64 {
    let labels = legend
        .ticks
        .iter()
        .map(|t| text_width(&t.label, cap))
        .fold(0.0, f64::max);
    let bar = cap * (BAR_WIDTH + TICK_LENGTH + LABEL_GAP) + labels;
    let title = text_width(&legend.title, cap);
    let swatches = legend
        .swatches
        .iter()
        .map(|(_, s)| cap * (BAR_WIDTH + LABEL_GAP) + text_width(s, cap))
        .fold(0.0, f64::max);
    bar.max(title).max(swatches).ceil() + 1.0
}

/// The legend drawn in its column: heading, bar, ticks, labels that do not collide, swatches.
fn legend_marks(legend: &Legend, rect: PxRect, cap: f64) -> Vec<Mark> {
    let mut marks = vec![Mark::Text {
        text: legend.title.clone(),
        x: rect.x0,
        y_baseline: rect.y0 + cap,
        cap_px: cap,
        anchor: Anchor::Start,
        colour: INK,
    }];
    let swatch_space = legend.swatches.len() as f64 * SWATCH_ROW * cap;
    let top = rect.y0 + 2.6 * cap;
    let available = rect.y1 - top - swatch_space - 0.6 * cap;
    let bar_height = (0.7 * rect.height()).min(available).max(2.0 * cap);
    let bar = PxRect {
        x0: rect.x0,
        y0: top,
        x1: rect.x0 + BAR_WIDTH * cap,
        y1: top + bar_height,
    };
    marks.push(Mark::Bar {
        rect: bar,
        paint: legend.bar.clone(),
    });
    marks.push(Mark::Outline {
        rect: bar,
        colour: INK,
        width_px: 1.0,
    });
    let tick_width = (0.09 * cap).max(1.0);
    let mut ticks: Vec<&crate::colour::Tick> = legend.ticks.iter().collect();
    ticks.sort_by_key(|t| !t.major);
    let mut labelled: Vec<f64> = Vec::new();
    for tick in ticks {
        let y = bar.y1 - tick.frac * bar_height;
        marks.push(Mark::Polyline {
            points: vec![[bar.x0, y], [bar.x1 + TICK_LENGTH * cap, y]],
            colour: INK,
            width_px: tick_width,
        });
        if labelled.iter().all(|&other| (other - y).abs() >= 1.7 * cap) {
            labelled.push(y);
            marks.push(Mark::Text {
                text: tick.label.clone(),
                x: bar.x1 + (TICK_LENGTH + LABEL_GAP) * cap,
                y_baseline: y + 0.5 * cap,
                cap_px: cap,
                anchor: Anchor::Start,
                colour: INK,
            });
        }
    }
    for (i, (colour, label)) in legend.swatches.iter().enumerate() {
        let y0 = bar.y1 + (0.8 + SWATCH_ROW * i as f64) * cap;
        let swatch = PxRect {
            x0: bar.x0,
            y0,
            x1: bar.x1,
            y1: y0 + 1.3 * cap,
        };
        marks.push(Mark::Rect {
            rect: swatch,
            fill: *colour,
            opacity: 1.0,
        });
        marks.push(Mark::Outline {
            rect: swatch,
            colour: INK,
            width_px: 1.0,
        });
        marks.push(Mark::Text {
            text: label.clone(),
            x: bar.x1 + LABEL_GAP * cap,
            y_baseline: y0 + 1.15 * cap,
            cap_px: cap,
            anchor: Anchor::Start,
            colour: INK,
        });
    }
    marks
}

/// The length a scale bar shows, mesh units: the nice number (1, 2, 5 × 10^k) at or below a
/// fifth of the plot's width.
pub(crate) fn scale_bar_length(visible_width: f64) -> f64 {
    nice_step(visible_width / 5.0)
}

/// The scale bar at the bottom left of the plot, on a light backdrop.
fn scale_bar(frame: &Frame, cap: f64) -> Vec<Mark> {
    let plot = frame.plot;
    let length = scale_bar_length(plot.width() / frame.scale);
    let length_px = length * frame.scale;
    if length_px.is_nan() || length_px < 2.0 {
        return Vec::new();
    }
    let label = format_number(length, length);
    let label_width = text_width(&label, cap);
    let x = plot.x0 + 1.2 * cap;
    let y = plot.y1 - 1.2 * cap;
    let backdrop = PxRect {
        x0: x - 0.6 * cap,
        y0: y - 2.5 * cap,
        x1: x + length_px.max(label_width) + 0.6 * cap,
        y1: y + 0.7 * cap,
    };
    vec![
        Mark::Rect {
            rect: backdrop,
            fill: WHITE,
            opacity: 0.85,
        },
        Mark::Polyline {
            points: vec![
                [x, y - 0.6 * cap],
                [x, y],
                [x + length_px, y],
                [x + length_px, y - 0.6 * cap],
            ],
            colour: INK,
            width_px: (0.18 * cap).max(1.5),
        },
        Mark::Text {
            text: label,
            x: x + 0.5 * length_px.max(label_width),
            y_baseline: y - 0.95 * cap,
            cap_px: cap,
            anchor: Anchor::Middle,
            colour: INK,
        },
    ]
}

/// Indices of the cells whose nodes' bounding box meets `view`.
fn visible_cells(mesh: &Mesh, view: &View) -> Vec<u32> {
    (0..mesh.cells.len())
        .filter(|&i| {
            let (mut x0, mut y0, mut x1, mut y1) = (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            );
            for &n in mesh.cells.get(i).nodes {
                let p = mesh.nodes[n as usize];
                x0 = x0.min(p[0]);
                y0 = y0.min(p[1]);
                x1 = x1.max(p[0]);
                y1 = y1.max(p[1]);
            }
            x0 <= view.x1 && view.x0 <= x1 && y0 <= view.y1 && view.y0 <= y1
        })
        .map(|i| i as u32)
        .collect()
}

/// The Lagrange points (mesh units) of local edge `edge` of `cell`, in the edge's direction:
/// its first corner, its high-order nodes (Gmsh order), its second corner.
fn edge_points(mesh: &Mesh, cell: CellRef<'_>, edge: usize, out: &mut Vec<[f64; 2]>) {
    out.clear();
    let shape = cell.ty.shape;
    let [a, b] = shape.edges()[edge];
    let inner = cell.ty.order.max(1) as usize - 1;
    let first = shape.corners() + edge * inner;
    out.push(mesh.xy(cell.nodes[a]));
    out.extend(cell.nodes[first..first + inner].iter().map(|&n| mesh.xy(n)));
    out.push(mesh.xy(cell.nodes[b]));
}

/// Fills of the visible cells, grouped by colour (groups in colour order).
fn fill_groups(
    mesh: &Mesh,
    frame: &Frame,
    visible: &[u32],
    per_cell: &[Option<Rgb>],
) -> Vec<FillGroup> {
    let mut index: HashMap<Rgb, usize> = HashMap::new();
    let mut groups: Vec<FillGroup> = Vec::new();
    let mut edge_buffers: Vec<Vec<[f64; 2]>> = vec![Vec::new(); 4];
    for &i in visible {
        let Some(colour) = per_cell[i as usize] else {
            continue;
        };
        let cell = mesh.cells.get(i as usize);
        let edge_count = cell.ty.shape.edges().len();
        for (e, buffer) in edge_buffers.iter_mut().enumerate().take(edge_count) {
            edge_points(mesh, cell, e, buffer);
        }
        let slices: Vec<&[[f64; 2]]> = edge_buffers[..edge_count]
            .iter()
            .map(|b| b.as_slice())
            .collect();
        let g = *index.entry(colour).or_insert_with(|| {
            groups.push(FillGroup {
                colour,
                curves: Vec::new(),
                outline_ends: Vec::new(),
            });
            groups.len() - 1
        });
        let group = &mut groups[g];
        if frame.push_outline(&slices, &mut group.curves) > 0 {
            group.outline_ends.push(group.curves.len() as u32);
        }
    }
    groups.retain(|g| !g.outline_ends.is_empty());
    groups.sort_by_key(|g| g.colour);
    groups
}

/// The edges of the visible cells, each drawn once (the first cell that names it gives its
/// direction and high-order nodes). For the SVG, edges shorter than a pixel are left out.
fn unique_edges(mesh: &Mesh, frame: &Frame, visible: &[u32], target: Target) -> Vec<Curve> {
    // `visible` is increasing, so an edge's first use is by its lowest visible cell
    let cells = visible.iter().map(|&i| {
        let c = mesh.cells.get(i as usize);
        (c.ty.shape, c.corners())
    });
    let edges = Edges::build(cells, []);
    let keys = (0..edges.len() as u32).map(|e| {
        let first = edges.cells(e)[0];
        (visible[first.cell as usize], first.local)
    });
    let mut curves = Vec::with_capacity(edges.len());
    let mut points = Vec::with_capacity(4);
    for (i, e) in keys {
        edge_points(mesh, mesh.cells.get(i as usize), e as usize, &mut points);
        let before = curves.len();
        frame.push_edge(&points, &mut curves);
        if target == Target::Svg && curves.len() == before + 1 && curves[before].extent_px() < 1.0 {
            curves.pop();
        }
    }
    curves
}

/// The note on first layers of `h` pixels, as long as fits in `room` pixels at `cap` (the
/// shortest when none does).
fn below_a_pixel(h: f64, room: f64, cap: f64) -> String {
    let h = px_text(h);
    let notes = [
        format!("first layers below a pixel (first {h}): zoom in to see them"),
        format!("first layers below a pixel ({h}): zoom in"),
        format!("first layers {h}: zoom in"),
    ];
    let fits = notes.iter().position(|n| text_width(n, cap) <= room);
    notes[fits.unwrap_or(notes.len() - 1)].clone()
}

/// A length in pixels for people: two digits, or a power of ten when very small.
fn px_text(h: f64) -> String {
    if h >= 0.01 {
        format!("{h:.2} px")
    } else {
        format!("{h:.0e} px")
    }
}

/// The thinnest wall line drawn, pixels.
const MIN_WALL_PX: f64 = 0.75;

/// The height of the first layer in view, pixels: the shortest edge of a visible cell with one
/// end on a wall and the other off it. `None` when no such edge is in view.
fn first_layer_px(mesh: &Mesh, frame: &Frame, visible: &[u32]) -> Option<f64> {
    let mut on_wall = vec![false; mesh.nodes.len()];
    for (facet, &patch) in mesh.boundary.iter().zip(&mesh.boundary_patch) {
        if mesh.patches[patch as usize].role == Role::Wall {
            for &n in facet.corners() {
                on_wall[n as usize] = true;
            }
        }
    }
    let mut least = f64::INFINITY;
    for &i in visible {
        let cell = mesh.cells.get(i as usize);
        let k = cell.corners();
        for j in 0..k.len() {
            let (a, b) = (k[j], k[(j + 1) % k.len()]);
            if on_wall[a as usize] != on_wall[b as usize] {
                let (p, q) = (mesh.xy(a), mesh.xy(b));
                least = least.min((p[0] - q[0]).hypot(p[1] - q[1]));
            }
        }
    }
    least.is_finite().then_some(least * frame.scale)
}

/// The boundary facets, one stroke group per role present (walls black `wall_px` wide, far
/// field dark blue `width_px` wide).
fn boundary_groups(mesh: &Mesh, frame: &Frame, width_px: f64, wall_px: f64) -> Vec<StrokeGroup> {
    let mut groups = Vec::new();
    let mut points = Vec::with_capacity(4);
    for role in [Role::Farfield, Role::Wall] {
        let mut curves = Vec::new();
        for (facet, &patch) in mesh.boundary.iter().zip(&mesh.boundary_patch) {
            if mesh.patches[patch as usize].role != role {
                continue;
            }
            // Gmsh line order: the two ends, then the inner nodes from the first end.
            points.clear();
            points.push(mesh.xy(facet.nodes[0]));
            points.extend(facet.nodes[2..].iter().map(|&n| mesh.xy(n)));
            points.push(mesh.xy(facet.nodes[1]));
            frame.push_edge(&points, &mut curves);
        }
        if !curves.is_empty() {
            groups.push(StrokeGroup {
                name: role.name(),
                colour: role_colour(role),
                opacity: 1.0,
                width_px: if role == Role::Wall {
                    wall_px
                } else {
                    width_px
                },
                curves,
            });
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::ColourBy;
    use mesh_model::{CellType, Dim, Patch, Shape};

    /// Two layers of quads on a wall along y = 0, the first 1e-4 high: below a pixel in any
    /// picture of the whole mesh.
    fn thin_layers() -> Mesh {
        let mut mesh = Mesh::new(Dim::Two, 1);
        for y in [0.0, 1e-4, 1.0] {
            mesh.nodes.extend([[0.0, y, 0.0], [1.0, y, 0.0]]);
        }
        let quad = CellType::new(Shape::Quad, 1);
        mesh.cells.push(quad, &[0, 1, 3, 2]);
        mesh.cells.push(quad, &[2, 3, 5, 4]);
        mesh.cell_layer = vec![0, 1];
        mesh.boundary.push(CellType::new(Shape::Line, 1), &[0, 1]);
        mesh.boundary_patch.push(0);
        mesh.patches.push(Patch {
            name: "wall".into(),
            role: Role::Wall,
        });
        mesh
    }

    /// The rows of the text marks that start with `start`.
    fn rows_of(scene: &Scene, start: &str) -> Vec<(f64, f64)> {
        scene
            .marks
            .iter()
            .filter_map(|m| match m {
                Mark::Text {
                    text,
                    y_baseline,
                    cap_px,
                    ..
                } if text.starts_with(start) => Some(text_rows(*y_baseline, *cap_px)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn the_note_on_first_layers_below_a_pixel_sits_above_the_plot_below_the_title() {
        let mesh = thin_layers();
        for (w, h) in [
            (2000, 1500),
            (900, 675),
            (400, 300),
            (200, 150),
            (100, 75),
            (40, 30),
        ] {
            for title in [Some("a title".to_string()), None] {
                for colour in [ColourBy::None, ColourBy::Layer] {
                    let params = DrawParams {
                        width_px: w,
                        height_px: h,
                        title: title.clone(),
                        colour,
                        ..DrawParams::default()
                    };
                    let what = format!("{w}x{h} title {title:?}");
                    let scene = build_scene(&mesh, &params, Target::Png).unwrap();
                    let notes = rows_of(&scene, "first layers");
                    // the plot's frame is a 1 px line on its edge
                    let plot_top = scene.plot.y0 - 0.5;
                    for &(top, bottom) in &notes {
                        assert!(
                            bottom < plot_top,
                            "{what}: note down to {bottom}, plot {plot_top}"
                        );
                        assert!(top >= 0.0, "{what}: note from {top}");
                    }
                    if let (Some(t), Some(&(top, _))) = (&title, notes.first()) {
                        let (_, title_bottom) = rows_of(&scene, t)[0];
                        assert!(
                            title_bottom < top,
                            "{what}: title to {title_bottom}, note {top}"
                        );
                    }
                    // a picture with room for a plot and the band says it (a smaller one
                    // may leave the note out)
                    assert!(notes.len() <= 1, "{what}");
                    assert!(h < 75 || notes.len() == 1, "{what}");
                }
            }
        }
    }

    #[test]
    fn the_note_fits_a_narrow_picture() {
        let cap = 7.0;
        let long = below_a_pixel(0.5, 2000.0, cap);
        assert!(long.contains("zoom in to see them"), "{long}");
        let short = below_a_pixel(0.5, 150.0, cap);
        assert!(text_width(&short, cap) <= 150.0, "{short}");
        assert!(short.contains("0.50 px"), "{short}");
    }
}
