//! What a caller asks for: the picture's size, the part of the plane to show, what colours the
//! cells, and which extras (legend, scale bar, title) to draw; plus helpers that make views.
//! It owns no drawing.

use mesh_model::{Mesh, Role};

use crate::error::DrawError;

/// A rectangle of the mesh plane to show, in mesh units (`x0 < x1`, `y0 < y1`).
///
/// The picture keeps the view's aspect ratio: the view is fitted, centred, inside the plot
/// area, and whatever lies beside it in the letterbox bands is drawn too (the view is the
/// region guaranteed to be visible, not a crop).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Left edge, mesh units.
    pub x0: f64,
    /// Bottom edge, mesh units.
    pub y0: f64,
    /// Right edge, mesh units.
    pub x1: f64,
    /// Top edge, mesh units.
    pub y1: f64,
}

impl View {
    /// The square view of half side `half_width` (mesh units) centred on `center`.
    pub fn around(center: [f64; 2], half_width: f64) -> View {
        View {
            x0: center[0] - half_width,
            y0: center[1] - half_width,
            x1: center[0] + half_width,
            y1: center[1] + half_width,
        }
    }

    /// Width, mesh units.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    /// Height, mesh units.
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }

    /// The centre point, mesh units.
    pub fn center(&self) -> [f64; 2] {
        [0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1)]
    }

    /// The view grown by `fraction` of its larger side on every side.
    pub fn with_margin(&self, fraction: f64) -> View {
        let pad = fraction * self.width().max(self.height());
        View {
            x0: self.x0 - pad,
            y0: self.y0 - pad,
            x1: self.x1 + pad,
            y1: self.y1 + pad,
        }
    }

    /// `Ok` when the corners are finite and `x0 < x1`, `y0 < y1`.
    pub fn check(&self) -> Result<(), DrawError> {
        let bad = |reason| DrawError::InvalidView {
            x0: self.x0,
            y0: self.y0,
            x1: self.x1,
            y1: self.y1,
            reason,
        };
        if ![self.x0, self.y0, self.x1, self.y1]
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(bad("a corner is NaN or infinite"));
        }
        if self.x0 >= self.x1 || self.y0 >= self.y1 {
            return Err(bad("it needs x0 < x1 and y0 < y1"));
        }
        if !(self.width().is_finite() && self.height().is_finite()) {
            return Err(bad("its size overflows"));
        }
        Ok(())
    }
}

/// The square view of half side `half_width` (mesh units) centred on `center` (mesh units):
/// the usual way to zoom on a leading edge, a trailing edge or a gap.
pub fn view_around(center: [f64; 2], half_width: f64) -> View {
    View::around(center, half_width)
}

/// The bounding box of every node used by a cell or a boundary facet, grown by
/// `margin_fraction` of its larger side on each side (the default view uses 0.04).
pub fn mesh_view(mesh: &Mesh, margin_fraction: f64) -> Result<View, DrawError> {
    crate::check::check_mesh(mesh)?;
    let used = mesh
        .cells
        .flat_nodes()
        .iter()
        .chain(mesh.boundary.flat_nodes());
    bounding_view(mesh, used, margin_fraction).ok_or(DrawError::EmptyMesh)
}

/// The bounding box of the boundary facets whose patch has role `role` (for instance every
/// wall loop: the airfoil elements), grown by `margin_fraction` of its larger side on each side.
pub fn view_of_role(mesh: &Mesh, role: Role, margin_fraction: f64) -> Result<View, DrawError> {
    crate::check::check_mesh(mesh)?;
    let used = mesh
        .boundary
        .iter()
        .zip(&mesh.boundary_patch)
        .filter(|(_, p)| mesh.patches[**p as usize].role == role)
        .flat_map(|(f, _)| f.nodes.iter());
    bounding_view(mesh, used, margin_fraction).ok_or(DrawError::NoSuchRole { role: role.name() })
}

/// Bounding box of the given nodes plus margin; `None` when there is no node. A box that is a
/// point or a segment is grown so that the view has a positive area.
fn bounding_view<'a>(
    mesh: &Mesh,
    nodes: impl Iterator<Item = &'a u32>,
    margin_fraction: f64,
) -> Option<View> {
    let mut bbox: Option<View> = None;
    for &n in nodes {
        let [x, y] = mesh.xy(n);
        let b = bbox.get_or_insert(View {
            x0: x,
            y0: y,
            x1: x,
            y1: y,
        });
        b.x0 = b.x0.min(x);
        b.y0 = b.y0.min(y);
        b.x1 = b.x1.max(x);
        b.y1 = b.y1.max(y);
    }
    let b = bbox?;
    let extent = b.width().max(b.height());
    let extent = if extent > 0.0 {
        extent
    } else {
        b.x0.abs().max(b.y0.abs()).max(1.0)
    };
    let pad = margin_fraction.max(0.0) * extent;
    let [cx, cy] = b.center();
    let half_w = (0.5 * b.width()).max(0.01 * extent) + pad;
    let half_h = (0.5 * b.height()).max(0.01 * extent) + pad;
    Some(View {
        x0: cx - half_w,
        y0: cy - half_h,
        x1: cx + half_w,
        y1: cy + half_h,
    })
}

/// What colours the cells. Every colouring but `None` draws a legend (when asked).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum ColourBy {
    /// Cells are not filled: white background, edges only.
    #[default]
    None,
    /// The layers grown from the walls, counted from the walls: a cell of `cell_layer` k
    /// (0 touches its boundary) is in layer k + 1, so the first layer is 1, as the legend
    /// (`layer from wall`) shows; a perceptual map from layer 1 to the outermost wall layer,
    /// every second layer slightly lighter so that neighbouring layers stay apart. Cells of
    /// layers grown from the far field (their `cell_pipe` is a far-field facet) are one light
    /// blue (`far field`), and the filled region (the last
    /// [`DrawParams::fill_cells`] cells) and cells with no layer (`mesh_model::NONE`) or no
    /// boundary pipe are neutral grey (`fill`). A mesh without `cell_pipe` has every layered
    /// cell counted as a wall's. Needs `mesh.cell_layer` with one entry per cell.
    Layer,
    /// The largest interior angle of each cell (corners only; quads cut along the shorter
    /// diagonal, the larger of the two triangles' angles), on a fixed 60–180° scale whose
    /// ticks mark the obtuse bins 95, 105, 115, 125, 135°.
    MaxAngle,
    /// The scaled Jacobian of each cell, as computed by the caller (one value per cell), on a
    /// fixed 0–1 scale; negative values (inverted cells) in red, NaN in grey.
    ScaledJacobian(Vec<f64>),
    /// A category per cell (one per cell, an index into `names`), each its own colour, the
    /// legend a block per name: the type of the 3D cell each polygon of a slice lies in.
    Categories {
        /// The category of each cell.
        values: Vec<u32>,
        /// The name of each category, for the legend.
        names: Vec<String>,
        /// The legend's heading (for instance `cell type`).
        label: String,
    },
    /// Any value per cell (one per cell), on the range of the finite values; NaN in grey.
    CellValues {
        /// The values, one per cell.
        values: Vec<f64>,
        /// What they are, for the legend (for instance `aspect ratio`).
        label: String,
    },
}

/// Everything [`crate::render_png`] and [`crate::render_svg`] need besides the mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawParams {
    /// Picture width, pixels (16 to 16384). Default 1200.
    pub width_px: u32,
    /// Picture height, pixels (16 to 16384). Default 900.
    pub height_px: u32,
    /// The region to show, mesh units; `None` (the default) shows the whole mesh: the bounding
    /// box of its nodes plus a margin of 4 % of its larger side.
    pub view: Option<View>,
    /// What colours the cells. Default [`ColourBy::None`].
    pub colour: ColourBy,
    /// Draw the colour legend at the right (only when cells are coloured; left out when the
    /// picture is too narrow to keep at least half its width for the mesh). Default true.
    pub show_legend: bool,
    /// Draw a scale bar (1, 2 or 5 × 10^k mesh units, labelled) at the bottom left.
    /// Default true.
    pub show_scale_bar: bool,
    /// A title line above the plot. Default none.
    pub title: Option<String>,
    /// How many of the mesh's cells, the last ones, are its filled region rather than layers
    /// (as in the meshes `afsf2d` grows, whose fill triangles come last and borrow a
    /// neighbour's `cell_layer`): drawn as fill by [`ColourBy::Layer`]. Default 0.
    pub fill_cells: usize,
}

impl Default for DrawParams {
    fn default() -> Self {
        DrawParams {
            width_px: 1200,
            height_px: 900,
            view: None,
            colour: ColourBy::None,
            show_legend: true,
            show_scale_bar: true,
            title: None,
            fill_cells: 0,
        }
    }
}
