//! The shape functions: Gmsh's reference nodes, the Kronecker and partition-of-unity
//! properties, and gradients against finite differences.

use jacobian_check::{
    JacobianError, reference_nodes, shape_functions, shape_gradients, supported_types,
};
use mesh_io::msh::cell_type_of_gmsh;
use mesh_io::node_order::gmsh_reference_nodes;
use mesh_model::{CellType, Shape};
use proptest::prelude::*;

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < tol)
}

#[test]
fn reference_nodes_are_gmsh_s_own() {
    // As dumped from Gmsh 4.15 by mesh-io's script (`getElementProperties`; the 40-node
    // prism's from a mesh Gmsh raised to order 3, its nodes placed along the geometry to
    // about 2e-12).
    let text = include_str!("../../../mesh-io/tests/data/reference_nodes.json");
    let json: serde_json::Value = serde_json::from_str(text).unwrap();
    let mut checked = 0;
    for e in json["gmsh"].as_array().unwrap() {
        let ty = cell_type_of_gmsh(e["type"].as_u64().unwrap() as u32).unwrap();
        let Ok(ours) = reference_nodes(ty) else {
            continue;
        };
        let theirs = e["nodes"].as_array().unwrap();
        assert_eq!(ours.len(), theirs.len(), "{ty:?}");
        for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
            let b = [0, 1, 2].map(|i| b[i].as_f64().unwrap());
            assert!(
                close(*a, b, 1e-11),
                "{ty:?} node {k}: ours {a:?}, Gmsh {b:?}"
            );
        }
        checked += 1;
    }
    // tri, quad, tet, prism, hex and pyramid of orders 1-3.
    assert_eq!(checked, 18);
    for ty in supported_types() {
        let theirs = gmsh_reference_nodes(ty).unwrap();
        let ours = reference_nodes(ty).unwrap();
        assert!(
            ours.iter().zip(&theirs).all(|(a, b)| close(*a, *b, 1e-12)),
            "{ty:?}"
        );
    }
}

#[test]
fn each_shape_function_is_one_at_its_node_and_zero_at_the_others() {
    for ty in supported_types() {
        let nodes = reference_nodes(ty).unwrap();
        for (j, x) in nodes.iter().enumerate() {
            let n = shape_functions(ty, *x).unwrap();
            for (i, v) in n.iter().enumerate() {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((v - e).abs() < 1e-12, "{ty:?}: N{i}(node {j}) = {v}");
            }
        }
    }
}

#[test]
fn unsupported_types_are_errors_not_panics() {
    for ty in [
        CellType::new(Shape::Pyramid, 4),
        CellType::new(Shape::Tet, 4),
        CellType::new(Shape::Line, 2),
        CellType::new(Shape::Tri, 4),
    ] {
        assert!(
            matches!(
                shape_functions(ty, [0.1, 0.1, 0.1]),
                Err(JacobianError::Unsupported { .. })
            ),
            "{ty:?}"
        );
        assert!(matches!(
            reference_nodes(ty),
            Err(JacobianError::Unsupported { .. })
        ));
    }
}

/// A point inside the reference cell of `shape` from three numbers in [0, 1).
fn inside(shape: Shape, a: f64, b: f64, c: f64) -> [f64; 3] {
    let s = |t: f64| 2.0 * t - 1.0;
    match shape {
        Shape::Tri => [a * (1.0 - b), b, 0.0],
        Shape::Quad => [s(a), s(b), 0.0],
        Shape::Tet => [a * (1.0 - b) * (1.0 - c), b * (1.0 - c), c],
        Shape::Prism => [a * (1.0 - b), b, s(c)],
        Shape::Hex => [s(a), s(b), s(c)],
        // Keep away from the apex, where the rational functions are singular.
        Shape::Pyramid => {
            let w = 0.9 * c;
            [(1.0 - w) * s(a), (1.0 - w) * s(b), w]
        }
        Shape::Line => [s(a), 0.0, 0.0],
    }
}

proptest! {
    #[test]
    fn shape_functions_sum_to_one_and_gradients_match_finite_differences(
        a in 0.0..1.0f64, b in 0.0..1.0f64, c in 0.0..1.0f64,
    ) {
        for ty in supported_types() {
            let x = inside(ty.shape, a, b, c);
            let n = shape_functions(ty, x).unwrap();
            prop_assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{:?}", ty);
            let g = shape_gradients(ty, x).unwrap();
            let h = 1e-6;
            for k in 0..ty.shape.dim() as usize {
                let (mut xp, mut xm) = (x, x);
                xp[k] += h;
                xm[k] -= h;
                let (np, nm) = (shape_functions(ty, xp).unwrap(), shape_functions(ty, xm).unwrap());
                for i in 0..n.len() {
                    let fd = (np[i] - nm[i]) / (2.0 * h);
                    prop_assert!((fd - g[i][k]).abs() < 1e-6, "{:?} N{} d/dx{}: {} vs {}", ty, i, k, g[i][k], fd);
                }
            }
            let total: [f64; 3] = [0, 1, 2].map(|k| g.iter().map(|gi| gi[k]).sum());
            prop_assert!(total.iter().all(|t| t.abs() < 1e-10), "{:?}: {:?}", ty, total);
        }
    }
}

#[test]
fn the_equispaced_line_basis_interpolates_and_sums_to_one() {
    use jacobian_check::lagrange::equispaced_line;
    for p in 1..=3usize {
        for j in 0..=p {
            let (l, _) = equispaced_line(p, j as f64 / p as f64);
            for (k, v) in l.iter().enumerate().take(p + 1) {
                assert!(
                    (v - f64::from(u8::from(k == j))).abs() < 1e-14,
                    "P{p} node {j}: {l:?}"
                );
            }
        }
        for s in [0.1, 0.37, 0.9] {
            let (l, dl) = equispaced_line(p, s);
            assert!((l.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(dl.iter().sum::<f64>().abs() < 1e-12);
            // the basis reproduces x(s) = s, so its derivatives weight the nodes to 1
            let slope: f64 = (0..=p).map(|j| dl[j] * j as f64 / p as f64).sum();
            assert!((slope - 1.0).abs() < 1e-12, "P{p} at {s}: {slope}");
        }
    }
}
