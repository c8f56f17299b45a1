//! AFSF in 2D: the advancing-front spring-field linear viscous mesh of mixed quads and
//! triangles, grown layer by layer from every boundary loop until the fronts close.
//!
//! Entry point: [`grow_mesh`] takes closed loops of boundary nodes ([`FrontLoop`]) and
//! [`AfsfParams`], and returns an [`AfsfOutput`]: a [`mesh_model::LayeredMesh`] — the linear
//! mesh whose boundary facets are the input loop edges and whose cells carry their layer and
//! pipe, with its [`mesh_model::Layering`] (the parents and layer of every node, the pipe
//! columns) — and run statistics. [`cut_quads_shorter_diagonal`] and
//! [`max_angle_histogram`] give triangles and the dissertation's quality figure.
//!
//! It owns the layer growth (`grow`), the closing of the fronts, and the filling of the region
//! left between them (`fill`). It does not place boundary nodes (`boundary1d`), curve
//! anything (`vector-adding`) or read files; the spring models and solver are `springfield`'s.
//! The method and every choice the dissertation left open are in `docs/afsf.md`.
//!
//! # Example
//!
//! A layered mesh around a NACA 0012 section inside a circular far field. The boundary nodes
//! here are simply the section's cosine-spaced points and points on the circle (in the
//! pipeline they come from `boundary1d`); lengths are in chords.
//!
//! ```
//! use afsf2d::{AfsfParams, FrontLoop, grow_mesh};
//! use mesh_model::{Role, Shape};
//!
//! let xy = |p: Vec<geom_curve::Point2<f64>>| p.iter().map(|q| [q.x, q.y]).collect::<Vec<_>>();
//! let section = xy(geom_curve::naca::naca4("0012", 41, true)?);
//! let circle = xy(geom_curve::circle_points([0.5, 0.0].into(), 5.0, 64)?);
//! let mut wall = FrontLoop::new(section, Role::Wall, "naca0012");
//! wall.is_corner[0] = true; // the sharp trailing edge (informational)
//! let loops = [wall, FrontLoop::new(circle, Role::Farfield, "farfield")];
//!
//! let params = AfsfParams {
//!     first_height: 1e-3, // the wall's first layer, chords
//!     growth: 1.3,        // each layer 30 % taller than the one below
//!     max_layers: 20,
//!     ..AfsfParams::default()
//! };
//! let out = grow_mesh(&loops, &params)?;
//! let mesh = &out.layered.mesh;
//! assert_eq!(out.layered.layering.check(mesh), None); // parents one layer below, columns rising
//!
//! assert!(mesh_model::validate(mesh).is_empty()); // conforming, every cell counter-clockwise
//! assert!(mesh.count(Shape::Quad) > 0 && out.stats.layers >= 5);
//! // boundary nodes come first, unmoved; the cells cover the domain exactly
//! assert_eq!(mesh.xy(0), loops[0].points[0]);
//! let domain = mesh_model::polygon_area(loops[1].points.iter().copied())
//!     - mesh_model::polygon_area(loops[0].points.iter().copied());
//! assert!((mesh.linear_area() - domain).abs() < 1e-9 * domain);
//! // quads cut along their shorter diagonal: the dissertation's largest-angle figure
//! let triangles = afsf2d::cut_quads_shorter_diagonal(mesh);
//! assert!(afsf2d::max_angle_histogram(&triangles).max_angle_deg < 150.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod contact;
mod error;
mod fill;
mod gaps;
mod geom;
mod grow;
mod input;
mod nodes;
mod output;
mod quality;
mod sanity;

use mesh_model::{CellType, Dim, LayeredMesh, Layering, Mesh, Patch, Role, Shape};

pub use error::AfsfError;
pub use gaps::NarrowGap;
pub use grow::{LayerStats, Timings};
pub use input::{AfsfParams, FrontLoop};
pub use quality::{
    ANGLE_BINS_DEG, AngleStats, cut_quads_shorter_diagonal, max_angle_histogram,
    max_triangle_angle_deg,
};

use grow::{Law, StartFront, Work};

/// Figures of one run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AfsfStats {
    /// Highest layer index reached by any front.
    pub layers: u32,
    /// One entry per layer step.
    pub layer_stats: Vec<LayerStats>,
    /// Spring-solver iterations, all steps together.
    pub iterations: usize,
    /// True when every step's accepted spring solve converged.
    pub all_converged: bool,
    /// Triangles made by the hole filling.
    pub fill_triangles: usize,
    /// Layered cells peeled back into the filled region to give its triangles room.
    pub peeled_cells: usize,
    /// Timings of the phases (seconds).
    pub timings: Timings,
    /// Wall facets with no layered cell on them (their first layer did not fit: a gap
    /// narrower than the layers, or a tight concave corner, where the fill meets the wall
    /// directly).
    pub bare_wall_facets: usize,
    /// The midpoints of those facets, for messages that say where.
    pub bare_wall_facets_at: Vec<[f64; 2]>,
    /// The narrowest gap whose boundary nodes admit no triangle across it below
    /// `gap_max_angle_deg` (only when `refuse_narrow_gaps` is off; else it is an error).
    pub unresolved_gap: Option<NarrowGap>,
}

/// The mesher's result.
#[derive(Debug, Clone, PartialEq)]
pub struct AfsfOutput {
    /// The linear mesh (quads and triangles) and its layers. Boundary nodes come first, loop
    /// after loop in input order and at their input coordinates; facet `k` of a loop joins
    /// its points `k` and `k + 1`, oriented with the domain on the left; one patch per loop.
    /// Cells `0..layered_cells` are layered cells (quadrilaterals and the triangles of fans
    /// and merges, each above its bottom edge in a pipe); the rest are the filled region's
    /// triangles, whose `cell_layer` and `cell_pipe` are borrowed from a neighbour. Fill nodes
    /// have no layer and no parent.
    pub layered: LayeredMesh,
    /// Run figures.
    pub stats: AfsfStats,
}

/// Grows the layered mesh from every loop at once and fills the region where the fronts
/// meet, so that the cells cover the domain exactly.
pub fn grow_mesh(loops: &[FrontLoop], params: &AfsfParams) -> Result<AfsfOutput, AfsfError> {
    grow_mesh_with(loops, params, |_, _| ()).map(|(out, _)| out)
}

/// What the task given to [`grow_mesh_with`] made, and which of the cells it was given the
/// mesh left out.
#[derive(Debug, Clone, PartialEq)]
pub struct MadeBeside<R> {
    /// What the task returned.
    pub made: R,
    /// The positions, among the cells the task was given, of those the fill peeled back
    /// (increasing): the mesh's cells are the others, in their order, then the fill's
    /// triangles.
    pub left_out: Vec<u32>,
}

/// [`grow_mesh`], with `beside` run on the layered cells and their node count (the mesh's
/// numbers, its first nodes) as the layer growth leaves them, while the region between the
/// fronts is filled (on another thread of the pool when there is one): work on the layered
/// part that need not wait for the fill. The fill may peel a few of those cells back; the
/// result tells which.
pub fn grow_mesh_with<R: Send>(
    loops: &[FrontLoop],
    params: &AfsfParams,
    beside: impl FnOnce(&mesh_model::Cells, usize) -> R + Send,
) -> Result<(AfsfOutput, MadeBeside<R>), AfsfError> {
    let t0 = std::time::Instant::now();
    params.check()?;
    let checked = input::check_loops(loops, params)?;
    let unresolved_gap = narrow_gap(loops, &checked, params)?;
    let (mut mesh, points, fronts) = boundary_and_fronts(loops, &checked, params);
    let mut work = Work::new(params, points, fronts);
    work.grow()?;
    let tf = std::time::Instant::now();
    let n_grown = work.nodes.pos.len();
    let facets: Vec<(u32, u32)> = mesh
        .boundary
        .iter()
        .map(|f| (f.nodes[0], f.nodes[1]))
        .collect();
    let fronts = work.front_edges();
    // the layered part of the mesh is made beside the fill (the fill only peels a few of its
    // cells, taken out again after it)
    let (grown_nodes, n_boundary) = (&work.nodes, work.n_boundary);
    let ((fill, steiner, peeled), (part, made)) = fill::fill_with_peeling(
        &mut work.cells,
        &facets,
        &fronts,
        &grown_nodes.pos,
        fill::FillAngles {
            min_angle_deg: params.fill_min_angle_deg,
            peel_max_angle_deg: params.peel_max_angle_deg,
            rounds: params.peel_rounds,
        },
        |cells| {
            let part = output::LayeredPart::new(cells, grown_nodes, n_boundary);
            let made = beside(part.cells(), part.node_count());
            (part, made)
        },
    )?;
    for p in steiner {
        work.nodes.push_node(nodes::NewNode::unlayered(p));
    }
    work.timings.fill = tf.elapsed().as_secs_f64();

    let (node_parents, node_layer, layered_cells, left_out) =
        output::output_cells(&mut mesh, part, (&work.cells, &work.nodes), &fill, &peeled);
    let mut layered_on_facet = vec![false; mesh.boundary.len()];
    for c in &work.cells {
        if c.len > 0 && c.layer == 0 && (c.pipe as usize) < layered_on_facet.len() {
            layered_on_facet[c.pipe as usize] = true;
        }
    }
    let bare: Vec<usize> = (0..mesh.boundary.len())
        .filter(|&f| {
            !layered_on_facet[f] && mesh.patches[mesh.boundary_patch[f] as usize].role == Role::Wall
        })
        .collect();
    let bare_wall_facets_at = bare
        .iter()
        .map(|&f| {
            let n = mesh.boundary.get(f).nodes;
            let (a, b) = (mesh.xy(n[0]), mesh.xy(n[1]));
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
        })
        .collect();
    let stats = AfsfStats {
        bare_wall_facets: bare.len(),
        bare_wall_facets_at,
        unresolved_gap,
        layers: work.nodes.layer[..n_grown]
            .iter()
            .copied()
            .max()
            .unwrap_or(0),
        iterations: work.layer_stats.iter().map(|s| s.iterations).sum(),
        all_converged: work.layer_stats.iter().all(|s| s.converged),
        layer_stats: std::mem::take(&mut work.layer_stats),
        fill_triangles: fill.len(),
        peeled_cells: peeled.len(),
        timings: Timings {
            total: t0.elapsed().as_secs_f64(),
            ..work.timings
        },
    };
    work.let_go();
    let layering = Layering::new(&mesh, node_layer, node_parents, layered_cells);
    let out = AfsfOutput {
        layered: LayeredMesh { mesh, layering },
        stats,
    };
    Ok((out, MadeBeside { made, left_out }))
}

/// A filled loop: its nodes and its triangles ([`fill_loop`]).
pub type FilledLoop = (Vec<[f64; 2]>, Vec<[u32; 3]>);

/// The inside of one closed loop of `points` (counter-clockwise, no two alike) filled with
/// triangles by the mesher's fill, without layers: the constrained Delaunay triangulation of
/// the loop's nodes refined toward `min_angle_deg` (the loop's edges never split), then
/// improved by largest-angle flips and smoothing, as the region between the fronts is. The
/// nodes are the loop's, first and at their coordinates, then the added ones; the triangles
/// are counter-clockwise. An isotropic mesh graded by the loop's own spacing (the wing's tip
/// caps).
pub fn fill_loop(points: &[[f64; 2]], min_angle_deg: f64) -> Result<FilledLoop, AfsfError> {
    let n = points.len() as u32;
    if n < 3 {
        return Err(AfsfError::Fill(format!(
            "a loop of {n} points has no inside"
        )));
    }
    let edges: Vec<(u32, u32)> = (0..n).map(|i| (i, (i + 1) % n)).collect();
    let (tris, added) = fill::fill_region(&edges, &[], points, min_angle_deg)?;
    Ok(([points, &added[..]].concat(), tris))
}

/// The narrowest gap that admits no good triangle across it: an error when the parameters
/// refuse narrow gaps, else reported in the statistics.
fn narrow_gap(
    loops: &[FrontLoop],
    checked: &[input::CheckedLoop],
    params: &AfsfParams,
) -> Result<Option<NarrowGap>, AfsfError> {
    let oriented: Vec<Vec<[f64; 2]>> = loops
        .iter()
        .zip(checked)
        .map(|(l, c)| {
            let mut p = l.points.clone();
            if c.reversed {
                p.reverse();
            }
            p
        })
        .collect();
    let unresolved_gap = gaps::unresolved_gap(&oriented, params.gap_max_angle_deg);
    if let (Some(g), true) = (unresolved_gap, params.refuse_narrow_gaps) {
        return Err(AfsfError::NarrowGap {
            loop_a: g.loop_a,
            name_a: loops[g.loop_a].name.clone(),
            loop_b: g.loop_b,
            name_b: loops[g.loop_b].name.clone(),
            width: g.width,
            x: g.at[0],
            y: g.at[1],
            spacing: g.spacing,
            angle: g.best_angle_deg,
            fits_spacing: 2.0 * g.width,
            fits_height: 0.25 * g.width,
        });
    }
    Ok(unresolved_gap)
}

/// The boundary of the mesh (one facet per loop edge, one patch per loop), the boundary
/// nodes, and the starting fronts with the domain on their left and their growth law.
fn boundary_and_fronts(
    loops: &[FrontLoop],
    checked: &[input::CheckedLoop],
    params: &AfsfParams,
) -> (Mesh, Vec<[f64; 2]>, Vec<StartFront>) {
    let mut points = Vec::new();
    let mut fronts = Vec::new();
    let mut mesh = Mesh::new(Dim::Two, 1);
    let line = CellType::new(Shape::Line, 1);
    for (li, (l, c)) in loops.iter().zip(checked).enumerate() {
        let off = points.len() as u32;
        let facet_off = mesh.boundary.len() as u32;
        let n = l.points.len() as u32;
        points.extend_from_slice(&l.points);
        for k in 0..n {
            let (a, b) = (off + k, off + (k + 1) % n);
            mesh.boundary
                .push(line, &if c.reversed { [b, a] } else { [a, b] });
            mesh.boundary_patch.push(li as u32);
        }
        mesh.patches.push(Patch {
            name: l.name.clone(),
            role: l.role,
        });
        let (items, pipes): (Vec<u32>, Vec<u32>) = if c.reversed {
            (0..n)
                .map(|i| (off + (n - i) % n, facet_off + (2 * n - i - 1) % n))
                .unzip()
        } else {
            (0..n).map(|i| (off + i, facet_off + i)).unzip()
        };
        let law = match l.role {
            Role::Wall => Law::Geometric {
                first: params.first_height,
                growth: params.growth,
            },
            Role::Farfield => Law::Isotropic {
                factor: params.farfield_height,
            },
        };
        fronts.push((items, pipes, law));
    }
    (mesh, points, fronts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loop_is_filled_with_its_nodes_first_and_its_area_kept() {
        // an ellipse 1 × 0.1 with 64 nodes: thin, as a wing section
        let points: Vec<[f64; 2]> = (0..64)
            .map(|i| {
                let t = i as f64 / 64.0 * std::f64::consts::TAU;
                [t.cos(), 0.1 * t.sin()]
            })
            .collect();
        let (nodes, tris) = fill_loop(&points, 20.0).unwrap();
        assert_eq!(&nodes[..64], &points[..]);
        let area2 = |[a, b, c]: [u32; 3]| {
            let (a, b, c) = (nodes[a as usize], nodes[b as usize], nodes[c as usize]);
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        };
        assert!(tris.iter().all(|&t| area2(t) > 0.0));
        let polygon: f64 = (0..64)
            .map(|i| {
                let (a, b) = (points[i], points[(i + 1) % 64]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum();
        let filled: f64 = tris.iter().map(|&t| area2(t)).sum();
        assert!((filled - polygon).abs() < 1e-12, "{filled} vs {polygon}");
        assert!(fill_loop(&points[..2], 20.0).is_err());
    }
}
