//! Lednicer airfoil coordinate text, the other common `.dat` layout: line 1 a title, then a
//! line with the point counts of the two surfaces `NU NL` (often written `61. 61.`), then the
//! upper surface from the leading to the trailing edge, then the lower surface from the
//! leading to the trailing edge (blank lines between the blocks are ignored).
//!
//! Owns this layout only; [`crate::selig::parse`] recognises it and hands it here, so callers
//! need not know which layout a file uses. The result is one loop in the Selig order (upper
//! trailing edge → leading edge → lower trailing edge), the shared leading-edge point and a
//! repeated trailing-edge point listed once.

use crate::dat_lines::{data_lines, drop_repeated_closing_point, excerpt, parse_pair};
use crate::{CurveError, Point2};

/// The surface counts `(NU, NL)` if the first data line is two whole numbers ≥ 2 and exactly
/// `NU + NL` data lines follow it.
fn counts(text: &str) -> Option<(usize, usize)> {
    let mut lines = data_lines(text);
    let (_, first) = lines.next()?;
    let mut tokens = first.split_whitespace();
    let (Some(a), Some(b), None) = (tokens.next(), tokens.next(), tokens.next()) else {
        return None;
    };
    let whole = |token: &str| -> Option<usize> {
        let value: f64 = token.parse().ok()?;
        (value.fract() == 0.0 && (2.0..=1e7).contains(&value)).then_some(value as usize)
    };
    let (upper, lower) = (whole(a)?, whole(b)?);
    (lines.count() == upper + lower).then_some((upper, lower))
}

/// Whether the text is in the Lednicer layout (a counts line that matches the points).
pub fn looks_like_lednicer(text: &str) -> bool {
    counts(text).is_some()
}

/// Parses Lednicer text into the points of one closed loop, counter-clockwise when the upper
/// surface is above the lower one.
///
/// # Errors
/// [`CurveError::MalformedLine`] when the counts line is missing or does not match the number
/// of points; [`CurveError::MalformedLine`] or [`CurveError::NonFiniteCoordinate`] naming a
/// bad coordinate line; [`CurveError::TooFewPoints`] when fewer than three points remain.
pub fn parse(text: &str) -> Result<Vec<Point2<f64>>, CurveError> {
    let Some((upper_count, _)) = counts(text) else {
        let (line, content) = data_lines(text).next().unwrap_or((2, ""));
        return Err(CurveError::MalformedLine {
            line,
            content: format!(
                "{} (expected the Lednicer counts \"NU NL\" matching the points that follow)",
                excerpt(content)
            ),
        });
    };
    let mut points = Vec::new();
    for (line_number, line) in data_lines(text).skip(1) {
        points.push(parse_pair(line_number, line)?);
    }
    let lower = points.split_off(upper_count);
    let mut upper = points;
    upper.reverse();
    let shared_leading_edge = upper.last() == lower.first();
    upper.extend(lower.into_iter().skip(usize::from(shared_leading_edge)));
    drop_repeated_closing_point(&mut upper);
    if upper.len() < 3 {
        return Err(CurveError::TooFewPoints { count: upper.len() });
    }
    Ok(upper)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: &str = "TEST FOIL\n3. 3.\n\n0 0\n0.5 0.1\n1 0\n\n0 0\n0.5 -0.1\n1 0\n";

    #[test]
    fn reads_both_surfaces_into_one_selig_ordered_loop() {
        let points = parse(SMALL).unwrap();
        let expected = [(1.0, 0.0), (0.5, 0.1), (0.0, 0.0), (0.5, -0.1)];
        assert_eq!(points.len(), expected.len(), "{points:?}");
        for (p, (x, y)) in points.iter().zip(expected) {
            assert_eq!(*p, Point2::new(x, y));
        }
        assert!(crate::loops::is_counter_clockwise(&points));
        // and the Selig entry point recognises it
        assert_eq!(crate::selig::parse(SMALL).unwrap(), points);
    }

    #[test]
    fn counts_that_do_not_match_are_not_lednicer() {
        let short = SMALL.replace("3. 3.", "3. 4.");
        assert!(!looks_like_lednicer(&short));
        assert!(matches!(
            parse(&short),
            Err(CurveError::MalformedLine { line: 2, .. })
        ));
        // a Selig file starting at (1, 0) is never taken for Lednicer
        assert!(!looks_like_lednicer("foil\n1 0\n0 0\n1 0\n"));
    }

    #[test]
    fn a_distinct_leading_edge_and_an_open_trailing_edge_are_kept() {
        let text = "t\n2 2\n0 0.001\n1 0.002\n0 -0.001\n1 -0.002\n";
        let points = parse(text).unwrap();
        assert_eq!(points.len(), 4);
        assert_eq!(points[0], Point2::new(1.0, 0.002));
        assert_eq!(points[3], Point2::new(1.0, -0.002));
    }
}
