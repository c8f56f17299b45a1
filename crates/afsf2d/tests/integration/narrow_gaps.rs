//! Narrow gaps between bodies (boundary nodes as the pipeline places them): the issue's
//! reproductions as fixed cases, and random 2–3-body domains with gaps of 1e-6 … 0.05. Every
//! mesh must be conforming, positive and cover the domain exactly; a gap the boundary nodes
//! cannot resolve must be refused with the one error that names it.

use crate::common;

use afsf2d::{AfsfError, grow_mesh};
use common::gaps::{self, Domain, Rng};
use common::{check_mesh, summary};
use proptest::prelude::*;

fn mesh(dom: &Domain) -> Result<(afsf2d::AfsfOutput, afsf2d::AngleStats), AfsfError> {
    let (loops, params) = test_cases::mesher_input(&dom.case());
    let out = grow_mesh(&loops, &params)?;
    let q = check_mesh(&loops, &params, &out);
    eprintln!("{}", summary(&dom.label, &out, &q));
    Ok((out, q))
}

/// Before the boundary spacing knew gaps, the nodes across this gap were 0.11 apart and the
/// gap check refused it (a 170.5° triangle without the check); with segments no longer than
/// the gap (`boundary1d`'s gap-width cap) it meshes in usable cells. The refusal itself is
/// tested on hand-placed nodes in `src/gaps.rs`.
#[test]
fn circles_1e_5_apart_meet_in_usable_cells() {
    let dom = gaps::two_bodies(
        gaps::circle([0.0, 0.0], 0.5),
        gaps::circle([1.0 + 1e-5, 0.0], 0.5),
        5e-5,
        1.3,
    );
    let (_, q) = mesh(&dom).expect("a mesh");
    assert!(q.max_angle_deg < 135.0, "{q:?}");
}

#[test]
fn circles_0_01_apart_meet_in_usable_cells() {
    let dom = gaps::two_bodies(
        gaps::circle([0.0, 0.0], 0.5),
        gaps::circle([1.01, 0.0], 0.5),
        5e-5,
        1.3,
    );
    // before: 143.7°
    let (_, q) = mesh(&dom).expect("a mesh");
    assert!(q.max_angle_deg < 135.0, "{q:?}");
}

#[test]
fn unit_squares_1e_7_apart_meet_in_usable_cells_without_layers_in_the_gap() {
    let dom = gaps::two_bodies(
        testkit::shapes::square([0.0, 0.0], 1.0),
        testkit::shapes::square([1.0 + 1e-7, 0.0], 1.0),
        5e-5,
        1.3,
    );
    // before: 175°
    let (out, q) = mesh(&dom).expect("a mesh");
    assert!(q.max_angle_deg < 135.0, "{q:?}");
    // the first layer (5e-5) does not fit in the 1e-7 gap: those facets are bare, and said so
    assert!(out.stats.bare_wall_facets > 0);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, .. ProptestConfig::default() })]
    #[test]
    fn random_narrow_gaps_mesh_validly_or_are_named(seed in any::<u64>(), bodies in 2usize..=3) {
        let mut rng = Rng(seed);
        let Some(dom) = gaps::random_domain(&mut rng, bodies, (1e-6, 0.05), (1e-6, 1e-3)) else {
            return Ok(());
        };
        let case = dom.case();
        let Ok((loops, params)) = std::panic::catch_unwind(|| test_cases::mesher_input(&case)) else {
            return Ok(());
        };
        match grow_mesh(&loops, &params) {
            Ok(out) => {
                let q = check_mesh(&loops, &params, &out);
                eprintln!("{}", summary(&dom.label, &out, &q));
                prop_assert!(q.max_angle_deg < 180.0);
            }
            Err(AfsfError::NarrowGap { .. }) | Err(AfsfError::Misplaced { .. }) | Err(AfsfError::LoopsCross { .. }) => {}
            Err(e) => prop_assert!(false, "{}: {e}", dom.label),
        }
    }
}
