//! STL surfaces (ASCII and binary) and triangulated `.msh` surfaces read as plain arrays:
//! nodes welded (vertices of identical coordinates merged, exactly; `-0.0` is `0.0`: the
//! repair of STL's separate corners, which changes no coordinate), triangles as three node
//! indices each, in the file's order and orientation, and the group of each triangle
//! ([`GroupedSurface`]). Whether the surface is closed, manifold and consistently oriented
//! is for the caller to check.
//!
//! Groups: one per `solid NAME` of an ASCII STL (solids of one name share a group; an
//! unnamed solid is a group of its own named `""`), one unnamed group for a binary STL,
//! one per physical group of a `.msh` (facets in none make the group `wall`, see
//! [`crate::msh::read`]); groups without a triangle are dropped. Naming unnamed groups is
//! the caller's.
//!
//! A file is binary when its size is exactly 84 bytes plus 50 per triangle its header
//! counts; otherwise it must be ASCII (text starting with `solid`, no NUL byte), and a file
//! of neither kind is reported as a truncated binary STL. Every error names the file and
//! the line (ASCII), byte (binary) or triangle (`.msh`): a malformed facet, a coordinate
//! that is not a finite number, a degenerate facet (two equal vertices, or three on one
//! line: the cross product of its edges exactly zero, `Surface::check`'s test in
//! `geom-surface`), no facet at all.

use std::collections::HashMap;
use std::path::Path;

use mesh_model::{Patch, Role, Shape};

use crate::IoError;

/// Nodes and triangles of a surface.
pub type Surface = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// A surface with the group of each triangle.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupedSurface {
    /// Welded node coordinates.
    pub nodes: Vec<[f64; 3]>,
    /// Triangles, three node indices each, in the file's order and orientation.
    pub triangles: Vec<[u32; 3]>,
    /// The group of each triangle (index into `groups`).
    pub triangle_group: Vec<u32>,
    /// The groups in the order of their first triangle: the name as the file gives it
    /// (`""` for an unnamed STL solid or a binary STL) and the role (a wall, except a `.msh`
    /// group named `farfield`).
    pub groups: Vec<Patch>,
}

impl GroupedSurface {
    /// The nodes and triangles, without the groups.
    pub fn into_plain(self) -> Surface {
        (self.nodes, self.triangles)
    }
}

/// Reads an STL file, ASCII or binary.
pub fn read(path: &Path) -> Result<Surface, IoError> {
    read_grouped(path).map(GroupedSurface::into_plain)
}

/// Reads an STL file, ASCII or binary, with its groups (one per solid).
pub fn read_grouped(path: &Path) -> Result<GroupedSurface, IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    parse_grouped(&bytes, path)
}

/// Reads a closed surface from `.stl` (ASCII or binary) or `.msh` (its linear triangles:
/// the boundary facets of a surface mesh, or the cells of a planar one), by extension.
pub fn read_surface(path: &Path) -> Result<Surface, IoError> {
    read_surface_grouped(path).map(GroupedSurface::into_plain)
}

/// [`read_surface`] with the groups: an STL's solids, a `.msh`'s physical groups.
///
/// Errors: [`IoError::UnknownSurfaceExtension`] for an extension other than `.stl` and
/// `.msh`; otherwise those of [`parse_grouped`] and [`crate::msh::read`].
pub fn read_surface_grouped(path: &Path) -> Result<GroupedSurface, IoError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("stl") => read_grouped(path),
        Some("msh") => msh_surface(path),
        _ => Err(IoError::UnknownSurfaceExtension {
            path: path.to_path_buf(),
        }),
    }
}

/// The triangles of a `.msh` file: a planar mesh's cells (one unnamed group), then the
/// boundary triangles in their patches' groups (patches of one name share a group).
fn msh_surface(path: &Path) -> Result<GroupedSurface, IoError> {
    let m = crate::msh::read(path)?;
    let mut w = Welder::new(path);
    let facets = m.cells.iter().map(|c| (c, None));
    let facets = facets.chain(
        m.boundary
            .iter()
            .zip(&m.boundary_patch)
            .map(|(c, &p)| (c, Some(p))),
    );
    let triangles = facets.filter(|(c, _)| c.ty.shape == Shape::Tri);
    for (i, (c, patch)) in triangles.enumerate() {
        match patch.and_then(|p| m.patches.get(p as usize)) {
            Some(p) => w.select(&p.name, p.role),
            None => w.select("", Role::Wall),
        }
        let k = c.corners();
        let t = [k[0], k[1], k[2]].map(|v| m.nodes[v as usize]);
        let name = || format!("triangle {} (in element tag order)", i + 1);
        w.facet(t, name, Place::Nowhere)?;
    }
    w.finish(Place::Nowhere)
}

/// Parses the bytes of an STL file; `path` only names it in errors.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Surface, IoError> {
    parse_grouped(bytes, path).map(GroupedSurface::into_plain)
}

/// Parses the bytes of an STL file with its groups; `path` only names it in errors.
///
/// Errors: [`IoError::Malformed`] (ASCII, with the line) and [`IoError::MalformedBinary`]
/// (with the byte offset) for anything that does not follow the format, a non-finite
/// coordinate, a degenerate facet or no facet.
pub fn parse_grouped(bytes: &[u8], path: &Path) -> Result<GroupedSurface, IoError> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if n.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len()) {
            return parse_binary(bytes, n, path);
        }
    }
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(0);
    let text = std::str::from_utf8(bytes)
        .ok()
        .filter(|t| bytes[start..].starts_with(b"solid") && !t.contains('\0'));
    if let Some(text) = text {
        return parse_ascii(text, path);
    }
    let message = if bytes.len() < 84 {
        format!(
            "truncated binary STL: {} bytes, shorter than its 84-byte header",
            bytes.len()
        )
    } else {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        format!(
            "truncated binary STL: the header counts {n} triangles ({} bytes) but the file has {}",
            84 + 50 * n,
            bytes.len()
        )
    };
    Err(IoError::MalformedBinary {
        path: path.to_path_buf(),
        offset: bytes.len().min(84),
        message,
    })
}

/// Where a fault is.
#[derive(Clone, Copy)]
enum Place {
    Line(usize),
    Byte(usize),
    /// No line or byte to name (a `.msh` surface: the facet names itself).
    Nowhere,
}

/// Merges vertices of identical coordinates and keeps each triangle's group.
struct Welder<'a> {
    path: &'a Path,
    index: HashMap<[u64; 3], u32>,
    nodes: Vec<[f64; 3]>,
    tris: Vec<[u32; 3]>,
    tri_group: Vec<u32>,
    groups: Vec<Patch>,
    /// The group of the facets to come.
    current: u32,
}

impl<'a> Welder<'a> {
    fn new(path: &'a Path) -> Self {
        Welder {
            path,
            index: HashMap::new(),
            nodes: Vec::new(),
            tris: Vec::new(),
            tri_group: Vec::new(),
            groups: Vec::new(),
            current: u32::MAX,
        }
    }

    fn error(&self, at: Place, message: String) -> IoError {
        let path = self.path.to_path_buf();
        match at {
            Place::Line(line) => IoError::Malformed {
                path,
                line,
                message,
            },
            Place::Byte(offset) => IoError::MalformedBinary {
                path,
                offset,
                message,
            },
            Place::Nowhere => IoError::BadSurface { path, message },
        }
    }

    /// The facets to come are in the group `name` (made if it is new).
    fn select(&mut self, name: &str, role: Role) {
        match self.groups.iter().position(|g| g.name == name) {
            Some(g) => self.current = g as u32,
            None => self.fresh(name, role),
        }
    }

    /// The facets to come are in a new group `name` (even if one has that name).
    fn fresh(&mut self, name: &str, role: Role) {
        self.current = self.groups.len() as u32;
        self.groups.push(Patch {
            name: name.to_string(),
            role,
        });
    }

    /// Adds a facet; `name` names it in errors.
    fn facet(
        &mut self,
        t: [[f64; 3]; 3],
        name: impl Fn() -> String,
        at: Place,
    ) -> Result<(), IoError> {
        if let Some(p) = t.iter().find(|p| !p.iter().all(|x| x.is_finite())) {
            return Err(self.error(at, format!("{}: vertex {p:?} is not finite", name())));
        }
        let mut k = [0u32; 3];
        for (v, p) in k.iter_mut().zip(t) {
            let key = p.map(|x| (x + 0.0).to_bits());
            let next = self.nodes.len() as u32;
            *v = *self.index.entry(key).or_insert(next);
            if *v == next {
                self.nodes.push(p.map(|x| x + 0.0));
            }
        }
        let why = if k[0] == k[1] || k[1] == k[2] || k[2] == k[0] {
            Some("two of its vertices are equal")
        } else if zero_cross(t) {
            Some("its three vertices are on one line")
        } else {
            None
        };
        if let Some(why) = why {
            let message = format!("{}: degenerate (zero area): {why}", name());
            return Err(self.error(at, message));
        }
        if self.current == u32::MAX {
            self.fresh("", Role::Wall);
        }
        self.tris.push(k);
        self.tri_group.push(self.current);
        Ok(())
    }

    /// The surface, groups without a triangle dropped.
    fn finish(mut self, at: Place) -> Result<GroupedSurface, IoError> {
        if self.tris.is_empty() {
            return Err(self.error(at, "no facet: the surface is empty".into()));
        }
        let mut used = vec![false; self.groups.len()];
        self.tri_group.iter().for_each(|&g| used[g as usize] = true);
        let mut new = vec![u32::MAX; self.groups.len()];
        let mut groups = Vec::new();
        for (g, patch) in self
            .groups
            .into_iter()
            .enumerate()
            .filter(|(g, _)| used[*g])
        {
            new[g] = groups.len() as u32;
            groups.push(patch);
        }
        self.tri_group
            .iter_mut()
            .for_each(|g| *g = new[*g as usize]);
        Ok(GroupedSurface {
            nodes: self.nodes,
            triangles: self.tris,
            triangle_group: self.tri_group,
            groups,
        })
    }
}

/// Whether the cross product of the triangle's edges is exactly zero in floating point:
/// no area (the test `geom-surface`'s `Surface::check` makes).
fn zero_cross(t: [[f64; 3]; 3]) -> bool {
    let (a, b) = (
        [0, 1, 2].map(|d| t[1][d] - t[0][d]),
        [0, 1, 2].map(|d| t[2][d] - t[0][d]),
    );
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() == 0.0
}

fn parse_binary(bytes: &[u8], n: usize, path: &Path) -> Result<GroupedSurface, IoError> {
    let mut w = Welder::new(path);
    let f32_at =
        |o: usize| f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
    for i in 0..n {
        let o = 84 + 50 * i;
        let t = [0, 1, 2].map(|j| [0, 1, 2].map(|d| f32_at(o + 12 + 12 * j + 4 * d) as f64));
        w.facet(t, || format!("triangle {}", i + 1), Place::Byte(o))?;
    }
    w.finish(Place::Byte(84))
}

/// Whitespace-separated words with their 1-based line.
fn words(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .flat_map(|(i, l)| l.split_whitespace().map(move |w| (i + 1, w)))
}

fn parse_ascii(text: &str, path: &Path) -> Result<GroupedSurface, IoError> {
    let mut w = Welder::new(path);
    let mut words = Words {
        it: words(text).peekable(),
        line: 1,
        start: 1,
    };
    let mut facets = 0usize;
    while let Some((line, word)) = words.it.next() {
        words.line = line;
        match word {
            // a solid's name runs to the end of its line; it names the solid's group
            "solid" | "endsolid" => {
                let mut name = Vec::new();
                while let Some((_, word)) = words.it.next_if(|&(l, _)| l == line) {
                    name.push(word);
                }
                match (word, name.is_empty()) {
                    ("solid", true) => w.fresh("", Role::Wall),
                    ("solid", false) => w.select(&name.join(" "), Role::Wall),
                    _ => {}
                }
            }
            "facet" => {
                facets += 1;
                words.start = line;
                let t = words.facet(&w)?;
                w.facet(
                    t,
                    || format!("facet {facets} (line {line})"),
                    Place::Line(line),
                )?;
            }
            other => {
                return Err(w.error(
                    Place::Line(line),
                    format!("expected `facet`, `solid` or `endsolid`, found `{other}`"),
                ));
            }
        }
    }
    w.finish(Place::Line(words.line))
}

/// The words of an ASCII STL, the line of the last one read and of the facet being read.
struct Words<'t, I: Iterator<Item = (usize, &'t str)>> {
    it: std::iter::Peekable<I>,
    line: usize,
    start: usize,
}

impl<'t, I: Iterator<Item = (usize, &'t str)>> Words<'t, I> {
    fn next(&mut self, w: &Welder<'_>, what: &str) -> Result<&'t str, IoError> {
        let Some((line, word)) = self.it.next() else {
            return Err(w.error(
                Place::Line(self.line),
                format!(
                    "malformed facet (line {}): the file ends where {what} was expected",
                    self.start
                ),
            ));
        };
        self.line = line;
        Ok(word)
    }

    fn expect(&mut self, w: &Welder<'_>, want: &str) -> Result<(), IoError> {
        let word = self.next(w, &format!("`{want}`"))?;
        if word == want {
            return Ok(());
        }
        Err(w.error(
            Place::Line(self.line),
            format!(
                "malformed facet (line {}): expected `{want}`, found `{word}`",
                self.start
            ),
        ))
    }

    fn number(&mut self, w: &Welder<'_>, what: &str) -> Result<f64, IoError> {
        let word = self.next(w, what)?;
        word.parse().map_err(|_| {
            w.error(
                Place::Line(self.line),
                format!(
                    "malformed facet (line {}): expected {what}, found `{word}`",
                    self.start
                ),
            )
        })
    }

    /// The rest of a facet after `facet`: `normal nx ny nz outer loop`, three
    /// `vertex x y z`, `endloop endfacet`.
    fn facet(&mut self, w: &Welder<'_>) -> Result<[[f64; 3]; 3], IoError> {
        self.expect(w, "normal")?;
        for _ in 0..3 {
            self.number(w, "a normal component")?;
        }
        self.expect(w, "outer")?;
        self.expect(w, "loop")?;
        let mut t = [[0.0; 3]; 3];
        for p in &mut t {
            self.expect(w, "vertex")?;
            for x in p.iter_mut() {
                *x = self.number(w, "a coordinate")?;
            }
        }
        self.expect(w, "endloop")?;
        self.expect(w, "endfacet")?;
        Ok(t)
    }
}

#[cfg(test)]
mod tests;
