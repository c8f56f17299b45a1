//! The checks of a new layer (positive corner tetrahedra of every cell, no self-intersection
//! of the new front) and the shrinking of the children where they fail.

use geom_surface::{Facet, first_self_intersection};
use mesh_model::is_positive_tet;
use rayon::prelude::*;

use crate::{GrowError, GrowStats};

/// Whether every corner tetrahedron of the cell over `facet` is positive: at each bottom
/// corner the corner, its next and previous neighbours and the child; at each top corner the
/// child, its previous and next neighbours and the parent.
pub(crate) fn cell_ok(parents: &[[f64; 3]], children: &[[f64; 3]], facet: &Facet) -> bool {
    let k = facet.nodes();
    let m = k.len();
    (0..m).all(|i| {
        let (p, a, c) = (
            k[(i + m - 1) % m] as usize,
            k[i] as usize,
            k[(i + 1) % m] as usize,
        );
        is_positive_tet(parents[a], parents[c], parents[p], children[a])
            && is_positive_tet(children[a], children[p], children[c], parents[a])
    })
}

/// The facets whose cells fail [`cell_ok`] (in parallel).
fn bad_cells(parents: &[[f64; 3]], children: &[[f64; 3]], facets: &[Facet]) -> Vec<usize> {
    facets
        .par_iter()
        .enumerate()
        .filter(|(_, f)| !cell_ok(parents, children, f))
        .map(|(i, _)| i)
        .collect()
}

/// Checks the layer `children` over `parents`; while a cell is inverted or the new front
/// intersects itself, moves the children of the failing facets halfway back to their
/// parents. Fails after `max_shrinks` rounds.
pub(crate) fn shrink_until_valid(
    parents: &[[f64; 3]],
    children: &mut [[f64; 3]],
    facets: &[Facet],
    max_shrinks: usize,
    layer: usize,
    stats: &mut GrowStats,
) -> Result<(), GrowError> {
    let mut round = 0;
    loop {
        let mut bad = bad_cells(parents, children, facets);
        let mut what = "an inverted cell";
        if bad.is_empty() {
            match first_self_intersection(children, facets) {
                None => return Ok(()),
                Some((f, g)) => {
                    bad = vec![f, g];
                    what = "the front intersects itself";
                }
            }
        }
        if round == max_shrinks {
            return Err(GrowError::LayerFailed {
                layer,
                facet: bad[0],
                what,
            });
        }
        round += 1;
        let mut moved = vec![false; children.len()];
        for &f in &bad {
            for &v in facets[f].nodes() {
                moved[v as usize] = true;
            }
        }
        for (i, _) in moved.iter().enumerate().filter(|(_, m)| **m) {
            children[i] = std::array::from_fn(|d| (parents[i][d] + children[i][d]) / 2.0);
            stats.shrunk_nodes += 1;
        }
        stats.shrinks += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_prism_over_a_counter_clockwise_triangle_is_valid_and_upside_down_is_not() {
        let bottom = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let up = bottom.map(|p| [p[0], p[1], 0.2]);
        let down = bottom.map(|p| [p[0], p[1], -0.2]);
        let f = Facet::tri(0, 1, 2);
        assert!(cell_ok(&bottom, &up, &f));
        assert!(!cell_ok(&bottom, &down, &f));
        // a child pushed across its neighbour's extrusion edge twists the cell
        let mut twisted = up;
        twisted[0] = [1.5, 0.8, 0.2];
        assert!(!cell_ok(&bottom, &twisted, &f));
    }
}
