//! `curvemesh._curvemesh`: the native half of the Python package `curvemesh`. It binds the
//! `curvemesh` library and nothing else — cases loaded, meshed, moved with sensitivities,
//! checked and written — and hands the results over as NumPy arrays and JSON text; the
//! pure-Python half (`python/curvemesh/__init__.py`) makes the public API of them.
//!
//! Every run releases the GIL and runs in a rayon pool entered by the calling thread, as the
//! command line does; a library error becomes `ValueError` (bad input), `FileNotFoundError`,
//! `OSError` or `KeyboardInterrupt` by its kind, with the library's one-line message; a panic
//! is caught and raised as `RuntimeError`, never unwinding into Python.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use curvemesh::airfoil::{self, AirfoilOptions};
use curvemesh::movement::{MoveOptions, Mover, Prepared, RbfKernel, motion};
use curvemesh::{AnyCase, Case, ErrorKind, Observer, Options, Snapshot};
use mesh_model::{CellType, Cells, Mesh, Shape};
use numpy::ndarray::{Array2, Array3};
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::{
    PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// A library error as the Python exception of its kind, with its one-line message.
fn py_error(e: curvemesh::Error) -> PyErr {
    let message = e.message().to_string();
    match e.kind() {
        ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        ErrorKind::Io => PyOSError::new_err(message),
        ErrorKind::Interrupted => PyKeyboardInterrupt::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

/// What a panic carried, as text.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_string()
    }
}

/// Runs `work` without the GIL, in a pool of `threads` threads (`None`: one per core, or
/// `RAYON_NUM_THREADS`) entered by this thread, a panic caught; `progress` is told of the
/// stages. An exception the progress callable raised is raised once the run is over.
fn run<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&mut dyn Observer) -> curvemesh::Result<T> + Send,
) -> PyResult<T> {
    let mut observer = Progress {
        callback: progress,
        error: None,
    };
    let outcome = py.detach(|| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start the threads: {e}")))?;
        let observer = &mut observer;
        catch_unwind(AssertUnwindSafe(|| pool.install(|| work(observer)))).map_err(|payload| {
            PyRuntimeError::new_err(format!(
                "internal error (a panic in curvemesh, please report it): {}",
                panic_text(payload.as_ref())
            ))
        })
    })?;
    if let Some(e) = observer.error {
        return Err(e);
    }
    outcome.map_err(py_error)
}

/// The observer of a run: tells the Python callable `progress(stage, done)` of each stage as
/// it begins (`done` false) and ends (`done` true); notes go to the `curvemesh` logger.
struct Progress {
    callback: Option<Py<PyAny>>,
    /// The first exception the callable raised (it is not called again after one).
    error: Option<PyErr>,
}

impl Progress {
    fn tell(&mut self, what: &str, done: bool) {
        if self.error.is_some() {
            return;
        }
        if let Some(callback) = &self.callback {
            Python::attach(|py| {
                if let Err(e) = callback.call1(py, (what, done)) {
                    self.error = Some(e);
                }
            });
        }
    }
}

impl Observer for Progress {
    fn stage_begun(&mut self, what: &str) {
        self.tell(what, false);
    }
    fn stage_ended(&mut self, what: &str, _seconds: f64) {
        self.tell(what, true);
    }
    fn note(&mut self, text: &str) {
        Python::attach(|py| {
            let logged = py
                .import("logging")
                .and_then(|logging| logging.call_method1("getLogger", ("curvemesh",)))
                .and_then(|logger| logger.call_method1("info", (text,)));
            if let Err(e) = logged {
                self.error.get_or_insert(e);
            }
        });
    }
}

/// A loaded case, 2D or 3D: what `mesh` and `move` take.
#[pyclass(frozen, module = "curvemesh._curvemesh")]
struct NativeCase {
    case: AnyCase,
}

#[pymethods]
impl NativeCase {
    /// The case's name.
    #[getter]
    fn name(&self) -> String {
        match &self.case {
            AnyCase::Two(c) => c.name.clone(),
            AnyCase::Three(c) => c.name.clone(),
        }
    }

    /// 2 or 3.
    #[getter]
    fn dimension(&self) -> u8 {
        match &self.case {
            AnyCase::Two(_) => 2,
            AnyCase::Three(_) => 3,
        }
    }

    /// The case's own order (`[curving] order`).
    #[getter]
    fn order(&self) -> u8 {
        match &self.case {
            AnyCase::Two(c) => c.order,
            AnyCase::Three(c) => c.order,
        }
    }

    /// The loops' names (2D; empty in 3D).
    #[getter]
    fn loops(&self) -> Vec<String> {
        match &self.case {
            AnyCase::Two(c) => c.loops.iter().map(|l| l.name.clone()).collect(),
            AnyCase::Three(_) => Vec::new(),
        }
    }
}

/// A built-in case or a case file (`.toml`).
#[pyfunction]
fn load(spec: &str) -> PyResult<NativeCase> {
    curvemesh::load(spec)
        .map(|case| NativeCase { case })
        .map_err(py_error)
}

/// A case from TOML text, its relative file names looked up in `dir`; `origin` names it in
/// messages, which then name no line (the text was made from a dict, not typed).
#[pyfunction]
fn parse_case(text: &str, origin: &str, dir: PathBuf) -> PyResult<NativeCase> {
    curvemesh::load::parse_str_in(text, origin, &dir)
        .map(|case| NativeCase { case })
        .map_err(|e| {
            let kind = e.kind();
            let message = without_line(e.message(), origin);
            py_error(match kind {
                ErrorKind::Input => curvemesh::Error::input(message),
                _ => e,
            })
        })
}

/// `message` without the line number after `origin` ("ORIGIN, line 4: x" → "ORIGIN: x").
fn without_line(message: &str, origin: &str) -> String {
    let Some(rest) = message
        .strip_prefix(origin)
        .and_then(|r| r.strip_prefix(", line "))
    else {
        return message.to_string();
    };
    match rest.split_once(": ") {
        Some((n, tail)) if n.bytes().all(|b| b.is_ascii_digit()) => format!("{origin}: {tail}"),
        _ => message.to_string(),
    }
}

/// Airfoil coordinate files (`.dat`, `.txt`) as a case, placed and layered as the command
/// line's airfoil flags say.
#[pyfunction]
#[pyo3(signature = (files, aoa=None, farfield=None, yplus=None, re=None, merge_walls=false,
                    first_height=None, growth=None, layers=None))]
#[allow(clippy::too_many_arguments)]
fn airfoil_case(
    files: Vec<String>,
    aoa: Option<f64>,
    farfield: Option<f64>,
    yplus: Option<f64>,
    re: Option<f64>,
    merge_walls: bool,
    first_height: Option<f64>,
    growth: Option<f64>,
    layers: Option<u32>,
) -> PyResult<NativeCase> {
    let options = AirfoilOptions {
        aoa,
        farfield,
        yplus,
        re,
        merge_walls,
        first_height,
        growth,
        layers,
    };
    airfoil::case(&files, &options)
        .map(|case| NativeCase {
            case: AnyCase::Two(case),
        })
        .map_err(py_error)
}

/// Whether `spec` names airfoil coordinates (`.dat`, `.txt`).
#[pyfunction]
fn is_coordinate_file(spec: &str) -> bool {
    airfoil::is_coordinate_file(spec)
}

/// The built-in cases' names.
#[pyfunction]
fn builtin_cases() -> Vec<(String, String)> {
    curvemesh::builtin::list()
        .map(|(name, about)| (name.to_string(), about.to_string()))
        .collect()
}

/// The sensitivities handed to Python: the design variables' names, and every node's
/// derivative by each, nodes × 2 × variables.
type Sensitivities<'py> = (Vec<String>, Bound<'py, PyArray3<f64>>);

/// A mesh with its report, and what it came from (to move it again).
#[pyclass(frozen, module = "curvemesh._curvemesh")]
struct NativeMesh {
    mesh: Mesh,
    report_json: String,
    valid: bool,
    /// 2D: each cell's certified least scaled Jacobian.
    scaled_jacobian: Vec<f64>,
    /// The 2D case it was meshed from (`None` for a mesh read from a file or a 3D case).
    case: Option<Case>,
    /// The stages of that run, where a move starts from.
    snapshot: Option<Snapshot>,
    /// Whether the quads were cut into triangles.
    triangles: bool,
    /// The sensitivities of a move: names and per node dX/dα.
    sensitivities: Option<Vec<(String, Vec<[f64; 2]>)>>,
}

impl NativeMesh {
    fn new(mesh: Mesh, report: &curvemesh::Report, scaled_jacobian: Vec<f64>) -> PyResult<Self> {
        let json = report.json().map_err(py_error)?;
        Ok(NativeMesh {
            mesh,
            report_json: String::from_utf8_lossy(&json).into_owned(),
            valid: report.is_valid(),
            scaled_jacobian,
            case: None,
            snapshot: None,
            triangles: false,
            sensitivities: None,
        })
    }
}

impl NativeMesh {
    /// `value` of each cell, the cells in the order of the blocks of `cells`.
    fn in_block_order<T>(&self, value: impl Fn(usize) -> T) -> Vec<T> {
        block_order(&self.mesh.cells, 0..self.mesh.cells.len())
            .into_iter()
            .flat_map(|(_, block)| block)
            .map(value)
            .collect()
    }
}

/// The name meshio (and this package) gives a cell type: Gmsh's element with its node count
/// (`triangle10`, `quad16`, `line3`, `tetra10`, `wedge18`, …), the linear ones bare.
fn element_name(ty: CellType) -> String {
    let base = match ty.shape {
        Shape::Line => "line",
        Shape::Tri => "triangle",
        Shape::Quad => "quad",
        Shape::Tet => "tetra",
        Shape::Pyramid => "pyramid",
        Shape::Prism => "wedge",
        Shape::Hex => "hexahedron",
    };
    if ty.order == 1 {
        base.to_string()
    } else {
        format!("{base}{}", ty.node_count())
    }
}

/// The cells `which` of `cells` grouped in blocks of one type, in the order each type first
/// appears, the cells of a block in their order in `which`: each block's type and cells.
fn block_order(cells: &Cells, which: impl Iterator<Item = usize>) -> Vec<(CellType, Vec<usize>)> {
    let mut order: Vec<(CellType, Vec<usize>)> = Vec::new();
    for i in which {
        let ty = cells.get(i).ty;
        match order.iter_mut().find(|(t, _)| *t == ty) {
            Some((_, block)) => block.push(i),
            None => order.push((ty, vec![i])),
        }
    }
    order
}

/// The cells `which` of `cells` in blocks of one type ([`block_order`]); each block as its
/// element name and its node indices (Gmsh's node order), an int64 array of one row per cell.
fn blocks<'py>(
    py: Python<'py>,
    cells: &Cells,
    which: impl Iterator<Item = usize>,
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for (ty, block) in block_order(cells, which) {
        let width = ty.node_count();
        let nodes: Vec<i64> = block
            .iter()
            .flat_map(|&i| cells.get(i).nodes.iter().map(|&n| i64::from(n)))
            .collect();
        let array = Array2::from_shape_vec((block.len(), width), nodes)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let block = PyTuple::new(
            py,
            [
                element_name(ty).into_pyobject(py)?.into_any(),
                PyArray2::from_owned_array(py, array).into_any(),
            ],
        )?;
        list.append(block)?;
    }
    Ok(list)
}

#[pymethods]
impl NativeMesh {
    /// 2 or 3.
    #[getter]
    fn dimension(&self) -> u8 {
        self.mesh.dim.as_u8()
    }

    /// The cells' order, 1 to 3.
    #[getter]
    fn order(&self) -> u8 {
        self.mesh.order
    }

    /// Whether the mesh passed validation (every cell certified, conforming, positive).
    #[getter]
    fn valid(&self) -> bool {
        self.valid
    }

    /// Whether the quads were cut into triangles.
    #[getter]
    fn triangles(&self) -> bool {
        self.triangles
    }

    /// The report as JSON text.
    #[getter]
    fn report_json(&self) -> &str {
        &self.report_json
    }

    /// Whether a move can start from this mesh (a 2D case's mesh made by `mesh`).
    #[getter]
    fn movable(&self) -> bool {
        self.case.is_some()
    }

    /// The nodes: N×2 in 2D, N×3 in 3D, float64.
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let d = usize::from(self.mesh.dim.as_u8());
        let flat: Vec<f64> = self
            .mesh
            .nodes
            .iter()
            .flat_map(|p| p[..d].iter().copied())
            .collect();
        let array = Array2::from_shape_vec((self.mesh.nodes.len(), d), flat)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(PyArray2::from_owned_array(py, array))
    }

    /// The domain cells as blocks `(element name, int64 array of node indices)`.
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        blocks(py, &self.mesh.cells, 0..self.mesh.cells.len())
    }

    /// The boundary groups (the physical groups of the `.msh`, the markers of the `.su2`),
    /// name → blocks of facets, in the groups' order.
    fn groups<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (groups, of_patch) =
            mesh_io::groups::boundary_groups(&self.mesh).map_err(PyValueError::new_err)?;
        let mut facets: Vec<Vec<usize>> = vec![Vec::new(); groups.len()];
        for (i, &patch) in self.mesh.boundary_patch.iter().enumerate() {
            if let Some(&g) = of_patch.get(patch as usize) {
                facets[g].push(i);
            }
        }
        let dict = PyDict::new(py);
        for (group, which) in groups.iter().zip(&facets) {
            dict.set_item(
                &group.name,
                blocks(py, &self.mesh.boundary, which.iter().copied())?,
            )?;
        }
        Ok(dict)
    }

    /// 2D: each cell's certified least scaled Jacobian, the cells in the order of the blocks
    /// of `cells` (empty in 3D).
    fn scaled_jacobian<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let values = &self.scaled_jacobian;
        if values.len() != self.mesh.cells.len() {
            return PyArray1::from_vec(py, Vec::new());
        }
        PyArray1::from_vec(py, self.in_block_order(|i| values[i]))
    }

    /// Each cell's layer counted from the boundary it grew from (0 touching it), -1 for none,
    /// the cells in the order of the blocks of `cells` (empty when unknown).
    fn cell_layer<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let layers = &self.mesh.cell_layer;
        if layers.len() != self.mesh.cells.len() {
            return PyArray1::from_vec(py, Vec::new());
        }
        PyArray1::from_vec(
            py,
            self.in_block_order(|i| match layers[i] {
                mesh_model::NONE => -1,
                l => i64::from(l),
            }),
        )
    }

    /// The sensitivities of a move, `(names, array nodes × 2 × variables)`, or `None`.
    fn sensitivities<'py>(&self, py: Python<'py>) -> PyResult<Option<Sensitivities<'py>>> {
        let Some(columns) = &self.sensitivities else {
            return Ok(None);
        };
        let (n, v) = (self.mesh.nodes.len(), columns.len());
        let mut array = Array3::<f64>::zeros((n, 2, v));
        for (j, (_, column)) in columns.iter().enumerate() {
            for (i, d) in column.iter().enumerate().take(n) {
                array[[i, 0, j]] = d[0];
                array[[i, 1, j]] = d[1];
            }
        }
        let names = columns.iter().map(|(name, _)| name.clone()).collect();
        Ok(Some((names, PyArray3::from_owned_array(py, array))))
    }

    /// Writes the mesh to `path` in the format of its extension (`.msh`, binary with
    /// `binary`; `.vtu`; `.su2`), or the report (`.json`); atomically.
    #[pyo3(signature = (path, binary=false))]
    fn write(&self, py: Python<'_>, path: PathBuf, binary: bool) -> PyResult<()> {
        py.detach(|| write_file(&path, &self.mesh, &self.report_json, binary))
            .map_err(py_error)
    }

    /// The mesh described and certified again, as a quality check of a file would (its report
    /// as JSON text).
    fn check(&self, py: Python<'_>, name: &str) -> PyResult<String> {
        let mesh = &self.mesh;
        let report = run(py, None, None, |_| {
            curvemesh::quality::check(mesh, name, name).map(|(r, _)| r)
        })?;
        report_text(&report)
    }
}

/// The report's JSON text.
fn report_text(report: &curvemesh::Report) -> PyResult<String> {
    let json = report.json().map_err(py_error)?;
    Ok(String::from_utf8_lossy(&json).into_owned())
}

/// [`NativeMesh::write`]'s work: one file, by its extension.
fn write_file(path: &Path, mesh: &Mesh, report: &str, binary: bool) -> curvemesh::Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let fail = |e: mesh_io::IoError| curvemesh::Error::from(e);
    match ext.as_deref() {
        Some("json") => {
            mesh_io::atomic::write_atomic(path, |out| {
                std::io::Write::write_all(out, report.as_bytes()).map_err(|source| {
                    mesh_io::IoError::Io {
                        path: path.to_path_buf(),
                        source,
                    }
                })
            })
            .map_err(fail)?;
        }
        Some("msh") if binary => {
            mesh_io::atomic::write_atomic(path, |out| {
                mesh_io::msh::write_binary_to(out, mesh, path)
            })
            .map_err(fail)?;
        }
        _ if binary => {
            return Err(curvemesh::Error::input(format!(
                "{}: binary applies to .msh files",
                path.display()
            )));
        }
        Some("msh" | "vtu" | "su2") => mesh_io::write(path, mesh).map_err(fail)?,
        _ => {
            return Err(curvemesh::Error::input(format!(
                "{}: give a .msh, .vtu, .su2 (the mesh) or .json (the report) file name",
                path.display()
            )));
        }
    }
    Ok(())
}

/// Meshes `case` (2D or 3D) and certifies every cell; a 2D run keeps its stages so that the
/// mesh can be moved later.
#[pyfunction]
#[pyo3(signature = (case, order=None, triangles=false, max_cells=None, threads=None, progress=None))]
fn mesh(
    py: Python<'_>,
    case: &Bound<'_, NativeCase>,
    order: Option<u8>,
    triangles: bool,
    max_cells: Option<u64>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<NativeMesh> {
    let case = &case.get().case;
    let two = matches!(case, AnyCase::Two(_));
    let options = Options {
        order,
        triangles,
        max_cells: max_cells.unwrap_or(Options::default().max_cells),
        snapshot: two,
    };
    let meshed = run(py, threads, progress, |observer| {
        curvemesh::mesh(case, &options, observer)
    })?;
    let mut out = NativeMesh::new(meshed.mesh, &meshed.report, meshed.scaled_jacobian)?;
    if let AnyCase::Two(c) = case {
        out.case = Some(c.clone());
        out.snapshot = meshed.snapshot;
    }
    out.triangles = triangles;
    Ok(out)
}

/// The case a move starts from and its options, from the arguments of `move_case` and
/// `prepare`: the 2D case (given, or the one `start` was meshed from), the stages kept with
/// `start`, and the options.
#[allow(clippy::too_many_arguments)]
fn move_setup(
    case: Option<&Bound<'_, NativeCase>>,
    start: Option<&Bound<'_, NativeMesh>>,
    order: Option<u8>,
    triangles: bool,
    (method, kernel, radius): (&str, &str, Option<f64>),
    smooth: bool,
    sensitivities: bool,
    max_cells: Option<u64>,
) -> PyResult<(Case, Option<Snapshot>, MoveOptions)> {
    let mover = match method {
        "springs" => Mover::Springs,
        "idw" => Mover::Idw,
        "rbf" => Mover::Rbf,
        other => {
            return Err(PyValueError::new_err(format!(
                "method={other:?}: give \"springs\", \"idw\" or \"rbf\""
            )));
        }
    };
    let kernel = match kernel {
        "wendland-c2" => RbfKernel::WendlandC2,
        "thin-plate" => RbfKernel::ThinPlate,
        other => {
            return Err(PyValueError::new_err(format!(
                "kernel={other:?}: give \"wendland-c2\" or \"thin-plate\""
            )));
        }
    };
    let start = start.map(Bound::get);
    let case: &Case = match (case.map(|c| &c.get().case), start) {
        (Some(AnyCase::Two(c)), _) => c,
        (Some(AnyCase::Three(c)), _) => {
            return Err(PyValueError::new_err(format!(
                "{}: a 3D case (dimension = 3): move takes 2D cases only",
                c.origin
            )));
        }
        (None, Some(NativeMesh { case: Some(c), .. })) => c,
        (None, _) => {
            return Err(PyValueError::new_err(
                "this mesh cannot be moved: give a 2D case, or a mesh made by curvemesh.mesh \
                 of one",
            ));
        }
    };
    let snapshot = start.and_then(|m| m.snapshot.clone());
    let options = MoveOptions {
        order,
        triangles,
        mover,
        kernel,
        radius,
        smooth,
        sensitivities,
        max_cells: max_cells.unwrap_or(MoveOptions::default().max_cells),
    };
    Ok((case.clone(), snapshot, options))
}

/// A moved mesh as the Python side takes it.
fn moved_mesh(moved: curvemesh::movement::Moved, triangles: bool) -> PyResult<NativeMesh> {
    let mut out = NativeMesh::new(moved.mesh, &moved.report, moved.scaled_jacobian)?;
    out.sensitivities = moved.sensitivities;
    out.triangles = triangles;
    Ok(out)
}

/// Moves a 2D case by the motions of a motion file's text (`[[motion]]` tables): from the
/// stages kept with `start` (a mesh of the case), else from the case meshed anew.
#[pyfunction]
#[pyo3(signature = (case, motions, start=None, order=None, triangles=false, method="springs",
                    kernel="wendland-c2", radius=None, smooth=false, sensitivities=false,
                    max_cells=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn move_case(
    py: Python<'_>,
    case: Option<&Bound<'_, NativeCase>>,
    motions: &str,
    start: Option<&Bound<'_, NativeMesh>>,
    order: Option<u8>,
    triangles: bool,
    method: &str,
    kernel: &str,
    radius: Option<f64>,
    smooth: bool,
    sensitivities: bool,
    max_cells: Option<u64>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<NativeMesh> {
    let (case, snapshot, options) = move_setup(
        case,
        start,
        order,
        triangles,
        (method, kernel, radius),
        smooth,
        sensitivities,
        max_cells,
    )?;
    let moved = run(py, threads, progress, |observer| {
        let motions = motion::parse_str(motions, "motions")?;
        let start = snapshot.map(|s| (s, "the mesh moved"));
        curvemesh::movement::move_case(&case, &motions, start, &options, observer)
    })?;
    moved_mesh(moved, triangles)
}

/// A 2D case prepared for many moves (`curvemesh::movement::Prepared`): its unmoved mesh,
/// the spring mover's field and Newton workspace made once.
#[pyclass(frozen, module = "curvemesh._curvemesh")]
struct NativePrepared {
    prepared: Prepared,
    triangles: bool,
}

#[pymethods]
impl NativePrepared {
    /// The case moved by the motions of a motion file's text, from the unmoved mesh.
    #[pyo3(signature = (motions, threads=None, progress=None))]
    fn move_by(
        &self,
        py: Python<'_>,
        motions: &str,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<NativeMesh> {
        let moved = run(py, threads, progress, |observer| {
            let motions = motion::parse_str(motions, "motions")?;
            self.prepared.move_by(&motions, observer)
        })?;
        moved_mesh(moved, self.triangles)
    }
}

/// A 2D case prepared for moves with the options of `move_case`: from the stages kept with
/// `start` (a mesh of the case), else from the case meshed anew.
#[pyfunction]
#[pyo3(signature = (case, start=None, order=None, triangles=false, method="springs",
                    kernel="wendland-c2", radius=None, smooth=false, sensitivities=false,
                    max_cells=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn prepare(
    py: Python<'_>,
    case: Option<&Bound<'_, NativeCase>>,
    start: Option<&Bound<'_, NativeMesh>>,
    order: Option<u8>,
    triangles: bool,
    method: &str,
    kernel: &str,
    radius: Option<f64>,
    smooth: bool,
    sensitivities: bool,
    max_cells: Option<u64>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<NativePrepared> {
    let (case, snapshot, options) = move_setup(
        case,
        start,
        order,
        triangles,
        (method, kernel, radius),
        smooth,
        sensitivities,
        max_cells,
    )?;
    let prepared = run(py, threads, progress, |observer| {
        let start = snapshot.map(|s| (s, "the mesh moved"));
        Prepared::new(&case, start, &options, observer)
    })?;
    Ok(NativePrepared {
        prepared,
        triangles,
    })
}

/// Reads a Gmsh `.msh` file (as `quality` does).
#[pyfunction]
fn read_msh(py: Python<'_>, path: PathBuf) -> PyResult<NativeMesh> {
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("mesh")
        .to_string();
    let origin = path.display().to_string();
    let (mesh, report, scaled_jacobian) = run(py, None, None, |_| {
        let mesh = mesh_io::read_msh(&path).map_err(|e| {
            curvemesh::Error::from(e).context(format!("reading {}", path.display()))
        })?;
        let (report, sj) = curvemesh::quality::check(&mesh, &name, &origin)?;
        Ok((mesh, report, sj))
    })?;
    NativeMesh::new(mesh, &report, scaled_jacobian)
}

/// TOML text of a JSON document (a dict made in Python): what the case and motion parsers
/// read.
#[pyfunction]
fn toml_of_json(json: &str) -> PyResult<String> {
    let value: serde_json::Value =
        serde_json::from_str(json).map_err(|e| PyValueError::new_err(e.to_string()))?;
    toml::to_string(&value).map_err(|e| PyValueError::new_err(format!("not TOML: {e}")))
}

/// Panics inside a run, for the tests: the panic must come out as `RuntimeError`.
#[pyfunction]
fn _test_panic(py: Python<'_>) -> PyResult<()> {
    run(py, Some(1), None, |_| -> curvemesh::Result<()> {
        panic!("a panic raised on purpose by curvemesh._curvemesh._test_panic")
    })
}

/// Whether this native module was built with debug assertions (a development build).
#[pyfunction]
fn debug_build() -> bool {
    cfg!(debug_assertions)
}

#[pymodule]
fn _curvemesh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeCase>()?;
    m.add_class::<NativeMesh>()?;
    m.add_class::<NativePrepared>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(parse_case, m)?)?;
    m.add_function(wrap_pyfunction!(airfoil_case, m)?)?;
    m.add_function(wrap_pyfunction!(is_coordinate_file, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_cases, m)?)?;
    m.add_function(wrap_pyfunction!(mesh, m)?)?;
    m.add_function(wrap_pyfunction!(move_case, m)?)?;
    m.add_function(wrap_pyfunction!(prepare, m)?)?;
    m.add_function(wrap_pyfunction!(read_msh, m)?)?;
    m.add_function(wrap_pyfunction!(toml_of_json, m)?)?;
    m.add_function(wrap_pyfunction!(debug_build, m)?)?;
    m.add_function(wrap_pyfunction!(_test_panic, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
