#!/usr/bin/env python3
"""Dump the reference-element node coordinates of Gmsh and of VTK as JSON, from the tools
themselves, so that mesh-io's node-order tables can be tested against them.

Usage: python3 tests/python/dump_reference_nodes.py > crates/mesh-io/tests/data/reference_nodes.json
Needs: pip install gmsh vtk

Gmsh: gmsh.model.mesh.getElementProperties(type) gives each node's reference coordinates;
for the 40-node prism (type 90), where it fails ("FaceClosureFull not implemented for prisms of
order 3"), Gmsh meshes the reference prism itself (one triangle extruded from z = -1 to 1) and
raises it to order 3 (setOrder), and its one element's nodes are read.
VTK: the Python wrapping does not expose GetParametricCoords, so each node's parametric
point is found on the lattice of spacing 1/order as the point where that node's interpolation
function is 1 (and all the others 0).
"""
import itertools
import json
import sys

import gmsh
import vtk

GMSH_TYPES = [1, 8, 26, 2, 9, 21, 3, 10, 36, 4, 11, 29, 5, 12, 92, 6, 13, 90, 7, 14, 118]

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


def gmsh_prism40():
    """The reference prism meshed by Gmsh as one element and raised to order 3: its nodes."""
    gmsh.model.add("prism40")
    geo = gmsh.model.geo
    pts = [geo.addPoint(x, y, -1.0) for x, y in ((0, 0), (1, 0), (0, 1))]
    lines = [geo.addLine(pts[i], pts[(i + 1) % 3]) for i in range(3)]
    for c in lines:
        geo.mesh.setTransfiniteCurve(c, 2)
    s = geo.addPlaneSurface([geo.addCurveLoop(lines)])
    geo.mesh.setTransfiniteSurface(s)
    geo.extrude([(2, s)], 0, 0, 2, [1], recombine=True)
    geo.synchronize()
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(3)
    types, _, nodes = gmsh.model.mesh.getElements(3)
    assert list(types) == [90] and len(nodes[0]) == 40, (types, nodes)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    at = {int(t): [float(v) for v in coords[3 * i:3 * i + 3]] for i, t in enumerate(tags)}
    pts = [at[int(n)] for n in nodes[0]]
    want = [[0, 0, -1], [1, 0, -1], [0, 1, -1], [0, 0, 1], [1, 0, 1], [0, 1, 1]]
    assert all(abs(a - b) < 1e-12 for p, q in zip(pts, want) for a, b in zip(p, q)), pts[:6]
    gmsh.model.remove()
    return {"type": 90, "name": "Prism 40", "dim": 3, "order": 3, "nodes": pts}


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    out = {"gmsh_version": gmsh.__version__, "vtk_version": vtk.vtkVersion.GetVTKVersion(),
           "gmsh": [], "vtk": []}
    for t in GMSH_TYPES:
        if t == 90:
            out["gmsh"].append(gmsh_prism40())
            continue
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
