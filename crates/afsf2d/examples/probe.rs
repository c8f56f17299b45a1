//! Profiling aid: meshes a built-in case (boundary nodes as the pipeline makes them) and lists
//! where the triangles with a large angle are, or draws a PNG around a point.
//!
//! `cargo run --release -p afsf2d --example probe -- CASE [GROWTH] [FIRST_HEIGHT] [x y halfwidth out.png]`

#[path = "../tests/integration/common/real.rs"]
mod real;

use afsf2d::{grow_mesh, max_angle_histogram, max_triangle_angle_deg};
use mesh_model::{NONE, Shape};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map(String::as_str).unwrap_or("naca0012");
    let growth: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(1.3);
    let case = real::real_case(name);
    let h: f64 = args
        .get(3)
        .map(|s| s.parse().unwrap())
        .unwrap_or(case.layers.first_height);
    let (loops, params) = real::mesher_input(&real::with_layers(&case, h, growth));
    let t = std::time::Instant::now();
    let out = grow_mesh(&loops, &params).unwrap();
    let dt = t.elapsed().as_secs_f64();
    let q = max_angle_histogram(&out.layered.mesh);
    let s = &out.stats;
    println!(
        "{name} G{growth} h{h:e}: tris {} max {:.1} hist {:?} time {dt:.3}s (solve {:.3} plan {:.3} build {:.3} verify {:.3} fill {:.3}) iters {} layers {} fill {}",
        q.triangles,
        q.max_angle_deg,
        q.histogram,
        s.timings.solve,
        s.timings.plan_and_closing,
        s.timings.build,
        s.timings.verify,
        s.timings.fill,
        s.iterations,
        s.layers,
        s.fill_triangles
    );
    let m = &out.layered.mesh;
    let n_layer_cells = m.cells.len() - s.fill_triangles;
    let nb = m.boundary.len();
    let lay = |g: u32| out.layered.layering.node_layer[g as usize];
    let threshold: f64 = std::env::var("PROBE_MIN")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(125.0);
    let mut rows = Vec::new();
    for (ci, c) in m.cells.iter().enumerate() {
        let k = c.corners();
        let tris: Vec<[u32; 3]> = if c.ty.shape == Shape::Quad {
            mesh_model::measure::split_quad_shorter_diagonal(m, k).to_vec()
        } else {
            vec![[k[0], k[1], k[2]]]
        };
        let worst = tris
            .iter()
            .map(|t| max_triangle_angle_deg(m.xy(t[0]), m.xy(t[1]), m.xy(t[2])))
            .fold(0.0, f64::max);
        if worst < threshold {
            continue;
        }
        let kind = if ci >= n_layer_cells {
            let fill_nodes = k.iter().filter(|&&g| lay(g) == NONE).count();
            format!("fill({fill_nodes} steiner)")
        } else if c.ty.shape == Shape::Quad {
            "quad".to_string()
        } else {
            let lo = k.iter().map(|&g| lay(g)).min().unwrap();
            let n_lo = k.iter().filter(|&&g| lay(g) == lo).count();
            if n_lo == 1 {
                "fan".into()
            } else {
                "merged".into()
            }
        };
        let cx = k.iter().map(|&g| m.xy(g)[0]).sum::<f64>() / k.len() as f64;
        let cy = k.iter().map(|&g| m.xy(g)[1]).sum::<f64>() / k.len() as f64;
        let corner_angles: Vec<String> = (0..k.len())
            .map(|i| {
                let a = m.xy(k[(i + k.len() - 1) % k.len()]);
                let b = m.xy(k[i]);
                let d = m.xy(k[(i + 1) % k.len()]);
                let u = [a[0] - b[0], a[1] - b[1]];
                let v = [d[0] - b[0], d[1] - b[1]];
                let ang = (u[0] * v[1] - u[1] * v[0])
                    .abs()
                    .atan2(u[0] * v[0] + u[1] * v[1]);
                format!("{:.0}", ang.to_degrees())
            })
            .collect();
        let lens: Vec<String> = (0..k.len())
            .map(|i| {
                let a = m.xy(k[i]);
                let b = m.xy(k[(i + 1) % k.len()]);
                format!(
                    "{:.2e}",
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
                )
            })
            .collect();
        let layers: Vec<String> = k
            .iter()
            .map(|&g| {
                if lay(g) == NONE {
                    "F".into()
                } else {
                    lay(g).to_string()
                }
            })
            .collect();
        let on_boundary = k.iter().filter(|&&g| (g as usize) < nb).count();
        rows.push((worst, format!(
            "{worst:6.1} {kind:14} L{:>3} at ({cx:.5},{cy:.5}) node layers {:?} angles {:?} sides {:?} bnd {on_boundary}",
            m.cell_layer[ci], layers, corner_angles, lens
        )));
    }
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    for r in rows.iter().take(80) {
        println!("{}", r.1);
    }
    println!("{} cells with a triangle >= {threshold}", rows.len());
    if args.len() >= 8 {
        let x: f64 = args[4].parse().unwrap();
        let y: f64 = args[5].parse().unwrap();
        let hw: f64 = args[6].parse().unwrap();
        let png = mesh_draw::render_png(
            m,
            &mesh_draw::DrawParams {
                view: Some(mesh_draw::view_around([x, y], hw)),
                colour: mesh_draw::ColourBy::MaxAngle,
                ..Default::default()
            },
        )
        .unwrap();
        std::fs::write(&args[7], png).unwrap();
    }
}
