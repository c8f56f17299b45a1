//! Writes the test-kit meshes to a directory in every format, for checking them with other
//! tools (`tests/python/check_msh.py` with Gmsh, `tests/python/check_pyfr.sh` with PyFR,
//! ParaView for the `.vtu`).
//!
//! Run: `cargo run -p mesh-io --features testkit --example write_samples -- DIR`.
//! Writes `annulus_p{1,2,3}_{quads,mixed,tris}.{msh,vtu,su2}`, `naca0012_ring_p{1,2,3}.{msh,vtu}`
//! and `cells3d_p{1,2}.msh`.

use std::path::PathBuf;

use mesh_io::testkit::{
    AnnulusParams, RingParams, airfoil_ring, annulus, reference_cells_3d, selig_points,
};

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
    let naca = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/geometry/naca0012.dat"
    );
    let text = std::fs::read_to_string(naca).map_err(|e| mesh_io::IoError::Io {
        path: naca.into(),
        source: e,
    })?;
    let points = selig_points(&text);
    for order in 1..=3 {
        let mesh = airfoil_ring(
            &points,
            &RingParams {
                order,
                layers: 3,
                thickness: 2e-3,
                triangle_mask: vec![false, false, true],
            },
        );
        for ext in ["msh", "vtu"] {
            let path = dir.join(format!("naca0012_ring_p{order}.{ext}"));
            mesh_io::write(&path, &mesh)?;
            println!("{}", path.display());
        }
    }
    for order in 1..=2 {
        let path = dir.join(format!("cells3d_p{order}.msh"));
        mesh_io::write(&path, &reference_cells_3d(order))?;
        println!("{}", path.display());
    }
    Ok(())
}
