//! Narrow-gap survey: random multi-body domains (2–4 circles, ellipses and NACA sections at
//! random angles, each placed at a gap of 1e-7 … 0.1 from another, far field r = 20, first
//! heights 1e-7 … 1e-2, growths 1.1–1.5; boundary nodes as the pipeline makes them), meshed
//! by `grow_mesh`. Prints per case the largest angle (quads cut along the shorter diagonal),
//! where the worst cell is (layered or fill, which fronts, how far from the nearest gap) and
//! the distribution over all cases.
//!
//! `cargo run --release -p afsf2d --example gap_survey -- [CASES] [SEED]`
//! (`VERBOSE=1` lists the five worst cells of every case.)

#[path = "../tests/integration/common/gaps.rs"]
mod gaps;

use afsf2d::{AfsfOutput, grow_mesh, max_angle_histogram};
use mesh_model::{NONE, Shape, measure};

/// The worst cell of a mesh, described.
struct Worst {
    angle: f64,
    text: String,
    kind: &'static str,
    at: [f64; 2],
}

fn loop_of(out: &AfsfOutput, loop_start: &[usize], mut g: u32) -> Option<usize> {
    while out.layered.layering.node_parents[g as usize][0] != NONE {
        g = out.layered.layering.node_parents[g as usize][0];
    }
    if out.layered.layering.node_layer[g as usize] == NONE {
        return None;
    }
    Some(loop_start.partition_point(|&s| s <= g as usize) - 1)
}

fn worst_cells(out: &AfsfOutput, loop_start: &[usize], gaps: &[gaps::Gap], k: usize) -> Vec<Worst> {
    let m = &out.layered.mesh;
    let mut rows: Vec<(f64, usize)> = (0..m.cells.len())
        .map(|i| (measure::cell_max_angle_deg(m, i), i))
        .collect();
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    rows.truncate(k);
    rows.into_iter()
        .map(|(angle, ci)| {
            let c = m.cells.get(ci);
            let nodes = c.corners();
            let fill = ci >= out.layered.layering.layered_cells;
            let kind = if fill {
                if nodes.iter().any(|&g| out.layered.layering.node_layer[g as usize] == NONE) {
                    "fill+steiner"
                } else {
                    "fill"
                }
            } else if c.ty.shape == Shape::Quad {
                "quad"
            } else {
                "layer-tri"
            };
            let cx = nodes.iter().map(|&g| m.xy(g)[0]).sum::<f64>() / nodes.len() as f64;
            let cy = nodes.iter().map(|&g| m.xy(g)[1]).sum::<f64>() / nodes.len() as f64;
            let mut fronts: Vec<usize> = nodes
                .iter()
                .filter_map(|&g| loop_of(out, loop_start, g))
                .collect();
            fronts.sort_unstable();
            fronts.dedup();
            let layers: Vec<String> = nodes
                .iter()
                .map(|&g| match out.layered.layering.node_layer[g as usize] {
                    NONE => "F".to_string(),
                    l => l.to_string(),
                })
                .collect();
            let near = gaps
                .iter()
                .map(|g| (((g.at[0] - cx).powi(2) + (g.at[1] - cy).powi(2)).sqrt(), g))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let gap_text = near.map_or(String::new(), |(d, g)| {
                format!("gap {}-{} w {:.1e} at dist {:.1e}", g.a, g.b, g.width, d)
            });
            let lens: Vec<String> = (0..nodes.len())
                .map(|i| {
                    let (a, b) = (m.xy(nodes[i]), m.xy(nodes[(i + 1) % nodes.len()]));
                    format!("{:.1e}", ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt())
                })
                .collect();
            Worst {
                angle,
                kind,
                at: [cx, cy],
                text: format!(
                    "{angle:6.2} {kind:12} ({cx:.4},{cy:.4}) fronts {fronts:?} layers {layers:?} sides {lens:?} {gap_text}"
                ),
            }
        })
        .collect()
}

/// `DRAW=k:halfwidth` draws case k around its worst cell into /tmp/gap_k.png.
fn draw_here(case: usize) -> Option<f64> {
    let v = std::env::var("DRAW").ok()?;
    let (k, hw) = v.split_once(':')?;
    (k.parse::<usize>().ok()? == case).then(|| hw.parse().ok())?
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let cases: usize = args.get(1).map_or(40, |s| s.parse().expect("CASES"));
    let seed: u64 = args.get(2).map_or(1, |s| s.parse().expect("SEED"));
    let verbose = std::env::var("VERBOSE").is_ok();
    let mut rng = gaps::Rng(seed);
    let mut worst_all = Vec::new();
    let mut kinds: std::collections::BTreeMap<&str, usize> = Default::default();
    let (mut errors, mut over135, mut over150) = (0, 0, 0);
    let mut done = 0;
    let mut flagged: Vec<f64> = Vec::new();
    let t0 = std::time::Instant::now();
    while done < cases {
        let bodies = rng.int(2, 4);
        let Some(dom) = gaps::random_domain(&mut rng, bodies, (1e-7, 0.1), (1e-7, 1e-2)) else {
            continue;
        };
        let case = dom.case();
        let (loops, mut params) = match std::panic::catch_unwind(|| test_cases::mesher_input(&case))
        {
            Ok(input) => input,
            Err(_) => {
                println!("skip: boundary mesh failed ({})", dom.label);
                continue;
            }
        };
        done += 1;
        // `REFUSE=1` keeps the default refusal of unresolved gaps; else they are meshed and
        // the gap check's verdict is printed next to the angle it predicted
        params.refuse_narrow_gaps = std::env::var("REFUSE").is_ok();
        let min_gap = dom
            .gaps
            .iter()
            .map(|g| g.width)
            .fold(f64::INFINITY, f64::min);
        let head = format!(
            "#{done:3} {} | h {:.1e} G {:.2} min gap {:.1e}",
            dom.label, dom.first_height, dom.growth, min_gap
        );
        let t = std::time::Instant::now();
        let out = match grow_mesh(&loops, &params) {
            Ok(o) => o,
            Err(e) => {
                errors += 1;
                println!("{head} | ERROR {e}");
                continue;
            }
        };
        let dt = t.elapsed().as_secs_f64();
        let q = max_angle_histogram(&out.layered.mesh);
        let mut loop_start = vec![0usize];
        for l in &loops {
            loop_start.push(loop_start.last().unwrap() + l.points.len());
        }
        let ws = worst_cells(&out, &loop_start, &dom.gaps, if verbose { 5 } else { 1 });
        worst_all.push(q.max_angle_deg);
        if q.max_angle_deg >= 135.0 {
            over135 += 1;
            *kinds.entry(ws[0].kind).or_default() += 1;
        }
        if q.max_angle_deg >= 150.0 {
            over150 += 1;
        }
        let verdict = out.stats.unresolved_gap.map_or("gap ok".to_string(), |g| {
            format!(
                "GAP {:.0}° w {:.1e} s {:.1e}",
                g.best_angle_deg, g.width, g.spacing
            )
        });
        if out.stats.unresolved_gap.is_some() {
            flagged.push(q.max_angle_deg);
        }
        println!(
            "{head} | max {:.2} hist {:?} tris {} bare {} {dt:.2}s | {verdict} | {}",
            q.max_angle_deg, q.histogram, q.triangles, out.stats.bare_wall_facets, ws[0].text
        );
        if let Some(hw) = draw_here(done) {
            let png = mesh_draw::render_png(
                &out.layered.mesh,
                &mesh_draw::DrawParams {
                    view: Some(mesh_draw::view_around(ws[0].at, hw)),
                    colour: mesh_draw::ColourBy::MaxAngle,
                    ..Default::default()
                },
            )
            .expect("a picture");
            std::fs::write(format!("/tmp/gap_{done}.png"), png).expect("write the picture");
        }
        if verbose {
            for w in &ws[1..] {
                println!("      {}", w.text);
            }
        }
        let _ = ws[0].angle;
    }
    worst_all.sort_by(f64::total_cmp);
    flagged.sort_by(f64::total_cmp);
    println!(
        "flagged by the gap check: {} cases, their worst angles {flagged:.0?}",
        flagged.len()
    );
    println!(
        "cases {done} meshed {} errors {errors} | worst angle median {:.1} p90 {:.1} max {:.1} | >=135: {over135} >=150: {over150} | worst cell kinds (>=135) {kinds:?} | {:.0}s",
        worst_all.len(),
        quantile(&worst_all, 0.5),
        quantile(&worst_all, 0.9),
        worst_all.last().copied().unwrap_or(f64::NAN),
        t0.elapsed().as_secs_f64()
    );
}
