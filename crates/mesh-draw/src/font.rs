//! A small built-in stroke font for the picture's text (legend numbers, scale-bar label,
//! title): digits, `a`–`z`, `A`–`Z` and the punctuation that numbers and units need (`. , - +
//! = : ; ( ) [ ] / ° % _ × ' " ! ? < > # * | μ`). Any other character is drawn as an empty box.
//!
//! Why a stroke font rather than a font rasteriser with an embedded font file: the picture
//! needs only labels, a stroke font is ~150 lines of outline data with no dependency and no
//! font licence to carry, it scales to any size, and tiny-skia strokes it anti-aliased like
//! the rest of the drawing, so the PNG output is the same on every machine. (The SVG output
//! writes real `<text>` elements and leaves the font to the viewer.)
//!
//! Glyphs are designed on a grid whose cap height is 10 units (x-height 7, descenders to -3),
//! as strokes written in a tiny path language: `M x y` starts a stroke, `L x y` draws a line,
//! `A cx cy rx ry a0 a1` continues the stroke along an elliptic arc from angle `a0` to `a1`
//! (degrees, counter-clockwise from +x, swept linearly), `O cx cy rx ry` is a closed ellipse.

/// Grid units between two glyphs (besides the stroke width).
const GAP: f64 = 2.6;
/// Advance of a space, grid units.
const SPACE: f64 = 4.5;
/// Cap height in grid units.
const CAP: f64 = 10.0;

/// The outline program of a glyph (see the module docs).
fn glyph_program(c: char) -> &'static str {
    match c {
        '0' => "O3 5 3 5",
        '1' => "M0.8 7.8 L3.4 10 L3.4 0",
        '2' => "A3 7 3 3 160 -35 L0 0 L6 0",
        '3' => "A3 7.6 2.7 2.4 150 -90 A3 2.6 3 2.6 90 -150",
        '4' => "M4.6 0 L4.6 10 L0 3 L6.3 3",
        '5' => "M5.6 10 L1.1 10 L0.6 5.4 A3 3.1 3.1 3.1 128 -145",
        '6' => "A6 3.2 6 6.6 98 180 O3 3.2 3 3.2",
        '7' => "M0 10 L6 10 L2 0",
        '8' => "O3 7.6 2.6 2.4 O3 2.6 3 2.6",
        '9' => "A0 6.8 6 6.6 278 360 O3 6.8 3 3.2",
        'a' => "O3 3.5 3 3.5 M6 7 L6 0",
        'b' => "M0 10 L0 0 O3 3.5 3 3.5",
        'c' => "A3 3.5 3 3.5 40 320",
        'd' => "M6 10 L6 0 O3 3.5 3 3.5",
        'e' => "M0 3.5 L6 3.5 A3 3.5 3 3.5 0 320",
        'f' => "A4 8.2 1.8 1.8 20 180 L2.2 0 M0.3 7 L4.5 7",
        'g' => "O3 3.5 3 3.5 M6 7 L6 -0.5 A3 -0.5 3 2.5 0 -150",
        'h' => "M0 10 L0 0 M0 4 A3 4 3 3 180 0 L6 0",
        'i' => "M0 7 L0 0 M0 9.4 L0 9.5",
        'j' => "M2 7 L2 -1 A0 -1 2 2 0 -120 M2 9.4 L2 9.5",
        'k' => "M0 10 L0 0 M5.5 7 L0 2.2 M2 3.8 L5.8 0",
        'l' => "M0 10 L0 0",
        'm' => "M0 7 L0 0 M0 4.5 A2 4.5 2 2.5 180 0 L4 0 M4 4.5 A6 4.5 2 2.5 180 0 L8 0",
        'n' => "M0 7 L0 0 M0 4 A3 4 3 3 180 0 L6 0",
        'o' => "O3 3.5 3 3.5",
        'p' => "M0 7 L0 -3 O3 3.5 3 3.5",
        'q' => "M6 7 L6 -3 O3 3.5 3 3.5",
        'r' => "M0 7 L0 0 M0 3.8 A3.6 3.8 3.6 3.2 180 70",
        's' => "A3 5.25 2.8 1.75 20 270 A3 1.75 3 1.75 90 -160",
        't' => "M2 9.5 L2 1.8 A4 1.8 2 1.8 180 280 M0 7 L5 7",
        'u' => "M0 7 L0 3 A3 3 3 3 180 360 M6 7 L6 0",
        'v' => "M0 7 L3 0 L6 7",
        'w' => "M0 7 L2 0 L4 5.5 L6 0 L8 7",
        'x' => "M0 7 L6 0 M0 0 L6 7",
        'y' => "M0 7 L3.1 0 M6.2 7 L1.8 -3",
        'z' => "M0 7 L6 7 L0 0 L6 0",
        'A' => "M0 0 L3.5 10 L7 0 M1.3 3.6 L5.7 3.6",
        'B' => "M0 5 L4 5 A4 7.5 2.6 2.5 -90 90 L0 10 L0 0 L4 0 A4 2.5 3 2.5 -90 90 L0 5",
        'C' => "A4 5 4 5 45 315",
        'D' => "M0 0 L0 10 L3 10 A3 5 4 5 90 -90 L0 0",
        'E' => "M6 10 L0 10 L0 0 L6 0 M0 5 L5 5",
        'F' => "M6 10 L0 10 L0 0 M0 5 L5 5",
        'G' => "A4 5 4 5 45 360 L4.5 5",
        'H' => "M0 0 L0 10 M7 0 L7 10 M0 5 L7 5",
        'I' => "M0 10 L3 10 M1.5 10 L1.5 0 M0 0 L3 0",
        'J' => "M5 10 L5 3 A2.5 3 2.5 3 0 -180",
        'K' => "M0 0 L0 10 M6.5 10 L0 3.5 M2.2 5.6 L7 0",
        'L' => "M0 10 L0 0 L6 0",
        'M' => "M0 0 L0 10 L4 2.5 L8 10 L8 0",
        'N' => "M0 0 L0 10 L7 0 L7 10",
        'O' => "O4 5 4 5",
        'P' => "M0 0 L0 10 L4 10 A4 7.3 3 2.7 90 -90 L0 4.6",
        'Q' => "O4 5 4 5 M5 2.5 L8 -0.5",
        'R' => "M0 0 L0 10 L4 10 A4 7.3 3 2.7 90 -90 L0 4.6 M3.8 4.6 L7 0",
        'S' => "A3.6 7.5 3.4 2.5 35 270 A3.6 2.5 3.6 2.5 90 -145",
        'T' => "M0 10 L7 10 M3.5 10 L3.5 0",
        'U' => "M0 10 L0 3.5 A3.5 3.5 3.5 3.5 180 360 L7 10",
        'V' => "M0 10 L3.5 0 L7 10",
        'W' => "M0 10 L2.3 0 L4.5 8 L6.7 0 L9 10",
        'X' => "M0 10 L7 0 M0 0 L7 10",
        'Y' => "M0 10 L3.5 5 L7 10 M3.5 5 L3.5 0",
        'Z' => "M0 10 L7 10 L0 0 L7 0",
        '.' => "M0 0 L0 0.1",
        ',' => "M0.6 0.4 L-0.2 -1.8",
        '-' | '−' => "M0 4 L4 4",
        '+' => "M0 4 L6 4 M3 1 L3 7",
        '=' => "M0 5.5 L5.5 5.5 M0 2.5 L5.5 2.5",
        ':' => "M0 0 L0 0.1 M0 5.5 L0 5.6",
        ';' => "M0 5.5 L0 5.6 M0.6 0.4 L-0.2 -1.8",
        '(' => "A3 4 3 7 120 240",
        ')' => "A0 4 3 7 60 -60",
        '[' => "M2 11 L0 11 L0 -2 L2 -2",
        ']' => "M0 11 L2 11 L2 -2 L0 -2",
        '/' => "M0 -1 L5 10",
        '°' => "O1.6 8.4 1.6 1.6",
        '%' => "M0 0 L7 10 O1.5 8.3 1.5 1.7 O5.5 1.7 1.5 1.7",
        '_' => "M0 -1.5 L6 -1.5",
        '×' => "M0 1.5 L5 6.5 M0 6.5 L5 1.5",
        '\'' => "M0 10 L0 7",
        '"' => "M0 10 L0 7 M2 10 L2 7",
        '!' => "M0 10 L0 3 M0 0 L0 0.1",
        '?' => "A3 7.5 3 2.5 160 -60 L3 3.3 L3 2.8 M3 0 L3 0.1",
        '<' => "M5 7 L0 3.5 L5 0",
        '>' => "M0 7 L5 3.5 L0 0",
        '#' => "M2 0 L3 10 M5 0 L6 10 M0 3.5 L7.5 3.5 M0.5 6.5 L8 6.5",
        '*' => "M2.5 8 L2.5 4 M0.6 7 L4.4 5 M0.6 5 L4.4 7",
        '|' => "M0 11 L0 -2",
        'μ' => "M0 7 L0 -3 M0 3 A3 3 3 3 180 360 M6 7 L6 0",
        _ => "M0 0 L6 0 L6 10 L0 10 L0 0",
    }
}

/// The strokes of a glyph in grid units (y up, baseline at 0), shifted so that its leftmost
/// point is at x = 0, and its width.
fn glyph(c: char) -> (Vec<Vec<[f64; 2]>>, f64) {
    let mut strokes: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut words = glyph_program(c).split_whitespace();
    let numbers = |first: &str, count: usize, words: &mut dyn Iterator<Item = &str>| {
        let mut v = vec![first.parse::<f64>().unwrap_or(0.0)];
        for _ in 1..count {
            v.push(words.next().and_then(|w| w.parse().ok()).unwrap_or(0.0));
        }
        v
    };
    while let Some(word) = words.next() {
        let (command, rest) = word.split_at(1);
        match command {
            "M" | "L" => {
                let v = numbers(rest, 2, &mut words);
                if command == "M" || strokes.is_empty() {
                    strokes.push(Vec::new());
                }
                if let Some(s) = strokes.last_mut() {
                    s.push([v[0], v[1]]);
                }
            }
            "A" | "O" => {
                let count = if command == "A" { 6 } else { 4 };
                let v = numbers(rest, count, &mut words);
                let (a0, a1) = if command == "A" {
                    (v[4], v[5])
                } else {
                    (0.0, 360.0)
                };
                if command == "O" || strokes.is_empty() {
                    strokes.push(Vec::new());
                }
                let steps = ((a1 - a0).abs() / 12.0).ceil().max(4.0) as usize;
                if let Some(s) = strokes.last_mut() {
                    for i in 0..=steps {
                        let a = (a0 + (a1 - a0) * i as f64 / steps as f64).to_radians();
                        s.push([v[0] + v[2] * a.cos(), v[1] + v[3] * a.sin()]);
                    }
                }
            }
            _ => {}
        }
    }
    let min_x = strokes
        .iter()
        .flatten()
        .map(|p| p[0])
        .fold(f64::INFINITY, f64::min);
    let max_x = strokes
        .iter()
        .flatten()
        .map(|p| p[0])
        .fold(f64::NEG_INFINITY, f64::max);
    if !min_x.is_finite() {
        return (strokes, 0.0);
    }
    for p in strokes.iter_mut().flatten() {
        p[0] -= min_x;
    }
    (strokes, max_x - min_x)
}

/// Stroke width, pixels, for text of cap height `cap_px`.
pub(crate) fn stroke_width(cap_px: f64) -> f64 {
    (cap_px * 0.12).max(1.0)
}

/// Width in pixels of `text` at cap height `cap_px` (from the first glyph's left edge to the
/// last glyph's right edge, strokes included).
pub(crate) fn text_width(text: &str, cap_px: f64) -> f64 {
    let unit = cap_px / CAP;
    let mut width = 0.0;
    let mut count = 0;
    for c in text.chars() {
        width += if c == ' ' { SPACE } else { glyph(c).1 + GAP };
        count += 1;
    }
    if count == 0 {
        return 0.0;
    }
    (width - GAP) * unit + stroke_width(cap_px)
}

/// Highest and lowest point of any glyph above and below the baseline, grid units (the box
/// every designed glyph stays in, tested below).
const ASCENT: f64 = 11.1;
const DESCENT: f64 = 3.1;

/// The rows of pixels (top, bottom; y down) that text with its baseline at `y_baseline` and
/// cap height `cap_px` can touch, whatever it says: from the top of the tallest glyph to the
/// bottom of the descenders, strokes included.
pub(crate) fn text_rows(y_baseline: f64, cap_px: f64) -> (f64, f64) {
    let (unit, half_stroke) = (cap_px / CAP, 0.5 * stroke_width(cap_px));
    (
        y_baseline - ASCENT * unit - half_stroke,
        y_baseline + DESCENT * unit + half_stroke,
    )
}

/// The strokes (polylines, pixel coordinates, y down) of `text` written with its left edge at
/// `x_left` and its baseline at `y_baseline`, at cap height `cap_px`.
pub(crate) fn text_strokes(
    text: &str,
    x_left: f64,
    y_baseline: f64,
    cap_px: f64,
) -> Vec<Vec<[f64; 2]>> {
    let unit = cap_px / CAP;
    let half_stroke = 0.5 * stroke_width(cap_px);
    let mut pen = x_left + half_stroke;
    let mut out = Vec::new();
    for c in text.chars() {
        if c == ' ' {
            pen += SPACE * unit;
            continue;
        }
        let (strokes, width) = glyph(c);
        for s in strokes {
            out.push(
                s.iter()
                    .map(|p| [pen + p[0] * unit, y_baseline - p[1] * unit])
                    .collect(),
            );
        }
        pen += (width + GAP) * unit;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_designed_glyph_stays_in_its_box() {
        let chars = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.,-+=:;()[]/°%_×'\"!?<>#*|μ";
        for c in chars.chars() {
            let (strokes, width) = glyph(c);
            assert!(!strokes.is_empty(), "{c:?} has no stroke");
            assert!((0.0..=10.0).contains(&width), "{c:?} width {width}");
            for p in strokes.iter().flatten() {
                assert!(
                    p[1] >= -DESCENT && p[1] <= ASCENT,
                    "{c:?} point {p:?} off the grid"
                );
            }
            // A designed glyph is not the fallback box.
            assert_ne!(glyph_program(c), glyph_program('\u{1}'), "{c:?}");
        }
    }

    #[test]
    fn text_grows_with_its_length_and_size() {
        assert!(text_width("123", 10.0) > text_width("12", 10.0));
        assert!(text_width("12", 20.0) > 1.9 * text_width("12", 10.0));
        assert_eq!(text_width("", 10.0), 0.0);
        let strokes = text_strokes("1.5", 0.0, 20.0, 10.0);
        let right = strokes.iter().flatten().map(|p| p[0]).fold(0.0, f64::max);
        assert!(right <= text_width("1.5", 10.0) + 1e-9);
    }
}
