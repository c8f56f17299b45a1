//! The line reading shared by the two airfoil `.dat` layouts ([`crate::selig`] and
//! [`crate::lednicer`]): the data lines after the title, one `x y` pair per line, the excerpt
//! of a faulty line echoed in error messages, and the dropping of a repeated closing point.

use crate::{CurveError, Point2};

/// Characters of a faulty line echoed in an error message.
const ECHO_CHARS: usize = 60;

/// The lines after the title that are not blank, trimmed, with their 1-based line numbers.
/// Lines end in LF, CRLF or a lone CR.
pub(crate) fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.split('\n')
        .flat_map(|piece| piece.strip_suffix('\r').unwrap_or(piece).split('\r'))
        .enumerate()
        .skip(1)
        .map(|(index, line)| (index + 1, line.trim()))
        .filter(|(_, line)| !line.is_empty())
}

/// The line as echoed in messages: at most [`ECHO_CHARS`] characters, then "…".
pub(crate) fn excerpt(line: &str) -> String {
    match line.char_indices().nth(ECHO_CHARS) {
        Some((cut, _)) => format!("{}…", &line[..cut]),
        None => line.to_string(),
    }
}

/// The two numbers `x y` of a data line.
pub(crate) fn parse_pair(line_number: usize, line: &str) -> Result<Point2<f64>, CurveError> {
    let malformed = || CurveError::MalformedLine {
        line: line_number,
        content: excerpt(line),
    };
    let mut tokens = line.split_whitespace();
    let (Some(x_text), Some(y_text), None) = (tokens.next(), tokens.next(), tokens.next()) else {
        return Err(malformed());
    };
    let x: f64 = x_text.parse().map_err(|_| malformed())?;
    let y: f64 = y_text.parse().map_err(|_| malformed())?;
    if !x.is_finite() || !y.is_finite() {
        return Err(CurveError::NonFiniteCoordinate {
            line: line_number,
            content: excerpt(line),
        });
    }
    Ok(Point2::new(x, y))
}

/// Removes the last point when it repeats the first within 1e-12 of the bounding-box diagonal.
pub(crate) fn drop_repeated_closing_point(points: &mut Vec<Point2<f64>>) {
    if points.len() < 2 {
        return;
    }
    let diagonal = crate::loops::bounding_box_diagonal(points);
    let first = points[0];
    let last = points[points.len() - 1];
    if (last - first).norm() <= 1e-12 * diagonal {
        points.pop();
    }
}
