//! The compass search the local passes over a layer's children share (`repair`, `shape`): a
//! child tried at ± each move, the step halving from a quarter of the moves.

/// Searches from `start` along ± each of `moves` (scaled by a step from 0.25, halved
/// `halvings` times, at most `rounds` rounds at each step while one is taken): `take(y)`
/// tries the place `y` and says whether it is kept. Returns the last place kept (`start`
/// when none).
pub(crate) fn compass_search(
    start: [f64; 3],
    moves: &[[f64; 3]],
    (halvings, rounds): (usize, usize),
    mut take: impl FnMut([f64; 3]) -> bool,
) -> [f64; 3] {
    let mut x = start;
    let mut step = 0.25;
    for _ in 0..halvings {
        let mut improved = true;
        let mut round = 0;
        while improved && round < rounds {
            improved = false;
            round += 1;
            for m in moves {
                for sign in [1.0, -1.0] {
                    let y: [f64; 3] = std::array::from_fn(|d| x[d] + sign * step * m[d]);
                    if take(y) {
                        x = y;
                        improved = true;
                    }
                }
            }
        }
        step /= 2.0;
    }
    x
}
