#!/usr/bin/env python3
"""Gmsh's side of `cargo xtask bench --vs-gmsh`: the same airfoil case meshed by Gmsh's Python
package the way a Gmsh user makes a curved viscous mesh — the walls as splines through the
.dat points (a straight segment closing a blunt trailing edge), a circular far field, a
boundary-layer field of quadrangles (`Quads = 1`) with the first height and growth of our
case, `setOrder(3)`, and Gmsh's high-order optimisers run only while some element has
minSJ <= 0 (see OPTIMISERS). It writes the P3 mesh as MSH 4.1 and prints one JSON line: the
cells, the elements left with minSJ <= 0, each step with the invalid elements after it, the
seconds inside Gmsh; a mesh Gmsh refuses is printed as {"failed": ...}, and an abort of Gmsh's
C++ code ends the process with a signal (the caller reports it). Gmsh runs with
`General.AbortOnError = 1`: its high-order optimiser then logs a patch it cannot untangle
("Failed to reach critical value ... ScaledJac") and goes on, where by default the error is
thrown inside a parallel region and terminates the process; the elements it leaves with
minSJ <= 0 are counted and reported. The caller
times the whole process (CPU and wall).

`--size F` scales every target size (the wall's, the far field's); `--calibrate CELLS` finds,
with untimed linear meshes, the F that gives about CELLS cells and prints it, so that the
timed runs mesh as many cells as ours (within 10 %).

Usage: gmsh_bench.py --dat A.dat [--dat B.dat ...] --first-height H [--size F] --out OUT.msh
       gmsh_bench.py --dat A.dat ... --first-height H --calibrate CELLS
"""
import argparse
import json
import math
import sys
import time

try:
    import gmsh
except ImportError:
    print(json.dumps({"skipped": "Gmsh's Python package is not installed"}))
    sys.exit(0)

# The far field and the layer growth of the built-in cases (fixtures/cases/*.toml).
FAR_CENTRE, FAR_RADIUS, GROWTH = (0.5, 0.0), 20.0, 1.3
# Target sizes at F = 1: along the walls, and on the far field.
WALL_SIZE, FAR_SIZE = 0.01, 1.0
# The boundary layer's thickness (chords): thicker layers do not fit the 30P30N's gaps
# ("Edge not recovered").
THICKNESS = 0.01
# Gmsh's high-order optimisers, each run only while some element has minSJ <= 0: the
# elastic analogy first, then the optimisation of the scaled Jacobian (which, without
# `General.AbortOnError = 1`, aborts the process on these meshes: "Failed to reach critical
# value"); fast curving leaves as many invalid elements as it found.
OPTIMISERS = ["HighOrderElastic", "HighOrder"]


def read_dat(path):
    """The (x, y) points of a Selig .dat file (the first line is its title)."""
    points = []
    with open(path) as f:
        for line in f.readlines()[1:]:
            parts = line.split()
            if len(parts) >= 2:
                points.append((float(parts[0]), float(parts[1])))
    return points


def wall_loop(points, size):
    """A closed curve loop through `points`: one spline, closed by a segment when the first and
    last points differ (blunt trailing edge). Returns (loop tag, curve tags, corner points)."""
    geo = gmsh.model.geo
    closed = math.dist(points[0], points[-1]) < 1e-12
    if closed:
        points = points[:-1]
    tags = [geo.addPoint(x, y, 0, size) for x, y in points]
    if closed:
        curves = [geo.addSpline(tags + [tags[0]])]
        corners = [tags[0]]
    else:
        curves = [geo.addSpline(tags), geo.addLine(tags[-1], tags[0])]
        corners = [tags[0], tags[-1]]
    return geo.addCurveLoop(curves), curves, corners


def build(dats, first_height, factor):
    """The model: the walls, the far field, the plane surface, the boundary-layer field."""
    gmsh.model.add("bench")
    geo = gmsh.model.geo
    wall_size, far_size = WALL_SIZE * factor, FAR_SIZE * factor
    loops, wall_curves, corners = [], [], []
    for path in dats:
        loop, curves, ends = wall_loop(read_dat(path), wall_size)
        loops.append(loop)
        wall_curves += curves
        corners += ends
    cx, cy = FAR_CENTRE
    centre = geo.addPoint(cx, cy, 0, far_size)
    ring = [
        geo.addPoint(cx + FAR_RADIUS * math.cos(a), cy + FAR_RADIUS * math.sin(a), 0, far_size)
        for a in (0.0, math.pi / 2, math.pi, 3 * math.pi / 2)
    ]
    arcs = [geo.addCircleArc(ring[i], centre, ring[(i + 1) % 4]) for i in range(4)]
    far = geo.addCurveLoop(arcs)
    surface = geo.addPlaneSurface([far] + loops)
    geo.synchronize()
    gmsh.model.addPhysicalGroup(1, wall_curves, name="wall")
    gmsh.model.addPhysicalGroup(1, arcs, name="farfield")
    gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    field = gmsh.model.mesh.field
    bl = field.add("BoundaryLayer")
    field.setNumbers(bl, "CurvesList", wall_curves)
    field.setNumbers(bl, "FanPointsList", corners)
    field.setNumber(bl, "Size", first_height)
    field.setNumber(bl, "Ratio", GROWTH)
    field.setNumber(bl, "Thickness", THICKNESS)
    field.setNumber(bl, "SizeFar", wall_size)
    field.setNumber(bl, "Quads", 1)
    field.setAsBoundaryLayer(bl)


def count_cells():
    """Triangles and quadrangles of the surface mesh, and their tags."""
    types, tags, _ = gmsh.model.mesh.getElements(2)
    return sum(len(t) for t in tags), [t for block in tags for t in block], types


def invalid_elements(tags):
    """Elements whose Gmsh minSJ is <= 0."""
    if not tags:
        return 0
    q = gmsh.model.mesh.getElementQualities(tags, "minSJ")
    return int(sum(1 for v in q if v <= 0.0))


def calibrate(args):
    """The size factor whose linear mesh has about --calibrate cells (untimed)."""
    factor = 1.0
    for _ in range(8):
        gmsh.clear()
        build(args.dat, args.first_height, factor)
        gmsh.model.mesh.generate(2)
        cells, _, _ = count_cells()
        ratio = cells / args.calibrate
        if abs(ratio - 1.0) < 0.04:
            break
        factor *= math.sqrt(ratio)
    print(json.dumps({"size": factor, "cells": cells}))


def mesh(args):
    """The timed run: mesh, P3, the optimiser while needed, the file."""
    start = time.perf_counter()
    build(args.dat, args.first_height, args.size)
    done = []
    try:
        gmsh.model.mesh.generate(2)
        gmsh.model.mesh.setOrder(3)
        cells, tags, _ = count_cells()
        invalid = invalid_elements(tags)
        done.append(["setOrder(3)", invalid])
        for method in OPTIMISERS:
            if invalid == 0:
                break
            gmsh.model.mesh.optimize(method)
            invalid = invalid_elements(tags)
            done.append([method, invalid])
        gmsh.write(args.out)
    except Exception as e:  # Gmsh raises on a failed mesh: report it, as a result
        print(json.dumps({"failed": str(e).splitlines()[0][:200],
                          "seconds": time.perf_counter() - start}))
        return
    print(json.dumps({"cells": cells, "invalid": invalid, "done": done,
                      "seconds": time.perf_counter() - start}))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dat", action="append", required=True)
    p.add_argument("--first-height", type=float, required=True)
    p.add_argument("--size", type=float, default=1.0)
    p.add_argument("--calibrate", type=int)
    p.add_argument("--out")
    args = p.parse_args()
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    # report the optimiser's failures instead of throwing them (see the module's docstring)
    gmsh.option.setNumber("General.AbortOnError", 1)
    try:
        if args.calibrate:
            calibrate(args)
        else:
            mesh(args)
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
