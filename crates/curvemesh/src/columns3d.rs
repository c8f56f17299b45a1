//! The columns of a 3D growth in the report (issue 47): where a column could not take its
//! next layer it stopped (`afsf3d`'s `stop`) and the rest grew on. Here: the coverage (wall
//! nodes with every layer), the least layers per boundary group, where columns stopped (the
//! first few, with their wall node's coordinates and why), and the run's verdict against
//! `[layers] min_coverage` — below it the run stops with one line naming where and why.

use std::collections::BTreeMap;

use geom_surface::Surface;
use serde::Serialize;

use crate::error::{Error, input_error};

/// How many stopped columns the report lists (the first by layer, then by wall node).
pub const LISTED_STOPS: usize = 10;

/// One column that stopped.
#[derive(Debug, Clone, Serialize)]
pub struct StoppedColumn {
    /// The layer (from 0) it could not take: it holds this many layers.
    pub layer: usize,
    /// Why.
    pub why: &'static str,
    /// Its wall node's coordinates.
    pub at: [f64; 3],
    /// The boundary group of a wall facet at that node.
    pub group: String,
}

/// The report's `columns` block.
#[derive(Debug, Clone, Serialize)]
pub struct Columns {
    /// What is counted.
    pub of: &'static str,
    /// Wall nodes (one column each).
    pub wall_nodes: usize,
    /// Columns with every layer.
    pub full: usize,
    /// `full / wall_nodes`.
    pub coverage: f64,
    /// The run's floor (`[layers] min_coverage`): below it the run fails (exit 1).
    pub min_coverage: f64,
    /// With a far field, the fraction of wall nodes whose columns did not stop for a failure
    /// (an inverted cell, fronts crossing): columns stopped to keep a gap for the fill, and
    /// their neighbours stepping down, are by design; this, not `coverage`, is held to
    /// `min_coverage` then.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coverage_without_gaps: Option<f64>,
    /// The fewest layers of any column at a node of each boundary group's wall facets.
    pub least_layers: BTreeMap<String, usize>,
    /// How many columns stopped, by why.
    pub stopped_by_why: BTreeMap<&'static str, usize>,
    /// The first [`LISTED_STOPS`] stopped columns (by layer, then wall node).
    pub first_stopped: Vec<StoppedColumn>,
    /// Wall nodes on sharp convex edges (a trailing edge) that grew a fan of columns
    /// (`[layers] fan_threshold_deg`); their first column is counted above.
    pub fanned_nodes: usize,
    /// The fans' other columns.
    pub fan_columns: usize,
    /// Wall nodes on sharp edges grown with one column because a column of their fan would
    /// have stopped in the first layer.
    pub unfanned_nodes: usize,
}

/// The columns of `grown`, grown from `wall` (its patches the boundary groups), against the
/// floor `min_coverage`; `gaps`: a fill follows, so columns stopped to keep a gap for it are
/// not held against the floor.
pub fn columns(wall: &Surface, grown: &afsf3d::Grown3d, min_coverage: f64, gaps: bool) -> Columns {
    let n = grown.stops.len();
    let layers = |v: usize| grown.columns[v].len() - 1;
    // a group per wall node (its first facet's), and the least layers per group
    let mut group_of = vec![None; n];
    let mut least_layers = BTreeMap::new();
    for (f, facet) in wall.facets.iter().enumerate() {
        let name = &wall.patches[wall.facet_patch[f] as usize].name;
        for &v in facet.nodes() {
            let v = v as usize;
            group_of[v].get_or_insert(name);
            let least = least_layers.entry(name.clone()).or_insert(usize::MAX);
            *least = (*least).min(layers(v));
        }
    }
    let mut stopped: Vec<(usize, usize)> = (0..n)
        .filter_map(|v| grown.stops[v].map(|s| (s.layer, v)))
        .collect();
    stopped.sort_unstable();
    let mut stopped_by_why = BTreeMap::new();
    for s in grown.stops.iter().flatten() {
        *stopped_by_why.entry(s.why.describe()).or_insert(0) += 1;
    }
    let first_stopped = stopped
        .iter()
        .take(LISTED_STOPS)
        .map(|&(layer, v)| StoppedColumn {
            layer,
            why: grown.stops[v].map_or("", |s| s.why.describe()),
            at: wall.nodes[v],
            group: group_of[v].cloned().unwrap_or_default(),
        })
        .collect();
    let full = n - stopped.len();
    let failed = grown
        .stops
        .iter()
        .flatten()
        .filter(|s| {
            matches!(
                s.why,
                afsf3d::StopWhy::InvertedCell | afsf3d::StopWhy::FrontsCross
            )
        })
        .count();
    let coverage_without_gaps = gaps.then(|| (n - failed) as f64 / n.max(1) as f64);
    Columns {
        of: "the wall nodes' columns of layers: where a column could not take its next layer \
             (an inverted cell, fronts crossing) it stopped, its neighbours stepping down to \
             it, and the rest grew on",
        wall_nodes: n,
        full,
        coverage: grown.coverage(),
        min_coverage,
        coverage_without_gaps,
        least_layers,
        stopped_by_why,
        first_stopped,
        fanned_nodes: grown.stats.fanned_nodes,
        fan_columns: grown.fan_columns.len(),
        unfanned_nodes: grown.stats.unfanned_nodes,
    }
}

impl Columns {
    /// The note a report gives when columns stopped (`None` when none did).
    pub fn note(&self) -> Option<String> {
        let first = self.first_stopped.first()?;
        Some(format!(
            "{} of {} columns stopped before the last layer (coverage {:.4}), the first in layer \
             {} at ({:.4}, {:.4}, {:.4}) ({}): {}; see `columns`",
            self.wall_nodes - self.full,
            self.wall_nodes,
            self.coverage,
            first.layer,
            first.at[0],
            first.at[1],
            first.at[2],
            first.group,
            first.why
        ))
    }

    /// The run's error when the coverage is below the floor: one line naming the first place
    /// a column stopped and why (`origin`: the case, for the message).
    pub fn check(&self, origin: &str) -> Result<(), Error> {
        if self.coverage_without_gaps.unwrap_or(self.coverage) >= self.min_coverage {
            return Ok(());
        }
        let first = self.first_stopped.first();
        let (layer, at, why) = first.map_or((0, [0.0; 3], ""), |s| (s.layer, s.at, s.why));
        Err(input_error!(
            "{origin}: growing the layers: coverage {:.4} is below [layers] min_coverage = {}: \
             {} of {} columns stopped, the first in layer {layer} at ({:.4}, {:.4}, {:.4}): {why}",
            self.coverage,
            self.min_coverage,
            self.wall_nodes - self.full,
            self.wall_nodes,
            at[0],
            at[1],
            at[2]
        ))
    }
}
