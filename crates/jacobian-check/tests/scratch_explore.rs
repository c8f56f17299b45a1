use jacobian_check::*;
use mesh_model::{CellType, Shape};

fn refnodes(ty: CellType) -> Vec<[f64; 2]> {
    reference_nodes(ty)
        .unwrap()
        .iter()
        .map(|p| [p[0], p[1]])
        .collect()
}

#[test]
fn explore() {
    // P2 random search
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for (ty, tries) in [
        (CellType::new(Shape::Tri, 2), 4000),
        (CellType::new(Shape::Quad, 2), 4000),
    ] {
        let base = refnodes(ty);
        let nc = ty.shape.corners();
        let mut found = 0;
        for _ in 0..tries {
            let dir: Vec<[f64; 2]> = (0..base.len())
                .map(|i| if i < nc { [0.0, 0.0] } else { [rnd(), rnd()] })
                .collect();
            let at = |s: f64| -> Vec<[f64; 2]> {
                base.iter()
                    .zip(&dir)
                    .map(|(b, d)| [b[0] + s * d[0], b[1] + s * d[1]])
                    .collect()
            };
            // bisection on s for dense min det = 0
            let dense = |s: f64| sampled_check(ty, &at(s), 121).unwrap();
            let (mut lo, mut hi) = (0.0, 2.0);
            if dense(hi).min_det > 0.0 {
                continue;
            }
            for _ in 0..50 {
                let m = 0.5 * (lo + hi);
                if dense(m).min_det > 0.0 {
                    lo = m
                } else {
                    hi = m
                }
            }
            let d = dense(hi);
            let p = d.at_min;
            // distance from corners
            let corners = refnodes(CellType::new(ty.shape, 1));
            let dc = corners
                .iter()
                .map(|c| ((c[0] - p[0]).powi(2) + (c[1] - p[1]).powi(2)).sqrt())
                .fold(f64::INFINITY, f64::min);
            if dc > 0.25 && found < 6 {
                found += 1;
                println!("{ty:?} s*={hi:.6} at={p:?} dcorner={dc:.3} dir={dir:?}");
            }
        }
    }
}
