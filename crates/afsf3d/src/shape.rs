//! The layer cells kept in shape as the fronts grow (issue 47's prisms on smooth bodies).
//!
//! Grown along their columns, a front's facets stretch one way and shrink the other wherever
//! the surface curves differently in two directions (a torus's inner side, two spheres'
//! crease): the offset of a torus's wall 0.144 out, node by node along the true normals, has
//! a least corner sine of 0.40 where the wall's is 0.63, and a prism's corner scaled Jacobian
//! is at most the sine of its corner. The springs balance the columns' lengths and
//! directions, not the facets' angles; this pass gives the angles back.
//!
//! Each front facet carries the bar of its wall facet ([`shape_bars`]: the least of
//! [`SHAPE_TARGET`] and that facet's least corner sine, the most its cells can have; none for
//! quads, nor near the wall's creases and edges). While the stack is a boundary layer's
//! ([`RESHAPE_SPACINGS`]), after a layer is checked and repaired, the children of each plain
//! cell whose top corners fell under its bar slide parallel to the front by a compass search
//! (the step halving from a quarter of the extrusion edge), leaning their columns: a move is
//! kept when the shortfall of the corners around the child under their bars falls (summed as
//! eighth powers, so the worst corner leads) while their least stays within [`FLOOR`] of
//! where it started, every cell around still passes its check, and the extrusion edge leans
//! at most [`MAX_LEAN_DEG`] off its front's normal (or as far as it already did). Sweeps
//! repeat while they move enough children. Where the new front then intersects itself, every
//! move is undone.
//!
//! Children beside a cell without a bar (a fan's, a merged or a stopped column's, a quad's,
//! one near a wall's edge) stay, and so do those whose cells touch a front node on or next to
//! a crease or an edge ([`near_sharp`], [`SHARP_DEG`]): there the front's shape is the fans',
//! the merges' and the stops' work, and leaning the columns beside a voxel body's edges or a
//! wing tip's trailing edge inverted later layers' cells. The built-in sphere, cube and step
//! are unchanged to the bit.

use geom_predicates::vector::{cross3, dist, sub};
use geom_surface::{Facet, angle_between, fan_normal, first_self_intersection, node_normals, unit};

use crate::check::{cell_corners, layer_cell_ok};
use crate::children::Layer;
use crate::compass::compass_search;

/// The corner scaled Jacobian a cell is held to where its wall facet allows it: above issue
/// 47's 0.5 for the prisms of smooth bodies, with a margin for the layers above (0.7 and 0.8
/// spread the effort over cells already good: the torus's worst fell from 0.56 to 0.44).
pub(crate) const SHAPE_TARGET: f64 = 0.6;

/// Layers are reshaped while the stack under them is at most this many wall spacings (mean
/// edges) thick: beyond, they are the far field's isotropic cells rather than a boundary
/// layer's prisms, and reshaping them leaned the built-in wing's far columns (19 extrusion
/// edges over 30°, 7 without; the torus's and the fused spheres' stacks are 1.6 and 2.4
/// spacings thick).
pub(crate) const RESHAPE_SPACINGS: f64 = 4.0;

/// A cell is reshaped when a top corner falls under this share of its bar (at 0.9 the torus
/// kept 0.53 against 0.56).
const SLACK: f64 = 0.99;

/// How far (degrees) a moved child's extrusion edge may lean off its front's normal (or as
/// far as it already did): under the mixed cut's 30°, so that no reshaped prism is cut.
const MAX_LEAN_DEG: f64 = 25.0;

/// A front node whose facets turn more than this (degrees) from its normal is on a crease
/// or an edge: the cells touching it keep their children.
const SHARP_DEG: f64 = 40.0;

/// Halvings of the compass step (from a quarter of the extrusion edge), and rounds at each.
const HALVINGS: usize = 4;
const ROUNDS: usize = 4;

/// Sweeps over the children of the cells still low; they stop when one moves fewer than a
/// twentieth of its children.
const SWEEPS: usize = 8;

/// A move may lower the least corner around a child to this share of what it was (or of
/// the target): one corner traded for its neighbours'.
const FLOOR: f64 = 0.9;

/// A child's search is kept when it cuts the shortfall around it to this share.
const GAIN: f64 = 0.95;

/// The least corner sine of `facet` (nodes `x`): what any cell over it can have at its
/// bottom corners.
fn least_corner_sine(x: &[[f64; 3]], facet: &Facet) -> f64 {
    let k = facet.nodes();
    let m = k.len();
    (0..m)
        .map(|i| {
            let o = x[k[i] as usize];
            let (a, b) = (x[k[(i + 1) % m] as usize], x[k[(i + m - 1) % m] as usize]);
            angle_between(sub(a, o), sub(b, o)).sin()
        })
        .fold(1.0, f64::min)
}

/// The corner scaled Jacobians of the plain cell over `facet` (bottom corners first).
fn corners(front: &[[f64; 3]], layer: &Layer, facet: &Facet) -> Vec<f64> {
    cell_corners(front, facet, |v| {
        layer.children[layer.child[v as usize] as usize]
    })
}

/// Each wall facet's bar (`facets` over `nodes`, the first `real` of them the wall's, the
/// rest a fan's, which have no shape to keep): the least of [`SHAPE_TARGET`] and the facet's
/// least corner sine, the most a cell's corners over it can have; 0 (none) for a quad,
/// whose hexahedra the growth keeps as they are (reshaped, the step's and the quad-side
/// wing's columns stopped at their edges), and for a facet near a wall's crease or edge
/// ([`near_sharp`]): the fronts round such edges off, and the columns reshaped there (the
/// quad-side wing's tips at its trailing edge) stopped 20 columns a few layers on.
pub(crate) fn shape_bars(nodes: &[[f64; 3]], facets: &[Facet], real: usize) -> Vec<f64> {
    let wall = &facets[..real];
    let normals = node_normals(nodes, wall);
    let near = near_sharp(nodes, wall, &normals);
    facets
        .iter()
        .enumerate()
        .map(|(f, facet)| {
            let k = facet.nodes();
            if f < real && k.len() == 3 && k.iter().all(|&v| !near[v as usize]) {
                SHAPE_TARGET.min(least_corner_sine(nodes, facet))
            } else {
                0.0
            }
        })
        .collect()
}

/// Reshapes `layer` (checked, over the front `front` with `facets`, each held to its wall
/// facet's bar `wall_bars`) as the module's doc says. Returns the children moved (0 when
/// every move is undone).
pub(crate) fn reshape_layer(
    front: &[[f64; 3]],
    facets: &[Facet],
    wall_bars: &[f64],
    layer: &mut Layer,
) -> usize {
    // each plain cell's bar (0: none)
    let bar: Vec<f64> = facets
        .iter()
        .zip(wall_bars)
        .map(|(f, &b)| if layer.is_plain(f) { b } else { 0.0 })
        .collect();
    let low = |layer: &Layer, f: usize| {
        bar[f] > 0.0 && {
            let q = corners(front, layer, &facets[f]);
            q[q.len() / 2..]
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min)
                < SLACK * bar[f]
        }
    };
    // a layer whose cells all keep their shape costs one look at each
    if !(0..facets.len()).any(|f| low(layer, f)) {
        return 0;
    }
    let around = layer.cells_around(facets);
    let normals = node_normals(front, facets);
    let sharp = near_sharp(front, facets, &normals);
    // the children that may move: every cell around them plain, with a bar, off sharp nodes
    let free: Vec<bool> = around
        .iter()
        .map(|cells| {
            cells.iter().all(|&f| {
                let facet = &facets[f as usize];
                bar[f as usize] > 0.0 && facet.nodes().iter().all(|&v| !sharp[v as usize])
            })
        })
        .collect();
    let saved = layer.children.clone();
    let mut moved = 0;
    for _ in 0..SWEEPS {
        let mut todo: Vec<u32> = (0..facets.len())
            .filter(|&f| low(layer, f))
            .flat_map(|f| facets[f].nodes().iter().map(|&v| layer.child[v as usize]))
            .collect();
        todo.sort_unstable();
        todo.dedup();
        todo.retain(|&c| free[c as usize]);
        let mut moved_now = 0;
        for &c in &todo {
            let c = c as usize;
            let normal = unit(layer.parents_sum(c, &normals));
            let star = Star {
                front,
                facets,
                around: &around[c],
                bar: &bar,
            };
            if reshape_child(&star, normal, c, layer) {
                moved_now += 1;
            }
        }
        moved += moved_now;
        if moved_now * 20 < todo.len() {
            break;
        }
    }
    if moved > 0 && first_self_intersection(&layer.children, &layer.top).is_some() {
        layer.children = saved;
        return 0;
    }
    moved
}

/// Whether each node of a surface (`nodes`, `facets`, angle-weighted `normals`) is on a crease
/// or an edge (one of its facets turns more than [`SHARP_DEG`] from its normal) or next to
/// one: the columns one ring off an edge lean into the next layer's cells at it (the slot's
/// sides stopped 18 columns in layer 3 when only the edges' own nodes were left alone).
fn near_sharp(nodes: &[[f64; 3]], facets: &[Facet], normals: &[[f64; 3]]) -> Vec<bool> {
    let max_turn = SHARP_DEG.to_radians();
    let mut sharp = vec![false; nodes.len()];
    for f in facets {
        let n = unit(fan_normal(nodes, f.nodes()));
        for &v in f.nodes() {
            sharp[v as usize] |= angle_between(n, normals[v as usize]) > max_turn;
        }
    }
    let mut near = sharp.clone();
    for f in facets {
        if f.nodes().iter().any(|&v| sharp[v as usize]) {
            f.nodes().iter().for_each(|&v| near[v as usize] = true);
        }
    }
    near
}

/// The cells around one child, with every plain cell's bar.
struct Star<'a> {
    front: &'a [[f64; 3]],
    facets: &'a [Facet],
    around: &'a [u32],
    bar: &'a [f64],
}

impl Star<'_> {
    /// (least corner, shortfall under the bars summed as eighth powers) of the cells (eighth
    /// powers: with squares the fused spheres' worst prism rose to 0.37, with fourth powers
    /// 0.42, with eighth 0.47, with sixteenth no further).
    fn score(&self, layer: &Layer) -> (f64, f64) {
        let mut least = f64::INFINITY;
        let mut short = 0.0;
        for &f in self.around {
            let bar = self.bar[f as usize];
            for q in corners(self.front, layer, &self.facets[f as usize]) {
                least = least.min(q);
                short += (bar - q).max(0.0).powi(8);
            }
        }
        (least, short)
    }

    /// Whether every cell around passes its check (`check`).
    fn valid(&self, layer: &Layer) -> bool {
        self.around
            .iter()
            .all(|&f| layer_cell_ok(self.front, layer, &self.facets[f as usize]))
    }
}

/// The compass search of one child `c` (its parents' normal `normal`) parallel to the front:
/// returns whether it moved.
fn reshape_child(star: &Star<'_>, normal: [f64; 3], c: usize, layer: &mut Layer) -> bool {
    let base = layer.base(star.front, c);
    let start = layer.children[c];
    let edge = sub(start, base);
    let h = dist(start, base);
    if h <= 0.0 {
        return false;
    }
    let first = star.score(layer);
    if first.1 <= 0.0 {
        return false;
    }
    let max_lean = angle_between(edge, normal).max(MAX_LEAN_DEG.to_radians());
    // the moves slide the child parallel to the front: its height over it stays
    let t1 = unit(cross3(
        normal,
        if normal[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        },
    ));
    let t2 = cross3(normal, t1);
    let moves = [t1, t2].map(|t| t.map(|x| x * h));
    // the least corner may fall a little, to trade one corner for its neighbours
    let floor = first.0.min(SHAPE_TARGET) * FLOOR;
    let mut best = first;
    compass_search(start, &moves, (HALVINGS, ROUNDS), |y| {
        if angle_between(sub(y, base), normal) > max_lean {
            return false;
        }
        let x = layer.children[c];
        layer.children[c] = y;
        let s = star.score(layer);
        if s.1 < best.1 && s.0 >= floor && star.valid(layer) {
            best = s;
            true
        } else {
            layer.children[c] = x;
            false
        }
    });
    if best.1 < GAIN * first.1 {
        true
    } else {
        layer.children[c] = start;
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat hexagon of six equilateral triangles around node 0, grown by 0.2 along z, the
    /// child of node 0 pushed sideways by `push`.
    fn hexagon(push: f64) -> (Vec<[f64; 3]>, Vec<Facet>, Layer) {
        let mut front = vec![[0.0, 0.0, 0.0]];
        front.extend((0..6).map(|i| {
            let a = std::f64::consts::FRAC_PI_3 * i as f64;
            [a.cos(), a.sin(), 0.0]
        }));
        let facets: Vec<Facet> = (0..6u32)
            .map(|i| Facet::tri(0, 1 + i, 1 + (i + 1) % 6))
            .collect();
        let mut children: Vec<[f64; 3]> = front.iter().map(|p| [p[0], p[1], 0.2]).collect();
        children[0][0] += push;
        let layer = Layer::unmerged(&front, &facets, &children);
        (front, facets, layer)
    }

    /// The shortfall of every cell's corners under their bars, as the search sums it.
    fn shortfall(front: &[[f64; 3]], facets: &[Facet], bars: &[f64], layer: &Layer) -> f64 {
        let around: Vec<u32> = (0..facets.len() as u32).collect();
        let star = Star {
            front,
            facets,
            around: &around,
            bar: bars,
        };
        star.score(layer).1
    }

    proptest::proptest! {
        /// Any star of six triangles around a node, its children lifted 0.2 and pushed
        /// sideways: the reshaped layer keeps every cell valid and every child's height, and
        /// its summed shortfall never rises.
        #[test]
        fn reshaping_keeps_every_cell_valid_and_never_worsens_the_shortfall(
            radii in proptest::collection::vec(0.6f64..1.4, 6),
            turns in proptest::collection::vec(-0.25f64..0.25, 6),
            pushes in proptest::collection::vec((-0.15f64..0.15, -0.15f64..0.15), 7),
        ) {
            let mut front = vec![[0.0, 0.0, 0.0]];
            front.extend((0..6).map(|i| {
                let a = std::f64::consts::FRAC_PI_3 * (i as f64 + turns[i]);
                [radii[i] * a.cos(), radii[i] * a.sin(), 0.0]
            }));
            let facets: Vec<Facet> =
                (0..6u32).map(|i| Facet::tri(0, 1 + i, 1 + (i + 1) % 6)).collect();
            let children: Vec<[f64; 3]> = front
                .iter()
                .zip(&pushes)
                .map(|(p, &(dx, dy))| [p[0] + dx, p[1] + dy, 0.2])
                .collect();
            let mut layer = Layer::unmerged(&front, &facets, &children);
            proptest::prop_assume!(facets.iter().all(|f| layer_cell_ok(&front, &layer, f)));
            let bars = shape_bars(&front, &facets, facets.len());
            let before = shortfall(&front, &facets, &bars, &layer);
            let moved = reshape_layer(&front, &facets, &bars, &mut layer);
            let after = shortfall(&front, &facets, &bars, &layer);
            proptest::prop_assert!(after <= before, "{before} -> {after}");
            proptest::prop_assert!(moved == 0 || after < before);
            proptest::prop_assert!(facets.iter().all(|f| layer_cell_ok(&front, &layer, f)));
            proptest::prop_assert!(layer.children.iter().all(|c| c[2] == 0.2));
        }
    }

    fn least_top_corner(front: &[[f64; 3]], facets: &[Facet], layer: &Layer) -> f64 {
        facets
            .iter()
            .flat_map(|f| corners(front, layer, f).split_off(3))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn a_leaning_child_is_stood_back_up_and_the_layer_stays_checked() {
        let (front, facets, mut layer) = hexagon(0.3);
        let bars = shape_bars(&front, &facets, facets.len());
        assert!(bars.iter().all(|&b| b == SHAPE_TARGET));
        assert!(facets.iter().all(|f| layer_cell_ok(&front, &layer, f)));
        let before = least_top_corner(&front, &facets, &layer);
        assert!(before < 0.5, "{before}");
        let moved = reshape_layer(&front, &facets, &bars, &mut layer);
        assert!(moved >= 1, "{moved}");
        let after = least_top_corner(&front, &facets, &layer);
        assert!(after >= SLACK * SHAPE_TARGET, "{before} -> {after}");
        assert!(facets.iter().all(|f| layer_cell_ok(&front, &layer, f)));
        // parallel to the front: the child keeps its height
        assert!(layer.children.iter().all(|c| (c[2] - 0.2).abs() < 1e-12));
        // a layer in shape is left to the bit, and so is one whose cells have no bar
        let (front, facets, mut upright) = hexagon(0.0);
        let children = upright.children.clone();
        assert_eq!(reshape_layer(&front, &facets, &bars, &mut upright), 0);
        assert_eq!(upright.children, children);
        let (front, facets, mut pushed) = hexagon(0.3);
        let children = pushed.children.clone();
        assert_eq!(reshape_layer(&front, &facets, &[0.0; 6], &mut pushed), 0);
        assert_eq!(pushed.children, children);
    }

    #[test]
    fn a_child_on_a_crease_stays() {
        // the hexagon folded along the y axis by 100°: node 0 and the nodes on the fold are
        // sharp, so no child touching them moves
        let (mut front, facets, _) = hexagon(0.0);
        let fold = 100f64.to_radians();
        for p in &mut front {
            if p[0] > 1e-9 {
                *p = [p[0] * fold.cos(), p[1], p[0] * fold.sin()];
            }
        }
        let normals = node_normals(&front, &facets);
        let sharp = near_sharp(&front, &facets, &normals);
        assert!(sharp[0]);
        let (_, _, pushed) = hexagon(0.3);
        let mut layer = pushed;
        let children = layer.children.clone();
        let bars = shape_bars(&front, &facets, facets.len());
        reshape_layer(&front, &facets, &bars, &mut layer);
        assert_eq!(layer.children, children);
    }
}
