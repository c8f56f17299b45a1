//! The MSH 4.1 ASCII writer (layout described in the parent module).

use std::collections::BTreeMap;
use std::io::{self, Write};
use std::path::Path;

use mesh_model::{Dim, Mesh};
use rayon::prelude::*;

use crate::groups::{Group, boundary_groups};

use super::{FLUID_GROUP, PATCH_SECTION, gmsh_type_id};
use crate::IoError;
use crate::atomic::write_atomic;
use crate::check::check_writable;
use crate::text::{push_f64, push_int, write_records};

/// Writes `mesh` to `path` as Gmsh MSH 4.1 ASCII, atomically.
///
/// Errors: [`IoError::NonFiniteNode`] or [`IoError::InvalidMesh`] before anything is
/// written, [`IoError::Io`] when the file cannot be written.
pub fn write(path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    write_atomic(path, |w| {
        body(w, mesh, &groups).map_err(|e| IoError::io(path, e))
    })
}

/// Writes `mesh` as MSH 4.1 ASCII to any writer (for example a `Vec<u8>`); `path` only names
/// the destination in errors. Not atomic: use [`write()`] for files.
pub fn write_to(out: &mut dyn Write, mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    body(out, mesh, &groups).map_err(|e| IoError::io(path, e))
}

/// Checks the mesh and returns its boundary groups (in the order of their physical tags) and
/// the group of each patch.
fn prepare(mesh: &Mesh, path: &Path) -> Result<(Vec<Group>, Vec<usize>), IoError> {
    check_writable(mesh, path)?;
    for (i, p) in mesh.patches.iter().enumerate() {
        if p.name.chars().any(char::is_control) {
            return Err(IoError::InvalidMesh {
                path: path.to_path_buf(),
                message: format!("patch {i} has a control character in its name {:?}", p.name),
            });
        }
    }
    boundary_groups(mesh).map_err(|message| IoError::InvalidMesh {
        path: path.to_path_buf(),
        message,
    })
}

/// Physical tag of the `fluid` group.
const FLUID_TAG: usize = 1;

/// Physical tag of boundary group number `k`.
fn group_tag(k: usize) -> usize {
    FLUID_TAG + 1 + k
}

/// Axis-aligned bounding box of some nodes: min then max; zeros when there is none.
fn bounding_box(mesh: &Mesh, nodes: impl Iterator<Item = u32>) -> [f64; 6] {
    let b = nodes.fold(EMPTY_BOX, |b, n| add_node(b, mesh.nodes[n as usize]));
    if b[0] > b[3] { [0.0; 6] } else { b }
}

/// The bounding box of the nodes of every cell, by chunks of cells in parallel (min and max
/// do not depend on the order they are taken in).
fn cells_bounding_box(mesh: &Mesh) -> [f64; 6] {
    let b = mesh
        .cells
        .flat_nodes()
        .par_chunks(1 << 16)
        .map(|nodes| bounding_box(mesh, nodes.iter().copied()))
        .reduce(|| EMPTY_BOX, merge_boxes);
    if b[0] > b[3] { [0.0; 6] } else { b }
}

const EMPTY_BOX: [f64; 6] = [
    f64::INFINITY,
    f64::INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
];

/// The box grown to hold `p`; of equal values (0.0 and -0.0) the first one met stays, so
/// that the box does not depend on how the nodes are split among threads.
fn add_node(mut b: [f64; 6], p: [f64; 3]) -> [f64; 6] {
    for k in 0..3 {
        if p[k] < b[k] {
            b[k] = p[k];
        }
        if p[k] > b[k + 3] {
            b[k + 3] = p[k];
        }
    }
    b
}

fn merge_boxes(a: [f64; 6], b: [f64; 6]) -> [f64; 6] {
    if a[0] > a[3] {
        return b;
    }
    if b[0] > b[3] {
        return a;
    }
    let lo = add_node(a, [b[0], b[1], b[2]]);
    add_node(lo, [b[3], b[4], b[5]])
}

fn write_box(w: &mut dyn Write, b: &[f64; 6]) -> io::Result<()> {
    write!(
        w,
        "{:?} {:?} {:?} {:?} {:?} {:?}",
        b[0], b[1], b[2], b[3], b[4], b[5]
    )
}

/// Quotes a name for the file: `"` and `\` are escaped with a backslash.
pub(crate) fn quote(name: &str) -> String {
    let mut s = String::with_capacity(name.len() + 2);
    s.push('"');
    for c in name.chars() {
        if c == '"' || c == '\\' {
            s.push('\\');
        }
        s.push(c);
    }
    s.push('"');
    s
}

/// One line per element of a block: its tag (`first_tag` + index + 1), then its nodes' tags.
fn write_elements<'m>(
    w: &mut dyn Write,
    elements: &[usize],
    first_tag: usize,
    nodes: impl Fn(usize) -> &'m [u32] + Sync,
) -> io::Result<()> {
    write_records(w, elements.len(), |k, b| {
        let i = elements[k];
        push_int(b, first_tag + i + 1);
        for &v in nodes(i) {
            b.push(b' ');
            push_int(b, v as usize + 1);
        }
        b.push(b'\n');
    })
}

fn body(
    w: &mut dyn Write,
    mesh: &Mesh,
    (groups, group_of): &(Vec<Group>, Vec<usize>),
) -> io::Result<()> {
    let d = mesh.dim.as_u8() as usize;
    let n_patches = mesh.patches.len();

    writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;

    writeln!(w, "$PhysicalNames\n{}", 1 + groups.len())?;
    writeln!(w, "{d} {FLUID_TAG} {}", quote(FLUID_GROUP))?;
    for (k, g) in groups.iter().enumerate() {
        writeln!(w, "{} {} {}", d - 1, group_tag(k), quote(&g.name))?;
    }
    writeln!(w, "$EndPhysicalNames")?;

    // Facets of each patch, grouped by element type (BTreeMap: deterministic block order).
    let mut patch_blocks: Vec<BTreeMap<u32, Vec<usize>>> = vec![BTreeMap::new(); n_patches];
    for (j, f) in mesh.boundary.iter().enumerate() {
        let ty = gmsh_type_id(f.ty).unwrap_or(0);
        patch_blocks[mesh.boundary_patch[j] as usize]
            .entry(ty)
            .or_default()
            .push(j);
    }

    writeln!(w, "$Entities")?;
    match mesh.dim {
        Dim::Two => writeln!(w, "0 {n_patches} 1 0")?,
        Dim::Three => writeln!(w, "0 0 {n_patches} 1")?,
    }
    for i in 0..n_patches {
        let nodes = patch_blocks[i]
            .values()
            .flatten()
            .flat_map(|&j| mesh.boundary.get(j).nodes.iter().copied());
        write!(w, "{} ", i + 1)?;
        write_box(w, &bounding_box(mesh, nodes))?;
        writeln!(w, " 1 {} 0", group_tag(group_of[i]))?;
    }
    write!(w, "1 ")?;
    write_box(w, &cells_bounding_box(mesh))?;
    write!(w, " 1 {FLUID_TAG} {n_patches}")?;
    for i in 0..n_patches {
        write!(w, " {}", i + 1)?;
    }
    writeln!(w, "\n$EndEntities")?;

    let n = mesh.nodes.len();
    writeln!(w, "$Nodes")?;
    if n == 0 {
        writeln!(w, "0 0 0 0")?;
    } else {
        writeln!(w, "1 {n} 1 {n}\n{d} 1 0 {n}")?;
        write_records(w, n, |i, b| {
            push_int(b, i + 1);
            b.push(b'\n');
        })?;
        write_records(w, n, |i, b| {
            let p = mesh.nodes[i];
            push_f64(b, p[0]);
            b.push(b' ');
            push_f64(b, p[1]);
            b.push(b' ');
            push_f64(b, p[2]);
            b.push(b'\n');
        })?;
    }
    writeln!(w, "$EndNodes")?;

    let mut cell_blocks: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
    for (i, t) in mesh.cells.types().iter().enumerate() {
        cell_blocks
            .entry(gmsh_type_id(*t).unwrap_or(0))
            .or_default()
            .push(i);
    }
    let n_cells = mesh.cells.len();
    let total = n_cells + mesh.boundary.len();
    let n_blocks = cell_blocks.len() + patch_blocks.iter().map(BTreeMap::len).sum::<usize>();
    writeln!(w, "$Elements")?;
    if total == 0 {
        writeln!(w, "0 0 0 0")?;
    } else {
        writeln!(w, "{n_blocks} {total} 1 {total}")?;
    }
    for (ty, cells) in &cell_blocks {
        writeln!(w, "{d} 1 {ty} {}", cells.len())?;
        write_elements(w, cells, 0, |i| mesh.cells.get(i).nodes)?;
    }
    for (p, blocks) in patch_blocks.iter().enumerate() {
        for (ty, facets) in blocks {
            writeln!(w, "{} {} {ty} {}", d - 1, p + 1, facets.len())?;
            write_elements(w, facets, n_cells, |j| mesh.boundary.get(j).nodes)?;
        }
    }
    writeln!(w, "$EndElements")?;

    writeln!(w, "${PATCH_SECTION}\n{n_patches}")?;
    for (i, p) in mesh.patches.iter().enumerate() {
        writeln!(w, "{} {} {}", i + 1, p.role.name(), quote(&p.name))?;
    }
    writeln!(w, "$End{PATCH_SECTION}")?;
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::{AnnulusParams, annulus};

    #[test]
    fn the_domain_box_is_the_first_zero_met_whatever_the_threads() {
        // more nodes than one chunk of the parallel box, the lowest x a zero of each sign
        let mut m = annulus(&AnnulusParams {
            order: 2,
            radial_cells: 40,
            angular_cells: 400,
            ..AnnulusParams::default()
        });
        let lowest = m.nodes.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        for p in &mut m.nodes {
            p[0] -= lowest;
        }
        let flat: Vec<u32> = m.cells.flat_nodes().to_vec();
        let (first, later) = (flat[0] as usize, flat[flat.len() - 1] as usize);
        m.nodes[first][0] = -0.0;
        m.nodes[later][0] = 0.0;
        let sequential = bounding_box(&m, m.cells.flat_nodes().iter().copied());
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let parallel = pool.install(|| cells_bounding_box(&m));
            assert_eq!(parallel.map(f64::to_bits), sequential.map(f64::to_bits));
        }
        assert!(sequential[0] == 0.0 && sequential[0].is_sign_negative());
    }
}
