//! The vector back-end: writes a [`Scene`] as SVG text. Coordinates are pixels rounded to a
//! tenth; each group of like things is one `<path>` (all edges in one, each boundary role in
//! one, the cells of each colour in one) written with relative commands, which keeps the file
//! small. Text is written as `<text>`, drawn by the viewer's sans-serif font.

use std::fmt::Write;

use crate::colour::{BarPaint, Rgb, WHITE};
use crate::frame::{Curve, PxRect};
use crate::scene::{Anchor, Mark, Scene, StrokeGroup};

/// Ratio of font size to cap height of common sans-serif fonts.
const FONT_SIZE_PER_CAP: f64 = 1.0 / 0.72;

/// Writes the scene as a standalone SVG document.
pub(crate) fn write_svg(scene: &Scene) -> String {
    let mut s = String::with_capacity(4096 + 24 * scene.edges.curves.len());
    let (w, h) = (scene.width_px, scene.height_px);
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let p = scene.plot;
    let _ = writeln!(
        s,
        r#"<defs><clipPath id="plot"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath></defs>"#,
        short(p.x0),
        short(p.y0),
        short(p.width()),
        short(p.height())
    );
    let _ = writeln!(
        s,
        r#"<rect width="100%" height="100%" fill="{}"/>"#,
        hex(WHITE)
    );
    let _ = writeln!(s, r#"<g clip-path="url(#plot)">"#);
    for group in &scene.fills {
        let mut d = PathData::default();
        let mut start = 0usize;
        for &end in &group.outline_ends {
            let outline = &group.curves[start..end as usize];
            start = end as usize;
            if let Some(first) = outline.first() {
                d.move_to(first.start());
                for c in outline {
                    d.segment(c);
                }
                d.s.push('z');
            }
        }
        // A thin stroke of the fill colour hides the anti-aliasing seams between cells.
        let _ = writeln!(
            s,
            r#"<path fill="{c}" stroke="{c}" stroke-width="0.5" d="{}"/>"#,
            d.s,
            c = hex(group.colour)
        );
    }
    write_strokes(&mut s, &scene.edges, false);
    for group in &scene.boundaries {
        write_strokes(&mut s, group, true);
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<g font-family="DejaVu Sans, Arial, Helvetica, sans-serif">"#
    );
    for (i, mark) in scene.marks.iter().enumerate() {
        write_mark(&mut s, mark, i);
    }
    let _ = writeln!(s, "</g>");
    s.push_str("</svg>\n");
    s
}

fn write_strokes(s: &mut String, group: &StrokeGroup, round: bool) {
    if group.curves.is_empty() {
        return;
    }
    let mut d = PathData::default();
    let mut last: Option<(i64, i64)> = None;
    for c in &group.curves {
        let start = tenths(c.start());
        if last != Some(start) {
            d.move_to(c.start());
        }
        d.segment(c);
        last = Some(d.current);
    }
    let joins = if round {
        r#" stroke-linecap="round" stroke-linejoin="round""#
    } else {
        ""
    };
    let opacity = if group.opacity < 1.0 {
        format!(r#" stroke-opacity="{}""#, short(group.opacity))
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        r#"<path id="{}" fill="none" stroke="{}" stroke-width="{}"{opacity}{joins} d="{}"/>"#,
        group.name,
        hex(group.colour),
        short(group.width_px),
        d.s
    );
}

fn write_mark(s: &mut String, mark: &Mark, index: usize) {
    match mark {
        Mark::Rect {
            rect,
            fill,
            opacity,
        } => {
            let o = if *opacity < 1.0 {
                format!(r#" fill-opacity="{}""#, short(*opacity))
            } else {
                String::new()
            };
            let _ = writeln!(
                s,
                r#"<rect {} fill="{}"{o}/>"#,
                rect_attrs(rect),
                hex(*fill)
            );
        }
        Mark::Outline {
            rect,
            colour,
            width_px,
        } => {
            let _ = writeln!(
                s,
                r#"<rect {} fill="none" stroke="{}" stroke-width="{}"/>"#,
                rect_attrs(rect),
                hex(*colour),
                short(*width_px)
            );
        }
        Mark::Bar { rect, paint } => match paint {
            BarPaint::Gradient(stops) => {
                let _ = write!(
                    s,
                    r#"<linearGradient id="bar{index}" x1="0" y1="1" x2="0" y2="0">"#
                );
                for (t, c) in stops {
                    let _ = write!(
                        s,
                        r#"<stop offset="{}" stop-color="{}"/>"#,
                        short(*t),
                        hex(*c)
                    );
                }
                let _ = writeln!(s, "</linearGradient>");
                let _ = writeln!(s, r#"<rect {} fill="url(#bar{index})"/>"#, rect_attrs(rect));
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
                    let _ = writeln!(s, r#"<rect {} fill="{}"/>"#, rect_attrs(&block), hex(*c));
                }
            }
        },
        Mark::Polyline {
            points,
            colour,
            width_px,
        } => {
            let pts: Vec<String> = points
                .iter()
                .map(|p| format!("{},{}", short(p[0]), short(p[1])))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="{}"/>"#,
                pts.join(" "),
                hex(*colour),
                short(*width_px)
            );
        }
        Mark::Text {
            text,
            x,
            y_baseline,
            cap_px,
            anchor,
            colour,
        } => {
            let anchor = match anchor {
                Anchor::Start => "start",
                Anchor::Middle => "middle",
            };
            let _ = writeln!(
                s,
                r#"<text x="{}" y="{}" font-size="{}" text-anchor="{anchor}" fill="{}">{}</text>"#,
                short(*x),
                short(*y_baseline),
                short(cap_px * FONT_SIZE_PER_CAP),
                hex(*colour),
                escape(text)
            );
        }
    }
}

fn rect_attrs(r: &PxRect) -> String {
    format!(
        r#"x="{}" y="{}" width="{}" height="{}""#,
        short(r.x0),
        short(r.y0),
        short(r.width()),
        short(r.height())
    )
}

/// `#rrggbb`.
fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// A number with at most two decimals, trailing zeros dropped.
fn short(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" || s.is_empty() {
        "0".into()
    } else {
        s.into()
    }
}

/// Escapes the XML special characters of a text node.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\t' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A point in tenths of a pixel.
fn tenths(p: [f32; 2]) -> (i64, i64) {
    (
        (p[0] as f64 * 10.0).round() as i64,
        (p[1] as f64 * 10.0).round() as i64,
    )
}

/// Path data being written: absolute moves, relative segments, in tenths of a pixel.
#[derive(Default)]
struct PathData {
    s: String,
    current: (i64, i64),
}

impl PathData {
    fn move_to(&mut self, p: [f32; 2]) {
        let t = tenths(p);
        self.s.push('M');
        push_tenths(&mut self.s, t.0, true);
        push_tenths(&mut self.s, t.1, false);
        self.current = t;
    }

    fn segment(&mut self, c: &Curve) {
        let points = c.points();
        let command = match points.len() {
            2 => 'l',
            3 => 'q',
            _ => 'c',
        };
        let origin = self.current;
        let rel: Vec<(i64, i64)> = points[1..]
            .iter()
            .map(|&p| {
                let t = tenths(p);
                (t.0 - origin.0, t.1 - origin.1)
            })
            .collect();
        if rel.iter().all(|&r| r == (0, 0)) {
            return;
        }
        self.s.push(command);
        for (i, r) in rel.iter().enumerate() {
            push_tenths(&mut self.s, r.0, i == 0);
            push_tenths(&mut self.s, r.1, false);
        }
        if let Some(last) = rel.last() {
            self.current = (origin.0 + last.0, origin.1 + last.1);
        }
    }
}

/// Writes a value given in tenths as a decimal ("12.3", "-4", ".5" is not used), preceded by
/// a space unless it is the first number after a command or it starts with a minus sign.
fn push_tenths(s: &mut String, v: i64, first: bool) {
    if !first && v >= 0 {
        s.push(' ');
    }
    if v < 0 {
        s.push('-');
    }
    let a = v.unsigned_abs();
    let (whole, tenth) = (a / 10, a % 10);
    let _ = write!(s, "{whole}");
    if tenth > 0 {
        let _ = write!(s, ".{tenth}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tenths_are_written_compactly() {
        let mut s = String::new();
        push_tenths(&mut s, 123, true);
        push_tenths(&mut s, -5, false);
        push_tenths(&mut s, 40, false);
        assert_eq!(s, "12.3-0.5 4");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
