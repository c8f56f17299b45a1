//! Curving by Vector-Adding (the dissertation's §2.2 and §3.3; method.md §4): turns the
//! layered linear mesh that `afsf2d` grows into a P2 or P3 mesh for high-order solvers.
//!
//! The boundary edges get their high-order nodes on the C2 curves (equally spaced in arc
//! length). Then, up each pipe of cells above a curved boundary edge, the top edge of every
//! cell receives the deviation of its bottom edge from its chord — the same as adding to each
//! high-order node the blend `(1 − s)·V_left + s·V_right` of the cell's two extrusion vectors —
//! until the pipe stops: its two children merged (the last cell is a triangle), it met
//! something that is not the next cell of the pipe, or the cell is certified valid with a
//! straight top, once `min_curved_layers` are curved. Extrusion edges stay straight, and so
//! does every edge the marching did not reach, except where a cell left invalid (a triangle
//! of the filled region on a curved boundary edge, say) is mended by bending its straight
//! edges the same way. Each decision is taken with the certified
//! Jacobian check of `jacobian-check`; a top that would make its cell invalid gets a part of
//! the deviation, or none. Interior nodes follow from the map the edges define. On request
//! quadrilaterals are cut into triangles with a straight diagonal where both halves stay
//! valid.
//!
//! Every decision is recorded ([`Decisions`], in [`Curved::decisions`]). With them fixed the
//! curving is a linear map of the linear nodes and the boundary's high-order nodes, so a
//! moved mesh of the same topology is curved the same way by [`curve_mesh_keeping`] (which
//! certifies every cell and decides afresh only for the pipes of cells that fail, listing
//! each [`DecisionChange`]), replayed by [`replay`], and differentiated by [`tangent`].
//!
//! In 3D ([`curve3d`], [`curve_mesh_3d`]) the linear mesh `topo-cut` makes of `afsf3d`'s
//! layers is curved to P2 or P3 the same way (dissertation §5.3): the wall's high-order
//! nodes on the true surface through a [`SurfaceProjector`], their displacements added up the
//! columns edge by edge (and face by face at P3), with the 2D stops, every decision certified
//! (tetrahedra, prisms, hexahedra and pyramids).
//!
//! The mesh's edge table may be given half-made ([`PartEdges`]: the table of its layered
//! cells, made while its fill was) to [`curve_mesh_owned_with`], which finishes it into the
//! table it would have built.
//!
//! It owns the placement of high-order nodes. It does not grow the linear mesh, does no file
//! IO, and does not certify the final mesh as a whole (the caller runs
//! `jacobian_check::check_mesh` on the result).
//!
//! # Example
//!
//! A NACA 0012 section and a far-field circle as C2 curves (`geom-curve`), their boundary
//! nodes (`boundary1d`), a layered linear mesh (`afsf2d`), then curved to P3 here, and every
//! cell of the result certified valid:
//!
//! ```
//! use afsf2d::{AfsfParams, FrontLoop};
//! use boundary1d::SpacingParams;
//! use geom_curve::{ClosedCurve, CurveParams, naca};
//! use mesh_model::Role;
//! use vector_adding::{CurvingParams, LoopCurve, curve_mesh};
//!
//! let fit = |p: &[geom_curve::Point2<f64>]| ClosedCurve::new(p, &CurveParams::default());
//! let curves = [
//!     fit(&naca::naca4("0012", 61, true)?)?, // counter-clockwise, as ClosedCurve wants
//!     fit(&geom_curve::circle_points([0.5, 0.0].into(), 5.0, 64)?)?,
//! ];
//! let spacing = SpacingParams { first_height: 1e-3, max_spacing: 0.8, ..Default::default() };
//! let nodes = boundary1d::mesh_loops(&curves, &spacing)?;
//! let loops: Vec<FrontLoop> = nodes
//!     .iter()
//!     .zip([Role::Wall, Role::Farfield])
//!     .map(|(n, role)| FrontLoop {
//!         points: n.points.iter().map(|p| [p.x, p.y]).collect(),
//!         is_corner: n.is_corner.clone(),
//!         role,
//!         name: format!("{role:?}"),
//!     })
//!     .collect();
//! let afsf = AfsfParams { first_height: 1e-3, max_layers: 20, ..Default::default() };
//! let linear = afsf2d::grow_mesh(&loops, &afsf)?;
//!
//! // patch l of the linear mesh is loop l: its nodes sit on curves[l] at parameters t
//! let on_curves: Vec<LoopCurve> = curves
//!     .iter()
//!     .zip(&nodes)
//!     .map(|(curve, n)| LoopCurve { curve, t: &n.t })
//!     .collect();
//! let p3 = curve_mesh(&linear.layered, &on_curves, &CurvingParams { order: 3, ..Default::default() })?;
//!
//! assert_eq!(p3.mesh.order, 3);
//! assert_eq!(p3.mesh.cells.len(), linear.layered.mesh.cells.len()); // same cells, same linear nodes
//! assert!(p3.stats.curved_edges > 0 && p3.stats.curved_edge_fraction < 0.5);
//! let validity = jacobian_check::check_mesh(&p3.mesh, &Default::default())?;
//! assert!(validity.invalid_cells.is_empty() && validity.undecided.is_empty());
//! assert!(validity.min_scaled_jacobian > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod assemble;
mod boundary;
mod cellcheck;
mod cellmap;
pub mod curve3d;
mod decisions;
mod edges;
pub mod error;
mod keep;
mod loop_curve;
mod march;
mod march3d;
pub mod params;
mod part;
mod projector;
mod quality;
mod repair;
mod roles;
mod scratch;
mod split;
pub mod stats;
mod table;

use mesh_model::{Dim, LayeredMesh, Mesh, Shape};

pub use curve3d::{Curved3d, Curving3dStats, SphereProjector, SurfaceProjector, curve_mesh_3d};
pub use decisions::{Carry, DecisionChange, Decisions, Diagonal, EdgeRule, EdgeRules};
pub use error::CurvingError;
pub use keep::{boundary_points, curve_mesh_keeping, replay, tangent};
pub use loop_curve::LoopCurve;
pub use params::{CurvingParams, Strategy};
pub use part::PartEdges;
pub use stats::{CurvingStats, StopCounts};

/// The curved mesh and the figures of the run.
#[derive(Debug, Clone)]
pub struct Curved {
    /// The mesh of order `params.order`.
    pub mesh: Mesh,
    /// What was done.
    pub stats: CurvingStats,
    /// Every decision taken, to curve a moved mesh the same way
    /// ([`curve_mesh_keeping`]) or differentiate the curving ([`tangent`]).
    pub decisions: Decisions,
}

/// Curves `input` to order `params.order`. `loops[l]` is the curve of patch `l`.
///
/// # Errors
/// Bad parameters, a mesh that is not linear 2D or lacks layer data, boundary facets that do
/// not match the curves, a cell the certified check cannot evaluate.
pub fn curve_mesh(
    input: &LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
) -> Result<Curved, CurvingError> {
    let decided = decide(input, loops, params)?;
    Ok(build(decided, &input.mesh, params, None))
}

/// [`curve_mesh`] on a linear mesh it is given to keep: the same curved mesh and record to the
/// last bit, with less memory at the run's peak, the assembly of the curved mesh. Before it
/// the linear mesh's nodes (the assembly reads its copy in the curved mesh's node array), its
/// cells (it reads them from the edge table) and its layers are let go, and, when the
/// quadrilaterals are not cut, its per-cell records (layer, pipe) move into the curved mesh
/// rather than being copied.
///
/// # Errors
/// As [`curve_mesh`].
pub fn curve_mesh_owned(
    input: LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
) -> Result<Curved, CurvingError> {
    curve_mesh_owned_with(input, loops, params, None, |_| ()).map(|(curved, ())| curved)
}

/// The edge table of a linear mesh's first cells made before the mesh was finished
/// ([`PartEdges`]), with the positions among those cells of the ones the mesh left out
/// (increasing; the mesh's cells are the others in their order, then the rest).
pub type MadeAhead<'a> = (PartEdges, &'a [u32]);

/// [`curve_mesh_owned`], with `beside` run on the linear mesh while the curving takes its
/// decisions after the edge table (on another thread of the pool when there is one): what a
/// caller wants of the linear mesh before it is let go, off the critical path. The edge table
/// is built first on every thread — or finished from `ahead`, the table of the mesh's first
/// cells made while the rest were (the same table; one that samples show to be of other
/// cells is set aside and the table built) —; the boundary, the marching and the
/// repair, which are mostly one thread's work, then run beside `beside`. Returns the curved
/// mesh and what `beside` gave; `beside` is not run when the input or the parameters are
/// refused.
///
/// # Errors
/// As [`curve_mesh`].
pub fn curve_mesh_owned_with<R: Send>(
    input: LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
    ahead: Option<MadeAhead<'_>>,
    beside: impl FnOnce(&Mesh) -> R + Send,
) -> Result<(Curved, R), CurvingError> {
    let mut input = input;
    params.check()?;
    check_input(&input)?;
    // the curving reads of the layers only the node layers and the layered cells' count: the
    // rest goes before the edge table is built (which can then take its memory)
    let layering = &mut input.layering;
    layering.node_parents = Vec::new();
    layering.pipe_start = Vec::new();
    layering.pipe_cells = Vec::new();
    let table = EdgeTableStage::new(&input.mesh, params, ahead);
    let (aside, decided) = rayon::join(
        || beside(&input.mesh),
        || decide_from(&input, loops, params, table),
    );
    let decided = decided?;
    let LayeredMesh { mut mesh, layering } = input;
    drop(layering);
    mesh.nodes = Vec::new();
    mesh.cells = mesh_model::Cells::new();
    // kept cells are the linear ones in their order: their records are the linear mesh's
    let records = (!params.triangles).then(|| {
        (
            std::mem::take(&mut mesh.cell_layer),
            std::mem::take(&mut mesh.cell_pipe),
        )
    });
    Ok((build(decided, &mesh, params, records), aside))
}

/// What the curving decided, before the curved mesh is assembled.
struct Decided {
    /// The edges with their points and rules.
    edges: edges::EdgeTable,
    /// How many leading edges of the table are the linear mesh's own.
    sorted_edges: usize,
    /// The cells of a cut, when cutting.
    cells: Option<Vec<split::OutCell>>,
    /// The diagonals of a cut (empty when not cutting).
    diagonals: Vec<Option<Diagonal>>,
    /// The interior-node maps.
    interiors: cellmap::Interiors,
    /// The figures so far (the assembly adds its lap).
    stats: CurvingStats,
    clock: Clock,
}

/// Every decision of the curving of `input`: the edge table after the boundary, the marching,
/// the repair and the cut.
fn decide(
    input: &LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
) -> Result<Decided, CurvingError> {
    params.check()?;
    check_input(input)?;
    decide_checked(input, loops, params)
}

/// [`decide`] on an input and parameters already checked.
fn decide_checked(
    input: &LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
) -> Result<Decided, CurvingError> {
    decide_from(
        input,
        loops,
        params,
        EdgeTableStage::new(&input.mesh, params, None),
    )
}

/// The curving's first stage: the edge table of the linear mesh with room for the nodes the
/// cut and the assembly add, and the interior-node maps.
struct EdgeTableStage {
    edges: edges::EdgeTable,
    interiors: cellmap::Interiors,
    clock: Clock,
}

impl EdgeTableStage {
    /// The stage of `mesh`, its topology finished from `ahead` when it is given and can be.
    fn new(mesh: &Mesh, params: &CurvingParams, ahead: Option<MadeAhead<'_>>) -> Self {
        let p = params.order as usize;
        let mut clock = Clock::default();
        let interiors = cellmap::Interiors::new(p);
        let room = assembly_room(mesh, &interiors, params);
        let topology = ahead.and_then(|(part, removed)| {
            let cells = &mesh.cells;
            part::finish(part, part::Changes { removed, cells })
        });
        let edges = edges::EdgeTable::with_room(mesh, p, room, topology);
        clock.lap("edges");
        EdgeTableStage {
            edges,
            interiors,
            clock,
        }
    }
}

/// The decisions of [`decide`] after its edge table (`table`, of `input`'s mesh).
fn decide_from(
    input: &LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
    table: EdgeTableStage,
) -> Result<Decided, CurvingError> {
    let mesh = &input.mesh;
    let EdgeTableStage {
        mut edges,
        interiors,
        mut clock,
    } = table;
    let sorted_edges = edges.len();
    boundary::place_on_curves(mesh, loops, &mut edges)?;
    let curved_boundary_edges = edges.curved.iter().filter(|&&c| c).count();
    clock.lap("boundary");
    let roles = roles::classify(
        mesh,
        &input.layering.node_layer,
        input.layering.layered_cells,
    );
    let marched = march::march(
        mesh,
        &roles,
        &mut edges,
        &interiors,
        params,
        input.layering.layered_cells,
    )?;
    clock.lap("march");
    let repaired = repair::repair(
        mesh,
        &roles,
        &mut edges,
        &interiors,
        params,
        &marched.certified,
    )?;
    clock.lap("repair");
    let (cells, cut) = if params.triangles {
        let (cells, cut) = split::cut(mesh, &roles, &mut edges, &interiors, params, None)?;
        (Some(cells), cut)
    } else {
        (None, split::CutOutcome::default())
    };
    clock.lap("cut");
    let curved_edges = edges.curved.iter().filter(|&&c| c).count();
    let stats = CurvingStats {
        edges: edges.len(),
        curved_edges,
        curved_edge_fraction: stats::share(curved_edges, edges.len()),
        curved_boundary_edges,
        stops: marched.stops,
        reduced_tops: marched.reduced_tops,
        handed_to_fill: marched.handed_to_fill,
        deepest_curved_layer: marched.deepest_curved_layer,
        repaired_cells: repaired.repaired,
        unrepaired_cells: repaired.unrepaired,
        curved_diagonals: cut.curved_diagonals,
        invalid_after_cut: cut.invalid,
        timings_s: Vec::new(),
    };
    Ok(Decided {
        edges,
        sorted_edges,
        cells,
        diagonals: cut.diagonals,
        interiors,
        stats,
        clock,
    })
}

/// The nodes the cut and the assembly add to the edge table's node array: each cell's
/// interior nodes, and when cutting, each quadrilateral's diagonal and its two triangles'
/// interior nodes instead of its own.
fn assembly_room(mesh: &Mesh, interiors: &cellmap::Interiors, params: &CurvingParams) -> usize {
    let p = params.order as usize;
    let quad = if params.triangles {
        (p - 1) + 2 * interiors.count(3, p)
    } else {
        interiors.count(4, p)
    };
    mesh.cells
        .shapes_and_corners()
        .map(|(_, corners)| {
            if corners.len() == 4 {
                quad
            } else {
                interiors.count(corners.len(), p)
            }
        })
        .sum()
}

/// The curved mesh of `decided` over the linear mesh `linear` (its nodes and cells are not
/// read: the edge table holds them), with its record. `records`: the linear mesh's per-cell layers and
/// pipes, taken out of it, for the curved mesh (its cells being the linear ones in order).
fn build(
    decided: Decided,
    linear: &Mesh,
    params: &CurvingParams,
    records: Option<(Vec<u32>, Vec<u32>)>,
) -> Curved {
    let Decided {
        mut edges,
        sorted_edges,
        cells,
        diagonals,
        interiors,
        mut stats,
        mut clock,
    } = decided;
    // what the assembly does not read is let go before it (the peak of the run is there):
    // the rules move into the record, the node array (with the edges' points) to the mesh
    let mut rules = std::mem::take(&mut edges.rules);
    rules.truncate(sorted_edges);
    let nodes = std::mem::take(&mut edges.nodes);
    edges.cells = Vec::new();
    edges.curved = Vec::new();
    let mut out = match cells {
        Some(cells) => assemble::assemble(
            linear,
            &edges,
            nodes,
            sorted_edges,
            (cells.len(), |i| cells[i]),
            &interiors,
        ),
        None => {
            let (cell_edges, ends) = (&edges.cell_edges, &edges.ends);
            let kept = |i| split::keep_at(cell_edges, ends, i);
            let count = cell_edges.len();
            assemble::assemble(
                linear,
                &edges,
                nodes,
                sorted_edges,
                (count, kept),
                &interiors,
            )
        }
    };
    if let Some((cell_layer, cell_pipe)) = records {
        (out.cell_layer, out.cell_pipe) = (cell_layer, cell_pipe);
    }
    clock.lap("assemble");
    stats.timings_s = clock.laps;
    let decisions = Decisions {
        order: params.order,
        triangles: params.triangles,
        strategy: params.strategy,
        edges: take_sorted(&mut edges.ends, sorted_edges),
        rules,
        diagonals: if params.triangles {
            diagonals
        } else {
            vec![None; edges.cell_edges.len()]
        },
    };
    Curved {
        mesh: out,
        stats,
        decisions,
    }
}

/// The first `sorted` entries of `v` (the linear mesh's own edges), moved out of it.
fn take_sorted<T>(v: &mut Vec<T>, sorted: usize) -> Vec<T> {
    let mut head = std::mem::take(v);
    head.truncate(sorted);
    head
}

/// The mesh is structurally sound (`mesh_model`'s checks), linear 2D, with a layering that
/// passes its checks. The two checks run side by side (the layering's reads only the lengths
/// it checks first, and no cell's nodes, so it is safe on any mesh); a fault of the mesh is
/// told before one of the layering.
fn check_input(input: &LayeredMesh) -> Result<(), CurvingError> {
    let mesh = &input.mesh;
    let (sound, layers) = rayon::join(
        || {
            sound_linear(
                mesh,
                Dim::Two,
                &[Shape::Tri, Shape::Quad],
                CurvingError::NotLinear2d,
            )
        },
        || input.layering.check(mesh),
    );
    sound?;
    match layers {
        Some(problem) => Err(CurvingError::BadLayers(problem)),
        None => Ok(()),
    }
}

/// The mesh is structurally sound (`mesh_model`'s checks) and linear, of dimension `dim`,
/// with cells of `shapes` only; `wrong` makes the error that says what else it is.
fn sound_linear(
    mesh: &Mesh,
    dim: Dim,
    shapes: &[Shape],
    wrong: fn(String) -> CurvingError,
) -> Result<(), CurvingError> {
    if let Some(problem) = mesh_model::first_structural_problem(mesh) {
        return Err(CurvingError::InvalidMesh(problem));
    }
    if mesh.dim != dim || mesh.order != 1 {
        return Err(wrong(format!(
            "the mesh is {}D of order {}",
            if mesh.dim == Dim::Two { 2 } else { 3 },
            mesh.order
        )));
    }
    if let Some(ty) = mesh
        .cells
        .types()
        .iter()
        .find(|t| t.order != 1 || !shapes.contains(&t.shape))
    {
        return Err(wrong(format!("it has a {ty:?} cell")));
    }
    Ok(())
}

/// Wall-clock seconds of each phase, in order.
#[derive(Debug)]
struct Clock {
    last: std::time::Instant,
    laps: Vec<(&'static str, f64)>,
}

impl Default for Clock {
    fn default() -> Self {
        Clock {
            last: std::time::Instant::now(),
            laps: Vec::new(),
        }
    }
}

impl Clock {
    fn lap(&mut self, phase: &'static str) {
        let now = std::time::Instant::now();
        self.laps
            .push((phase, now.duration_since(self.last).as_secs_f64()));
        self.last = now;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The edge table's node array is reserved at the curved mesh's final node count, for
    /// every order and with or without the cut: the assembly never moves it to grow it.
    #[test]
    fn the_node_array_is_reserved_at_its_final_size() {
        let g = test_cases::grow(&test_cases::real_case("naca0012"));
        let loops: Vec<LoopCurve<'_>> = g
            .curves
            .iter()
            .zip(&g.nodes)
            .map(|(curve, bn)| LoopCurve { curve, t: &bn.t })
            .collect();
        for (order, triangles) in [(2, false), (3, false), (2, true), (3, true)] {
            let params = CurvingParams {
                order,
                triangles,
                ..CurvingParams::default()
            };
            let decided = decide(&g.output.layered, &loops, &params).unwrap();
            let (reserved, at) = (decided.edges.nodes.capacity(), decided.edges.nodes.as_ptr());
            let curved = build(decided, &g.output.layered.mesh, &params, None);
            let nodes = &curved.mesh.nodes;
            assert_eq!(reserved, nodes.len(), "P{order}, cut {triangles}");
            assert_eq!(
                at,
                nodes.as_ptr(),
                "P{order}, cut {triangles}: the array moved"
            );
        }
    }
}
