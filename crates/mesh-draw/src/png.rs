//! The raster back-end: draws a [`Scene`] with tiny-skia and encodes it as PNG. Fills are not
//! anti-aliased (neighbouring cells then tile without seams; the anti-aliased edges drawn over
//! them give the smooth look), all strokes and text are.

use tiny_skia::{
    Color, FillRule, GradientStop, LineCap, LineJoin, LinearGradient, Paint, PathBuilder, Pixmap,
    Point, Rect, SpreadMode, Stroke, Transform,
};

use crate::colour::{BarPaint, Rgb, WHITE};
use crate::error::DrawError;
use crate::font::{stroke_width, text_strokes, text_width};
use crate::frame::{Curve, PxRect};
use crate::scene::{Anchor, Mark, Scene, StrokeGroup};

/// Draws the scene into a new pixmap.
pub(crate) fn rasterise(scene: &Scene) -> Result<Pixmap, DrawError> {
    let mut pixmap =
        Pixmap::new(scene.width_px, scene.height_px).ok_or(DrawError::InvalidSize {
            width_px: scene.width_px,
            height_px: scene.height_px,
        })?;
    pixmap.fill(Color::WHITE);
    for group in &scene.fills {
        let mut pb = PathBuilder::new();
        let mut start = 0usize;
        for &end in &group.outline_ends {
            let outline = &group.curves[start..end as usize];
            start = end as usize;
            if let Some(first) = outline.first() {
                pb.move_to(first.start()[0], first.start()[1]);
                for c in outline {
                    segment_to(&mut pb, c);
                }
                pb.close();
            }
        }
        if let Some(path) = pb.finish() {
            let paint = solid(group.colour, 1.0, false);
            pixmap.fill_path(
                &path,
                &paint,
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
    stroke_group(&mut pixmap, &scene.edges, false);
    for group in &scene.boundaries {
        stroke_group(&mut pixmap, group, true);
    }
    blank_margins(&mut pixmap, scene);
    for mark in &scene.marks {
        draw_mark(&mut pixmap, mark);
    }
    Ok(pixmap)
}

/// Encodes the pixmap as PNG bytes.
pub(crate) fn encode(pixmap: &Pixmap) -> Result<Vec<u8>, DrawError> {
    pixmap
        .encode_png()
        .map_err(|e| DrawError::PngEncode(e.to_string()))
}

fn solid(colour: Rgb, opacity: f64, anti_alias: bool) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color(Color::from_rgba8(
        colour[0],
        colour[1],
        colour[2],
        (opacity.clamp(0.0, 1.0) * 255.0).round() as u8,
    ));
    paint.anti_alias = anti_alias;
    paint
}

fn segment_to(pb: &mut PathBuilder, c: &Curve) {
    match c.points() {
        [_, b] => pb.line_to(b[0], b[1]),
        [_, q, b] => pb.quad_to(q[0], q[1], b[0], b[1]),
        [_, c1, c2, b] => pb.cubic_to(c1[0], c1[1], c2[0], c2[1], b[0], b[1]),
        _ => {}
    }
}

/// Strokes a group in one path; a curve starting where the previous ended continues it.
fn stroke_group(pixmap: &mut Pixmap, group: &StrokeGroup, round: bool) {
    let mut pb = PathBuilder::new();
    let mut last: Option<[f32; 2]> = None;
    for c in &group.curves {
        if last != Some(c.start()) {
            pb.move_to(c.start()[0], c.start()[1]);
        }
        segment_to(&mut pb, c);
        last = Some(c.end());
    }
    let Some(path) = pb.finish() else { return };
    let mut stroke = Stroke {
        width: group.width_px as f32,
        ..Stroke::default()
    };
    if round {
        stroke.line_cap = LineCap::Round;
        stroke.line_join = LineJoin::Round;
    }
    let paint = solid(group.colour, group.opacity, true);
    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
}

/// Paints the margins white, which clips the mesh to the plot rectangle.
fn blank_margins(pixmap: &mut Pixmap, scene: &Scene) {
    let (w, h) = (scene.width_px as f64, scene.height_px as f64);
    let p = scene.plot;
    let paint = solid(WHITE, 1.0, false);
    // Reaching a pixel past the picture: tiny-skia leaves the last row and column of a
    // rectangle that ends exactly at the border unpainted.
    let (w, h) = (w + 1.0, h + 1.0);
    for r in [
        PxRect {
            x0: -1.0,
            y0: -1.0,
            x1: w,
            y1: p.y0,
        },
        PxRect {
            x0: -1.0,
            y0: p.y1,
            x1: w,
            y1: h,
        },
        PxRect {
            x0: -1.0,
            y0: p.y0,
            x1: p.x0,
            y1: p.y1,
        },
        PxRect {
            x0: p.x1,
            y0: p.y0,
            x1: w,
            y1: p.y1,
        },
    ] {
        if let Some(rect) = to_rect(&r) {
            pixmap.fill_rect(rect, &paint, Transform::identity(), None);
        }
    }
}

fn to_rect(r: &PxRect) -> Option<Rect> {
    Rect::from_ltrb(r.x0 as f32, r.y0 as f32, r.x1 as f32, r.y1 as f32)
}

fn draw_mark(pixmap: &mut Pixmap, mark: &Mark) {
    match mark {
        Mark::Rect {
            rect,
            fill,
            opacity,
        } => {
            if let Some(r) = to_rect(rect) {
                pixmap.fill_rect(
                    r,
                    &solid(*fill, *opacity, true),
                    Transform::identity(),
                    None,
                );
            }
        }
        Mark::Outline {
            rect,
            colour,
            width_px,
        } => {
            // Snap thin outlines to pixel centres so that they stay crisp.
            let snap = |v: f64| v.round() + 0.5;
            let (x0, y0, x1, y1) = (
                snap(rect.x0),
                snap(rect.y0),
                snap(rect.x1) - 1.0,
                snap(rect.y1) - 1.0,
            );
            let points = vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]];
            polyline(pixmap, &points, *colour, *width_px, false);
        }
        Mark::Bar { rect, paint } => draw_bar(pixmap, rect, paint),
        Mark::Polyline {
            points,
            colour,
            width_px,
        } => polyline(pixmap, points, *colour, *width_px, false),
        Mark::Text {
            text,
            x,
            y_baseline,
            cap_px,
            anchor,
            colour,
        } => {
            let width = text_width(text, *cap_px);
            let left = match anchor {
                Anchor::Start => *x,
                Anchor::Middle => x - 0.5 * width,
            };
            let mut pb = PathBuilder::new();
            for stroke in text_strokes(text, left, *y_baseline, *cap_px) {
                if let Some(first) = stroke.first() {
                    pb.move_to(first[0] as f32, first[1] as f32);
                    if stroke.len() == 1 {
                        pb.line_to(first[0] as f32, first[1] as f32);
                    }
                    for p in &stroke[1..] {
                        pb.line_to(p[0] as f32, p[1] as f32);
                    }
                }
            }
            if let Some(path) = pb.finish() {
                let stroke = Stroke {
                    width: stroke_width(*cap_px) as f32,
                    line_cap: LineCap::Round,
                    line_join: LineJoin::Round,
                    ..Stroke::default()
                };
                pixmap.stroke_path(
                    &path,
                    &solid(*colour, 1.0, true),
                    &stroke,
                    Transform::identity(),
                    None,
                );
            }
        }
    }
}

fn polyline(pixmap: &mut Pixmap, points: &[[f64; 2]], colour: Rgb, width_px: f64, round: bool) {
    let mut pb = PathBuilder::new();
    if let Some(first) = points.first() {
        pb.move_to(first[0] as f32, first[1] as f32);
        for p in &points[1..] {
            pb.line_to(p[0] as f32, p[1] as f32);
        }
    }
    let Some(path) = pb.finish() else { return };
    let mut stroke = Stroke {
        width: width_px as f32,
        line_join: LineJoin::Miter,
        ..Stroke::default()
    };
    if round {
        stroke.line_cap = LineCap::Round;
        stroke.line_join = LineJoin::Round;
    }
    pixmap.stroke_path(
        &path,
        &solid(colour, 1.0, true),
        &stroke,
        Transform::identity(),
        None,
    );
}

fn draw_bar(pixmap: &mut Pixmap, rect: &PxRect, paint: &BarPaint) {
    match paint {
        BarPaint::Gradient(stops) => {
            let stops: Vec<GradientStop> = stops
                .iter()
                .map(|(t, c)| {
                    GradientStop::new(*t as f32, Color::from_rgba8(c[0], c[1], c[2], 255))
                })
                .collect();
            let shader = LinearGradient::new(
                Point::from_xy(rect.x0 as f32, rect.y1 as f32),
                Point::from_xy(rect.x0 as f32, rect.y0 as f32),
                stops,
                SpreadMode::Pad,
                Transform::identity(),
            );
            if let (Some(shader), Some(r)) = (shader, to_rect(rect)) {
                let paint = Paint {
                    shader,
                    ..Paint::default()
                };
                pixmap.fill_rect(r, &paint, Transform::identity(), None);
            }
        }
        BarPaint::Blocks(colours) => {
            let n = colours.len().max(1) as f64;
            for (i, c) in colours.iter().enumerate() {
                let block = PxRect {
                    x0: rect.x0,
                    x1: rect.x1,
                    y0: rect.y1 - rect.height() * (i as f64 + 1.0) / n,
                    y1: rect.y1 - rect.height() * i as f64 / n,
                };
                if let Some(r) = to_rect(&block) {
                    pixmap.fill_rect(r, &solid(*c, 1.0, true), Transform::identity(), None);
                }
            }
        }
    }
}
