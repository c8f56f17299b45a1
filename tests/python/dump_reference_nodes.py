#!/usr/bin/env python3
"""Dump the reference-element node coordinates of Gmsh and of VTK as JSON, from the tools
themselves, so that mesh-io's node-order tables can be tested against them.

Usage: python3 tests/python/dump_reference_nodes.py > crates/mesh-io/tests/data/reference_nodes.json
Needs: pip install gmsh vtk

Gmsh: gmsh.model.mesh.getElementProperties(type) gives each node's reference coordinates.
VTK: the Python wrapping does not expose GetParametricCoords, so each node's parametric
point is found on the lattice of spacing 1/order as the point where that node's interpolation
function is 1 (and all the others 0).
"""
import itertools
import json
import sys

import gmsh
import vtk

GMSH_TYPES = [1, 8, 26, 2, 9, 21, 3, 10, 36, 4, 11, 29, 5, 12, 92, 6, 13, 7, 14, 118]

# (VTK type id, class name, order, node count, lattice kind)
VTK_CELLS = [
    (5, "vtkTriangle", 1, 3, "tri"),
    (9, "vtkQuad", 1, 4, "quad"),
    (10, "vtkTetra", 1, 4, "tet"),
    (12, "vtkHexahedron", 1, 8, "hex"),
    (13, "vtkWedge", 1, 6, "wedge"),
    (14, "vtkPyramid", 1, 5, "pyramid"),
    (69, "vtkLagrangeTriangle", 2, 6, "tri"),
    (69, "vtkLagrangeTriangle", 3, 10, "tri"),
    (70, "vtkLagrangeQuadrilateral", 2, 9, "quad"),
    (70, "vtkLagrangeQuadrilateral", 3, 16, "quad"),
    (71, "vtkLagrangeTetra", 2, 10, "tet"),
    (71, "vtkLagrangeTetra", 3, 20, "tet"),
    (72, "vtkLagrangeHexahedron", 2, 27, "hex"),
    (72, "vtkLagrangeHexahedron", 3, 64, "hex"),
    (73, "vtkLagrangeWedge", 2, 18, "wedge"),
    (73, "vtkLagrangeWedge", 3, 40, "wedge"),
]


def lattice(kind, p):
    r = range(p + 1)
    if kind == "tri":
        return [(i / p, j / p, 0.0) for i, j in itertools.product(r, r) if i + j <= p]
    if kind == "quad":
        return [(i / p, j / p, 0.0) for i, j in itertools.product(r, r)]
    if kind == "tet":
        return [(i / p, j / p, k / p) for i, j, k in itertools.product(r, r, r) if i + j + k <= p]
    if kind == "hex":
        return [(i / p, j / p, k / p) for i, j, k in itertools.product(r, r, r)]
    if kind == "wedge":
        return [(i / p, j / p, k / p) for i, j, k in itertools.product(r, r, r) if i + j <= p]
    if kind == "pyramid":
        return [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1.0)]
    raise ValueError(kind)


def vtk_nodes(cls, p, n, kind):
    c = getattr(vtk, cls)()
    c.GetPointIds().SetNumberOfIds(n)
    c.GetPoints().SetNumberOfPoints(n)
    for i in range(n):
        c.GetPointIds().SetId(i, i)
        c.GetPoints().SetPoint(i, 0.0, 0.0, 0.0)
    if hasattr(c, "SetOrder"):
        # Quadrilaterals, hexahedra and wedges take their degrees explicitly.
        # (wedges also take the point count).
        c.SetOrder(*{"quad": [p, p], "hex": [p, p, p], "wedge": [p, p, p, n]}[kind])
    if hasattr(c, "Initialize"):
        c.Initialize()
    coords = [None] * n
    for pc in lattice(kind, p):
        w = [0.0] * n
        c.InterpolateFunctions(list(pc), w)
        hits = [k for k in range(n) if abs(w[k] - 1.0) < 1e-9]
        others = [k for k in range(n) if k not in hits and abs(w[k]) > 1e-9]
        if len(hits) == 1 and not others:
            coords[hits[0]] = list(pc)
    if any(x is None for x in coords):
        raise RuntimeError(f"{cls} P{p}: nodes not found on the lattice: {coords}")
    return coords


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    out = {"gmsh_version": gmsh.__version__, "vtk_version": vtk.vtkVersion.GetVTKVersion(),
           "gmsh": [], "vtk": []}
    for t in GMSH_TYPES:
        name, dim, order, n, coords, _ = gmsh.model.mesh.getElementProperties(t)
        pts = [list(coords[i * dim:(i + 1) * dim]) + [0.0] * (3 - dim) for i in range(n)]
        out["gmsh"].append({"type": t, "name": name, "dim": dim, "order": order, "nodes": pts})
    gmsh.finalize()
    for vtype, cls, p, n, kind in VTK_CELLS:
        out["vtk"].append({"type": vtype, "class": cls, "order": p,
                           "nodes": vtk_nodes(cls, p, n, kind)})
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
