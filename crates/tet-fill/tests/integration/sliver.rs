//! Sliver removal: refined fills with no dihedral angle above 160° (the target is 150°),
//! where the same fills without it have flat tets.

use crate::common::*;
use tet_fill::{Fill, FillInput, FillOptions, fill};

fn run(points: &[[f64; 3]], facets: &[[u32; 3]], target: f64) -> Fill {
    let options = FillOptions {
        max_dihedral_deg: target,
        ..FillOptions::default()
    };
    let out = fill(&FillInput { points, facets }, &options).unwrap();
    check_fill(points, facets, &out);
    let worst = out
        .tets
        .iter()
        .map(|t| max_dihedral(&out.points, *t))
        .fold(0.0, f64::max);
    assert!((worst - out.max_dihedral_deg).abs() < 1e-6);
    out
}

/// Checks a refined fill with and without sliver removal.
fn check_improved(points: &[[f64; 3]], facets: &[[u32; 3]]) {
    let plain = run(points, facets, 180.0);
    let improved = run(points, facets, 150.0);
    println!(
        "largest dihedral: {:.2}° without sliver removal, {:.2}° with ({} tets)",
        plain.max_dihedral_deg,
        improved.max_dihedral_deg,
        improved.tets.len()
    );
    assert!(
        plain.max_dihedral_deg > 160.0,
        "the case has no sliver to remove"
    );
    assert!(improved.max_dihedral_deg <= 160.0);
}

#[test]
fn refined_sphere_in_a_box_has_no_sliver() {
    let mut p = Vec::new();
    let mut f = Vec::new();
    append(&mut p, &mut f, grid_box([-3.0; 3], [3.0; 3], 3), true);
    append(&mut p, &mut f, icosphere([0.0; 3], 1.0, 2), false);
    check_improved(&p, &f);
}

#[test]
fn refined_two_bodies_in_a_box_have_no_sliver() {
    let mut p = Vec::new();
    let mut f = Vec::new();
    append(&mut p, &mut f, grid_box([-3.0; 3], [3.0; 3], 4), true);
    append(&mut p, &mut f, icosphere([-1.0, 0.0, 0.0], 0.8, 2), false);
    append(
        &mut p,
        &mut f,
        grid_box([0.5, -0.5, -0.5], [1.5, 0.5, 0.5], 3),
        false,
    );
    check_improved(&p, &f);
}

#[test]
fn sphere_in_a_large_sphere_has_no_sliver() {
    let mut p = Vec::new();
    let mut f = Vec::new();
    append(&mut p, &mut f, icosphere([0.0; 3], 20.0, 2), true);
    append(&mut p, &mut f, icosphere([0.3, -0.2, 0.1], 1.0, 3), false);
    check_improved(&p, &f);
}
