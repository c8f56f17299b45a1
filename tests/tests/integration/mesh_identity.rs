//! Refactors keep meshes identical: every built-in case, linear, P2, P3 and P3 cut into
//! triangles, read back from its `.msh`, hashes to the digest recorded in
//! `fixtures/golden/mesh-digests.txt` (node coordinates to the last bit, cells, facets,
//! patches). A change that moves a node on purpose updates the file with
//! `UPDATE_GOLDEN=1 cargo test -p end-to-end --test integration -- mesh_identity::` and says why in its commit.

use std::fmt::Write as _;
use std::path::Path;

use curvemesh::builtin;
use end_to_end::{Outcome, s, xtask_ok};
use mesh_model::Mesh;

const GOLDEN: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../fixtures/golden/mesh-digests.txt"
);

/// FNV-1a over 64-bit words: enough to tell two meshes apart, and no dependency.
struct Digest(u64);

impl Digest {
    fn new() -> Self {
        Digest(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

fn digest(mesh: &Mesh) -> u64 {
    let mut d = Digest::new();
    for p in &mesh.nodes {
        p.iter().for_each(|c| d.word(c.to_bits()));
    }
    for cells in [&mesh.cells, &mesh.boundary] {
        for c in cells.iter() {
            d.word(((c.ty.shape as u64) << 8) | u64::from(c.ty.order));
            c.nodes.iter().for_each(|&n| d.word(u64::from(n)));
        }
    }
    mesh.boundary_patch
        .iter()
        .for_each(|&p| d.word(u64::from(p)));
    for p in &mesh.patches {
        p.name.bytes().for_each(|b| d.word(u64::from(b)));
        d.word(p.role as u64);
    }
    d.0
}

fn mesh_of(dir: &Path, case: &str, flags: &[&str]) -> Mesh {
    let msh = dir.join(format!("{case}{}.msh", flags.join("")));
    let mut args = vec!["mesh", case, "--quiet", "--out", s(&msh)];
    args.extend(flags);
    assert_eq!(xtask_ok(&args), Outcome::Valid, "{args:?}");
    mesh_io::read_msh(&msh).unwrap()
}

#[test]
fn builtin_meshes_are_unchanged_to_the_last_bit() {
    let dir = tempfile::tempdir().unwrap();
    let variants: [&[&str]; 4] = [
        &["--order", "1"],
        &["--order", "2"],
        &["--order", "3"],
        &["--order", "3", "--triangles"],
    ];
    let mut table = String::new();
    for case in builtin::names() {
        for flags in variants {
            let mesh = mesh_of(dir.path(), case, flags);
            let key = format!("{case} {}", flags.join(" "));
            writeln!(
                table,
                "{key:<40} {:016x} nodes {} cells {}",
                digest(&mesh),
                mesh.nodes.len(),
                mesh.cells.len()
            )
            .unwrap();
        }
    }
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(GOLDEN, &table).unwrap();
        return;
    }
    let golden = std::fs::read_to_string(GOLDEN).expect("fixtures/golden/mesh-digests.txt");
    for (now, then) in table.lines().zip(golden.lines()) {
        assert_eq!(
            now, then,
            "a built-in mesh changed; if on purpose, rerun with UPDATE_GOLDEN=1 and say why"
        );
    }
    assert_eq!(table.lines().count(), golden.lines().count());
}

/// The library's `mesh` makes, in-process, the very mesh the command writes: the same digest
/// as the `.msh` file read back (2D at P2 and P3, with triangles, and 3D).
#[test]
fn the_library_makes_the_mesh_the_command_writes() {
    let dir = tempfile::tempdir().unwrap();
    for (name, flags) in [
        ("naca0012", &["--order", "3"][..]),
        ("lshape", &["--order", "2", "--triangles"][..]),
        ("step", &["--order", "1"][..]),
    ] {
        let written = mesh_of(dir.path(), name, flags);
        let case = curvemesh::load(name).unwrap();
        let options = curvemesh::Options {
            order: Some(flags[1].parse().unwrap()),
            triangles: flags.contains(&"--triangles"),
            ..curvemesh::Options::default()
        };
        let meshed = curvemesh::mesh(&case, &options, &mut curvemesh::Silent).unwrap();
        assert!(
            meshed.report.is_valid(),
            "{name}: {:?}",
            meshed.report.problems
        );
        assert_eq!(digest(&meshed.mesh), digest(&written), "{name} {flags:?}");
    }
}
