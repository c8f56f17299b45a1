//! The crate's one error type. Every variant names the file at fault; reader variants also
//! name the line.

use std::path::PathBuf;

/// Everything that can go wrong reading or writing a mesh or snapshot file.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The operating system refused a read, a write, a rename or a directory listing.
    /// Fix: check that the directory exists and is writable, and that the disk is not full.
    #[error("{path}: {source}", path = path.display())]
    Io {
        /// The file the operation was about.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },

    /// Two outputs of one [`crate::atomic::Transaction`] name the same file (one would replace
    /// the other). Fix: give each output its own file name.
    #[error("{path}: the same file as the earlier output {first}: give each output its own file", path = path.display(), first = first.display())]
    DuplicateOutput {
        /// The later output.
        path: PathBuf,
        /// The earlier output naming the same file.
        first: PathBuf,
    },

    /// An output was reserved in a [`crate::atomic::Transaction`] but never written, so the
    /// transaction could not commit; nothing was replaced. Fix: the caller is at fault.
    #[error("{path}: reserved as an output but never written; no output was replaced", path = path.display())]
    Unwritten {
        /// The output never written.
        path: PathBuf,
    },

    /// The process was interrupted ([`crate::atomic::on_interrupt`]); nothing was replaced.
    #[error("{path}: interrupted; no output was replaced", path = path.display())]
    Interrupted {
        /// The output at hand.
        path: PathBuf,
    },

    /// The output path has an extension no writer knows.
    /// Fix: end the file name in `.msh`, `.vtu` or `.su2`.
    #[error("{path}: unknown mesh file extension (expected .msh, .vtu or .su2)", path = path.display())]
    UnknownExtension {
        /// The path given.
        path: PathBuf,
    },

    /// A surface to be read has an extension no surface reader knows.
    /// Fix: give an STL (`.stl`, ASCII or binary) or a Gmsh `.msh` of triangles.
    #[error("{path}: unknown surface file extension (expected .stl or .msh)", path = path.display())]
    UnknownSurfaceExtension {
        /// The path given.
        path: PathBuf,
    },

    /// A surface read from a file where no line or byte names the fault (a `.msh` surface):
    /// a degenerate or non-finite triangle, no triangle at all. Fix: the message names the
    /// triangle and what is wrong with it.
    #[error("{path}: {message}", path = path.display())]
    BadSurface {
        /// The file read.
        path: PathBuf,
        /// What is wrong, and where.
        message: String,
    },

    /// A node to be written has a NaN or infinite coordinate; nothing was written.
    /// Fix: the stage that produced the mesh is at fault (run `mesh_model::validate`).
    #[error("{path}: node {node} has a non-finite coordinate {coords:?}; nothing written", path = path.display())]
    NonFiniteNode {
        /// The file that was to be written.
        path: PathBuf,
        /// Index of the node (0-based).
        node: usize,
        /// Its coordinates.
        coords: [f64; 3],
    },

    /// The mesh to be written breaks a structural invariant of the data model (an index out
    /// of range, a per-facet array of the wrong length, a cell type foreign to the mesh's
    /// dimension). Fix: the stage that produced the mesh is at fault.
    #[error("{path}: cannot write this mesh: {message}", path = path.display())]
    InvalidMesh {
        /// The file that was to be written.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },

    /// The format cannot represent something in the mesh (for example a high-order pyramid in
    /// `.vtu`). Fix: choose another format or order.
    #[error("{path}: {format} cannot hold {what}", path = path.display())]
    Unsupported {
        /// The file that was to be written.
        path: PathBuf,
        /// The format (`vtu`, `su2`, `msh`).
        format: &'static str,
        /// What it cannot hold.
        what: String,
    },

    /// The file is a binary MSH file of another machine (big-endian, or `size_t` not of 8
    /// bytes). Fix: save it from Gmsh as ASCII (`Mesh.Binary = 0`).
    #[error("{path}:{line}: binary MSH other than little-endian with 8-byte sizes is not supported: save as ASCII", path = path.display())]
    BinaryMsh {
        /// The file read.
        path: PathBuf,
        /// The line of the `$MeshFormat` header.
        line: usize,
    },

    /// The MSH file is of a version other than 4.1.
    /// Fix: save it from Gmsh as MSH 4.1 (`Mesh.MshFileVersion = 4.1`).
    #[error("{path}:{line}: MSH version {version} is not supported: save as MSH 4.1", path = path.display())]
    UnsupportedVersion {
        /// The file read.
        path: PathBuf,
        /// The line of the version number.
        line: usize,
        /// The version found.
        version: String,
    },

    /// The MSH file holds an element type this crate does not know (serendipity elements,
    /// orders above 3, polygons). Fix: export complete Lagrange elements of order 1 to 3.
    #[error("{path}:{line}: unknown MSH element type {type_id} (supported: complete Lagrange lines, triangles, quadrangles, tetrahedra, pyramids, prisms and hexahedra of order 1 to 3)", path = path.display())]
    UnknownElementType {
        /// The file read.
        path: PathBuf,
        /// The line of the element block header.
        line: usize,
        /// The Gmsh element type number.
        type_id: i64,
    },

    /// A section the reader needs (`$MeshFormat`, `$Entities`, `$Nodes`, `$Elements`) is
    /// missing. Fix: save the file from Gmsh with all sections.
    #[error("{path}: the ${section} section is missing", path = path.display())]
    MissingSection {
        /// The file read.
        path: PathBuf,
        /// The section's name, without `$`.
        section: &'static str,
    },

    /// The file does not follow the format: a token that is not a number, a count that does
    /// not match, a truncated section, a node reference to nothing, a physical group that is
    /// not a known role. Fix: the message names the line and what was expected there.
    #[error("{path}:{line}: {message}", path = path.display())]
    Malformed {
        /// The file read.
        path: PathBuf,
        /// 1-based line number of the fault.
        line: usize,
        /// What was expected and what was found.
        message: String,
    },

    /// A binary file does not follow its format (a truncated binary STL, a count that does
    /// not match the size). Fix: the message names the byte offset and what was expected.
    #[error("{path}: byte {offset}: {message}", path = path.display())]
    MalformedBinary {
        /// The file read.
        path: PathBuf,
        /// Byte offset of the fault.
        offset: usize,
        /// What was expected and what was found.
        message: String,
    },

    /// The file is not a snapshot of this program (wrong magic bytes), or of an older or newer
    /// snapshot format version, or its contents do not decode as the expected type.
    /// Fix: regenerate the snapshot with this version of the program.
    #[error("{path}: {message}", path = path.display())]
    Snapshot {
        /// The file read or written.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

impl IoError {
    /// An operating-system error about `path`.
    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        IoError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}
