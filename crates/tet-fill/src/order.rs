//! The insertion order: a biased randomised insertion order (BRIO, Amenta–Choi–Rote) whose
//! rounds double in size and are each sorted along a Morton (Z-order) curve, so that
//! consecutive points are close (short walks) while the rounds keep the randomness that bounds
//! the expected work.

/// The indices of `points` in BRIO order.
pub(crate) fn brio(points: &[[f64; 3]]) -> Vec<u32> {
    let n = points.len();
    let mut order: Vec<u32> = (0..n as u32).collect();
    // a fixed-seed shuffle: runs are reproducible
    let mut s = 0x2545_f491_4f6c_dd1du64;
    for i in (1..n).rev() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        order.swap(i, (s % (i as u64 + 1)) as usize);
    }
    let keys = morton_keys(points);
    let mut end = n;
    while end > 0 {
        let start = if end > 256 { end / 2 } else { 0 };
        order[start..end].sort_unstable_by_key(|&i| keys[i as usize]);
        end = start;
    }
    order
}

/// Each point's Morton code on a 2^21 grid over the bounding box.
fn morton_keys(points: &[[f64; 3]]) -> Vec<u64> {
    let Some(geom_predicates::Aabb { lo, hi }) = geom_predicates::Aabb::of_points(points) else {
        return Vec::new();
    };
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let scale = if extent > 0.0 {
        ((1u64 << 21) - 1) as f64 / extent
    } else {
        0.0
    };
    points
        .iter()
        .map(|p| {
            let c = [0, 1, 2].map(|k| ((p[k] - lo[k]) * scale) as u64);
            spread(c[0]) | (spread(c[1]) << 1) | (spread(c[2]) << 2)
        })
        .collect()
}

/// The 21 low bits of `x` spread to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | (x << 32)) & 0x1f_0000_0000_ffff;
    x = (x | (x << 16)) & 0x1f_0000_ff00_00ff;
    x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x << 2)) & 0x1249_2492_4924_9249;
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_interleaves() {
        assert_eq!(spread(0b11), 0b1001);
        assert_eq!(spread(0x1f_ffff).count_ones(), 21);
    }

    #[test]
    fn brio_is_a_permutation() {
        let points: Vec<[f64; 3]> = (0..1000)
            .map(|i| [i as f64, (i * 7 % 13) as f64, 0.5])
            .collect();
        let mut order = brio(&points);
        order.sort_unstable();
        assert!(order.iter().enumerate().all(|(i, &v)| v as usize == i));
    }
}
