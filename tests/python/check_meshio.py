#!/usr/bin/env python3
"""Independent check of .vtu and .su2 files with meshio, the reader most Python pipelines use to
convert meshes (its own XML and SU2 readers, not VTK's).

Usage: python3 tests/python/check_meshio.py MESH.vtu|MESH.su2...   (needs: pip install meshio)

Prints one JSON line per file: the number of points, the domain cells by VTK type id (meshio's
cell types mapped back to VTK's ids, so they compare with check_vtu.py's), the point counts of
the cells of each type, the number of distinct corner points of the domain cells (2D), and the
boundary facets counted per boundary group, by name:
- .vtu: the facets are the cells with cell data `boundary_group` >= 0, an index into the group
  names, which the field data holds as one numeric array `boundary_group:NAME` per group
  (holding the index); meshio refuses a file with any non-numeric field data, such as VTK's
  string arrays, and "field_data" lists what it read;
- .su2: meshio reads each marker's facets with cell data `su2:tag` 1, 2, ... in the file's
  order (it replaces the marker names by numbers): they are named by the file's MARKER_TAG
  lines, in the same order; the domain cells have tag 0.
meshio exits the process (sys.exit) on a file it cannot read: that is caught, and the file
gives a line with an "error" key; the exit status is then 1.
"""
import collections
import contextlib
import io
import json
import sys

import meshio
import numpy as np
from meshio._vtk_common import meshio_to_vtk_type

GROUP_PREFIX = "boundary_group:"  # the field data naming a boundary group (mesh_io::vtu)
# the corners of a cell come first in VTK's ordering (linear and Lagrange cells alike)
CORNERS = {"triangle": 3, "quad": 4, "VTK_LAGRANGE_TRIANGLE": 3,
           "VTK_LAGRANGE_QUADRILATERAL": 4}


def marker_names(path):
    """The MARKER_TAG names of an .su2 file, in order."""
    with open(path) as f:
        return [line.split("=", 1)[1].strip() for line in f
                if line.strip().startswith("MARKER_TAG")]


def read(path):
    """The summary of one file, as a dict (see the module doc)."""
    said = io.StringIO()
    try:
        with contextlib.redirect_stdout(said):  # meshio prints its ReadError before exiting
            mesh = meshio.read(path)
    except (SystemExit, Exception) as e:  # noqa: BLE001  (meshio exits on a file it refuses)
        return {"file": path, "error": f"meshio could not read the file: "
                                       f"{said.getvalue().strip()[-500:]} {e!r}"}
    if path.endswith(".vtu"):
        tag_name, domain = "boundary_group", -1
        names = {int(v.ravel()[0]): k[len(GROUP_PREFIX):]
                 for k, v in mesh.field_data.items() if k.startswith(GROUP_PREFIX)}
    else:
        tag_name, domain = "su2:tag", 0
        names = dict(enumerate(marker_names(path), start=1))
    types, points_per_cell, groups = collections.Counter(), collections.defaultdict(set), \
        collections.Counter()
    corners = set()
    for block, tags in zip(mesh.cells, mesh.cell_data[tag_name]):
        tags = np.asarray(tags).ravel()
        inside = tags == domain
        n_inside = int(inside.sum())
        if n_inside:
            vtk_id = str(meshio_to_vtk_type[block.type])
            types[vtk_id] += n_inside
            points_per_cell[vtk_id].add(int(block.data.shape[1]))
            if block.type in CORNERS:
                corners.update(np.unique(block.data[inside][:, :CORNERS[block.type]]).tolist())
        for k, n in collections.Counter(tags[~inside].tolist()).items():
            groups[names.get(int(k), f"unnamed {k}")] += n
    return {"file": path, "points": len(mesh.points),
            "cells": sum(types.values()),
            "types": dict(sorted(types.items())),
            "points_per_cell": {k: sorted(v) for k, v in sorted(points_per_cell.items())},
            "corners": len(corners),
            "boundary_groups": dict(sorted(groups.items())),
            "field_data": sorted(mesh.field_data)}


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
