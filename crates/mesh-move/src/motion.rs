//! Motions of boundary loops: a rigid motion (uniform scale, rotation, translation) and
//! Hicks–Henne bumps that morph a wall section, their validation, and the check that moved
//! loops stay simple, do not cross one another and stay inside the far field.
//!
//! Points are `[f64; 2]`. A [`Motion`] applies its bumps first, on the loop as given (the body
//! frame), then its rigid motion.

use geom_curve::{Point2, loops};
use mesh_model::Role;

use crate::MoveError;

/// Largest bump amplitude accepted, in chords: a larger one folds thin sections.
pub const MAX_BUMP_AMPLITUDE: f64 = 0.1;

/// A 2×2 matrix, row-major: `m[r][c]`.
pub type Mat2 = [[f64; 2]; 2];

/// The identity matrix.
pub const IDENTITY: Mat2 = [[1.0, 0.0], [0.0, 1.0]];

/// Sine and cosine of an angle in degrees, exact for multiples of 90° (so that a quarter turn
/// maps (1, 0) to (0, 1) exactly).
pub fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r == 0.0 {
        (0.0, 1.0)
    } else if r == 90.0 {
        (1.0, 0.0)
    } else if r == 180.0 {
        (0.0, -1.0)
    } else if r == 270.0 {
        (-1.0, 0.0)
    } else {
        r.to_radians().sin_cos()
    }
}

/// A rigid motion with uniform scaling, applied in this order: scale by `scale` about
/// `about`, rotate by `rotate_deg` (counter-clockwise) about `about`, then translate by
/// `translate`: `p' = about + scale · R(rotate_deg) · (p − about) + translate`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidMotion {
    /// Uniform scale factor, > 0 (1 keeps the size).
    pub scale: f64,
    /// Rotation angle, degrees, counter-clockwise.
    pub rotate_deg: f64,
    /// Centre of the scaling and of the rotation.
    pub about: [f64; 2],
    /// Translation, applied last.
    pub translate: [f64; 2],
}

impl Default for RigidMotion {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl RigidMotion {
    /// The motion that moves nothing.
    pub const IDENTITY: RigidMotion = RigidMotion {
        scale: 1.0,
        rotate_deg: 0.0,
        about: [0.0, 0.0],
        translate: [0.0, 0.0],
    };

    /// A rotation by `deg` degrees about `about`.
    pub fn rotation(deg: f64, about: [f64; 2]) -> Self {
        RigidMotion {
            rotate_deg: deg,
            about,
            ..Self::IDENTITY
        }
    }

    /// The exact rotation angle, radians, counter-clockwise (what the rotation-aware
    /// inverse-distance weighting carries for every node of the body).
    pub fn angle_rad(&self) -> f64 {
        self.rotate_deg.to_radians()
    }

    /// The turn of the body, radians, in [−π, π]: the rotation reduced by whole turns, with
    /// ±180° kept as given (a rotation by 540° turns the body as one by 180° does). The movers
    /// read a turn of ±π from this, never from the moved positions, whose angle is on the
    /// branch cut of `atan2` (rounding puts one node at +π and its neighbour at −π).
    pub fn turn_rad(&self) -> f64 {
        let r = self.rotate_deg.rem_euclid(360.0);
        let deg = if r > 180.0 || (r == 180.0 && self.rotate_deg < 0.0) {
            r - 360.0
        } else {
            r
        };
        deg.to_radians()
    }

    /// The linear part `scale · R(rotate_deg)`.
    pub fn linear(&self) -> Mat2 {
        let (s, c) = sin_cos_deg(self.rotate_deg);
        let k = self.scale;
        [[k * c, -k * s], [k * s, k * c]]
    }

    /// Checks that every value is finite and the scale positive.
    ///
    /// # Errors
    /// [`MoveError::NotFinite`] or [`MoveError::BadScale`].
    pub fn validate(&self) -> Result<(), MoveError> {
        finite("scale", self.scale)?;
        finite("rotate_deg", self.rotate_deg)?;
        finite("about.x", self.about[0])?;
        finite("about.y", self.about[1])?;
        finite("translate.x", self.translate[0])?;
        finite("translate.y", self.translate[1])?;
        if self.scale <= 0.0 {
            return Err(MoveError::BadScale { scale: self.scale });
        }
        Ok(())
    }

    /// Point `p` moved. Computed as `p` plus its displacement, so that the identity returns
    /// `p` exactly.
    pub fn apply(&self, p: [f64; 2]) -> [f64; 2] {
        let m = self.linear();
        let r = [p[0] - self.about[0], p[1] - self.about[1]];
        [
            p[0] + ((m[0][0] - 1.0) * r[0] + m[0][1] * r[1]) + self.translate[0],
            p[1] + (m[1][0] * r[0] + (m[1][1] - 1.0) * r[1]) + self.translate[1],
        ]
    }

    /// The motion that undoes this one: `inverse().apply(apply(p)) = p` up to rounding.
    pub fn inverse(&self) -> RigidMotion {
        RigidMotion {
            scale: 1.0 / self.scale,
            rotate_deg: -self.rotate_deg,
            about: [
                self.about[0] + self.translate[0],
                self.about[1] + self.translate[1],
            ],
            translate: [-self.translate[0], -self.translate[1]],
        }
    }
}

/// Which arc of a section a bump deforms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Surface {
    /// The arc on the left of the chord directed from the leading to the trailing edge (the
    /// suction side of an airfoil drawn nose left).
    Upper,
    /// The other arc.
    Lower,
}

/// A Hicks–Henne bump `A · c · b(x)`, `b(x) = sin^t(π x^m)`, `m = ln 0.5 / ln position`, with
/// `x` the chord-wise coordinate (0 at the leading edge, 1 at the trailing edge), `c` the
/// chord, `A` the amplitude in chords; the point moves along the chord's normal, outward from
/// the section for `A > 0`. `b` peaks (= 1) at `x = position` and vanishes at both ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HicksHenne {
    /// Where the bump peaks, as a fraction of the chord, in (0, 1).
    pub position: f64,
    /// Height at the peak, in chords; positive pushes the surface out of the section.
    /// At most [`MAX_BUMP_AMPLITUDE`] in magnitude.
    pub amplitude: f64,
    /// Width exponent `t` (> 0; larger is narrower). 3 by default.
    pub width: f64,
    /// The arc it deforms.
    pub surface: Surface,
}

impl HicksHenne {
    /// A bump of the default width exponent 3.
    pub fn new(position: f64, amplitude: f64, surface: Surface) -> Self {
        HicksHenne {
            position,
            amplitude,
            width: 3.0,
            surface,
        }
    }

    /// `b(x)`: 0 outside the open interval (0, 1), 1 at `x = position`.
    pub fn shape(&self, x: f64) -> f64 {
        if x <= 0.0 || x >= 1.0 {
            return 0.0;
        }
        let m = 0.5f64.ln() / self.position.ln();
        (std::f64::consts::PI * x.powf(m)).sin().powf(self.width)
    }

    /// Checks the bump's values.
    ///
    /// # Errors
    /// [`MoveError::NotFinite`], [`MoveError::BumpPosition`], [`MoveError::BumpWidth`] or
    /// [`MoveError::BumpAmplitude`].
    pub fn validate(&self) -> Result<(), MoveError> {
        finite("bump position", self.position)?;
        finite("bump amplitude", self.amplitude)?;
        finite("bump width", self.width)?;
        if !(self.position > 0.0 && self.position < 1.0) {
            return Err(MoveError::BumpPosition {
                position: self.position,
            });
        }
        if self.width <= 0.0 {
            return Err(MoveError::BumpWidth { width: self.width });
        }
        if self.amplitude.abs() > MAX_BUMP_AMPLITUDE {
            return Err(MoveError::BumpAmplitude {
                amplitude: self.amplitude,
                max: MAX_BUMP_AMPLITUDE,
            });
        }
        Ok(())
    }
}

/// The chord of a wall loop and the split of its points into two arcs.
///
/// The rule, independent of the loop's orientation and of the section's attitude: the
/// trailing edge is the loop's sharpest convex point (largest turn towards the inside), unless
/// the sharper of its two neighbours is a corner too (turn over [`BASE_CORNER_TURN_DEG`]):
/// then the two are the corners of a blunt base and the trailing edge is the base's midpoint.
/// The leading edge is the point farthest from the trailing edge. Walking the loop
/// counter-clockwise, the points from the trailing edge to the leading edge form the upper arc
/// and the rest the lower one (for an airfoil drawn nose left, exactly its upper and lower
/// surfaces, whatever its camber).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Index of the leading edge in the loop.
    pub leading_edge: usize,
    /// Indices of the trailing edge in the loop: twice the same for a sharp trailing edge,
    /// the two corners of a blunt base (in counter-clockwise order) otherwise.
    pub trailing_edge: [usize; 2],
    le: [f64; 2],
    te: [f64; 2],
    n: usize,
    ccw: bool,
}

/// Turn, degrees, above which the neighbour of the sharpest point makes a blunt base with it.
pub const BASE_CORNER_TURN_DEG: f64 = 45.0;

impl Section {
    /// The section of the closed loop `points`, or `None` when it has fewer than 3 points or
    /// no chord (all points equal).
    pub fn of_loop(points: &[[f64; 2]]) -> Option<Section> {
        let n = points.len();
        if n < 3 {
            return None;
        }
        let ccw = mesh_model::polygon_area(points.iter().copied()) >= 0.0;
        let sign = if ccw { 1.0 } else { -1.0 };
        let turn = |i: usize| {
            let (a, b, c) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let u = [b[0] - a[0], b[1] - a[1]];
            let v = [c[0] - b[0], c[1] - b[1]];
            sign * (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1])
        };
        let sharpest = (0..n).fold(0, |best, i| if turn(i) > turn(best) { i } else { best });
        let (prev, next) = ((sharpest + n - 1) % n, (sharpest + 1) % n);
        let other = if turn(prev) >= turn(next) { prev } else { next };
        let trailing_edge = if turn(other) > BASE_CORNER_TURN_DEG.to_radians() {
            // in counter-clockwise order
            let forward = other == next;
            if forward == ccw {
                [sharpest, other]
            } else {
                [other, sharpest]
            }
        } else {
            [sharpest, sharpest]
        };
        let (a, b) = (points[trailing_edge[0]], points[trailing_edge[1]]);
        let te = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        let d2 = |p: [f64; 2]| (p[0] - te[0]).powi(2) + (p[1] - te[1]).powi(2);
        let leading_edge = (0..n).fold(trailing_edge[0], |best, i| {
            if d2(points[i]) > d2(points[best]) {
                i
            } else {
                best
            }
        });
        if d2(points[leading_edge]) == 0.0 {
            return None;
        }
        Some(Section {
            leading_edge,
            trailing_edge,
            le: points[leading_edge],
            te,
            n,
            ccw,
        })
    }

    /// The chord length.
    pub fn chord(&self) -> f64 {
        (self.te[0] - self.le[0]).hypot(self.te[1] - self.le[1])
    }

    /// The unit normal of the chord on its left (directed from leading to trailing edge).
    pub fn normal(&self) -> [f64; 2] {
        let c = self.chord();
        [
            -(self.te[1] - self.le[1]) / c,
            (self.te[0] - self.le[0]) / c,
        ]
    }

    /// The chord-wise coordinate of `p`: its projection on the chord, 0 at the leading edge
    /// and 1 at the trailing edge.
    pub fn chord_coordinate(&self, p: [f64; 2]) -> f64 {
        let d = [self.te[0] - self.le[0], self.te[1] - self.le[1]];
        ((p[0] - self.le[0]) * d[0] + (p[1] - self.le[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])
    }

    /// The arc of point `i`; `None` for the leading and trailing edges themselves.
    pub fn surface(&self, i: usize) -> Option<Surface> {
        let [t0, t1] = self.trailing_edge;
        if i == self.leading_edge || i == t0 || i == t1 {
            return None;
        }
        // steps from a to b walking counter-clockwise
        let ccw_steps = |a: usize, b: usize| {
            let fwd = (b + self.n - a) % self.n;
            if self.ccw {
                fwd
            } else {
                (self.n - fwd) % self.n
            }
        };
        let upper = ccw_steps(t1, i) < ccw_steps(t1, self.leading_edge);
        Some(if upper {
            Surface::Upper
        } else {
            Surface::Lower
        })
    }

    /// The displacement of point `i` at `p` by `bump`.
    pub fn bump_displacement(&self, bump: &HicksHenne, i: usize, p: [f64; 2]) -> [f64; 2] {
        if self.surface(i) != Some(bump.surface) {
            return [0.0, 0.0];
        }
        let outward = match bump.surface {
            Surface::Upper => 1.0,
            Surface::Lower => -1.0,
        };
        let h = outward * bump.amplitude * self.chord() * bump.shape(self.chord_coordinate(p));
        let n = self.normal();
        [h * n[0], h * n[1]]
    }
}

/// The motion of one loop: its bumps, applied first on the loop as given, then its rigid
/// motion. The default moves nothing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Motion {
    /// Rigid motion, applied after the bumps.
    pub rigid: Option<RigidMotion>,
    /// Hicks–Henne bumps, added together (each computed on the unmoved loop).
    pub bumps: Vec<HicksHenne>,
}

impl Motion {
    /// A rigid motion alone.
    pub fn rigid(rigid: RigidMotion) -> Self {
        Motion {
            rigid: Some(rigid),
            bumps: Vec::new(),
        }
    }

    /// Bumps alone.
    pub fn bumps(bumps: Vec<HicksHenne>) -> Self {
        Motion { rigid: None, bumps }
    }

    /// Checks every value of the rigid motion and of the bumps.
    ///
    /// # Errors
    /// The first fault: see [`RigidMotion::validate`] and [`HicksHenne::validate`].
    pub fn validate(&self) -> Result<(), MoveError> {
        if let Some(r) = &self.rigid {
            r.validate()?;
        }
        self.bumps.iter().try_for_each(HicksHenne::validate)
    }

    /// The linear part of the rigid motion (the identity without one): what every point of the
    /// body turns and stretches by.
    pub fn linear(&self) -> Mat2 {
        self.rigid.map_or(IDENTITY, |r| r.linear())
    }

    /// The turn of the rigid motion ([`RigidMotion::turn_rad`]; 0 without one).
    pub fn turn_rad(&self) -> f64 {
        self.rigid.map_or(0.0, |r| r.turn_rad())
    }

    /// The loop `points` moved (validate first). The bumps need a chord: a loop of fewer than
    /// 3 points with bumps is returned unmoved by them.
    pub fn apply(&self, points: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let mut out = points.to_vec();
        // (no let-chain: the MSRV is 1.85)
        let section = if self.bumps.is_empty() {
            None
        } else {
            Section::of_loop(points)
        };
        if let Some(section) = section {
            for (i, q) in out.iter_mut().enumerate() {
                for bump in &self.bumps {
                    let d = section.bump_displacement(bump, i, points[i]);
                    q[0] += d[0];
                    q[1] += d[1];
                }
            }
        }
        if let Some(r) = &self.rigid {
            out.iter_mut().for_each(|q| *q = r.apply(*q));
        }
        out
    }
}

/// A named boundary loop.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryLoop {
    /// Its name (`main`, `flap`, `farfield`).
    pub name: String,
    /// Wall or far field.
    pub role: Role,
    /// Its points, closed implicitly.
    pub points: Vec<[f64; 2]>,
}

/// The motion of the loop named `loop_name`.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopMotion {
    /// The loop's name.
    pub loop_name: String,
    /// Its motion.
    pub motion: Motion,
}

/// For each of the loops `names`, its motion among `motions` (`None`: it stays), after
/// checking every motion's values and that each names exactly one loop, once.
///
/// # Errors
/// [`MoveError::UnknownLoop`], [`MoveError::AmbiguousLoop`], [`MoveError::MovedTwice`], or a
/// value fault as [`MoveError::InLoop`]; bumps on a far field: [`MoveError::BumpOnFarfield`].
pub fn resolve_motions<'m>(
    loops: &[(&str, Role)],
    motions: &'m [LoopMotion],
) -> Result<Vec<Option<&'m Motion>>, MoveError> {
    let mut out = vec![None; loops.len()];
    for m in motions {
        let matches: Vec<usize> = (0..loops.len())
            .filter(|&i| loops[i].0 == m.loop_name)
            .collect();
        let &[i] = matches.as_slice() else {
            if matches.is_empty() {
                let known: Vec<&str> = loops.iter().map(|l| l.0).collect();
                return Err(MoveError::UnknownLoop {
                    name: m.loop_name.clone(),
                    known: known.join(", "),
                });
            }
            return Err(MoveError::AmbiguousLoop {
                name: m.loop_name.clone(),
                count: matches.len(),
            });
        };
        m.motion.validate().map_err(|e| e.in_loop(&m.loop_name))?;
        if loops[i].1 == Role::Farfield && !m.motion.bumps.is_empty() {
            return Err(MoveError::BumpOnFarfield {
                name: m.loop_name.clone(),
            });
        }
        if out[i].replace(&m.motion).is_some() {
            return Err(MoveError::MovedTwice {
                name: m.loop_name.clone(),
            });
        }
    }
    Ok(out)
}

/// The loops moved by `motions`, after checking the motions ([`resolve_motions`]) and the
/// moved loops ([`check_loops`]). Loops without a motion stay where they are.
///
/// # Errors
/// See [`resolve_motions`] and [`check_loops`]; also [`MoveError::NoChord`] for bumps on a
/// loop without a chord.
pub fn move_loops(
    loops: &[BoundaryLoop],
    motions: &[LoopMotion],
) -> Result<Vec<BoundaryLoop>, MoveError> {
    let names: Vec<(&str, Role)> = loops.iter().map(|l| (l.name.as_str(), l.role)).collect();
    let resolved = resolve_motions(&names, motions)?;
    let mut moved = Vec::with_capacity(loops.len());
    for (l, m) in loops.iter().zip(resolved) {
        moved.push(BoundaryLoop {
            points: moved_points(l, m)?,
            ..l.clone()
        });
    }
    check_loops(&moved)?;
    Ok(moved)
}

/// The points of loop `l` moved by `m` (unmoved for `None`).
///
/// # Errors
/// [`MoveError::NoChord`] for bumps on a loop without a chord.
pub(crate) fn moved_points(
    l: &BoundaryLoop,
    m: Option<&Motion>,
) -> Result<Vec<[f64; 2]>, MoveError> {
    let Some(m) = m else {
        return Ok(l.points.clone());
    };
    if !m.bumps.is_empty() && Section::of_loop(&l.points).is_none() {
        return Err(MoveError::NoChord {
            name: l.name.clone(),
        });
    }
    Ok(m.apply(&l.points))
}

/// Checks that the loops are fit to bound a domain: each simple, no two crossing or touching
/// (exact predicates of `geom_curve::loops`), every wall inside every far field and no wall
/// inside another wall.
///
/// # Errors
/// [`MoveError::SelfCrossing`], [`MoveError::LoopsCross`], [`MoveError::OutsideFarfield`] or
/// [`MoveError::InsideWall`], each naming the loops.
pub fn check_loops(loops: &[BoundaryLoop]) -> Result<(), MoveError> {
    let pts: Vec<Vec<Point2<f64>>> = loops
        .iter()
        .map(|l| l.points.iter().map(|p| Point2::new(p[0], p[1])).collect())
        .collect();
    for (l, p) in loops.iter().zip(&pts) {
        if let Some(c) = loops::find_self_intersection(p) {
            return Err(MoveError::SelfCrossing {
                name: l.name.clone(),
                x: c.point.x,
                y: c.point.y,
            });
        }
    }
    if let Err(geom_curve::CurveError::LoopsCross {
        loop_a,
        loop_b,
        x,
        y,
        ..
    }) = loops::check_loops_disjoint(&pts)
    {
        return Err(MoveError::LoopsCross {
            a: loops[loop_a].name.clone(),
            b: loops[loop_b].name.clone(),
            x,
            y,
        });
    }
    for (i, wall) in loops.iter().enumerate() {
        if wall.role != Role::Wall {
            continue;
        }
        for (j, other) in loops.iter().enumerate() {
            let inside = i != j && loops::loop_inside_loop(&pts[i], &pts[j]);
            match other.role {
                Role::Farfield if i != j && !inside => {
                    return Err(MoveError::OutsideFarfield {
                        wall: wall.name.clone(),
                        farfield: other.name.clone(),
                    });
                }
                Role::Wall if inside => {
                    return Err(MoveError::InsideWall {
                        inner: wall.name.clone(),
                        outer: other.name.clone(),
                    });
                }
                _ => {}
            }
        }
    }
    Ok(())
}

fn finite(what: &'static str, value: f64) -> Result<(), MoveError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(MoveError::NotFinite { what, value })
    }
}
