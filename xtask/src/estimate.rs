//! How many cells a case will make, told before the expensive stages run (`--max-cells`):
//! a lower bound from the loops' lengths before the boundary mesh is made, then an estimate
//! from the boundary nodes before the domain is meshed. A legal but huge request (a tiny
//! `max_spacing`, a boundary growth of 1.0001, a far field of 1e5 chords) is refused with one
//! line naming the estimate and the keys to change, or announced on a terminal when large.

use std::io::IsTerminal;

use anyhow::{Result, bail};
use boundary1d::BoundaryNodes;
use mesh_model::Role;

use crate::case::Case;

/// The default of `--max-cells`.
pub const DEFAULT_MAX_CELLS: u64 = 20_000_000;

/// From this many expected cells on, the estimate is printed on a terminal.
const ANNOUNCE_CELLS: u64 = 2_000_000;

/// Fill triangles per boundary node (the graded region left between the fronts), measured on
/// the built-in cases.
const FILL_PER_NODE: f64 = 4.0;

/// Refuses a case whose boundary mesh alone would hold more than `max_cells` nodes: every
/// segment of a loop is at most its `max_spacing` long, so a loop has at least its length
/// over that many segments, each under one cell or more. Checked before the boundary mesh is
/// made (which would allocate them).
pub fn check_loops(case: &Case, max_cells: u64) -> Result<()> {
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
    Ok(())
}

/// The cells expected from the boundary nodes: on wall loops, one column of layered cells per
/// segment, as many layers as it takes the layer height, from `first_height` growing by
/// `[layers] growth`, to reach the segment's length (at most `max_layers`); on far-field
/// loops a few isotropic layers; and the fill, a few triangles per boundary node.
pub fn cells(case: &Case, nodes: &[BoundaryNodes]) -> u64 {
    let (h0, g, most) = (
        case.layers.first_height,
        case.layers.growth,
        f64::from(case.layers.max_layers),
    );
    let mut cells = 0.0;
    for (input, bn) in case.loops.iter().zip(nodes) {
        let n = bn.points.len();
        cells += FILL_PER_NODE * n as f64;
        if input.role != Role::Wall {
            cells += 2.0 * n as f64;
            continue;
        }
        for i in 0..n {
            let s = (bn.points[(i + 1) % n] - bn.points[i]).norm();
            let layers = if s > h0 {
                1.0 + (s / h0).ln() / g.ln()
            } else {
                1.0
            };
            cells += layers.min(most);
        }
    }
    cells as u64
}

/// Refuses an estimate above `max_cells`, and announces a large one on a terminal (unless
/// quiet).
pub fn check_cells(estimate: u64, boundary_nodes: usize, max_cells: u64, quiet: bool) -> Result<()> {
    if estimate > max_cells {
        bail!(
            "about {} cells expected ({boundary_nodes} boundary nodes), more than the limit \
             {max_cells}: raise [boundary] max_spacing or growth, or [layers] first_height, or \
             give --max-cells {}",
            readable(estimate as f64),
            estimate.saturating_mul(2)
        );
    }
    if estimate >= ANNOUNCE_CELLS && !quiet && std::io::stderr().is_terminal() {
        eprintln!(
            "note: about {} cells expected ({boundary_nodes} boundary nodes): this may take a while",
            readable(estimate as f64)
        );
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
