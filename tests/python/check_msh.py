#!/usr/bin/env python3
"""Independent check of a .msh file with Gmsh's own reader.

Usage: python3 tests/python/check_msh.py MESH.msh      (needs: pip install gmsh)

Prints one JSON line: node count, element counts per Gmsh element type name, the physical
groups (dim, tag, name, element count), and the minimum over all 2D/3D elements of Gmsh's
scaled Jacobian (`minSJ` from gmsh.model.mesh.getElementQualities). Exits 1 if Gmsh cannot
read the file (or reports an error while reading it).
"""
import json
import sys

import gmsh


def main(path):
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    try:
        gmsh.open(path)
    except Exception as e:  # Gmsh raises on a read error
        print(json.dumps({"file": path, "error": str(e), "log": gmsh.logger.get()}))
        return 1
    log = gmsh.logger.get()
    errors = [l for l in log if l.startswith("Error")]
    if errors:
        print(json.dumps({"file": path, "error": errors}))
        return 1

    node_tags, _, _ = gmsh.model.mesh.getNodes()
    counts = {}
    min_sj = None
    for dim in (1, 2, 3):
        types, tags, _ = gmsh.model.mesh.getElements(dim)
        for t, ts in zip(types, tags):
            name = gmsh.model.mesh.getElementProperties(t)[0]
            counts[name] = counts.get(name, 0) + len(ts)
            if dim >= 2 and len(ts):
                q = gmsh.model.mesh.getElementQualities(ts, "minSJ")
                m = float(min(q))
                min_sj = m if min_sj is None else min(min_sj, m)
    groups = []
    for dim, tag in gmsh.model.getPhysicalGroups():
        n = 0
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            _, tags, _ = gmsh.model.mesh.getElements(dim, ent)
            n += sum(len(t) for t in tags)
        groups.append({"dim": dim, "tag": tag,
                       "name": gmsh.model.getPhysicalName(dim, tag), "elements": n})
    warnings = [l for l in log if l.startswith("Warning")]
    print(json.dumps({"file": path, "nodes": len(node_tags), "elements": counts,
                      "physical_groups": groups, "min_scaled_jacobian": min_sj,
                      "warnings": warnings}))
    gmsh.finalize()
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
