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
use crate::text::{push_int, write_points, write_records};

/// Writes `mesh` to `path` as Gmsh MSH 4.1 ASCII, atomically.
///
/// Errors: [`IoError::NonFiniteNode`] or [`IoError::InvalidMesh`] before anything is
/// written, [`IoError::Io`] when the file cannot be written.
pub fn write(path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    write_atomic(path, |w| {
        body(w, mesh, &groups, Encoding::Ascii).map_err(|e| IoError::io(path, e))
    })
}

/// Writes `mesh` as MSH 4.1 ASCII to any writer (for example a `Vec<u8>`); `path` only names
/// the destination in errors. Not atomic: use [`write()`] for files.
pub fn write_to(out: &mut dyn Write, mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    body(out, mesh, &groups, Encoding::Ascii).map_err(|e| IoError::io(path, e))
}

/// Writes `mesh` as MSH 4.1 *binary* (file type 1, little-endian, `size_t` of 8 bytes) to
/// any writer: the same sections as [`write_to`], with `$Entities`, `$Nodes` and
/// `$Elements` in binary, as Gmsh writes them with `Mesh.Binary = 1`. Not atomic.
///
/// Errors: as [`write_to`].
pub fn write_binary_to(out: &mut dyn Write, mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    body(out, mesh, &groups, Encoding::Binary).map_err(|e| IoError::io(path, e))
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

/// The elements of a block: each one's tag (`first_tag` + index + 1), then its nodes' tags;
/// a line each in text, `size_t` numbers in binary.
fn write_elements<'m>(
    w: &mut dyn Write,
    encoding: Encoding,
    (elements, first_tag): (&[usize], usize),
    nodes: impl Fn(usize) -> &'m [u32] + Sync,
) -> io::Result<()> {
    write_records(w, elements.len(), |k, b| {
        let i = elements[k];
        match encoding {
            Encoding::Ascii => {
                push_int(b, first_tag + i + 1);
                for &v in nodes(i) {
                    b.push(b' ');
                    push_int(b, v as usize + 1);
                }
                b.push(b'\n');
            }
            Encoding::Binary => {
                b.size(first_tag + i + 1);
                nodes(i).iter().for_each(|&v| b.size(v as usize + 1));
            }
        }
    })
}

/// How the `$Entities`, `$Nodes` and `$Elements` sections are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    /// Text (file type 0).
    Ascii,
    /// Little-endian binary (file type 1): `int` 4 bytes, `size_t` 8, `double` 8.
    Binary,
}

/// The element blocks of a mesh: its cells by Gmsh element type, and each patch's facets by
/// element type (BTreeMap: deterministic block order).
struct Blocks<'g> {
    cells: BTreeMap<u32, Vec<usize>>,
    patches: Vec<BTreeMap<u32, Vec<usize>>>,
    /// The boundary group of each patch.
    group_of: &'g [usize],
    /// The mesh's dimension.
    d: usize,
}

impl<'g> Blocks<'g> {
    fn new(mesh: &Mesh, group_of: &'g [usize]) -> Self {
        let mut patches: Vec<BTreeMap<u32, Vec<usize>>> = vec![BTreeMap::new(); mesh.patches.len()];
        for (j, f) in mesh.boundary.iter().enumerate() {
            let ty = gmsh_type_id(f.ty).unwrap_or(0);
            patches[mesh.boundary_patch[j] as usize]
                .entry(ty)
                .or_default()
                .push(j);
        }
        let mut cells: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
        for (i, t) in mesh.cells.types().iter().enumerate() {
            cells
                .entry(gmsh_type_id(*t).unwrap_or(0))
                .or_default()
                .push(i);
        }
        Blocks {
            cells,
            patches,
            group_of,
            d: mesh.dim.as_u8() as usize,
        }
    }

    fn count(&self) -> usize {
        self.cells.len() + self.patches.iter().map(BTreeMap::len).sum::<usize>()
    }

    /// The box of the facets of patch `i`.
    fn patch_box(&self, mesh: &Mesh, i: usize) -> [f64; 6] {
        let nodes = self.patches[i]
            .values()
            .flatten()
            .flat_map(|&j| mesh.boundary.get(j).nodes.iter().copied());
        bounding_box(mesh, nodes)
    }
}

fn body(
    w: &mut dyn Write,
    mesh: &Mesh,
    (groups, group_of): &(Vec<Group>, Vec<usize>),
    encoding: Encoding,
) -> io::Result<()> {
    let d = mesh.dim.as_u8() as usize;
    let blocks = Blocks::new(mesh, group_of);
    match encoding {
        Encoding::Ascii => writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?,
        Encoding::Binary => {
            // the 1 as a binary int tells the reader the byte order
            w.write_all(b"$MeshFormat\n4.1 1 8\n")?;
            w.write_all(&1i32.to_le_bytes())?;
            w.write_all(b"\n$EndMeshFormat\n")?;
        }
    }

    writeln!(w, "$PhysicalNames\n{}", 1 + groups.len())?;
    writeln!(w, "{d} {FLUID_TAG} {}", quote(FLUID_GROUP))?;
    for (k, g) in groups.iter().enumerate() {
        writeln!(w, "{} {} {}", d - 1, group_tag(k), quote(&g.name))?;
    }
    writeln!(w, "$EndPhysicalNames")?;

    match encoding {
        Encoding::Ascii => ascii_sections(w, mesh, &blocks)?,
        Encoding::Binary => binary_sections(w, mesh, &blocks)?,
    }

    writeln!(w, "${PATCH_SECTION}\n{}", mesh.patches.len())?;
    for (i, p) in mesh.patches.iter().enumerate() {
        writeln!(w, "{} {} {}", i + 1, p.role.name(), quote(&p.name))?;
    }
    writeln!(w, "$End{PATCH_SECTION}")?;
    w.flush()
}

/// `$Entities`, `$Nodes` and `$Elements` as text.
fn ascii_sections(w: &mut dyn Write, mesh: &Mesh, blocks: &Blocks) -> io::Result<()> {
    let (d, n_patches, group_of) = (blocks.d, mesh.patches.len(), blocks.group_of);
    writeln!(w, "$Entities")?;
    match mesh.dim {
        Dim::Two => writeln!(w, "0 {n_patches} 1 0")?,
        Dim::Three => writeln!(w, "0 0 {n_patches} 1")?,
    }
    for (i, &group) in group_of.iter().enumerate().take(n_patches) {
        write!(w, "{} ", i + 1)?;
        write_box(w, &blocks.patch_box(mesh, i))?;
        writeln!(w, " 1 {} 0", group_tag(group))?;
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
        write_points(w, &mesh.nodes)?;
    }
    writeln!(w, "$EndNodes")?;

    let n_cells = mesh.cells.len();
    let total = n_cells + mesh.boundary.len();
    writeln!(w, "$Elements")?;
    if total == 0 {
        writeln!(w, "0 0 0 0")?;
    } else {
        writeln!(w, "{} {total} 1 {total}", blocks.count())?;
    }
    for (ty, cells) in &blocks.cells {
        writeln!(w, "{d} 1 {ty} {}", cells.len())?;
        write_elements(w, Encoding::Ascii, (cells, 0), |i| mesh.cells.get(i).nodes)?;
    }
    for (p, patch) in blocks.patches.iter().enumerate() {
        for (ty, facets) in patch {
            writeln!(w, "{} {} {ty} {}", d - 1, p + 1, facets.len())?;
            let nodes = |j| mesh.boundary.get(j).nodes;
            write_elements(w, Encoding::Ascii, (facets, n_cells), nodes)?;
        }
    }
    writeln!(w, "$EndElements")
}

/// Little-endian `int`, `size_t` and `double` values, appended to a buffer.
trait PushBinary {
    fn int(&mut self, v: usize);
    fn size(&mut self, v: usize);
    fn double(&mut self, v: f64);
}

impl PushBinary for Vec<u8> {
    fn int(&mut self, v: usize) {
        // tags and counts of entities and types: small (checked by `prepare`'s callers)
        self.extend_from_slice(&(v as i32).to_le_bytes());
    }
    fn size(&mut self, v: usize) {
        self.extend_from_slice(&(v as u64).to_le_bytes());
    }
    fn double(&mut self, v: f64) {
        self.extend_from_slice(&v.to_le_bytes());
    }
}

/// `$Entities`, `$Nodes` and `$Elements` in binary, each followed by a newline before its
/// end line, as Gmsh writes them.
fn binary_sections(w: &mut dyn Write, mesh: &Mesh, blocks: &Blocks) -> io::Result<()> {
    let (d, n_patches) = (blocks.d, mesh.patches.len());
    let mut b: Vec<u8> = Vec::new();
    let counts = match mesh.dim {
        Dim::Two => [0, n_patches, 1, 0],
        Dim::Three => [0, 0, n_patches, 1],
    };
    counts.into_iter().for_each(|c| b.size(c));
    for (i, &group) in blocks.group_of.iter().enumerate().take(n_patches) {
        b.int(i + 1);
        blocks
            .patch_box(mesh, i)
            .into_iter()
            .for_each(|x| b.double(x));
        b.size(1);
        b.int(group_tag(group));
        b.size(0);
    }
    b.int(1);
    cells_bounding_box(mesh)
        .into_iter()
        .for_each(|x| b.double(x));
    b.size(1);
    b.int(FLUID_TAG);
    b.size(n_patches);
    (1..=n_patches).for_each(|i| b.int(i));
    w.write_all(b"$Entities\n")?;
    w.write_all(&b)?;
    w.write_all(b"\n$EndEntities\n")?;

    let n = mesh.nodes.len();
    b.clear();
    let header = if n == 0 { [0; 4] } else { [1, n, 1, n] };
    header.into_iter().for_each(|c| b.size(c));
    if n > 0 {
        b.int(d);
        b.int(1);
        b.int(0);
        b.size(n);
    }
    w.write_all(b"$Nodes\n")?;
    w.write_all(&b)?;
    write_records(w, n, |i, b| b.size(i + 1))?;
    write_records(w, n, |i, b| {
        mesh.nodes[i].into_iter().for_each(|x| b.double(x))
    })?;
    w.write_all(b"\n$EndNodes\n")?;

    let n_cells = mesh.cells.len();
    let total = n_cells + mesh.boundary.len();
    b.clear();
    let header = if total == 0 {
        [0; 4]
    } else {
        [blocks.count(), total, 1, total]
    };
    header.into_iter().for_each(|c| b.size(c));
    w.write_all(b"$Elements\n")?;
    w.write_all(&b)?;
    let block = |w: &mut dyn Write, dim: usize, entity: usize, ty: u32, elements: &[usize]| {
        let mut b = Vec::new();
        b.int(dim);
        b.int(entity);
        b.int(ty as usize);
        b.size(elements.len());
        w.write_all(&b)
    };
    let binary = Encoding::Binary;
    for (&ty, cells) in &blocks.cells {
        block(w, d, 1, ty, cells)?;
        write_elements(w, binary, (cells, 0), |i| mesh.cells.get(i).nodes)?;
    }
    for (p, patch) in blocks.patches.iter().enumerate() {
        for (&ty, facets) in patch {
            block(w, d - 1, p + 1, ty, facets)?;
            write_elements(w, binary, (facets, n_cells), |j| mesh.boundary.get(j).nodes)?;
        }
    }
    w.write_all(b"\n$EndElements\n")
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
