//! Where an airfoil sits and how fine its first layer is, shared by airfoil files and case
//! files: the reference chord (the walls' x-extent) and the quarter-chord point, the angle of
//! attack about it (nose up), a far-field circle a number of chords about it, and the first
//! layer height of a target y⁺ at a Reynolds number, by the flat-plate estimate at x = c:
//! `Cf = 0.026 / Re^(1/7)` (Schlichting, White), `y = y⁺ c / (Re √(Cf/2))`.

use serde::Serialize;

/// Points on a far-field circle (its geometry, not its mesh spacing).
pub const FARFIELD_POINTS: usize = 256;

/// The first layer height for a target y⁺ at Reynolds number `re` (based on `chord`), by the
/// flat-plate estimate of the module doc.
pub fn first_height(yplus: f64, re: f64, chord: f64) -> f64 {
    let cf = 0.026 / re.powf(1.0 / 7.0);
    yplus * chord / (re * (0.5 * cf).sqrt())
}

/// The inputs that placed an airfoil and set its first layer, when they were given (the
/// report's `inputs` echoes them).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Placement {
    /// The angle of attack in degrees, nose up, about the quarter chord.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aoa_deg: Option<f64>,
    /// The target y⁺ of the first layer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yplus: Option<f64>,
    /// The Reynolds number based on the chord.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub re: Option<f64>,
    /// The far-field circle's radius in chords.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub farfield_chords: Option<f64>,
    /// The reference chord: the walls' extent in x.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub chord: Option<f64>,
}

/// The walls' reference chord and leading edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The leftmost x of every wall point.
    pub x_min: f64,
    /// The walls' extent in x.
    pub chord: f64,
    /// The y of the leftmost wall point (the first one found).
    pub y_le: f64,
}

impl Frame {
    /// The frame of the wall points `walls`; `None` when they have no extent in x.
    pub fn of<'a>(walls: impl Iterator<Item = &'a [[f64; 2]]> + Clone) -> Option<Frame> {
        let all = || walls.clone().flat_map(|l| l.iter());
        let x_min = all().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        let x_max = all().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
        let chord = x_max - x_min;
        if !(chord.is_finite() && chord > 0.0) {
            return None;
        }
        let y_le = all().find(|p| p[0] == x_min).map_or(0.0, |p| p[1]);
        Some(Frame { x_min, chord, y_le })
    }

    /// The quarter-chord point `(x_min + c/4, y_le)`.
    pub fn quarter_chord(&self) -> [f64; 2] {
        [self.x_min + 0.25 * self.chord, self.y_le]
    }

    /// `points` turned by `aoa_deg` nose up (clockwise in x-right, y-up axes) about the
    /// quarter chord; left as they are at 0 (a turn by zero would still round them).
    pub fn pitch(&self, points: &mut [[f64; 2]], aoa_deg: f64) {
        if aoa_deg == 0.0 {
            return;
        }
        let centre = self.quarter_chord();
        let (sin, cos) = (-aoa_deg.to_radians()).sin_cos();
        for p in points {
            let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
            *p = [
                centre[0] + dx * cos - dy * sin,
                centre[1] + dx * sin + dy * cos,
            ];
        }
    }

    /// The far-field circle of `radius_chords` chords about the quarter chord.
    pub fn farfield(&self, radius_chords: f64) -> Result<Vec<[f64; 2]>, geom_curve::CurveError> {
        let [x, y] = self.quarter_chord();
        let circle = geom_curve::circle_points(
            geom_curve::Point2::new(x, y),
            radius_chords * self.chord,
            FARFIELD_POINTS,
        )?;
        Ok(circle.iter().map(|p| [p.x, p.y]).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_height_is_the_flat_plate_estimate() {
        // Re 6e6, y+ 1: Cf = 0.026 / 6e6^(1/7) = 0.002799, u_tau = 0.03741, y = 1 / (6e6 u_tau)
        let y = first_height(1.0, 6e6, 1.0);
        assert!((y - 4.455e-6).abs() < 0.005e-6, "{y}");
        // linear in y+ and in the chord
        assert!((first_height(30.0, 6e6, 2.0) - 60.0 * y).abs() < 1e-15);
    }

    #[test]
    fn the_nose_goes_up_about_the_quarter_chord() {
        let wall = [[0.0, 0.0], [1.0, 0.0]];
        let frame = Frame::of([&wall[..]].into_iter()).unwrap();
        assert_eq!(frame.quarter_chord(), [0.25, 0.0]);
        let mut p = wall;
        frame.pitch(&mut p, 90.0);
        assert!(
            (p[0][1] - 0.25).abs() < 1e-12 && (p[1][1] + 0.75).abs() < 1e-12,
            "{p:?}"
        );
        assert!(Frame::of([&[[1.0, 0.0]][..]].into_iter()).is_none());
    }
}
