#!/usr/bin/env python3
"""Compares curvemesh's far-field cases (several bodies, boundary layers, tetrahedra out to a far
field) with Gmsh's and Netgen's meshes of the same geometry and the same layer stack (the case
file's `[layers]`: first height, growth, number of layers), every mesh measured alike in Gmsh.

Cases (`fixtures/cases/NAME.toml`): two-spheres, two-cubes and wing-sphere by default (any 3D
case with a `[farfield]` works). The geometry is the case file's:

- Built-in spheres and cubes are rebuilt in the meshers' OpenCASCADE kernels (a sphere of the
  case's radius about its `translate`; a cube of its `size` with a corner at its `translate`),
  with the far field (the case's sphere or box). Their surface mesh size is the mean edge of
  curvemesh's wall triangles (read from a quick export, below; else the icosphere's or the
  cube grid's edge); the far field's is curvemesh's (a box: `max_size`, default a tenth of the
  extent; a sphere: the edge of the icosphere curvemesh makes for that size).
- Other surfaces (the wing) are curvemesh's own wall triangles: the case meshed without its
  `[farfield]` and with one layer (DIR/NAME-wall.msh), every boundary group but the near-body
  outer one taken as the wall (a wall triangle whose column stopped in that layer is outside
  that mesh: the hole it leaves is closed again). Gmsh takes them as discrete surfaces (joined by
  `createTopology`) beside the OCC far field; Netgen as a hand-made surface mesh (the far field's
  triangles Gmsh's mesh of the OCC shape), volume-meshed by `GenerateVolumeMesh`.

The meshers (each in a child process, `--timeout` seconds, default 600, one at a time; the
child, measuring included, killed with its descendants past `--timeout` + 300 s or, with
`--max-memory GB`, when they hold more than that resident; its peak resident memory goes to
DIR/NAME-MESHER.json):

- `ours`: `target/release/curvemesh mesh CASE --out DIR/NAME-ours.msh --report ...` (or the
  binary `--bin` names) on the case as it is; its time is the whole command's (writing
  included).
- `gmsh`: Gmsh's layers by `gmsh.model.geo.extrudeBoundaryLayer` (one prism per layer at the
  stack's cumulative heights; Gmsh's `BoundaryLayer` field is 2D only) from the walls' surface
  mesh, the extrusion's top surfaces and the far field bounding a volume tetrahedralised by
  `generate(3)`. Gmsh's extrusion does not stop where layers meet (between two bodies, or past
  the far field), so:
- `gmsh-cap`: the same with the stack cut to the layers that fit: none taller than the wall's
  mesh size (where curvemesh's layers turn isotropic) and the whole stack under 0.45 times the
  smallest gap between bodies (built-in bodies: exact; other surfaces: the least distance
  between the connected pieces of curvemesh's wall triangles). Run only when that cuts the
  stack.
- `netgen`: Netgen (`netgen-mesher`), `BoundaryLayerParameters(boundary="wall",
  thickness=the layer heights, domain="fluid")` given to `OCCGeometry.GenerateMesh` (or, for
  curvemesh's wall triangles, `Mesh.GenerateVolumeMesh`), maxh the far field's size.
- `netgen-limit`: the same with `limit_growth_vectors=True` (Netgen's option that shortens
  columns which would cross or invert: it keeps the number of layers, thinner where they
  would meet).
- `netgen-cap`: the stack cut as for `gmsh-cap`.

Netgen runs in this interpreter when `import netgen` works, else in /tmp/venv-netgen/bin/python
(`python3 -m venv /tmp/venv-netgen && /tmp/venv-netgen/bin/pip install netgen-mesher`), its
mesh handed back as NumPy arrays (DIR/NAME-MESHER.npz) and measured here. Netgen reports why
a mesh failed on its standard error: that line (kept in DIR/NAME-MESHER.log) is the failure.

Measures, every mesh read into Gmsh (its cells' primary nodes for the angles):
cells by type; the tetrahedra's largest dihedral angle, and how many exceed 150 and 160
degrees; Gmsh's `minSJ` over all 3D cells (`getElementQualities`), how many are <= 0 and the
least; the total volume (Gmsh's `volume` of each cell, summed) against the exact one (the far
field's volume less the bodies': a sphere's and cube's exact, other bodies' enclosed by their
triangles), as a relative difference; the wall's triangles (ours: the report's wall facets;
Gmsh, Netgen: the triangles of the wall surfaces); the stack's layers; the time; whether it
completed (a run that fails gets its message; one that completes with a volume more than 5 %
off the exact one is flagged: Gmsh's extrusion can run through the far field and still mesh).

Run from the repository root with `target/release/curvemesh` built
(`cargo build --release -p curvemesh-cli --bin curvemesh`):

    .venv-checkers/bin/python tests/surfaces/compare_farfield.py TABLE.md [NAME ...]
        [--timeout S] [--out DIR] [--meshers ours,gmsh,...] [--bin PATH] [--max-memory GB]

It prints a Markdown table (one row per case and mesher) and writes it to TABLE.md, each run's
figures in DIR/NAME-MESHER.json and the meshes in DIR/NAME-MESHER.msh (default DIR
/tmp/cmp-farfield).
"""
import argparse
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.path.join(ROOT, "target", "release", "curvemesh")
CASES = ["two-spheres", "two-cubes", "wing-sphere"]
MESHERS = ["ours", "gmsh", "gmsh-cap", "netgen", "netgen-limit", "netgen-cap"]
LABEL = {"ours": "curvemesh", "gmsh": "Gmsh extrudeBoundaryLayer",
         "gmsh-cap": "Gmsh extrudeBoundaryLayer, stack cut",
         "netgen": "Netgen boundary_layers", "netgen-limit": "Netgen, limit_growth_vectors",
         "netgen-cap": "Netgen boundary_layers, stack cut"}
FAMILY = {"Tetrahedron": "tet", "Prism": "prism", "Pyramid": "pyramid", "Hexahedron": "hex"}
BUILTIN_KEYS = {"builtin", "radius", "refinement", "size", "divisions", "triangles",
                "translate", "name"}
NEAR_BODY_OUTER = {"outer", "farfield", "fluid"}
# a completed mesh whose volume is further than this from the exact one is flagged
VOLUME_OFF = 0.05


# ---------------------------------------------------------------------------------------------
# the case


def case(name, out):
    """The case's geometry and stack: its path, the layer heights, the far field, the bodies
    (built-in spheres and cubes, else None: curvemesh's wall triangles stand for them), the
    wall and far-field mesh sizes, the exact volume, the smallest gap between bodies."""
    path = name if name.endswith(".toml") else os.path.join(ROOT, "fixtures", "cases",
                                                               name + ".toml")
    with open(path, "rb") as f:
        spec = tomllib.load(f)
    lay = spec["layers"]
    heights = [lay["first_height"] * lay["growth"] ** k for k in range(lay["max_layers"])]
    ff = spec["farfield"]
    if "sphere" in ff:
        c, r = ff["sphere"]["center"], float(ff["sphere"]["radius"])
        far = {"kind": "sphere", "center": c, "radius": r}
        far_volume = 4 / 3 * math.pi * r ** 3
        extent = 2 * r
    else:
        lo, hi = ff["box"]["min"], ff["box"]["max"]
        far = {"kind": "box", "min": lo, "max": hi}
        far_volume = math.prod(h - l for l, h in zip(lo, hi))
        extent = max(h - l for l, h in zip(lo, hi))
    max_size = ff.get("max_size", extent / 10)
    far_size = max_size
    if far["kind"] == "sphere":  # curvemesh's icosphere: refined until its edge <= max_size
        k = 0
        while 1.0515 * far["radius"] / 2 ** k > max_size and k < 8:
            k += 1
        far_size = 1.0515 * far["radius"] / 2 ** k
    surfaces = spec["surface"] if isinstance(spec["surface"], list) else [spec["surface"]]
    bodies = []
    for s in surfaces:
        if not set(s) <= BUILTIN_KEYS or s.get("builtin") not in ("sphere", "cube"):
            bodies = None
            break
        t = s.get("translate", [0.0, 0.0, 0.0])
        if s["builtin"] == "sphere":
            r = float(s.get("radius", 1.0))
            bodies.append({"kind": "sphere", "center": t, "radius": r,
                           "edge": 1.0515 * r / 2 ** s.get("refinement", 3),
                           "volume": 4 / 3 * math.pi * r ** 3})
        else:
            a = float(s.get("size", 1.0))
            bodies.append({"kind": "box", "min": t, "max": [v + a for v in t],
                           "edge": a / s.get("divisions", 8), "volume": a ** 3})
    gap = None
    if bodies:
        for i, a in enumerate(bodies):
            for b in bodies[i + 1:]:
                d = body_gap(a, b)
                gap = d if gap is None else min(gap, d)
    return {"name": os.path.basename(path)[:-5], "path": path, "heights": heights,
            "far": far, "far_volume": far_volume, "far_size": far_size, "bodies": bodies,
            "gap": gap, "wall": os.path.join(out, os.path.basename(path)[:-5] + "-wall.npz")}


def body_gap(a, b):
    """The distance between two built-in bodies (spheres: exact; boxes: exact; a sphere and a
    box: its centre's distance to the box less the radius)."""
    def box_dist(p, lo, hi):
        return math.sqrt(sum(max(l - x, 0, x - h) ** 2 for x, l, h in zip(p, lo, hi)))
    if a["kind"] == b["kind"] == "sphere":
        return math.dist(a["center"], b["center"]) - a["radius"] - b["radius"]
    if a["kind"] == b["kind"] == "box":
        return math.sqrt(sum(max(a["min"][d] - b["max"][d], b["min"][d] - a["max"][d], 0) ** 2
                             for d in range(3)))
    s, x = (a, b) if a["kind"] == "sphere" else (b, a)
    return box_dist(s["center"], x["min"], x["max"]) - s["radius"]


def cap(c):
    """The layers that fit: none taller than the wall's mesh size, the stack under 0.45 times
    the smallest gap between bodies (built-in bodies' exact one, else the wall triangles')."""
    size = wall_size(c)
    gap = c["gap"] if c["gap"] is not None else wall_gap(c)
    n = 0
    total = 0.0
    for h in c["heights"]:
        if h > size or (gap is not None and total + h > 0.45 * gap):
            break
        total += h
        n += 1
    return max(n, 1)


def wall_size(c):
    """The walls' mesh size: the mean edge of curvemesh's wall triangles, else the built-in
    bodies' (icosphere, cube grid) edge."""
    if os.path.exists(c["wall"]):
        import numpy as np
        return float(np.load(c["wall"])["mean_edge"])
    return min(b["edge"] for b in c["bodies"])


def wall_gap(c):
    """The smallest gap between bodies from curvemesh's wall triangles (saved by export_wall;
    None for one body or no export)."""
    if not os.path.exists(c["wall"]):
        return None
    import numpy as np
    w = np.load(c["wall"])
    if "gap" not in w or not np.isfinite(w["gap"]):
        return None
    return float(w["gap"])


def components(tri, n):
    """Each point's body: the connected pieces of the triangles (points sharing triangles)."""
    import numpy as np
    label = np.arange(n)
    while True:
        m = label[tri].min(axis=1)
        new = label.copy()
        for k in range(3):
            np.minimum.at(new, tri[:, k], m)
        new = new[new]  # pointer jumping
        if np.array_equal(new, label):
            break
        label = new
    return np.unique(label, return_inverse=True)[1]


def point_triangle_distance(p, a, b, c):
    """Distances from points p (n, 3) to triangles a, b, c (each (m, 3)): (n, m)."""
    import numpy as np
    p = p[:, None, :]
    nrm = np.cross(b - a, c - a)
    area2 = np.einsum("ij,ij->i", nrm, nrm)
    # the projection's barycentric coordinates: inside, the distance to the plane
    inside = np.ones((p.shape[0], len(a)), dtype=bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("nmj,mj->nm", np.cross(v - u, p - u), nrm) >= 0
    inside &= area2 > 0
    plane = np.abs(np.einsum("nmj,mj->nm", p - a, nrm)) / np.sqrt(np.where(area2 > 0, area2, 1))
    best = np.full(inside.shape, np.inf)
    for u, v in ((a, b), (b, c), (c, a)):
        e = v - u
        ee = np.einsum("ij,ij->i", e, e)
        t = np.clip(np.einsum("nmj,mj->nm", p - u, e) / np.where(ee > 0, ee, 1), 0, 1)
        best = np.minimum(best, np.linalg.norm(p - (u + t[..., None] * e), axis=2))
    return np.where(inside, plane, best)


def triangles_gap(pts, tri):
    """The smallest distance between two bodies of the triangles (their connected pieces): the
    least point-to-triangle distance between any two, over the pairs of points and triangles
    that can be that close (a triangle no further than the least point-to-point distance d0
    plus its longest edge from the other body's points, a point no further than d0 plus the
    longest edge of those triangles from their points). None for one body."""
    import numpy as np
    body = components(tri, len(pts))
    nb = body.max() + 1
    if nb < 2:
        return None
    x = pts[tri]
    edge = np.max([np.linalg.norm(x[:, i] - x[:, (i + 1) % 3], axis=1) for i in range(3)],
                  axis=0)
    tbody = body[tri[:, 0]]
    gap = np.inf
    for i in range(nb):
        for j in range(i + 1, nb):
            ia, ib = np.flatnonzero(body == i), np.flatnonzero(body == j)
            A, B = pts[ia], pts[ib]
            near = np.full(len(pts), np.inf)  # each point's distance to the other's points
            near_b = np.full(len(B), np.inf)
            bb = np.einsum("ij,ij->i", B, B)
            for k in range(0, len(A), 512):
                a = A[k:k + 512]
                d2 = np.einsum("ij,ij->i", a, a)[:, None] + bb[None, :] - 2 * a @ B.T
                d = np.sqrt(np.maximum(d2, 0))
                near[ia[k:k + 512]] = d.min(axis=1)
                near_b = np.minimum(near_b, d.min(axis=0))
            near[ib] = near_b
            d0 = near[ia].min()
            for src, dst in ((ia, j), (ib, i)):
                ids = np.flatnonzero((tbody == dst) & (near[tri].min(axis=1) <= d0 + edge))
                if not len(ids):
                    continue
                P = pts[src[near[src] <= d0 + edge[ids].max()]]
                step = max(1, 1_000_000 // len(ids))
                for k in range(0, len(P), step):
                    d = point_triangle_distance(P[k:k + step],
                                                *(pts[tri[ids, q]] for q in range(3)))
                    gap = min(gap, float(d.min()))
    return gap


def export_wall(c, timeout):
    """curvemesh's wall triangles: the case without its far field and with one layer, meshed;
    every boundary group but the near-body outer one is wall. Saved to c["wall"] (nodes,
    triangles facing the fluid, a group index per triangle, the mean edge, the enclosed
    volume, the smallest gap between bodies: NaN for one body)."""
    import gmsh
    import numpy as np
    with open(c["path"]) as f:
        lines = f.read().splitlines()
    text, skip = [], False
    base = os.path.dirname(os.path.abspath(c["path"]))
    for line in lines:
        s = line.strip()
        if s.startswith("["):
            skip = s == "[farfield]"
        if skip:
            continue
        if s.startswith("max_layers"):
            line = "max_layers = 1"
        if s.startswith("file") and "=" in s:  # surface files relative to the case
            v = s.split("=", 1)[1].strip().strip('"')
            line = f'file = "{os.path.join(base, v)}"'
        text.append(line)
    out = os.path.dirname(c["wall"])
    toml = os.path.join(out, c["name"] + "-wall.toml")
    msh = os.path.join(out, c["name"] + "-wall.msh")
    with open(toml, "w") as f:
        f.write("\n".join(text) + "\n")
    p = subprocess.run([EXE, "mesh", toml, "--out", msh, "--report", msh[:-4] + ".json", "-q"],
                       capture_output=True, text=True, timeout=timeout)
    if not os.path.exists(msh):
        raise RuntimeError("exporting the wall: " + last_line(p.stderr, p.returncode))
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(msh)
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    tris, group = [], []
    for dim, tag in gmsh.model.getPhysicalGroups(2):
        if gmsh.model.getPhysicalName(dim, tag) in NEAR_BODY_OUTER:
            continue
        for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            for t, _, nodes in zip(*gmsh.model.mesh.getElements(2, e)):
                if t == 2:
                    tris.append(nodes.reshape(-1, 3))
                    group += [tag] * (len(nodes) // 3)
    gmsh.finalize()
    tri = np.concatenate(tris).astype(int)
    used, inv = np.unique(tri, return_inverse=True)
    pos = np.zeros((int(tags.max()) + 1, 3))
    pos[tags.astype(int)] = xyz.reshape(-1, 3)
    pts = pos[used]
    tri = inv.reshape(-1, 3)
    group = np.asarray(group)
    tri, group, holes = close_holes(tri, group)
    x = pts[tri]
    vol = np.einsum("ij,ij->i", x[:, 0], np.cross(x[:, 1], x[:, 2])).sum() / 6
    if vol < 0:  # the triangles facing into the bodies: turn them to face the fluid
        tri = tri[:, [0, 2, 1]]
    edges = np.concatenate([x[:, 1] - x[:, 0], x[:, 2] - x[:, 1], x[:, 0] - x[:, 2]])
    gap = triangles_gap(pts, tri)
    np.savez(c["wall"], points=pts, triangles=tri, group=group,
             mean_edge=float(np.linalg.norm(edges, axis=1).mean()), volume=abs(vol),
             gap=math.nan if gap is None else gap, holes_closed=holes)


def close_holes(tri, group):
    """The wall triangles closed where the export left holes (a wall triangle whose column
    stopped in the first layer is outside the near-body domain, so in no boundary group): each
    loop of open edges fanned into triangles turned as their neighbours, in the group most of
    its neighbours are in. Returns the triangles, their groups and how many were added."""
    import numpy as np
    from collections import Counter
    owner = {}
    for k, t in enumerate(tri):
        for i in range(3):
            owner[(int(t[i]), int(t[(i + 1) % 3]))] = k
    # the holes' edges run against their neighbours' open edges
    nxt = {}
    for (a, b), k in owner.items():
        if (b, a) not in owner:
            if b in nxt:  # a point on two holes (or an edge turned the wrong way): left
                return tri, group, 0
            nxt[b] = (a, k)
    new_tri, new_group = [], []
    while nxt:
        start = next(iter(nxt))
        loop, votes, v = [], Counter(), start
        while v in nxt:
            loop.append(v)
            v, k = nxt.pop(v)
            votes[int(group[k])] += 1
        if v != start or len(loop) < 3:
            return tri, group, 0
        g = votes.most_common(1)[0][0]
        for i in range(1, len(loop) - 1):
            new_tri.append([loop[0], loop[i], loop[i + 1]])
            new_group.append(g)
    if not new_tri:
        return tri, group, 0
    return (np.concatenate([tri, np.asarray(new_tri, dtype=tri.dtype)]),
            np.concatenate([group, np.asarray(new_group, dtype=group.dtype)]), len(new_tri))


def exact_volume(c):
    if c["bodies"]:
        return c["far_volume"] - sum(b["volume"] for b in c["bodies"])
    import numpy as np
    return c["far_volume"] - float(np.load(c["wall"])["volume"])


def last_line(text, code):
    if code is not None and code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    lines = [line for line in text.strip().splitlines() if line.strip()]
    err = [line for line in lines if "error" in line.lower()]
    return (err or lines or [f"exit {code}"])[-1].strip()


# ---------------------------------------------------------------------------------------------
# measures (the mesh in the current Gmsh model)


def tet_dihedrals(x):
    """The largest dihedral angle (degrees) of each tetrahedron, x of shape (n, 4, 3)."""
    import numpy as np
    worst = np.zeros(len(x))
    for i, j, k, l in [(0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2),
                       (2, 3, 0, 1)]:
        u = x[:, j] - x[:, i]
        u /= np.linalg.norm(u, axis=1)[:, None]
        a = x[:, k] - x[:, i]
        b = x[:, l] - x[:, i]
        a -= np.einsum("ij,ij->i", a, u)[:, None] * u
        b -= np.einsum("ij,ij->i", b, u)[:, None] * u
        cos = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) *
                                             np.linalg.norm(b, axis=1))
        worst = np.maximum(worst, np.degrees(np.arccos(np.clip(np.nan_to_num(cos), -1, 1))))
    return worst


def measure():
    """Figures of the 3D cells of the current Gmsh model (any order: the angles on the primary
    nodes)."""
    import gmsh
    import numpy as np
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    pos = np.zeros((int(tags.max()) + 1, 3))
    pos[tags.astype(int)] = xyz.reshape(-1, 3)
    out = {"cells": {}, "minsj_le_0": 0, "least_minsj": None, "volume": 0.0}
    types, els, nodes = gmsh.model.mesh.getElements(3)
    for t, el, nd in zip(types, els, nodes):
        name, _, order, count, _, primary = gmsh.model.mesh.getElementProperties(t)
        family = FAMILY.get(name.split()[0], name)
        out["cells"][family] = out["cells"].get(family, 0) + len(el)
        if order > 1:
            out["order"] = order
        q = np.asarray(gmsh.model.mesh.getElementQualities(el, "minSJ"))
        out["minsj_le_0"] += int((q <= 0).sum())
        least = float(q.min())
        out["least_minsj"] = least if out["least_minsj"] is None else min(out["least_minsj"],
                                                                           least)
        out["volume"] += float(np.sum(gmsh.model.mesh.getElementQualities(el, "volume")))
        if family == "tet":
            x = pos[nd.astype(int).reshape(-1, count)[:, :4]]
            d = tet_dihedrals(x)
            out["tet_max_dihedral"] = max(out.get("tet_max_dihedral", 0.0), float(d.max()))
            out["tets_over_150"] = out.get("tets_over_150", 0) + int((d > 150).sum())
            out["tets_over_160"] = out.get("tets_over_160", 0) + int((d > 160).sum())
            w = int(d.argmax())
            out["worst_tet_at"] = [round(float(v), 4) for v in x[w].mean(0)]
    out["cells_total"] = sum(out["cells"].values())
    return out


# ---------------------------------------------------------------------------------------------
# the meshers (each in a child process)


def run_ours(c, out, timeout):
    import gmsh
    msh = os.path.join(out, f"{c['name']}-ours.msh")
    rep = os.path.join(out, f"{c['name']}-ours.report.json")
    for p in (msh, rep):
        if os.path.exists(p):
            os.remove(p)
    t0 = time.time()
    try:
        p = subprocess.run([EXE, "mesh", c["path"], "--out", msh, "--report", rep],
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"ok": False, "error": f"timeout after {timeout:g} s", "time_s": time.time() - t0}
    res = {"exit": p.returncode, "time_s": time.time() - t0, "layers": len(c["heights"])}
    if p.returncode not in (0, 2) or not os.path.exists(msh):
        res.update(ok=False, error=f"exit {p.returncode}: {last_line(p.stderr, p.returncode)}")
        return res
    res["ok"] = p.returncode == 0
    if not res["ok"]:
        res["error"] = f"exit {p.returncode}: {last_line(p.stderr, p.returncode)}"
    if os.path.exists(rep):
        with open(rep) as f:
            r = json.load(f)
        res.update(report_cells=r.get("cells"), report_time_s=r.get("timings_s", {}).get("total"),
                   timings_s=r.get("timings_s"), layers=r.get("layers", res["layers"]),
                   report_max_dihedral=(r.get("quality") or {}).get("max_dihedral_deg"),
                   report_volume=r.get("volume"), fill=r.get("fill"),
                   coverage=r.get("coverage"), problems=r.get("problems"),
                   wall_triangles=(r.get("boundary_facets") or {}).get("wall"))
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(msh)
    res.update(measure())
    gmsh.finalize()
    return res


def gmsh_model(c, heights):
    """Gmsh's mesh of the case in the current model: the far field and the walls (OCC shapes for
    built-in bodies; else curvemesh's wall triangles and the far field's, as discrete surfaces),
    the layers extruded from the walls, the rest tetrahedra. Returns the wall surfaces' tags."""
    import gmsh
    import numpy as np
    if c["bodies"]:
        occ = gmsh.model.occ
        far = occ_far(c)
        bodies = []
        for b in c["bodies"]:
            if b["kind"] == "sphere":
                bodies.append(occ.addSphere(*b["center"], b["radius"]))
            else:
                bodies.append(occ.addBox(*b["min"],
                                         *(h - l for l, h in zip(b["min"], b["max"]))))
        occ.synchronize()
        far_faces = [t for _, t in gmsh.model.getBoundary([(3, far)], oriented=False)]
        gmsh.model.mesh.setSize(gmsh.model.getBoundary([(3, far)], recursive=True),
                                c["far_size"])
        solids = [(3, v) for v in bodies]
        wall = [t for _, t in gmsh.model.getBoundary(solids, oriented=False)]
        gmsh.model.mesh.setSize(gmsh.model.getBoundary(solids, recursive=True), wall_size(c))
        # the OCC solids' surfaces stay, their volumes go: the fluid is the volume made below
        occ.remove([(3, far)] + solids)
        occ.synchronize()
        gmsh.model.mesh.generate(2)
    else:
        # discrete surfaces only (`createTopology` spoils OCC entities' curves)
        far_pts, far_tri = far_triangles(c)
        w = np.load(c["wall"])
        pts, tri, group = w["points"], w["triangles"], w["group"]
        s = gmsh.model.addDiscreteEntity(2)
        gmsh.model.mesh.addNodes(2, s, list(range(1, len(far_pts) + 1)), far_pts.ravel().tolist())
        gmsh.model.mesh.addElementsByType(s, 2, [], (far_tri + 1).ravel().tolist())
        far_faces = [s]
        start = len(far_pts) + 1
        wall = []
        for g in np.unique(group):
            s = gmsh.model.addDiscreteEntity(2)
            sel = tri[group == g]
            used = np.unique(sel)
            gmsh.model.mesh.addNodes(2, s, (used + start).tolist(), pts[used].ravel().tolist())
            gmsh.model.mesh.addElementsByType(s, 2, [], (sel + start).ravel().tolist())
            wall.append(s)
        # the groups joined by discrete curves (else the extrusion stops at their seams)
        gmsh.model.mesh.createTopology()
    gmsh.option.setNumber("Geometry.ExtrudeReturnLateralEntities", 0)
    geo = gmsh.model.geo
    ext = geo.extrudeBoundaryLayer([(2, t) for t in wall], [1] * len(heights),
                                   [float(v) for v in np.cumsum(heights)], True)
    top = [t for d, t in ext if d == 2]
    geo.addVolume([geo.addSurfaceLoop(far_faces), geo.addSurfaceLoop(top)])
    geo.synchronize()
    gmsh.model.mesh.generate(3)
    return wall


def occ_far(c):
    """The far field as an OCC solid in the current model; its tag."""
    import gmsh
    f = c["far"]
    if f["kind"] == "sphere":
        return gmsh.model.occ.addSphere(*f["center"], f["radius"])
    return gmsh.model.occ.addBox(*f["min"], *(h - l for l, h in zip(f["min"], f["max"])))


def far_triangles(c):
    """The far field's triangles (Gmsh's mesh of the OCC shape at the far field's size, in a
    model of its own), facing out of the fluid: points and 0-based triangles."""
    import gmsh
    import numpy as np
    current = gmsh.model.getCurrent()
    gmsh.model.add("farfield")
    v = occ_far(c)
    gmsh.model.occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getBoundary([(3, v)], recursive=True), c["far_size"])
    gmsh.model.mesh.generate(2)
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    _, tri = gmsh.model.mesh.getElementsByType(2)
    gmsh.model.remove()
    gmsh.model.setCurrent(current)
    index = {int(t): i for i, t in enumerate(tags)}
    far_tri = np.array([index[int(t)] for t in tri]).reshape(-1, 3)
    far_pts = xyz.reshape(-1, 3)
    x = far_pts[far_tri]
    if np.einsum("ij,ij->i", x[:, 0], np.cross(x[:, 1], x[:, 2])).sum() < 0:
        far_tri = far_tri[:, [0, 2, 1]]
    return far_pts, far_tri


def run_gmsh(c, out, mesher, timeout, result):
    import threading
    import gmsh
    heights = c["heights"][:cap(c)] if mesher == "gmsh-cap" else c["heights"]
    res = {"layers": len(heights)}
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    t0 = time.time()

    def stop():  # Gmsh meshing past the timeout: the result written, the process ended
        res.update(ok=False, time_s=time.time() - t0, error=f"timeout after {timeout:g} s")
        with open(result, "w") as f:
            json.dump(res, f, indent=1)
        os._exit(1)
    timer = threading.Timer(timeout, stop)
    timer.start()
    try:
        wall = gmsh_model(c, heights)
        res.update(ok=True, time_s=time.time() - t0)
    except Exception as e:  # Gmsh's errors come as Exception(message)
        res.update(ok=False, time_s=time.time() - t0, error=str(e))
        gmsh.finalize()
        return res
    finally:
        timer.cancel()
    res["wall_triangles"] = sum(len(gmsh.model.mesh.getElementsByType(2, t)[0]) for t in wall)
    gmsh.write(os.path.join(out, f"{c['name']}-{mesher}.msh"))
    res.update(measure())
    if not res["cells"].get("tet"):
        res.update(ok=False, error="no tetrahedra outside the layers")
    gmsh.finalize()
    return res


def netgen_input(c, out):
    """For a case on curvemesh's wall triangles, Netgen's surface mesh: those and Gmsh's far
    field triangles (facing out of the fluid), saved for the Netgen child."""
    import gmsh
    import numpy as np
    w = np.load(c["wall"])
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("case")
    far_pts, far_tri = far_triangles(c)
    gmsh.finalize()
    path = os.path.join(out, f"{c['name']}-netgen-input.npz")
    np.savez(path, wall_points=w["points"], wall_triangles=w["triangles"], far_points=far_pts,
             far_triangles=far_tri)
    return path


def run_netgen(c, out, mesher, timeout):
    """Netgen in a grandchild (this interpreter or /tmp/venv-netgen's), its mesh measured here."""
    import gmsh
    import numpy as np
    heights = c["heights"][:cap(c)] if mesher == "netgen-cap" else c["heights"]
    py = netgen_python()
    if py is None:
        return {"ok": False, "error": "netgen-mesher not installed (python3 -m venv "
                "/tmp/venv-netgen && /tmp/venv-netgen/bin/pip install netgen-mesher)"}
    job = {"heights": heights, "limit": mesher == "netgen-limit", "far": c["far"],
           "far_size": c["far_size"], "bodies": c["bodies"],
           "wall_size": wall_size(c) if c["bodies"] else None,
           "input": None if c["bodies"] else netgen_input(c, out),
           "npz": os.path.join(out, f"{c['name']}-{mesher}.npz"),
           "log": os.path.join(out, f"{c['name']}-{mesher}.log")}
    if os.path.exists(job["npz"]):
        os.remove(job["npz"])
    spec = os.path.join(out, f"{c['name']}-{mesher}.job.json")
    with open(spec, "w") as f:
        json.dump(job, f)
    t0 = time.time()
    try:
        p = subprocess.run([py, os.path.abspath(__file__), "--netgen-job", spec],
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"ok": False, "error": f"timeout after {timeout:g} s", "time_s": time.time() - t0,
                "layers": len(heights)}
    if not os.path.exists(job["npz"]):
        error = "crashed: " + last_line(p.stderr, p.returncode)
        if os.path.exists(job["log"]):  # a failure Netgen reported before it crashed
            with open(job["log"], errors="replace") as f:
                failed = [line.strip() for line in f if "failed" in line.lower()]
            if failed:
                error += f", after: {failed[-1]}"
        return {"ok": False, "error": error, "time_s": time.time() - t0,
                "layers": len(heights)}
    d = np.load(job["npz"])
    res = json.loads(str(d["result"]))
    res["layers"] = len(heights)
    if not res["ok"]:
        return res
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("netgen")
    vol = gmsh.model.addDiscreteEntity(3)
    pts = d["points"]
    gmsh.model.mesh.addNodes(3, vol, list(range(1, len(pts) + 1)), pts.ravel().tolist())
    for gtype, key in ((4, "tet"), (5, "hex"), (6, "prism"), (7, "pyramid")):
        conn = d[key]
        if len(conn):
            gmsh.model.mesh.addElementsByType(vol, gtype, [], conn.ravel().tolist())
    gmsh.write(os.path.join(out, f"{c['name']}-{mesher}.msh"))
    res.update(measure())
    if not res["cells"].get("tet"):
        res.update(ok=False, error="no tetrahedra outside the layers")
    gmsh.finalize()
    return res


def netgen_python():
    """An interpreter where `import netgen.meshing` works: this one, else /tmp/venv-netgen's."""
    for py in (sys.executable, "/tmp/venv-netgen/bin/python"):
        if not os.path.exists(py):
            continue
        probe = [py, "-c", "import netgen.meshing, netgen.occ"]
        if subprocess.run(probe, capture_output=True).returncode == 0:
            return py
    return None


# Netgen's volume elements turn the other way from Gmsh's (see compare.py): these orders give
# Gmsh's.
NETGEN_TO_GMSH = {"TET": ("tet", [0, 2, 1, 3]), "PRISM": ("prism", [0, 2, 1, 3, 5, 4]),
                  "PYRAMID": ("pyramid", [3, 2, 1, 0, 4]),
                  "HEX": ("hex", [0, 1, 5, 4, 3, 2, 6, 7])}


def netgen_job(spec):
    """The Netgen grandchild: meshes the job (no Gmsh here), saves the cells in Gmsh's order."""
    import numpy as np
    import netgen.meshing as ngm
    with open(spec) as f:
        job = json.load(f)
    res = {"ok": False}
    arrays = {}
    t0 = time.time()
    try:
        bl = ngm.BoundaryLayerParameters(boundary="wall", thickness=job["heights"],
                                         new_material="layers", domain="fluid",
                                         limit_growth_vectors=job["limit"])
        with captured(job["log"]):
            if job["input"] is None:
                mesh = netgen_occ(job, bl)
            else:
                mesh = netgen_surface(job, bl)
        res.update(ok=True, time_s=time.time() - t0)
    except Exception as e:
        res.update(ok=False, time_s=time.time() - t0, error=str(e))
        mesh = None
    with open(job["log"]) as f:
        lines = [line.strip() for line in f if line.strip()]
    # the most telling line first: a failure, an error, then warnings
    failed = sorted((line for line in lines
                     if any(w in line.lower() for w in ("failed", "error", "overlap", "intersect"))
                     and "Meshing failed!" not in line),
                    key=lambda x: 0 if "failed" in x.lower() else 1 if "error" in x.lower() else 2)
    if failed and not res["ok"]:
        res["error"] = failed[0] if res.get("error") in (None, "", "Meshing failed!") \
            else f"{res['error']} ({failed[0]})"
    elif res["ok"] and any("failed" in line.lower() for line in failed):
        # a failed volume mesh reported on standard error, the call returning
        res.update(ok=False, error=next(x for x in failed if "failed" in x.lower()))
    if mesh is not None:
        els = mesh.Elements3D().NumPy()
        arrays["points"] = mesh.Coordinates()
        known = 0
        for kind, (key, order) in NETGEN_TO_GMSH.items():
            sel = els[els["type"] == int(getattr(ngm.ElementType, kind))]
            known += len(sel)
            arrays[key] = (sel["nodes"][:, :len(order)][:, order].astype(np.int64) if len(sel)
                           else np.zeros((0, len(order)), dtype=np.int64))
        if len(els) - known:
            res["other_cells"] = int(len(els) - known)
        # the wall's triangles: the surface elements on faces named wall
        try:
            names = {i + 1: mesh.GetBCName(i) for i in range(mesh.GetNFaceDescriptors())}
            idx = mesh.Elements2D().NumPy()["index"]
            res["wall_triangles"] = int(sum(names.get(int(i)) == "wall" for i in idx))
        except Exception:
            pass
    np.savez(job["npz"], result=json.dumps(res), **arrays)


class captured:
    """Netgen's standard output and error (file descriptors 1 and 2) into a log file."""

    def __init__(self, path):
        self.path = path

    def __enter__(self):
        sys.stdout.flush()
        sys.stderr.flush()
        self.saved = [os.dup(1), os.dup(2)]
        self.file = open(self.path, "w")
        os.dup2(self.file.fileno(), 1)
        os.dup2(self.file.fileno(), 2)

    def __exit__(self, *exc):
        sys.stdout.flush()
        sys.stderr.flush()
        for fd, old in zip((1, 2), self.saved):
            os.dup2(old, fd)
            os.close(old)
        self.file.close()
        return False


def netgen_occ(job, bl):
    """Netgen's mesh of the OCC geometry: the far field less the bodies, the walls `wall`."""
    from netgen.occ import Box, OCCGeometry, Pnt, Sphere
    f = job["far"]
    if f["kind"] == "sphere":
        fluid = Sphere(Pnt(*f["center"]), f["radius"])
    else:
        fluid = Box(Pnt(*f["min"]), Pnt(*f["max"]))
    fluid.faces.name = "farfield"
    fluid.faces.maxh = job["far_size"]
    for b in job["bodies"]:
        s = (Sphere(Pnt(*b["center"]), b["radius"]) if b["kind"] == "sphere"
             else Box(Pnt(*b["min"]), Pnt(*b["max"])))
        s.faces.name = "wall"
        s.faces.maxh = job["wall_size"]
        fluid = fluid - s
    fluid.mat("fluid")
    return OCCGeometry(fluid).GenerateMesh(maxh=job["far_size"], boundary_layers=[bl])


def netgen_surface(job, bl):
    """Netgen's mesh of a surface mesh: curvemesh's wall triangles (fluid outside) and the far
    field's, volume-meshed by GenerateVolumeMesh."""
    import numpy as np
    import netgen.meshing as ngm
    d = np.load(job["input"])
    mesh = ngm.Mesh(dim=3)
    for i, (pk, tk) in enumerate((("wall_points", "wall_triangles"),
                                  ("far_points", "far_triangles"))):
        ids = [mesh.Add(ngm.MeshPoint(ngm.Pnt(*map(float, x)))) for x in d[pk]]
        # the wall's normals point out of the body into the fluid (domain 0 to 1); the far
        # field's out of the fluid (1 to 0)
        fd = mesh.Add(ngm.FaceDescriptor(surfnr=i + 1, domin=i, domout=1 - i, bc=i + 1))
        mesh.SetBCName(i, ("wall", "farfield")[i])
        for t in d[tk]:
            mesh.Add(ngm.Element2D(fd, [ids[int(v)] for v in t]))
    mesh.SetMaterial(1, "fluid")
    mesh.GenerateVolumeMesh(maxh=job["far_size"], boundary_layers=[bl])
    return mesh


def child(mesher, name, out, timeout):
    t0 = time.time()
    try:
        c = case(name, out)
        if not c["bodies"] and not os.path.exists(c["wall"]):
            raise RuntimeError("no wall triangles (curvemesh's export failed)")
        if mesher == "ours":
            res = run_ours(c, out, timeout)
        elif mesher.startswith("gmsh"):
            res = run_gmsh(c, out, mesher, timeout,
                           os.path.join(out, f"{name}-{mesher}.json"))
        else:
            res = run_netgen(c, out, mesher, timeout)
        if res.get("volume") is not None:
            exact = exact_volume(c)
            res["exact_volume"] = exact
            res["volume_rel_diff"] = (res["volume"] - exact) / exact
    except Exception as e:
        res = {"ok": False, "error": f"{type(e).__name__}: {e}", "time_s": time.time() - t0}
    with open(os.path.join(out, f"{name}-{mesher}.json"), "w") as f:
        json.dump(res, f, indent=1)


def run_child(cmd, limit, max_gb):
    """Runs a child in a session of its own, killed with its descendants past `limit` seconds
    or past `max_gb` GB resident (the session's, sampled twice a second). Returns its exit
    code, its standard error, the peak resident GB and why it was killed (None)."""
    import tempfile
    page = os.sysconf("SC_PAGE_SIZE")

    def rss(sid):
        total = 0
        for d in os.listdir("/proc"):
            if not d.isdigit():
                continue
            try:
                with open(f"/proc/{d}/stat") as f:
                    st = f.read()
            except OSError:
                continue
            fields = st[st.rfind(")") + 2:].split()  # from the state (field 3) on
            if int(fields[3]) == sid:  # the session (field 6)
                total += int(fields[21]) * page  # the resident pages (field 24)
        return total

    t0 = time.time()
    peak, why = 0, None
    with tempfile.TemporaryFile("w+") as err:
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err, text=True,
                             start_new_session=True)
        while p.poll() is None:
            peak = max(peak, rss(p.pid))
            if max_gb and peak > max_gb * 2 ** 30:
                why = f"out of memory above {max_gb:g} GB"
            elif time.time() - t0 > limit:
                why = f"timeout after {limit:g} s"
            if why:
                break
            time.sleep(0.5)
        try:  # the child, or what it left running
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        p.wait()
        err.seek(0)
        return p.returncode, err.read(), peak / 2 ** 30, why


# ---------------------------------------------------------------------------------------------
# the table


def num(v):
    return f"{v:,}".replace(",", " ")


def row(name, mesher, res):
    t = "—" if res.get("time_s") is None else f"{res['time_s']:.1f}"
    layers = res.get("layers", "—")
    status = "ok" if res.get("ok") else "failed: " + short(res.get("error", "?"))
    if res.get("ok") and abs(res.get("volume_rel_diff") or 0) > VOLUME_OFF:
        status = "ok, but the volume is off: cells overlap or leave gaps"
    if "cells" not in res:
        return f"| {name} | {LABEL[mesher]} | {status} | {t} | {layers} | | | | | | |"
    c = res["cells"]
    cells = " / ".join(num(c.get(k, 0)) for k in ("tet", "prism", "pyramid", "hex"))
    if res.get("other_cells"):
        cells += f" (+{num(res['other_cells'])} other)"
    wall = num(res["wall_triangles"]) if res.get("wall_triangles") is not None else "—"
    dihedral = "—"
    if res.get("tet_max_dihedral") is not None:
        dihedral = (f"{res['tet_max_dihedral']:.1f}° / {num(res['tets_over_150'])} / "
                    f"{num(res['tets_over_160'])}")
    least = res.get("least_minsj")
    sj = num(res["minsj_le_0"]) + ("" if least is None else f" ({least:.3g})")
    vol = "—"
    if res.get("volume_rel_diff") is not None:
        vol = f"{res['volume']:.6g} ({100 * res['volume_rel_diff']:+.2f} %)"
    return (f"| {name} | {LABEL[mesher]} | {status} | {t} | {layers} | {wall} | {cells} | "
            f"{dihedral} | {sj} | {vol} |")


def short(text, n=140):
    text = " ".join(str(text).split())
    text = re.sub(r"-?\d+\.\d{5,}(e-?\d+)?", lambda m: f"{float(m.group()):.4g}", text)
    return text if len(text) <= n else text[:n - 3] + "..."


HEADER = ("| case | mesher | result | time (s) | layers | wall triangles | "
          "tets / prisms / pyramids / hexes | tets' max dihedral / over 150° / over 160° | "
          "minSJ ≤ 0 (least) | volume (vs exact) |\n"
          "|---|---|---|---|---|---|---|---|---|---|")


def versions():
    import gmsh
    py = netgen_python()
    ng = "not installed"
    if py:
        ng = subprocess.run([py, "-c", "import netgen.version; print(netgen.version.__version__)"],
                            capture_output=True, text=True).stdout.strip() or "?"
    return f"Gmsh {gmsh.__version__}, Netgen {ng}, Python {sys.version.split()[0]}."


def main():
    global EXE
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("table", nargs="?", help="the Markdown table's file")
    ap.add_argument("names", nargs="*", help="cases (default: " + ", ".join(CASES) + ")")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per mesher (600)")
    ap.add_argument("--out", default="/tmp/cmp-farfield", help="output folder")
    ap.add_argument("--meshers", default=",".join(MESHERS), help=",".join(MESHERS))
    ap.add_argument("--bin", default=EXE, help="the curvemesh binary (target/release/curvemesh)")
    ap.add_argument("--max-memory", type=float, metavar="GB",
                    help="kill a mesher whose processes hold more (default: no limit)")
    ap.add_argument("--one", nargs=2, metavar=("MESHER", "NAME"), help=argparse.SUPPRESS)
    ap.add_argument("--netgen-job", help=argparse.SUPPRESS)
    args = ap.parse_args()
    EXE = os.path.abspath(args.bin)
    if args.netgen_job:
        netgen_job(args.netgen_job)
        return
    os.makedirs(args.out, exist_ok=True)
    if args.one:
        child(args.one[0], args.one[1], args.out, args.timeout)
        return
    if not args.table:
        ap.error("give the table's file")
    if not os.path.exists(EXE):
        sys.exit(f"{EXE} is missing: cargo build --release -p curvemesh-cli --bin curvemesh")
    lines = []
    start = time.time()
    for name in args.names or CASES:
        try:
            c = case(name, args.out)
        except Exception as e:
            lines.append(f"| {name} | — | failed: {short(f'{type(e).__name__}: {e}')} "
                         "| | | | | | | |")
            continue
        notes = []
        try:
            if os.path.exists(c["wall"]):
                os.remove(c["wall"])
            export_wall(c, args.timeout)
        except Exception as e:
            notes.append(f"{type(e).__name__}: {e}")
        for mesher in args.meshers.split(","):
            if mesher.endswith("-cap") and cap(c) >= len(c["heights"]):
                continue  # the whole stack fits: the run would repeat the full one
            result = os.path.join(args.out, f"{name}-{mesher}.json")
            if os.path.exists(result):
                os.remove(result)
            # the children time their mesher themselves, then measure
            limit = args.timeout + 300
            t0 = time.time()
            code, err, peak, why = run_child(
                [sys.executable, os.path.abspath(__file__), "--one", mesher, name, "--out",
                 args.out, "--timeout", str(args.timeout), "--bin", EXE], limit,
                args.max_memory)
            if why:
                res = {"ok": False, "error": why, "time_s": time.time() - t0}
            elif os.path.exists(result):
                with open(result) as f:
                    res = json.load(f)
            else:
                res = {"ok": False, "time_s": time.time() - t0,
                       "error": "crashed: " + last_line(err, code)}
            res["peak_memory_gb"] = round(peak, 2)
            with open(result, "w") as f:
                json.dump(res, f, indent=1)
            if notes and not res.get("ok") and not c["bodies"]:
                res["error"] = f"{res.get('error')} ({notes[0]})"
            line = row(c["name"], mesher, res)
            print(line, file=sys.stderr, flush=True)
            lines.append(line)
    table = (HEADER + "\n" + "\n".join(lines) + "\n\n" + versions() +
             f" The whole comparison took {time.time() - start:.0f} s.\n")
    with open(args.table, "w") as f:
        f.write(table)
    print(table)


if __name__ == "__main__":
    main()
