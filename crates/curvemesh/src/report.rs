//! The JSON report of a run (`--report`), with the keys of the interface contract. Keys whose
//! stage has not run are left out rather than filled with made-up values.

use std::collections::BTreeMap;
use std::path::Path;

use mesh_model::{Mesh, Role, Shape};
use serde::Serialize;

use crate::error::{Result, bail};

/// Everything a run reports.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Report {
    /// The case's name.
    pub case: String,
    /// 2 or 3.
    pub dimension: u8,
    /// Polynomial order of the cells.
    pub order: u8,
    /// Number of mesh nodes (high-order nodes included).
    pub nodes: usize,
    /// Domain cells by type (`tri`, `quad`).
    pub cells: BTreeMap<&'static str, usize>,
    /// Boundary facets by patch role (`wall`, `farfield`).
    pub boundary_facets: BTreeMap<&'static str, usize>,
    /// Boundary facets by boundary group, as named in the `.msh` physical groups and the
    /// `.su2` markers: each wall body (`slat`, `main`, `flap`, or one `wall` with
    /// `merge_walls = true`) and `farfield`.
    pub boundary_groups: BTreeMap<String, usize>,
    /// Most layers grown from any boundary, when the domain was meshed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layers: Option<u32>,
    /// Seconds spent in each stage, and in all.
    pub timings_s: BTreeMap<&'static str, f64>,
    /// The process's peak resident memory when the outputs were written, in bytes (Linux).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_memory_bytes: Option<u64>,
    /// Quality figures, when the domain was meshed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quality: Option<Quality>,
    /// Fraction of the edges left curved, when the mesh was curved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curved_edge_fraction: Option<f64>,
    /// What the curving did, when the mesh was curved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curving: Option<vector_adding::CurvingStats>,
    /// Area of the meshed domain (integrated over the curved cells when curved), when meshed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area: Option<f64>,
    /// 3D: the quality figures (written as `quality`, in place of the 2D block).
    #[serde(rename = "quality", skip_serializing_if = "Option::is_none")]
    pub quality_3d: Option<Quality3d>,
    /// 3D: the sum of the cell volumes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub volume: Option<f64>,
    /// 3D: the cell volumes against the volume between the wall and the final front.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub volume_check: Option<VolumeCheck>,
    /// 3D: the fraction of wall nodes that keep their full column of layers.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coverage: Option<f64>,
    /// 3D: the columns of layers: coverage, the least layers per boundary group, where
    /// columns stopped and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub columns: Option<crate::columns3d::Columns>,
    /// 3D with a far field: the volume fill between the layers' final front and the far field.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fill: Option<crate::fill3d::FillStats>,
    /// Each boundary loop: name, role, node count, corner count.
    pub loops: Vec<LoopReport>,
    /// The files written.
    pub files: Vec<String>,
    /// Each mesh file written, with its format and the order of the cells actually in it
    /// (`.su2` holds the linear mesh whatever `order` says).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub meshes: Vec<WrittenMesh>,
    /// What a user should know about this run (stages not available, limits reached).
    pub notes: Vec<String>,
    /// `move` at order 2 or 3: curving decisions of the original mesh that the motion
    /// changed (`vector_adding::curve_mesh_keeping`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curving_decisions_changed: Option<usize>,
    /// What failed validation, if anything (the run then exits with status 2).
    pub problems: Vec<String>,
    /// `move` only: the motion, the mover and the quality before and after the move.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub movement: Option<crate::movement::report::MovementReport>,
    /// The cells expected before the domain was meshed (`mesh` only), see `--max-cells`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimated_cells: Option<u64>,
    /// The inputs the run used: the layers' first height, growth and count, and where given
    /// the angle of attack, y⁺, Reynolds number, far-field radius and reference chord.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inputs: Option<Inputs>,
}

impl Report {
    /// An empty report for a case at an order.
    pub fn new(case: &str, order: u8) -> Report {
        Report {
            case: case.to_string(),
            dimension: 2,
            order,
            ..Report::default()
        }
    }

    /// The report as pretty JSON.
    pub fn json(&self) -> Result<Vec<u8>> {
        Ok(serde_json::to_string_pretty(self)?.into_bytes())
    }

    /// The line that tells a run's caller its mesh failed validation: the first problem, how
    /// many there are, and the report at `path` (when written); `subject` is what failed
    /// ("the mesh was written but", "FILE.msh"). `None` when the mesh is valid.
    pub fn verdict(&self, path: Option<&Path>, subject: &str) -> Option<String> {
        let first = self.problems.first()?;
        let more = match self.problems.len() {
            1 => String::new(),
            n => format!(" (and {} more problems)", n - 1),
        };
        let see = path.map_or_else(String::new, |p| format!("; see {}", p.display()));
        Some(format!("{subject} failed validation: {first}{more}{see}"))
    }

    /// True when validation found no problem.
    pub fn is_valid(&self) -> bool {
        self.problems.is_empty()
    }

    /// Fills what can be read off a finished 2D mesh: counts, angles, and the structural
    /// problems found by `mesh_model::validate`.
    pub fn describe(&mut self, mesh: &Mesh) {
        self.describe_over(mesh, LinearAngles::Of(mesh));
    }

    /// [`Report::describe`], with the angle figures of `linear`, the linear mesh under `mesh`
    /// ([`ANGLES_OF`]), or those figures already computed; timed as
    /// `describe` (with the seconds the given figures took).
    pub fn describe_over(&mut self, mesh: &Mesh, linear: LinearAngles<'_>) {
        let t = std::time::Instant::now();
        self.nodes = mesh.nodes.len();
        for shape in [Shape::Tri, Shape::Quad] {
            self.cells.insert(shape.name(), mesh.count(shape));
        }
        self.count_boundary(mesh);
        let problems = mesh_model::validate(mesh);
        // orientation and conformity problems leave every index and array sound: the angles
        // (and the certified check, see `certify`) still tell what is wrong where
        let sound = !problems.iter().any(mesh_model::Problem::is_structural);
        self.problems = problems.iter().map(ToString::to_string).collect();
        let mut seconds = 0.0;
        if sound && !mesh.cells.is_empty() {
            let angles = match linear {
                LinearAngles::Of(linear) => afsf2d::max_angle_histogram(linear),
                LinearAngles::Given { angles, seconds: s } => {
                    seconds = s;
                    angles
                }
            };
            self.set_angles(&angles);
        }
        self.timings_s
            .insert("describe", seconds + t.elapsed().as_secs_f64());
    }

    /// Counts the boundary facets by role and by boundary group.
    fn count_boundary(&mut self, mesh: &Mesh) {
        for role in [Role::Wall, Role::Farfield] {
            let n = mesh
                .boundary_patch
                .iter()
                .filter(|&&p| mesh.patches.get(p as usize).is_some_and(|q| q.role == role))
                .count();
            if n > 0 {
                self.boundary_facets.insert(role.name(), n);
            }
        }
        if let Ok((groups, of_patch)) = mesh_io::groups::boundary_groups(mesh) {
            for (g, group) in groups.iter().enumerate() {
                let n = mesh
                    .boundary_patch
                    .iter()
                    .filter(|&&p| of_patch.get(p as usize) == Some(&g))
                    .count();
                self.boundary_groups.insert(group.name.clone(), n);
            }
        }
    }

    /// Fills what can be read off a finished linear 3D mesh with its measures `m`: counts,
    /// quality, volume, coverage, and as problems whatever `mesh_model::validate` finds (the
    /// structure, conformity, positive corner Jacobians by the exact `orient3d`) and a volume
    /// that differs from the volume between the wall and the front by more than
    /// [`VOLUME_TOLERANCE`].
    pub fn describe_3d(&mut self, mesh: &Mesh, m: &crate::pipeline3d::Measures3d) {
        self.describe_3d_structure(mesh);
        let difference = (m.volume - m.volume_between).abs() / m.volume_between.abs();
        // NaN (no volume between) fails too
        if difference.is_nan() || difference > VOLUME_TOLERANCE {
            self.problems.push(format!(
                "the cell volumes sum to {:e}, the volume between the wall and the final front \
                 is {:e} (relative difference {difference:e}, above {VOLUME_TOLERANCE:e})",
                m.volume, m.volume_between
            ));
        }
        self.volume = Some(m.volume);
        self.volume_check = Some(VolumeCheck {
            between_wall_and_front: m.volume_between,
            relative_difference: difference,
            tolerance: VOLUME_TOLERANCE,
        });
        self.coverage = m.coverage;
        self.quality_3d = Some(Quality3d {
            max_dihedral_deg: m.max_dihedral_deg,
            min_cell_volume: m.min_cell_volume,
            histograms: m.histograms.to_vec(),
            min_corner_scaled_jacobian: m.min_corner_sj.clone(),
            validity: None,
        });
    }

    /// Fills what a 3D mesh shows without measuring it: the counts (nodes, cells by type,
    /// boundary facets by role and group) and as problems whatever `mesh_model::validate`
    /// finds. [`Report::describe_3d`] starts with it; alone, for a mesh whose structure is
    /// broken (an index out of range, a coordinate not finite), which cannot be measured.
    pub fn describe_3d_structure(&mut self, mesh: &Mesh) {
        self.dimension = 3;
        self.nodes = mesh.nodes.len();
        self.cells = [Shape::Tet, Shape::Pyramid, Shape::Prism, Shape::Hex]
            .into_iter()
            .map(|s| (s.name(), mesh.count(s)))
            .collect();
        self.count_boundary(mesh);
        self.problems = mesh_model::validate(mesh)
            .iter()
            .map(ToString::to_string)
            .collect();
    }

    /// Certifies every cell of the P2 or P3 mesh `curved` (after [`Report::describe_3d`]) as
    /// [`Report::certify`] does in 2D: the validity figures in the quality block, every
    /// invalid, undecided or uncertified cell a problem ([`Report::certify_cells_3d`]); and
    /// what the curving did, as notes.
    pub fn certify_3d(
        &mut self,
        curved: &vector_adding::Curved3d,
        shape: &crate::pipeline3d::TrueShape,
    ) -> Result<()> {
        use crate::pipeline3d::TrueShape;
        if !self.certify_cells_3d(&curved.mesh)? {
            return Ok(());
        }
        let s = &curved.stats;
        self.curved_edge_fraction = Some(s.curved_edge_fraction);
        let p = curved.mesh.order;
        let wall = match shape {
            TrueShape::Sphere(_) => format!("the wall's P{p} nodes on the true sphere"),
            TrueShape::Wing(_) => format!(
                "the wall's P{p} nodes on the true wing (the section's curve times the span; the \
                 tip caps flat)"
            ),
            TrueShape::Smooth(s) => format!(
                "the wall's P{p} nodes on a smooth surface rebuilt from its facets (PN triangles; \
                 {} edges between facets over {}° apart kept sharp)",
                s.0.feature_edge_count(),
                geom_surface::DEFAULT_FEATURE_ANGLE_DEG
            ),
            TrueShape::Flat => format!(
                "the wall is flat-faceted (a cube or step): its P{p} nodes where the straight \
                 facets put them, so the cells are straight-sided P{p} cells"
            ),
            TrueShape::Bodies(b) => format!(
                "the wall's P{p} nodes on each of the {} bodies' true surfaces (a sphere's, a \
                 wing's, one rebuilt from a file's facets; a cube's or step's flat)",
                b.len()
            ),
        };
        self.notes.push(format!(
            "P{p} by Vector-Adding up the pipes: {wall}; {} of {} edges curved, up to layer {}; \
             {} cells the marching left invalid mended by the repair ({} not); {P2_VALIDITY}",
            s.curved_edges, s.edges, s.deepest_curved_layer, s.repaired, s.unrepaired
        ));
        Ok(())
    }

    /// Certifies every cell of the high-order 3D `mesh` (after [`Report::describe_3d`]): the
    /// validity figures in the quality block, every invalid, undecided or uncertified cell a
    /// problem. False when the check could not run on a mesh that already has problems (that
    /// is then one more problem); an error when it could not run on a mesh without.
    pub fn certify_cells_3d(&mut self, mesh: &Mesh) -> Result<bool> {
        let v = match jacobian_check::check_mesh(mesh, &jacobian_check::CertifyParams::default()) {
            Ok(v) => v,
            Err(e) if !self.problems.is_empty() => {
                self.problems
                    .push(format!("the certified Jacobian check could not run: {e}"));
                return Ok(false);
            }
            Err(e) => bail!("certifying the mesh: {e}"),
        };
        if let Some(q) = self.quality_3d.as_mut() {
            q.validity = Some(Validity3d {
                min_scaled_jacobian: v.min_scaled_jacobian,
                scaled_jacobian_of: SCALED_JACOBIAN_OF,
                invalid_cells: v.invalid_cells.len(),
                certified: v.undecided.is_empty() && v.uncertified.is_empty(),
            });
        }
        let verdicts = [
            ("invalid", &v.invalid_cells),
            ("undecided", &v.undecided),
            ("uncertified", &v.uncertified),
        ];
        for (what, cells) in verdicts {
            if let Some(&c) = cells.first() {
                let first: Vec<String> = cells.iter().take(5).map(ToString::to_string).collect();
                let k = mesh.cells.get(c).corners();
                let x = [0, 1, 2].map(|d| {
                    k.iter().map(|&n| mesh.nodes[n as usize][d]).sum::<f64>() / k.len() as f64
                });
                self.problems.push(format!(
                    "{} cells {what} by the certified Jacobian check (first: {}; cell {c} near \
                     ({:.6e}, {:.6e}, {:.6e}))",
                    cells.len(),
                    first.join(", "),
                    x[0],
                    x[1],
                    x[2]
                ));
            }
        }
        Ok(true)
    }

    /// Fills the angle figures from those of the linear mesh under the final one (its cell
    /// corners, quads cut along the shorter diagonal), so that they do not depend on the order
    /// or on `--triangles`.
    fn set_angles(&mut self, angles: &afsf2d::AngleStats) {
        let q = self.quality.get_or_insert_with(Quality::default);
        q.max_angle_deg = angles.max_angle_deg;
        q.obtuse_hist = angles.histogram;
        q.angles_of = ANGLES_OF;
    }

    /// Records a mesh file written at `order`, with a note when the format cannot hold the
    /// order of the run (SU2 holds linear cells only).
    pub fn wrote_mesh(&mut self, path: &Path, format: mesh_io::Format, order: u8) {
        let written = match format {
            mesh_io::Format::Su2 => 1,
            _ => order,
        };
        if written != order {
            self.notes.push(format!(
                "{} holds the linear mesh (order 1, straight edges): SU2 reads linear cells only \
                 (the order-{order} curved mesh goes to .msh and .vtu outputs)",
                path.display()
            ));
        }
        let format = match format {
            mesh_io::Format::Msh => "msh",
            mesh_io::Format::Vtu => "vtu",
            mesh_io::Format::Su2 => "su2",
        };
        self.meshes.push(WrittenMesh {
            file: path.display().to_string(),
            format,
            order: written,
        });
    }

    /// Certifies every cell (Bernstein coefficients of the Jacobian determinant), fills the
    /// validity figures and the area integrated over the curved cells, and names every
    /// invalid or undecided cell as a problem. Returns the scaled Jacobian of each cell.
    ///
    /// It runs after structural problems too (a cell counted negative by its corners, a
    /// non-conforming edge), so that they never hide real inversions; only a mesh whose
    /// structure it cannot read (a node out of range, a non-finite coordinate) is left
    /// uncertified, and that is then one more problem rather than an error.
    pub fn certify(&mut self, mesh: &Mesh) -> Result<Vec<f64>> {
        if mesh.cells.is_empty() {
            return Ok(Vec::new());
        }
        let broken = !self.problems.is_empty();
        let v = match jacobian_check::check_mesh(mesh, &jacobian_check::CertifyParams::default()) {
            Ok(v) => v,
            Err(e) if broken => {
                self.problems
                    .push(format!("the certified Jacobian check could not run: {e}"));
                return Ok(Vec::new());
            }
            Err(e) => bail!("certifying the mesh: {e}"),
        };
        let q = self.quality.get_or_insert_with(Quality::default);
        q.min_scaled_jacobian = Some(v.min_scaled_jacobian);
        q.scaled_jacobian_of = Some(SCALED_JACOBIAN_OF);
        q.worst_cell = worst(mesh, &v.per_cell_scaled_jacobian);
        let gmsh = gmsh_min_sj(mesh, &v.per_cell_min_det);
        q.min_sj_gmsh = worst(mesh, &gmsh);
        q.min_sj_gmsh_of = Some(MIN_SJ_GMSH_OF);
        q.invalid_cells = Some(v.invalid_cells.len());
        q.certified = Some(v.undecided.is_empty() && v.uncertified.is_empty());
        for (what, cells) in [("invalid", &v.invalid_cells), ("undecided", &v.undecided)] {
            if !cells.is_empty() {
                let first: Vec<String> = cells.iter().take(5).map(ToString::to_string).collect();
                let [x, y] = centroid(mesh, cells[0]);
                self.problems.push(format!(
                    "{} cells {what} by the certified Jacobian check (first: {}; cell {} near ({x:.6e}, {y:.6e}))",
                    cells.len(),
                    first.join(", "),
                    cells[0]
                ));
            }
        }
        // the integral of det J over each cell from the coefficients its certificate rests
        // on: `jacobian_check::integrate_area` up to rounding, without integrating again
        self.area = Some(v.measure);
        Ok(v.per_cell_scaled_jacobian)
    }
}

/// Where the angle figures of a 2D run come from: the linear mesh under the final one, or
/// its figures computed earlier (so that the linear mesh need not be kept; sound by then).
#[derive(Debug, Clone, Copy)]
pub enum LinearAngles<'a> {
    /// Computed from this mesh, when the final mesh is structurally sound.
    Of(&'a Mesh),
    /// Already computed, in `seconds`.
    Given {
        /// The figures.
        angles: afsf2d::AngleStats,
        /// What computing them took.
        seconds: f64,
    },
}

/// How a P2 or P3 3D mesh is judged, as the notes of `mesh` and `quality` say.
pub const P2_VALIDITY: &str = "validity: every cell certified by the Bernstein Jacobian check; \
    volume: the curved cells' (integrated) against the volume the curved boundary encloses";

/// How a linear 3D mesh is judged, as the notes of `mesh` and `quality` say.
pub const P1_VALIDITY: &str = "linear cells: validity is every corner Jacobian positive by the \
    exact orient3d (mesh_model::validate)";

/// What `min_scaled_jacobian` is.
pub const SCALED_JACOBIAN_OF: &str = "the mesh as written (its order): per cell, the certified \
    lower bound of min det J / max det J over the cell (Bernstein coefficients of det J after \
    subdivision), then the least over the cells; 1 for a straight-sided triangle or \
    parallelogram";

/// What `min_sj_gmsh` is.
pub const MIN_SJ_GMSH_OF: &str = "Gmsh's minSJ (gmsh.model.mesh.getElementQualities(.., \
    \"minSJ\"), Gmsh 4.15): per cell, min det J over the cell (here its certified lower \
    bound) / det J of the straight-sided cell through its corners at the reference centre; \
    1 for a straight-sided triangle or parallelogram, above 1 possible for a curved cell";

/// The cell of least `value` (not NaN), with where it is.
fn worst(mesh: &Mesh, value: &[f64]) -> Option<WorstCell> {
    let (cell, &v) = value
        .iter()
        .enumerate()
        .filter(|(_, v)| !v.is_nan())
        .min_by(|a, b| a.1.total_cmp(b.1))?;
    let [x, y] = centroid(mesh, cell);
    Some(WorstCell {
        value: v,
        cell,
        x,
        y,
    })
}

/// Gmsh's `minSJ` of every cell ([`MIN_SJ_GMSH_OF`]) from the certified lower bound of its
/// det J (`min_det`, NaN for a cell not certified valid, from the certification that already
/// ran); NaN for a cell that is not certified valid.
fn gmsh_min_sj(mesh: &Mesh, min_det: &[f64]) -> Vec<f64> {
    use jacobian_check::jacobian;
    use mesh_model::CellType;
    use rayon::prelude::*;
    min_det
        .par_iter()
        .with_min_len(1024)
        .enumerate()
        .map(|(i, &min_det)| {
            if min_det.is_nan() {
                return f64::NAN;
            }
            let c = mesh.cells.get(i);
            // the corners on the stack (no allocation per cell)
            let mut corners = [[0.0; 2]; 4];
            let k = c.corners();
            for (x, &v) in corners.iter_mut().zip(k) {
                *x = mesh.xy(v);
            }
            let centre = match c.ty.shape {
                Shape::Quad => [0.0, 0.0],
                _ => [1.0 / 3.0, 1.0 / 3.0],
            };
            match jacobian(
                CellType::new(c.ty.shape, 1),
                &corners[..k.len().min(4)],
                centre,
            ) {
                Ok(j) if j.det > 0.0 => min_det / j.det,
                _ => f64::NAN,
            }
        })
        .collect()
}

/// The mean of a cell's corners, to say where a named cell is.
fn centroid(mesh: &Mesh, cell: usize) -> [f64; 2] {
    let c = mesh.cells.get(cell);
    let k = c.corners();
    let n = k.len() as f64;
    let sum = k.iter().fold([0.0, 0.0], |s, &v| {
        let x = mesh.xy(v);
        [s[0] + x[0], s[1] + x[1]]
    });
    [sum[0] / n, sum[1] / n]
}

/// What the angle figures are about.
pub const ANGLES_OF: &str =
    "the linear mesh (cell corners), quads cut along the shorter diagonal, at any order";

/// A mesh file written by the run.
#[derive(Debug, Clone, Serialize)]
pub struct WrittenMesh {
    /// The path as given.
    pub file: String,
    /// `msh`, `vtu` or `su2`.
    pub format: &'static str,
    /// The order of the cells in this file.
    pub order: u8,
}

/// The quality block of the report.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Quality {
    /// Largest interior angle of any triangle (quads cut on the shorter diagonal), degrees.
    pub max_angle_deg: f64,
    /// Triangles by largest angle in \[95,105), \[105,115), \[115,125), \[125,135), \[135,180\].
    pub obtuse_hist: [usize; 5],
    /// Which mesh `max_angle_deg` and `obtuse_hist` are about ([`ANGLES_OF`]).
    pub angles_of: &'static str,
    /// Least scaled Jacobian (min J / max J) over the cells: certified lower bounds for the
    /// cells proved valid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_scaled_jacobian: Option<f64>,
    /// Which mesh and which measure `min_scaled_jacobian` is ([`SCALED_JACOBIAN_OF`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scaled_jacobian_of: Option<&'static str>,
    /// The cell of least scaled Jacobian (`min_scaled_jacobian`): index and corner mean.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_cell: Option<WorstCell>,
    /// Gmsh's minSJ of the same mesh, least over the cells, and its cell ([`MIN_SJ_GMSH_OF`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_sj_gmsh: Option<WorstCell>,
    /// What `min_sj_gmsh` is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_sj_gmsh_of: Option<&'static str>,
    /// Cells whose Jacobian determinant is not positive everywhere (certified check).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub invalid_cells: Option<usize>,
    /// False only if some cell could be neither proved valid nor proved invalid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub certified: Option<bool>,
}

/// The largest relative difference allowed between the sum of the cell volumes and the volume
/// between the wall and the final front.
pub const VOLUME_TOLERANCE: f64 = 1e-9;

/// The quality block of a 3D report.
#[derive(Debug, Clone, Serialize)]
pub struct Quality3d {
    /// The largest dihedral angle of any tetrahedron, degrees (0 without tetrahedra).
    pub max_dihedral_deg: f64,
    /// The smallest cell volume (from the corners, faces fanned from their centroid).
    pub min_cell_volume: f64,
    /// The dissertation's tables 5, 6 and 7.
    pub histograms: Vec<crate::pipeline3d::Histogram>,
    /// The prisms' and hexahedra's smallest corner scaled Jacobian (absent without any).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_corner_scaled_jacobian: Option<crate::pipeline3d::CornerJacobian>,
    /// Order 2: the certified check, its keys those of the 2D quality block.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub validity: Option<Validity3d>,
}

/// The certified check of a P2 or P3 3D mesh, as the 2D quality block gives it.
#[derive(Debug, Clone, Serialize)]
pub struct Validity3d {
    /// The least certified scaled Jacobian over the cells ([`SCALED_JACOBIAN_OF`]).
    pub min_scaled_jacobian: f64,
    /// What `min_scaled_jacobian` is.
    pub scaled_jacobian_of: &'static str,
    /// Cells whose Jacobian determinant is not positive everywhere (certified).
    pub invalid_cells: usize,
    /// False only when some cell could not be decided.
    pub certified: bool,
}

/// The volume check of a 3D report.
#[derive(Debug, Clone, Serialize)]
pub struct VolumeCheck {
    /// The volume the final front encloses minus the wall's: the divergence theorem over the
    /// mesh's boundary facets (`farfield` and `wall`), independent of the cells.
    pub between_wall_and_front: f64,
    /// |sum of cell volumes − that| / that.
    pub relative_difference: f64,
    /// Above this the run fails validation.
    pub tolerance: f64,
}

/// A cell named by a quality figure.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct WorstCell {
    /// The figure's value there.
    pub value: f64,
    /// Cell index (0-based, the order of the cells in the files; `.msh` element tag − 1).
    pub cell: usize,
    /// Mean of the cell's corners, x.
    pub x: f64,
    /// Mean of the cell's corners, y.
    pub y: f64,
}

/// The inputs of a run, as it used them (the report's `inputs`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Inputs {
    /// The first layer's height (given, or from y⁺ and Re).
    pub first_height: f64,
    /// The ratio of one layer's height to the one below.
    pub growth: f64,
    /// The most layers grown from a boundary (3D: the layers grown).
    pub max_layers: u32,
    /// The placement's inputs, where given.
    #[serde(flatten)]
    pub placement: crate::placement::Placement,
}

/// One boundary loop in the report.
#[derive(Debug, Clone, Serialize)]
pub struct LoopReport {
    /// The loop's name.
    pub name: String,
    /// `wall` or `farfield`.
    pub role: &'static str,
    /// Boundary mesh nodes on the loop.
    pub nodes: usize,
    /// Sharp corners kept as nodes.
    pub corners: usize,
    /// Shortest and longest boundary segment.
    pub spacing_min: f64,
    /// Longest boundary segment.
    pub spacing_max: f64,
}
