//! How many cells a case will make, told before the expensive stages run (`--max-cells`):
//! a lower bound from the loops' lengths before the boundary mesh is made, then an estimate
//! from the boundary nodes before the domain is meshed. A legal but huge request (a tiny
//! `max_spacing`, a boundary growth of 1.0001, a far field of 1e5 chords) is refused with one
//! line naming the estimate and the keys to change, or told to the observer when large (the CLI prints it on a terminal).

use crate::error::{Result, bail};
use boundary1d::BoundaryNodes;
use mesh_model::Role;

use crate::case::Case;
use crate::observer::Observer;

/// The default of `--max-cells`.
pub const DEFAULT_MAX_CELLS: u64 = 20_000_000;

/// From this many expected cells on, the estimate is told to the observer (as a note).
const ANNOUNCE_CELLS: u64 = 2_000_000;

/// From this many boundary nodes (a lower bound) on, a note is told to the observer.
const ANNOUNCE_NODES: f64 = 200_000.0;

/// Fill triangles per boundary node (the graded region left between the fronts), measured on
/// the built-in cases.
const FILL_PER_NODE: f64 = 8.0;

/// Cells of the isotropic far-field layers per far-field node.
const FARFIELD_PER_NODE: f64 = 4.0;

/// Refuses a case whose boundary mesh alone would hold more than `max_cells` nodes: every
/// segment of a loop is at most its `max_spacing` long, so a loop has at least its length
/// over that many segments, each under one cell or more. Checked before the boundary mesh is
/// made (which would allocate them).
pub fn check_loops(case: &Case, max_cells: u64, observer: &mut dyn Observer) -> Result<()> {
    let mut nodes = 0.0;
    for l in &case.loops {
        let cap = l.max_spacing.unwrap_or(case.boundary.max_spacing);
        let n = l.points.len();
        let length: f64 = (0..n)
            .map(|i| {
                let (a, b) = (l.points[i], l.points[(i + 1) % n]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            })
            .sum();
        nodes += length / cap;
    }
    if nodes > max_cells as f64 {
        bail!(
            "the boundary alone needs at least {} nodes (loop lengths over max_spacing), so more \
             cells than the limit {max_cells}: raise [boundary] max_spacing (or a loop's \
             max_spacing), or --max-cells",
            readable(nodes)
        );
    }
    if nodes >= ANNOUNCE_NODES {
        observer.note(&format!(
            "at least {} boundary nodes: the boundary mesh alone may take a while",
            readable(nodes)
        ));
    }
    Ok(())
}

/// The cells expected from the boundary nodes: on wall loops, one column of layered cells per
/// segment, as many layers as it takes their total height (from `first_height`, growing by
/// `[layers] growth`) to fill the room in front of the wall (`room`), at most `max_layers`
/// (half as many columns on average inside a loop, where the front shrinks); on far-field loops a few
/// isotropic layers; and the fill, a few triangles per boundary node. Within a factor of two
/// of the cells made on the built-in cases.
pub fn cells(case: &Case, nodes: &[BoundaryNodes]) -> u64 {
    let (h0, g) = (case.layers.first_height, case.layers.growth);
    let room = room(case);
    let layers = (1.0 + room * (g - 1.0) / h0).ln() / g.ln();
    let layers = layers.clamp(1.0, f64::from(case.layers.max_layers));
    let mut cells = 0.0;
    for (input, bn) in case.loops.iter().zip(nodes) {
        let n = bn.points.len() as f64;
        cells += FILL_PER_NODE * n;
        cells += if input.role == Role::Wall && case.layers.inside {
            // the front shrinks toward the medial axis: half the columns survive on average
            0.5 * layers * n
        } else if input.role == Role::Wall {
            layers * n
        } else {
            FARFIELD_PER_NODE * n
        };
    }
    cells as u64
}

/// The distance layers may grow over: the diagonal of the bounding box of every loop; for
/// `inside = true`, twice the loop's area over its length (a circle's radius).
fn room(case: &Case) -> f64 {
    if case.layers.inside {
        let p = &case.loops[0].points;
        let n = p.len();
        let (mut area2, mut length) = (0.0, 0.0);
        for i in 0..n {
            let (a, b) = (p[i], p[(i + 1) % n]);
            area2 += (a[0] - p[0][0]) * (b[1] - p[0][1]) - (b[0] - p[0][0]) * (a[1] - p[0][1]);
            length += (b[0] - a[0]).hypot(b[1] - a[1]);
        }
        return area2.abs() / length;
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in case.loops.iter().flat_map(|l| &l.points) {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

/// Refuses an estimate above `max_cells`, and tells `observer` of a large one.
pub fn check_cells(
    estimate: u64,
    boundary_nodes: usize,
    max_cells: u64,
    observer: &mut dyn Observer,
) -> Result<()> {
    if estimate > max_cells {
        bail!(
            "about {} cells expected ({boundary_nodes} boundary nodes), more than the limit \
             {max_cells}: raise [boundary] max_spacing or growth, or [layers] first_height, or \
             give --max-cells {}",
            readable(estimate as f64),
            estimate.saturating_mul(2)
        );
    }
    if estimate >= ANNOUNCE_CELLS {
        observer.note(&format!(
            "about {} cells expected ({boundary_nodes} boundary nodes): this may take a while",
            readable(estimate as f64)
        ));
    }
    Ok(())
}

/// A count for people: `23 million`, `4.1e12`.
fn readable(n: f64) -> String {
    if n < 1e6 {
        format!("{n:.0}")
    } else if n < 1e10 {
        format!("{:.1} million", n / 1e6)
    } else {
        format!("{n:.1e}")
    }
}
