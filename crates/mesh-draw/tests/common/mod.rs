//! Meshes built by hand for the tests and benches: a structured annulus (quads near the inner
//! wall with layers, triangles outside, P1 to P3 with edge nodes on the circles), and an O-mesh
//! around the real NACA 0012 section of `fixtures/geometry/naca0012.dat`.

#![allow(dead_code)]

use mesh_model::{CellType, Dim, Mesh, NONE, Patch, Role, Shape};

/// The annulus to build.
pub struct Annulus {
    /// Cells around.
    pub around: usize,
    /// Rings of quads from the inner circle, with layers 0, 1, …
    pub quad_rings: usize,
    /// Rings of triangle pairs outside them (no layer).
    pub tri_rings: usize,
    /// Polynomial order, 1 to 3.
    pub order: u8,
    /// Moves the nodes of the triangle rings by up to this fraction of the local spacing
    /// (order 1 only), so that angles vary.
    pub jitter: f64,
}

/// Inner (wall) radius.
pub const R_WALL: f64 = 0.5;

/// Radius of ring `j` (0 = wall): geometric growth from a thin first layer, capped.
fn ring_radius(j: f64, around: usize) -> f64 {
    let first = 0.004;
    let growth: f64 = 1.18;
    let cap = 2.0 * std::f64::consts::PI * R_WALL / around as f64 * 1.5;
    let mut r = R_WALL;
    let mut h = first;
    let whole = j.floor() as usize;
    for _ in 0..whole {
        r += h;
        h = (h * growth).min(cap);
    }
    r + (j - whole as f64) * h
}

/// A cheap deterministic hash to [-1, 1].
fn wobble(a: usize, b: usize, salt: u64) -> f64 {
    let mut x = (a as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (b as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ salt;
    x ^= x >> 29;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 32;
    (x % 20001) as f64 / 10000.0 - 1.0
}

/// Builds the annulus: wall inside, far field outside.
pub fn annulus(a: &Annulus) -> Mesh {
    let p = a.order as usize;
    let rings = a.quad_rings + a.tri_rings;
    let fine_around = a.around * p;
    let mut mesh = Mesh::new(Dim::Two, a.order);
    for ia in 0..=rings * p {
        for ib in 0..fine_around {
            let j = ia as f64 / p as f64;
            let mut r = ring_radius(j, a.around);
            let mut theta = 2.0 * std::f64::consts::PI * ib as f64 / fine_around as f64;
            let ring = ia / p;
            if a.jitter > 0.0 && p == 1 && ring > a.quad_rings && ring < rings {
                let dr = ring_radius(j + 1.0, a.around) - r;
                r += a.jitter * dr * wobble(ia, ib, 1);
                theta += a.jitter * wobble(ia, ib, 2) * std::f64::consts::PI / a.around as f64;
            }
            mesh.nodes.push([r * theta.cos(), r * theta.sin(), 0.0]);
        }
    }
    // Fine-grid node at (radial, angular) fine indices.
    let id = |ia: usize, ib: usize| (ia * fine_around + ib % fine_around) as u32;
    for ring in 0..rings {
        for k in 0..a.around {
            let (r0, t0) = (ring * p, k * p);
            // Local (radial, angular) offsets: corners of the quad, counter-clockwise.
            let node = |l: (usize, usize)| id(r0 + l.0, t0 + l.1);
            let corners = [(0, 0), (p, 0), (p, p), (0, p)];
            if ring < a.quad_rings {
                let mut nodes: Vec<u32> = corners.iter().map(|&c| node(c)).collect();
                for e in 0..4 {
                    let (c0, c1) = (corners[e], corners[(e + 1) % 4]);
                    nodes.extend(edge_inner(c0, c1, p).into_iter().map(node));
                }
                let inner: Vec<(usize, usize)> = match p {
                    2 => vec![(1, 1)],
                    3 => vec![(1, 1), (2, 1), (2, 2), (1, 2)],
                    _ => vec![],
                };
                nodes.extend(inner.into_iter().map(node));
                mesh.cells.push(CellType::new(Shape::Quad, a.order), &nodes);
                mesh.cell_layer.push(ring as u32);
            } else {
                for (tri, centre) in [([0, 1, 2], (2, 1)), ([0, 2, 3], (1, 2))] {
                    let c: Vec<(usize, usize)> = tri.iter().map(|&i| corners[i]).collect();
                    let mut nodes: Vec<u32> = c.iter().map(|&l| node(l)).collect();
                    for e in 0..3 {
                        nodes.extend(edge_inner(c[e], c[(e + 1) % 3], p).into_iter().map(node));
                    }
                    if p == 3 {
                        nodes.push(node(centre));
                    }
                    mesh.cells.push(CellType::new(Shape::Tri, a.order), &nodes);
                    mesh.cell_layer.push(NONE);
                }
            }
        }
    }
    mesh.patches.push(Patch {
        name: "body".into(),
        role: Role::Wall,
    });
    mesh.patches.push(Patch {
        name: "farfield".into(),
        role: Role::Farfield,
    });
    let line = CellType::new(Shape::Line, a.order);
    for k in 0..a.around {
        // Wall: clockwise (domain on the left); far field: counter-clockwise.
        let (s, e) = ((k + 1) * p, k * p);
        let mut nodes = vec![id(0, s), id(0, e)];
        nodes.extend((1..p).map(|m| id(0, s - m)));
        mesh.boundary.push(line, &nodes);
        mesh.boundary_patch.push(0);
        let outer = rings * p;
        let (s, e) = (k * p, (k + 1) * p);
        let mut nodes = vec![id(outer, s), id(outer, e)];
        nodes.extend((1..p).map(|m| id(outer, s + m)));
        mesh.boundary.push(line, &nodes);
        mesh.boundary_patch.push(1);
    }
    mesh
}

/// Fine-grid offsets of the inner nodes of the edge from `c0` to `c1`, in its direction.
fn edge_inner(c0: (usize, usize), c1: (usize, usize), p: usize) -> Vec<(usize, usize)> {
    (1..p)
        .map(|m| {
            let f = |a: usize, b: usize| {
                (a as isize + (b as isize - a as isize) * m as isize / p as isize) as usize
            };
            (f(c0.0, c1.0), f(c0.1, c1.1))
        })
        .collect()
}

/// An O-mesh of quads around a closed counter-clockwise loop: ring j blends each wall point
/// towards the point of a circle (radius `radius` about (0.5, 0)) at the same angle, with
/// geometrically growing steps; layers numbered from the wall.
pub fn o_mesh(wall: &[[f64; 2]], rings: usize, radius: f64) -> Mesh {
    let n = wall.len();
    let mut mesh = Mesh::new(Dim::Two, 1);
    let growth: f64 = 1.2;
    let total: f64 = (0..rings).map(|j| growth.powi(j as i32)).sum();
    let mut s = vec![0.0];
    for j in 0..rings {
        s.push(s[j] + growth.powi(j as i32) / total);
    }
    for &sj in &s {
        for w in wall {
            let phi = (w[1]).atan2(w[0] - 0.5);
            let c = [0.5 + radius * phi.cos(), radius * phi.sin()];
            mesh.nodes
                .push([w[0] + sj * (c[0] - w[0]), w[1] + sj * (c[1] - w[1]), 0.0]);
        }
    }
    let id = |j: usize, i: usize| (j * n + i % n) as u32;
    let quad = CellType::new(Shape::Quad, 1);
    for j in 0..rings {
        for i in 0..n {
            mesh.cells.push(
                quad,
                &[id(j, i), id(j + 1, i), id(j + 1, i + 1), id(j, i + 1)],
            );
            mesh.cell_layer.push(j as u32);
        }
    }
    mesh.patches.push(Patch {
        name: "airfoil".into(),
        role: Role::Wall,
    });
    mesh.patches.push(Patch {
        name: "farfield".into(),
        role: Role::Farfield,
    });
    let line = CellType::new(Shape::Line, 1);
    for i in 0..n {
        mesh.boundary.push(line, &[id(0, i + 1), id(0, i)]);
        mesh.boundary_patch.push(0);
        mesh.boundary.push(line, &[id(rings, i), id(rings, i + 1)]);
        mesh.boundary_patch.push(1);
    }
    mesh
}

/// The O-mesh around the NACA 0012 of the fixtures.
pub fn naca0012_o_mesh(rings: usize) -> Mesh {
    o_mesh(&testkit::fixtures::selig_xy("naca0012.dat"), rings, 6.0)
}
