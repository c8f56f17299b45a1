//! Airfoil coordinate text (`.dat`): Selig, where line 1 is a title and then one `x y` pair
//! per line, and Lednicer, recognised automatically (see [`crate::lednicer`]).
//!
//! Owns parsing only; it takes the text (the caller reads the file) and does no geometric
//! checking beyond what the format needs: use [`crate::loops::validate_loop`] on the result.
//! Lines may end in LF, CRLF or a lone CR (old Mac files); error messages echo at most the
//! first 60 characters of a line.

use crate::dat_lines::{data_lines, drop_repeated_closing_point, parse_pair};
use crate::{CurveError, Point2};

/// Parses airfoil `.dat` text, Selig or Lednicer, into the points of one closed loop.
///
/// Lednicer text (see [`crate::lednicer`]) is recognised by its counts line and handed to
/// [`crate::lednicer::parse`]. Otherwise the text is Selig: line 1 is the title and is ignored
/// whatever it holds. Every later non-blank line must be exactly two numbers separated by
/// white space. A final point that repeats the first one (within 1e-12 of the loop's size,
/// files "closed by repetition") is dropped, so the result follows the crate convention of an
/// implicitly closed loop.
///
/// # Errors
/// [`CurveError::MalformedLine`] or [`CurveError::NonFiniteCoordinate`] naming the 1-based
/// line; [`CurveError::TooFewPoints`] when fewer than three points remain.
pub fn parse(text: &str) -> Result<Vec<Point2<f64>>, CurveError> {
    if crate::lednicer::looks_like_lednicer(text) {
        return crate::lednicer::parse(text);
    }
    let mut points = Vec::new();
    for (line_number, line) in data_lines(text) {
        points.push(parse_pair(line_number, line)?);
    }
    drop_repeated_closing_point(&mut points);
    if points.len() < 3 {
        return Err(CurveError::TooFewPoints {
            count: points.len(),
        });
    }
    Ok(points)
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

    /// D10 (issue 15): CR-only line ends (old Mac files) read as zero points.
    #[test]
    fn cr_lf_and_crlf_line_ends_are_all_accepted() {
        let lf = "foil\n1 0\n0.5 0.1\n0 0\n0.5 -0.1\n";
        let expected = parse(lf).unwrap();
        assert_eq!(expected.len(), 4);
        assert_eq!(parse(&lf.replace('\n', "\r")).unwrap(), expected);
        assert_eq!(parse(&lf.replace('\n', "\r\n")).unwrap(), expected);
        // line numbers count CR lines too, and CRLF as one
        let bad = "foil\r1 0\r0.5 x\r";
        assert!(matches!(
            parse(bad),
            Err(CurveError::MalformedLine { line: 3, .. })
        ));
        let bad = "foil\r\n1 0\r\n0.5 x\r\n";
        assert!(matches!(
            parse(bad),
            Err(CurveError::MalformedLine { line: 3, .. })
        ));
    }

    /// D10 (issue 15): a 1 MB line was echoed whole in the message.
    #[test]
    fn long_lines_are_truncated_in_messages() {
        let long = "7 ".repeat(500_000);
        let text = format!("foil\n1 0\n{long}\n");
        let message = parse(&text).unwrap_err().to_string();
        assert!(message.len() < 120, "{} chars", message.len());
        assert!(
            message.contains("line 3") && message.contains('…'),
            "{message}"
        );
        let multibyte = format!("foil\n{}\n", "é".repeat(100));
        assert!(parse(&multibyte).unwrap_err().to_string().contains('…'));
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
