//! Writes 3D meshes cut by `topo-cut` for the end-to-end checks with Gmsh and VTK
//! (`tests/python/e2e.py`): a layered cube-sphere with merged children (prisms from a
//! triangulated wall, hexahedra from a quadrilateral one), cut to tetrahedra and to mixed
//! cells, linear and raised to order 2 with straight sides, as `.msh` and `.vtu` in OUTDIR.
//! Prints one JSON line per mesh: its files, node count, cells by type, boundary facets by
//! group. A format that cannot hold a mesh (VTK has no verified order-2 pyramid here) is
//! reported with `"vtu": null`.
//!
//! Usage: cargo run --release -p end-to-end --example cut3d -- OUTDIR

use std::path::Path;

use mesh_model::{Mesh, Shape};
use testkit::layered::{Merge, Spec, poly, straight_p2};

fn summary(mesh: &Mesh, msh: &Path, vtu: Option<&Path>) -> serde_json::Value {
    let count = |s| mesh.count(s);
    let group = |p: u32| mesh.boundary_patch.iter().filter(|&&q| q == p).count();
    serde_json::json!({
        "msh": msh, "vtu": vtu, "order": mesh.order, "nodes": mesh.nodes.len(),
        "cells": {"tet": count(Shape::Tet), "pyramid": count(Shape::Pyramid),
                  "prism": count(Shape::Prism), "hex": count(Shape::Hex)},
        "boundary_groups": {"wall": group(0), "farfield": group(1)},
    })
}

fn main() -> anyhow::Result<()> {
    let out = std::env::args()
        .nth(1)
        .ok_or_else(|| anyhow::anyhow!("usage: cut3d OUTDIR"))?;
    let out = Path::new(&out);
    std::fs::create_dir_all(out)?;
    for quads in [false, true] {
        let mut spec = Spec::new(4, quads, 6);
        (spec.h0, spec.growth) = (0.15, 1.2);
        spec.merge = Merge::Random(0.3);
        let poly = poly(&spec);
        let wall = if quads { "hex" } else { "prism" };
        for (cut, linear) in [
            ("tets", topo_cut::cut_to_tets(&poly)?),
            ("mixed", topo_cut::cut_to_mixed(&poly)?),
        ] {
            let p2 = straight_p2(&linear);
            for (order, mesh) in [(1, &linear), (2, &p2)] {
                let stem = out.join(format!("{wall}-{cut}-p{order}"));
                let (msh, vtu) = (stem.with_extension("msh"), stem.with_extension("vtu"));
                mesh_io::write(&msh, mesh)?;
                let vtu = match mesh_io::write(&vtu, mesh) {
                    Ok(()) => Some(vtu),
                    Err(mesh_io::IoError::Unsupported { .. }) => None,
                    Err(e) => return Err(e.into()),
                };
                println!("{}", summary(mesh, &msh, vtu.as_deref()));
            }
        }
    }
    Ok(())
}
