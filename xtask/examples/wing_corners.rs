//! Diagnostic: where a 3D case's prisms and hexahedra have their smallest corner scaled
//! Jacobian. Prints the wall's smallest facet angle per patch, then the smallest corner SJ per
//! region (the trailing edge: cells over wall facets with x > 0.97 chord on the side; the
//! tips: over the caps, or over side facets within 0.05 of a tip; the rest) and layer band,
//! with the worst cell's wall facet:
//! `cargo run --release -p xtask --example wing_corners -- <case.toml> [layers]`.
//! With `WING_CORNERS_DETAIL` set it also prints each region's worst cell corner by corner
//! (its scaled Jacobian, face angle and extrusion tilt); with `WING_CORNERS_CAP` the root
//! cap's facets at the trailing edge (x > 0.97).

use anyhow::{Result, bail};
use curvemesh::pipeline3d;
use curvemesh::{AnyCase, load as load_any};
use mesh_model::measure3d;

fn angle(a: [f64; 3], o: [f64; 3], b: [f64; 3]) -> f64 {
    let u: [f64; 3] = std::array::from_fn(|d| a[d] - o[d]);
    let v: [f64; 3] = std::array::from_fn(|d| b[d] - o[d]);
    let dot: f64 = (0..3).map(|d| u[d] * v[d]).sum();
    let n = |w: [f64; 3]| (0..3).map(|d| w[d] * w[d]).sum::<f64>().sqrt();
    (dot / (n(u) * n(v))).clamp(-1.0, 1.0).acos().to_degrees()
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(file) = args.first() else {
        bail!("usage: wing_corners <case.toml> [layers]");
    };
    let AnyCase::Three(mut case) = load_any(file)? else {
        bail!("{file}: not a 3D case");
    };
    if let Some(n) = args.get(1) {
        case.layers.layers = n.parse()?;
    }
    let t = std::time::Instant::now();
    let (surface, _) = pipeline3d::surface(&case)?;
    pipeline3d::check_surface(&case, &surface)?;
    let span = surface.nodes.iter().map(|p| p[2]).fold(0.0, f64::max);
    // the wall's facets: smallest corner angle per patch
    let min_angle = |f: usize| {
        let k = surface.facets[f].nodes();
        let x = |i: usize| surface.nodes[k[i % k.len()] as usize];
        (0..k.len())
            .map(|i| angle(x(i + 1), x(i), x(i + k.len() - 1)))
            .fold(180.0, f64::min)
    };
    let centre = |f: usize| {
        let k = surface.facets[f].nodes();
        let c: [f64; 3] = std::array::from_fn(|d| {
            k.iter().map(|&v| surface.nodes[v as usize][d]).sum::<f64>() / k.len() as f64
        });
        c
    };
    let region = |f: usize| {
        let patch = &surface.patches[surface.facet_patch[f] as usize].name;
        let c = centre(f);
        if patch != "wall" {
            "caps"
        } else if c[2] < 0.05 || c[2] > span - 0.05 {
            "tip-side"
        } else if c[0] > 0.97 {
            "TE"
        } else {
            "rest"
        }
    };
    for name in ["wall", "tip-root", "tip-far"] {
        let (mut a, mut at) = (180.0, 0);
        for f in 0..surface.facets.len() {
            if surface.patches[surface.facet_patch[f] as usize].name == name && min_angle(f) < a {
                (a, at) = (min_angle(f), f);
            }
        }
        let below = |lim: f64| {
            (0..surface.facets.len())
                .filter(|&f| {
                    surface.patches[surface.facet_patch[f] as usize].name == name
                        && min_angle(f) < lim
                })
                .count()
        };
        println!(
            "surface {name}: smallest facet angle {a:.2}° (facet {at} at {:?}, {} corners), {} facets under 11.5°, {} under 20°",
            centre(at),
            surface.facets[at].nodes().len(),
            below(11.54),
            below(20.0)
        );
    }
    if std::env::var_os("WING_CORNERS_CAP").is_some() {
        for f in 0..surface.facets.len() {
            if surface.patches[surface.facet_patch[f] as usize].name == "tip-root"
                && centre(f)[0] > 0.97
            {
                let k = surface.facets[f].nodes();
                let p: Vec<String> = k
                    .iter()
                    .map(|&v| {
                        let x = surface.nodes[v as usize];
                        format!("{v}:({:.5},{:.5})", x[0], x[1])
                    })
                    .collect();
                println!("cap facet {f}: {} angle {:.1}", p.join(" "), min_angle(f));
            }
        }
    }
    let grown = match pipeline3d::grow(&case, &surface) {
        Ok(g) => g,
        Err(e) => {
            let msg = e.to_string();
            let f = msg
                .split("wall facet ")
                .nth(1)
                .and_then(|t| t.split(':').next())
                .and_then(|t| t.parse::<usize>().ok());
            if let Some(f) = f {
                println!(
                    "facet {f} at {:?}, smallest angle {:.1}°",
                    centre(f),
                    min_angle(f)
                );
            }
            bail!("{msg}");
        }
    };
    let front = pipeline3d::front_measures(&surface, &grown);
    let (mesh, _) = pipeline3d::cut(&case, &grown, &front)?;
    println!(
        "grown and cut in {:.1} s: {} cells",
        t.elapsed().as_secs_f64(),
        mesh.cells.len()
    );
    let bands = [(0, 0), (1, 4), (5, 9), (10, 19), (20, 29), (30, 44)];
    let mut worst = std::collections::BTreeMap::new();
    for i in 0..mesh.cells.len() {
        let Some(q) = measure3d::min_corner_scaled_jacobian(&mesh, i) else {
            continue;
        };
        let f = mesh.cell_pipe[i] as usize;
        let l = mesh.cell_layer[i];
        let b = bands
            .iter()
            .position(|&(a, z)| a <= l && l <= z)
            .unwrap_or(0);
        for key in [(region(f), b), ("all", b), (region(f), 99), ("all", 99)] {
            let e = worst.entry(key).or_insert((f64::INFINITY, 0usize));
            if q < e.0 {
                *e = (q, i);
            }
        }
    }
    for ((r, b), (q, i)) in &worst {
        let f = mesh.cell_pipe[*i] as usize;
        let band = bands
            .get(*b)
            .map_or("all".to_string(), |(a, z)| format!("{a}-{z}"));
        println!(
            "{r:5} layers {band:6} min corner SJ {q:.4}: cell {i} layer {} over {} facet {f} at [{:.4}, {:.4}, {:.4}] (facet's smallest angle {:.1}°)",
            mesh.cell_layer[*i],
            surface.patches[surface.facet_patch[f] as usize].name,
            centre(f)[0],
            centre(f)[1],
            centre(f)[2],
            min_angle(f)
        );
    }
    // the worst cell of each region over all layers: its corners (bottom, then top), each
    // corner's scaled Jacobian, its face angle and its extrusion edge's angle off the face's
    // normal (the corner SJ is the sine of the one times the cosine of the other)
    if std::env::var_os("WING_CORNERS_DETAIL").is_some() {
        for ((r, b), (_, i)) in worst.iter().filter(|((_, b), _)| *b == 99) {
            let _ = b;
            detail(&mesh, r, *i);
        }
    }
    Ok(())
}

fn detail(mesh: &mesh_model::Mesh, region: &str, i: usize) {
    let c = mesh.cells.get(i);
    let k = c.corners();
    let p: Vec<[f64; 3]> = k.iter().map(|&v| mesh.nodes[v as usize]).collect();
    let q = measure3d::corner_determinants(&p, true);
    let m = p.len() / 2;
    println!("{region}: cell {i} layer {}", mesh.cell_layer[i]);
    for (j, qj) in q.iter().enumerate() {
        let (face, i) = (j / m * m, j % m);
        let o = p[face + i];
        let a = p[face + (i + 1) % m];
        let b = p[face + (i + m - 1) % m];
        let e: [f64; 3] = std::array::from_fn(|d| p[m + i][d] - p[i][d]);
        let u: [f64; 3] = std::array::from_fn(|d| a[d] - o[d]);
        let v: [f64; 3] = std::array::from_fn(|d| b[d] - o[d]);
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let z = [0.0; 3];
        let tilt = angle(n, z, e);
        println!(
            "  corner {j} at [{:.5}, {:.5}, {:.5}]: SJ {qj:.3}, face angle {:.1}°, extrusion {:.1}° off the face normal, edge {:.2e}",
            o[0],
            o[1],
            o[2],
            angle(a, o, b),
            tilt,
            e.iter().map(|x| x * x).sum::<f64>().sqrt()
        );
    }
}
