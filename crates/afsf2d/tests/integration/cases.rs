//! The required cases: NACA0012, 30P30N (first heights 5e-6 and 5e-5), a concave loop meshed
//! inside, bodies with sharp convex and concave corners; each at growth 1.3, 1.4 and 1.5.
//! Every mesh must be conforming, cover the domain exactly (area), keep the boundary nodes,
//! have the right first layer, and carry layer, pipe and parent data; NACA0012 at every growth
//! also must have no triangle angle of 135° or more after cutting the quads (the other cases
//! print their figures; see docs/afsf.md for what is still above 135°).

use crate::common;

use afsf2d::{AfsfParams, AngleStats, FrontLoop, grow_mesh};
use common::*;

const GROWTHS: [f64; 3] = [1.3, 1.4, 1.5];

fn run(name: &str, loops: &[FrontLoop], params: &AfsfParams) -> AngleStats {
    let out = grow_mesh(loops, params).unwrap_or_else(|e| panic!("{name}: {e}"));
    let q = check_mesh(loops, params, &out);
    eprintln!("{}", summary(name, &out, &q));
    q
}

fn params(first_height: f64, growth: f64) -> AfsfParams {
    AfsfParams {
        first_height,
        growth,
        ..AfsfParams::default()
    }
}

#[test]
fn naca0012_at_three_growths() {
    let loops = naca0012(0.01);
    for g in GROWTHS {
        let q = run(&format!("naca0012 G{g}"), &loops, &params(5e-5, g));
        assert!(q.max_angle_deg < 135.0, "G{g}: {q:?}");
    }
}

#[test]
fn thirty_p_thirty_n_first_height_5e_5() {
    let loops = three_element(0.01);
    for g in GROWTHS {
        run(&format!("30p30n h5e-5 G{g}"), &loops, &params(5e-5, g));
    }
}

#[test]
fn thirty_p_thirty_n_first_height_5e_6() {
    let loops = three_element(0.01);
    for g in GROWTHS {
        run(&format!("30p30n h5e-6 G{g}"), &loops, &params(5e-6, g));
    }
}

#[test]
fn concave_star_meshed_inside() {
    let loops = star(400);
    for g in GROWTHS {
        let p = AfsfParams {
            inside: true,
            ..params(1e-3, g)
        };
        run(&format!("star inside G{g}"), &loops, &p);
    }
}

#[test]
fn l_shape_with_sharp_corners() {
    let loops = cornered(false, 0.002, 0.02);
    for g in GROWTHS {
        run(&format!("L-shape G{g}"), &loops, &params(1e-3, g));
    }
}

#[test]
fn cross_with_sharp_corners() {
    let loops = cornered(true, 0.002, 0.02);
    for g in GROWTHS {
        run(&format!("cross G{g}"), &loops, &params(1e-3, g));
    }
}
