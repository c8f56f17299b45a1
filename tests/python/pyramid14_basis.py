#!/usr/bin/env python3
"""Writes Gmsh's shape functions of its 14-node pyramid (element type 14) and their gradients
at 43 points of the reference pyramid, the fixture `jacobian-check` compares its own Bergot basis
with (crates/jacobian-check/tests/data/gmsh_pyramid14_basis.txt).

Usage: python3 tests/python/pyramid14_basis.py > FILE      (needs: pip install gmsh)
"""
import random

import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
name, dim, order, nn, coord, npn = gmsh.model.mesh.getElementProperties(14)
print("#", name, dim, order, nn, npn)
print("# nodes", " ".join(str(float(c)) for c in coord))
random.seed(7)
pts = []
for _ in range(40):
    w = random.random() ** 2 * 0.999
    u = (2 * random.random() - 1) * (1 - w)
    v = (2 * random.random() - 1) * (1 - w)
    pts += [u, v, w]
pts += [0.3, -0.2, 0.0, 0.0, 0.0, 0.5, -0.5, 0.5, 0.5]
_, f, _ = gmsh.model.mesh.getBasisFunctions(14, pts, "Lagrange")
_, g, _ = gmsh.model.mesh.getBasisFunctions(14, pts, "GradLagrange")
for i in range(len(pts) // 3):
    row = list(pts[3 * i:3 * i + 3]) + [float(x) for x in f[i * 14:(i + 1) * 14]]
    row += [float(x) for x in g[i * 42:(i + 1) * 42]]
    print(" ".join(repr(x) for x in row))
gmsh.finalize()
