#!/usr/bin/env python3
"""Independent check of .vtu files with VTK's own reader and VTK's own Lagrange cells.

Usage: python3 tests/python/check_vtu.py MESH.vtu...      (needs: pip install vtk)

Prints one JSON line per file: point and cell counts, cell counts per VTK type id, the point
counts of the cells of each type, the cell-data arrays, and two areas of a 2D mesh:
- "area": the integral of det J over every cell, with the Jacobian built from VTK's own shape
  function derivatives of each cell type (vtkLagrangeTriangle, vtkLagrangeQuadrilateral, ...)
  applied to the cell's points in the file's order: exact for the curved cells, so a node order
  that VTK reads differently from what we meant shows as a wrong area on curved cells;
- "min_scaled_jacobian": the least, over the cells, of min det J / max det J at those Gauss
  points: a node order VTK reads differently folds even a straight-sided cell, so it shows here
  as a value ≤ 0;
- "area_linearised": what VTK's own filter vtkIntegrateAttributes gives. VTK's filters
  (vtkIntegrateAttributes, vtkCellSizeFilter) cannot integrate Lagrange cells: they cut a
  curved cell into linear pieces through its points, so for P2/P3 cells this is only close to
  the true area (exact for linear cells). 3D meshes give "volume_linearised", and "volume" and
  "min_scaled_jacobian" as above from VTK's shape functions of the tetrahedra, wedges and
  hexahedra (linear and Lagrange) at 5 Gauss points per direction (exact to degree 9: every
  determinant of a cubic cell but the hexahedron's, degree 8 per direction, ... exact too), its
  pyramids (VTK's linear and quadratic pyramids) left out and counted in "pyramids_unmeasured".
The counts and measures are of the domain cells; the boundary facets the file also holds
(cell data `boundary_group` ≥ 0, an index into the group names, which the field data holds
as one numeric array `boundary_group:NAME` per group, holding the index) are counted per group
under "boundary_groups", named by VTK's own reading of those arrays.
A file VTK cannot read gives a line with an "error" key; the exit status is then 1.
"""
import collections
import json
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

GROUP_PREFIX = "boundary_group:"  # the field data naming a boundary group (mesh_io::vtu)
GAUSS_POINTS = 6  # per direction: exact for det J of cubic quads (degree 5 in each variable)


def quadrature(triangle):
    """Gauss points and weights on VTK's parametric cells: the unit square [0,1]², or the unit
    triangle by collapsing the square (Duffy), which stays exact for polynomials."""
    x, w = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    x, w = (x + 1) / 2, w / 2
    u, v = (a.ravel() for a in np.meshgrid(x, x, indexing="ij"))
    ww = np.outer(w, w).ravel()
    if triangle:
        return np.c_[u, v * (1 - u)], ww * (1 - u)
    return np.c_[u, v], ww


def quadrature_3d(kind):
    """Gauss points and weights on VTK's parametric 3D cells ([0,1]³, the unit simplex, the
    unit triangle × [0,1]), the simplex and the triangle collapsed from the cube (Duffy)."""
    x, w = np.polynomial.legendre.leggauss(5)
    x, w = (x + 1) / 2, w / 2
    u, v, t = (a.ravel() for a in np.meshgrid(x, x, x, indexing="ij"))
    ww = np.einsum("i,j,k->ijk", w, w, w).ravel()
    if kind == "tet":
        return np.c_[u, v * (1 - u), t * (1 - u) * (1 - v)], ww * (1 - u) ** 2 * (1 - v)
    if kind == "wedge":
        return np.c_[u, v * (1 - u), t], ww * (1 - u)
    return np.c_[u, v, t], ww


def shape_derivatives(cell, n, pcoords, dim=2):
    """dN/dr, dN/ds (and dN/dt in 3D) of a VTK cell with n points at each parametric point,
    shape (q, dim, n).

    VTK lays InterpolateDerivs out as all d/dr then all d/ds for some cell classes and
    interleaved per point for others (vtkLagrangeQuadrilateral); the layout is chosen by
    comparing with central differences of InterpolateFunctions, so neither is assumed."""
    def pad(p):
        return [float(p[k]) if k < dim else 0.0 for k in range(3)]

    def functions(p):
        f = [0.0] * n
        cell.InterpolateFunctions(pad(p), f)
        return np.asarray(f)

    def derivs(p):
        d = [0.0] * (dim * n)
        cell.InterpolateDerivs(pad(p), d)
        return np.asarray(d)

    probe, h = np.array([0.21, 0.17, 0.23][:dim]), 1e-6
    fd = np.array([(functions(probe + h * e) - functions(probe - h * e)) / (2 * h)
                   for e in np.eye(dim)])
    d = derivs(probe)
    layouts = [lambda a: a.reshape(dim, n), lambda a: a.reshape(n, dim).T]
    for layout in layouts:
        if np.allclose(layout(d), fd, rtol=1e-5, atol=1e-5 * np.abs(fd).max()):
            return np.array([layout(derivs(p)) for p in pcoords])
    raise RuntimeError(f"VTK cell {cell.GetClassName()}: derivatives match no known layout")


def lagrange_area(grid):
    """The integral of det J over the 2D cells of grid, with VTK's own shape functions, and the
    least ratio min det J / max det J of a cell at the quadrature points."""
    pts = vtk_to_numpy(grid.GetPoints().GetData())[:, :2]
    types = vtk_to_numpy(grid.GetCellTypes())
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    sizes = np.diff(offsets)
    total, min_ratio = 0.0, 1.0
    for t, n in sorted(set(zip(types.tolist(), sizes.tolist()))):
        ids = np.nonzero((types == t) & (sizes == n))[0]
        cell = grid.GetCell(int(ids[0]))
        pcoords, weights = quadrature(cell.GetNumberOfEdges() == 3)
        dn = shape_derivatives(cell, n, pcoords)  # (q, 2, n)
        x = pts[conn[offsets[ids][:, None] + np.arange(n)]]  # (cells, n, 2)
        jac = np.einsum("qan,cnb->cqab", dn, x)  # d(x, y)/d(r, s)
        det = jac[..., 0, 0] * jac[..., 1, 1] - jac[..., 0, 1] * jac[..., 1, 0]
        total += float((det @ weights).sum())
        min_ratio = min(min_ratio, float((det.min(axis=1) / np.abs(det).max(axis=1)).min()))
    return total, min_ratio


# VTK's 3D cell types measured by lagrange_volume, by the shape of their parametric domain
SOLIDS = {10: "tet", 71: "tet", 12: "hex", 72: "hex", 13: "wedge", 73: "wedge"}


def lagrange_volume(grid):
    """The integral of det J over the tetrahedra, wedges and hexahedra of grid with VTK's own
    shape functions, the least ratio min det J / max det J of one of them at the quadrature
    points, and the number of cells left out (pyramids)."""
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    types = vtk_to_numpy(grid.GetCellTypes())
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    sizes = np.diff(offsets)
    total, min_ratio, left = 0.0, 1.0, 0
    for t, n in sorted(set(zip(types.tolist(), sizes.tolist()))):
        ids = np.nonzero((types == t) & (sizes == n))[0]
        if t not in SOLIDS:
            left += len(ids)
            continue
        cell = grid.GetCell(int(ids[0]))
        pcoords, weights = quadrature_3d(SOLIDS[t])
        dn = shape_derivatives(cell, n, pcoords, 3)  # (q, 3, n)
        x = pts[conn[offsets[ids][:, None] + np.arange(n)]]  # (cells, n, 3)
        det = np.linalg.det(np.einsum("qan,cnb->cqba", dn, x))  # d(x, y, z)/d(r, s, t)
        total += float((det @ weights).sum())
        min_ratio = min(min_ratio, float((det.min(axis=1) / np.abs(det).max(axis=1)).min()))
    return total, min_ratio, left


def group_names(grid):
    """The boundary group names by index: the field-data arrays `boundary_group:NAME`, each
    one tuple holding the group's index, as VTK reads them."""
    fd = grid.GetFieldData()
    names = {}
    for i in range(fd.GetNumberOfArrays()):
        name, arr = fd.GetArrayName(i), fd.GetArray(i)
        if name and name.startswith(GROUP_PREFIX) and arr is not None:
            names[int(arr.GetTuple1(0))] = name[len(GROUP_PREFIX):]
    return names


def split_boundary(grid):
    """The domain cells of grid (boundary_group −1) as a grid of their own, and the number of
    boundary facets of each group, by name (group_names)."""
    arr = grid.GetCellData().GetArray("boundary_group")
    if arr is None:
        return grid, {}
    names = group_names(grid)
    group = vtk_to_numpy(arr)
    counts = collections.Counter(group[group >= 0].tolist())
    named = {names.get(int(k), f"unnamed {k}"): int(n) for k, n in sorted(counts.items())}
    ids = vtk.vtkIdList()
    for i in np.nonzero(group < 0)[0].tolist():
        ids.InsertNextId(i)
    extract = vtk.vtkExtractCells()
    extract.SetInputData(grid)
    extract.SetCellList(ids)
    extract.Update()
    return extract.GetOutput(), named


def read(path):
    """The summary of one file, as a dict (see the module doc)."""
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    errors = []
    reader.AddObserver("ErrorEvent", lambda obj, ev: errors.append(ev))
    reader.Update()
    grid = reader.GetOutput()
    if errors or grid is None or grid.GetNumberOfCells() == 0:
        return {"file": path, "error": "VTK could not read the file"}
    # the file's points, counted before the boundary facets are split off: the extraction
    # keeps only points some cell uses, and VTK's quadratic pyramid leaves out the base node
    # of a P2 pyramid (a node no other cell may use)
    points = grid.GetNumberOfPoints()
    grid, boundary_groups = split_boundary(grid)
    types = vtk_to_numpy(grid.GetCellTypes())
    sizes = np.diff(vtk_to_numpy(grid.GetCells().GetOffsetsArray()))
    points_per_cell = collections.defaultdict(set)
    for t, n in set(zip(types.tolist(), sizes.tolist())):
        points_per_cell[str(t)].add(n)
    dims = {grid.GetCell(int(i)).GetCellDimension()
            for i in np.unique(types, return_index=True)[1]}
    integrate = vtk.vtkIntegrateAttributes()
    integrate.SetInputData(grid)
    integrate.Update()
    measure = {}
    for name in ("Area", "Volume"):
        arr = integrate.GetOutput().GetCellData().GetArray(name)
        if arr is not None:
            measure[name.lower() + "_linearised"] = arr.GetValue(0)
    if dims == {2}:
        measure["area"], measure["min_scaled_jacobian"] = lagrange_area(grid)
    if dims == {3}:
        volume, ratio, left = lagrange_volume(grid)
        measure.update(volume=volume, min_scaled_jacobian=ratio, pyramids_unmeasured=left)
    cd = grid.GetCellData()
    return {"file": path, "points": points, "cells": grid.GetNumberOfCells(),
            "types": {str(k): int(v) for k, v in sorted(collections.Counter(types).items())},
            "points_per_cell": {k: sorted(v) for k, v in sorted(points_per_cell.items())},
            "cell_data": [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())],
            "boundary_groups": boundary_groups, **measure}


def main(paths):
    status = 0
    for path in paths:
        out = read(path)
        status |= "error" in out
        print(json.dumps(out), flush=True)
    return int(status)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1:]))
