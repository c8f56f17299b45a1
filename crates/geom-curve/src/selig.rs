//! Selig airfoil coordinate text: line 1 is a title, then one `x y` pair per line.
//!
//! Owns parsing only; it takes the text (the caller reads the file) and does no geometric
//! checking beyond what the format needs: use [`crate::loops::validate_loop`] on the result.

use crate::{CurveError, Point2};

/// Parses Selig text into the points of one closed loop.
///
/// Line 1 is the title and is ignored whatever it holds. Every later non-blank line must be
/// exactly two numbers separated by white space. A final point that repeats the first one
/// (within 1e-12 of the loop's size, files "closed by repetition") is dropped, so the result
/// follows the crate convention of an implicitly closed loop.
///
/// # Errors
/// [`CurveError::MalformedLine`] or [`CurveError::NonFiniteCoordinate`] naming the 1-based
/// line; [`CurveError::TooFewPoints`] when fewer than three points remain.
pub fn parse(text: &str) -> Result<Vec<Point2<f64>>, CurveError> {
    let mut points = Vec::new();
    for (index, raw_line) in text.lines().enumerate().skip(1) {
        let line_number = index + 1;
        let line = raw_line.trim();
        if line.is_empty() {
            continue;
        }
        let malformed = || CurveError::MalformedLine {
            line: line_number,
            content: line.to_string(),
        };
        let mut tokens = line.split_whitespace();
        let (Some(x_text), Some(y_text), None) = (tokens.next(), tokens.next(), tokens.next())
        else {
            return Err(malformed());
        };
        let x: f64 = x_text.parse().map_err(|_| malformed())?;
        let y: f64 = y_text.parse().map_err(|_| malformed())?;
        if !x.is_finite() || !y.is_finite() {
            return Err(CurveError::NonFiniteCoordinate {
                line: line_number,
                content: line.to_string(),
            });
        }
        points.push(Point2::new(x, y));
    }
    drop_repeated_closing_point(&mut points);
    if points.len() < 3 {
        return Err(CurveError::TooFewPoints {
            count: points.len(),
        });
    }
    Ok(points)
}

/// Removes the last point when it repeats the first within 1e-12 of the bounding-box diagonal.
fn drop_repeated_closing_point(points: &mut Vec<Point2<f64>>) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_title_blank_lines_and_drops_repeated_first_point() {
        let text = "My foil\n1.0 0.0\n\n 0.5  0.1 \n0.0 0.0\r\n0.5 -0.1\n1.0 0.0\n";
        let points = parse(text).unwrap();
        assert_eq!(points.len(), 4);
        assert_eq!(points[1], Point2::new(0.5, 0.1));
        assert_eq!(points[3], Point2::new(0.5, -0.1));
    }

    #[test]
    fn title_line_is_never_data() {
        let text = "1.0 0.0\n0.0 0.0\n0.5 0.5\n0.2 0.7\n";
        assert_eq!(parse(text).unwrap().len(), 3);
    }

    #[test]
    fn malformed_line_names_its_number_and_content() {
        let text = "t\n1 0\n0 0\n0.5 zero\n";
        assert_eq!(
            parse(text),
            Err(CurveError::MalformedLine {
                line: 4,
                content: "0.5 zero".into()
            })
        );
        let three_numbers = "t\n1 0 0\n";
        assert!(matches!(
            parse(three_numbers),
            Err(CurveError::MalformedLine { line: 2, .. })
        ));
        let one_number = "t\n1 0\n\n0.5\n";
        assert!(matches!(
            parse(one_number),
            Err(CurveError::MalformedLine { line: 4, .. })
        ));
    }

    #[test]
    fn non_finite_values_are_rejected_with_the_line() {
        for bad in ["NaN 0", "0 inf", "-infinity 1"] {
            let text = format!("t\n1 0\n{bad}\n0 1\n");
            assert_eq!(
                parse(&text),
                Err(CurveError::NonFiniteCoordinate {
                    line: 3,
                    content: bad.into()
                })
            );
        }
    }

    #[test]
    fn too_few_points_is_an_error() {
        assert_eq!(parse(""), Err(CurveError::TooFewPoints { count: 0 }));
        assert_eq!(
            parse("t\n0 0\n1 0\n0 0\n"),
            Err(CurveError::TooFewPoints { count: 2 })
        );
    }
}
