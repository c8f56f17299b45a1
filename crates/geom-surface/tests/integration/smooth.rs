//! The smooth surface rebuilt from facets (`SmoothSurface`): its patches interpolate the
//! nodes with the sector normals there, two facets agree along their edge, flat regions and
//! straight feature lines stay as they are, creases stay sharp, and on a triangulated sphere
//! its edge midpoints are far closer to the sphere than the chords'.

use geom_surface::{DEFAULT_FEATURE_ANGLE_DEG, Facet, SmoothSurface, Surface};
use proptest::prelude::*;

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>().sqrt()
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|d| a[d] * b[d]).sum()
}

fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    std::array::from_fn(|d| a[d] + t * (b[d] - a[d]))
}

/// The unit sphere's icosphere with each node moved radially by a smooth bump field.
fn bumpy_sphere(refinement: u32, amp: f64, freq: [f64; 3]) -> Surface {
    let mut s = Surface::sphere(1.0, refinement);
    for p in &mut s.nodes {
        let r = 1.0 + amp * (freq[0] * p[0]).sin() * (freq[1] * p[1] + freq[2] * p[2]).cos();
        *p = p.map(|x| x * r);
    }
    s
}

/// A closed cylinder of radius 1 and height `h` along z: `n` nodes round, `m` quads (or
/// triangle pairs) up the side, each cap a fan of triangles from its centre.
fn cylinder(n: usize, m: usize, h: f64, triangles: bool) -> Surface {
    let mut nodes = Vec::new();
    for j in 0..=m {
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            nodes.push([a.cos(), a.sin(), h * j as f64 / m as f64]);
        }
    }
    let ring = |i: usize, j: usize| (j * n + i % n) as u32;
    let (bottom, top) = (nodes.len() as u32, nodes.len() as u32 + 1);
    nodes.extend([[0.0, 0.0, 0.0], [0.0, 0.0, h]]);
    let mut facets = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let q = [
                ring(i, j),
                ring(i + 1, j),
                ring(i + 1, j + 1),
                ring(i, j + 1),
            ];
            if triangles {
                facets.push(Facet::tri(q[0], q[1], q[2]));
                facets.push(Facet::tri(q[0], q[2], q[3]));
            } else {
                facets.push(Facet::quad(q[0], q[1], q[2], q[3]));
            }
        }
    }
    for i in 0..n {
        facets.push(Facet::tri(bottom, ring(i + 1, 0), ring(i, 0)));
        facets.push(Facet::tri(top, ring(i, m), ring(i + 1, m)));
    }
    Surface::single_patch(nodes, facets, "cylinder")
}

/// Every edge of `s` seen from both facets: the same point at fraction `t` (of the chord
/// from the smaller node to the larger), up to rounding.
fn assert_conforming(s: &Surface, smooth: &SmoothSurface, t: f64) -> Result<(), TestCaseError> {
    let mut first: std::collections::HashMap<(u32, u32), [f64; 3]> = Default::default();
    for (f, facet) in s.facets.iter().enumerate() {
        let k = facet.nodes();
        for i in 0..k.len() {
            let (a, b) = (
                k[i].min(k[(i + 1) % k.len()]),
                k[i].max(k[(i + 1) % k.len()]),
            );
            let p = lerp(s.nodes[a as usize], s.nodes[b as usize], t);
            let q = smooth.point(p, f);
            if let Some(other) = first.insert((a, b), q) {
                prop_assert!(dist(q, other) < 1e-12, "edge {a}-{b}: {q:?} vs {other:?}");
            }
        }
    }
    Ok(())
}

/// Every facet's patches map points of the flat facet onto themselves.
fn assert_facets_kept(
    s: &Surface,
    smooth: &SmoothSurface,
    b: [f64; 3],
) -> Result<(), TestCaseError> {
    let total = b[0] + b[1] + b[2];
    for (f, facet) in s.facets.iter().enumerate() {
        for sub in 0..smooth.patch_count(f) {
            let c = SmoothSurface::patch_corners(sub).map(|i| s.nodes[facet.nodes()[i] as usize]);
            let p: [f64; 3] =
                std::array::from_fn(|d| (0..3).map(|i| b[i] * c[i][d]).sum::<f64>() / total);
            let q = smooth.point(p, f);
            prop_assert!(dist(p, q) < 1e-12, "facet {f}: {p:?} went to {q:?}");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn patches_interpolate_the_nodes_with_their_normals(
        refinement in 2u32..4,
        amp in 0.0f64..0.08,
        freq in proptest::array::uniform3(0.5f64..2.5),
    ) {
        let s = bumpy_sphere(refinement, amp, freq);
        let smooth = SmoothSurface::new(&s, DEFAULT_FEATURE_ANGLE_DEG);
        for (f, facet) in s.facets.iter().enumerate() {
            let patch = smooth.patch(f, 0);
            for (i, &v) in facet.nodes().iter().enumerate() {
                let mut b = [0.0; 3];
                b[i] = 1.0;
                prop_assert_eq!(patch.point(b), s.nodes[v as usize]);
                if !smooth.is_corner(v as usize) {
                    let (n, want) = (patch.normal(b), smooth.normal(f, i));
                    prop_assert!(dot(n, want) > 1.0 - 1e-12, "facet {f} corner {i}: {n:?} vs {want:?}");
                }
            }
        }
    }

    #[test]
    fn facets_agree_along_their_edges(
        refinement in 2u32..4,
        amp in 0.0f64..0.3,
        freq in proptest::array::uniform3(0.5f64..4.0),
        n in 8usize..40,
        triangles: bool,
        t in 0.0f64..1.0,
    ) {
        // a bump field strong enough to make feature edges on the sphere too
        let sphere = bumpy_sphere(refinement, amp, freq);
        assert_conforming(&sphere, &SmoothSurface::new(&sphere, DEFAULT_FEATURE_ANGLE_DEG), t)?;
        let cyl = cylinder(n, 3, 1.5, triangles);
        prop_assert_eq!(cyl.check(), Ok(()));
        assert_conforming(&cyl, &SmoothSurface::new(&cyl, DEFAULT_FEATURE_ANGLE_DEG), t)?;
        let step = Surface::step(1);
        assert_conforming(&step, &SmoothSurface::new(&step, DEFAULT_FEATURE_ANGLE_DEG), t)?;
    }

    #[test]
    fn flat_input_stays_flat(
        nx in 1usize..6,
        ny in 1usize..6,
        jitter in 0.0f64..0.3,
        seed in 0u64..1000,
        axis in proptest::array::uniform3(-1.0f64..1.0),
        b in proptest::array::uniform3(0.01f64..1.0),
    ) {
        // a jittered grid of triangles in a tilted plane (its rim open: feature edges)
        prop_assume!(dot(axis, axis) > 0.01);
        let len = dot(axis, axis).sqrt();
        let z = axis.map(|x| x / len);
        let helper = if z[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
        let mut x = std::array::from_fn::<f64, 3, _>(|d| helper[d] - dot(helper, z) * z[d]);
        let lx = dot(x, x).sqrt();
        x = x.map(|c| c / lx);
        let y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]];
        let mut nodes = Vec::new();
        let mut r = seed;
        let mut rand = || {
            r = r.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for j in 0..=ny {
            for i in 0..=nx {
                let inner = i > 0 && i < nx && j > 0 && j < ny;
                let (u, v) = if inner {
                    (i as f64 + jitter * rand(), j as f64 + jitter * rand())
                } else {
                    (i as f64, j as f64)
                };
                nodes.push(std::array::from_fn(|d| 3.0 + u * x[d] + v * y[d]));
            }
        }
        let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
        let mut facets = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                facets.push(Facet::tri(id(i, j), id(i + 1, j), id(i + 1, j + 1)));
                facets.push(Facet::tri(id(i, j), id(i + 1, j + 1), id(i, j + 1)));
            }
        }
        let s = Surface::single_patch(nodes, facets, "plane");
        let smooth = SmoothSurface::new(&s, DEFAULT_FEATURE_ANGLE_DEG);
        assert_facets_kept(&s, &smooth, b)?;
    }

    #[test]
    fn a_cube_keeps_its_flat_faces_and_sharp_edges(
        size in 0.1f64..10.0,
        n in 1usize..5,
        triangles: bool,
        b in proptest::array::uniform3(0.01f64..1.0),
    ) {
        let s = Surface::cube(size, n, triangles);
        let smooth = SmoothSurface::new(&s, DEFAULT_FEATURE_ANGLE_DEG);
        prop_assert_eq!(smooth.feature_edge_count(), 12 * n);
        assert_facets_kept(&s, &smooth, b)?;
        let step = Surface::step(1);
        assert_facets_kept(&step, &SmoothSurface::new(&step, DEFAULT_FEATURE_ANGLE_DEG), b)?;
    }
}

#[test]
fn a_cylinder_keeps_its_flat_caps_and_gets_round_rims() {
    for triangles in [false, true] {
        let s = cylinder(24, 4, 2.0, triangles);
        let smooth = SmoothSurface::new(&s, DEFAULT_FEATURE_ANGLE_DEG);
        assert_eq!(smooth.feature_edge_count(), 48);
        let (mut flat, mut curved) = (0.0f64, 0.0f64);
        for (f, facet) in s.facets.iter().enumerate() {
            let k = facet.nodes();
            for i in 0..k.len() {
                let (a, b) = (
                    s.nodes[k[i] as usize],
                    s.nodes[k[(i + 1) % k.len()] as usize],
                );
                let p = lerp(a, b, 0.5);
                let q = smooth.point(p, f);
                if a[2] == b[2] {
                    // a rim or ring edge: on the circle of its z; a cap's edge stays in its plane
                    let r = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1]).sqrt();
                    assert!((q[2] - p[2]).abs() < 1e-14, "facet {f}: {q:?}");
                    if r(a) > 0.5 && r(b) > 0.5 {
                        flat = flat.max(1.0 - r(p));
                        curved = curved.max((1.0 - r(q)).abs());
                    }
                }
            }
        }
        assert!(
            curved < flat / 50.0,
            "rims: chords {flat:e}, curves {curved:e}"
        );
    }
}

/// The acceptance of issue 47 (item 3): on an STL-like sphere (plain triangles, radius 1)
/// the smooth surface's edge midpoints are over 5× nearer the sphere than the chords'.
#[test]
fn a_triangulated_sphere_is_rebuilt_far_closer_than_its_chords() {
    for refinement in [2, 3, 4] {
        let sphere = Surface::sphere(1.0, refinement);
        let tris: Vec<[u32; 3]> = sphere
            .facets
            .iter()
            .map(|f| [f.0[0], f.0[1], f.0[2]])
            .collect();
        let s = Surface::from_triangles(sphere.nodes.clone(), &tris);
        let smooth = SmoothSurface::new(&s, DEFAULT_FEATURE_ANGLE_DEG);
        assert_eq!(smooth.feature_edge_count(), 0);
        let (mut flat, mut curved) = (0.0f64, 0.0f64);
        for (f, facet) in s.facets.iter().enumerate() {
            let k = facet.nodes();
            for i in 0..3 {
                let p = lerp(
                    s.nodes[k[i] as usize],
                    s.nodes[k[(i + 1) % 3] as usize],
                    0.5,
                );
                let q = smooth.point(p, f);
                flat = flat.max((1.0 - dot(p, p).sqrt()).abs());
                curved = curved.max((1.0 - dot(q, q).sqrt()).abs());
            }
        }
        println!(
            "refinement {refinement}: chords' midpoints {flat:.3e} off the sphere, smooth {curved:.3e}"
        );
        assert!(
            curved * 5.0 < flat,
            "refinement {refinement}: {flat:e} vs {curved:e}"
        );
    }
}
