//! The required cases: NACA0012, 30P30N, a concave loop meshed inside, bodies with sharp
//! corners, each at growth 1.3, 1.4 and 1.5; every mesh must be conforming, cover the domain
//! exactly, keep the boundary nodes, have the right first layer and no triangle angle of
//! 135° or more after cutting the quads.

mod common;

use afsf2d::{AfsfParams, grow_mesh};
use common::*;

fn run(name: &str, loops: &[afsf2d::FrontLoop], params: &AfsfParams) -> afsf2d::AngleStats {
    let out = grow_mesh(loops, params).unwrap_or_else(|e| panic!("{name}: {e}"));
    let q = check_mesh(loops, params, &out);
    eprintln!("{}", summary(name, &out, &q));
    q
}

#[test]
fn naca0012_smoke() {
    let loops = naca0012(0.01);
    let params = AfsfParams {
        first_height: 5e-5,
        growth: 1.3,
        ..AfsfParams::default()
    };
    let q = run("naca0012 G1.3", &loops, &params);
    assert!(q.triangles > 0);
}
