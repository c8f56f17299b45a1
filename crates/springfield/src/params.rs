//! Spring coefficients and solver settings, with the dissertation's values as defaults. Both
//! structs deserialise with `#[serde(default)]`, so a case file sets only what it changes.

use serde::{Deserialize, Serialize};

use crate::error::SpringError;

/// Coefficients of the spring models (all dimensionless).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SpringParams {
    /// K_extru: stiffness of the extrusion (parent–child) spring. Default 1 (dissertation, 2D).
    pub k_extrusion: f64,
    /// K_nei: stiffness of the neighbour (A–K–B) spring. Default 1 (dissertation, 2D).
    pub k_neighbour: f64,
    /// K_ang: stiffness of the angle spring. Default 1 (dissertation).
    pub k_angle: f64,
    /// Fac_A: divides the angle spring force (larger = softer). Default 20 (dissertation).
    pub fac_a: f64,
    /// Fac_B: cap of the shape factor (|AK|+|KB|)/(2|KO|) of the angle spring. Default 50
    /// (dissertation).
    pub fac_b: f64,
    /// C_percent: share of the angle spring force that acts on the centre node K (the child
    /// O gets the rest). Default 0.5 (dissertation).
    pub c_percent: f64,
    /// Aspect ratio (|AK|+|KB|)/(2|KP|) below which the neighbour spring is strengthened
    /// (§4.1, "a given global factor" in the text). Default 4.
    pub neighbour_boost_below_aspect: f64,
    /// Largest strengthening factor of the neighbour spring, reached as the aspect ratio goes
    /// to zero (the text multiplies by Fac_A = 20). Default 20.
    pub neighbour_boost: f64,
    /// The angle spring is off until its extrusion edge has reached this fraction of its
    /// ideal length (§4.1: "blocked until the node moves close to its target"). Default 0.8.
    pub angle_activation_ratio: f64,
}

impl Default for SpringParams {
    fn default() -> Self {
        SpringParams {
            k_extrusion: 1.0,
            k_neighbour: 1.0,
            k_angle: 1.0,
            fac_a: 20.0,
            fac_b: 50.0,
            c_percent: 0.5,
            neighbour_boost_below_aspect: 4.0,
            neighbour_boost: 20.0,
            angle_activation_ratio: 0.8,
        }
    }
}

impl SpringParams {
    /// Checks every coefficient's range.
    pub fn check(&self) -> Result<(), SpringError> {
        let nonneg = [
            ("k_extrusion", self.k_extrusion),
            ("k_neighbour", self.k_neighbour),
            ("k_angle", self.k_angle),
            (
                "neighbour_boost_below_aspect",
                self.neighbour_boost_below_aspect,
            ),
            ("angle_activation_ratio", self.angle_activation_ratio),
        ];
        for (name, value) in nonneg {
            if !(value.is_finite() && value >= 0.0) {
                return Err(SpringError::BadParameter {
                    name,
                    value,
                    expected: "finite and >= 0",
                });
            }
        }
        let positive = [("fac_a", self.fac_a), ("fac_b", self.fac_b)];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(SpringError::BadParameter {
                    name,
                    value,
                    expected: "finite and > 0",
                });
            }
        }
        if !(self.neighbour_boost.is_finite() && self.neighbour_boost >= 1.0) {
            return Err(SpringError::BadParameter {
                name: "neighbour_boost",
                value: self.neighbour_boost,
                expected: "finite and >= 1",
            });
        }
        if !(0.0..=1.0).contains(&self.c_percent) {
            return Err(SpringError::BadParameter {
                name: "c_percent",
                value: self.c_percent,
                expected: "in [0, 1]",
            });
        }
        Ok(())
    }
}

/// Settings of the damped explicit pseudo-time solver ([`crate::solve()`]).
///
/// Lengths are relative to each node's own length scale, so the same settings serve a 1e-6
/// first layer and a 10-chord far field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SolverParams {
    /// Iteration budget. Default 200. Running out is reported (`converged: false`), not an
    /// error.
    pub max_iterations: usize,
    /// Pseudo-time step ω: a node moves by ω·F/(S·m) per iteration, F its force, S the sum
    /// of its springs' stiffnesses, m its mass. In (0, 2); default 0.7.
    pub relaxation: f64,
    /// Largest move of a node in one iteration, as a fraction of its length scale.
    /// Default 0.25.
    pub max_move: f64,
    /// Separate move limits (§4.1, for movement: the extrusion springs and the neighbour and
    /// angle springs each with their own limit): when set, a node's move along its extrusion
    /// axis ([`crate::ForceModel::extrusion_axis`]) is limited by `max_move` and its move
    /// across it by this, both as fractions of its length scale. The two are the groups'
    /// moves: the extrusion force lies along the edge, the neighbour and angle forces on a
    /// child at right angles to it. `None` (the default, the mesher's): `max_move` for the
    /// whole move.
    pub lateral_max_move: Option<f64>,
    /// Iterations at constant (unit) mass before oscillating nodes may get heavier (§4.1).
    /// Default 30.
    pub constant_mass_iterations: usize,
    /// Factor applied to the mass of a node found oscillating. Default 2.
    pub mass_factor: f64,
    /// Distance a node may travel (as a fraction of its scale) before it is judged: if its
    /// net displacement since the last judgement is less than half that travel it is
    /// oscillating and gets heavier; either way its travel is reset. Default 0.5.
    pub judge_travel: f64,
    /// Convergence: largest move of any node in one iteration, relative to its scale.
    /// Default 1e-3.
    pub tolerance: f64,
    /// Active set of [`crate::solve_active()`]: a node stays awake while it, or a node its
    /// force depends on, moved by at least this fraction of `tolerance` (relative to its
    /// scale) in the last iteration. In (0, 1]; smaller is closer to updating every node
    /// every iteration. Default 0.1.
    pub wake_fraction: f64,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            max_iterations: 200,
            relaxation: 0.7,
            max_move: 0.25,
            lateral_max_move: None,
            constant_mass_iterations: 30,
            mass_factor: 2.0,
            judge_travel: 0.5,
            tolerance: 1e-3,
            wake_fraction: 0.1,
        }
    }
}

impl SolverParams {
    /// Checks every setting's range.
    pub fn check(&self) -> Result<(), SpringError> {
        let lateral = self.lateral_max_move.unwrap_or(self.max_move);
        let checks: [(&'static str, f64, bool, &'static str); 7] = [
            ("lateral_max_move", lateral, lateral > 0.0, "finite and > 0"),
            (
                "relaxation",
                self.relaxation,
                self.relaxation > 0.0 && self.relaxation < 2.0,
                "in (0, 2)",
            ),
            (
                "max_move",
                self.max_move,
                self.max_move > 0.0,
                "finite and > 0",
            ),
            (
                "mass_factor",
                self.mass_factor,
                self.mass_factor >= 1.0,
                "finite and >= 1",
            ),
            (
                "judge_travel",
                self.judge_travel,
                self.judge_travel > 0.0,
                "finite and > 0",
            ),
            (
                "tolerance",
                self.tolerance,
                self.tolerance > 0.0,
                "finite and > 0",
            ),
            (
                "wake_fraction",
                self.wake_fraction,
                self.wake_fraction > 0.0 && self.wake_fraction <= 1.0,
                "in (0, 1]",
            ),
        ];
        for (name, value, ok, expected) in checks {
            if !(value.is_finite() && ok) {
                return Err(SpringError::BadParameter {
                    name,
                    value,
                    expected,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_partial_input_keeps_the_other_defaults() {
        SpringParams::default().check().unwrap();
        SolverParams::default().check().unwrap();
        let p: SpringParams = serde_json::from_str(r#"{"fac_a": 10.0}"#).unwrap();
        assert_eq!(p.fac_a, 10.0);
        assert_eq!(p.fac_b, SpringParams::default().fac_b);
    }

    #[test]
    fn out_of_range_values_are_named() {
        let p = SpringParams {
            c_percent: 1.5,
            ..SpringParams::default()
        };
        let e = p.check().unwrap_err();
        assert!(e.to_string().contains("c_percent"), "{e}");
        let s = SolverParams {
            relaxation: 2.5,
            ..SolverParams::default()
        };
        assert!(s.check().unwrap_err().to_string().contains("relaxation"));
    }
}
