//! Diagnostic: grows the layers of a 3D case and writes the raw polyhedral mesh (before the
//! cut) to a flat little-endian file, for the `cut_diag` example:
//! `cargo run --release -p xtask --example dump_poly -- <case.toml> <out.poly>`.

use std::io::Write;

use anyhow::{Result, bail};
use curvemesh::pipeline3d;
use curvemesh::{AnyCase, load as load_any};

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [case, out] = args.as_slice() else {
        bail!("usage: dump_poly <case.toml> <out.poly>");
    };
    let AnyCase::Three(case) = load_any(case)? else {
        bail!("{case}: not a 3D case");
    };
    let (surface, _shape) = pipeline3d::surface(&case)?;
    pipeline3d::check_surface(&case, &surface)?;
    let grown = pipeline3d::grow(&case, &surface)?;
    let p = &grown.mesh;
    let mut b: Vec<u8> = Vec::new();
    let u = |b: &mut Vec<u8>, x: u64| b.extend_from_slice(&x.to_le_bytes());
    u(&mut b, p.nodes.len() as u64);
    p.nodes
        .iter()
        .flatten()
        .for_each(|x| b.extend_from_slice(&x.to_le_bytes()));
    u(&mut b, p.face_count() as u64);
    for f in 0..p.face_count() {
        u(&mut b, p.face(f).len() as u64);
        p.face(f).iter().for_each(|&v| u(&mut b, v as u64));
    }
    u(&mut b, p.cell_count() as u64);
    for c in 0..p.cell_count() {
        u(&mut b, p.cell(c).len() as u64);
        for cf in p.cell(c) {
            u(&mut b, cf.face as u64 | (cf.reversed as u64) << 63);
        }
        u(&mut b, p.cell_layer[c] as u64);
        u(&mut b, p.cell_pipe[c] as u64);
    }
    std::fs::File::create(out)?.write_all(&b)?;
    println!("{}: {} nodes, {} cells", out, p.nodes.len(), p.cell_count());
    Ok(())
}
