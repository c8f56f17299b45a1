//! STL surfaces (ASCII and binary) and triangulated `.msh` surfaces read as plain arrays:
//! nodes welded (vertices of identical coordinates merged, exactly; `-0.0` is `0.0`) and
//! triangles as three node indices each, in the file's order and orientation. Whether the
//! surface is closed, manifold and consistently oriented is for the caller to check.
//!
//! A file is binary when its size is exactly 84 bytes plus 50 per triangle its header
//! counts; otherwise it must be ASCII (text starting with `solid`, no NUL byte), and a file
//! of neither kind is reported as a truncated binary STL. Every error names
//! the file and the line (ASCII) or byte (binary): a malformed facet, a coordinate that is
//! not a finite number, a facet with two equal vertices, no facet at all.

use std::collections::HashMap;
use std::path::Path;

use mesh_model::Shape;

use crate::IoError;

/// Nodes and triangles of a surface.
pub type Surface = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// Reads an STL file, ASCII or binary.
pub fn read(path: &Path) -> Result<Surface, IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    parse(&bytes, path)
}

/// Reads a closed surface from `.stl` (ASCII or binary) or `.msh` (its linear triangles:
/// the boundary facets of a surface mesh, or the cells of a planar one), by extension.
pub fn read_surface(path: &Path) -> Result<Surface, IoError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("stl") => read(path),
        Some("msh") => {
            let m = crate::msh::read(path)?;
            let mut w = Welder::new(path);
            let mut tris = Vec::new();
            for c in m.cells.iter().chain(m.boundary.iter()) {
                if c.ty.shape == Shape::Tri {
                    let k = c.corners();
                    tris.push([k[0], k[1], k[2]].map(|v| m.nodes[v as usize]));
                }
            }
            for (i, t) in tris.into_iter().enumerate() {
                w.facet(t, || format!("triangle {}", i + 1), Place::Line(0))?;
            }
            w.finish(Place::Line(0))
        }
        _ => Err(IoError::UnknownExtension {
            path: path.to_path_buf(),
        }),
    }
}

/// Parses the bytes of an STL file; `path` only names it in errors.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Surface, IoError> {
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
}

/// Merges vertices of identical coordinates.
struct Welder<'a> {
    path: &'a Path,
    index: HashMap<[u64; 3], u32>,
    nodes: Vec<[f64; 3]>,
    tris: Vec<[u32; 3]>,
}

impl<'a> Welder<'a> {
    fn new(path: &'a Path) -> Self {
        Welder {
            path,
            index: HashMap::new(),
            nodes: Vec::new(),
            tris: Vec::new(),
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
        }
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
        if k[0] == k[1] || k[1] == k[2] || k[2] == k[0] {
            return Err(self.error(at, format!("{}: two of its vertices are equal", name())));
        }
        self.tris.push(k);
        Ok(())
    }

    fn finish(self, at: Place) -> Result<Surface, IoError> {
        if self.tris.is_empty() {
            return Err(self.error(at, "no facet: the surface is empty".into()));
        }
        Ok((self.nodes, self.tris))
    }
}

fn parse_binary(bytes: &[u8], n: usize, path: &Path) -> Result<Surface, IoError> {
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

fn parse_ascii(text: &str, path: &Path) -> Result<Surface, IoError> {
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
            // a solid's name runs to the end of its line
            "solid" | "endsolid" => {
                while words.it.peek().is_some_and(|&(l, _)| l == line) {
                    words.it.next();
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
