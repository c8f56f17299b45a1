//! The mesher's input: boundary loops (already meshed) and parameters, and their checking and
//! orientation. It owns the rule "the domain is inside the far field and outside every wall,
//! or inside the one wall loop when `inside`"; it does not build any mesh.

use geom_predicates::{find_overlapping_pair, point_in_loop, polygon_area, segments_meet};
use mesh_model::Role;
use serde::{Deserialize, Serialize};
use springfield::{SolverParams, SpringParams};

use crate::error::AfsfError;
use crate::geom::Aabb;

/// One closed boundary loop whose nodes are already placed (by `boundary1d` or by hand).
/// Orientation does not matter; the first point is not repeated at the end.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrontLoop {
    /// The boundary nodes, in order around the loop (length units).
    pub points: Vec<[f64; 2]>,
    /// One flag per point: true at sharp corners (trailing edges). Informational: fans are
    /// decided geometrically from the turning angle of the front, corner or not.
    pub is_corner: Vec<bool>,
    /// Wall (layers grow out of the body) or far field (layers grow inward).
    pub role: Role,
    /// A name for people, copied into the mesh patch.
    pub name: String,
}

impl FrontLoop {
    /// A loop without corner flags.
    pub fn new(points: Vec<[f64; 2]>, role: Role, name: impl Into<String>) -> Self {
        let is_corner = vec![false; points.len()];
        FrontLoop {
            points,
            is_corner,
            role,
            name: name.into(),
        }
    }
}

/// Parameters of the linear viscous mesher. Lengths are in the input's length unit; every
/// other threshold is relative to local sizes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AfsfParams {
    /// l_extru: height of the first layer on walls (length). Default 5e-5.
    pub first_height: f64,
    /// G_ratio: growth of the layer height from one layer to the next on walls, > 1.
    /// Default 1.3.
    pub growth: f64,
    /// Largest number of layers grown, at least 1; the region left is filled. Default 60.
    pub max_layers: u32,
    /// Coe_shrink: a new neighbour edge shorter than this fraction of its extrusion edges
    /// breaks and its two nodes merge (quad → triangle). Default 0.65.
    pub coe_shrink: f64,
    /// Mesh the inside of the single wall loop (no far field). Default false.
    pub inside: bool,
    /// Layer height of the far-field front, as a fraction of its local node spacing (its
    /// layers are isotropic). Default 1.0.
    pub farfield_height: f64,
    /// A front node turning by more than this (degrees, toward the region to mesh, i.e. a
    /// convex corner) gets a fan of children. Default 45.
    pub fan_threshold_deg: f64,
    /// Largest apex angle (degrees) of a fan triangle. Default 60.
    pub fan_max_angle_deg: f64,
    /// Closing: a new cell stops (its edge is frozen) when it would come nearer to another
    /// part of the fronts than this factor times max(its height, half its width). Default 1.
    pub closing_factor: f64,
    /// Smallest angle (degrees) the filling of the region left between the fronts refines
    /// toward, by adding nodes inside it (front edges are never split); 0 keeps the bare
    /// constrained Delaunay triangulation of the front nodes. Default 30 (which bounds the
    /// largest angle by 120° wherever it is reached).
    pub fill_min_angle_deg: f64,
    /// Largest angle (degrees) a fill triangle may have before the layered cells touching it
    /// are peeled back into the filled region (never first-layer cells), see
    /// `peel_rounds`. Default 120.
    pub peel_max_angle_deg: f64,
    /// A new layered cell (above the first layer) whose triangles, a quad cut along its
    /// shorter diagonal, have an angle of this many degrees or more is refused: its front
    /// edge freezes and the fill covers the place. Default 130.
    pub cell_max_angle_deg: f64,
    /// Rounds of peeling and filling again; 0 fills once and never peels. Default 8.
    pub peel_rounds: u32,
    /// Narrow gaps: a boundary facet facing another loop nearer than a third of its length
    /// must have a node across the gap that makes a triangle with all angles below this
    /// (degrees); else the gap cannot be meshed with usable cells from these boundary nodes.
    /// Default 150.
    pub gap_max_angle_deg: f64,
    /// Refuse such a gap with an error naming it (default true); when false the mesh is made
    /// anyway and the gap is reported in `AfsfStats::unresolved_gap`.
    pub refuse_narrow_gaps: bool,
    /// Number of top layers that move in each spring solve (the dissertation: three).
    /// Default 3.
    pub moving_layers: u32,
    /// Spring coefficients.
    pub springs: SpringParams,
    /// Solver settings. Default: springfield's, with at most 1000 iterations.
    pub solver: SolverParams,
}

impl Default for AfsfParams {
    fn default() -> Self {
        AfsfParams {
            first_height: 5e-5,
            growth: 1.3,
            max_layers: 60,
            coe_shrink: 0.65,
            inside: false,
            farfield_height: 1.0,
            fan_threshold_deg: 45.0,
            fan_max_angle_deg: 60.0,
            closing_factor: 1.0,
            fill_min_angle_deg: 30.0,
            peel_max_angle_deg: 120.0,
            peel_rounds: 16,
            cell_max_angle_deg: 130.0,
            gap_max_angle_deg: 150.0,
            refuse_narrow_gaps: true,
            moving_layers: 3,
            springs: SpringParams::default(),
            // a handful of nodes where layers fold (a concave corner's first layer, a cusp's
            // fan) settle only after a few hundred steps of the mass schedule; the solve
            // iterates active nodes alone, so the larger budget costs nothing measurable on
            // the built-ins, every one of whose balances then converges (200 left the
            // 30P30N's layers 1 and 24-31 at the limit)
            solver: SolverParams {
                max_iterations: 1000,
                ..SolverParams::default()
            },
        }
    }
}

impl AfsfParams {
    /// Checks every parameter's range.
    pub fn check(&self) -> Result<(), AfsfError> {
        let checks: [(&'static str, f64, bool, &'static str); 11] = [
            (
                "gap_max_angle_deg",
                self.gap_max_angle_deg,
                self.gap_max_angle_deg > 90.0 && self.gap_max_angle_deg <= 180.0,
                "in (90, 180]",
            ),
            (
                "cell_max_angle_deg",
                self.cell_max_angle_deg,
                self.cell_max_angle_deg > 90.0 && self.cell_max_angle_deg <= 180.0,
                "in (90, 180]",
            ),
            (
                "peel_max_angle_deg",
                self.peel_max_angle_deg,
                self.peel_max_angle_deg > 60.0 && self.peel_max_angle_deg <= 180.0,
                "in (60, 180]",
            ),
            (
                "fill_min_angle_deg",
                self.fill_min_angle_deg,
                (0.0..=33.0).contains(&self.fill_min_angle_deg),
                "in [0, 33]",
            ),
            (
                "first_height",
                self.first_height,
                self.first_height > 0.0,
                "> 0",
            ),
            ("growth", self.growth, self.growth > 1.0, "> 1"),
            (
                "coe_shrink",
                self.coe_shrink,
                self.coe_shrink > 0.0 && self.coe_shrink < 1.0,
                "in (0, 1)",
            ),
            (
                "farfield_height",
                self.farfield_height,
                self.farfield_height > 0.0,
                "> 0",
            ),
            (
                "fan_threshold_deg",
                self.fan_threshold_deg,
                self.fan_threshold_deg > 0.0 && self.fan_threshold_deg < 180.0,
                "in (0, 180)",
            ),
            (
                "fan_max_angle_deg",
                self.fan_max_angle_deg,
                self.fan_max_angle_deg >= 10.0 && self.fan_max_angle_deg <= 90.0,
                "in [10, 90]",
            ),
            (
                "closing_factor",
                self.closing_factor,
                self.closing_factor > 0.0,
                "> 0",
            ),
        ];
        for (name, value, ok, expected) in checks {
            if !(value.is_finite() && ok) {
                return Err(AfsfError::BadParameter {
                    name,
                    value,
                    expected,
                });
            }
        }
        if self.max_layers == 0 {
            return Err(AfsfError::BadParameter {
                name: "max_layers",
                value: 0.0,
                expected: ">= 1",
            });
        }
        if self.moving_layers == 0 {
            return Err(AfsfError::BadParameter {
                name: "moving_layers",
                value: 0.0,
                expected: ">= 1",
            });
        }
        self.springs.check()?;
        self.solver.check()?;
        Ok(())
    }
}

/// A checked loop: `reversed` tells whether the input order runs with the domain on its right
/// (then the fronts and facets run against the input order).
#[derive(Debug, Clone)]
pub(crate) struct CheckedLoop {
    pub reversed: bool,
}

/// Checks the loops and decides their orientation.
pub(crate) fn check_loops(
    loops: &[FrontLoop],
    params: &AfsfParams,
) -> Result<Vec<CheckedLoop>, AfsfError> {
    if loops.is_empty() {
        return Err(AfsfError::NoLoop);
    }
    for (index, l) in loops.iter().enumerate() {
        check_points(index, l)?;
    }
    let farfield = check_roles(loops, params)?;
    if let Some(e) = first_crossing(loops) {
        return Err(e);
    }
    if let Some(f) = farfield {
        check_placement(loops, f)?;
    }
    Ok(loops
        .iter()
        .map(|l| {
            let ccw = polygon_area(l.points.iter().copied()) > 0.0;
            // domain on the left: far field and `inside` wall run counter-clockwise, walls
            // seen from outside run clockwise
            let want_ccw = l.role == Role::Farfield || params.inside;
            CheckedLoop {
                reversed: ccw != want_ccw,
            }
        })
        .collect())
}

/// One loop's points: at least three, a corner flag each, finite, no point repeated next to
/// itself.
fn check_points(index: usize, l: &FrontLoop) -> Result<(), AfsfError> {
    let name = l.name.clone();
    if l.points.len() < 3 {
        return Err(AfsfError::TooFewPoints {
            index,
            name,
            points: l.points.len(),
        });
    }
    if l.is_corner.len() != l.points.len() {
        return Err(AfsfError::CornerFlagsMismatch {
            index,
            name,
            points: l.points.len(),
            flags: l.is_corner.len(),
        });
    }
    if let Some(point) = l
        .points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(AfsfError::NonFinitePoint { index, name, point });
    }
    let n = l.points.len();
    if let Some(point) = (0..n).find(|&i| l.points[i] == l.points[(i + 1) % n]) {
        return Err(AfsfError::RepeatedPoint { index, name, point });
    }
    Ok(())
}

/// Exactly one far field around the walls, or one wall and no far field with `inside`;
/// returns the far field's index.
fn check_roles(loops: &[FrontLoop], params: &AfsfParams) -> Result<Option<usize>, AfsfError> {
    let farfields: Vec<usize> = (0..loops.len())
        .filter(|&i| loops[i].role == Role::Farfield)
        .collect();
    if params.inside {
        if loops.len() != 1 || !farfields.is_empty() {
            return Err(AfsfError::BadLoopSet(format!(
                "`inside` needs exactly one wall loop and no far field; got {} loops, {} far field",
                loops.len(),
                farfields.len()
            )));
        }
    } else if farfields.len() != 1 {
        return Err(AfsfError::BadLoopSet(format!(
            "expected exactly one far-field loop around the walls (or one wall with `inside`), got {}",
            farfields.len()
        )));
    }
    Ok(farfields.first().copied())
}

/// The first two edges that cross or touch, except consecutive edges of one loop at their
/// shared node.
fn first_crossing(loops: &[FrontLoop]) -> Option<AfsfError> {
    let mut segs: Vec<(usize, usize)> = Vec::new();
    let mut boxes = Vec::new();
    for (li, l) in loops.iter().enumerate() {
        let n = l.points.len();
        for i in 0..n {
            segs.push((li, i));
            boxes.push(Aabb::of_segment(l.points[i], l.points[(i + 1) % n], 0.0));
        }
    }
    find_overlapping_pair(&boxes, |x, y| {
        let ((la, ea), (lb, eb)) = (segs[x], segs[y]);
        let (pa, pb) = (&loops[la].points, &loops[lb].points);
        let (na, nb) = (pa.len(), pb.len());
        // consecutive edges of one loop meet only at their shared node unless folded back
        let consecutive = la == lb && ((ea + 1) % na == eb || (eb + 1) % nb == ea);
        if consecutive {
            return None;
        }
        let meet = segments_meet(pa[ea], pa[(ea + 1) % na], pb[eb], pb[(eb + 1) % nb]);
        meet.then_some(AfsfError::LoopsCross {
            loop_a: la,
            edge_a: ea,
            loop_b: lb,
            edge_b: eb,
        })
    })
}

/// Walls inside the far field `f` and not inside each other.
fn check_placement(loops: &[FrontLoop], f: usize) -> Result<(), AfsfError> {
    for (index, l) in loops.iter().enumerate() {
        if index == f {
            continue;
        }
        if !point_in_loop(l.points[0], &loops[f].points) {
            return Err(AfsfError::Misplaced {
                index,
                name: l.name.clone(),
                what: "a wall must lie inside the far-field loop",
            });
        }
        for (other, o) in loops.iter().enumerate() {
            if other != index && other != f && point_in_loop(l.points[0], &o.points) {
                return Err(AfsfError::Misplaced {
                    index,
                    name: l.name.clone(),
                    what: "a wall lies inside another wall",
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(c: [f64; 2], h: f64, role: Role) -> FrontLoop {
        FrontLoop::new(
            vec![
                [c[0] - h, c[1] - h],
                [c[0] + h, c[1] - h],
                [c[0] + h, c[1] + h],
                [c[0] - h, c[1] + h],
            ],
            role,
            "sq",
        )
    }

    /// A wall whose first point lies inside the far field by less than the rounding of the
    /// edge's x at that height: the old crossing-number test (x interpolated in floating
    /// point) put it outside and refused a valid domain; the exact winding number does not.
    #[test]
    fn a_wall_just_inside_a_slanted_far_field_edge_is_inside() {
        let p = [9.57496912230954, 1.4167695923015322];
        // exactly left of the edge (10, 0) -> (7, 10), i.e. inside
        assert!(geom_predicates::orient2d([10.0, 0.0], [7.0, 10.0], p) > 0.0);
        let far = FrontLoop::new(
            vec![[0.0, 0.0], [10.0, 0.0], [7.0, 10.0], [0.0, 10.0]],
            Role::Farfield,
            "far",
        );
        let wall = FrontLoop::new(
            vec![p, [p[0] - 1.0, p[1] + 0.5], [p[0] - 1.0, p[1] - 0.5]],
            Role::Wall,
            "wall",
        );
        let checked = check_loops(&[far, wall], &AfsfParams::default()).unwrap();
        assert_eq!(checked.len(), 2);
    }

    #[test]
    fn bad_loop_sets_are_named_errors() {
        let p = AfsfParams::default();
        assert_eq!(check_loops(&[], &p).unwrap_err(), AfsfError::NoLoop);
        let wall = square([0.0, 0.0], 1.0, Role::Wall);
        assert!(matches!(
            check_loops(std::slice::from_ref(&wall), &p).unwrap_err(),
            AfsfError::BadLoopSet(_)
        ));
        let far = square([5.0, 5.0], 1.0, Role::Farfield);
        assert!(matches!(
            check_loops(&[wall.clone(), far], &p).unwrap_err(),
            AfsfError::Misplaced { index: 0, .. } | AfsfError::LoopsCross { .. }
        ));
        let mut bow = square([0.0, 0.0], 1.0, Role::Wall);
        bow.points.swap(0, 1);
        let far = square([0.0, 0.0], 10.0, Role::Farfield);
        assert!(matches!(
            check_loops(&[bow, far.clone()], &p).unwrap_err(),
            AfsfError::LoopsCross { .. }
        ));
        let mut rep = wall.clone();
        rep.points.push(rep.points[0]);
        rep.is_corner.push(false);
        assert!(matches!(
            check_loops(&[rep, far], &p).unwrap_err(),
            AfsfError::RepeatedPoint { .. }
        ));
    }

    #[test]
    fn layer_growth_and_count_have_one_range() {
        // the case file refused growth 1 and no layers while this check let them through:
        // now this check is the one rule, and the case file uses it
        let named = |p: AfsfParams| match p.check() {
            Err(AfsfError::BadParameter { name, .. }) => name,
            other => panic!("{other:?}"),
        };
        let d = AfsfParams::default();
        assert_eq!(named(AfsfParams { growth: 1.0, ..d }), "growth");
        assert_eq!(named(AfsfParams { max_layers: 0, ..d }), "max_layers");
        assert!(
            AfsfParams {
                growth: 1.01,
                max_layers: 1,
                ..d
            }
            .check()
            .is_ok()
        );
    }

    #[test]
    fn loops_are_oriented_with_the_domain_on_the_left() {
        let p = AfsfParams::default();
        let wall = square([0.0, 0.0], 1.0, Role::Wall); // counter-clockwise
        let far = square([0.0, 0.0], 10.0, Role::Farfield); // counter-clockwise
        let c = check_loops(&[wall.clone(), far], &p).unwrap();
        assert!(c[0].reversed && !c[1].reversed);
        let inside = AfsfParams { inside: true, ..p };
        let c = check_loops(&[wall], &inside).unwrap();
        assert!(!c[0].reversed);
    }
}
