//! Every built-in case (the 30P30N at its first height of 5e-6 included), grown as the
//! pipeline grows it and curved at P2 and P3, mixed and cut into triangles, with both vector
//! strategies on two cases: every cell certified valid, the mesh conforming, the boundary's
//! high-order nodes on their curves, the area of the cells equal to the area the curved
//! boundary encloses, a curved-edge fraction in (0, 0.5), and the first `min_curved_layers`
//! layers above curved wall edges curved. A table of the runs goes to stderr.

use crate::common;

use std::time::Instant;

use common::{Checked, check_curved, curved_layers_above_walls};
use test_cases::{grow, real_case, real_cases};
use vector_adding::{Curved, CurvingParams, Strategy};

/// One curving run: order, cut into triangles, strategy.
type Run = (u8, bool, Strategy);

fn row(name: &str, run: Run, curved: &Curved, c: &Checked, seconds: f64) -> String {
    let s = &curved.stats;
    format!(
        "{name:<12} P{} {:<5} {:<10} {:>7} {:>8.4} {:>6} {:>6} {:>6} {:>4} {:>6} {:>5} {:>5} {:>8.4} {:>7.3}",
        run.0,
        if run.1 { "tri" } else { "mixed" },
        match run.2 {
            Strategy::TwoVector => "two-vector",
            Strategy::OneVector => "one-vector",
        },
        curved.mesh.cells.len(),
        c.fraction,
        s.stops.jacobian,
        s.stops.collapsed,
        s.stops.pipe_ended,
        s.stops.invalid,
        s.reduced_tops,
        s.repaired_cells,
        s.curved_diagonals,
        c.validity.min_scaled_jacobian,
        seconds,
    )
}

const HEADER: &str = "case         P  cut   strategy     cells  curved    jac   coll  ended  inv reduced repair  diag   min SJ curve s";

fn case(name: &str, both_strategies: bool) {
    let case = real_case(name);
    let g = grow(&case);
    let mut runs: Vec<Run> = Vec::new();
    for order in [2, 3] {
        for triangles in [false, true] {
            runs.push((order, triangles, Strategy::TwoVector));
            if both_strategies {
                runs.push((order, triangles, Strategy::OneVector));
            }
        }
    }
    let mut table = vec![format!(
        "{name}: {} linear cells ({} layered)",
        g.output.layered.mesh.cells.len(),
        g.output.layered.layering.layered_cells
    )];
    table.push(HEADER.to_string());
    for run in runs {
        let (order, triangles, strategy) = run;
        let params = CurvingParams {
            order,
            triangles,
            strategy,
            ..CurvingParams::default()
        };
        let what = format!("{name} P{order} triangles={triangles} {strategy:?}");
        let t0 = Instant::now();
        let curved = g.curve(&params).unwrap_or_else(|e| panic!("{what}: {e}"));
        let seconds = t0.elapsed().as_secs_f64();
        let c = check_curved(&what, &curved, &g.curves, order);
        if name == "lshape" {
            // straight walls: only the far-field circle and the layers above it are curved
            assert!(
                c.fraction > 0.0 && c.fraction < 0.5,
                "{what}: {}",
                c.fraction
            );
        } else {
            assert!(
                c.fraction > 1e-3 && c.fraction < 0.5,
                "{what}: curved-edge fraction {}",
                c.fraction
            );
        }
        let layers = curved_layers_above_walls(&g.output, &curved.mesh, params.min_curved_layers);
        table.push(row(name, run, &curved, &c, seconds));
        table.push(format!(
            "    curved walls {}, pipes reaching {} layers {} (ended {:?}), straight bottoms below that {:?}",
            layers.curved_walls,
            params.min_curved_layers,
            layers.full_pipes,
            layers.ended,
            layers.early.iter().take(5).collect::<Vec<_>>()
        ));
        // the built-in cases never need to stop a wall pipe early (the full deviation is
        // always valid that close to the wall), so every such bottom edge is curved
        assert!(
            layers.early.is_empty(),
            "{what}: {} straight bottom edges below layer {} above curved walls: {:?}",
            layers.early.len(),
            params.min_curved_layers,
            layers.early.iter().take(5).collect::<Vec<_>>()
        );
        if name != "lshape" {
            assert!(layers.curved_walls > 0, "{what}: no curved wall edge");
            assert!(layers.full_pipes > 0, "{what}: no pipe reaches its layers");
            assert!(
                curved.stats.deepest_curved_layer >= params.min_curved_layers,
                "{what}: deepest curved layer {}",
                curved.stats.deepest_curved_layer
            );
        }
    }
    eprintln!("{}", table.join("\n"));
}

#[test]
fn every_builtin_case_has_a_test() {
    assert_eq!(real_cases().len(), 5);
}

#[test]
fn naca0012() {
    case("naca0012", true);
}

#[test]
fn two_element() {
    case("two-element", true);
}

#[test]
fn bat_inside() {
    case("bat", false);
}

#[test]
fn lshape() {
    case("lshape", false);
}

#[test]
fn thirty_p_thirty_n() {
    case("30p30n", false);
}
