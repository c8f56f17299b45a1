//! The narrow-gap reproductions of the robustness issue, meshed as the pipeline meshes them,
//! with their worst cells listed (`VERBOSE` as in `gap_survey`).
//!
//! `cargo run --release -p afsf2d --example gap_repro`

#[path = "../tests/integration/common/gaps.rs"]
mod gaps;

use afsf2d::{grow_mesh, max_angle_histogram};

fn main() {
    let draw = std::env::var("DRAW").ok();
    let cases = [
        (
            "circles gap 1e-5",
            gaps::two_bodies(
                gaps::circle([0.0, 0.0], 0.5),
                gaps::circle([1.0 + 1e-5, 0.0], 0.5),
                5e-5,
                1.3,
            ),
        ),
        (
            "circles gap 0.01",
            gaps::two_bodies(
                gaps::circle([0.0, 0.0], 0.5),
                gaps::circle([1.01, 0.0], 0.5),
                5e-5,
                1.3,
            ),
        ),
        (
            "squares gap 1e-7",
            gaps::two_bodies(
                testkit::shapes::square([0.0, 0.0], 1.0),
                testkit::shapes::square([1.0 + 1e-7, 0.0], 1.0),
                5e-5,
                1.3,
            ),
        ),
    ];
    for (name, dom) in cases {
        let (loops, params) = test_cases::mesher_input(&dom.case());
        match grow_mesh(&loops, &params) {
            Err(e) => println!("{name}: ERROR {e}"),
            Ok(out) => {
                let q = max_angle_histogram(&out.layered.mesh);
                println!(
                    "{name}: max {:.2} hist {:?} tris {} fill {} peeled {}",
                    q.max_angle_deg,
                    q.histogram,
                    q.triangles,
                    out.stats.fill_triangles,
                    out.stats.peeled_cells
                );
                let m = &out.layered.mesh;
                let mut rows: Vec<(f64, usize)> = (0..m.cells.len())
                    .map(|i| (mesh_model::measure::cell_max_angle_deg(m, i), i))
                    .collect();
                rows.sort_by(|a, b| b.0.total_cmp(&a.0));
                for &(a, ci) in rows.iter().take(6) {
                    let k = m.cells.get(ci).corners().to_vec();
                    let pts: Vec<String> = k
                        .iter()
                        .map(|&g| {
                            format!(
                                "({:.7},{:.7})L{}",
                                m.xy(g)[0],
                                m.xy(g)[1],
                                out.layered.layering.node_layer[g as usize] as i64
                            )
                        })
                        .collect();
                    println!(
                        "   {a:.2} {} {}",
                        if ci >= out.layered.layering.layered_cells {
                            "fill"
                        } else {
                            "layer"
                        },
                        pts.join(" ")
                    );
                }
                if let Some(d) = &draw
                    && name.starts_with(d.split(':').next().unwrap())
                {
                    let hw: f64 = d.split(':').nth(1).unwrap().parse().unwrap();
                    let k = m.cells.get(rows[0].1).corners().to_vec();
                    let at = m.xy(k[0]);
                    let png = mesh_draw::render_png(
                        m,
                        &mesh_draw::DrawParams {
                            view: Some(mesh_draw::view_around([at[0], at[1]], hw)),
                            colour: mesh_draw::ColourBy::MaxAngle,
                            ..Default::default()
                        },
                    )
                    .unwrap();
                    std::fs::write("/tmp/gap_repro.png", png).unwrap();
                }
            }
        }
    }
}
