"""Cell-by-cell quality of a moved 2D mesh against the unmoved one, by four measures, as issue 43
asks: `lin` (each cell's corner scaled Jacobian of its straight corners: skew), `sj` (Gmsh's
minSJ of the curved cell: the Jacobian's variation and curving), `sicn` (Gmsh's minSICN: both)
and `edge` (the cell's shortest corner-to-corner edge: collapse). For each, the worst ratio
after / before over the cells (the moved and unmoved meshes have the same cells in the same
order) and where it is. `inverted` counts the cells whose det J is at most zero at a sampled
point: Gmsh's minSJ and minSICN are lower bounds, which can be negative on a valid but very thin
curved cell (`sampled_inverted`).

Usage: python measures.py BEFORE.msh AFTER.msh [LABEL]   (prints one JSON line)
"""

import json
import math
import sys

import gmsh
import numpy as np


def load(path):
    """Element types, tags, corner coordinates and Gmsh's minSJ and minSICN of a 2D .msh."""
    gmsh.clear()
    gmsh.open(path)
    tags_all, corners_all, sj_all, sicn_all = [], [], [], []
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = np.zeros((int(node_tags.max()) + 1, 3))
    xyz[node_tags.astype(int)] = coords.reshape(-1, 3)
    types, tags, nodes = gmsh.model.mesh.getElements(dim=2)
    for t, tg, nd in zip(types, tags, nodes):
        _, _, _, n_nodes, _, n_primary = gmsh.model.mesh.getElementProperties(t)
        conn = nd.astype(int).reshape(-1, n_nodes)[:, :n_primary]
        tags_all.append(tg)
        corners_all.extend(xyz[conn][:, :, :2])
        sj_all.append(gmsh.model.mesh.getElementQualities(tg, "minSJ"))
        sicn_all.append(gmsh.model.mesh.getElementQualities(tg, "minSICN"))
    return (
        np.concatenate(tags_all),
        corners_all,
        np.concatenate(sj_all),
        np.concatenate(sicn_all),
    )


def corner_sj(c):
    """The smallest corner scaled Jacobian of the straight polygon `c` (counter-clockwise)."""
    n = len(c)
    worst = math.inf
    for i in range(n):
        p, a, b = c[i], c[(i + 1) % n], c[(i - 1) % n]
        u, v = a - p, b - p
        cross = u[0] * v[1] - u[1] * v[0]
        worst = min(worst, cross / (np.linalg.norm(u) * np.linalg.norm(v)))
    if n == 3:
        worst *= 2.0 / math.sqrt(3.0)  # an equilateral triangle scores 1
    return worst


def shortest_edge(c):
    n = len(c)
    return min(np.linalg.norm(c[(i + 1) % n] - c[i]) for i in range(n))


def sampled_inverted(tag):
    """Whether the open model's element `tag` has det J <= 0 at one of 21 × 21 points of its
    reference cell. Gmsh's minSJ is a lower bound from the Jacobian's Bézier coefficients, and on
    a very thin curved cell it can be negative where det J is positive everywhere (two wall
    cells under the NACA0012's bumps, aspect ratio about 200, for every mover)."""
    u = np.linspace(0.0, 1.0, 21)
    etype = gmsh.model.mesh.getElement(tag)[0]
    if gmsh.model.mesh.getElementProperties(etype)[0].lower().startswith("quad"):
        pts = [(2 * a - 1, 2 * b - 1, 0.0) for a in u for b in u]
    else:
        pts = [(a, b, 0.0) for a in u for b in u if a + b <= 1.0]
    # Gmsh's determinant of a surface element is unsigned: the plane's own from the Jacobians
    jac = np.array(gmsh.model.mesh.getJacobian(tag, [c for p in pts for c in p])[0])
    j = jac.reshape(-1, 3, 3)
    return bool(np.min(j[:, 0, 0] * j[:, 1, 1] - j[:, 0, 1] * j[:, 1, 0]) <= 0.0)


def main():
    before, after = sys.argv[1], sys.argv[2]
    label = sys.argv[3] if len(sys.argv) > 3 else after
    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 1)
    tb, cb, sjb, sicnb = load(before)
    ta, ca, sja, sicna = load(after)
    inverted = sum(1 for tag, q in zip(ta, sja) if q <= 0 and sampled_inverted(int(tag)))
    gmsh.finalize()
    if len(tb) != len(ta):
        sys.exit(f"{before} and {after} do not have the same cells")
    lin = np.array([corner_sj(a) / corner_sj(b) for a, b in zip(ca, cb)])
    edge = np.array([shortest_edge(a) / shortest_edge(b) for a, b in zip(ca, cb)])
    out = {"label": label, "cells": len(tb)}
    for name, r, cells in [
        ("lin", lin, ca),
        ("sj", sja / sjb, ca),
        ("sicn", sicna / sicnb, ca),
        ("edge", edge, ca),
    ]:
        i = int(np.argmin(r))
        centre = cells[i].mean(axis=0)
        out[name] = round(float(r[i]), 4)
        out[name + "_at"] = [round(float(centre[0]), 4), round(float(centre[1]), 4)]
    out["inverted"] = inverted
    print(json.dumps(out))


if __name__ == "__main__":
    main()
