//! The built-in surfaces: an icosphere, and closed surfaces of voxels (the cube, the step).

use std::collections::HashMap;

use crate::{Facet, Surface};

impl Surface {
    /// A sphere of radius `radius` centred at the origin: an icosahedron whose triangles are
    /// split in four `refinement` times, every node projected onto the sphere
    /// (20·4^refinement triangles). One wall patch `wall` (its boundary group).
    pub fn sphere(radius: f64, refinement: u32) -> Surface {
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let mut nodes: Vec<[f64; 3]> = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .to_vec();
        let mut tris: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..refinement {
            let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
            let mut midpoint = |a: u32, b: u32, nodes: &mut Vec<[f64; 3]>| {
                *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (p, q) = (nodes[a as usize], nodes[b as usize]);
                    nodes.push(std::array::from_fn(|d| (p[d] + q[d]) / 2.0));
                    nodes.len() as u32 - 1
                })
            };
            let mut next = Vec::with_capacity(4 * tris.len());
            for [a, b, c] in tris {
                let ab = midpoint(a, b, &mut nodes);
                let bc = midpoint(b, c, &mut nodes);
                let ca = midpoint(c, a, &mut nodes);
                next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            tris = next;
        }
        for p in &mut nodes {
            let l = crate::norm(*p);
            *p = p.map(|x| x * radius / l);
        }
        let facets = tris.iter().map(|t| Facet::tri(t[0], t[1], t[2])).collect();
        Surface::single_patch(nodes, facets, "wall")
    }

    /// A cube of side `size`, corner at the origin, each face an `n`×`n` grid of quads (or
    /// of triangles, each quad split along a diagonal, when `triangles`). Sharp edges and
    /// corners. One wall patch `wall`.
    pub fn cube(size: f64, n: usize, triangles: bool) -> Surface {
        let n = n.max(1);
        voxel_surface([n, n, n], size / n as f64, |_| true, triangles, "wall")
    }

    /// The step: a 1×1×0.5 block (corner at the origin) with a 0.4×0.4×0.5 tower centred on
    /// its top, so the surface has 90° concave edges where the tower meets the block; quads
    /// of side 0.1 / `refine`. One wall patch `wall`.
    pub fn step(refine: usize) -> Surface {
        let r = refine.max(1);
        let cells = [10 * r, 10 * r, 10 * r];
        voxel_surface(
            cells,
            0.1 / r as f64,
            |[i, j, k]| k < 5 * r || ((3 * r..7 * r).contains(&i) && (3 * r..7 * r).contains(&j)),
            false,
            "wall",
        )
    }

    /// The boundary of the filled voxels of a `cells[0]`×`cells[1]`×`cells[2]` grid of
    /// spacing `h` (corner at the origin): one quad per face between a filled voxel and an
    /// empty one or the outside. `filled` must leave no two voxels meeting only along an
    /// edge or at a corner. One wall patch `name`. For shapes made in tests (slots, towers).
    pub fn voxels(
        cells: [usize; 3],
        h: f64,
        filled: impl Fn([usize; 3]) -> bool,
        name: &str,
    ) -> Surface {
        voxel_surface(cells, h, filled, false, name)
    }
}

/// The boundary of the filled voxels of a `cells[0]`×`cells[1]`×`cells[2]` grid of spacing
/// `h` (corner at the origin): one quad (or two triangles) per face between a filled voxel
/// and an empty one or the outside, counter-clockwise seen from the empty side. The filled
/// set must have no two voxels meeting only along an edge or at a corner (the surface would
/// not be manifold).
fn voxel_surface(
    cells: [usize; 3],
    h: f64,
    filled: impl Fn([usize; 3]) -> bool,
    triangles: bool,
    name: &str,
) -> Surface {
    let inside = |c: [i64; 3]| {
        (0..3).all(|d| c[d] >= 0 && (c[d] as usize) < cells[d]) && filled(c.map(|x| x as usize))
    };
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut node = |p: [i64; 3], nodes: &mut Vec<[f64; 3]>| {
        *index.entry(p).or_insert_with(|| {
            nodes.push(p.map(|x| x as f64 * h));
            nodes.len() as u32 - 1
        })
    };
    let mut facets = Vec::new();
    for k in 0..cells[2] as i64 {
        for j in 0..cells[1] as i64 {
            for i in 0..cells[0] as i64 {
                let c = [i, j, k];
                if !inside(c) {
                    continue;
                }
                for a in 0..3 {
                    let (b, e) = ((a + 1) % 3, (a + 2) % 3);
                    for positive in [true, false] {
                        let mut nb = c;
                        nb[a] += if positive { 1 } else { -1 };
                        if inside(nb) {
                            continue;
                        }
                        // corners (0,0) (1,0) (1,1) (0,1) in the (b, e) plane: counter-clockwise
                        // seen from +a
                        let mut square = [[0, 0], [1, 0], [1, 1], [0, 1]];
                        if !positive {
                            square.swap(1, 3);
                        }
                        let q = square.map(|[u, v]| {
                            let mut p = c;
                            p[a] += positive as i64;
                            p[b] += u;
                            p[e] += v;
                            node(p, &mut nodes)
                        });
                        if triangles {
                            facets.push(Facet::tri(q[0], q[1], q[2]));
                            facets.push(Facet::tri(q[0], q[2], q[3]));
                        } else {
                            facets.push(Facet::quad(q[0], q[1], q[2], q[3]));
                        }
                    }
                }
            }
        }
    }
    Surface::single_patch(nodes, facets, name)
}
