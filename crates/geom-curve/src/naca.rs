//! NACA 4-digit sections generated from the standard camber-line and thickness formulas
//! (Abbott & von Doenhoff, "Theory of Wing Sections", §6.4), unit chord, leading edge at the
//! origin.
//!
//! Owns point generation only; no file IO and no curve fitting.

use crate::{CurveError, Point2};

/// x⁴ coefficient of the thickness polynomial that closes the trailing edge (zero thickness
/// at x = 1), as in the NASA Turbulence Modeling Resource definition.
pub const A4_CLOSED_TE: f64 = -0.1036;
/// x⁴ coefficient of the classical thickness polynomial (trailing-edge thickness 0.252 % of
/// the thickness ratio ×10, e.g. 0.00252 c for a 12 % section).
pub const A4_OPEN_TE: f64 = -0.1015;

/// The points of a NACA 4-digit section `MPTT` (camber `M` % at `P`/10 chord, thickness
/// `TT` %), as one counter-clockwise loop.
///
/// `points_per_side` stations (leading and trailing edge included) are cosine-spaced in x:
/// x = (1 − cos β)/2, β uniform in [0, π]. The loop starts at the upper trailing-edge point,
/// runs over the upper surface to the leading edge (listed once) and back over the lower
/// surface. With `closed_te` the thickness uses `a4 = −0.1036`, the upper and lower
/// trailing-edge points coincide and are listed once (2·N − 2 points); otherwise
/// `a4 = −0.1015` and the lower trailing-edge point ends the loop (2·N − 1 points), the
/// closing edge being the blunt base. The first point is never repeated.
///
/// # Errors
/// [`CurveError::InvalidNaca`] unless `digits` is four ASCII digits with a positive thickness
/// and, when the camber is non-zero, a non-zero camber position;
/// [`CurveError::InvalidParameter`] when `points_per_side < 3` or above half of
/// [`crate::MAX_GENERATED_POINTS`].
pub fn naca4(
    digits: &str,
    points_per_side: usize,
    closed_te: bool,
) -> Result<Vec<Point2<f64>>, CurveError> {
    let invalid = |reason| CurveError::InvalidNaca {
        digits: digits.to_string(),
        reason,
    };
    let bytes = digits.as_bytes();
    if bytes.len() != 4 || !bytes.iter().all(u8::is_ascii_digit) {
        return Err(invalid(
            "expected exactly four digits, such as \"0012\" or \"2412\"",
        ));
    }
    let digit = |i: usize| f64::from(bytes[i] - b'0');
    let max_camber = digit(0) / 100.0;
    let camber_position = digit(1) / 10.0;
    let thickness = (10.0 * digit(2) + digit(3)) / 100.0;
    if thickness <= 0.0 {
        return Err(invalid("the thickness (last two digits) must be positive"));
    }
    if max_camber > 0.0 && camber_position <= 0.0 {
        return Err(invalid(
            "a cambered section needs a camber position (second digit) above 0",
        ));
    }
    if points_per_side < 3 {
        return Err(CurveError::InvalidParameter {
            name: "points_per_side",
            value: points_per_side as f64,
            reason: "at least 3 stations per side are needed",
        });
    }
    if points_per_side > crate::MAX_GENERATED_POINTS / 2 {
        return Err(CurveError::InvalidParameter {
            name: "points_per_side",
            value: points_per_side as f64,
            reason: "at most 500000 stations per side (the mesh spacing is set separately)",
        });
    }
    let a4 = if closed_te { A4_CLOSED_TE } else { A4_OPEN_TE };
    let section = Section {
        max_camber,
        camber_position,
        thickness,
        a4,
    };

    let last = points_per_side - 1;
    let station = |j: usize| {
        let beta = std::f64::consts::PI * j as f64 / last as f64;
        if j == last {
            1.0
        } else {
            0.5 * (1.0 - beta.cos())
        }
    };
    let mut points = Vec::with_capacity(2 * points_per_side);
    for j in (0..=last).rev() {
        points.push(section.upper(station(j)));
    }
    let lower_end = if closed_te { last - 1 } else { last };
    for j in 1..=lower_end {
        points.push(section.lower(station(j)));
    }
    Ok(points)
}

/// The parameters of one section, as fractions of the chord.
struct Section {
    max_camber: f64,
    camber_position: f64,
    thickness: f64,
    a4: f64,
}

impl Section {
    /// Half thickness at chord station x.
    fn half_thickness(&self, x: f64) -> f64 {
        5.0 * self.thickness
            * (0.2969 * x.sqrt() - 0.1260 * x - 0.3516 * x * x
                + 0.2843 * x * x * x
                + self.a4 * x * x * x * x)
    }

    /// Camber-line height and slope at x.
    fn camber(&self, x: f64) -> (f64, f64) {
        let (m, p) = (self.max_camber, self.camber_position);
        if m == 0.0 {
            (0.0, 0.0)
        } else if x < p {
            (
                m / (p * p) * (2.0 * p * x - x * x),
                2.0 * m / (p * p) * (p - x),
            )
        } else {
            let q = (1.0 - p) * (1.0 - p);
            (
                m / q * ((1.0 - 2.0 * p) + 2.0 * p * x - x * x),
                2.0 * m / q * (p - x),
            )
        }
    }

    fn surface(&self, x: f64, side: f64) -> Point2<f64> {
        let half = self.half_thickness(x);
        let (yc, slope) = self.camber(x);
        let theta = slope.atan();
        Point2::new(
            x - side * half * theta.sin(),
            yc + side * half * theta.cos(),
        )
    }

    fn upper(&self, x: f64) -> Point2<f64> {
        self.surface(x, 1.0)
    }

    fn lower(&self, x: f64) -> Point2<f64> {
        self.surface(x, -1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loops::signed_area;

    #[test]
    fn point_counts_and_orientation() {
        let closed = naca4("2412", 51, true).unwrap();
        assert_eq!(closed.len(), 100);
        let open = naca4("2412", 51, false).unwrap();
        assert_eq!(open.len(), 101);
        assert!(signed_area(&closed) > 0.0);
        assert!(signed_area(&open) > 0.0);
        // the leading edge is listed once, at the origin
        assert_eq!(closed.iter().filter(|p| p.x == 0.0).count(), 1);
        // the closed trailing edge is at (1, 0) and listed once
        assert!((closed[0] - Point2::new(1.0, 0.0)).norm() < 1e-15);
        assert!(closed[closed.len() - 1].x < 1.0);
    }

    #[test]
    fn thickness_ratio_is_respected() {
        for (digits, t) in [("0012", 0.12), ("0006", 0.06), ("0021", 0.21)] {
            let points = naca4(digits, 201, true).unwrap();
            let max_y = points.iter().map(|p| p.y).fold(f64::MIN, f64::max);
            let min_y = points.iter().map(|p| p.y).fold(f64::MAX, f64::min);
            assert!(((max_y - min_y) - t).abs() < 2e-4 * t / 0.12, "{digits}");
        }
    }

    #[test]
    fn bad_designations_are_errors() {
        for bad in ["", "001", "00120", "00a2", "2012", "0000", "O012"] {
            assert!(
                matches!(naca4(bad, 50, true), Err(CurveError::InvalidNaca { .. })),
                "{bad}"
            );
        }
        assert!(matches!(
            naca4("0012", 2, true),
            Err(CurveError::InvalidParameter { .. })
        ));
    }
}
