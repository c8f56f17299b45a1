#!/usr/bin/env python3
"""Compares curvemesh's 3D boundary layers with Gmsh's and Netgen's on the six untuned surfaces
of issue 47 (`fixtures/surfaces/*.stl`, made by `fixtures/surfaces/make.py`), each mesher given
the same wall triangles and the same layer stack: the one in `fixtures/cases3d/NAME.toml`
(15 layers from a first height of 2e-3, growth 1.2: 0.144 thick).

- curvemesh: `target/release/curvemesh mesh` on the case as it is (the mixed cut) and on a copy
  with `[cut] cells = "tets"` (the tetrahedral cut). Its domain is the layers alone.
- Gmsh: the STL merged (its solids discrete surfaces joined by `createTopology`),
  `gmsh.model.geo.extrudeBoundaryLayer` with one element per layer at the stack's cumulative
  heights (Gmsh's `BoundaryLayer` field is 2D only), the extrusion's top surface the hole in a
  box two body lengths larger than the body on every side, the rest tetrahedralised
  (`generate(3)`, far size half the body's length). When that fails, the layers are extruded
  again alone and measured.
- Netgen (`netgen-mesher`): a `netgen.meshing.Mesh` holding the STL's triangles (the wall,
  fluid outside) and the same box, volume-meshed by `GenerateVolumeMesh` with
  `boundary_layers=[BoundaryLayerParameters(boundary="wall", thickness=the 15 layer heights)]`
  (maxh half the body's length), at its defaults and again with `limit_growth_vectors=True`
  (Netgen's option that shortens columns which would cross or invert). Netgen reports a failed
  volume mesh on standard error and returns; that line (kept in DIR/NAME-MESHER.log) is its
  failure.

Each mesher runs in a child process with a timeout (`--timeout`, default 300 s). Every mesh it
writes is read into Gmsh and measured the same way: cells by type; Gmsh's `minSJ` of every cell
(`getElementQualities`) and how many are <= 0; the tetrahedra's largest dihedral angle and how
many exceed 160 degrees; the prisms' smallest corner scaled Jacobian, det(e1, e2, e3) / (|e1|
|e2| |e3|) of the three edges at a corner (the measure of curvemesh's report). Coverage, the
share of wall nodes with all their layers, and the fewest layers on one: for curvemesh the
report's; for Gmsh and Netgen the wall nodes with 15 prisms above them (followed up the prisms'
side edges). Reach, alike for all: the share of wall nodes whose nearest node on the layers'
outer surface (curvemesh's `farfield`, the top of Gmsh's and Netgen's prism columns) is at
least 99 % of the stack's thickness away, and the least such distance over the thickness (a
lower bound of the local stack's height: it is the height where the layers stand upright and
less where they close in, as in a concave crease). Time is the
wall time of the run (curvemesh: the whole command, writing included; Gmsh, Netgen: from
reading the STL to the volume mesh). A mesher that fails or times out gets its message.

Run from the repository root, after `bash tests/python/install.sh` and
`.venv-checkers/bin/pip install netgen-mesher`, with `target/release/curvemesh` built
(`cargo build --release -p curvemesh-cli --bin curvemesh`):

    .venv-checkers/bin/python tests/surfaces/compare.py [NAME ...] [--timeout S] [--out DIR]

It prints a Markdown table and writes it to DIR/table.md (default /tmp/cmp), with each run's
figures in DIR/NAME-MESHER.json and the meshes in DIR/NAME-MESHER.msh.
"""
import argparse
import json
import os
import subprocess
import sys
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = ["swept-wing", "capsule-fin", "torus", "fused-spheres", "box-tower", "two-spheres"]
MESHERS = ["ours-mixed", "ours-tets", "gmsh", "netgen", "netgen-limit"]
LABEL = {"ours-mixed": "curvemesh, mixed", "ours-tets": "curvemesh, tets",
         "gmsh": "Gmsh extrudeBoundaryLayer", "netgen": "Netgen boundary_layers",
         "netgen-limit": "Netgen, limit_growth_vectors"}
GMSH_TYPES = {4: "tet", 5: "hex", 6: "prism", 7: "pyramid"}


def case(name):
    """The case file's path, its STL's absolute path and the layer heights (first height times
    growth^k, k < max_layers)."""
    path = os.path.join(ROOT, "fixtures", "cases3d", name + ".toml")
    with open(path, "rb") as f:
        spec = tomllib.load(f)
    stl = os.path.normpath(os.path.join(os.path.dirname(path), spec["surface"]["file"]))
    lay = spec["layers"]
    heights = [lay["first_height"] * lay["growth"] ** k for k in range(lay["max_layers"])]
    return path, stl, heights


# ---------------------------------------------------------------------------------------------
# measures (in a child, the mesh in the current Gmsh model)


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
        c = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
        worst = np.maximum(worst, np.degrees(np.arccos(np.clip(c, -1, 1))))
    return worst


def corner_sj(x, corners):
    """The smallest corner scaled Jacobian of each cell, x of shape (n, nodes, 3), corners a list
    of (corner, a, b, c) with det(xa - x0, xb - x0, xc - x0) > 0 on a valid cell."""
    import numpy as np
    worst = np.full(len(x), np.inf)
    for o, a, b, c in corners:
        e = [x[:, v] - x[:, o] for v in (a, b, c)]
        det = np.einsum("ij,ij->i", np.cross(e[0], e[1]), e[2])
        norm = np.prod([np.linalg.norm(v, axis=1) for v in e], axis=0)
        worst = np.minimum(worst, det / norm)
    return worst


PRISM_CORNERS = [(0, 1, 2, 3), (1, 2, 0, 4), (2, 0, 1, 5), (3, 5, 4, 0), (4, 3, 5, 1),
                 (5, 4, 3, 2)]
HEX_CORNERS = [(i, (i + 1) % 4, (i + 3) % 4, i + 4) for i in range(4)] + \
    [(i + 4, (i + 3) % 4 + 4, (i + 1) % 4 + 4, i) for i in range(4)]


def measure(wall_nodes=None, thickness=None, layers=None, front_nodes=None):
    """Figures of the linear 3D cells of the current Gmsh model. With the wall's node tags, the
    stack's thickness and its number of layers, also how far the layers reach from the wall
    (`reach`) with the nodes of their outer surface (`front_nodes`); without those, the
    coverage of the prism columns and their tops as the outer surface."""
    import gmsh
    import numpy as np
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    pos = np.zeros((int(tags.max()) + 1, 3))
    pos[tags.astype(int)] = xyz.reshape(-1, 3)
    out = {"cells": {}, "minsj_le_0": 0, "least_minsj": None}
    prisms = tets = None
    for t, name in GMSH_TYPES.items():
        el, nodes = gmsh.model.mesh.getElementsByType(t)
        out["cells"][name] = len(el)
        if not len(el):
            continue
        q = np.asarray(gmsh.model.mesh.getElementQualities(el, "minSJ"))
        out["minsj_le_0"] += int((q <= 0).sum())
        least = float(q.min())
        out["least_minsj"] = least if out["least_minsj"] is None else min(out["least_minsj"], least)
        out.setdefault("minsj_le_0_by_type", {})[name] = int((q <= 0).sum())
        n = {4: 4, 5: 8, 6: 6, 7: 5}[t]
        conn = nodes.astype(int).reshape(-1, n)
        x = pos[conn]
        if name == "tet":
            d = tet_dihedrals(x)
            out["tet_max_dihedral"] = float(d.max())
            out["tets_over_160"] = int((d > 160).sum())
            out["tets_over_150"] = int((d > 150).sum())
            tets = (conn, d)
            w = int(d.argmax())
            out["worst_tet_at"] = [round(float(v), 4) for v in x[w].mean(0)]
        if name in ("prism", "hex"):
            s = corner_sj(x, PRISM_CORNERS if name == "prism" else HEX_CORNERS)
            key = "min_corner_sj"
            out[key] = float(s.min()) if key not in out else min(out[key], float(s.min()))
            if name == "prism":
                prisms = conn
                out["prisms_corner_sj_le_0"] = int((s <= 0).sum())
    out["cells_total"] = sum(out["cells"].values())
    if prisms is not None and tets is not None:
        # the tetrahedra touching the layers (a node on a prism)
        near = np.isin(tets[0], np.unique(prisms)).any(axis=1)
        if near.any():
            out["tets_at_layers"] = int(near.sum())
            out["tets_at_layers_max_dihedral"] = float(tets[1][near].max())
            out["tets_at_layers_over_160"] = int((tets[1][near] > 160).sum())
    if wall_nodes is not None:
        if front_nodes is None:
            figures, front_nodes = columns(prisms, wall_nodes, layers)
            out.update(figures)
        out.update(reach(pos, wall_nodes, front_nodes, thickness))
    return out


def columns(prisms, wall_nodes, layers):
    """Follows each wall node up the prisms' side edges (corner k to corner k + 3): the share of
    wall nodes with `layers` prisms above them, the fewest prisms above one, and the columns'
    top nodes."""
    up = {}
    if prisms is not None:
        for k in range(3):
            for a, b in zip(prisms[:, k], prisms[:, k + 3]):
                up.setdefault(int(a), set()).add(int(b))
                up.setdefault(int(b), set()).add(int(a))
    full = 0
    least = layers
    tops = set()
    for w in wall_nodes:
        prev, cur, n = None, int(w), 0
        while True:
            nxt = [v for v in up.get(cur, ()) if v != prev]
            if len(nxt) != 1 or n > 10 * layers:
                break
            prev, cur, n = cur, nxt[0], n + 1
        least = min(least, n)
        full += n >= layers
        if n:
            tops.add(cur)
    return {"coverage": full / len(wall_nodes), "least_layers": least}, sorted(tops)


def reach(pos, wall_nodes, front_nodes, thickness):
    """How far the layers' outer surface is from each wall node (its nearest node there): the
    share of wall nodes at least 99 % of `thickness` away and the least distance over
    `thickness`."""
    import numpy as np
    if not len(front_nodes):
        return {"reach": 0.0, "least_reach": 0.0}
    front = pos[np.asarray(front_nodes, dtype=int)]
    d = np.empty(len(wall_nodes))
    wall = pos[np.asarray(wall_nodes, dtype=int)]
    for i in range(0, len(wall), 256):
        w = wall[i:i + 256]
        d[i:i + 256] = np.sqrt(((w[:, None, :] - front[None, :, :]) ** 2).sum(-1)).min(1)
    return {"reach": float((d >= 0.99 * thickness).mean()),
            "least_reach": float(d.min() / thickness)}


def bounding(xyz):
    """The box two body lengths larger than the body on every side and the body's length."""
    lo = [min(p[i] for p in xyz) for i in range(3)]
    hi = [max(p[i] for p in xyz) for i in range(3)]
    size = max(h - l for l, h in zip(lo, hi))
    return [v - 2 * size for v in lo], [v + 2 * size for v in hi], size


# ---------------------------------------------------------------------------------------------
# the meshers (each in a child process)


def run_ours(name, cut, out, timeout):
    import gmsh
    path, stl, heights = case(name)
    with open(path) as f:
        text = f.read()
    text = text.replace('file = "../surfaces/', 'file = "' + os.path.dirname(stl) + "/")
    if cut == "tets":
        text += '\n[cut]\ncells = "tets"\n'
    tmp = os.path.join(out, f"{name}-ours-{cut}.toml")
    with open(tmp, "w") as f:
        f.write(text)
    msh = os.path.join(out, f"{name}-ours-{cut}.msh")
    rep = os.path.join(out, f"{name}-ours-{cut}.report.json")
    for p in (msh, rep):
        if os.path.exists(p):
            os.remove(p)
    exe = os.path.join(ROOT, "target", "release", "curvemesh")
    t0 = time.time()
    try:
        p = subprocess.run([exe, "mesh", tmp, "--out", msh, "--report", rep],
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"ok": False, "error": f"timeout after {timeout:g} s", "time_s": time.time() - t0}
    res = {"exit": p.returncode, "time_s": time.time() - t0}
    if p.returncode not in (0, 2) or not os.path.exists(msh):
        err = (p.stderr.strip().splitlines() or ["no message"])[-1]
        res.update(ok=False, error=f"exit {p.returncode}: {err}")
        return res
    with open(rep) as f:
        r = json.load(f)
    cols = r.get("columns", {})
    q = r.get("quality", {})
    res.update(ok=p.returncode == 0, report_time_s=r["timings_s"]["total"],
               coverage=cols.get("coverage", r.get("coverage")),
               least_layers=cols.get("least_layers"), first_stopped=cols.get("first_stopped"),
               report_max_dihedral=q.get("max_dihedral_deg"),
               report_min_corner_sj=(q.get("min_corner_scaled_jacobian") or {}).get("value"),
               report_min_corner_sj_at=(q.get("min_corner_scaled_jacobian") or {}).get("at"),
               problems=r.get("problems"))
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(msh)
    # the wall's nodes (every boundary group but the outer front's, `outer` without a far
    # field) and the final front's
    groups = {}
    for dim, tag in gmsh.model.getPhysicalGroups(2):
        name = gmsh.model.getPhysicalName(dim, tag)
        nodes = groups.setdefault(name in ("outer", "farfield"), set())
        for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            for tags in gmsh.model.mesh.getElements(2, entity)[2]:
                nodes.update(int(v) for v in tags)
    res.update(measure(sorted(groups[False]), sum(heights), len(heights), sorted(groups[True])))
    gmsh.finalize()
    return res


def gmsh_mesh(stl, heights, box):
    """Gmsh's layers on the STL and, with `box`, the tetrahedra between them and the box; the
    STL's solids' surface tags."""
    import gmsh
    import numpy as np
    gmsh.merge(stl)
    gmsh.model.mesh.removeDuplicateNodes()
    # the STL's solids as discrete surfaces joined by discrete curves (without the curves the
    # extrusion stops at the swept wing's tips: "Could not find extruded node");
    # `classifySurfaces` + `createGeometry` refuse the closed bodies ("Invalid exterior boundary
    # mesh for parametrization")
    gmsh.model.mesh.createTopology()
    surface = gmsh.model.getEntities(2)
    _, xyz, _ = gmsh.model.mesh.getNodes()
    gmsh.option.setNumber("Geometry.ExtrudeReturnLateralEntities", 0)
    geo = gmsh.model.geo
    ext = geo.extrudeBoundaryLayer(surface, [1] * len(heights), list(np.cumsum(heights)), True)
    if box:
        top = [t for d, t in ext if d == 2]
        lo, hi, size = bounding(xyz.reshape(-1, 3).tolist())
        p = [geo.addPoint(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1],
                          hi[2] if i & 4 else lo[2], size / 2) for i in range(8)]
        lines = {}

        def edge(a, b):
            if (b, a) in lines:
                return -lines[(b, a)]
            lines.setdefault((a, b), geo.addLine(p[a], p[b]))
            return lines[(a, b)]
        faces = []
        for f in [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                  (1, 3, 7, 5)]:
            loop = geo.addCurveLoop([edge(f[i], f[(i + 1) % 4]) for i in range(4)])
            faces.append(geo.addPlaneSurface([loop]))
        geo.addVolume([geo.addSurfaceLoop(faces), geo.addSurfaceLoop(top)])
    geo.synchronize()
    gmsh.model.mesh.generate(3)
    return [t for _, t in surface]


def run_gmsh(name, out):
    import gmsh
    _, stl, heights = case(name)
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    res = {}
    t0 = time.time()
    try:
        surface = gmsh_mesh(stl, heights, True)
        res.update(ok=True, time_s=time.time() - t0)
    except Exception as e:  # Gmsh's errors come as Exception(message)
        res.update(ok=False, time_s=time.time() - t0, error=str(e))
        gmsh.finalize()
        # the layers alone (the failed run's are not the extrusion's: the volume's meshing
        # changes them, 100 prisms with minSJ <= 0 on the swept wing against 46)
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        try:
            gmsh_mesh(stl, heights, False)
            res["partial"] = measure()
        except Exception as e:
            res["partial_error"] = str(e)
        gmsh.finalize()
        return res
    gmsh.write(os.path.join(out, f"{name}-gmsh.msh"))
    # the wall's nodes (after `generate`, which numbers the nodes anew)
    wall = set()
    for t in surface:
        wall.update(int(v) for v in gmsh.model.mesh.getNodes(2, t, includeBoundary=True)[0])
    res.update(measure(sorted(wall), sum(heights), len(heights)))
    gmsh.finalize()
    return res


# Netgen's volume elements turn the other way from Gmsh's: the corner determinant of every
# tetrahedron and prism of a valid Netgen mesh is negative in Gmsh's orientation, and
# netgen/read_gmsh.py maps Gmsh's prisms by [0, 2, 1, 3, 5, 4], pyramids by [3, 2, 1, 0, 4] and
# hexahedra by [0, 1, 5, 4, 3, 2, 6, 7] (each its own inverse); these give Gmsh's order.
NETGEN_TO_GMSH = {"TET": (4, [0, 2, 1, 3]), "PRISM": (6, [0, 2, 1, 3, 5, 4]),
                  "PYRAMID": (7, [3, 2, 1, 0, 4]), "HEX": (5, [0, 1, 5, 4, 3, 2, 6, 7])}


def run_netgen(name, out, mesher):
    import gmsh
    _, stl, heights = case(name)
    res = {}
    t0 = time.time()
    try:
        import netgen.meshing as ngm
    except ImportError:
        return {"ok": False, "error": "netgen-mesher not installed "
                "(.venv-checkers/bin/pip install netgen-mesher)"}
    # the STL's nodes (duplicates merged) and triangles, read by Gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.merge(stl)
    gmsh.model.mesh.removeDuplicateNodes()
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    xyz = xyz.reshape(-1, 3)
    _, tri = gmsh.model.mesh.getElementsByType(2)
    gmsh.finalize()
    index = {int(t): i for i, t in enumerate(tags)}
    try:
        mesh = ngm.Mesh(dim=3)
        ids = [mesh.Add(ngm.MeshPoint(ngm.Pnt(*map(float, x)))) for x in xyz]
        wall = mesh.Add(ngm.FaceDescriptor(surfnr=1, domin=0, domout=1, bc=1))
        mesh.SetBCName(0, "wall")
        for t in tri.reshape(-1, 3):
            mesh.Add(ngm.Element2D(wall, [ids[index[int(v)]] for v in t]))
        lo, hi, size = bounding(xyz.tolist())
        corner = [mesh.Add(ngm.MeshPoint(ngm.Pnt(hi[0] if i & 1 else lo[0],
                                                 hi[1] if i & 2 else lo[1],
                                                 hi[2] if i & 4 else lo[2])))
                  for i in range(8)]
        far = mesh.Add(ngm.FaceDescriptor(surfnr=2, domin=1, domout=0, bc=2))
        mesh.SetBCName(1, "farfield")
        for q in [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                  (1, 3, 7, 5)]:
            a, b, c, d = (corner[i] for i in q)
            mesh.Add(ngm.Element2D(far, [a, b, c]))
            mesh.Add(ngm.Element2D(far, [a, c, d]))
        mesh.SetMaterial(1, "fluid")
        bl = ngm.BoundaryLayerParameters(boundary="wall", thickness=heights,
                                         new_material="layers", domain="fluid",
                                         limit_growth_vectors=mesher == "netgen-limit")
        # Netgen reports a failed volume mesh on its standard error and returns
        log = os.path.join(out, f"{name}-{mesher}.log")
        sys.stdout.flush()
        sys.stderr.flush()
        saved = [os.dup(1), os.dup(2)]
        with open(log, "w") as f:
            os.dup2(f.fileno(), 1)
            os.dup2(f.fileno(), 2)
            try:
                mesh.GenerateVolumeMesh(maxh=size / 2, boundary_layers=[bl])
            finally:
                sys.stdout.flush()
                sys.stderr.flush()
                for fd, old in zip((1, 2), saved):
                    os.dup2(old, fd)
                    os.close(old)
        res.update(ok=True, time_s=time.time() - t0)
        with open(log) as f:
            failed = [line.strip() for line in f if "failed" in line.lower()]
        if failed:
            res.update(ok=False, error=failed[0])
    except Exception as e:
        res.update(ok=False, time_s=time.time() - t0, error=str(e))
        return res
    els = mesh.Elements3D().NumPy()
    pts = mesh.Coordinates()
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("netgen")
    vol = gmsh.model.addDiscreteEntity(3)
    gmsh.model.mesh.addNodes(3, vol, list(range(1, len(pts) + 1)), pts.ravel().tolist())
    for kind, (gtype, order) in NETGEN_TO_GMSH.items():
        sel = els[els["type"] == int(getattr(ngm.ElementType, kind))]
        if len(sel):
            conn = sel["nodes"][:, :len(order)][:, order]  # Netgen's nodes count from 1
            gmsh.model.mesh.addElementsByType(vol, gtype, [], conn.ravel().tolist())
    other = len(els) - sum(int((els["type"] == int(getattr(ngm.ElementType, k))).sum())
                           for k in NETGEN_TO_GMSH)
    if other:
        res["other_cells"] = other
    gmsh.write(os.path.join(out, f"{name}-{mesher}.msh"))
    figures = measure(list(range(1, len(xyz) + 1)), sum(heights), len(heights))
    if not figures["cells"]["tet"] and res["ok"]:
        res.update(ok=False, error="no tetrahedra outside the layers")
    if res["ok"]:
        res.update(figures)
    else:
        res["partial"] = figures  # the layers made before the failure
    gmsh.finalize()
    return res


def child(mesher, name, out, timeout):
    if mesher == "ours-mixed":
        res = run_ours(name, "mixed", out, timeout)
    elif mesher == "ours-tets":
        res = run_ours(name, "tets", out, timeout)
    elif mesher == "gmsh":
        res = run_gmsh(name, out)
    else:
        res = run_netgen(name, out, mesher)
    with open(os.path.join(out, f"{name}-{mesher}.json"), "w") as f:
        json.dump(res, f, indent=1)


# ---------------------------------------------------------------------------------------------
# the table


def cell(res, key, fmt="{}"):
    v = res.get(key)
    return "—" if v is None else fmt.format(v)


def row(name, mesher, res):
    if not res.get("ok") and "cells" not in res:
        error = " ".join(res.get("error", "").split())
        if len(error) > 110:
            error = error[:107] + "..."
        part = res.get("partial")
        extra = ""
        if part and part.get("cells", {}).get("prism"):
            what = "its layers alone" if mesher == "gmsh" else "its layers"
            prisms = f"{part['cells']['prism']:,}".replace(",", " ")
            bad = f"{part['minsj_le_0']:,}".replace(",", " ")
            extra = f" ({what}: {prisms} prisms, {bad} with minSJ ≤ 0)"
        t = cell(res, "time_s", "{:.1f}")
        return f"| {name} | {LABEL[mesher]} | failed: {error}{extra} | {t} | | | | | | | |"
    c = res["cells"]
    cells = " / ".join(f"{c.get(k, 0):,}".replace(",", " ") for k in ("prism", "pyramid", "tet"))
    cov = cell(res, "coverage", "{:.3f}")
    least = res.get("least_layers")
    if isinstance(least, dict):  # curvemesh's report: per boundary group
        least = min(least.values())
    if least is not None:
        cov += f" ({least})"
    far = cell(res, "reach", "{:.3f}")
    if res.get("least_reach") is not None:
        far += f" ({res['least_reach']:.2f})"
    bad = f"{res['minsj_le_0']:,}".replace(",", " ")
    sj = cell(res, "min_corner_sj", "{:.3f}")
    if res.get("prisms_corner_sj_le_0"):
        sj += f" ({res['prisms_corner_sj_le_0']} ≤ 0)"
    dihedral = "—"
    if res.get("tet_max_dihedral") is not None:
        dihedral = f"{res['tet_max_dihedral']:.1f}° ({res['tets_over_160']})"
    near = "—"
    if res.get("tets_at_layers_max_dihedral") is not None:
        near = f"{res['tets_at_layers_max_dihedral']:.1f}° ({res['tets_at_layers_over_160']})"
    status = "ok" if res.get("ok") else f"exit {res.get('exit')}"
    return (f"| {name} | {LABEL[mesher]} | {status} | {res['time_s']:.1f} | {cov} | {far} | "
            f"{cells} | {bad} | {sj} | {dihedral} | {near} |")


HEADER = ("| surface | mesher | result | time (s) | coverage (least layers) | "
          "reach ≥ 99 % (least) | prisms / pyramids / tets | minSJ ≤ 0 | "
          "prisms' min corner SJ | tets' max dihedral (over 160°) | "
          "tets touching a prism: max dihedral (over 160°) |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|")


def versions():
    """The meshers' versions, one line."""
    import gmsh
    try:
        import netgen.version
        ng = netgen.version.__version__
    except ImportError:
        ng = "not installed"
    return f"Gmsh {gmsh.__version__}, Netgen {ng}, Python {sys.version.split()[0]}."


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", default=CASES, help="surfaces (default: all six)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds per mesher (300)")
    ap.add_argument("--out", default="/tmp/cmp", help="output folder (/tmp/cmp)")
    ap.add_argument("--meshers", default=",".join(MESHERS), help=",".join(MESHERS))
    ap.add_argument("--one", nargs=2, metavar=("MESHER", "NAME"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.one:
        child(args.one[0], args.one[1], args.out, args.timeout)
        return
    exe = os.path.join(ROOT, "target", "release", "curvemesh")
    if not os.path.exists(exe):
        sys.exit(f"{exe} is missing: cargo build --release -p curvemesh-cli --bin curvemesh")
    lines = []
    for name in args.names:
        for mesher in args.meshers.split(","):
            result = os.path.join(args.out, f"{name}-{mesher}.json")
            if os.path.exists(result):
                os.remove(result)
            # the curvemesh children time the command themselves, then measure
            limit = args.timeout + (120 if mesher.startswith("ours") else 0)
            t0 = time.time()
            try:
                p = subprocess.run([sys.executable, os.path.abspath(__file__), "--one", mesher,
                                    name, "--out", args.out, "--timeout", str(args.timeout)],
                                   capture_output=True, text=True, timeout=limit)
                if os.path.exists(result):
                    with open(result) as f:
                        res = json.load(f)
                else:
                    tail = (p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1]
                    res = {"ok": False, "error": f"crashed: {tail}",
                           "time_s": time.time() - t0}
            except subprocess.TimeoutExpired:
                res = {"ok": False, "error": f"timeout after {args.timeout:g} s",
                       "time_s": time.time() - t0}
            line = row(name, mesher, res)
            print(line, file=sys.stderr, flush=True)
            lines.append(line)
    table = HEADER + "\n" + "\n".join(lines) + "\n\n" + versions() + "\n"
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write(table)
    print(table)


if __name__ == "__main__":
    main()
