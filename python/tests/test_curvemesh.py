"""Tests of the Python package `curvemesh` (python/): meshes, groups, files read back by Gmsh and
meshio, dict cases, movement with sensitivities against the command line's CSV, errors, and the
user guide's Python examples. Run by python/test.sh, which builds the package into
.venv-python/ and sets CURVEMESH_CLI to the `curvemesh` binary of the same sources.
"""

import csv
import os
import re
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import curvemesh

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "user-guide.md"
FLAP_LE = [0.873554825783, 0.013674191199]  # the 30P30N flap's leading edge (fixtures/motions)
FLAP_MOVE = {"loop": "flap", "rotate_deg": 5.0, "about": FLAP_LE}


def cli():
    """The `curvemesh` binary built from the same sources (python/test.sh builds it)."""
    path = os.environ.get("CURVEMESH_CLI") or str(ROOT / "target" / "release" / "curvemesh")
    if not os.access(path, os.X_OK):
        pytest.fail(f"no curvemesh binary at {path}: run python/test.sh (or set CURVEMESH_CLI)")
    return path


def run_cli(*args, cwd):
    return subprocess.run([cli(), *map(str, args)], cwd=cwd, capture_output=True, text=True)


@pytest.fixture(scope="module")
def p3():
    """The 30P30N at P3, meshed once for the tests that read it."""
    return curvemesh.mesh("30p30n", order=3)


@pytest.fixture(scope="module")
def flap(p3):
    """The 30P30N's flap turned by 5 degrees about its leading edge, with sensitivities."""
    return curvemesh.move(p3, [FLAP_MOVE], sensitivities=True)


# --- the 30P30N at P3 -------------------------------------------------------------------------

def test_30p30n_p3_is_certified(p3):
    assert p3.valid
    assert p3.report["problems"] == []
    assert p3.report["case"] == "30p30n" and p3.report["order"] == 3
    assert p3.dimension == 2 and p3.order == 3
    assert p3.points.shape == (p3.report["nodes"], 2) and p3.points.dtype == np.float64
    names = [name for name, _ in p3.cells]
    assert set(names) <= {"quad16", "triangle10"} and "quad16" in names
    assert sum(len(c) for _, c in p3.cells) == len(p3.scaled_jacobian) == len(p3.cell_layer)
    for name, cells in p3.cells:
        assert cells.dtype == np.int64 and cells.shape[1] == {"quad16": 16, "triangle10": 10}[name]
        assert cells.min() >= 0 and cells.max() < len(p3.points)
    # every cell certified: its least scaled Jacobian is positive
    assert p3.scaled_jacobian.min() > 0


def test_30p30n_has_a_group_per_element(p3):
    assert list(p3.groups) == ["slat", "main", "flap", "farfield"]
    for name, blocks in p3.groups.items():
        assert [n for n, _ in blocks] == ["line4"], name
        facets = blocks[0][1]
        assert facets.shape[1] == 4 and len(facets) > 10
        # a closed loop: every corner node starts one facet and ends another
        assert sorted(facets[:, 0]) == sorted(facets[:, 1])
    # the report counts each group's facets
    assert p3.report["boundary_groups"] == {
        name: sum(len(f) for _, f in blocks) for name, blocks in p3.groups.items()}


def test_30p30n_msh_reads_back_in_gmsh(p3, tmp_path):
    gmsh = pytest.importorskip("gmsh")
    path = tmp_path / "30p30n.msh"
    p3.write(path)
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(path))
        tags, coords, _ = gmsh.model.mesh.getNodes()
        xyz = np.asarray(coords).reshape(-1, 3)[np.argsort(tags)]
        np.testing.assert_array_equal(xyz[:, :2], p3.points)
        assert np.all(xyz[:, 2] == 0)
        counts = {}
        for ty in gmsh.model.mesh.getElementTypes(dim=2):
            name, _, order, nodes, _, _ = gmsh.model.mesh.getElementProperties(ty)
            counts[(order, nodes)] = len(gmsh.model.mesh.getElementsByType(ty)[0])
        assert counts == {(3, len(c[0])): len(c) for _, c in p3.cells}
        groups = {gmsh.model.getPhysicalName(d, t): d for d, t in gmsh.model.getPhysicalGroups()}
        assert {n for n, d in groups.items() if d == 1} == set(p3.groups)
        # Gmsh's own minimum scaled Jacobian of every cell is positive
        for ty in gmsh.model.mesh.getElementTypes(dim=2):
            tags, _ = gmsh.model.mesh.getElementsByType(ty)
            sj = gmsh.model.mesh.getElementQualities(tags, "minSJ")
            assert min(sj) > 0
    finally:
        gmsh.finalize()


def test_30p30n_vtu_reads_back_in_meshio(p3, tmp_path):
    meshio = pytest.importorskip("meshio")
    path = tmp_path / "30p30n.vtu"
    p3.write(path)
    back = meshio.read(path)
    np.testing.assert_array_equal(back.points[:, :2], p3.points)
    # the .vtu keeps the mesh's own cell order, quads and triangles mixed: count by type
    counts = {}
    for block in back.cells:
        if block.dim == 2:
            counts[block.data.shape[1]] = counts.get(block.data.shape[1], 0) + len(block.data)
    assert counts == {c.shape[1]: len(c) for _, c in p3.cells}


def test_to_meshio_is_what_meshio_reads_from_the_msh(p3, tmp_path):
    meshio = pytest.importorskip("meshio")
    path = tmp_path / "30p30n.msh"
    p3.write(path)
    back = meshio.read(path)
    ours = p3.to_meshio()
    np.testing.assert_array_equal(ours.points[:, :2], back.points[:, :2])
    domain = {b.type: b.data for b in back.cells if b.dim == 2}
    for name, cells in p3.cells:
        np.testing.assert_array_equal(
            np.sort(cells, axis=0), np.sort(domain[name], axis=0))
    assert set(ours.cell_sets) == {"fluid", *p3.groups}
    for group, blocks in p3.groups.items():
        n = sum(len(s) for s in ours.cell_sets[group])
        assert n == sum(len(f) for _, f in blocks)


def test_quality_of_the_written_mesh(p3, tmp_path):
    path = tmp_path / "30p30n.msh"
    p3.write(path)
    report = curvemesh.quality(path)
    assert report["problems"] == [] and report["order"] == 3
    assert report["cells"] == p3.report["cells"]
    again = curvemesh.quality(p3)
    assert again["problems"] == [] and again["cells"] == p3.report["cells"]
    back = curvemesh.read(path)
    np.testing.assert_array_equal(back.points, p3.points)
    assert back.valid and list(back.groups) == list(p3.groups)


def test_every_format_is_written(p3, tmp_path):
    for name in ("a.msh", "a.vtu", "a.su2", "a.json"):
        p3.write(tmp_path / name)
        assert (tmp_path / name).stat().st_size > 0
    p3.write(tmp_path / "b.msh", binary=True)
    assert curvemesh.read(tmp_path / "b.msh").valid
    with pytest.raises(ValueError, match="give a .msh"):
        p3.write(tmp_path / "a.xyz")
    assert not (tmp_path / "a.xyz").exists()


def test_python_takes_about_the_cli_time(tmp_path):
    """The overhead of Python (the arrays are made on first use): the best of two runs each,
    the mesh written to .msh both ways."""
    def python_run():
        t = time.perf_counter()
        curvemesh.mesh("30p30n", order=3).write(tmp_path / "py.msh")
        return time.perf_counter() - t

    def cli_run():
        t = time.perf_counter()
        r = run_cli("mesh", "30p30n", "--order", "3", "--out", "cli.msh", "--quiet", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        return time.perf_counter() - t

    py = min(python_run() for _ in range(2))
    cl = min(cli_run() for _ in range(2))
    print(f"\n30P30N P3 meshed and written: Python {py:.3f} s, command line {cl:.3f} s")
    if curvemesh._curvemesh.debug_build():
        pytest.skip("a debug build of the extension")
    assert py < 1.5 * cl + 0.2


# --- cases -------------------------------------------------------------------------------------

NACA_DICT = {
    "name": "dict-naca",
    "loop": [
        {"role": "wall", "name": "wing", "naca": "0012"},
        {"role": "farfield", "circle": {"center": [0.5, 0.0], "radius": 20.0}},
    ],
    "layers": {"first_height": 1e-4, "growth": 1.3},
    "curving": {"order": 2},
}


def test_a_dict_case():
    mesh = curvemesh.mesh(NACA_DICT)
    assert mesh.valid and mesh.order == 2
    assert mesh.report["case"] == "dict-naca"
    assert list(mesh.groups) == ["wing", "farfield"]
    assert [n for n, _ in mesh.groups["wing"]] == ["line3"]
    # the same case as a file meshes the same
    case = curvemesh.load(NACA_DICT)
    assert case.name == "dict-naca" and case.loops == ["wing", "farfield"] and case.order == 2


def test_a_dict_case_reads_files_relative_to_the_current_folder(monkeypatch):
    monkeypatch.chdir(ROOT / "fixtures" / "geometry")
    case = {"loop": [{"role": "wall", "file": "naca0012.dat"},
                     {"role": "farfield", "circle": {"center": [0.5, 0.0], "radius": 20.0}}]}
    mesh = curvemesh.mesh(case, order=1)
    assert mesh.valid and mesh.report["case"] == "case" and "naca0012" in mesh.groups


def test_airfoil_coordinates_with_the_airfoil_options():
    dat = ROOT / "fixtures" / "geometry" / "naca0012.dat"
    mesh = curvemesh.mesh(dat, order=1, aoa=4, yplus=1, re=6e6)
    assert mesh.valid and list(mesh.groups) == ["naca0012", "farfield"]
    inputs = mesh.report["inputs"]
    assert (inputs["aoa_deg"], inputs["yplus"], inputs["re"]) == (4.0, 1.0, 6e6)


def test_a_3d_case_and_an_stl_surface(tmp_path):
    sphere = curvemesh.mesh("sphere", order=1)
    assert sphere.valid and sphere.dimension == 3 and sphere.points.shape[1] == 3
    assert list(sphere.groups) == ["wall", "outer"]
    assert len(sphere.scaled_jacobian) == 0
    # its wall, turned to face out of the body, as an STL file: the same surface meshed again
    wall = sphere.groups["wall"][0][1][:, ::-1]
    stl = tmp_path / "ball.stl"
    with open(stl, "w") as f:
        f.write("solid ball\n")
        for tri in wall:
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for p in sphere.points[tri]:
                f.write("   vertex %r %r %r\n" % tuple(float(x) for x in p))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid ball\n")
    ball = curvemesh.mesh(stl)
    assert ball.valid and ball.report["case"] == "ball"
    assert sum(len(c) for _, c in ball.cells) == sum(len(c) for _, c in sphere.cells)
    meshio = pytest.importorskip("meshio")
    assert isinstance(ball.to_meshio(), meshio.Mesh)


def test_progress_is_told_of_every_stage():
    seen = []
    mesh = curvemesh.mesh("naca0012", order=2, progress=lambda stage, done: seen.append((stage, done)))
    assert mesh.valid and seen
    begun = [s for s, done in seen if not done]
    ended = [s for s, done in seen if done]
    assert begun == ended and len(begun) >= 3

    def fail(stage, done):
        raise KeyError("stop here")
    with pytest.raises(KeyError, match="stop here"):
        curvemesh.mesh("naca0012", order=1, progress=fail)


def test_the_gil_is_released_while_meshing():
    ticks = 0
    worker = threading.Thread(target=lambda: curvemesh.mesh("30p30n", order=3, threads=1))
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    assert ticks > 20


# --- errors ------------------------------------------------------------------------------------

def test_a_bad_case_raises_value_error_with_the_cli_line(tmp_path):
    with pytest.raises(ValueError) as e:
        curvemesh.mesh("no-such-case")
    message = str(e.value)
    assert "\n" not in message and "neither a built-in case" in message
    r = run_cli("mesh", "no-such-case", cwd=tmp_path)
    assert r.returncode == 1 and r.stderr.strip() == f"error: {message}"

    bad = dict(NACA_DICT, layers={"growth": 0.9})
    with pytest.raises(ValueError) as e:
        curvemesh.mesh(bad)
    assert str(e.value) == "case dict: [layers] growth = 0.9: must be > 1"
    with pytest.raises(ValueError, match="unknown field `bogus`"):
        curvemesh.mesh(dict(NACA_DICT, bogus=1))
    with pytest.raises(ValueError, match="order 7"):
        curvemesh.mesh("naca0012", order=7)
    with pytest.raises(ValueError, match="aoa applies to airfoil coordinate files"):
        curvemesh.mesh("naca0012", aoa=4)
    with pytest.raises(TypeError):
        curvemesh.mesh("naca0012", bogus=4)


def test_a_missing_file_raises_file_not_found(tmp_path):
    for name in ("missing.toml", "missing.dat", "missing.stl"):
        with pytest.raises(FileNotFoundError) as e:
            curvemesh.mesh(tmp_path / name)
        assert "\n" not in str(e.value) and name in str(e.value)
    with pytest.raises(FileNotFoundError):
        curvemesh.quality(tmp_path / "missing.msh")


def test_a_panic_is_a_runtime_error():
    with pytest.raises(RuntimeError, match="internal error"):
        curvemesh._curvemesh._test_panic()


# --- movement ----------------------------------------------------------------------------------

def test_flap_move_sensitivities_are_the_cli_csv(p3, flap, tmp_path):
    assert flap.valid and flap.order == 3
    assert flap.design_variables == ["flap.rotate_deg", "flap.translate_x", "flap.translate_y",
                                     "flap.scale"]
    s = flap.sensitivities
    assert s.shape == (len(flap.points), 2, 4) and s.dtype == np.float64
    # same nodes and cells as the unmoved mesh
    assert flap.points.shape == p3.points.shape
    for (a, x), (b, y) in zip(p3.cells, flap.cells):
        assert a == b and np.array_equal(x, y)
    r = run_cli("move", "30p30n", "--loop", "flap", "--rotate", "5",
                "--about", ",".join(map(repr, FLAP_LE)), "--order", "3",
                "--out", "moved.msh", "--sensitivities", "moved.csv", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    with open(tmp_path / "moved.csv") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    table = np.array(rows[1:], dtype=np.float64)
    assert header[:3] == ["node", "x", "y"] and len(table) == len(flap.points)
    # the same numbers (the CSV's are shortest round-trip): equal but for the order of parallel
    # sums, should a solver's threads ever change it
    np.testing.assert_allclose(table[:, 1:3], flap.points, rtol=0, atol=1e-13)
    for k, var in enumerate(flap.design_variables):
        for c, axis in enumerate("xy"):
            column = table[:, header.index(f"d_{var}_{axis}")]
            scale = np.abs(s[:, :, k]).max()
            np.testing.assert_allclose(column, s[:, c, k], rtol=0, atol=1e-12 * scale)


def test_the_transposed_product_is_the_forward_one(flap):
    rng = np.random.default_rng(44)
    s = flap.sensitivities
    v = rng.standard_normal(s.shape[:2])
    dalpha = rng.standard_normal(s.shape[2])
    forward = np.einsum("ijk,k->ij", s, dalpha)          # dX for a design step dalpha
    adjoint = flap.sensitivities_transposed(v)           # one number per design variable
    assert adjoint.shape == (len(flap.design_variables),)
    assert np.isclose(np.sum(v * forward), adjoint @ dalpha, rtol=1e-12, atol=0)
    with pytest.raises(ValueError):
        flap.sensitivities_transposed(v[:10])


def test_moving_a_mesh_is_moving_its_case():
    mesh = curvemesh.mesh("naca0012", order=2)
    motion = {"loop": "naca0012", "rotate_deg": 3.0, "about": [0.25, 0.0]}
    from_mesh = curvemesh.move(mesh, motion)
    from_case = curvemesh.move("naca0012", [motion], order=2)
    assert from_mesh.valid and from_case.valid
    np.testing.assert_array_equal(from_mesh.points, from_case.points)
    assert from_mesh.sensitivities is None and from_mesh.design_variables == []
    with pytest.raises(ValueError, match="no sensitivities"):
        from_mesh.sensitivities_transposed(np.zeros_like(from_mesh.points))
    with pytest.raises(ValueError, match="no-such-loop"):
        curvemesh.move(mesh, {"loop": "no-such-loop", "rotate_deg": 1.0})
    with pytest.raises(ValueError, match="2D"):
        curvemesh.move("sphere", {"loop": "wall", "rotate_deg": 1.0})


def test_a_prepared_case_moves_as_move_does():
    mesh = curvemesh.mesh("naca0012", order=2)
    prepared = curvemesh.prepare(mesh, sensitivities=True)
    with pytest.raises(ValueError, match="no-such-loop"):
        prepared.move({"loop": "no-such-loop", "rotate_deg": 1.0})
    for degrees in (4.0, -2.0, 4.0):
        motion = {"loop": "naca0012", "rotate_deg": degrees, "about": [0.25, 0.0]}
        again = prepared.move(motion)
        fresh = curvemesh.move(mesh, motion, sensitivities=True)
        assert again.valid and fresh.valid
        # the same balance, to the Newton solve's tolerance
        np.testing.assert_allclose(again.points, fresh.points, rtol=0, atol=1e-12)
        np.testing.assert_allclose(again.sensitivities, fresh.sensitivities, rtol=1e-8,
                                   atol=1e-9)
        assert again.design_variables == fresh.design_variables
        assert "naca0012.rotate_deg" in again.design_variables
    with pytest.raises(ValueError, match="2D"):
        curvemesh.prepare("sphere")


# --- the user guide ----------------------------------------------------------------------------

def guide_examples():
    """The ```python blocks of docs/user-guide.md."""
    text = GUIDE.read_text()
    return re.findall(r"^```python\n(.*?)^```$", text, flags=re.S | re.M)


def test_the_guide_has_python_examples():
    assert len(guide_examples()) >= 1


@pytest.mark.parametrize("index", range(len(guide_examples())))
def test_the_guide_python_example_runs(index, tmp_path):
    """Each example of the user guide's Python section runs as written, in a fresh folder that
    holds the repository's fixtures/ (as a clone's root does)."""
    code = guide_examples()[index]
    shutil.copytree(ROOT / "fixtures", tmp_path / "fixtures")
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                       text=True)
    assert r.returncode == 0, f"{r.stdout}\n{r.stderr}"
