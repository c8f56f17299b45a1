//! The advancing-front spring-field mesher in 3D (dissertation §5.2.1–5.2.2): layers grown
//! from the wall facets of a closed [`Surface`], one child per front node per layer,
//! balanced by the 3D springs of `springfield` ([`springfield::SpringField3d`]), neighbouring
//! children merged where the front shrinks (Coe_shrink), every layer checked and shrunk where
//! it fails.
//!
//! Layer k (from 0) has the height `first_height × growth^k` (with
//! [`LayerParams::max_aspect`], at most that many times the front's local spacing from the
//! second layer on, never below the node's previous height). Each front node's ideal
//! direction is the angle-weighted normal of the front facets around it (with
//! [`LayerParams::patch_normals`], each wall patch's apart, the patches weighted alike); its ideal length is
//! the layer height, divided, at a concave node, by the smallest cosine between the direction
//! and the normals of its facets (so that the child stands the layer height off every facet
//! there; see `docs/afsf3d.md`). The children start at their ideal places and are balanced
//! twice: by the extrusion, neighbour and angle springs, then with the tension springs added
//! (ideal length 0.9 × the length after the first balance).
//!
//! Then, from the second layer on, the children of a front edge closer than
//! [`LayerParams::coe_shrink`] (0.65) times the mean of their two ideal extrusion lengths
//! merge at their midpoint (the shortest edges first, each node in one merge per layer): a
//! quad of the new front that loses a node becomes a triangle, a triangle that loses one
//! collapses to an edge and leaves the front, and the cells below become the non-standard
//! cells `topo-cut` cuts (a quad under a triangle, a triangle under an edge, …). A merge is
//! kept only if the new front stays a closed manifold (no facet repeating a node or another
//! facet, every edge in two facets running opposite ways) and its child has a place (the
//! middle of the two children, either child, or over the middle of the edge) where every
//! merged cell around it is strictly convex (every cone from a node of the cell over its
//! other faces positive, so every cut of `topo-cut` is) and every cell around it that was
//! valid without merges stays valid; where that place leans the child's extrusion edges over
//! 30° off their parents' normals, places nearer upright over the edge's middle are tried and
//! the least leaning kept whose cells around still pass and keep a cone cut under 140°
//! (table 6, `docs/3d.md`). A cell still failing then merges the children of its
//! shortest edge if that edge is shorter than its ideal extrusion (the dissertation's second
//! trigger, "a cell twisted to a negative volume").
//!
//! Then every cell is checked: each corner tetrahedron of a cell that keeps all its top
//! nodes (a corner, its two neighbours on the bottom or top face and the node above or
//! below) must be positive by the exact `orient3d`, a merged cell must stay strictly convex,
//! and the new front must not intersect itself anywhere (facet pairs by sort-and-sweep over
//! the whole front, the exact triangle test). The children of a failing cell or facet pair
//! are moved halfway back to their parents (a merged child to the midpoint of its two), and
//! the check repeated, once where a cell is inverted (halved further it would only flatten),
//! at most [`LayerParams::max_shrinks`] times where the front crosses itself. A layer still
//! invalid then drops the merges of its failing cells' nodes (a merged child stands half an
//! edge off its parents' columns and shrinks towards their middle, so a neighbour it shears
//! stays inverted) and is built and shrunk again, at most four times; then its failing
//! columns stop (below). With [`LayerParams::patch_normals`] such a layer first turns
//! the steps of the nodes whose bottom corners fail (a step that does not stand off a
//! corner triangle of the front, which no shrink mends) and is built again.
//!
//! Where a layer still fails, its columns stop there rather than the growth (`stop`): the
//! front nodes of the failing cells (or of the facets where the new front crosses itself or
//! another body's front) keep themselves as their children, the cells beside them become
//! pyramids and tetrahedra (each checked strictly convex like a merged cell), a facet whose
//! nodes all stopped has no cell and stays on the front, and the layer is checked again until
//! it passes; the rest keep growing. Around stopped columns the layers are lower, so the step
//! down to them is at most 45° (a node left under a quarter of its layer stops too). The
//! columns record where and why they stopped ([`Grown3d::stops`]).
//!
//! Then, from the second layer on, where a cell over a front triangle has no cone cut (any
//! apex, any diagonals) with every tetrahedron under 140° — a cap on its top, one child
//! almost on the line of two others — its children are moved by a small checked search to
//! improve the cells' best cuts (`repair`, counted in [`GrowStats::repaired`];
//! `docs/3d.md`). Layers without such a cell are left to the bit.
//!
//! The result ([`Grown3d`]) is a [`PolyMesh`] of the raw layer cells with `cell_layer` and
//! `cell_pipe` (the wall facet each cell descends from), the column of every wall node (its
//! node and its children, bottom-up; a merged child is in the columns of both its parents),
//! each node's layer and parents (the layering record), and the final front, the outer
//! boundary of the near-body mesh the layers make. Each cell's faces follow the contract with
//! `topo-cut`: face 0 the bottom (on the previous front, outward of the cell: towards the
//! wall), face 1 the top (left out when merged children leave fewer than three nodes), then
//! the side faces in the order of the bottom's edges (a triangle where the edge's two
//! children merged).
//!
//! Fronts that meet (between bodies, or two parts of one front growing into each other) do
//! not close: the columns where they would cross stop.
//!
//! ```
//! use afsf3d::{LayerParams, grow_layers};
//! use geom_surface::Surface;
//!
//! let sphere = Surface::sphere(1.0, 2);
//! let params = LayerParams { first_height: 0.01, growth: 1.2, layers: 5, ..LayerParams::default() };
//! let grown = grow_layers(&sphere, &params)?;
//! assert_eq!(grown.mesh.cell_count(), 5 * sphere.facets.len());
//! assert!(grown.mesh.validate().is_empty());
//! assert!(grown.columns.iter().all(|c| c.len() == 6)); // every node keeps its five children
//! assert_eq!(grown.stats.merges, 0); // a sphere's front grows: no edge shrinks
//! # Ok::<(), afsf3d::GrowError>(())
//! ```
//!
//! At a chain of sharp convex edges (a wing's trailing edge: the facets' normals turning by
//! more than [`LayerParams::fan_threshold_deg`]) each node grows a fan of columns instead of
//! one along the bisector (`fan`): its copies' first children turned evenly from one side's
//! normal to the other's, the first layer's cells between two copies prisms lying on their
//! side (no bottom face: their first side is face 0), tetrahedra next to the chain's end.
//!
//! Modules, bottom up (each uses only modules before it, and the parameter, error and result
//! types here at the crate root): the leaves `front` and `children` (a layer's children and
//! cells); then `fan` (the wall opened at its sharp edges), `aspect`, `check`, `repair`,
//! `upright`, `layer` (the merging), `squeeze`, `stop` (columns that stop), `grow`.

mod aspect;
mod check;
mod children;
mod compass;
mod fan;
mod front;
mod grow;
mod layer;
mod proximity;
mod repair;
mod shape;
mod squeeze;
mod stop;
mod upright;

pub use grow::grow_layers;

use geom_surface::{Surface, SurfaceError};
use mesh_model::poly::PolyMesh;
use springfield::{SolverParams, SpringError, SpringParams3d};

/// What to grow.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerParams {
    /// Height of the first layer.
    pub first_height: f64,
    /// Ratio of each layer's height to the one below (≥ 1).
    pub growth: f64,
    /// Number of layers.
    pub layers: usize,
    /// The spring coefficients.
    pub springs: SpringParams3d,
    /// The balance's solver settings.
    pub solver: SolverParams,
    /// How many times the children of the facets where the new front crosses itself are moved
    /// halfway back before those columns stop (an inverted cell's are moved back once).
    pub max_shrinks: usize,
    /// Rounds of smoothing of the ideal directions over the front (each direction replaced
    /// by the normalised sum of its own and its neighbours'): fans the directions out of
    /// concave edges, so the front there spreads instead of folding. Default 8.
    pub smoothing: usize,
    /// Coe_shrink: the children of a front edge closer than this fraction of the mean of
    /// their ideal extrusion lengths merge into one node (not in the first layer). Default
    /// 0.65; 0 never merges.
    pub coe_shrink: f64,
    /// The smallest cosine wanted between a node's ideal direction and the normal of each
    /// facet around it — on a rectangular facet, the corner scaled Jacobian of the cell
    /// grown there. A direction below it (after the smoothing) is turned towards the one
    /// that stands most steeply off all the node's facets, just far enough (see
    /// `docs/afsf3d.md`). Default 0: none turned. 0.55 lifts the step's smallest corner
    /// scaled Jacobian in layers 0–11 from 0.34 to 0.51, but the step at a first height of
    /// 3e-3 then fails in its merging layer (13), so it is not the default yet.
    pub stand_off: f64,
    /// A cell whose smallest corner scaled Jacobian (with its balanced children) falls below
    /// this merges the children of the edge along which the front shrinks most (not in the
    /// first layer; see `docs/afsf3d.md`): the front loses nodes where it is squeezed, as
    /// at the step's concave edges once the layers are as thick as the wall's spacing.
    /// Default 0 (off); 0 never merges by it.
    pub squeeze: f64,
    /// Each node's direction from its patches alike: the unit angle-weighted normal of its
    /// facets of each wall patch (the pipes' patches), summed over the patches and
    /// normalised, instead of the angle-weighted normal of all its facets. On a rim where
    /// the wing's quad side meets its tip cap, the plain weights feed back: a side quad
    /// sheared by the growth has a smaller angle at the rim node, which then leans to the
    /// cap, which shears the quad more, until the front's quads twist and a cell inverts
    /// (layer 11 of the quad wing; with this, layer 21, `docs/3d.md`). Also turns, in a
    /// layer that stays invalid after its shrinks, the steps of failing bottom corners
    /// (see the crate's doc). Default false.
    pub patch_normals: bool,
    /// The most a layer's height may be relative to the front's spacing (the mean length of
    /// its edges), from the second layer on: a layer that would be higher is held to it, but
    /// never below the previous layer's height (the layers turn isotropic far from the wall,
    /// where Coe_shrink coarsens the front too slowly for the geometric heights; the wing with
    /// a quad side fails in layer 28 without it and grows its 45 layers with 1, `docs/3d.md`).
    /// Default 0: no limit, layer k is `first_height × growth^k` high.
    pub max_aspect: f64,
    /// Merges carried along rows of quads: each pair of children merged by Coe_shrink merges
    /// the opposite side of each quad on its edge too where that side's ratio (its children's
    /// distance over their mean ideal extrusion length) is below this, and so on along the row
    /// (a thin quad merged on one side only becomes a triangle of about 1° on the quad
    /// wing's trailing edge; `docs/3d.md`). Default 0: each edge by itself.
    pub merge_rows: f64,
    /// Where a volume fill follows the layers: growth stops, for every column, before the
    /// first layer (after the first) higher than this × the front's mean edge — the layers
    /// have turned isotropic, and isotropic cells are the fill's to make. Default 0: every
    /// layer grows.
    pub stop_aspect: f64,
    /// Growth stops, for every column, before the layers would be thicker than this (a far
    /// field's distance from the wall, halved, so the last front stays well inside it).
    /// Default infinite.
    pub max_thickness: f64,
    /// Before each layer, a column whose front node faces another part of the front (another
    /// body's, or its own across a gap) nearer than this × the layer's height stops, so the
    /// fronts keep a gap for a volume fill (`proximity`). Default 0: none stops so; fronts
    /// that would cross stop their columns all the same.
    pub stop_gap: f64,
    /// With [`LayerParams::stop_gap`]: the gap kept is at least this × the front's spacing at
    /// the node (the mean length of its front edges), so a fill's cells across it are not
    /// flat against the front's curving. Default 0.
    pub stop_gap_spacing: f64,
    /// Whether the children of cells whose facets lost their shape slide to give them their
    /// angles back (`shape`; default true). Off, the layers are those of the springs alone
    /// (a caller whose fill cannot recover a reshaped front grows them again so).
    pub reshape: bool,
    /// A convex wall edge whose two facets' normals turn by more than this (degrees) is
    /// sharp, and each node of a chain of such edges grows a fan of columns around it
    /// instead of one along the bisector (`fan`; 2D's `fan_threshold_deg`). Default 120 (a
    /// wedge under 60°: a trailing edge, a slat's cusp; a 90° rim keeps one column); 0: no
    /// fans.
    pub fan_threshold_deg: f64,
    /// The widest turn between two neighbouring columns of a fan (degrees): a fan turning by
    /// θ has ⌈θ / this⌉ pieces. Default 60, as in 2D: narrower pieces make its first
    /// layer's edges short against the next layer's height, and Coe_shrink merges them.
    pub fan_max_angle_deg: f64,
}

impl Default for LayerParams {
    fn default() -> Self {
        LayerParams {
            first_height: 1e-3,
            growth: 1.2,
            layers: 30,
            springs: SpringParams3d::default(),
            solver: SolverParams {
                max_iterations: 300,
                tolerance: 1e-3,
                ..SolverParams::default()
            },
            max_shrinks: 8,
            smoothing: 8,
            coe_shrink: 0.65,
            stand_off: 0.0,
            squeeze: 0.0,
            patch_normals: false,
            max_aspect: 0.0,
            merge_rows: 0.0,
            stop_aspect: 0.0,
            max_thickness: f64::INFINITY,
            stop_gap: 0.0,
            stop_gap_spacing: 0.0,
            reshape: true,
            fan_threshold_deg: 120.0,
            fan_max_angle_deg: 60.0,
        }
    }
}

/// Why the layers could not be grown.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GrowError {
    /// The surface fails its checks.
    #[error("bad surface: {0}")]
    Surface(#[from] SurfaceError),
    /// A parameter is out of range.
    #[error("bad layer parameter: {0}")]
    Params(String),
    /// Far-field facets on the surface: growth from part of a surface is not supported yet.
    #[error("facet {facet} is not a wall: layers grow from closed wall surfaces only")]
    NotWall {
        /// The first such facet.
        facet: usize,
    },
    /// The spring solver failed.
    #[error("spring balance of layer {layer}: {source}")]
    Spring {
        /// The layer (from 0).
        layer: usize,
        /// The solver's error.
        source: SpringError,
    },
    /// A layer stays invalid however much its children are shrunk and however many of its
    /// columns stop (not expected: a layer whose columns all stop is its front, valid).
    #[error("layer {layer} cannot be grown over wall facet {facet}: {what}")]
    LayerFailed {
        /// The layer (from 0).
        layer: usize,
        /// The wall facet of the pipe where it fails.
        facet: usize,
        /// What fails.
        what: &'static str,
    },
}

/// Measures of a growth.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GrowStats {
    /// How many times some children were moved halfway back.
    pub shrinks: usize,
    /// Children moved back (counted once per shrink).
    pub shrunk_nodes: usize,
    /// Whether every balance converged.
    pub converged: bool,
    /// Merged children (each merging two front nodes).
    pub merges: usize,
    /// Children moved by the repair of cells without a good cone cut (`docs/3d.md`).
    pub repaired: usize,
    /// Children moved to give cells that lost their shape their angles back (`shape`).
    pub reshaped: usize,
    /// Layers whose height the limit of [`LayerParams::max_aspect`] held below
    /// `first_height × growth^k`.
    pub capped_layers: usize,
    /// The first layer (from 0) with such a child.
    pub first_capped: Option<usize>,
    /// Wall nodes whose columns stopped before the last layer.
    pub stopped_columns: usize,
    /// Wall nodes on sharp edges that grew a fan of columns (`fan`).
    pub fanned_nodes: usize,
    /// Nodes on sharp edges grown with one column because a column of their fan stopped in
    /// the first layer.
    pub unfanned_nodes: usize,
}

/// Why a column stopped before the last layer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum StopWhy {
    /// A cell of its next layer stayed inverted (or, merged or beside a stopped column, not
    /// strictly convex).
    InvertedCell,
    /// Its next layer's front would cross itself or another body's front.
    FrontsCross,
    /// Next to a stopped column: its layer would have been under a quarter of the layer's
    /// height, to keep the step down to that column at most 45°.
    Transition,
    /// It faced another front (another body's, or its own across a gap) nearer than
    /// [`LayerParams::stop_gap`] × its next layer's height.
    FrontsNear,
}

impl StopWhy {
    /// A few words for messages and reports.
    pub fn describe(self) -> &'static str {
        match self {
            StopWhy::InvertedCell => "an inverted cell",
            StopWhy::FrontsCross => "the front crosses itself or another body's front",
            StopWhy::Transition => "next to a stopped column (the step down kept gradual)",
            StopWhy::FrontsNear => "the front came near another front (a gap kept for the fill)",
        }
    }
}

/// Where a wall node's column stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ColumnStop {
    /// The layer (from 0) it could not take: its column holds this many layers.
    pub layer: usize,
    /// Why.
    pub why: StopWhy,
}

/// Grown layers.
#[derive(Debug, Clone)]
pub struct Grown3d {
    /// The layer cells (see the crate's doc for the order of their faces); node `i` of the
    /// surface is node `i` here, the children of each layer follow (one per front node, two
    /// merged front nodes sharing one).
    pub mesh: PolyMesh,
    /// For each surface node, its node and its children, bottom-up (`layers + 1` nodes where
    /// the column took every layer, fewer where it stopped); a merged child is in the columns
    /// of both its parents' wall nodes, and every column above it.
    pub columns: Vec<Vec<u32>>,
    /// For each surface node, where and why its column stopped (`None`: every layer).
    pub stops: Vec<Option<ColumnStop>>,
    /// The other columns of the fanned nodes at sharp edges (`fan`): each with its wall node
    /// (whose own column, in `columns`, is the fan's first) and its nodes bottom-up, the wall
    /// node first.
    pub fan_columns: Vec<(u32, Vec<u32>)>,
    /// The final front, the outer boundary of the layers: the wall's facets over the top
    /// children, less those that collapsed to an edge (node `i` of the front is mesh node
    /// `front_nodes[i]`).
    pub front: Surface,
    /// The mesh node of each node of the final front.
    pub front_nodes: Vec<u32>,
    /// For each mesh node, its layer (0 on the wall).
    pub node_layer: Vec<u32>,
    /// For each mesh node, the nodes it grew from ([`mesh_model::NONE`] when absent): none on
    /// the wall, the second parent of a merged child.
    pub node_parents: Vec<[u32; 2]>,
    /// Merged children in each layer.
    pub layer_merges: Vec<usize>,
    /// Each layer's height: `first_height × growth^k`, or less where
    /// [`LayerParams::max_aspect`] limits it.
    pub layer_heights: Vec<f64>,
    /// Measures of the growth.
    pub stats: GrowStats,
}

impl Grown3d {
    /// Every column, bottom-up: each wall node's ([`Grown3d::columns`]), then the fans'
    /// other columns ([`Grown3d::fan_columns`]).
    pub fn all_columns(&self) -> Vec<Vec<u32>> {
        let fans = self.fan_columns.iter().map(|(_, c)| c.clone());
        self.columns.iter().cloned().chain(fans).collect()
    }

    /// The fraction of the wall nodes whose columns took every layer (1 without wall nodes).
    pub fn coverage(&self) -> f64 {
        if self.stops.is_empty() {
            return 1.0;
        }
        let full = self.stops.iter().filter(|s| s.is_none()).count();
        full as f64 / self.stops.len() as f64
    }
}
