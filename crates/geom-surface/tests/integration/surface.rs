//! The built-in surfaces pass every check and converge to their exact volumes; each kind of
//! bad surface gets its one-line error.

use geom_surface::{Facet, Surface, SurfaceError};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn spheres_are_closed_oriented_and_converge(radius in 0.1f64..10.0, refinement in 0u32..4) {
        let s = Surface::sphere(radius, refinement);
        prop_assert_eq!(s.check(), Ok(()));
        prop_assert_eq!(s.facets.len(), 20 * 4usize.pow(refinement));
        let exact = 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
        let v = s.enclosed_volume();
        // an inscribed polyhedron: below the sphere, the gap shrinking about 4× per refinement
        prop_assert!(v < exact && exact - v < 0.7 * exact / 4f64.powi(refinement as i32));
        for (n, p) in s.node_normals().iter().zip(&s.nodes) {
            let radial = p.map(|x| x / radius);
            prop_assert!((n[0] * radial[0] + n[1] * radial[1] + n[2] * radial[2]) > 0.98);
        }
    }

    #[test]
    fn cubes_and_steps_are_exact(size in 0.1f64..10.0, n in 1usize..6, triangles: bool) {
        let s = Surface::cube(size, n, triangles);
        prop_assert_eq!(s.check(), Ok(()));
        prop_assert_eq!(s.facets.len(), 6 * n * n * if triangles { 2 } else { 1 });
        let v = s.enclosed_volume();
        prop_assert!((v - size.powi(3)).abs() < 1e-12 * size.powi(3));
        prop_assert!((s.area() - 6.0 * size * size).abs() < 1e-12 * size * size);
    }
}

#[test]
fn the_step_is_a_block_with_a_tower() {
    for refine in [1, 2] {
        let s = Surface::step(refine);
        assert_eq!(s.check(), Ok(()));
        let v = s.enclosed_volume();
        assert!((v - (0.5 + 0.4 * 0.4 * 0.5)).abs() < 1e-12, "{v}");
    }
}

fn assert_error(s: &Surface, want: impl Fn(&SurfaceError) -> bool) {
    let e = s.check().expect_err("a bad surface");
    assert!(want(&e), "{e:?}");
    let line = e.to_string();
    assert!(!line.contains('\n') && !line.is_empty(), "{line}");
}

#[test]
fn bad_surfaces_get_one_line_errors() {
    let good = Surface::cube(1.0, 2, true);
    let mut open = good.clone();
    open.facets.pop();
    open.facet_patch.pop();
    assert_error(&open, |e| matches!(e, SurfaceError::Open { .. }));

    let mut inverted = good.clone();
    for f in &mut inverted.facets {
        f.0.swap(0, 1);
    }
    assert_error(&inverted, |e| matches!(e, SurfaceError::Inverted { .. }));

    let mut flipped = good.clone();
    flipped.facets[3].0.swap(0, 1);
    assert_error(&flipped, |e| matches!(e, SurfaceError::Misoriented { .. }));

    let mut doubled = good.clone();
    doubled.facets.push(good.facets[0]);
    doubled.facet_patch.push(0);
    assert_error(&doubled, |e| matches!(e, SurfaceError::NonManifold { .. }));

    let mut nan = good.clone();
    nan.nodes[5][1] = f64::NAN;
    assert_error(&nan, |e| *e == SurfaceError::NonFinite { node: 5 });

    let mut bad = good.clone();
    bad.facets[0] = Facet::tri(0, 0, 1);
    assert_error(&bad, |e| *e == SurfaceError::BadFacet { facet: 0 });

    let mut flat = good.clone();
    let [a, b, _, _] = flat.facets[0].0;
    flat.nodes[flat.facets[0].0[2] as usize] = {
        let (p, q) = (flat.nodes[a as usize], flat.nodes[b as usize]);
        std::array::from_fn(|d| 2.0 * q[d] - p[d])
    };
    assert!(flat.check().is_err());

    assert_error(&Surface::from_triangles(vec![], &[]), |e| {
        *e == SurfaceError::Empty
    });
}

#[test]
fn two_overlapping_spheres_intersect() {
    let a = Surface::sphere(1.0, 1);
    let b = Surface::sphere(1.0, 1);
    let offset = a.nodes.len() as u32;
    let mut nodes = a.nodes.clone();
    nodes.extend(
        b.nodes
            .iter()
            .map(|p| [p[0] + 0.5, p[1] + 0.01, p[2] - 0.02]),
    );
    let mut tris: Vec<[u32; 3]> = a.facets.iter().map(|f| [f.0[0], f.0[1], f.0[2]]).collect();
    b.facets
        .iter()
        .for_each(|f| tris.push([f.0[0] + offset, f.0[1] + offset, f.0[2] + offset]));
    let s = Surface::from_triangles(nodes.clone(), &tris);
    assert_error(&s, |e| matches!(e, SurfaceError::SelfIntersecting { .. }));
    // every crossing pair, each once, the check's among them, one facet of each body
    let all = geom_surface::self_intersections(&s.nodes, &s.facets);
    assert!(all.len() > 10, "{}", all.len());
    assert!(all.windows(2).all(|w| w[0] < w[1]));
    let first = geom_surface::first_self_intersection(&s.nodes, &s.facets).unwrap();
    assert!(all.contains(&first));
    let faces = a.facets.len();
    assert!(all.iter().all(|&(f, g)| f < faces && g >= faces));
    // apart, the two spheres are a valid surface of two bodies
    let apart: Vec<[f64; 3]> = nodes
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if i >= offset as usize {
                [p[0] + 3.0, p[1], p[2]]
            } else {
                *p
            }
        })
        .collect();
    assert_eq!(Surface::from_triangles(apart, &tris).check(), Ok(()));
}

#[test]
fn a_folded_surface_intersects_itself() {
    // a cube whose one corner is pushed through the opposite face
    let mut s = Surface::cube(1.0, 2, true);
    let corner = s.nodes.iter().position(|p| *p == [1.0, 1.0, 1.0]).unwrap();
    s.nodes[corner] = [-0.3, -0.2, -0.4];
    assert!(matches!(
        s.check(),
        Err(SurfaceError::SelfIntersecting { .. }) | Err(SurfaceError::Inverted { .. })
    ));
}

/// `a` and `b` (moved by `shift` and scaled by `scale` about the origin first) as one
/// surface of two bodies, `b`'s patches after `a`'s.
fn two_bodies(a: &Surface, b: &Surface, scale: f64, shift: [f64; 3]) -> Surface {
    let mut s = a.clone();
    let (n, p) = (a.nodes.len() as u32, a.patches.len() as u32);
    s.nodes.extend(
        b.nodes
            .iter()
            .map(|q| std::array::from_fn(|d| scale * q[d] + shift[d])),
    );
    s.facets.extend(b.facets.iter().map(|f| {
        let mut k = f.0;
        k.iter_mut()
            .filter(|v| **v != geom_surface::NO_NODE)
            .for_each(|v| *v += n);
        Facet(k)
    }));
    s.facet_patch.extend(b.facet_patch.iter().map(|&q| q + p));
    s.patches.extend(b.patches.iter().cloned());
    s
}

#[test]
fn a_body_inside_another_is_named_and_bodies_side_by_side_pass() {
    let sphere = Surface::sphere(1.0, 2);
    let mut inner = Surface::sphere(1.0, 1);
    inner.patches[0].name = "inner".into();
    let nested = two_bodies(&sphere, &inner, 0.5, [0.1, 0.0, 0.0]);
    let e = nested.check().unwrap_err();
    assert_eq!(
        e.to_string(),
        "the surface's body 2 (group \"inner\", facet 320) lies inside body 1 (group \"wall\", \
         facet 0): bodies must lie side by side"
    );
    // the outer body listed second: the same two named the other way round
    let nested = two_bodies(&inner, &sphere, 2.0, [0.0; 3]);
    assert!(matches!(
        nested.check(),
        Err(SurfaceError::NestedBody {
            body: 1,
            outer: 2,
            ..
        })
    ));
    // a cube of quads inside a cube of quads
    let cubes = two_bodies(
        &Surface::cube(1.0, 2, false),
        &Surface::cube(1.0, 1, false),
        0.25,
        [0.3, 0.4, 0.5],
    );
    assert_error(&cubes, |e| matches!(e, SurfaceError::NestedBody { .. }));
    // side by side, and one in the other's bounding box but outside it (a corner's notch)
    let apart = two_bodies(&sphere, &inner, 0.5, [2.0, 0.0, 0.0]);
    assert_eq!(apart.check(), Ok(()));
    let step = Surface::step(1);
    let notch = two_bodies(&step, &Surface::cube(1.0, 1, true), 0.2, [0.05, 0.05, 0.75]);
    assert_eq!(notch.check(), Ok(()));
}

#[test]
fn an_inverted_body_beside_a_larger_one_is_named() {
    let sphere = Surface::sphere(1.0, 2);
    let mut small = Surface::sphere(1.0, 1);
    small.facets.iter_mut().for_each(|f| f.0.swap(0, 1));
    let s = two_bodies(&sphere, &small, 0.3, [3.0, 0.0, 0.0]);
    assert_error(&s, |e| {
        matches!(
            e,
            SurfaceError::InvertedBody {
                body: 2,
                facet: 320,
                ..
            }
        )
    });
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Two spheres: refused when the smaller lies inside the larger, accepted when apart.
    #[test]
    fn spheres_are_nested_or_apart(
        r in 0.05f64..0.6,
        dir in proptest::array::uniform3(-1.0f64..1.0),
        reach in 0.0f64..1.0,
        inside: bool,
    ) {
        let l = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt().max(1e-3);
        // inside: the centre at most 0.9 - r from the origin (the facets' inradius is 0.95);
        // apart: at least 1 + r + 0.05
        let d = if inside { reach * (0.9 - r).max(0.0) } else { 1.05 + r + reach };
        let shift = dir.map(|x| x / l * d);
        let s = two_bodies(&Surface::sphere(1.0, 2), &Surface::sphere(1.0, 1), r, shift);
        let got = s.check();
        if inside {
            prop_assert!(matches!(got, Err(SurfaceError::NestedBody { body: 2, outer: 1, .. })), "{got:?}");
        } else {
            prop_assert_eq!(got, Ok(()));
        }
    }
}
