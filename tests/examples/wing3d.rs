//! The NACA0012 wing of the dissertation's tables 5–7 (§5.4): the built-in 2D case's section
//! made into a finite wing (`xtask::wing`), layers grown by `afsf3d`, cut to tetrahedra and
//! to mixed cells by `topo-cut`. Prints one JSON line: sizes, timings, peak memory, coverage,
//! the three histograms of tables 5–7 (neighbour triangle max angle, extrusion-edge
//! deviation, tetrahedron max dihedral angle), the largest dihedral angle and the smallest
//! corner scaled Jacobian of the mixed mesh's prisms (hexahedra with `--quads`) at the
//! trailing edge, at the tips and everywhere.
//!
//! Usage: cargo run --release -p end-to-end --example wing3d -- [--surface-h H] [--h H]
//! [--growth G] [--layers N] [--span S] [--chord-refine R] [--quads] [--case CASE]
//! (defaults: the dissertation's case 1: 1e-3, 1e-3, 1.3, 45 layers, span 2; `--surface-h`
//! is the first height of the 2D section and of the span grading, `--h` the volume's;
//! `--chord-refine R` caps the section's boundary segments at 0.03 / R; `--case` a 2D case
//! with one wall loop, built-in or a file, instead of the built-in `naca0012`).

use std::time::Instant;

use afsf3d::{LayerParams, grow_layers};
use geom_surface::{Surface, angle_between, unit};
use mesh_model::Shape;
use mesh_model::poly::PolyMesh;

struct Args {
    surface_h: f64,
    h: f64,
    growth: f64,
    layers: usize,
    span: f64,
    chord_refine: f64,
    quads: bool,
    case: String,
}

fn args() -> anyhow::Result<Args> {
    let mut a = Args {
        surface_h: 1e-3,
        h: 1e-3,
        growth: 1.3,
        layers: 45,
        span: 2.0,
        chord_refine: 1.0,
        quads: false,
        case: "naca0012".to_string(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        if flag == "--quads" {
            a.quads = true;
            continue;
        }
        if flag == "--case" {
            a.case = it
                .next()
                .ok_or_else(|| anyhow::anyhow!("--case needs a value"))?;
            continue;
        }
        let v: f64 = it
            .next()
            .ok_or_else(|| anyhow::anyhow!("{flag} needs a value"))?
            .parse()?;
        match flag.as_str() {
            "--surface-h" => a.surface_h = v,
            "--h" => a.h = v,
            "--growth" => a.growth = v,
            "--layers" => a.layers = v as usize,
            "--span" => a.span = v,
            "--chord-refine" => a.chord_refine = v,
            _ => anyhow::bail!("unknown flag {flag}"),
        }
    }
    Ok(a)
}

/// Counts of `values` in the bins whose upper ends are `edges` (the first bin from −∞, a
/// value on an edge in the lower bin), and the rest above the last edge.
fn histogram(values: impl Iterator<Item = f64>, edges: &[f64]) -> Vec<usize> {
    let mut h = vec![0; edges.len() + 1];
    for v in values {
        h[edges.iter().position(|&e| v <= e).unwrap_or(edges.len())] += 1;
    }
    h
}

fn triangle_max_angle(p: [[f64; 3]; 3]) -> f64 {
    (0..3)
        .map(|i| {
            let o = p[i];
            let a = geom_predicates::vector::sub(p[(i + 1) % 3], o);
            let b = geom_predicates::vector::sub(p[(i + 2) % 3], o);
            angle_between(a, b).to_degrees()
        })
        .fold(0.0, f64::max)
}

/// Table 5: the largest angle of every layer's top triangles (quads cut along the shorter
/// diagonal).
fn neighbour_triangles(poly: &PolyMesh) -> Vec<f64> {
    let mut out = Vec::new();
    for c in 0..poly.cell_count() {
        let Some(top) = poly.cell(c).get(1) else {
            continue;
        };
        let k = poly.face(top.face as usize);
        let p = |i: usize| poly.nodes[k[i] as usize];
        match k.len() {
            3 => out.push(triangle_max_angle([p(0), p(1), p(2)])),
            4 => {
                let d = |a: usize, b: usize| {
                    let v = geom_predicates::vector::sub(p(a), p(b));
                    geom_predicates::vector::dot(v, v)
                };
                let (t1, t2) = if d(0, 2) <= d(1, 3) {
                    ([0, 1, 2], [0, 2, 3])
                } else {
                    ([0, 1, 3], [1, 2, 3])
                };
                out.push(triangle_max_angle(t1.map(p)));
                out.push(triangle_max_angle(t2.map(p)));
            }
            _ => {}
        }
    }
    out
}

/// Table 6: the angle between every extrusion edge and the angle-weighted normal of the
/// front it grew from.
fn deviations(wall: &Surface, grown: &afsf3d::Grown3d) -> Vec<f64> {
    let layers = grown.columns[0].len() - 1;
    let mut out = Vec::with_capacity(layers * wall.nodes.len());
    for l in 0..layers {
        let front = Surface {
            nodes: grown
                .columns
                .iter()
                .map(|c| grown.mesh.nodes[c[l] as usize])
                .collect(),
            ..wall.clone()
        };
        for (v, n) in front.node_normals().into_iter().enumerate() {
            let c = &grown.columns[v];
            let e = geom_predicates::vector::sub(
                grown.mesh.nodes[c[l + 1] as usize],
                grown.mesh.nodes[c[l] as usize],
            );
            out.push(angle_between(unit(e), n).to_degrees());
        }
    }
    out
}

/// The scaled Jacobian at every corner of a linear prism or hexahedron (Gmsh's node order):
/// the determinant of the corner's three edges over the product of their lengths.
fn corner_scaled_jacobians(shape: Shape, p: &[[f64; 3]]) -> Vec<f64> {
    corner_dets(shape, p, true)
}

/// The corner determinants of a linear prism or hexahedron
/// ([`mesh_model::measure3d::corner_determinants`]), none for other shapes.
fn corner_dets(shape: Shape, p: &[[f64; 3]], normalised: bool) -> Vec<f64> {
    match shape {
        Shape::Prism | Shape::Hex => mesh_model::measure3d::corner_determinants(p, normalised),
        _ => vec![],
    }
}

/// The smallest corner scaled Jacobian of the prisms and hexahedra: at the trailing edge
/// (a node within 1 % of the chord of its end), at the tips (a node within 2 % of the chord
/// of a tip), everywhere.
fn corner_quality(mesh: &mesh_model::Mesh, x_te: f64, span: f64) -> [f64; 3] {
    let mut worst = [f64::INFINITY; 3];
    for c in mesh.cells.iter() {
        let k = c.corners();
        let p: Vec<[f64; 3]> = k.iter().map(|&v| mesh.nodes[v as usize]).collect();
        let Some(q) = corner_scaled_jacobians(c.ty.shape, &p)
            .into_iter()
            .reduce(f64::min)
        else {
            continue;
        };
        let te = p.iter().any(|x| x[0] > x_te - 0.01);
        let tip = p.iter().any(|x| x[2] < 0.02 || x[2] > span - 0.02);
        for (i, at) in [te, tip, true].into_iter().enumerate() {
            if at {
                worst[i] = worst[i].min(q);
            }
        }
    }
    worst
}

/// The wall's triangles: the histogram of their largest angle (as table 5) per patch.
fn wall_angles(wall: &Surface) -> serde_json::Value {
    let mut per = serde_json::Map::new();
    for (p, patch) in wall.patches.iter().enumerate() {
        let angles = (0..wall.facets.len())
            .filter(|&f| wall.facet_patch[f] as usize == p)
            .flat_map(|f| wall.facets[f].triangles().collect::<Vec<_>>())
            .map(|t| triangle_max_angle(t.map(|v| wall.nodes[v as usize])));
        per.insert(
            patch.name.clone(),
            histogram(angles, &[90.0, 125.0, 140.0]).into(),
        );
    }
    per.into()
}

/// The prism or hexahedron with the smallest corner scaled Jacobian: its value, layer and
/// centroid; and how many have one below 0.2, by layer.
fn worst_cell(mesh: &mesh_model::Mesh) -> serde_json::Value {
    let mut worst = (f64::INFINITY, 0, [0.0; 3]);
    let mut ratio = f64::INFINITY;
    let mut low = std::collections::BTreeMap::new();
    for (i, c) in mesh.cells.iter().enumerate() {
        let p: Vec<[f64; 3]> = c
            .corners()
            .iter()
            .map(|&v| mesh.nodes[v as usize])
            .collect();
        let Some(q) = corner_scaled_jacobians(c.ty.shape, &p)
            .into_iter()
            .reduce(f64::min)
        else {
            continue;
        };
        let d = corner_dets(c.ty.shape, &p, false);
        let (lo, hi) = d.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| {
            (a.min(x), b.max(x.abs()))
        });
        ratio = ratio.min(lo / hi);
        if q < 0.2 {
            *low.entry(mesh.cell_layer[i]).or_insert(0usize) += 1;
        }
        if q < worst.0 {
            let n = p.len() as f64;
            let centre = std::array::from_fn(|d| p.iter().map(|x| x[d]).sum::<f64>() / n);
            worst = (q, mesh.cell_layer[i], centre);
        }
    }
    serde_json::json!({"min_corner_det_ratio": ratio, "sj": worst.0, "layer": worst.1, "centroid": worst.2, "below_0.2_by_layer": low})
}

fn peak_memory_mb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// Tetrahedra with a dihedral angle above 160°, by region (trailing edge, tips, elsewhere)
/// and by layer.
fn bad_tets(mesh: &mesh_model::Mesh, dihedral: &[f64], x_te: f64, span: f64) -> serde_json::Value {
    let mut region = [0usize; 3];
    let mut by_layer = std::collections::BTreeMap::new();
    for (i, c) in mesh.cells.iter().enumerate() {
        if dihedral[i] <= 160.0 {
            continue;
        }
        let p: Vec<[f64; 3]> = c
            .corners()
            .iter()
            .map(|&v| mesh.nodes[v as usize])
            .collect();
        let r = if p.iter().any(|x| x[0] > x_te - 0.01) {
            0
        } else if p.iter().any(|x| x[2] < 0.02 || x[2] > span - 0.02) {
            1
        } else {
            2
        };
        region[r] += 1;
        *by_layer.entry(mesh.cell_layer[i]).or_insert(0usize) += 1;
    }
    serde_json::json!({"te_tips_other": region, "by_layer": by_layer})
}

/// The largest dihedral angle of every cell (all tetrahedra after `cut_to_tets`).
fn tet_dihedrals(mesh: &mesh_model::Mesh) -> Vec<f64> {
    let at = |v: u32| mesh.nodes[v as usize];
    mesh.cells
        .shapes_and_corners()
        .map(|(_, k)| {
            let angles =
                topo_cut::tet_dihedral_angles_deg([at(k[0]), at(k[1]), at(k[2]), at(k[3])]);
            angles.iter().copied().fold(0.0, f64::max)
        })
        .collect()
}

fn main() -> anyhow::Result<()> {
    let a = args()?;
    let mut case = curvemesh::load::load_2d(&a.case)?;
    case.layers.first_height = a.surface_h;
    case.layers.growth = a.growth;
    case.boundary.growth = a.growth;
    if a.chord_refine > 1.0 {
        let longest = 0.03 / a.chord_refine;
        for l in &mut case.loops {
            if l.role == mesh_model::Role::Wall {
                l.max_spacing = Some(longest);
            }
        }
    }
    let t0 = Instant::now();
    let (wall, _shape) = curvemesh::wing::wing_surface(&case, a.span, !a.quads)?;
    let t_surface = t0.elapsed().as_secs_f64();
    let params = LayerParams {
        first_height: a.h,
        growth: a.growth,
        layers: a.layers,
        ..LayerParams::default()
    };
    let t1 = Instant::now();
    let grown = grow_layers(&wall, &params);
    let t_grow = t1.elapsed().as_secs_f64();
    let grown = match grown {
        Ok(g) => g,
        Err(e) => {
            let at = match &e {
                afsf3d::GrowError::LayerFailed { facet, .. } => {
                    let k = wall.facets[*facet].nodes();
                    let p: Vec<[f64; 3]> = k.iter().map(|&v| wall.nodes[v as usize]).collect();
                    let patch = &wall.patches[wall.facet_patch[*facet] as usize].name;
                    serde_json::json!({"patch": patch, "nodes": p})
                }
                _ => serde_json::Value::Null,
            };
            println!(
                "{}",
                serde_json::json!({"wall_nodes": wall.nodes.len(), "wall_facets": wall.facets.len(),
                    "grow_s": t_grow, "error": e.to_string(), "at": at})
            );
            return Ok(());
        }
    };
    let t2 = Instant::now();
    let tets = topo_cut::cut_to_tets(&grown.mesh)?;
    let t_tets = t2.elapsed().as_secs_f64();
    let t3 = Instant::now();
    let mixed = topo_cut::cut_to_mixed(&grown.mesh)?;
    let t_mixed = t3.elapsed().as_secs_f64();
    let full = grown
        .columns
        .iter()
        .filter(|c| c.len() == a.layers + 1)
        .count();
    let x_te = wall.nodes.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    let dihedral = tet_dihedrals(&tets);
    let json = serde_json::json!({
        "surface_h": a.surface_h, "h": a.h, "growth": a.growth, "layers": a.layers,
        "span": a.span, "quads": a.quads,
        "wall_nodes": wall.nodes.len(), "wall_facets": wall.facets.len(),
        "coverage": full as f64 / grown.columns.len() as f64,
        "shrinks": grown.stats.shrinks, "converged": grown.stats.converged,
        "tets": tets.cells.len(),
        "mixed": {"tet": mixed.count(Shape::Tet), "pyramid": mixed.count(Shape::Pyramid),
                  "prism": mixed.count(Shape::Prism), "hex": mixed.count(Shape::Hex)},
        "table5_tri_max_angle_60_90_125_140_180": histogram(neighbour_triangles(&grown.mesh).into_iter(), &[90.0, 125.0, 140.0]),
        "table6_deviation_10_20_30_180": histogram(deviations(&wall, &grown).into_iter(), &[10.0, 20.0, 30.0]),
        "table7_tet_dihedral_90_130_150_160_180": histogram(dihedral.iter().copied(), &[90.0, 130.0, 150.0, 160.0]),
        "max_dihedral_deg": dihedral.iter().copied().fold(0.0, f64::max),
        "mixed_max_dihedral_deg": topo_cut::max_dihedral_deg(&mixed),
        "min_corner_sj_te_tips_all": corner_quality(&mixed, x_te, a.span),
        "wall_tri_max_angle": wall_angles(&wall),
        "worst_prism": worst_cell(&mixed),
        "tets_over_160": bad_tets(&tets, &dihedral, x_te, a.span),
        "poly_problems": grown.mesh.validate().len(),
        "time_s": {"surface": t_surface, "grow": t_grow, "cut_tets": t_tets, "cut_mixed": t_mixed},
        "peak_memory_mb": peak_memory_mb(),
    });
    println!("{json}");
    Ok(())
}
