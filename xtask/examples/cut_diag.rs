//! Diagnostic of the cut on a raw polyhedral mesh written by `xtask`'s `dump_poly` example:
//! `cargo run --release -p xtask --example cut_diag -- <file.poly> [tets|mixed]`.
//! For every raw cell whose cut has a tetrahedron over 150°: its layer, node count and face
//! sizes, the worst piece of the cut and the best worst piece over every cone cut of the cell
//! alone (every apex, every diagonal of the quadrilaterals away from it): when even the best
//! is over 160°, the raw cell's geometry is the cause, not the order of the cuts.
//! Environment: `DEPTH`, `DEEP`, `EXTRA` (the refining passes' depths: over 150°, over 160°,
//! then over 150° again), `OLD` (a mixed cut refined without whole sides), `CELL` (print that
//! cell, its sides' diagonals and the cells across, two levels), `DIAG` (every bad cell).

use mesh_model::poly::{CellFace, PolyMesh};
use mesh_model::{Shape, validate};
use topo_cut::cone::{CellFaces, Piece};
use topo_cut::improve::piece_quality;

fn read(path: &str) -> PolyMesh {
    let b = std::fs::read(path).expect("read");
    let mut at = 0usize;
    let mut u = || {
        let x = u64::from_le_bytes(b[at..at + 8].try_into().unwrap());
        at += 8;
        x
    };
    let mut p = PolyMesh::new();
    let n = u();
    for _ in 0..n {
        let x = [
            f64::from_bits(u()),
            f64::from_bits(u()),
            f64::from_bits(u()),
        ];
        p.nodes.push(x);
    }
    let nf = u();
    for _ in 0..nf {
        let k = u();
        let nodes: Vec<u32> = (0..k).map(|_| u() as u32).collect();
        p.push_face(&nodes);
    }
    let nc = u();
    for _ in 0..nc {
        let k = u();
        let faces: Vec<CellFace> = (0..k)
            .map(|_| {
                let x = u();
                CellFace {
                    face: (x & 0xffff_ffff) as u32,
                    reversed: x >> 63 == 1,
                }
            })
            .collect();
        let (layer, pipe) = (u() as u32, u() as u32);
        p.push_cell(&faces, layer, pipe);
    }
    p
}

/// The worst piece of the cone from `apex` with the far quadrilaterals' diagonals by `bits`.
fn cone_quality(p: &PolyMesh, f: &CellFaces, apex: u32, bits: u32) -> f64 {
    let mut worst: f64 = 0.0;
    let mut q = 0;
    for k in f.faces().filter(|k| !k.contains(&apex)) {
        let mut pieces: Vec<Piece> = Vec::new();
        let tet = |a: u32, b: u32, c: u32| {
            let mut x = [0u32; 8];
            x[..4].copy_from_slice(&[a, c, b, apex]);
            (Shape::Tet, x)
        };
        if k.len() == 3 {
            pieces.push(tet(k[0], k[1], k[2]));
        } else {
            let s = ((bits >> q) & 1) as usize;
            q += 1;
            let r = |j: usize| k[(s + j) % 4];
            pieces.push(tet(r(0), r(1), r(2)));
            pieces.push(tet(r(0), r(2), r(3)));
        }
        for pc in &pieces {
            worst = worst.max(piece_quality(&p.nodes, pc));
        }
    }
    worst
}

fn best_cone(p: &PolyMesh, f: &CellFaces) -> f64 {
    let mut nodes = Vec::new();
    f.distinct_nodes(&mut nodes);
    let mut best = f64::INFINITY;
    for &apex in &nodes {
        let quads = f
            .faces()
            .filter(|k| !k.contains(&apex) && k.len() == 4)
            .count();
        for bits in 0..1u32 << quads {
            best = best.min(cone_quality(p, f, apex, bits));
        }
    }
    best
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let p = read(&args[0]);
    let mixed = args.get(1).is_some_and(|a| a == "mixed");
    let t = std::time::Instant::now();
    let rank = topo_cut::order::sweep_ranks(&p);
    let mut rank = if mixed {
        topo_cut::order::round_cut_ranks(&p, &rank, &[]).expect("ranks")
    } else {
        rank
    };
    let swaps = std::env::var("SWAPS").map_or(0, |s| s.parse().unwrap());
    topo_cut::improve::improve(&p, &mut rank, 150.0, swaps);
    let mut cut = topo_cut::refine::Cut::from_ranks(&p, &rank);
    let dt = t.elapsed().as_secs_f64();
    let before = topo_cut::assemble_cut(&p, &cut).expect("cut");
    println!("before refine (sweep + swaps) {dt:.3}s:");
    report(&p, &before);
    let t = std::time::Instant::now();
    let passes = std::env::var("PASSES").map_or(8, |s| s.parse().unwrap());
    let depth = std::env::var("DEPTH").map_or(2, |s| s.parse().unwrap());
    let refine = if mixed && std::env::var("OLD").is_err() {
        topo_cut::refine::refine_mixed
    } else {
        topo_cut::refine::refine
    };
    refine(&p, &mut cut, 150.0, passes, depth);
    if let Ok(deep) = std::env::var("DEEP") {
        refine(&p, &mut cut, 160.0, passes, deep.parse().unwrap());
    }
    if let Ok(extra) = std::env::var("EXTRA") {
        refine(&p, &mut cut, 150.0, passes, extra.parse().unwrap());
    }
    println!(
        "after refine ({passes} passes, depth {depth}) +{:.3}s:",
        t.elapsed().as_secs_f64()
    );
    let after = topo_cut::assemble_cut(&p, &cut).expect("cut");
    report(&p, &after);
    if let Ok(c) = std::env::var("CELL") {
        explain(&p, &cut, c.parse().unwrap(), 2);
    }
}

/// Prints cell `c`'s faces, their diagonals and the cells across (two levels).
fn explain(p: &PolyMesh, cut: &topo_cut::refine::Cut, c: usize, depth: usize) {
    let mut across = vec![Vec::new(); p.face_count()];
    for d in 0..p.cell_count() {
        for cf in p.cell(d) {
            across[cf.face as usize].push(d);
        }
    }
    let mut seen = vec![c];
    let mut todo = vec![(c, 0)];
    while let Some((d, lvl)) = todo.pop() {
        let mut f = CellFaces::default();
        f.load(p, d);
        let mut nodes = Vec::new();
        f.distinct_nodes(&mut nodes);
        let mut pieces = Vec::new();
        cut.pieces(&f, d, &mut pieces);
        let q: Vec<String> = pieces
            .iter()
            .map(|x| format!("{:?}{:.1}", x.0, piece_quality(&p.nodes, x)))
            .collect();
        println!(
            "{}cell {d} layer {} nodes {nodes:?} apex {} best alone {:.1} pieces {q:?}",
            "  ".repeat(lvl),
            p.cell_layer[d],
            cut.apex[d] as i64,
            best_cone(p, &f)
        );
        for i in 0..f.len() {
            let id = f.id(i) as usize;
            let other: Vec<usize> = across[id].iter().copied().filter(|&x| x != d).collect();
            println!(
                "{}  face {i} id {id} {:?} split {} across {:?}",
                "  ".repeat(lvl),
                f.face(i),
                cut.split[id] as i64,
                other
            );
            if lvl < depth && f.face(i).len() == 4 {
                for o in other {
                    if !seen.contains(&o) {
                        seen.push(o);
                        todo.push((o, lvl + 1));
                    }
                }
            }
        }
    }
}

fn report(p: &PolyMesh, mesh: &mesh_model::Mesh) {
    let dt = 0.0;
    let problems = validate(mesh);
    let mut bins = [0usize; 5];
    let mut maxd: f64 = 0.0;
    let mut bad_cells = Vec::new();
    let mut f = CellFaces::default();
    // the mesh's cells come cell by cell: recount by cutting again per cell is not public, so
    // map through (layer, pipe)
    let mut by_lp = std::collections::HashMap::new();
    for c in 0..p.cell_count() {
        by_lp.insert((p.cell_layer[c], p.cell_pipe[c]), c);
    }
    let mut inverted = 0;
    for (i, c) in mesh.cells.iter().enumerate() {
        let k = c.corners();
        let q = piece_quality(
            &mesh.nodes,
            &(c.ty.shape, {
                let mut x = [0u32; 8];
                x[..k.len()].copy_from_slice(k);
                x
            }),
        );
        if q >= 360.0 {
            inverted += 1;
            if std::env::var("DIAG").is_ok() {
                println!(
                    "inverted {:?} in cell {}",
                    c.ty.shape,
                    by_lp[&(mesh.cell_layer[i], mesh.cell_pipe[i])]
                );
            }
        }
        if c.ty.shape != Shape::Tet {
            if q >= 360.0 {
                bad_cells.push(by_lp[&(mesh.cell_layer[i], mesh.cell_pipe[i])]);
            }
            continue;
        }
        maxd = maxd.max(q);
        let b = [90.0, 130.0, 150.0, 160.0]
            .iter()
            .filter(|&&e| q > e)
            .count();
        bins[b] += 1;
        if q > 150.0 {
            bad_cells.push(by_lp[&(mesh.cell_layer[i], mesh.cell_pipe[i])]);
        }
    }
    bad_cells.sort();
    bad_cells.dedup();
    println!(
        "cells {} tets {} max dihedral {maxd:.2} bins {bins:?} (>160: {}) inverted {inverted} problems {} cut {dt:.3}s",
        p.cell_count(),
        bins.iter().sum::<usize>(),
        bins[4],
        problems.len()
    );
    pyramids(mesh);
    let verbose = std::env::var("DIAG").is_ok();
    let (mut order_fault, mut geom_fault) = (0, 0);
    let mut summary: std::collections::BTreeMap<String, (usize, usize)> = Default::default();
    for &c in &bad_cells {
        f.load(p, c);
        let mut nodes = Vec::new();
        f.distinct_nodes(&mut nodes);
        let sizes: Vec<usize> = f.faces().map(|k| k.len()).collect();
        let best = best_cone(p, &f);
        // the worst tet of this cell in the actual cut
        let actual = mesh
            .cells
            .iter()
            .enumerate()
            .filter(|(i, _)| {
                (mesh.cell_layer[*i], mesh.cell_pipe[*i]) == (p.cell_layer[c], p.cell_pipe[c])
            })
            .map(|(_, x)| {
                let k = x.corners();
                let mut y = [0u32; 8];
                y[..k.len()].copy_from_slice(k);
                piece_quality(&mesh.nodes, &(x.ty.shape, y))
            })
            .fold(0.0, f64::max);
        let shape = format!("n{} faces{:?}", nodes.len(), sizes);
        let e = summary.entry(shape.clone()).or_default();
        if actual > 160.0 {
            if best > 160.0 {
                geom_fault += 1;
                e.1 += 1;
            } else {
                order_fault += 1;
                e.0 += 1;
            }
        }
        if verbose || (actual > 160.0 && best > 160.0 && geom_fault <= 10) {
            let mut x = [0.0; 3];
            for &v in &nodes {
                (0..3).for_each(|d| x[d] += p.nodes[v as usize][d] / nodes.len() as f64);
            }
            println!(
                "cell {c} layer {} pipe {} {shape} cut {actual:.1} best cone {best:.1} at ({:.4}, {:.4}, {:.4})",
                p.cell_layer[c], p.cell_pipe[c], x[0], x[1], x[2]
            );
        }
    }
    println!(
        "cells with a tet > 160: order/cut {order_fault}, raw geometry (no cone cut <= 160) {geom_fault}"
    );
    for (k, v) in summary {
        println!("  {k}: order {} geometry {}", v.0, v.1);
    }
}

/// The pyramids' smallest base-corner scaled Jacobian and the worst of their best splits.
fn pyramids(mesh: &mesh_model::Mesh) {
    let (mut n, mut min_sj, mut worst_split, mut low, mut over) =
        (0, f64::INFINITY, 0.0f64, 0, [0; 3]);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    for c in mesh.cells.iter() {
        if c.ty.shape != Shape::Pyramid {
            continue;
        }
        n += 1;
        let k = c.corners();
        let p: Vec<[f64; 3]> = k.iter().map(|&v| mesh.nodes[v as usize]).collect();
        let mut sj = f64::INFINITY;
        for i in 0..4 {
            let o = p[i];
            let (a, b, e) = (sub(p[(i + 1) % 4], o), sub(p[(i + 3) % 4], o), sub(p[4], o));
            let cr = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let d = cr[0] * e[0] + cr[1] * e[1] + cr[2] * e[2];
            let l = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            sj = sj.min(d / (l(a) * l(b) * l(e)));
        }
        if sj < 0.1 {
            low += 1;
        }
        min_sj = min_sj.min(sj);
        let split = |s: usize| {
            let t = |x: usize, y: usize, z: usize| {
                topo_cut::tet_dihedral_angles_deg([p[x], p[y], p[z], p[4]])
                    .into_iter()
                    .fold(0.0, f64::max)
            };
            t(s, (s + 1) % 4, (s + 2) % 4).max(t(s, (s + 2) % 4, (s + 3) % 4))
        };
        let q = split(0).min(split(1));
        worst_split = worst_split.max(q);
        for (j, e) in [130.0, 150.0, 160.0].iter().enumerate() {
            if q > *e {
                over[j] += 1;
            }
        }
    }
    println!(
        "pyramids {n}: min base-corner SJ {min_sj:.4} (under 0.1: {low}), worst best split {worst_split:.2}, over 130/150/160: {over:?}"
    );
}
