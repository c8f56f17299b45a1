//! The spring mover (dissertation chapter 4): the layered mesh follows its moved boundary with
//! the geometry of its original layers, so that near the walls a moved mesh looks like the
//! original one; the rest of the mesh takes the deformation.
//!
//! 1. **Fronts.** Each node's neighbours along its front: the boundary facets (domain on the
//!    left) and, for every layered cell, its top edge (the corners that have a parent among
//!    the cell's corners), oriented like the facet below it.
//! 2. **Kept layers**: the nodes grown from the walls (every parent on a wall or kept), layer
//!    by layer, up to the last layer whose median cell is at least
//!    [`SpringMoveParams::core_aspect`] times wider than high: a band that wraps every wall,
//!    corners included. Layers grown from the far field are not kept.
//! 3. **Predictor**, layer by layer from the boundary up: a kept node goes to its moved parent
//!    plus its original offset from that parent turned by the rotation of the parent's front
//!    (the mean rotation, old → new, of the directions to its placed front neighbours, or its
//!    parents' rotation); a node with two parents takes the mean of both predictions. A rigid
//!    motion of a wall carries its band rigidly; a bump turns each column with the wall.
//! 4. **Springs** ([`springfield`]) built from the layering with the original layers carried
//!    by the moved wall as the ideal: an extrusion spring per parent–child edge (ideal length
//!    the original one), a neighbour spring per kept node between its front neighbours (ideal
//!    share of the two sides the predicted one), an angle spring per parent–child edge whose
//!    ideal direction is the parent's bisector turned by the predicted angle. Along a wall
//!    that stretches (a scaled body, a bump) the spacing between columns stretches while the
//!    heights stay, so the original shares and angles would pull a corner's fan sideways; a
//!    rigid motion predicts the original ones. The original mesh is an equilibrium, and so is
//!    any rigid motion of it. The kept nodes move, everything else
//!    is held; all together ([`Strategy::AllTogether`]) or one layer after the other, then
//!    all together ([`Strategy::LayerByLayer`]). springfield's solver keeps the mass constant
//!    for its first iterations and the angle springs off until an edge reaches
//!    `angle_activation_ratio` of its ideal length.
//! 5. **Wall cells outside the band** (fill triangles on a wall facet): their other corners
//!    move rigidly with the facet's nodes and are held, so every first-layer cell keeps its
//!    shape.
//! 6. **The rest** (filled region and upper layers) starts from the nodes that bound it,
//!    each with its local rigid motion (its turn, taking its original place to its moved
//!    one), by one [`Fill`]: by default the screw fill (each motion's logarithm in se(2),
//!    blended by inverse-distance weights and exponentiated: a rigid motion stays exact, a
//!    rotation becomes a twist about its centre; each angle read on the branch of its body's
//!    turn from the motion, so ±180° is a half turn like 179.999°).
//! 7. **The shape balance** ([`crate::balance`]): every cell held to its original shape,
//!    balanced by Newton's method with the boundary held. Its result does not depend on the
//!    start inside its basin, and it is a smooth function of the boundary: no selection
//!    among candidates and no non-smooth polish, so the sensitivities are its linearisation.
//!
//! A motion that moves no boundary node returns the mesh unchanged, to the bit.

use std::cell::OnceCell;
use std::collections::HashMap;

use mesh_model::{LayeredMesh, Layering, Mesh, NONE, Role};
use rayon::prelude::*;
use springfield::{
    AngleSpring, ExtrusionSpring, NeighbourSpring, ShapeLaw, SpringField2d, SpringSet2d, bisector,
    solve_model_active,
};

use crate::MoveError;
use crate::balance::ShapeField;
use crate::boundary::BoundaryMotion;
use crate::movers::{Method, Rbf, Sources, check_boundary, move_mesh};
pub use crate::outcome::SpringStats;
use crate::outcome::{MoveStats, Moved};
use crate::params::RbfParams;
pub use crate::params::{Fill, SpringMoveParams, Strategy};

/// `layered` moved by `method` to follow `boundary`: the springs use the layering, IDW and
/// RBF take the mesh alone ([`move_mesh`]). One entry point for every method.
///
/// # Errors
/// Those of [`move_mesh`]; [`MoveError::BadLayering`] when the layering does not fit the
/// mesh; [`MoveError::Springs`] for bad spring or solver parameters or a failed solve.
pub fn move_layered(
    layered: &LayeredMesh,
    boundary: &BoundaryMotion,
    method: &Method,
) -> Result<Moved, MoveError> {
    match method {
        Method::Springs(p) => move_springs(layered, boundary, p, (None, None)),
        other => move_mesh(&layered.mesh, boundary, other),
    }
}

/// [`move_layered`] with the spring mover's shape field given: built once by
/// [`ShapeField::of`] the same layered mesh with the method's law, its springs and its
/// Newton workspace (the matrix's pattern, ordering and symbolic factorisation, kept from its
/// last balance) serve this move's balance — the same balance, in a move that does not build
/// them again (many moves of one mesh: a shape optimisation's designs). IDW and RBF ignore
/// `field`.
///
/// # Errors
/// Those of [`move_layered`].
pub fn move_layered_in(
    layered: &LayeredMesh,
    boundary: &BoundaryMotion,
    method: &Method,
    field: &ShapeField,
) -> Result<Moved, MoveError> {
    match method {
        Method::Springs(p) => move_springs(layered, boundary, p, (None, Some(field))),
        other => move_mesh(&layered.mesh, boundary, other),
    }
}

/// The previous step of a motion sequence: where its balance started and where it ended.
#[derive(Debug, Clone, Copy)]
pub struct Warm<'a> {
    /// The start of its balance ([`Moved::start`]).
    pub start: &'a [[f64; 2]],
    /// Its balanced nodes.
    pub balanced: &'a [[f64; 2]],
    /// The shape field of its balance ([`ShapeField::of`] the same layered mesh with the
    /// same law), kept for this one: built once for a sequence, its Newton workspace (the
    /// matrix's pattern and ordering) serving every step's balance. `None`: built afresh.
    pub field: Option<&'a ShapeField>,
    /// The starts and the balanced nodes of the steps before it, the latest first, when the
    /// steps are equal steps of one motion: this balance then starts from the line through
    /// the two latest corrections extended, or the parabola through the three latest
    /// ([`move_layered_from`]).
    pub before: &'a [StartAndBalance<'a>],
}

/// A step's start of its balance and its balanced nodes.
pub type StartAndBalance<'a> = (&'a [[f64; 2]], &'a [[f64; 2]]);

/// [`move_layered`], the spring mover's balance started from this move's fill plus the
/// previous step's correction (`warm.balanced − warm.start`), or with [`Warm::before`] the
/// line through the two previous corrections or the parabola through the three previous
/// extended: close to the balance, so fewer Newton steps, and the same balance (it does not
/// depend on its start inside its basin). A start that inverts a cell falls back to the
/// lower degrees, then to the fill alone; IDW and RBF ignore `warm`.
///
/// # Errors
/// Those of [`move_layered`]; [`MoveError::BadBoundaryMotion`] when `warm` does not have one
/// point per node.
pub fn move_layered_from(
    layered: &LayeredMesh,
    boundary: &BoundaryMotion,
    method: &Method,
    warm: Warm<'_>,
) -> Result<Moved, MoveError> {
    let n = layered.mesh.nodes.len();
    let lengths: Vec<usize> = std::iter::once((warm.start, warm.balanced))
        .chain(warm.before.iter().copied())
        .flat_map(|(s, b)| [s.len(), b.len()])
        .collect();
    if lengths.iter().any(|&l| l != n) {
        return Err(MoveError::BadBoundaryMotion {
            what: format!("a warm start of {lengths:?} points for {n} nodes"),
        });
    }
    match method {
        Method::Springs(p) => move_springs(layered, boundary, p, (Some(warm), warm.field)),
        other => move_mesh(&layered.mesh, boundary, other),
    }
}

fn spring_error(e: impl std::fmt::Display) -> MoveError {
    MoveError::Springs {
        what: e.to_string(),
    }
}

fn move_springs(
    layered: &LayeredMesh,
    boundary: &BoundaryMotion,
    p: &SpringMoveParams,
    (warm, given): (Option<Warm<'_>>, Option<&ShapeField>),
) -> Result<Moved, MoveError> {
    let (mesh, layering) = (&layered.mesh, &layered.layering);
    check_boundary(mesh, boundary)?;
    if let Some(what) = layering.check(mesh) {
        return Err(MoveError::BadLayering { what });
    }
    p.springs.check().map_err(spring_error)?;
    p.solver.check().map_err(spring_error)?;
    for (what, value) in [
        ("IDW exponent", p.idw.exponent),
        ("screw exponent", p.screw_exponent),
        ("core aspect", p.core_aspect),
    ] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(MoveError::BadParameter { what, value });
        }
    }
    let old: Vec<[f64; 2]> = (0..mesh.nodes.len() as u32).map(|k| mesh.xy(k)).collect();
    let mut fixed = vec![false; old.len()];
    let mut x = old.clone();
    for (&k, t) in boundary.nodes.iter().zip(&boundary.targets) {
        x[k as usize] = *t;
        fixed[k as usize] = true;
    }
    let mut stats = SpringStats {
        converged: true,
        ..SpringStats::default()
    };
    if x == old {
        return Ok(finish(mesh, boundary, &old, &x, stats));
    }
    let field = LazyField {
        given,
        own: OnceCell::new(),
        layered,
        law: p.shape,
    };
    let start = match start(layered, boundary, (p, &field), &mut stats, 0)? {
        Ok(start) => start,
        // no start: the failure is reported as it is (the fill that inverted)
        Err(failed) => return Ok(finish(mesh, boundary, &old, &failed, stats)),
    };
    x.clone_from(&start);
    if let Some(y) = warm.and_then(|w| corrected(mesh, w, &x, &fixed)) {
        x = y;
    }
    stats.newton = Some(field.get()?.balance(&mut x, &fixed, &p.newton)?);
    let mut moved = finish(mesh, boundary, &old, &x, stats);
    moved.start = Some(start);
    Ok(moved)
}

/// The fill `x` of a step of a sequence corrected by the steps before ([`Warm`]): by the
/// parabola through the three latest corrections (each a step's balance minus its fill)
/// extended, the line through the two latest, or the latest alone — the first of these the
/// steps give that inverts no cell; `None` when all do.
///
/// Why the corrections and not the balanced nodes: the line through two balanced steps of a
/// turning flap misses the next one by the square of the step, but 10⁻⁴ of a chord is
/// already through the first layers (32 cells inverted on every step of the 30P30N flap in
/// 8 steps); the fill carries the layers with their wall exactly, and what the balance
/// corrects it by is smooth. The line misses the next correction by the square of the step,
/// the parabola by its cube: on that flap the Newton solve then starts within 3–8·10⁻⁴ of
/// the nodes' smallest edges (the line: 2.5·10⁻³), and one factorisation and two chord steps
/// converge (three from the line).
fn corrected(mesh: &Mesh, warm: Warm<'_>, x: &[[f64; 2]], fixed: &[bool]) -> Option<Vec<[f64; 2]>> {
    // the corrections of the latest steps, the latest first
    let steps: Vec<StartAndBalance<'_>> = std::iter::once((warm.start, warm.balanced))
        .chain(warm.before.iter().copied())
        .take(3)
        .collect();
    // the extrapolation's weights of the corrections, the highest degree the steps allow first
    let weights: &[&[f64]] = &[&[3.0, -3.0, 1.0], &[2.0, -1.0], &[1.0]];
    weights
        .iter()
        .filter(|w| w.len() <= steps.len())
        .find_map(|w| {
            let y: Vec<[f64; 2]> = (0..x.len())
                .map(|k| {
                    if fixed[k] {
                        return x[k];
                    }
                    let mut p = x[k];
                    for (&c, (start, balanced)) in w.iter().zip(&steps) {
                        p[0] += c * (balanced[k][0] - start[k][0]);
                        p[1] += c * (balanced[k][1] - start[k][1]);
                    }
                    p
                })
                .collect();
            (inverted(mesh, &y) == 0).then_some(y)
        })
}

/// The shape field of a move: the one given (a sequence's), or built at its first use and
/// then shared by the balances of a halved motion's start and the move's own balance (the
/// same springs and held nodes: one pattern, ordering and symbolic factorisation).
struct LazyField<'a> {
    given: Option<&'a ShapeField>,
    own: OnceCell<ShapeField>,
    layered: &'a LayeredMesh,
    law: ShapeLaw,
}

impl LazyField<'_> {
    fn get(&self) -> Result<&ShapeField, MoveError> {
        if let Some(field) = self.given.or(self.own.get()) {
            return Ok(field);
        }
        let built = ShapeField::of(self.layered, self.law)?;
        Ok(self.own.get_or_init(|| built))
    }
}

/// A start of the balance (`Ok`), or the fill that inverted a cell (`Err`).
type Start = Result<Vec<[f64; 2]>, Vec<[f64; 2]>>;

/// How many times a motion is halved at most when no fill gives an uninverted start (a
/// half turn in a far field of 20 chords needs one halving).
const MAX_HALVINGS: u32 = 3;

/// The start of the shape balance of `layered` moved to `boundary`: the layers by the
/// predictor and their springs, the rest by the fill (the chosen one, then the others in turn
/// while the start inverts a cell — a choice by validity alone, not by quality: inside its
/// basin the balance does not depend on its start). When every fill inverts a cell, the
/// motion is halved: the half motion is moved and balanced (recursively), and the start is
/// the fill of the remaining half from that balanced mesh — a continuation, for the turns
/// near 180° that no blend of the two ends can fill. `Err` with the inverted fill when that
/// fails too.
fn start(
    layered: &LayeredMesh,
    boundary: &BoundaryMotion,
    (p, field): (&SpringMoveParams, &LazyField<'_>),
    stats: &mut SpringStats,
    halvings: u32,
) -> Result<Start, MoveError> {
    let x = filled(layered, boundary, p, stats)?;
    if inverted(&layered.mesh, &x) == 0 {
        return Ok(Ok(x));
    }
    if halvings >= MAX_HALVINGS {
        return Ok(Err(x));
    }
    let (half, rest) = halves(layered, boundary);
    let Ok(mut mid) = start(layered, &half, (p, field), stats, halvings + 1)? else {
        return Ok(Err(x));
    };
    let mut fixed = vec![false; mid.len()];
    half.nodes.iter().for_each(|&k| fixed[k as usize] = true);
    if field.get()?.balance(&mut mid, &fixed, &p.newton).is_err() {
        return Ok(Err(x));
    }
    // the fill of the rest would peak on top of the half balance's factor, which the main
    // balance makes afresh anyway (the 30P30N turned 180° in 50 chords: 68.3 → 65.9 MB)
    field.get()?.release_factor();
    let from = LayeredMesh {
        mesh: with_nodes(&layered.mesh, &mid),
        layering: layered.layering.clone(),
    };
    let y = filled(&from, &rest, p, stats)?;
    if inverted(&layered.mesh, &y) == 0 {
        Ok(Ok(y))
    } else {
        Ok(Err(x))
    }
}

/// The first phase of the spring mover: `layered`'s nodes with the boundary at `boundary`,
/// the kept layers placed by the predictor and their springs, the rest by the fills in turn
/// until one inverts no cell (the last one's when all do).
fn filled(
    layered: &LayeredMesh,
    boundary: &BoundaryMotion,
    p: &SpringMoveParams,
    stats: &mut SpringStats,
) -> Result<Vec<[f64; 2]>, MoveError> {
    let (mesh, layering) = (&layered.mesh, &layered.layering);
    let old: Vec<[f64; 2]> = (0..mesh.nodes.len() as u32).map(|k| mesh.xy(k)).collect();
    let mut x = old.clone();
    let mut fixed = vec![false; old.len()];
    for (&k, t) in boundary.nodes.iter().zip(&boundary.targets) {
        x[k as usize] = *t;
        fixed[k as usize] = true;
    }
    let fronts = Fronts::of(mesh, layering);
    let mut wall = vec![false; old.len()];
    for (f, facet) in mesh.boundary.iter().enumerate() {
        if mesh.patches[mesh.boundary_patch[f] as usize].role == Role::Wall {
            facet
                .corners()
                .iter()
                .for_each(|&k| wall[k as usize] = true);
        }
    }
    let layers = layer_nodes(layering, &fixed, &wall, &old, &fronts, p.core_aspect);
    stats.layer_nodes = layers.iter().map(Vec::len).sum();
    let mut held = fixed.clone();
    layers
        .iter()
        .flatten()
        .for_each(|&n| held[n as usize] = true);
    predict(&old, &mut x, &fronts, layering, &layers, &fixed);
    balance(&old, &mut x, &fronts, layering, &layers, &held, p, stats)?;
    let mut turn = vec![[1.0, 0.0]; old.len()];
    held_turns(&old, &x, &fronts, layering, &[], &held, &fixed, &mut turn);
    for layer in layers.iter().filter(|l| !l.is_empty()) {
        held_turns(&old, &x, &fronts, layering, layer, &held, &fixed, &mut turn);
    }
    pin_wall_cells(mesh, &wall, &old, &mut x, &mut turn, &mut held);
    // the filled region's cells, and the reference turns of the held nodes bounding it
    let free: Vec<bool> = held.iter().map(|h| !h).collect();
    let cells = fill_cells(mesh, &free);
    let reference = reference_turns(&old, boundary, &bounding_nodes(&cells, &held));
    let placed = x.clone();
    let mut order = vec![p.fill];
    order.extend(
        [Fill::Screw, Fill::Rbf, Fill::Idw]
            .into_iter()
            .filter(|&f| f != p.fill),
    );
    for fill_with in order {
        x.copy_from_slice(&placed);
        let p = SpringMoveParams {
            fill: fill_with,
            ..*p
        };
        let turns = (&turn[..], &reference[..]);
        fill(mesh, (&old, &mut x), turns, (&free, &cells), &p, stats);
        if inverted(mesh, &x) == 0 {
            break;
        }
    }
    Ok(x)
}

/// The boundary motion split in two halves: from `layered`'s nodes to halfway, and from
/// halfway to the whole. Each node's motion is its similarity (its body's turn and scale,
/// taking it to its target) as a logarithm, halved: a rigid motion of a body becomes exactly
/// the half rigid motion, a bump half the bump.
fn halves(layered: &LayeredMesh, boundary: &BoundaryMotion) -> (BoundaryMotion, BoundaryMotion) {
    let mesh = &layered.mesh;
    let o = [0.0, 0.0];
    let mut half = boundary.clone();
    for (i, &k) in boundary.nodes.iter().enumerate() {
        let p = mesh.xy(k);
        let theta = boundary.turn[i];
        let sigma = crate::movers::log_scale(boundary.linear[i]);
        let z = [theta.cos(), theta.sin()];
        let log = screw_log(o, (z, theta, sigma), p, boundary.targets[i]);
        half.targets[i] = screw_exp(o, log.map(|v| 0.5 * v), p);
        let (sh, ch) = (0.5 * theta).sin_cos();
        let k = (0.5 * sigma).exp();
        half.linear[i] = [[k * ch, -k * sh], [k * sh, k * ch]];
        half.turn[i] = 0.5 * theta;
    }
    // the rest: from the half-moved nodes to the targets, by the other half of each motion
    let rest = BoundaryMotion {
        nodes: boundary.nodes.clone(),
        targets: boundary.targets.clone(),
        linear: half.linear.clone(),
        turn: half.turn.clone(),
    };
    (half, rest)
}

/// The cells of `mesh` inverted with its nodes at `x`.
fn inverted(mesh: &Mesh, x: &[[f64; 2]]) -> usize {
    crate::quality::inverted_cells_at(mesh, |k| x[k as usize])
}

/// `mesh` with its nodes at `x`.
fn with_nodes(mesh: &Mesh, x: &[[f64; 2]]) -> Mesh {
    let mut moved = mesh.clone();
    for (n, p) in moved.nodes.iter_mut().zip(x) {
        n[0] = p[0];
        n[1] = p[1];
    }
    moved
}

/// The moved mesh and its figures.
fn finish(
    mesh: &Mesh,
    boundary: &BoundaryMotion,
    old: &[[f64; 2]],
    x: &[[f64; 2]],
    springs: SpringStats,
) -> Moved {
    let moved = with_nodes(mesh, x);
    let mut stats = MoveStats {
        boundary_nodes: boundary.nodes.len(),
        interior_nodes: mesh.nodes.len() - boundary.nodes.len(),
        springs: Some(springs),
        ..MoveStats::default()
    };
    for &k in &boundary.nodes {
        let (a, b) = (old[k as usize], x[k as usize]);
        let d = (a[0] - b[0]).hypot(a[1] - b[1]);
        stats.largest_boundary_displacement = stats.largest_boundary_displacement.max(d);
    }
    for (a, b) in old.iter().zip(x) {
        stats.largest_displacement = stats
            .largest_displacement
            .max((a[0] - b[0]).hypot(a[1] - b[1]));
    }
    stats.inverted_cells = crate::quality::inverted_cells(&moved);
    Moved {
        mesh: moved,
        stats,
        start: None,
    }
}

/// Each node's neighbours along its front ([`NONE`] when absent), the front running with the
/// region still to mesh on its left.
struct Fronts {
    left: Vec<u32>,
    right: Vec<u32>,
}

impl Fronts {
    fn of(mesh: &Mesh, layering: &Layering) -> Fronts {
        let n = mesh.nodes.len();
        let mut f = Fronts {
            left: vec![NONE; n],
            right: vec![NONE; n],
        };
        for facet in mesh.boundary.iter() {
            let k = facet.corners();
            f.link(k[0], k[1]);
        }
        for c in 0..layering.layered_cells {
            let cell = mesh.cells.get(c);
            let k = cell.corners();
            let top = |u: u32| {
                layering.node_parents[u as usize]
                    .iter()
                    .any(|p| *p != NONE && k.contains(p))
            };
            for j in 0..k.len() {
                let (u, v) = (k[j], k[(j + 1) % k.len()]);
                // a counter-clockwise cell runs along its top edge against the front
                if top(u) && top(v) {
                    f.link(v, u);
                }
            }
        }
        f
    }

    fn link(&mut self, a: u32, b: u32) {
        if self.right[a as usize] == NONE {
            self.right[a as usize] = b;
        }
        if self.left[b as usize] == NONE {
            self.left[b as usize] = a;
        }
    }

    /// The rotation (cos, sin) of node `p`'s front from `old` to `new`: the normalised sum of
    /// the rotations of the unit directions to its placed front neighbours; none without one.
    fn rotation(
        &self,
        old: &[[f64; 2]],
        new: &[[f64; 2]],
        placed: &[bool],
        p: usize,
    ) -> Option<[f64; 2]> {
        let mut z = [0.0, 0.0];
        for q in [self.left[p], self.right[p]] {
            if q == NONE || !placed[q as usize] {
                continue;
            }
            let q = q as usize;
            let (Some(a), Some(b)) = (unit(old[p], old[q]), unit(new[p], new[q])) else {
                continue;
            };
            z[0] += b[0] * a[0] + b[1] * a[1];
            z[1] += b[1] * a[0] - b[0] * a[1];
        }
        let l = z[0].hypot(z[1]);
        (l > 0.0).then(|| [z[0] / l, z[1] / l])
    }

    /// [`Fronts::rotation`], or without a placed front neighbour the mean of the parents'
    /// (`turn`), or none.
    fn turn(
        &self,
        old: &[[f64; 2]],
        new: &[[f64; 2]],
        placed: &[bool],
        parents: [u32; 2],
        turn: &[[f64; 2]],
        p: usize,
    ) -> [f64; 2] {
        if let Some(z) = self.rotation(old, new, placed, p) {
            return z;
        }
        let mut z = [0.0, 0.0];
        for &q in parents.iter().filter(|&&q| q != NONE) {
            z[0] += turn[q as usize][0];
            z[1] += turn[q as usize][1];
        }
        let l = z[0].hypot(z[1]);
        if l > 0.0 {
            [z[0] / l, z[1] / l]
        } else {
            [1.0, 0.0]
        }
    }
}

fn unit(a: [f64; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l = d[0].hypot(d[1]);
    (l > 0.0).then(|| [d[0] / l, d[1] / l])
}

fn rotate(z: [f64; 2], v: [f64; 2]) -> [f64; 2] {
    [z[0] * v[0] - z[1] * v[1], z[1] * v[0] + z[0] * v[1]]
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])).sqrt()
}

/// The layer nodes that keep their original layer geometry, grouped by layer (index 0 is
/// empty): the nodes grown from the walls (every parent on a wall or kept) up to the last
/// layer whose median cell is still anisotropic (front spacing at least `aspect` times the
/// extrusion length), so that the kept layers wrap every wall in a band, corners included.
fn layer_nodes(
    layering: &Layering,
    fixed: &[bool],
    wall: &[bool],
    old: &[[f64; 2]],
    fronts: &Fronts,
    aspect: f64,
) -> Vec<Vec<u32>> {
    let mut by_layer: Vec<Vec<u32>> = Vec::new();
    for (k, &l) in layering.node_layer.iter().enumerate() {
        if l != NONE && l > 0 && !fixed[k] {
            if by_layer.len() <= l as usize {
                by_layer.resize(l as usize + 1, Vec::new());
            }
            by_layer[l as usize].push(k as u32);
        }
    }
    // the layers grown from the walls, and each node's aspect
    let mut kept = wall.to_vec();
    let mut stop = by_layer.len();
    for (l, layer) in by_layer.iter_mut().enumerate() {
        let mut aspects = Vec::with_capacity(layer.len());
        layer.retain(|&n| {
            let n = n as usize;
            let parents = layering.node_parents[n];
            let (mut ok, mut height) = (parents[0] != NONE, f64::INFINITY);
            for &q in parents.iter().filter(|&&q| q != NONE) {
                ok &= kept[q as usize];
                height = height.min(dist(old[q as usize], old[n]));
            }
            let (mut spacing, mut sides) = (0.0, 0.0);
            for q in [fronts.left[n], fronts.right[n]] {
                if q != NONE {
                    spacing += dist(old[q as usize], old[n]);
                    sides += 1.0;
                }
            }
            if ok && sides > 0.0 {
                aspects.push(spacing / sides / height);
            }
            kept[n] = ok && !fixed[n];
            kept[n]
        });
        if l > 1 && !aspects.is_empty() {
            aspects.sort_unstable_by(f64::total_cmp);
            if aspects[aspects.len() / 2] < aspect {
                stop = l;
                break;
            }
        }
    }
    by_layer.truncate(stop);
    by_layer
}

/// The other corners of the cells on a wall facet that no layer keeps (the filled region's
/// triangles that reach a wall) move rigidly with the facet's nodes (the mean of their
/// predictions, each node turning by its `turn`) and are then held, so that every first-layer
/// cell keeps its shape.
fn pin_wall_cells(
    mesh: &Mesh,
    wall: &[bool],
    old: &[[f64; 2]],
    x: &mut [[f64; 2]],
    turn: &mut [[f64; 2]],
    held: &mut [bool],
) {
    let facets: std::collections::HashSet<(u32, u32)> = mesh
        .boundary
        .iter()
        .map(|f| (f.corners()[0], f.corners()[1]))
        .filter(|&(a, b)| wall[a as usize] && wall[b as usize])
        .collect();
    for c in 0..mesh.cells.len() {
        let cell = mesh.cells.get(c);
        let k = cell.corners();
        let on_wall: Vec<usize> = (0..k.len())
            .filter(|&j| facets.contains(&(k[j], k[(j + 1) % k.len()])))
            .flat_map(|j| [k[j] as usize, k[(j + 1) % k.len()] as usize])
            .collect();
        if on_wall.is_empty() {
            continue;
        }
        for &n in k {
            let n = n as usize;
            if held[n] {
                continue;
            }
            let (mut sum, mut z) = ([0.0, 0.0], [0.0, 0.0]);
            for &b in &on_wall {
                let off = rotate(turn[b], [old[n][0] - old[b][0], old[n][1] - old[b][1]]);
                sum[0] += x[b][0] + off[0];
                sum[1] += x[b][1] + off[1];
                z[0] += turn[b][0];
                z[1] += turn[b][1];
            }
            let count = on_wall.len() as f64;
            x[n] = [sum[0] / count, sum[1] / count];
            let l = z[0].hypot(z[1]);
            turn[n] = if l > 0.0 {
                [z[0] / l, z[1] / l]
            } else {
                [1.0, 0.0]
            };
            held[n] = true;
        }
    }
}

/// The predictor: each layer node at its moved parents plus its original offset turned with
/// the parent's front, layer by layer.
fn predict(
    old: &[[f64; 2]],
    x: &mut [[f64; 2]],
    fronts: &Fronts,
    layering: &Layering,
    layers: &[Vec<u32>],
    fixed: &[bool],
) {
    let mut placed = fixed.to_vec();
    let mut turn = vec![[1.0, 0.0]; old.len()];
    held_turns(old, x, fronts, layering, &[], &placed, fixed, &mut turn);
    for layer in layers.iter().filter(|l| !l.is_empty()) {
        for &n in layer {
            let n = n as usize;
            let (mut sum, mut count) = ([0.0, 0.0], 0.0);
            for &q in layering.node_parents[n].iter().filter(|&&q| q != NONE) {
                let q = q as usize;
                let off = rotate(turn[q], [old[n][0] - old[q][0], old[n][1] - old[q][1]]);
                sum[0] += x[q][0] + off[0];
                sum[1] += x[q][1] + off[1];
                count += 1.0;
            }
            x[n] = [sum[0] / count, sum[1] / count];
            placed[n] = true;
        }
        held_turns(old, x, fronts, layering, layer, &placed, fixed, &mut turn);
    }
}

/// The rotation of the held nodes `layer` (or, `layer` empty, of the boundary nodes `fixed`)
/// from `old` to `x`: their fronts', or their parents' ([`Fronts::turn`]).
#[allow(clippy::too_many_arguments)]
fn held_turns(
    old: &[[f64; 2]],
    x: &[[f64; 2]],
    fronts: &Fronts,
    layering: &Layering,
    layer: &[u32],
    placed: &[bool],
    fixed: &[bool],
    turn: &mut [[f64; 2]],
) {
    if layer.is_empty() {
        for k in (0..old.len()).filter(|&k| fixed[k]) {
            turn[k] = fronts.turn(old, x, placed, [NONE; 2], turn, k);
        }
    }
    for &n in layer {
        let n = n as usize;
        turn[n] = fronts.turn(old, x, placed, layering.node_parents[n], turn, n);
    }
}

/// The springs of the layers with the original geometry as the ideal one, and each node's
/// length scale (its shortest original extrusion edge). Neighbour and angle springs are made
/// only between `held` nodes (boundary and kept layer nodes). The neighbour springs' shares
/// and the angle springs' angles are those of the `predicted` layers (module docs, step 4:
/// with the original ones a corner's fan turned 13° at the NACA0012's blunt trailing edge
/// under ×1.5).
fn build_springs(
    old: &[[f64; 2]],
    predicted: &[[f64; 2]],
    fronts: &Fronts,
    layering: &Layering,
    layers: &[Vec<u32>],
    held: &[bool],
) -> (SpringSet2d, Vec<f64>) {
    let mut set = SpringSet2d::default();
    let mut scale = vec![f64::INFINITY; old.len()];
    for &n in layers.iter().flatten() {
        let nu = n as usize;
        let parents = layering.node_parents[nu];
        for &p in parents.iter().filter(|&&p| p != NONE) {
            let pu = p as usize;
            let ideal = dist(old[pu], old[nu]);
            if ideal <= 0.0 {
                continue;
            }
            scale[nu] = scale[nu].min(ideal);
            set.extrusion.push(ExtrusionSpring {
                lower: p,
                upper: n,
                ideal_length: ideal,
                lower_share: 1.0,
            });
            let (a, b) = (fronts.left[pu], fronts.right[pu]);
            if a == NONE || b == NONE || !held[a as usize] || !held[b as usize] {
                continue;
            }
            let q = predicted;
            if let Some(bis) = bisector(q[a as usize], q[pu], q[b as usize]) {
                let v = [q[nu][0] - q[pu][0], q[nu][1] - q[pu][1]];
                let offset_rad =
                    (bis[0] * v[1] - bis[1] * v[0]).atan2(bis[0] * v[0] + bis[1] * v[1]);
                set.angle.push(AngleSpring {
                    left: a,
                    centre: p,
                    right: b,
                    child: n,
                    offset_rad,
                    ideal_length: ideal,
                });
            }
        }
        let (a, b, p) = (fronts.left[nu], fronts.right[nu], parents[0]);
        if a != NONE && b != NONE && p != NONE && held[a as usize] && held[b as usize] {
            let (la, lb) = (
                dist(predicted[a as usize], predicted[nu]),
                dist(predicted[nu], predicted[b as usize]),
            );
            if la + lb > 0.0 {
                set.neighbour.push(NeighbourSpring {
                    left: a,
                    centre: n,
                    right: b,
                    parent: p,
                    left_share: la / (la + lb),
                });
            }
        }
    }
    for s in &mut scale {
        if !s.is_finite() {
            *s = 1.0;
        }
    }
    (set, scale)
}

/// Re-balances the springs of the layers (boundary and fill held).
#[allow(clippy::too_many_arguments)]
fn balance(
    old: &[[f64; 2]],
    x: &mut [[f64; 2]],
    fronts: &Fronts,
    layering: &Layering,
    layers: &[Vec<u32>],
    held: &[bool],
    p: &SpringMoveParams,
    stats: &mut SpringStats,
) -> Result<(), MoveError> {
    let (set, scale) = build_springs(old, x, fronts, layering, layers, held);
    stats.springs = set.extrusion.len() + set.neighbour.len() + set.angle.len();
    let model = SpringField2d::new(&set, &p.springs, old.len());
    let mut movable = vec![false; old.len()];
    let mut run = |movable: &[bool], x: &mut [[f64; 2]]| -> Result<(), MoveError> {
        let out =
            solve_model_active(x, &scale, movable, &model, &p.solver).map_err(spring_error)?;
        stats.solves += 1;
        stats.iterations += out.iterations;
        stats.converged &= out.converged;
        stats.residual = out.max_relative_step;
        Ok(())
    };
    if p.strategy == Strategy::LayerByLayer {
        for layer in layers.iter().filter(|l| !l.is_empty()) {
            movable.iter_mut().for_each(|m| *m = false);
            layer.iter().for_each(|&n| movable[n as usize] = true);
            run(&movable, x)?;
        }
    }
    movable.iter_mut().for_each(|m| *m = false);
    layers
        .iter()
        .flatten()
        .for_each(|&n| movable[n as usize] = true);
    if movable.iter().any(|&m| m) {
        run(&movable, x)?;
    }
    Ok(())
}

/// The filled region (the `free` nodes, `cells` its cells) placed by the fill `p.fill` from
/// its bounding nodes.
fn fill(
    mesh: &Mesh,
    (old, x): (&[[f64; 2]], &mut [[f64; 2]]),
    (turns, reference): (&[[f64; 2]], &[[f64; 2]]),
    (free, cells): (&[bool], &[Vec<u32>]),
    p: &SpringMoveParams,
    stats: &mut SpringStats,
) {
    let nodes: Vec<u32> = (0..old.len() as u32)
        .filter(|&k| free[k as usize])
        .collect();
    stats.fill_nodes = nodes.len();
    if nodes.is_empty() {
        return;
    }
    let sources = fill_sources(old, x, turns, reference, cells, free);
    stats.fill = p.fill;
    match p.fill {
        Fill::Idw => {
            let moved: Vec<[f64; 2]> = nodes
                .par_iter()
                .map(|&k| {
                    let (o, d) = (
                        old[k as usize],
                        sources.idw(old[k as usize], p.idw.exponent),
                    );
                    [o[0] + d[0], o[1] + d[1]]
                })
                .collect();
            for (&k, m) in nodes.iter().zip(moved) {
                x[k as usize] = m;
            }
        }
        Fill::Screw => screw(old, x, &sources, &nodes, p.screw_exponent),
        Fill::Arap => {
            screw(old, x, &sources, &nodes, p.screw_exponent);
            let graph = Graph::new(old, cells, free);
            stats.arap_iterations = arap(old, x, &graph, p.arap_iterations);
        }
        Fill::Rbf => match Rbf::fit(mesh, &sources, &RbfParams::default()) {
            Ok(rbf) => {
                let moved: Vec<[f64; 2]> = nodes
                    .par_iter()
                    .map(|&k| {
                        let (o, d) = (old[k as usize], rbf.displacement(old[k as usize]));
                        [o[0] + d[0], o[1] + d[1]]
                    })
                    .collect();
                for (&k, m) in nodes.iter().zip(moved) {
                    x[k as usize] = m;
                }
            }
            // a singular system: the screw fill
            Err(_) => {
                screw(old, x, &sources, &nodes, p.screw_exponent);
                stats.fill = Fill::Screw;
            }
        },
    }
}

/// The cells with a corner in the filled region (`free`), as corner lists.
fn fill_cells(mesh: &Mesh, free: &[bool]) -> Vec<Vec<u32>> {
    (0..mesh.cells.len())
        .map(|c| mesh.cells.get(c).corners().to_vec())
        .filter(|k| k.iter().any(|&n| free[n as usize]))
        .collect()
}

/// The nodes that bound the filled region (on an edge of one fill cell only, or held), as IDW
/// sources turning with their fronts.
fn fill_sources(
    old: &[[f64; 2]],
    x: &[[f64; 2]],
    turns: &[[f64; 2]],
    reference: &[[f64; 2]],
    cells: &[Vec<u32>],
    free: &[bool],
) -> Sources {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for k in cells {
        for j in 0..k.len() {
            let (a, b) = (k[j], k[(j + 1) % k.len()]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut area: HashMap<u32, f64> = HashMap::new();
    for (&(a, b), &c) in &count {
        if c == 1 || !free[a as usize] && !free[b as usize] {
            let half = 0.5 * dist(old[a as usize], old[b as usize]);
            for n in [a, b].into_iter().filter(|&n| !free[n as usize]) {
                *area.entry(n).or_default() += half;
            }
        }
    }
    let mut list: Vec<(u32, f64)> = area.into_iter().collect();
    list.sort_unstable_by_key(|e| e.0);
    let mut s = Sources {
        at: Vec::with_capacity(list.len()),
        d: Vec::with_capacity(list.len()),
        m: Vec::with_capacity(list.len()),
        area: Vec::with_capacity(list.len()),
        turn: Vec::with_capacity(list.len()),
        log_scale: Vec::with_capacity(list.len()),
    };
    for (n, a) in list {
        let k = n as usize;
        let z = turns[k];
        s.turn.push(reference[k][0]);
        s.log_scale.push(reference[k][1]);
        s.at.push(old[k]);
        s.d.push([x[k][0] - old[k][0], x[k][1] - old[k][1]]);
        s.m.push([[z[0] - 1.0, -z[1]], [z[1], z[0] - 1.0]]);
        s.area.push(a);
    }
    s
}

/// The filled region as a graph: its cells' edges weighted by 1/length² (original), the free
/// nodes numbered, and the Laplacian over them.
struct Graph {
    /// Per cell, its edges (a, b, weight).
    edges: Vec<Vec<(usize, usize, f64)>>,
    /// Global → free number, [`NONE`] for held nodes.
    index: Vec<u32>,
    /// Free number → global.
    order: Vec<usize>,
    /// The 1/length²-weighted Laplacian.
    laplacian: Laplacian,
}

impl Graph {
    fn new(old: &[[f64; 2]], cells: &[Vec<u32>], free: &[bool]) -> Graph {
        let mut index = vec![NONE; old.len()];
        let order: Vec<usize> = (0..old.len()).filter(|&k| free[k]).collect();
        for (i, &k) in order.iter().enumerate() {
            index[k] = i as u32;
        }
        let edges: Vec<Vec<(usize, usize, f64)>> = cells
            .iter()
            .map(|k| {
                (0..k.len())
                    .map(|j| {
                        let (a, b) = (k[j] as usize, k[(j + 1) % k.len()] as usize);
                        let l = dist(old[a], old[b]);
                        (a, b, if l > 0.0 { 1.0 / (l * l) } else { 0.0 })
                    })
                    .collect()
            })
            .collect();
        let laplacian = Laplacian::new(&edges, &index, order.len());
        Graph {
            edges,
            index,
            order,
            laplacian,
        }
    }
}

/// Complex product.
fn mul(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]]
}

/// Complex quotient `a / b`.
fn div(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let n = b[0] * b[0] + b[1] * b[1];
    mul(a, [b[0] / n, -b[1] / n])
}

/// `e^a` for a complex `a = σ + iθ`: scaling by `e^σ`, turning by `θ`.
fn exp(a: [f64; 2]) -> [f64; 2] {
    let (s, c) = a[1].sin_cos();
    let r = a[0].exp();
    [r * c, r * s]
}

/// `V(a) = (e^a − 1)/a`, the translation part of the exponential of a similarity (a rigid
/// motion when `σ = 0`).
fn screw_v(a: [f64; 2]) -> [f64; 2] {
    if a[0].hypot(a[1]) < 1e-8 {
        [1.0 + 0.5 * a[0], 0.5 * a[1]]
    } else {
        let e = exp(a);
        div([e[0] - 1.0, e[1]], a)
    }
}

/// The logarithm `(σ, θ, w)` about `o` of the similarity that scales by `e^σ`, turns by `z`
/// and takes `from` to `to`. The angle of `z` is read on the branch nearest `reference` (its
/// body's turn, from its motion): a half turn is then ±π as the motion says, for every node
/// of the body.
fn screw_log(
    o: [f64; 2],
    (z, reference, sigma): ([f64; 2], f64, f64),
    from: [f64; 2],
    to: [f64; 2],
) -> [f64; 4] {
    let (s, c) = reference.sin_cos();
    let relative = mul(z, [c, -s]);
    let a = [sigma, reference + relative[1].atan2(relative[0])];
    let r = mul(exp(a), [from[0] - o[0], from[1] - o[1]]);
    let t = [to[0] - o[0] - r[0], to[1] - o[1] - r[1]];
    let w = div(t, screw_v(a));
    [a[0], a[1], w[0], w[1]]
}

/// The exponential of the logarithm `log` about `o`, applied to `p`.
fn screw_exp(o: [f64; 2], log: [f64; 4], p: [f64; 2]) -> [f64; 2] {
    let a = [log[0], log[1]];
    let r = mul(exp(a), [p[0] - o[0], p[1] - o[1]]);
    let t = mul(screw_v(a), [log[2], log[3]]);
    [o[0] + r[0] + t[0], o[1] + r[1] + t[1]]
}

/// The screw fill: each source's local similarity (its body's scale, its turn, taking its
/// original position to its current one) as a logarithm `(σ, θ, w)`; at each free node the
/// inverse-distance-weighted mean of the sources' logarithms, exponentiated. Blending
/// logarithms keeps a rigid motion exact and makes a rotation a twist about its centre and a
/// scaling a graded one, without the shrinking of blended positions; near a wall its nodes
/// dominate, so a node there moves with the wall's own motion.
fn screw(old: &[[f64; 2]], x: &mut [[f64; 2]], sources: &Sources, nodes: &[u32], exponent: f64) {
    let o = centre(old);
    let logs: Vec<[f64; 4]> = (0..sources.at.len())
        .map(|i| {
            let m = sources.m[i];
            let z = [m[0][0] + 1.0, m[1][0]];
            let b = sources.at[i];
            let to = [b[0] + sources.d[i][0], b[1] + sources.d[i][1]];
            screw_log(o, (z, sources.turn[i], sources.log_scale[i]), b, to)
        })
        .collect();
    let columns = Columns::of(&sources.at, &sources.area, &logs);
    // the default exponent 2.5 (and 2) by a division and square roots: powf was this
    // nodes × sources loop's largest cost
    let blend = |p: [f64; 2]| match exponent {
        2.5 => columns.blend(p, |r2| 1.0 / (r2 * r2.sqrt().sqrt())),
        2.0 => columns.blend(p, |r2| 1.0 / r2),
        _ => columns.blend(p, |r2| r2.powf(-0.5 * exponent)),
    };
    let moved: Vec<[f64; 2]> = nodes
        .par_iter()
        .map(|&k| {
            let p = old[k as usize];
            screw_exp(o, blend(p), p)
        })
        .collect();
    for (&k, m) in nodes.iter().zip(moved) {
        x[k as usize] = m;
    }
}

/// The lanes of [`Columns::blend`]'s sums.
const LANES: usize = 4;

/// The screw fill's sources by columns (position, weight, logarithm), padded to a multiple
/// of [`LANES`] with weightless copies of the first, so that the weighted sums run in lanes
/// the compiler vectorises (a node's blend is a sum over every source).
struct Columns {
    x: Vec<f64>,
    y: Vec<f64>,
    area: Vec<f64>,
    log: [Vec<f64>; 4],
}

impl Columns {
    fn of(at: &[[f64; 2]], area: &[f64], logs: &[[f64; 4]]) -> Columns {
        let n = at.len().div_ceil(LANES) * LANES;
        let padded = |i: usize| i.min(at.len().saturating_sub(1));
        let column = |f: &dyn Fn(usize) -> f64| -> Vec<f64> { (0..n).map(f).collect() };
        Columns {
            x: column(&|i| at.get(padded(i)).map_or(0.0, |p| p[0])),
            y: column(&|i| at.get(padded(i)).map_or(0.0, |p| p[1])),
            area: column(&|i| if i < at.len() { area[i] } else { 0.0 }),
            log: std::array::from_fn(|c| column(&|i| logs.get(padded(i)).map_or(0.0, |l| l[c]))),
        }
    }

    /// The mean of the sources' logarithms at `p`, weighted by their areas times
    /// `inverse(r²)`.
    fn blend(&self, p: [f64; 2], inverse: impl Fn(f64) -> f64) -> [f64; 4] {
        let (mut sum, mut total) = ([[0.0; LANES]; 4], [0.0; LANES]);
        let chunks = self.x.len() / LANES;
        for ch in 0..chunks {
            let at = ch * LANES..(ch + 1) * LANES;
            let (x, y, area) = (
                &self.x[at.clone()],
                &self.y[at.clone()],
                &self.area[at.clone()],
            );
            let log: [&[f64]; 4] = std::array::from_fn(|c| &self.log[c][at.clone()]);
            for l in 0..LANES {
                let r2 = (p[0] - x[l]) * (p[0] - x[l]) + (p[1] - y[l]) * (p[1] - y[l]);
                let w = area[l] * inverse(r2);
                for c in 0..4 {
                    sum[c][l] += w * log[c][l];
                }
                total[l] += w;
            }
        }
        let total: f64 = total.iter().sum();
        sum.map(|lanes| lanes.iter().sum::<f64>() / total)
    }
}

/// The held nodes that bound the filled region: the held corners of its cells
/// ([`fill_cells`]; the fill's sources are among them).
fn bounding_nodes(cells: &[Vec<u32>], held: &[bool]) -> Vec<bool> {
    let mut bounding = vec![false; held.len()];
    for &k in cells.iter().flatten().filter(|&&k| held[k as usize]) {
        bounding[k as usize] = true;
    }
    bounding
}

/// Each `wanted` node's reference turn and log-scale (the others' `[0, 0]`): those of the
/// nearest boundary node's body ([`BoundaryMotion::turn`], [`BoundaryMotion::linear`]); the
/// branch on which its rotation angle is read, and the scale of its local similarity.
fn reference_turns(old: &[[f64; 2]], boundary: &BoundaryMotion, wanted: &[bool]) -> Vec<[f64; 2]> {
    let points: Vec<[f64; 2]> = boundary.nodes.iter().map(|&k| old[k as usize]).collect();
    let tree = geom_predicates::PointTree::new(&points);
    old.iter()
        .zip(wanted)
        .map(|(&p, &wanted)| {
            if !wanted {
                return [0.0, 0.0];
            }
            tree.nearest(p).map_or([0.0, 0.0], |(i, _)| {
                [
                    boundary.turn[i],
                    crate::movers::log_scale(boundary.linear[i]),
                ]
            })
        })
        .collect()
}

/// The centre of the bounding box of `points`.
fn centre(points: &[[f64; 2]]) -> [f64; 2] {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]
}

/// As-rigid-as-possible iterations on the free nodes of `graph` from `x` (held nodes stay):
/// each cell's best rotation of its original edges onto its current ones, then the global
/// step; returns the iterations done.
fn arap(old: &[[f64; 2]], x: &mut [[f64; 2]], graph: &Graph, iterations: usize) -> usize {
    let size = old
        .iter()
        .chain(x.iter())
        .fold(0.0f64, |s, p| s.max(p[0].abs()).max(p[1].abs()));
    let mut rotations = vec![[1.0, 0.0]; graph.edges.len()];
    let mut done = 0;
    while done < iterations {
        done += 1;
        for (ce, z) in graph.edges.iter().zip(&mut rotations) {
            let (mut c, mut s) = (0.0, 0.0);
            for &(a, b, w) in ce {
                let e0 = [old[b][0] - old[a][0], old[b][1] - old[a][1]];
                let e1 = [x[b][0] - x[a][0], x[b][1] - x[a][1]];
                c += w * (e0[0] * e1[0] + e0[1] * e1[1]);
                s += w * (e0[0] * e1[1] - e0[1] * e1[0]);
            }
            let l = c.hypot(s);
            *z = if l > 0.0 { [c / l, s / l] } else { [1.0, 0.0] };
        }
        let change = global_step(
            old,
            x,
            &graph.edges,
            &rotations,
            &graph.index,
            &graph.order,
            &graph.laplacian,
        );
        if change <= 1e-12 * size {
            break;
        }
    }
    done
}

/// The free positions that fit the original edges turned by each cell's rotation best;
/// returns the largest coordinate change.
fn global_step(
    old: &[[f64; 2]],
    x: &mut [[f64; 2]],
    edges: &[Vec<(usize, usize, f64)>],
    rotations: &[[f64; 2]],
    index: &[u32],
    order: &[usize],
    laplacian: &Laplacian,
) -> f64 {
    let mut rhs = vec![[0.0; 2]; order.len()];
    for (ce, &z) in edges.iter().zip(rotations) {
        for &(a, b, w) in ce {
            let r = rotate(z, [old[a][0] - old[b][0], old[a][1] - old[b][1]]);
            for (i, j, sign) in [(a, b, 1.0), (b, a, -1.0)] {
                if index[i] == NONE {
                    continue;
                }
                let row = &mut rhs[index[i] as usize];
                row[0] += sign * w * r[0];
                row[1] += sign * w * r[1];
                if index[j] == NONE {
                    row[0] += w * x[j][0];
                    row[1] += w * x[j][1];
                }
            }
        }
    }
    let mut change = 0.0f64;
    for c in 0..2 {
        let b: Vec<f64> = rhs.iter().map(|r| r[c]).collect();
        let mut v: Vec<f64> = order.iter().map(|&k| x[k][c]).collect();
        laplacian.solve(&b, &mut v);
        for (&k, val) in order.iter().zip(v) {
            change = change.max((x[k][c] - val).abs());
            x[k][c] = val;
        }
    }
    change
}

/// The weighted graph Laplacian of the free nodes (held neighbours moved to the right-hand
/// side), in compressed rows, with its conjugate-gradient solve.
struct Laplacian {
    diagonal: Vec<f64>,
    start: Vec<usize>,
    col: Vec<usize>,
    value: Vec<f64>,
}

impl Laplacian {
    fn new(edges: &[Vec<(usize, usize, f64)>], index: &[u32], m: usize) -> Laplacian {
        let mut diagonal = vec![0.0; m];
        let mut off: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
        for &(a, b, w) in edges.iter().flatten() {
            for (i, j) in [(a, b), (b, a)] {
                if index[i] == NONE {
                    continue;
                }
                let r = index[i] as usize;
                diagonal[r] += w;
                if index[j] != NONE {
                    off[r].push((index[j] as usize, -w));
                }
            }
        }
        let mut start = vec![0];
        let (mut col, mut value) = (Vec::new(), Vec::new());
        for row in off {
            for (c, v) in row {
                col.push(c);
                value.push(v);
            }
            start.push(col.len());
        }
        Laplacian {
            diagonal,
            start,
            col,
            value,
        }
    }

    fn apply(&self, v: &[f64], out: &mut [f64]) {
        for (r, o) in out.iter_mut().enumerate() {
            let mut s = self.diagonal[r] * v[r];
            for e in self.start[r]..self.start[r + 1] {
                s += self.value[e] * v[self.col[e]];
            }
            *o = s;
        }
    }

    /// Jacobi-preconditioned conjugate gradients from the guess in `v`, to a residual of
    /// 1e-13 of the right-hand side.
    fn solve(&self, b: &[f64], v: &mut [f64]) {
        let n = b.len();
        let dot = |a: &[f64], c: &[f64]| a.iter().zip(c).map(|(p, q)| p * q).sum::<f64>();
        let mut q = vec![0.0; n];
        self.apply(v, &mut q);
        let mut r: Vec<f64> = b.iter().zip(&q).map(|(b, q)| b - q).collect();
        let goal = 1e-13 * dot(b, b).sqrt();
        let mut z: Vec<f64> = r.iter().zip(&self.diagonal).map(|(r, d)| r / d).collect();
        let mut d = z.clone();
        let mut rz = dot(&r, &z);
        for _ in 0..10 * n.max(10) {
            if dot(&r, &r).sqrt() <= goal {
                break;
            }
            self.apply(&d, &mut q);
            let alpha = rz / dot(&d, &q);
            for i in 0..n {
                v[i] += alpha * d[i];
                r[i] -= alpha * q[i];
                z[i] = r[i] / self.diagonal[i];
            }
            let rz_next = dot(&r, &z);
            let beta = rz_next / rz;
            rz = rz_next;
            for i in 0..n {
                d[i] = z[i] + beta * d[i];
            }
        }
    }
}
