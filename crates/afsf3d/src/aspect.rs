//! The limit on a layer's height relative to the front's spacing
//! ([`LayerParams::max_aspect`](crate::LayerParams::max_aspect)). Far from the wall the
//! layers should turn isotropic (dissertation §5.4, Fig. 69: "the mesh deforms from
//! anisotropic to isotropic", its layer 45 still a wing-like front), but the geometric
//! height `first_height × growth^k` outruns the front's coarsening by Coe_shrink: at layer 28
//! of the wing with a quad side a layer is 1.5 chords high over front edges 0.15 apart near
//! the far tip, and a cell there inverts. The layer's height is held to `max_aspect` times
//! the mean length of the front's edges, but never below the previous layer's height: the
//! heights never shrink and never grow faster than `growth`. One height for the whole
//! layer, as without the limit: a height per node (from its own edges, even smoothed over
//! its neighbours) makes the front uneven where the spacing changes, and the quad wing then
//! fails earlier (layers 19–25, `docs/3d.md`). Where the limit never binds, the heights are
//! untouched to the bit.

use crate::front::Topo;

/// The mean length of the front's edges (`topo`, over the nodes `x`); infinite without edges.
pub(crate) fn mean_edge(topo: &Topo, x: &[[f64; 3]]) -> f64 {
    if topo.edges.is_empty() {
        return f64::INFINITY;
    }
    let sum: f64 = topo
        .edges
        .iter()
        .map(|e| geom_predicates::vector::dist(x[e.nodes[0] as usize], x[e.nodes[1] as usize]))
        .sum();
    sum / topo.edges.len() as f64
}

/// The factor on the layer height `height` (the layer before having been `height /
/// growth`), from the previous layer's factor `ratio`: `ratio` unless `ratio × height`
/// exceeds `max_aspect × spacing`, then `max_aspect × spacing / height`, but at least
/// `ratio / growth` (the previous layer's height).
pub(crate) fn limit_ratio(
    ratio: f64,
    spacing: f64,
    height: f64,
    growth: f64,
    max_aspect: f64,
) -> f64 {
    let cap = max_aspect * spacing;
    if ratio * height > cap {
        (cap / height).max(ratio / growth)
    } else {
        ratio
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The heights never shrink and never grow faster than `growth`; a height is the limit
    /// or the previous height where the limit binds; without a binding limit the factor
    /// stays exactly 1.
    #[test]
    fn heights_stay_monotone_within_growth_and_meet_the_limit() {
        let (first, growth, aspect): (f64, f64, f64) = (1e-3, 1.3, 2.0);
        for coarsening in [1.0f64, 1.05, 1.2, 1.5] {
            let mut ratio = 1.0;
            let mut previous = 0.0f64;
            for k in 0..45 {
                let height = first * growth.powi(k);
                let spacing = 0.01 * coarsening.powi(k);
                ratio = limit_ratio(ratio, spacing, height, growth, aspect);
                let h = ratio * height;
                if k > 0 {
                    assert!(h >= previous * (1.0 - 1e-12), "layer {k}: shrank");
                    assert!(
                        h <= previous * growth * (1.0 + 1e-12),
                        "layer {k}: too fast"
                    );
                }
                let at_limit = h <= aspect * spacing * (1.0 + 1e-12);
                assert!(at_limit || (h - previous).abs() <= 1e-12 * h, "layer {k}");
                previous = h;
            }
            if coarsening < growth {
                // limited by the end: 2 × 0.01 × coarsening^44, not 1e-3 × 1.3^44 ≈ 102
                assert!(previous <= 2.0 * 0.01 * coarsening.powi(44) * (1.0 + 1e-12));
            } else {
                assert_eq!(ratio, 1.0);
            }
        }
        // never limited: exactly 1
        assert_eq!(limit_ratio(1.0, 1.0, 1.0, 1.3, 1.0), 1.0);
    }

    #[test]
    fn a_front_without_edges_is_never_limited() {
        let topo = Topo::from_facets(&[]);
        let s = mean_edge(&topo, &[]);
        assert_eq!(limit_ratio(1.0, s, 1e9, 1.3, 1.0), 1.0);
    }
}
