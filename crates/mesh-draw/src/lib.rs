//! Pictures of 2D meshes as a mesh engineer wants to see them: PNG (rasterised with
//! tiny-skia) and SVG (written as text), the whole mesh or a zoomed view.
//!
//! What a picture shows: a white background; every mesh edge once, thin, dark grey and
//! anti-aliased (curved P2/P3 edges drawn as the exact polynomial curve through their nodes);
//! the boundary loops bold, coloured by role (walls black, far field dark blue); optionally the
//! cells filled by layer (counted from the walls, the first layer 1; the far field's layers
//! and the fill in neutral colours of their own), by largest angle, by the caller's scaled
//! Jacobian or any per-cell value, with a legend; a scale bar; a title.
//!
//! Conventions: the light (yellow) end of the map is the good end in every quality colouring
//! (small largest angle, high scaled Jacobian); the angle scale fits the data (whole 5° steps
//! within 60–180°). The legend's column has one width whatever it holds (and is kept empty
//! when there is no legend), so a view lands on the same pixels in every colouring. The wall
//! line is no thicker than the first layer in view (down to 0.75 px), and a picture whose first
//! layers are below a pixel says so in a line of its own between the title and the plot, never
//! over the cells.
//!
//! What it owns: the layout, the colour map, the drawing. What it does not own: files (the
//! functions return bytes and strings, the caller writes them), mesh checking beyond what
//! drawing needs (see `mesh_model::validate`), and quality measures other than the largest
//! angle (Jacobians are computed by the caller and passed in).
//!
//! Text: tiny-skia draws no text, and the picture needs only short labels, so the crate carries
//! its own small stroke font (see the `font` module for the reasons) instead of a font
//! rasteriser and a font file; the SVG writes `<text>` elements for the viewer's font.
//!
//! 3D meshes are drawn as a plane cut through them ([`mod@slice`]): the polygons where the cells
//! meet the plane, a 2D mesh like any other, coloured by the type of their cell
//! ([`ColourBy::Categories`]) or any other way.
//!
//! Inputs that are refused with a [`DrawError`] rather than drawn: an empty mesh (no cell and no
//! boundary facet), a 3D mesh, a view that is empty or not finite, a picture side outside 16 to
//! 16384 px, per-cell values of the wrong length, broken indices or non-finite coordinates.
//!
//! Curved cells: each cell's own order is used (P1 straight; P2 and P3 edges through their
//! Gmsh-ordered edge nodes). The Lagrange interpolant through an edge's equally spaced nodes is
//! converted exactly to a quadratic or cubic Bézier curve, which tiny-skia and SVG viewers draw
//! natively; edges that are straight to within 0.05 px are drawn as lines.
//!
//! Speed (see `benches/draw.rs`): every edge is drawn once, cells and edges outside the view
//! are skipped, the SVG leaves out edges shorter than a pixel, and fills of one colour and all
//! edges are each one path. A 2000 × 1500 px picture of a 100k-cell mesh takes 0.13 s (edges
//! only) to 0.23 s (filled by layer) as PNG, 0.05 s to 0.12 s as SVG, on the project's 2-core
//! machine.
//!
//! # Example
//!
//! A PNG of a small mesh (the unit square as two triangles, its sides a far-field patch),
//! cells coloured by their largest angle, as bytes for the caller to write:
//!
//! ```
//! use mesh_draw::{ColourBy, DrawParams, render_png, render_svg};
//! use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape};
//!
//! let mut mesh = Mesh::new(Dim::Two, 1);
//! mesh.nodes = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! mesh.cells.push(CellType::new(Shape::Tri, 1), &[0, 1, 2]);
//! mesh.cells.push(CellType::new(Shape::Tri, 1), &[0, 2, 3]);
//! for k in 0..4 {
//!     mesh.boundary.push(CellType::new(Shape::Line, 1), &[k, (k + 1) % 4]);
//!     mesh.boundary_patch.push(0);
//! }
//! mesh.patches.push(Patch { name: "farfield".into(), role: Role::Farfield });
//!
//! let params = DrawParams {
//!     width_px: 400,
//!     height_px: 300,
//!     colour: ColourBy::MaxAngle,
//!     title: Some("unit square".into()),
//!     ..DrawParams::default()
//! };
//! let png: Vec<u8> = render_png(&mesh, &params)?;
//! assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
//! let svg: String = render_svg(&mesh, &params)?;
//! assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
//! // std::fs::write("square.png", &png)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod check;
mod colour;
mod error;
mod font;
mod frame;
mod params;
mod png;
mod quality;
mod scene;
pub mod slice;
mod svg;

use mesh_model::Mesh;

pub use error::DrawError;
pub use params::{ColourBy, DrawParams, View, mesh_view, view_around, view_of_role};
pub use quality::{max_angle_deg, triangle_max_angle_deg};

use scene::{Target, build_scene};

/// Draws `mesh` as `params` asks and returns the encoded PNG file's bytes.
pub fn render_png(mesh: &Mesh, params: &DrawParams) -> Result<Vec<u8>, DrawError> {
    let scene = build_scene(mesh, params, Target::Png)?;
    let pixmap = png::rasterise(&scene)?;
    png::encode(&pixmap)
}

/// Draws `mesh` as `params` asks and returns the RGBA pixels (row by row, top row first,
/// premultiplied alpha, fully opaque) without encoding them: for callers that compose pictures
/// or test pixels.
pub fn render_rgba(mesh: &Mesh, params: &DrawParams) -> Result<Vec<u8>, DrawError> {
    let scene = build_scene(mesh, params, Target::Png)?;
    Ok(png::rasterise(&scene)?.take())
}

/// Draws `mesh` as `params` asks and returns a standalone SVG document. Edges shorter than a
/// pixel at the chosen view are left out to keep the file small.
pub fn render_svg(mesh: &Mesh, params: &DrawParams) -> Result<String, DrawError> {
    let scene = build_scene(mesh, params, Target::Svg)?;
    Ok(svg::write_svg(&scene))
}
