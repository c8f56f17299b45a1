//! The stages of a 3D run as plain functions: the wall surface (built in or read through
//! `mesh-io`), its check, the layers (`afsf3d`), the cut into standard cells (`topo-cut`), and
//! the measures of the result (cells by type, dihedral angles, volume against the volume
//! between the wall and the final front, coverage, the histograms of the dissertation's
//! tables 5–7); at orders 2 and 3 the curving (`vector-adding`, each wall onto its true surface)
//! and the curved volumes. No file is written here.

use crate::error::{Context, Result, input_error};
use geom_surface::Surface;
use mesh_model::measure3d;
use mesh_model::{Mesh, Role, Shape};
use rayon::prelude::*;
use serde::Serialize;

use crate::case3d::{Case3d, CutCells, SurfaceSource};

/// The true shape of a wall, where the P2 and P3 wall nodes go.
#[derive(Debug, Clone)]
pub enum TrueShape {
    /// The built-in sphere (centred at the origin).
    Sphere(vector_adding::SphereProjector),
    /// The wing: the section's curve times a straight line, the caps flat.
    Wing(Box<crate::wing::WingProjector>),
    /// A smooth surface rebuilt from the facets (STL and `.msh` surfaces): PN triangles,
    /// feature edges kept sharp (`geom_surface::SmoothSurface`).
    Smooth(Box<SmoothWall>),
    /// The facets themselves (cube, step): straight-sided P2 and P3 cells.
    Flat,
    /// Several bodies, or one moved or renamed: each body's shape over its facets.
    Bodies(Vec<BodyShape>),
}

/// One body's true shape among several: its facets in the case's surface, where it was moved.
#[derive(Debug, Clone)]
pub struct BodyShape {
    /// Its facets' indices in the case's surface.
    pub facets: std::ops::Range<usize>,
    /// How far it was moved from where its shape was built.
    pub translate: [f64; 3],
    /// Its shape where it was built.
    pub shape: TrueShape,
}

impl TrueShape {
    /// The projector onto this shape.
    fn projector(&self) -> &dyn vector_adding::SurfaceProjector {
        match self {
            TrueShape::Sphere(s) => s,
            TrueShape::Wing(w) => w.as_ref(),
            TrueShape::Smooth(s) => s.as_ref(),
            TrueShape::Flat => &FlatWall,
            TrueShape::Bodies(_) => self,
        }
    }
}

impl vector_adding::SurfaceProjector for TrueShape {
    /// Onto the body of wall facet `facet` (only [`TrueShape::Bodies`] is asked this way).
    fn project(&self, p: [f64; 3], facet: usize) -> [f64; 3] {
        let TrueShape::Bodies(bodies) = self else {
            return self.projector().project(p, facet);
        };
        let Some(b) = bodies.iter().find(|b| b.facets.contains(&facet)) else {
            return p;
        };
        let by = b.translate;
        let q = b.shape.projector().project(
            std::array::from_fn(|d| p[d] - by[d]),
            facet - b.facets.start,
        );
        std::array::from_fn(|d| q[d] + by[d])
    }
}

/// A wall known only by its facets, onto the smooth surface rebuilt from them.
#[derive(Debug, Clone)]
pub struct SmoothWall(pub geom_surface::SmoothSurface);

impl vector_adding::SurfaceProjector for SmoothWall {
    /// `p` is a point of wall facet `facet` (an edge's midpoint): onto that facet's patch.
    fn project(&self, p: [f64; 3], facet: usize) -> [f64; 3] {
        self.0.point(p, facet)
    }
}

/// A surface read from a file with its true shape: the smooth surface through its facets,
/// edges over [`geom_surface::DEFAULT_FEATURE_ANGLE_DEG`] kept sharp.
fn smoothed(surface: Surface) -> (Surface, TrueShape) {
    let smooth =
        geom_surface::SmoothSurface::new(&surface, geom_surface::DEFAULT_FEATURE_ANGLE_DEG);
    (surface, TrueShape::Smooth(Box::new(SmoothWall(smooth))))
}

/// Projects nothing: a flat (faceted) wall.
struct FlatWall;

impl vector_adding::SurfaceProjector for FlatWall {
    fn project(&self, p: [f64; 3], _facet: usize) -> [f64; 3] {
        p
    }
}

/// The wall surface of a case: its bodies built, or read from their files (not yet checked),
/// moved and put together, and their true shape. One body where it is built is that body's
/// surface and shape unchanged.
pub fn surface(case: &Case3d) -> Result<(Surface, TrueShape)> {
    if let [body] = case.bodies.as_slice()
        && body.translate == [0.0; 3]
        && body.name.is_none()
    {
        return body_surface(case, &body.source);
    }
    let mut all = Surface {
        nodes: Vec::new(),
        facets: Vec::new(),
        facet_patch: Vec::new(),
        patches: Vec::new(),
    };
    let mut taken: Vec<String> = vec![
        Role::Farfield.name().into(),
        "fluid".into(),
        crate::groups3d::OUTER_GROUP.into(),
    ];
    let mut shapes = Vec::with_capacity(case.bodies.len());
    for body in &case.bodies {
        let (s, shape) = body_surface(case, &body.source)?;
        let (node0, facet0, patch0) = (all.nodes.len(), all.facets.len(), all.patches.len());
        let by = body.translate;
        all.nodes.extend(
            s.nodes
                .iter()
                .map(|p| std::array::from_fn(|d| p[d] + by[d])),
        );
        all.facets.extend(s.facets.iter().map(|f| {
            geom_surface::Facet(f.0.map(|v| match v {
                geom_surface::NO_NODE => v,
                v => v + node0 as u32,
            }))
        }));
        all.facet_patch
            .extend(s.facet_patch.iter().map(|&p| p + patch0 as u32));
        for p in s.patches {
            // the body's name for its wall, its other patches after it
            let name = match (&body.name, p.name.as_str()) {
                (Some(n), "wall") => n.clone(),
                (Some(n), other) => format!("{n}_{other}"),
                (None, other) => other.to_string(),
            };
            let name = crate::case::wall_group_name(&name, &mut taken);
            all.patches.push(mesh_model::Patch { name, role: p.role });
        }
        shapes.push(BodyShape {
            facets: facet0..all.facets.len(),
            translate: by,
            shape,
        });
    }
    Ok((all, TrueShape::Bodies(shapes)))
}

/// One body's surface where it is built, and its true shape.
fn body_surface(case: &Case3d, source: &SurfaceSource) -> Result<(Surface, TrueShape)> {
    Ok(match source {
        SurfaceSource::Sphere { radius, refinement } => {
            let sphere = vector_adding::SphereProjector {
                centre: [0.0; 3],
                radius: *radius,
            };
            (
                Surface::sphere(*radius, *refinement),
                TrueShape::Sphere(sphere),
            )
        }
        SurfaceSource::Cube {
            size,
            divisions,
            triangles,
        } => (
            Surface::cube(*size, *divisions, *triangles),
            TrueShape::Flat,
        ),
        SurfaceSource::Step { refinement } => (Surface::step(*refinement), TrueShape::Flat),
        SurfaceSource::File(path) => {
            // a patch per group of the file: STL solids, `.msh` physical surfaces
            let read = mesh_io::stl::read_surface_grouped(path)
                .with_context(|| format!("{}: [surface] file", case.origin))?;
            smoothed(crate::groups3d::surface_of_file(read))
        }
        SurfaceSource::Wing {
            case: section,
            span,
            span_step,
            first_height,
            triangles,
            cap,
            element,
        } => {
            let at = || format!("{}: [surface] wing = {section:?}", case.origin);
            let mut section_case = crate::load::load_2d(section).with_context(at)?;
            if let Some(name) = element {
                // that wall loop alone (the far field's loops stay: they shape nothing here)
                let walls: Vec<String> = section_case
                    .loops
                    .iter()
                    .filter(|l| l.role == Role::Wall)
                    .map(|l| l.name.clone())
                    .collect();
                if !walls.contains(name) {
                    return Err(input_error!(
                        "{}: [surface] element = {name:?}: the case {section:?} has no wall loop of that name (it has {})",
                        case.origin,
                        walls.join(", ")
                    ));
                }
                section_case
                    .loops
                    .retain(|l| l.role != Role::Wall || &l.name == name);
            }
            if let Some(h) = first_height {
                section_case.layers.first_height = *h;
            }
            let (surface, shape) =
                crate::wing::wing_surface_with(&section_case, *span, *triangles, *cap, *span_step)
                    .with_context(at)?;
            let projector = crate::wing::WingProjector {
                surface: surface.clone(),
                shape,
            };
            (surface, TrueShape::Wing(Box::new(projector)))
        }
    })
}

/// The cut mesh curved to P2 or P3 (`order`) by Vector-Adding, the wall's high-order nodes
/// on its true shape.
pub fn curve(
    case: &Case3d,
    shape: &TrueShape,
    grown: &afsf3d::Grown3d,
    mesh: &Mesh,
    order: u8,
) -> Result<vector_adding::Curved3d> {
    let params = vector_adding::CurvingParams {
        order,
        ..vector_adding::CurvingParams::default()
    };
    vector_adding::curve_mesh_3d(mesh, &grown.all_columns(), shape.projector(), &params)
        .map_err(|e| input_error!("{}: curving to P{order}: {e}", case.origin))
}

/// The curved mesh's volume (the sum of `jacobian_check::cell_volume` over the cells in
/// order, as `jacobian_check::integrate_volume` adds them; the cells on all cores), its
/// smallest cell volume and the volume its curved boundary encloses
/// (`jacobian_check::enclosed_volume`), into `m` in place of the linear mesh's.
pub fn curved_volumes(curved: &Mesh, m: &mut Measures3d) -> Result<()> {
    let volumes: Vec<f64> = (0..curved.cells.len())
        .into_par_iter()
        .map(|i| {
            let cell = curved.cells.get(i);
            let x: Vec<[f64; 3]> = cell
                .nodes
                .iter()
                .map(|&n| curved.nodes[n as usize])
                .collect();
            jacobian_check::cell_volume(cell.ty, &x)
        })
        .collect::<Result<_, _>>()
        .context("the curved cells' volumes")?;
    m.min_cell_volume = volumes.iter().copied().fold(f64::INFINITY, f64::min);
    m.volume = volumes.iter().sum();
    m.volume_between =
        jacobian_check::enclosed_volume(curved).context("the curved boundary's volume")?;
    Ok(())
}

/// Checks that the surface can be meshed; the error names the first bad facet (or edge or
/// node) and where the surface came from.
pub fn check_surface(case: &Case3d, surface: &Surface) -> Result<()> {
    surface.check().map_err(|e| {
        let source = match case.bodies.as_slice() {
            [body] => match &body.source {
                SurfaceSource::File(path) => path.display().to_string(),
                _ => format!("{}: the built-in surface", case.origin),
            },
            _ => format!("{}: the bodies' surfaces", case.origin),
        };
        input_error!("{source}: {e}")
    })
}

/// The layers grown from the wall. A layer that fails names its wall facet and where that
/// facet is, so the user can find it.
pub fn grow(case: &Case3d, surface: &Surface) -> Result<afsf3d::Grown3d> {
    afsf3d::grow_layers(surface, &case.layers).map_err(|e| {
        let at = match &e {
            afsf3d::GrowError::LayerFailed { facet, .. } => facet_centre(surface, *facet)
                .map(|c| {
                    format!(
                        " (wall facet {facet} is centred at {:.4}, {:.4}, {:.4})",
                        c[0], c[1], c[2]
                    )
                })
                .unwrap_or_default(),
            _ => String::new(),
        };
        input_error!("{}: growing the layers: {e}{at}", case.origin)
    })
}

/// The mean of facet `f`'s nodes (`None` past the last facet).
fn facet_centre(surface: &Surface, f: usize) -> Option<[f64; 3]> {
    let nodes = surface.facets.get(f)?.nodes();
    let mut c = [0.0; 3];
    for &v in nodes {
        let p = surface.nodes[v as usize];
        for d in 0..3 {
            c[d] += p[d] / nodes.len() as f64;
        }
    }
    Some(c)
}

/// The layer cells cut into tetrahedra or mixed standard cells; in the mixed cut, the
/// standard cells [`cut_anyway`] flags are cut too (how many: the second value). `front` is
/// the grown layers' [`front_measures`].
pub fn cut(
    case: &Case3d,
    grown: &afsf3d::Grown3d,
    front: &FrontMeasures,
) -> Result<(Mesh, CutAnyway)> {
    let (mesh, flagged) = match case.cells {
        CutCells::Tets => (topo_cut::cut_to_tets(&grown.mesh), CutAnyway::default()),
        CutCells::Mixed => {
            let (flags, flagged) = cut_anyway(case, grown, front);
            (topo_cut::cut_to_mixed_cutting(&grown.mesh, &flags), flagged)
        }
        CutCells::Prisms => {
            let (flags, flagged) = cut_anyway(case, grown, front);
            (topo_cut::cut_to_prisms(&grown.mesh, &flags), flagged)
        }
    };
    let mesh = mesh.map_err(|e| input_error!("{}: cutting the layer cells: {e}", case.origin))?;
    Ok((mesh, flagged))
}

/// The largest dihedral angle (degrees) over which [`smooth`] moves a tetrahedron's nodes:
/// the aim (150°), under its bar (160°).
pub const SMOOTH_TARGET_DEG: f64 = 150.0;

/// Moves the nodes of `mesh`'s tetrahedra over [`SMOOTH_TARGET_DEG`] (`topo_cut::smooth`):
/// every node but the walls' and a far field's, the columns' first children only across their
/// extrusion edges (the first layer's height stays what the user asked). `mesh` is the linear mesh,
/// the layers `layers` (its first nodes) and their fill `filled` (its points after them);
/// both take the moved positions.
pub fn smooth(
    mesh: &mut Mesh,
    grown: &afsf3d::Grown3d,
    layers: &mut Mesh,
    filled: Option<&mut crate::fill3d::Filled>,
) -> topo_cut::smooth::Smoothed {
    use topo_cut::smooth::Freedom;
    let mut freedom = vec![Freedom::Free; mesh.nodes.len()];
    for column in grown.all_columns() {
        if let [wall, first, ..] = column[..] {
            let e =
                geom_predicates::vector::sub(mesh.nodes[first as usize], mesh.nodes[wall as usize]);
            freedom[first as usize] = Freedom::Across(e);
        }
    }
    for (f, facet) in mesh.boundary.iter().enumerate() {
        let patch = &mesh.patches[mesh.boundary_patch[f] as usize];
        if patch.role == Role::Wall || patch.name != crate::groups3d::OUTER_GROUP {
            for &v in facet.corners() {
                freedom[v as usize] = Freedom::Fixed;
            }
        }
    }
    let smoothed = topo_cut::smooth::smooth_worst_tets(mesh, &freedom, SMOOTH_TARGET_DEG);
    if smoothed.moves > 0 {
        let n = layers.nodes.len();
        layers.nodes.copy_from_slice(&mesh.nodes[..n]);
        if let Some(f) = filled {
            f.points.copy_from_slice(&mesh.nodes[n..]);
            let x = |v: u32| mesh.nodes[v as usize];
            f.stats.max_dihedral_deg = f
                .cells
                .iter()
                .filter(|(shape, _)| *shape == Shape::Tet)
                .map(|(_, k)| measure3d::tet_max_dihedral_deg_of([0, 1, 2, 3].map(|j| x(k[j]))))
                .fold(0.0, f64::max);
        }
    }
    smoothed
}

/// How many prisms and hexahedra the mixed cut was asked to cut rather than keep, by reason
/// (a cell may have both).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CutAnyway {
    /// Over an extrusion edge leaning more than `[cut] max_lean_deg`.
    pub leaning: usize,
    /// With a corner scaled Jacobian below `[cut] min_corner_sj`.
    pub low_corner: usize,
}

/// One flag per layer cell the mixed cut round-cuts though it is a standard cell (empty when
/// none is): the leaning ones ([`leaning_cells`]) and the prisms and hexahedra with a corner
/// scaled Jacobian below `[cut] min_corner_sj` ([`topo_cut::quality::low_corner_cells`]);
/// and how many of each.
pub fn cut_anyway(
    case: &Case3d,
    grown: &afsf3d::Grown3d,
    front: &FrontMeasures,
) -> (Vec<bool>, CutAnyway) {
    let leaning = leaning_cells(grown, &front.deviations, case.max_lean_deg);
    let low = if case.min_corner_sj > 0.0 {
        topo_cut::quality::low_corner_cells(&grown.mesh, case.min_corner_sj)
    } else {
        Vec::new()
    };
    let counts = CutAnyway {
        leaning: topo_cut::quality::flagged_layer_shapes(&grown.mesh, &leaning),
        low_corner: low.iter().filter(|&&x| x).count(),
    };
    let flags = match (leaning.is_empty(), low.is_empty()) {
        (_, true) => leaning,
        (true, false) => low,
        (false, false) => leaning.iter().zip(&low).map(|(&a, &b)| a || b).collect(),
    };
    (flags, counts)
}

/// One flag per layer cell: whether both ends of an extrusion edge leaning more than
/// `limit_deg` off its front's normal (table 6's angle, `deviations` of [`front_measures`])
/// are nodes of it (so, in a prism or hexahedron, one of its side edges). Empty (none
/// flagged) at 180° and where no edge leans more.
pub fn leaning_cells(
    grown: &afsf3d::Grown3d,
    deviations: &[((u32, u32), f64)],
    limit_deg: f64,
) -> Vec<bool> {
    if limit_deg >= 180.0 {
        return Vec::new();
    }
    // each leaning edge by its two nodes, lower first
    let mut leaning: Vec<(u32, u32)> = deviations
        .iter()
        .filter(|d| d.1 > limit_deg)
        .map(|&((a, b), _)| (a.min(b), a.max(b)))
        .collect();
    if leaning.is_empty() {
        return Vec::new();
    }
    leaning.sort_unstable();
    let poly = &grown.mesh;
    let mut nodes = Vec::new();
    (0..poly.cell_count())
        .map(|c| {
            nodes.clear();
            for f in poly.cell(c) {
                nodes.extend_from_slice(poly.face(f.face as usize));
            }
            nodes.sort_unstable();
            nodes.dedup();
            // a cell's pairs of nodes (at most 28) looked up among the leaning edges
            (0..nodes.len()).any(|i| {
                nodes[i + 1..]
                    .iter()
                    .any(|&b| leaning.binary_search(&(nodes[i], b)).is_ok())
            })
        })
        .collect()
}

/// The upper bin edges of table 5 (largest angle of the front facets), degrees.
pub const FRONT_ANGLE_EDGES: [f64; 3] = [90.0, 125.0, 140.0];
/// The upper bin edges of table 6 (extrusion-edge deviation), degrees.
pub const DEVIATION_EDGES: [f64; 3] = [10.0, 20.0, 30.0];
/// The upper bin edges of table 7 (largest dihedral angle of the tetrahedra), degrees.
pub const DIHEDRAL_EDGES: [f64; 4] = [90.0, 130.0, 150.0, 160.0];

/// A histogram of the report: counts in `(-∞, e₀], (e₀, e₁], …, (eₙ₋₁, 180]`.
#[derive(Debug, Clone, Serialize)]
pub struct Histogram {
    /// A short name.
    pub name: &'static str,
    /// What is counted.
    pub of: &'static str,
    /// The bins' upper edges, degrees (the last bin runs to 180).
    pub upper_edges_deg: Vec<f64>,
    /// How many in each bin.
    pub counts: Vec<usize>,
    /// The largest value, degrees.
    pub max_deg: f64,
}

impl Histogram {
    fn new((name, of): (&'static str, &'static str), edges: &[f64], values: &[f64]) -> Histogram {
        Histogram {
            name,
            of,
            upper_edges_deg: edges.to_vec(),
            counts: measure3d::histogram(values.iter().copied(), edges),
            max_deg: values.iter().copied().fold(0.0, f64::max),
        }
    }
}

/// What a 3D mesh measures.
#[derive(Debug, Clone)]
pub struct Measures3d {
    /// Cells by type.
    pub cells: [(&'static str, usize); 4],
    /// Sum of the cell volumes.
    pub volume: f64,
    /// The volume between the wall and the final front: the volume the front's facets
    /// enclose minus the wall's, by the divergence theorem over the mesh's boundary facets
    /// alone (the front as the cut triangulates it), independent of the cells. For a mesh
    /// read back ([`mesh_measures`]) the volume its boundary facets enclose, the same thing.
    pub volume_between: f64,
    /// The smallest cell volume.
    pub min_cell_volume: f64,
    /// The largest dihedral angle of the tetrahedra (0 without any).
    pub max_dihedral_deg: f64,
    /// Fraction of the wall nodes with their full column of layers (`None` for a mesh read
    /// back, whose growth is not known).
    pub coverage: Option<f64>,
    /// Tables 5, 6 and 7, then table 6 over the extrusion edges of the prisms and
    /// hexahedra alone when the mesh has any (the mixed cut's layers); table 7 alone for a
    /// mesh read back (5 and 6 measure the growth).
    pub histograms: Vec<Histogram>,
    /// The smallest corner scaled Jacobian of the prisms and hexahedra (`None` without any).
    pub min_corner_sj: Option<CornerJacobian>,
}

/// The smallest corner scaled Jacobian of a mesh's prisms and hexahedra and where it is.
#[derive(Debug, Clone, Serialize)]
pub struct CornerJacobian {
    /// What is measured.
    pub of: &'static str,
    /// The smallest value.
    pub value: f64,
    /// Its cell (0-based).
    pub cell: usize,
    /// Its cell's layer (0 on the wall; absent for a mesh read back, which has no layers).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layer: Option<u32>,
    /// The mean of its cell's corners.
    pub at: [f64; 3],
    /// The smallest value over the cells grown from each wall patch (by name; empty for a
    /// mesh read back, whose cells' pipes are not known).
    #[serde(skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub by_wall_patch: std::collections::BTreeMap<String, f64>,
}

/// The prisms' and hexahedra's smallest corner scaled Jacobian ([`CornerJacobian`]); the
/// smallest by wall patch when the `wall` the cells' pipes number is given.
fn min_corner_sj(wall: Option<&Surface>, mesh: &Mesh) -> Option<CornerJacobian> {
    let (value, cell) = (0..mesh.cells.len())
        .into_par_iter()
        .filter_map(|i| measure3d::min_corner_scaled_jacobian(mesh, i).map(|q| (q, i)))
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))?;
    let mut by_wall_patch = std::collections::BTreeMap::new();
    for i in 0..mesh.cells.len() {
        let (Some(wall), Some(q), Some(&f)) = (
            wall,
            measure3d::min_corner_scaled_jacobian(mesh, i),
            mesh.cell_pipe.get(i),
        ) else {
            continue;
        };
        let Some(patch) = wall
            .facet_patch
            .get(f as usize)
            .and_then(|&p| wall.patches.get(p as usize))
        else {
            continue;
        };
        let name = patch.name.clone();
        let v = by_wall_patch.entry(name).or_insert(q);
        *v = q.min(*v);
    }
    let k = mesh.cells.get(cell).corners();
    let at = std::array::from_fn(|d| {
        k.iter().map(|&v| mesh.nodes[v as usize][d]).sum::<f64>() / k.len() as f64
    });
    Some(CornerJacobian {
        of: "smallest edge-normalised corner scaled Jacobian of the prisms and hexahedra: \
             det(e1, e2, e3) / (|e1| |e2| |e3|) of the three edges at each corner",
        value,
        cell,
        layer: mesh.cell_layer.get(cell).copied(),
        at,
        by_wall_patch,
    })
}

/// Measures the cut `mesh` of the layers `grown` from `wall` ([`Measures3d`]); `front` is the
/// grown layers' [`front_measures`] (tables 5 and 6).
pub fn measure(
    wall: &Surface,
    grown: &afsf3d::Grown3d,
    front: &FrontMeasures,
    mesh: &Mesh,
    layers: usize,
) -> Measures3d {
    let mut m = measure_cells(mesh, Some(wall));
    debug_assert!(grown.columns.iter().all(|c| c.len() <= layers + 1));
    m.coverage = Some(grown.coverage());
    let (front_angles, deviations) = (&front.angles, &front.deviations);
    let layered = layered_deviations(mesh, deviations);
    let growth = [
        Histogram::new(
            (
                "front facet max angle",
                "largest corner angle of every front facet grown (layers 1 to n; \
                 dissertation table 5)",
            ),
            &FRONT_ANGLE_EDGES,
            front_angles,
        ),
        Histogram::new(
            (
                "extrusion edge deviation",
                "angle between each extrusion edge and the angle-weighted normal of the \
                 front it grew from (dissertation table 6)",
            ),
            &DEVIATION_EDGES,
            &deviations.iter().map(|d| d.1).collect::<Vec<_>>(),
        ),
    ];
    // tables 5 and 6 before the mesh's table 7, then table 6 over the layers' cells
    m.histograms.splice(0..0, growth);
    m.histograms.extend(layered.map(|values| {
        Histogram::new(
            (
                "layer extrusion edge deviation",
                "table 6 over the extrusion edges of the prisms and hexahedra alone (the \
                 mixed cut's layers; the extrusion edges of merged children are cut into \
                 tetrahedra and pyramids)",
            ),
            &DEVIATION_EDGES,
            &values,
        )
    }));
    m
}

/// Measures a 3D mesh from its cells and boundary facets alone, for a mesh read back
/// from a file ([`crate::quality`]): what [`measure`] measures of a run's mesh but what needs
/// the growth (the coverage, tables 5 and 6, the minimum corner scaled Jacobian by wall
/// patch). The mesh must be structurally sound (`mesh_model::first_structural_problem`).
/// At order 2 the volumes are the corners' (the linear cells'): [`curved_volumes`] puts the
/// curved cells' in their place.
pub fn mesh_measures(mesh: &Mesh) -> Measures3d {
    measure_cells(mesh, None)
}

/// The measures of `mesh` that need no growth: counts, volumes, the volume its boundary
/// encloses, table 7, the minimum corner scaled Jacobian (by patch of `wall` when given).
fn measure_cells(mesh: &Mesh, wall: Option<&Surface>) -> Measures3d {
    let n = mesh.cells.len();
    let volumes: Vec<f64> = (0..n)
        .into_par_iter()
        .map(|i| measure3d::cell_volume(mesh, i))
        .collect();
    let dihedral: Vec<f64> = (0..n)
        .into_par_iter()
        .filter(|&i| mesh.cells.get(i).ty.shape == Shape::Tet)
        .map(|i| measure3d::tet_max_dihedral_deg(mesh, i))
        .collect();
    let count = |s| mesh.count(s);
    Measures3d {
        cells: [
            ("tet", count(Shape::Tet)),
            ("pyramid", count(Shape::Pyramid)),
            ("prism", count(Shape::Prism)),
            ("hex", count(Shape::Hex)),
        ],
        volume: volumes.iter().sum(),
        volume_between: enclosed(mesh, Role::Farfield) + enclosed(mesh, Role::Wall),
        min_cell_volume: volumes.iter().copied().fold(f64::INFINITY, f64::min),
        max_dihedral_deg: dihedral.iter().copied().fold(0.0, f64::max),
        coverage: None,
        histograms: vec![Histogram::new(
            (
                "tet max dihedral",
                "largest dihedral angle of every tetrahedron (dissertation table 7)",
            ),
            &DIHEDRAL_EDGES,
            &dihedral,
        )],
        min_corner_sj: min_corner_sj(wall, mesh),
    }
}

/// The deviations (of [`front_measures`]) of the extrusion edges that are side edges of a
/// prism or a hexahedron of the cut `mesh` (bottom corner `i` to top corner `m + i`, the cut
/// keeping the grown nodes); `None` when the mesh has no prism or hexahedron.
fn layered_deviations(mesh: &Mesh, deviations: &[((u32, u32), f64)]) -> Option<Vec<f64>> {
    let mut sides: Vec<(u32, u32)> = (0..mesh.cells.len())
        .map(|i| mesh.cells.get(i))
        .filter(|c| matches!(c.ty.shape, Shape::Prism | Shape::Hex))
        .flat_map(|c| {
            let k = c.corners();
            let m = k.len() / 2;
            (0..m).map(move |i| (k[i], k[m + i]))
        })
        .collect();
    if sides.is_empty() {
        return None;
    }
    sides.sort_unstable();
    sides.dedup();
    Some(
        deviations
            .iter()
            .filter(|(e, _)| sides.binary_search(e).is_ok())
            .map(|d| d.1)
            .collect(),
    )
}

/// The volume the boundary facets of `role` enclose, by the divergence theorem (facets turned
/// out of the domain, so a wall's is negative), each facet fanned from its centroid.
fn enclosed(mesh: &Mesh, role: Role) -> f64 {
    let o = mesh.nodes.first().copied().unwrap_or_default();
    let mut points = Vec::with_capacity(4);
    let mut sum = 0.0;
    for (f, &p) in mesh.boundary.iter().zip(&mesh.boundary_patch) {
        if mesh.patches[p as usize].role == role {
            points.clear();
            points.extend(f.corners().iter().map(|&v| mesh.nodes[v as usize]));
            sum += measure3d::cone_volume6(&points, o);
        }
    }
    sum / 6.0
}

/// The largest corner angle of every facet of the fronts of layers 1 to n, and the deviation
/// of every extrusion edge from the angle-weighted normal of the front it grew from. A front
/// is the wall's facets over the nodes of that layer (a stopped column's top where it has
/// fewer layers): where children merged, a facet loses its repeated corner (a quad becomes a
/// triangle) or, left with two corners, is no facet of that front (it collapsed to an edge)
/// and is not counted, nor is a facet all of whose columns stopped below that layer (it was
/// not grown there); an extrusion edge two merged columns share is counted once.
pub fn front_measures(wall: &Surface, grown: &afsf3d::Grown3d) -> FrontMeasures {
    let depth = grown.columns.iter().map(Vec::len).max().unwrap_or(0);
    let mut angles = Vec::new();
    let mut deviations = Vec::new();
    let mut points = Vec::with_capacity(4);
    let nodes = &grown.mesh.nodes;
    let mut below = layer_front(wall, grown, 0);
    for k in 0..depth.saturating_sub(1) {
        let normals = geom_surface::node_normals(nodes, &below);
        let mut edges: Vec<(u32, u32)> = grown
            .columns
            .iter()
            .filter(|c| c.len() > k + 1)
            .map(|c| (c[k], c[k + 1]))
            .filter(|(a, b)| a != b)
            .collect();
        edges.sort_unstable();
        edges.dedup();
        for (a, b) in edges {
            let (p, q) = (nodes[a as usize], nodes[b as usize]);
            deviations.push((
                (a, b),
                measure3d::angle_deg(std::array::from_fn(|d| q[d] - p[d]), normals[a as usize]),
            ));
        }
        let above = layer_front(wall, grown, k + 1);
        for f in &above {
            points.clear();
            points.extend(f.nodes().iter().map(|&v| nodes[v as usize]));
            angles.push(measure3d::polygon_max_angle_deg(&points));
        }
        below = above;
    }
    FrontMeasures { angles, deviations }
}

/// Tables 5 and 6 of the grown layers ([`front_measures`]): what the mixed cut's leaning test
/// and the report's measures both read, measured once.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontMeasures {
    /// The largest corner angle of every facet of the fronts of layers 1 to n, degrees.
    pub angles: Vec<f64>,
    /// Every extrusion edge (its two nodes, lower layer first) and its deviation from the
    /// normal of the front it grew from, degrees.
    pub deviations: Vec<((u32, u32), f64)>,
}

/// The front of layer `k` as facets over the grown mesh's nodes: each wall facet over its
/// corners' layer-`k` nodes (the top of a column with fewer layers), repeated corners
/// dropped, those left with fewer than three corners left out, and those whose columns all
/// hold fewer than `k` layers (stopped below: not grown in layer `k − 1`).
fn layer_front(wall: &Surface, grown: &afsf3d::Grown3d, k: usize) -> Vec<geom_surface::Facet> {
    let mut facets = Vec::with_capacity(wall.facets.len());
    let mut corners: Vec<u32> = Vec::with_capacity(4);
    for f in &wall.facets {
        let column = |v: u32| &grown.columns[v as usize];
        if k > 0 && f.nodes().iter().all(|&v| column(v).len() <= k) {
            continue;
        }
        corners.clear();
        for &v in f.nodes() {
            let c = column(v);
            let node = c[k.min(c.len() - 1)];
            if corners.last() != Some(&node) {
                corners.push(node);
            }
        }
        while corners.len() > 1 && corners.first() == corners.last() {
            corners.pop();
        }
        match corners[..] {
            [a, b, c] if a != c => facets.push(geom_surface::Facet::tri(a, b, c)),
            [a, b, c, d] => facets.push(geom_surface::Facet::quad(a, b, c, d)),
            _ => {}
        }
    }
    facets
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom_surface::Facet;

    /// A square wall split in two triangles, two layers; at layer 1 the children of wall
    /// nodes 1 and 2 merged (node 5), so the first triangle's child collapsed to an edge.
    fn merged() -> (Surface, afsf3d::Grown3d) {
        let wall = Surface::single_patch(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            vec![Facet::tri(0, 1, 2), Facet::tri(0, 2, 3)],
            "wall",
        );
        let mut mesh = mesh_model::poly::PolyMesh::new();
        mesh.nodes = wall.nodes.clone();
        mesh.nodes
            .extend([[0.0, 0.0, 1.0], [1.0, 0.5, 1.0], [0.0, 1.0, 1.0]]);
        mesh.nodes
            .extend([[0.0, 0.0, 2.0], [1.0, 0.5, 2.0], [0.0, 1.0, 2.0]]);
        let grown = afsf3d::Grown3d {
            mesh,
            columns: vec![vec![0, 4, 7], vec![1, 5, 8], vec![2, 5, 8], vec![3, 6, 9]],
            stops: vec![None; 4],
            fan_columns: vec![],
            front: wall.clone(),
            front_nodes: vec![],
            node_layer: vec![],
            node_parents: vec![],
            layer_merges: vec![0, 1, 0],
            layer_heights: vec![1.0; 3],
            stats: Default::default(),
        };
        (wall, grown)
    }

    #[test]
    fn collapsed_facets_and_shared_extrusion_edges_are_not_counted() {
        let (wall, grown) = merged();
        let front = layer_front(&wall, &grown, 1);
        assert_eq!(front, vec![Facet::tri(4, 5, 6)]);
        let FrontMeasures { angles, deviations } = front_measures(&wall, &grown);
        // layer 1: the one triangle left; layer 2: the same
        assert_eq!(angles.len(), 2, "{angles:?}");
        assert!(angles.iter().all(|&a| a < 90.0), "{angles:?}");
        // layer 0 to 1: four edges; layer 1 to 2: three (5 -> 8 once)
        assert_eq!(deviations.len(), 7, "{deviations:?}");
        assert!(deviations[..4].iter().all(|d| d.1 < 60.0), "{deviations:?}");
        assert!(deviations[4..].iter().all(|d| d.1 < 1e-9), "{deviations:?}");
    }

    #[test]
    fn the_layers_table_6_counts_only_the_side_edges_of_prisms_and_hexahedra() {
        use mesh_model::{CellType, Dim};
        let mut mesh = Mesh::new(Dim::Three, 1);
        mesh.nodes = vec![[0.0; 3]; 8];
        // a prism 0 1 2 | 3 4 5 and a tetrahedron 0 2 6 7 (its edge 6-7 is no prism's)
        mesh.cells
            .push(CellType::new(Shape::Prism, 1), &[0, 1, 2, 3, 4, 5]);
        mesh.cells.push(CellType::new(Shape::Tet, 1), &[0, 2, 6, 7]);
        let deviations = [
            ((0, 3), 5.0),
            ((1, 4), 35.0),
            ((6, 7), 40.0),
            ((0, 1), 50.0),
        ];
        assert_eq!(
            layered_deviations(&mesh, &deviations),
            Some(vec![5.0, 35.0])
        );
        let mut tets = Mesh::new(Dim::Three, 1);
        tets.nodes = vec![[0.0; 3]; 4];
        tets.cells.push(CellType::new(Shape::Tet, 1), &[0, 1, 2, 3]);
        assert_eq!(layered_deviations(&tets, &deviations), None);
    }
}
