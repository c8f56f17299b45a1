#!/usr/bin/env python3
"""Writes Gmsh's shape functions of its 14-node pyramid (element type 14), or of its 30-node
pyramid (type 118) when given 118, and their gradients at 43 points of the reference pyramid, the
fixtures `jacobian-check` compares its own Bergot bases with
(crates/jacobian-check/tests/data/gmsh_pyramid14_basis.txt, gmsh_pyramid30_basis.txt).

Usage: python3 tests/python/pyramid14_basis.py [14|118] > FILE      (needs: pip install gmsh)
"""
import random
import sys

import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
etype = int(sys.argv[1]) if len(sys.argv) > 1 else 14
name, dim, order, nn, coord, npn = gmsh.model.mesh.getElementProperties(etype)
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
_, f, _ = gmsh.model.mesh.getBasisFunctions(etype, pts, "Lagrange")
_, g, _ = gmsh.model.mesh.getBasisFunctions(etype, pts, "GradLagrange")
for i in range(len(pts) // 3):
    row = list(pts[3 * i:3 * i + 3]) + [float(x) for x in f[i * nn:(i + 1) * nn]]
    row += [float(x) for x in g[i * 3 * nn:(i + 1) * 3 * nn]]
    print(" ".join(repr(x) for x in row))
gmsh.finalize()
