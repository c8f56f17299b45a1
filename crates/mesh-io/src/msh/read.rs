//! The MSH 4.1 reader, ASCII and binary. It reads tokens, not lines (as Gmsh itself does),
//! and remembers the line of each token for error messages; in a binary file the numbers of
//! `$Entities`, `$Nodes` and `$Elements` are read as little-endian binary instead.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::Path;
use std::str::FromStr;

use mesh_model::{CellType, Cells, Dim, Mesh, Patch, Role};

use super::{GMSH_POINT, PATCH_SECTION, cell_type_of_gmsh};
use crate::IoError;

/// Reads a Gmsh MSH 4.1 file (ASCII, or binary little-endian with 8-byte sizes) into a
/// [`Mesh`].
///
/// How the file becomes a mesh:
/// - The dimension is the highest dimension of its elements: 3 gives a volume mesh; 2 gives
///   a 2D mesh when every node has z = 0, and otherwise a 3D *surface* mesh (no cells, the
///   triangles and quadrangles become boundary facets). Points and elements two or more
///   dimensions below the top are ignored.
/// - Domain cells are all elements of the top dimension, in the order of their element tags.
/// - Boundary facets are the elements one dimension lower, in the order of their tags. Each
///   entity holding facets becomes a patch (patches in the order of entity tags), in exactly
///   one physical group. Its role: `wall` or `farfield` when the group is so named (case
///   ignored); else the role the `$MeshIoPatches` section this crate writes gives it; else
///   (a group named after a body, `slat`, in a file without that section) a wall. Its name
///   comes from that section, or else is the group's name. In a surface mesh an entity may
///   be in no physical group (as Gmsh saves a mesh without any): a wall named `wall`.
/// - Nodes are all nodes of the file, in the order of their tags. The order of the mesh is
///   the highest order of its cells (of its facets for a surface mesh).
///
/// Errors: [`IoError::Io`] if the file cannot be read; otherwise see [`parse`].
pub fn read(path: &Path) -> Result<Mesh, IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    parse(&bytes, path)
}

/// Parses the bytes of an MSH 4.1 file (see [`read`]); `path` names the file in errors.
///
/// Errors: [`IoError::BinaryMsh`], [`IoError::UnsupportedVersion`],
/// [`IoError::MissingSection`], [`IoError::UnknownElementType`], and [`IoError::Malformed`]
/// with the line for anything else that does not follow the format.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh, IoError> {
    let mut cur = Cursor {
        bytes,
        pos: 0,
        line: 1,
        path,
        binary_file: false,
        binary: false,
    };
    let mut file = RawFile::default();
    let mut seen_format = false;
    while let Some((tok, line)) = cur.token() {
        let Some(name) = tok.strip_prefix(b"$") else {
            return Err(cur.malformed(
                line,
                format!(
                    "expected a section header such as $Nodes, found '{}'",
                    show(tok)
                ),
            ));
        };
        if !seen_format && name != b"MeshFormat" {
            return Err(IoError::MissingSection {
                path: path.to_path_buf(),
                section: "MeshFormat",
            });
        }
        match name {
            b"MeshFormat" => {
                read_format(&mut cur)?;
                seen_format = true;
            }
            b"PhysicalNames" => read_physical_names(&mut cur, &mut file)?,
            b"Entities" => cur.in_data(|cur| read_entities(cur, &mut file))?,
            b"Nodes" => cur.in_data(|cur| read_nodes(cur, &mut file))?,
            b"Elements" => cur.in_data(|cur| read_elements(cur, &mut file))?,
            n if n == PATCH_SECTION.as_bytes() => read_patch_names(&mut cur, &mut file)?,
            other => skip_section(&mut cur, other, line)?,
        }
    }
    if !seen_format {
        return Err(IoError::MissingSection {
            path: path.to_path_buf(),
            section: "MeshFormat",
        });
    }
    assemble(file, &cur)
}

/// What the sections hold, before it is turned into a mesh.
#[derive(Default)]
struct RawFile {
    /// (dimension, physical tag) → name.
    physical_names: HashMap<(u8, i64), String>,
    /// (dimension, entity tag) → physical tags; `None` until `$Entities` is read.
    entities: Option<HashMap<(u8, i64), Vec<i64>>>,
    /// Node tags and coordinates; `None` until `$Nodes` is read.
    nodes: Option<Vec<(u64, [f64; 3])>>,
    /// Elements; `None` until `$Elements` is read.
    elements: Option<Vec<RawElement>>,
    /// Node tags of all elements, flat.
    element_nodes: Vec<u64>,
    /// Line of the `$Elements` header.
    elements_line: usize,
    /// Entity tag → patch name, from `$MeshIoPatches`.
    patch_names: BTreeMap<i64, String>,
    /// Entity tag → patch role, from `$MeshIoPatches`.
    patch_roles: BTreeMap<i64, Role>,
}

/// One element as read.
struct RawElement {
    tag: u64,
    ty: CellType,
    entity: i64,
    /// Line of the element, for errors.
    line: usize,
    /// Start of its node tags in `RawFile::element_nodes`.
    start: usize,
}

/// A position in the file.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    path: &'a Path,
    /// The file is binary (file type 1): `$Entities`, `$Nodes` and `$Elements` hold binary
    /// numbers.
    binary_file: bool,
    /// The numbers being read are binary (inside one of those sections of a binary file).
    binary: bool,
}

/// The width of a binary number: Gmsh's `int` or `size_t`.
#[derive(Debug, Clone, Copy)]
enum Width {
    Int,
    Size,
}

/// Shows a token in an error message (lossy, shortened).
fn show(tok: &[u8]) -> String {
    let s = String::from_utf8_lossy(tok);
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s.into_owned()
    }
}

impl<'a> Cursor<'a> {
    fn malformed(&self, line: usize, message: String) -> IoError {
        IoError::Malformed {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    /// The next whitespace-separated token and its line, or `None` at the end of the file.
    fn token(&mut self) -> Option<(&'a [u8], usize)> {
        let b = self.bytes;
        while self.pos < b.len() && b[self.pos].is_ascii_whitespace() {
            if b[self.pos] == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
        if self.pos == b.len() {
            return None;
        }
        let start = self.pos;
        while self.pos < b.len() && !b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        Some((&b[start..self.pos], self.line))
    }

    /// The next token, or an error naming what was expected at the end of the file.
    fn expect(&mut self, what: &str) -> Result<(&'a [u8], usize), IoError> {
        self.token().ok_or_else(|| {
            self.malformed(
                self.line,
                format!("unexpected end of file: expected {what}"),
            )
        })
    }

    /// The next token parsed as a number.
    fn number<T: FromStr>(&mut self, what: &str) -> Result<(T, usize), IoError> {
        let (tok, line) = self.expect(what)?;
        std::str::from_utf8(tok)
            .ok()
            .and_then(|s| s.parse::<T>().ok())
            .map(|v| (v, line))
            .ok_or_else(|| self.malformed(line, format!("expected {what}, found '{}'", show(tok))))
    }

    fn int<T: FromStr>(&mut self, what: &str) -> Result<T, IoError> {
        self.number::<T>(what).map(|(v, _)| v)
    }

    /// Runs `read` on a section's data, binary in a binary file: the data starts after the
    /// newline that ends the header line.
    fn in_data<T>(
        &mut self,
        read: impl FnOnce(&mut Self) -> Result<T, IoError>,
    ) -> Result<T, IoError> {
        if self.binary_file {
            if self.bytes.get(self.pos) != Some(&b'\n') {
                return Err(
                    self.malformed(self.line, "expected a newline before binary data".into())
                );
            }
            self.pos += 1;
            self.line += 1;
            self.binary = true;
        }
        let result = read(self);
        self.binary = false;
        result
    }

    /// The next `N` bytes of binary data.
    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], IoError> {
        let bytes = self
            .bytes
            .get(self.pos..self.pos + N)
            .and_then(|b| <[u8; N]>::try_from(b).ok())
            .ok_or_else(|| {
                self.malformed(
                    self.line,
                    format!("unexpected end of file: expected {what} (binary)"),
                )
            })?;
        self.pos += N;
        Ok(bytes)
    }

    /// An integer field of `$Entities`, `$Nodes` or `$Elements`: a token, or in a binary
    /// file a little-endian `int` or `size_t` (by `width`).
    fn num<T: FromStr + TryFrom<i64>>(
        &mut self,
        what: &str,
        width: Width,
    ) -> Result<(T, usize), IoError> {
        if !self.binary {
            return self.number::<T>(what);
        }
        let line = self.line;
        let v = match width {
            Width::Int => i64::from(i32::from_le_bytes(self.take::<4>(what)?)),
            Width::Size => {
                let v = u64::from_le_bytes(self.take::<8>(what)?);
                i64::try_from(v).unwrap_or(i64::MAX)
            }
        };
        T::try_from(v)
            .map(|v| (v, line))
            .map_err(|_| self.malformed(line, format!("expected {what}, found {v}")))
    }

    /// A floating-point field: a token, or in a binary file a little-endian `double`.
    fn real(&mut self, what: &str) -> Result<(f64, usize), IoError> {
        if !self.binary {
            return self.number::<f64>(what);
        }
        let line = self.line;
        Ok((f64::from_le_bytes(self.take::<8>(what)?), line))
    }

    /// A count, checked against the bytes left so that a corrupt count cannot make the
    /// reader reserve absurd amounts of memory.
    fn count(&mut self, what: &str, min_bytes_each: usize) -> Result<usize, IoError> {
        let (n, line) = self.num::<usize>(what, Width::Size)?;
        let left = self.bytes.len() - self.pos;
        if n.saturating_mul(min_bytes_each) > left {
            return Err(self.malformed(
                line,
                format!("{what} is {n}, more than the rest of the file can hold"),
            ));
        }
        Ok(n)
    }

    /// A finite coordinate.
    fn coordinate(&mut self) -> Result<f64, IoError> {
        let (v, line) = self.real("a coordinate")?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.malformed(line, format!("non-finite coordinate {v}")))
        }
    }

    /// The rest of the current line, without surrounding whitespace.
    fn rest_of_line(&mut self) -> (&'a [u8], usize) {
        let b = self.bytes;
        let start = self.pos;
        while self.pos < b.len() && b[self.pos] != b'\n' {
            self.pos += 1;
        }
        (b[start..self.pos].trim_ascii(), self.line)
    }

    /// Expects the `$End…` token of a section.
    fn expect_end(&mut self, section: &str) -> Result<(), IoError> {
        let want = format!("$End{section}");
        let (tok, line) = self.expect(&want)?;
        if tok == want.as_bytes() {
            Ok(())
        } else {
            Err(self.malformed(
                line,
                format!(
                    "expected {want}, found '{}' (a count in ${section} does not match its content)",
                    show(tok)
                ),
            ))
        }
    }
}

fn read_format(cur: &mut Cursor<'_>) -> Result<(), IoError> {
    let (version, line) = cur.expect("the MSH version")?;
    if version != b"4.1" {
        return Err(IoError::UnsupportedVersion {
            path: cur.path.to_path_buf(),
            line,
            version: show(version),
        });
    }
    let (file_type, line) = cur.number::<i64>("the file type (0 for ASCII, 1 for binary)")?;
    let data_size: i64 = cur.int("the data size")?;
    match file_type {
        0 => {}
        1 => {
            // the binary int 1 that follows tells the byte order
            let one = cur
                .bytes
                .get(cur.pos + 1..cur.pos + 5)
                .map(|b| [b[0], b[1], b[2], b[3]]);
            if data_size != 8 || cur.bytes.get(cur.pos) != Some(&b'\n') || one != Some([1, 0, 0, 0])
            {
                return Err(IoError::BinaryMsh {
                    path: cur.path.to_path_buf(),
                    line,
                });
            }
            cur.pos += 5;
            cur.line += 1;
            cur.binary_file = true;
        }
        other => {
            return Err(cur.malformed(line, format!("file type {other} is neither 0 nor 1")));
        }
    }
    cur.expect_end("MeshFormat")
}

/// Parses a quoted name, undoing the backslash escapes the writer adds.
fn unquote(cur: &Cursor<'_>, raw: &[u8], line: usize) -> Result<String, IoError> {
    let text = std::str::from_utf8(raw)
        .map_err(|_| cur.malformed(line, "a name is not valid UTF-8".into()))?;
    let inner = text
        .strip_prefix('"')
        .and_then(|t| t.strip_suffix('"'))
        .ok_or_else(|| {
            cur.malformed(
                line,
                format!("expected a name in double quotes, found '{}'", show(raw)),
            )
        })?;
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            match chars.next() {
                Some(e) => out.push(e),
                None => out.push('\\'),
            }
        } else {
            out.push(c);
        }
    }
    Ok(out)
}

fn read_physical_names(cur: &mut Cursor<'_>, file: &mut RawFile) -> Result<(), IoError> {
    let n = cur.count("the number of physical names", 6)?;
    for _ in 0..n {
        let (dim, line) = cur.number::<u8>("a physical group dimension")?;
        if dim > 3 {
            return Err(cur.malformed(line, format!("physical group dimension {dim} is above 3")));
        }
        let tag: i64 = cur.int("a physical tag")?;
        let (raw, line) = cur.rest_of_line();
        let name = unquote(cur, raw, line)?;
        file.physical_names.insert((dim, tag), name);
    }
    cur.expect_end("PhysicalNames")
}

fn read_entities(cur: &mut Cursor<'_>, file: &mut RawFile) -> Result<(), IoError> {
    let mut counts = [0usize; 4];
    for (d, c) in counts.iter_mut().enumerate() {
        let what = ["points", "curves", "surfaces", "volumes"][d];
        *c = cur.count(&format!("the number of {what} entities"), 8)?;
    }
    let mut entities = HashMap::new();
    for (d, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let (tag, _): (i64, _) = cur.num("an entity tag", Width::Int)?;
            let n_coords = if d == 0 { 3 } else { 6 };
            for _ in 0..n_coords {
                cur.real("an entity coordinate")?;
            }
            let n_phys = cur.count("the number of physical tags", 2)?;
            let mut phys = Vec::with_capacity(n_phys);
            for _ in 0..n_phys {
                phys.push(cur.num::<i64>("a physical tag", Width::Int)?.0.abs());
            }
            if d > 0 {
                let n_bound = cur.count("the number of bounding entities", 2)?;
                for _ in 0..n_bound {
                    cur.num::<i64>("a bounding entity tag", Width::Int)?;
                }
            }
            entities.insert((d as u8, tag), phys);
        }
    }
    file.entities = Some(entities);
    cur.expect_end("Entities")
}

fn read_nodes(cur: &mut Cursor<'_>, file: &mut RawFile) -> Result<(), IoError> {
    let n_blocks = cur.count("the number of node blocks", 8)?;
    let header_line = cur.line;
    let n_nodes = cur.count("the number of nodes", 8)?;
    let _min_tag: (u64, _) = cur.num("the smallest node tag", Width::Size)?;
    let _max_tag: (u64, _) = cur.num("the largest node tag", Width::Size)?;
    let mut nodes = Vec::with_capacity(n_nodes);
    let mut tags = Vec::new();
    for _ in 0..n_blocks {
        let (dim, line) = cur.num::<usize>("a node block's entity dimension", Width::Int)?;
        if dim > 3 {
            return Err(cur.malformed(line, format!("entity dimension {dim} is above 3")));
        }
        let _entity: (i64, _) = cur.num("a node block's entity tag", Width::Int)?;
        let (parametric, line) =
            cur.num::<u8>("a node block's parametric flag (0 or 1)", Width::Int)?;
        let extra = match parametric {
            0 => 0,
            1 => dim,
            other => {
                return Err(
                    cur.malformed(line, format!("parametric flag {other} is neither 0 nor 1"))
                );
            }
        };
        let count = cur.count("the number of nodes in a block", 8)?;
        tags.clear();
        for _ in 0..count {
            tags.push(cur.num::<u64>("a node tag", Width::Size)?.0);
        }
        for &tag in &tags {
            let p = [cur.coordinate()?, cur.coordinate()?, cur.coordinate()?];
            for _ in 0..extra {
                cur.real("a parametric coordinate")?;
            }
            nodes.push((tag, p));
        }
    }
    if nodes.len() != n_nodes {
        return Err(cur.malformed(
            header_line,
            format!(
                "$Nodes announces {n_nodes} nodes but its blocks hold {}",
                nodes.len()
            ),
        ));
    }
    file.nodes = Some(nodes);
    cur.expect_end("Nodes")
}

fn read_elements(cur: &mut Cursor<'_>, file: &mut RawFile) -> Result<(), IoError> {
    let n_blocks = cur.count("the number of element blocks", 8)?;
    let header_line = cur.line;
    let n_elements = cur.count("the number of elements", 4)?;
    let _min_tag: (u64, _) = cur.num("the smallest element tag", Width::Size)?;
    let _max_tag: (u64, _) = cur.num("the largest element tag", Width::Size)?;
    let mut elements = Vec::with_capacity(n_elements);
    let mut total = 0usize;
    for _ in 0..n_blocks {
        let (dim, line) = cur.num::<u8>("an element block's entity dimension", Width::Int)?;
        let (entity, _): (i64, _) = cur.num("an element block's entity tag", Width::Int)?;
        let (type_id, type_line) = cur.num::<i64>("an element type", Width::Int)?;
        let count = cur.count("the number of elements in a block", 4)?;
        total += count;
        let (ty, n_nodes) = if type_id == i64::from(GMSH_POINT) {
            (None, 1)
        } else {
            let ty = u32::try_from(type_id)
                .ok()
                .and_then(cell_type_of_gmsh)
                .ok_or_else(|| IoError::UnknownElementType {
                    path: cur.path.to_path_buf(),
                    line: type_line,
                    type_id,
                })?;
            (Some(ty), ty.node_count())
        };
        let type_dim = ty.map_or(0, |t| t.shape.dim());
        if type_dim != dim {
            return Err(cur.malformed(
                line,
                format!("element type {type_id} has dimension {type_dim}, but its block is of dimension {dim}"),
            ));
        }
        for _ in 0..count {
            let (tag, line) = cur.num::<u64>("an element tag", Width::Size)?;
            let start = file.element_nodes.len();
            for _ in 0..n_nodes {
                let what = if cur.binary {
                    "a node tag of an element"
                } else {
                    &format!("one of the {n_nodes} node tags of element {tag}")
                };
                let v = cur.num::<u64>(what, Width::Size)?.0;
                file.element_nodes.push(v);
            }
            match ty {
                Some(ty) => elements.push(RawElement {
                    tag,
                    ty,
                    entity,
                    line,
                    start,
                }),
                None => file.element_nodes.truncate(start),
            }
        }
    }
    if total != n_elements {
        return Err(cur.malformed(
            header_line,
            format!("$Elements announces {n_elements} elements but its blocks hold {total}"),
        ));
    }
    file.elements = Some(elements);
    file.elements_line = header_line;
    cur.expect_end("Elements")
}

fn read_patch_names(cur: &mut Cursor<'_>, file: &mut RawFile) -> Result<(), IoError> {
    let n = cur.count("the number of patch names", 4)?;
    for _ in 0..n {
        let tag: i64 = cur.int("a patch entity tag")?;
        let (raw, line) = cur.rest_of_line();
        // `tag role "name"`, or `tag "name"` in files written before roles were recorded
        let (role, raw) = match raw.iter().position(|&b| b == b' ') {
            Some(k) if raw[0] != b'"' => {
                let word = std::str::from_utf8(&raw[..k]).unwrap_or_default();
                let role = role_of_name(word).ok_or_else(|| {
                    cur.malformed(line, format!("unknown patch role '{}'", show(&raw[..k])))
                })?;
                (Some(role), raw[k..].trim_ascii())
            }
            _ => (None, raw),
        };
        let name = unquote(cur, raw, line)?;
        file.patch_names.insert(tag, name);
        if let Some(role) = role {
            file.patch_roles.insert(tag, role);
        }
    }
    cur.expect_end(PATCH_SECTION)
}

fn skip_section(cur: &mut Cursor<'_>, name: &[u8], line: usize) -> Result<(), IoError> {
    let mut end = b"$End".to_vec();
    end.extend_from_slice(name);
    while let Some((tok, _)) = cur.token() {
        if tok == end.as_slice() {
            return Ok(());
        }
    }
    Err(cur.malformed(
        line,
        format!("section ${} has no {}", show(name), show(&end)),
    ))
}

/// Maps node tags to node indices.
enum NodeIndex {
    /// Tags are dense enough for a table.
    Dense(Vec<u32>),
    /// Sparse tags.
    Sparse(HashMap<u64, u32>),
}

impl NodeIndex {
    fn get(&self, tag: u64) -> Option<u32> {
        match self {
            NodeIndex::Dense(v) => v
                .get(usize::try_from(tag).ok()?)
                .copied()
                .filter(|&i| i != u32::MAX),
            NodeIndex::Sparse(m) => m.get(&tag).copied(),
        }
    }
}

fn role_of_name(name: &str) -> Option<Role> {
    [Role::Wall, Role::Farfield]
        .into_iter()
        .find(|r| r.name().eq_ignore_ascii_case(name))
}

/// The nodes in tag order and the index from a tag to its position; a tag given twice is an
/// error (named at `elements_line`, the nearest line the reader kept).
fn node_table(
    mut raw_nodes: Vec<(u64, [f64; 3])>,
    cur: &Cursor<'_>,
    elements_line: usize,
) -> Result<(Vec<[f64; 3]>, NodeIndex), IoError> {
    if !raw_nodes.is_sorted_by_key(|n| n.0) {
        raw_nodes.sort_by_key(|n| n.0);
    }
    if let Some(w) = raw_nodes.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err(cur.malformed(
            elements_line,
            format!("node tag {} appears twice in $Nodes", w[0].0),
        ));
    }
    if raw_nodes.len() >= u32::MAX as usize {
        return Err(cur.malformed(1, "more nodes than this reader can index".into()));
    }
    let max_tag = raw_nodes.last().map_or(0, |n| n.0);
    let index = if max_tag <= 4 * raw_nodes.len() as u64 + 1024 {
        let mut v = vec![u32::MAX; max_tag as usize + 1];
        for (i, n) in raw_nodes.iter().enumerate() {
            v[n.0 as usize] = i as u32;
        }
        NodeIndex::Dense(v)
    } else {
        NodeIndex::Sparse(
            raw_nodes
                .iter()
                .enumerate()
                .map(|(i, n)| (n.0, i as u32))
                .collect(),
        )
    };
    let nodes = raw_nodes.into_iter().map(|n| n.1).collect();
    Ok((nodes, index))
}

/// The boundary patches: the entities holding facets and those named in `$MeshIoPatches`,
/// each with its name and role (from its one physical group; in a surface mesh, an entity in
/// none is a wall named `wall`), and the entity → patch map.
fn patches_of(
    file: &RawFile,
    facet_elems: &[&RawElement],
    (fd, surface): (u8, bool),
    cur: &Cursor<'_>,
) -> Result<(Vec<Patch>, HashMap<i64, u32>), IoError> {
    let mut patch_entities: BTreeSet<i64> = facet_elems.iter().map(|e| e.entity).collect();
    patch_entities.extend(file.patch_names.keys().copied());
    let mut patches = Vec::with_capacity(patch_entities.len());
    let mut patch_of_entity = HashMap::with_capacity(patch_entities.len());
    for &entity in &patch_entities {
        let line = facet_elems
            .iter()
            .find(|e| e.entity == entity)
            .map_or(file.elements_line, |e| e.line);
        let entities = file
            .entities
            .as_ref()
            .ok_or_else(|| IoError::MissingSection {
                path: cur.path.to_path_buf(),
                section: "Entities",
            })?;
        let groups: Vec<&str> = entities
            .get(&(fd, entity))
            .into_iter()
            .flatten()
            .filter_map(|t| file.physical_names.get(&(fd, *t)).map(String::as_str))
            .collect();
        let roles: BTreeSet<&str> = groups
            .iter()
            .copied()
            .filter(|g| role_of_name(g).is_some())
            .collect();
        let role = match roles.len() {
            1 => role_of_name(roles.first().copied().unwrap_or_default()),
            // a group named after its body (`slat`): the role written beside the patch name,
            // else (a file without our section) a wall
            0 if groups.len() == 1 => file.patch_roles.get(&entity).copied().or(Some(Role::Wall)),
            // a surface saved without physical groups (Gmsh's default): a wall to mesh around
            0 if groups.is_empty() && surface => Some(Role::Wall),
            _ => None,
        }
        .ok_or_else(|| {
            cur.malformed(
                line,
                format!(
                    "boundary entity (dimension {fd}, tag {entity}) must be in exactly one physical group (\"farfield\", or a wall's name); its groups are {groups:?}"
                ),
            )
        })?;
        let name = file
            .patch_names
            .get(&entity)
            .cloned()
            .or_else(|| groups.first().map(|g| g.to_string()))
            .unwrap_or_else(|| role.name().to_string());
        patch_of_entity.insert(entity, patches.len() as u32);
        patches.push(Patch { name, role });
    }
    Ok((patches, patch_of_entity))
}

fn assemble(mut file: RawFile, cur: &Cursor<'_>) -> Result<Mesh, IoError> {
    let path = cur.path;
    let missing = |section| IoError::MissingSection {
        path: path.to_path_buf(),
        section,
    };
    let raw_nodes = file.nodes.take().ok_or_else(|| missing("Nodes"))?;
    let elements = file.elements.take().ok_or_else(|| missing("Elements"))?;

    let (nodes, index) = node_table(raw_nodes, cur, file.elements_line)?;

    let top = elements.iter().map(|e| e.ty.shape.dim()).max().unwrap_or(0);
    let planar = nodes.iter().all(|p| p[2] == 0.0);
    let (dim, cell_dim, facet_dim) = match top {
        3 => (Dim::Three, Some(3), 2),
        2 if planar => (Dim::Two, Some(2), 1),
        2 => (Dim::Three, None, 2),
        _ => {
            return Err(cur.malformed(
                file.elements_line,
                "the file has no 2D or 3D elements, so there is no mesh to read".into(),
            ));
        }
    };

    let resolve = |e: &RawElement| -> Result<Vec<u32>, IoError> {
        file.element_nodes[e.start..e.start + e.ty.node_count()]
            .iter()
            .map(|&t| {
                index.get(t).ok_or_else(|| {
                    cur.malformed(
                        e.line,
                        format!("element {} names node {t}, which is not in $Nodes", e.tag),
                    )
                })
            })
            .collect()
    };

    let mut cell_elems: Vec<&RawElement> = elements
        .iter()
        .filter(|e| Some(e.ty.shape.dim()) == cell_dim)
        .collect();
    cell_elems.sort_by_key(|e| e.tag);
    let mut facet_elems: Vec<&RawElement> = elements
        .iter()
        .filter(|e| e.ty.shape.dim() == facet_dim)
        .collect();
    facet_elems.sort_by_key(|e| e.tag);

    let surface = cell_dim.is_none();
    let (patches, patch_of_entity) = patches_of(&file, &facet_elems, (facet_dim, surface), cur)?;

    let mut cells = Cells::with_capacity(cell_elems.len(), 0);
    for e in &cell_elems {
        cells.push(e.ty, &resolve(e)?);
    }
    let mut boundary = Cells::with_capacity(facet_elems.len(), 0);
    let mut boundary_patch = Vec::with_capacity(facet_elems.len());
    for e in &facet_elems {
        boundary.push(e.ty, &resolve(e)?);
        boundary_patch.push(patch_of_entity[&e.entity]);
    }
    let order_of = |c: &Cells| c.types().iter().map(|t| t.order).max();
    let order = order_of(&cells).or(order_of(&boundary)).unwrap_or(1);

    Ok(Mesh {
        dim,
        order,
        nodes,
        cells,
        boundary,
        boundary_patch,
        patches,
        cell_layer: Vec::new(),
        cell_pipe: Vec::new(),
    })
}
