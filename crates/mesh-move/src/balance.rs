//! The smooth balance: the last phase of the spring mover, and the mesh sensitivities.
//!
//! The large-motion phase (predictor, layer springs, fill) puts every node near where it
//! should go, but it is made of choices (the best fill, the springs' switches) and stops at a
//! tolerance, so its result is not a smooth function of the boundary: a 10⁻¹⁰ bump can move
//! it by 10⁻⁵, which is what broke the dissertation's shape optimisation. This phase then
//! holds every cell to its original shape with `springfield`'s shape springs (a triangle by
//! itself, a quadrilateral by its four corner triangles; the energy of each is its
//! distortion from the original, zero for a rigid motion and infinite for a flat cell; a
//! quadrilateral's opposite corners held to the same deformation above the first layers),
//! the first layers' extrusion edges to their lengths and their angles with the wall, and
//! balances them by Newton's method to machine precision, boundary nodes held. The balance
//! is a smooth function of the boundary (the implicit function theorem, wherever its
//! stiffness is positive definite), does not depend on where the predictor put the nodes as
//! long as it is in the balance's basin, and never inverts a cell (the energy would be
//! infinite). Its linearisation gives the sensitivities: for a motion `dB` of the boundary
//! nodes, `dX = (−∂F/∂X)⁻¹ ∂F/∂B dB` for every other node, one solve per design variable with
//! one factorisation.
//!
//! It owns the shape balance of a moved mesh and its linearisation. It does not move the
//! boundary (the caller), nor curve (Vector-Adding).

use std::sync::Mutex;

use geom_predicates::{PointTree, point_segment_distance};
use mesh_model::topology::Edges;
use mesh_model::{LayeredMesh, Mesh, NONE, Role};
use springfield::{
    BalanceSpring, CornerSpring, LengthSpring, Linearised, NewtonOutcome, NewtonParams,
    NewtonWorkspace, QuadSpring, ShapeLaw, ShapeSpring, SpringList, SpringParams, shape_springs,
    solve_newton_in,
};

use crate::MoveError;

/// The shape springs of `original`, the length springs of its extrusion edges, and each
/// node's length scale (its shortest edge); and the Newton workspace of its last balance,
/// which the next balance with the same held nodes starts from (a motion sequence balances
/// one field once per step).
pub struct ShapeField {
    springs: Vec<BalanceSpring>,
    scale: Vec<f64>,
    params: SpringParams,
    workspace: Mutex<Option<NewtonWorkspace<2>>>,
}

impl std::fmt::Debug for ShapeField {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShapeField")
            .field("springs", &self.springs.len())
            .field("nodes", &self.scale.len())
            .finish_non_exhaustive()
    }
}

impl ShapeField {
    /// The field holding every cell of `layered` (a linear 2D mesh) to its shape and every
    /// extrusion edge (a layer node and its parents) to its length.
    ///
    /// # Errors
    /// [`MoveError::Springs`] when a cell is not a positive triangle or quadrilateral.
    pub fn of(layered: &LayeredMesh, law: ShapeLaw) -> Result<ShapeField, MoveError> {
        let original = &layered.mesh;
        let rest: Vec<[f64; 2]> = (0..original.nodes.len() as u32)
            .map(|k| original.xy(k))
            .collect();
        let weight = weights(original, &rest);

        let shapes = shape_springs(original.cells.iter().map(|c| c.nodes), &rest, law, &weight)
            .ok_or_else(|| MoveError::Springs {
                what: "a cell of the original mesh is not a positive triangle or quadrilateral"
                    .into(),
            })?;
        let mut springs = cell_springs(layered, &weight, shapes);
        springs.extend(
            extrusion_springs(layered, &rest, &weight)
                .into_iter()
                .map(BalanceSpring::Length),
        );
        springs.extend(
            corner_springs(original, &rest, &weight)
                .into_iter()
                .map(BalanceSpring::Corner),
        );
        let mut scale = vec![f64::INFINITY; rest.len()];
        for c in original.cells.iter() {
            let n = c.nodes.len();
            for i in 0..n {
                let (a, b) = (c.nodes[i] as usize, c.nodes[(i + 1) % n] as usize);
                let l = (rest[a][0] - rest[b][0]).hypot(rest[a][1] - rest[b][1]);
                scale[a] = scale[a].min(l);
                scale[b] = scale[b].min(l);
            }
        }
        scale
            .iter_mut()
            .filter(|s| !s.is_finite())
            .for_each(|s| *s = 1.0);
        Ok(ShapeField {
            springs,
            scale,
            params: SpringParams::default(),
            workspace: Mutex::new(None),
        })
    }

    fn model(&self) -> SpringList<'_, BalanceSpring> {
        SpringList {
            springs: &self.springs,
            params: &self.params,
        }
    }

    /// Balances the nodes not `fixed` of `x` (which must have no inverted cell) by Newton's
    /// method.
    ///
    /// # Errors
    /// [`MoveError::Springs`] when `x` has an inverted cell or the solve fails.
    pub fn balance(
        &self,
        x: &mut [[f64; 2]],
        fixed: &[bool],
        params: &NewtonParams,
    ) -> Result<NewtonOutcome, MoveError> {
        let movable: Vec<bool> = fixed.iter().map(|f| !f).collect();
        // a poisoned lock only means a balance panicked: its workspace is dropped
        let kept = self.workspace.lock().ok().and_then(|mut w| w.take());
        let mut workspace = match kept {
            Some(w) if w.movable() == movable.as_slice() => w,
            _ => NewtonWorkspace::new(&movable),
        };
        let outcome = solve_newton_in(&self.model(), x, &self.scale, &mut workspace, params)
            .map_err(|e| MoveError::Springs {
                what: format!("the shape balance: {e}"),
            })?;
        if let Ok(mut w) = self.workspace.lock() {
            *w = Some(workspace);
        }
        Ok(outcome)
    }

    /// Frees the numeric factor of its last balance, keeping its pattern and ordering
    /// ([`NewtonWorkspace::release_factor`]): for a caller that fills a start before the
    /// next balance.
    pub fn release_factor(&self) {
        if let Ok(mut kept) = self.workspace.lock()
            && let Some(w) = kept.as_mut()
        {
            w.release_factor();
        }
    }

    /// The linearised balance at `x` (a balance of this field with `fixed` held), for
    /// [`Sensitivity::respond`].
    ///
    /// # Errors
    /// [`MoveError::Springs`] when the balance is not stable there.
    pub fn linearise(&self, x: &[[f64; 2]], fixed: &[bool]) -> Result<Sensitivity, MoveError> {
        let movable: Vec<bool> = fixed.iter().map(|f| !f).collect();
        let lin = Linearised::at(&self.model(), x, &movable).map_err(|e| MoveError::Springs {
            what: format!("linearising the balance: {e}"),
        })?;
        Ok(Sensitivity { lin })
    }
}

/// How much stiffer a skewed cell is: its weight is divided by its original scaled Jacobian
/// to this power (at most [`MAX_STIFFENING`] times).
const SKEW_STIFFENING: f64 = 30.0;
/// The most a cell is stiffened for its skewness (why 15: below).
const MAX_STIFFENING: f64 = 15.0;

/// The power of its area a cell's weight grows with (below).
const AREA_POWER: f64 = 0.75;
/// The power of the wall distance a cell's weight is divided by (below).
const DISTANCE_POWER: f64 = 0.9;

/// Each cell's weight in the balance: its area to the power 0.75 over its distance to the
/// nearest wall (to the nearest boundary when there is no wall) to the power 0.9, stiffened
/// by its skewness.
///
/// Why: a body turned inside a fixed far field twists the mesh between them, and where the
/// balance puts the twist depends on the weights. With equal weights it goes where cells are
/// few (the coarse outer region, sheared hard); weighted by area, where cells are small (the
/// first layers, crushed). Area over distance² gives every ring about the body the same
/// weight per unit of log-distance, which for a twist spreads the shear evenly in
/// log-distance, and makes the thin wall cells stiff. But a flap or a slat deflected beside
/// a fixed element squeezes the gap between them, where every cell is near a wall, and the
/// worst-cell ratios are made by the smallest cells (a corner fan's, a trailing edge's):
/// weighted by their area they are the cheapest to distort. Area^0.75 keeps a small cell
/// dearer, and distance^0.9 keeps about the same balance between the near and the far
/// field for cells graded with their distance (area ∝ d²: weight ∝ d^0.6, against d^0.5
/// with area over d^1.5). Since the first layers' heights and angles have their own springs
/// ([`extrusion_springs`], [`corner_springs`]), the weights need not hold the walls.
///
/// The skewness: a balance minimises a sum, and any smooth energy is quadratic in a small
/// strain, so a few cells may take a few per cent of it; a skewed cell's scaled Jacobian
/// moves with its angles about cot θ times faster than a square's, so the worst-cell ratio
/// is made there. Dividing the weight by sj^30 (sj = 0.9: ×24) leaves the strain to the
/// well-shaped cells: on the NACA0012 pitched by 10° the worst-cell ratio went from 0.915 to
/// 0.990. But at ×1000 (the cap it had) the skewed cells of a fan or a trailing edge were so
/// much stiffer than the fill beside them that the strain piled up in the fill and in their
/// outer ring: a cap of 15 (reached at sj = 0.91) spreads it.
///
/// Measured at P3 by the four measures of issue 43 (lin / sj / sicn / edge, worst-cell
/// ratios by Gmsh), from area/d^1.5 with the cap at 1000 (and the neighbouring cells of
/// weights three times apart joined by jump springs, which made no difference since and
/// were removed) to these: the 30P30N flap +10° 0.844/0.937/0.776/0.857 →
/// 0.870/0.980/0.880/0.922, its slat 10° 0.893/0.942/0.900/0.930 → 0.899/0.983/0.912/0.945,
/// slat + flap 0.845/0.936/0.776/0.856 → 0.870/0.980/0.880/0.922, the NACA0012 pitched 90°
/// 0.791/0.854/0.769/0.675 → 0.738/0.873/0.732/0.775 (in 5 chords 0.683/0.785/0.639/0.654
/// → 0.678/0.852/0.650/0.666); and on motions not used to choose them: the two-element flap
/// 5° with a bump 0.947/0.837/0.773/0.711 → 0.845/0.837/0.842/0.812, the 30P30N flap −10°
/// 0.823/0.893/0.788/0.699 → 0.825/0.960/0.833/0.794, the NACA0012 pitched 60° in 5 chords
/// 0.801/0.906/0.754/0.781 → 0.817/0.900/0.782/0.784, the 30P30N turned 90° in 50 chords
/// 0.606/0.721/0.627/0.444 → 0.662/0.841/0.650/0.570 (45 Newton steps → 23). Caps of 10, 20
/// and 30 (with area/d^1.5): the flap 0.800/0.982/0.854/0.905, 0.838/0.976/0.852/0.901,
/// 0.852/0.973/0.842/0.892; area^0.5/d^0.4: the flap 0.918/0.962/0.904/0.920 but the pitch
/// 0.699/0.834/0.691/0.797. A larger size term of the quadrilaterals' shape law (1 to 3,
/// against 0.05) held the NACA0012's leading-edge columns under 8 bumps better (edge 0.846 →
/// 0.90–0.96) but lowered the flap's sicn (0.880 → 0.853–0.867), and at 2 the ×1.5 body's
/// balance stopped unconverged after 60 steps.
fn weights(mesh: &Mesh, rest: &[[f64; 2]]) -> Vec<f64> {
    let has_wall = mesh.patches.iter().any(|p| p.role == Role::Wall);
    // the wall facets, and the facets at each of their nodes
    let facets: Vec<[u32; 2]> = mesh
        .boundary
        .iter()
        .enumerate()
        .filter(|(f, _)| {
            !has_wall || mesh.patches[mesh.boundary_patch[*f] as usize].role == Role::Wall
        })
        .map(|(_, facet)| [facet.nodes[0], facet.nodes[1]])
        .collect();
    let mut at_node: Vec<(u32, u32)> = facets
        .iter()
        .enumerate()
        .flat_map(|(f, e)| e.map(|k| (k, f as u32)))
        .collect();
    at_node.sort_unstable();
    let nodes: Vec<u32> = at_node.iter().map(|&(k, _)| k).collect();
    let points: Vec<[f64; 2]> = nodes.iter().map(|&k| rest[k as usize]).collect();
    let tree = PointTree::new(&points);
    let distance = |p: [f64; 2]| -> f64 {
        let Some((i, d)) = tree.nearest(p) else {
            return 1.0;
        };
        let k = nodes[i];
        at_node[at_node.partition_point(|&(n, _)| n < k)..]
            .iter()
            .take_while(|&&(n, _)| n == k)
            .map(|&(_, f)| {
                let [a, b] = facets[f as usize];
                point_segment_distance(p, rest[a as usize], rest[b as usize])
            })
            .fold(d, f64::min)
    };
    mesh.cells
        .iter()
        .map(|c| {
            let n = c.nodes.len();
            let (mut centre, mut area) = ([0.0; 2], 0.0);
            for i in 0..n {
                let (p, q) = (
                    rest[c.nodes[i] as usize],
                    rest[c.nodes[(i + 1) % n] as usize],
                );
                centre = [centre[0] + p[0] / n as f64, centre[1] + p[1] / n as f64];
                area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
            }
            // a cell is never nearer its wall than a quarter of its own size
            let d = distance(centre).max(0.25 * area.abs().sqrt());
            let pts: Vec<[f64; 2]> = c.nodes.iter().map(|&k| rest[k as usize]).collect();
            let sj = crate::quality::scaled_jacobian(&pts).max(f64::MIN_POSITIVE);
            area.abs().powf(AREA_POWER) / d.powf(DISTANCE_POWER)
                * sj.powf(-SKEW_STIFFENING).min(MAX_STIFFENING)
        })
        .collect()
}

/// The weight of a quadrilateral's jump springs ([`quad_jumps_of`]) over the quadrilateral's.
const QUAD_AFFINITY: f64 = 100.0;
/// The layers whose quadrilaterals keep no jump springs of their own ([`quad_jumps_of`]): those
/// with every node in the first four layers.
const QUAD_AFFINITY_FROM: u32 = 4;
/// The layer from which a quadrilateral's jump springs have their whole weight; between the
/// two, the weight grows as the square of the layer ([`quad_jumps_of`]).
const QUAD_AFFINITY_FULL: u32 = 14;

/// The weight of quadrilateral `c`'s jump springs, its opposite corner triangles held to the
/// same deformation gradient (`springfield::quad_jumps`): [`QUAD_AFFINITY`] times the cell's
/// weight; none in the first layers, growing from [`QUAD_AFFINITY_FROM`] to
/// [`QUAD_AFFINITY_FULL`] (the cell's layer: its deepest node's).
///
/// Why: the shape springs hold each corner triangle to its shape, but a quadrilateral's
/// triangles may each stay nearly similar while the quadrilateral keystones, and then its
/// Jacobian varies over it: Gmsh's minSJ at P3, issue 43's `sj`, fell to 0.875 on the 30P30N
/// flap and slat where IDW and the thin-plate RBF, whose maps are smooth, keep 0.90–0.97.
/// These springs cost only the quadrilateral's non-affine part and couple no node outside it
/// (no fill-in of the Newton factor). Measured at P3 (`tests/movement/measures.sh`, lin / sj /
/// sicn / edge) on every quadrilateral, weights 0 → 30 → 100 → 300: the flap +10°
/// 0.890/0.875/0.791/0.859 → 0.872/0.921/0.768/0.870 → 0.842/0.937/0.775/0.855 →
/// 0.803/0.952/0.749/0.825; the slat 10° 0.905/0.876/0.884/0.893 → 0.912/0.921/0.908/0.916
/// → 0.893/0.942/0.899/0.930 → 0.831/0.958/0.900/0.919; the NACA0012 pitched 90° in 20
/// chords 0.760/0.770/0.755/0.634 → 0.777/0.834/0.777/0.661 → 0.790/0.853/0.769/0.675 →
/// 0.768/0.895/0.740/0.683. But held affine, the layers next to the wall no longer follow a
/// wall that bends or a squeezed gap: the first layer drifted by 7.7° under 8 bumps of 1 %
/// chord, by 2.8 % and 8.0° on the NACA0012 ×1.5, by 1.7 % and 4.7° on the 30P30N's flap in a
/// far field of 50 chords (first height 5e-5, 60 layers), against 2.1°, 1.5 % and 6.3°, 0.3 %
/// and 1.1° without them.
///
/// Where they start is a trade between the NACA0012's pitch in a far field of 5 chords, whose
/// quadrilaterals of layers 5 to 12 keystone (sj 0.673 with none below the thirteenth layer,
/// 0.840 from the fifth), and that far-field flap's first layer. With the first three layers'
/// extrusion edges at [`LENGTH_STIFFNESS`] 150, the weight ramped from layer 4 (squared) to
/// 12, 14, 16, 18 and 20 gave that pitch's sj 0.815, –, 0.765, 0.748, 0.735 and the flap's
/// drift 1.31 %, –, 1.04 %, 0.94 %, 0.85 %: no ramp both above the thin-plate RBF's 0.763 and
/// under 1 %. With the edges at 300, the ramp to 14 gives 0.785 and 0.65 % (4.5° with the
/// flap turned the other way; 12: 0.813 but 5.04°), and every first layer within 1 % and 5°
/// but the ×1.5 body's angle (0.98 %, 6.6°; 1.9° with [`corner_springs`]); the 30P30N flap's
/// sj 0.906 → 0.937.
fn quad_jumps_of(layered: &LayeredMesh, weight: &[f64], c: usize) -> Option<f64> {
    let cell = layered.mesh.cells.get(c);
    let layer = &layered.layering.node_layer;
    // the cell's layer: its deepest node's (a node of no layer is above them all)
    let depth = cell
        .nodes
        .iter()
        .map(|&k| layer.get(k as usize).copied().unwrap_or(NONE))
        .map(|l| if l == NONE { u32::MAX } else { l })
        .max()?;
    if depth <= QUAD_AFFINITY_FROM || cell.nodes.len() != 4 {
        return None;
    }
    let ramp = if depth > QUAD_AFFINITY_FULL {
        1.0
    } else {
        let span = f64::from(QUAD_AFFINITY_FULL - QUAD_AFFINITY_FROM + 1);
        (f64::from(depth - QUAD_AFFINITY_FROM) / span).powi(2)
    };
    Some(QUAD_AFFINITY * ramp * weight[c])
}

/// The springs of each cell of `layered`: a triangle's shape spring, a quadrilateral's four
/// corner triangles' with its jump springs ([`quad_jumps_of`]) as one spring (`shapes`: the
/// cells' shape springs in order, as `springfield::shape_springs` makes them).
fn cell_springs(
    layered: &LayeredMesh,
    weight: &[f64],
    shapes: Vec<ShapeSpring>,
) -> Vec<BalanceSpring> {
    let mut shapes = shapes.into_iter();
    let mut out = Vec::with_capacity(layered.mesh.cells.len());
    for (c, cell) in layered.mesh.cells.iter().enumerate() {
        match (cell.nodes, shapes.next()) {
            ([a, b, c4, d], Some(first)) => {
                let rest_of: Vec<ShapeSpring> = shapes.by_ref().take(3).collect();
                let [s1, s2, s3] = rest_of[..] else {
                    break;
                };
                let jumps = quad_jumps_of(layered, weight, c);
                let Some(quad) = QuadSpring::new([*a, *b, *c4, *d], [first, s1, s2, s3], jumps)
                else {
                    break;
                };
                out.push(BalanceSpring::Quad(Box::new(quad)));
            }
            (_, Some(s)) => out.push(BalanceSpring::Shape(Box::new(s))),
            (_, None) => break,
        }
    }
    out
}

/// How much a first-layer extrusion edge's length counts against its cells' shapes: its
/// spring's weight over the sum of the weights of the (one or two) cells beside it (why:
/// [`extrusion_springs`]).
const FIRST_LAYER_STIFFNESS: f64 = 600.0;
/// [`FIRST_LAYER_STIFFNESS`] in the next [`LENGTH_LAYERS`] − 1 layers.
const LENGTH_STIFFNESS: f64 = 300.0;
/// [`FIRST_LAYER_STIFFNESS`] above those, where a cell beside the edge is thin.
const THIN_STIFFNESS: f64 = 10.0;
/// The layers whose extrusion edges are all held (1: the first layer's).
const LENGTH_LAYERS: u32 = 3;
/// Above those, the width over height of a quadrilateral whose extrusion edges are held.
const THIN_ASPECT: f64 = 10.0;

/// The length springs of the extrusion edges of `layered` (each layer node and its parents):
/// those of the first [`LENGTH_LAYERS`] layers, and above them those of the thin cells (width
/// [`THIN_ASPECT`] times their height or more), weighted by the cells beside them.
///
/// Why: a shape spring holds a cell's shape, not its height. Where a bump stretches the wall
/// (near a leading edge by 15 %), the thin wall cells stayed similar and their height grew
/// with their width: a first-layer height drift of 17 % with 8 bumps of 1 % chord on the
/// NACA0012. Holding the extrusion edges keeps the layers' heights, the original layer
/// geometry, as the dissertation's mover does with its extrusion springs. Where the wall
/// shrinks instead, the layers above the third kept their aspect and lost height with the
/// wall's width: the bumps' shortest edges 0.846 of their length (IDW 0.952). Holding the
/// thin cells' heights too (at 10, weaker than the wall's layers, which a scaled body's wall
/// stretches under) makes that 0.943 and changes the other measures of the fourteen motions
/// of `tests/movement` by at most 0.001, but the two-element gap's (lin, sicn and edge 0.004,
/// 0.010, 0.008 lower). Every layer held instead (at 10): the 30P30N flap's lin 0.870 → 0.796;
/// the layers to the twelfth: the NACA0012's pitch by 30° in 5 chords 0.932 → 0.910; thin
/// cells from an aspect of 4: the two-element edge 0.812 → 0.784, of 25: the bumps 0.905.
/// The first layer at 600 halves its height drift on every motion (×1.5: 0.98 % → 0.52 %)
/// with the same measures; at 300 and layers 2 and 3 at 500 the flap's sicn fell 0.880 →
/// 0.856. History of the stiffness at 300: 150 held the bumps' first layer under 1 %, 400
/// stopped the ×1.5 body's convergence before the Newton solve's convex steps.
fn extrusion_springs(
    layered: &LayeredMesh,
    rest: &[[f64; 2]],
    weight: &[f64],
) -> Vec<LengthSpring> {
    let (parents, layer) = (&layered.layering.node_parents, &layered.layering.node_layer);
    let mesh = &layered.mesh;
    // the layer of `child` when it is a layer node extruded from `parent`
    let extruded = |child: u32, parent: u32| {
        let l = layer.get(child as usize).copied().unwrap_or(NONE);
        (l != NONE
            && parents
                .get(child as usize)
                .is_some_and(|p| p.contains(&parent)))
        .then_some(l)
    };
    let length = |a: u32, b: u32| {
        let (p, q) = (rest[a as usize], rest[b as usize]);
        (q[0] - p[0]).hypot(q[1] - p[1])
    };
    // the mesh's unique edges (sorted by their nodes, so the springs come in a fixed order)
    let edges = Edges::build(mesh.cells.shapes_and_corners(), []);
    (0..edges.len() as u32)
        .filter_map(|e| {
            let [a, b] = edges.key(e);
            let child_layer = extruded(a, b).or_else(|| extruded(b, a))?;
            let l = length(a, b);
            // the widest quadrilateral beside the edge: its perimeter less this edge and the
            // one opposite, over twice this edge
            let aspect = || {
                edges
                    .cells(e)
                    .iter()
                    .map(|u| mesh.cells.get(u.cell as usize).corners())
                    .filter(|c| c.len() == 4)
                    .map(|c| {
                        let perimeter: f64 = (0..4).map(|i| length(c[i], c[(i + 1) % 4])).sum();
                        (perimeter - 2.0 * l) / (2.0 * l)
                    })
                    .fold(0.0, f64::max)
            };
            let stiffness = match child_layer {
                1 => FIRST_LAYER_STIFFNESS,
                k if k <= LENGTH_LAYERS => LENGTH_STIFFNESS,
                _ if aspect() >= THIN_ASPECT => THIN_STIFFNESS,
                _ => return None,
            };
            let w: f64 = edges.cells(e).iter().map(|u| weight[u.cell as usize]).sum();
            (l > 0.0).then_some(LengthSpring {
                ends: [a, b],
                rest: l,
                weight: stiffness * w,
            })
        })
        .collect()
}

/// How much a wall corner's angle counts against its cell's shape: its spring's weight over
/// the cell's (why: below).
const CORNER_STIFFNESS: f64 = 100.0;

/// The corner springs of the wall quadrilaterals of `mesh`: at both wall nodes of each, the
/// angle between the wall facet and the extrusion edge held, weighted by the cell.
///
/// Why: where the wall stretches under its layers (a scaled body), the extrusion springs
/// ([`extrusion_springs`]) keep the layers' heights and the shape springs would keep their
/// aspect; the balance settled that disagreement by shearing the first layer where the
/// wall's columns meet a corner's fan: the NACA0012 scaled 1.5× turned the first layer's
/// edges at the blunt trailing edge's corners by 6.6° (the bar is 5°). Holding the angles
/// at the wall moves that shear off the wall.
fn corner_springs(mesh: &Mesh, rest: &[[f64; 2]], weight: &[f64]) -> Vec<CornerSpring> {
    use std::collections::HashMap;
    let mut edge_cell: HashMap<[u32; 2], (usize, usize)> = HashMap::new();
    for (i, cell) in mesh.cells.iter().enumerate() {
        if cell.nodes.len() == 4 {
            for j in 0..4 {
                edge_cell.insert([cell.nodes[j], cell.nodes[(j + 1) % 4]], (i, j));
            }
        }
    }
    let angle = |[a, b, c]: [u32; 3]| {
        let (p, q, r) = (rest[a as usize], rest[b as usize], rest[c as usize]);
        let (u, v) = ([p[0] - q[0], p[1] - q[1]], [r[0] - q[0], r[1] - q[1]]);
        (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1])
    };
    let mut out = Vec::new();
    for f in 0..mesh.boundary.len() {
        if mesh.patches[mesh.boundary_patch[f] as usize].role != Role::Wall {
            continue;
        }
        let k = mesh.boundary.get(f).corners();
        // a wall facet a → b is its cell's edge a → b (the domain on its left)
        let Some(&(cell, j)) = edge_cell.get(&[k[0], k[1]]) else {
            continue;
        };
        let q = mesh.cells.get(cell).nodes;
        // at b: from the facet (b → a) to the edge b → q[j + 2]; at a: from a → q[j + 3] to a → b
        for nodes in [[k[0], k[1], q[(j + 2) % 4]], [q[(j + 3) % 4], k[0], k[1]]] {
            out.push(CornerSpring {
                nodes,
                rest: angle(nodes),
                weight: CORNER_STIFFNESS * weight[cell],
            });
        }
    }
    out
}

/// The balance linearised at a moved mesh: the motion of every node for a motion of the
/// boundary nodes.
pub struct Sensitivity {
    lin: Linearised<2>,
}

impl Sensitivity {
    /// `dX` of every node for the boundary motion `d_boundary` (one entry per node; only the
    /// held nodes' entries are read, and returned as given).
    pub fn respond(&self, d_boundary: &[[f64; 2]]) -> Vec<[f64; 2]> {
        self.lin.respond(d_boundary)
    }
}
