#!/usr/bin/env python3
"""Draws how far the curved wall of a sphere's P2 and P3 meshes lies off the true unit sphere,
the figure of docs/3d.md's P3 section: each wall triangle (Gmsh's 6- or 10-node triangle, read
by Gmsh's own reader and evaluated with its own basis functions) sampled on a lattice of 15
points a side, the distance |r - 1| drawn as colour over the triangles round the north pole
(seen from above, x and y), one panel per file, one logarithmic scale.

Usage: python3 tests/python/p3_wall_figure.py P2.msh P3.msh OUT.png   (needs gmsh, matplotlib)
  e.g. curvemesh mesh sphere --order 2 --out p2.msh; curvemesh mesh sphere --order 3 --out p3.msh
"""
import sys

import gmsh
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

SIDE = 15  # lattice points per side of a wall triangle
CAP = 0.93  # the triangles drawn: every corner above z = CAP


def lattice():
    """The reference points (u, v) of the lattice and its small triangles."""
    ij = [(i, j) for j in range(SIDE) for i in range(SIDE - j)]
    index = {p: k for k, p in enumerate(ij)}
    tris = []
    for j in range(SIDE - 1):
        for i in range(SIDE - 1 - j):
            a, b, c = index[(i, j)], index[(i + 1, j)], index[(i, j + 1)]
            tris.append((a, b, c))
            if i + j < SIDE - 2:
                tris.append((b, index[(i + 1, j + 1)], c))
    return np.array(ij, dtype=float) / (SIDE - 1), tris


def wall_samples(path):
    """The sampled points of the wall triangles near the pole: (points (m, 3), triangles)."""
    gmsh.clear()
    gmsh.open(path)
    tag = next(t for d, t in gmsh.model.getPhysicalGroups(2)
               if gmsh.model.getPhysicalName(2, t) == "wall")
    tags, coords, _ = gmsh.model.mesh.getNodes()
    at = dict(zip(tags.tolist(), coords.reshape(-1, 3)))
    ref, small = lattice()
    uvw = np.c_[ref, np.zeros(len(ref))].ravel().tolist()
    points, tris = [], []
    for entity in gmsh.model.getEntitiesForPhysicalGroup(2, tag):
        types, _, nodes = gmsh.model.mesh.getElements(2, entity)
        for etype, enodes in zip(types, nodes):
            _, _, _, n, _, _ = gmsh.model.mesh.getElementProperties(etype)
            _, basis, _ = gmsh.model.mesh.getBasisFunctions(etype, uvw, "Lagrange")
            basis = np.asarray(basis).reshape(len(ref), n)
            for element in np.asarray(enodes).reshape(-1, n):
                x = np.array([at[int(t)] for t in element])
                if x[:3, 2].min() < CAP:
                    continue
                start = len(points)
                points.extend(basis @ x)
                tris.extend((start + a, start + b, start + c) for a, b, c in small)
    return np.array(points), tris


def main(p2, p3, out):
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    panels = [(f"P{k}", *wall_samples(path)) for k, path in ((2, p2), (3, p3))]
    gmsh.finalize()
    off = [np.abs(np.linalg.norm(p, axis=1) - 1.0) for _, p, _ in panels]
    low = max(min(o[o > 0].min() for o in off), 1e-9)
    norm = LogNorm(vmin=low, vmax=max(o.max() for o in off))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.6), constrained_layout=True)
    for ax, (name, p, tris), o in zip(axes, panels, off):
        t = Triangulation(p[:, 0], p[:, 1], tris)
        m = ax.tripcolor(t, np.maximum(o, low), norm=norm, shading="gouraud", cmap="viridis")
        ax.set_aspect("equal")
        ax.set_title(f"{name}: the wall at most {o.max():.1e} off the sphere")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.colorbar(m, ax=axes, label="|r - 1|, distance to the unit sphere")
    fig.savefig(out, dpi=110)
    print(" ".join(f"{name} {o.max():.3e}" for (name, _, _), o in zip(panels, off)))


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
