//! Writes the test-kit meshes to a directory in every format, for checking them with other
//! tools (`tests/python/check_msh.py` with Gmsh, `tests/python/check_pyfr.sh` with PyFR,
//! ParaView for the `.vtu`).
//!
//! Run: `cargo run -p mesh-io --features testkit --example write_samples -- DIR`.
//! Writes `annulus_p{1,2,3}_{quads,mixed,tris}.{msh,vtu,su2}` and `cells3d_p{1,2}.msh`.

use std::path::PathBuf;

use mesh_io::testkit::{AnnulusParams, annulus, reference_cells_3d};

fn main() -> Result<(), mesh_io::IoError> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    for order in 1..=3 {
        for (kind, mask) in [
            ("quads", vec![]),
            ("mixed", vec![true, false, false]),
            ("tris", vec![true]),
        ] {
            let mesh = annulus(&AnnulusParams {
                order,
                triangle_mask: mask,
                ..AnnulusParams::default()
            });
            for ext in ["msh", "vtu", "su2"] {
                let path = dir.join(format!("annulus_p{order}_{kind}.{ext}"));
                mesh_io::write(&path, &mesh)?;
                println!("{}", path.display());
            }
        }
    }
    for order in 1..=2 {
        let path = dir.join(format!("cells3d_p{order}.msh"));
        mesh_io::write(&path, &reference_cells_3d(order))?;
        println!("{}", path.display());
    }
    Ok(())
}
