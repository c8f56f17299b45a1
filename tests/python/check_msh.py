#!/usr/bin/env python3
"""Independent check of .msh files with Gmsh's own reader.

Usage: python3 tests/python/check_msh.py MESH.msh...      (needs: pip install gmsh)

Prints one JSON line per file: node count, element counts per Gmsh element type name
("Triangle 6", ...), the element types with their dimension, order and node count, the physical
groups (dim, tag, name, element count), the minimum over all 2D/3D elements of Gmsh's scaled
Jacobian (`minSJ` from gmsh.model.mesh.getElementQualities), and the area (2D) or volume (3D)
that Gmsh integrates from its own Jacobians of the curved elements. Gmsh 4.15 reads the 40-node
prism (type 90) but evaluates nothing of it ("FaceClosureFull not implemented for prisms of
order 3", from getElementProperties, getElementQualities and getJacobians alike): its elements are
counted, and listed under "unmeasured" with no minSJ or volume of theirs (a file with them gives
no volume). A file Gmsh cannot read (or reports an error while reading) gives a line with an
"error" key; the exit status is then 1.
"""
import json
import sys

import gmsh
import numpy as np

# Gmsh's Gauss rule exact to degree 12: the Jacobian determinant of a cubic quadrilateral is of
# degree 5 in each variable (10 in all), of a cubic triangle 4, so the integral is exact.
QUADRATURE = "Gauss12"
# Linear cells: det J is constant on a tetrahedron and of degree 2 in each variable on a
# prism, hexahedron or pyramid, so Gauss4 is exact. It matters in 3D: getJacobians returns
# every point's matrix and position, and Gauss12 has 210 points on a tetrahedron (about 20 KB
# per element: the 505 000-tetrahedron wing would need 10 GB).
QUADRATURE_LINEAR = "Gauss4"
# Element types Gmsh reads but cannot evaluate: (name, order, nodes).
UNMEASURED = {90: ("Prism 40", 3, 40)}


def measure(etype, order):
    """Sum over all elements of one type of the integral of det J (area in 2D, volume in 3D),
    from Gmsh's Jacobians at Gmsh's own Gauss points; signed, so an inverted cell lowers it."""
    rule = QUADRATURE_LINEAR if order == 1 else QUADRATURE
    uvw, weights = gmsh.model.mesh.getIntegrationPoints(etype, rule)
    _, det, _ = gmsh.model.mesh.getJacobians(etype, uvw)
    det = np.asarray(det).reshape(-1, len(weights))
    return float((det @ np.asarray(weights)).sum())


def read(path):
    """The summary of one file, as a dict (see the module doc)."""
    gmsh.clear()
    gmsh.logger.stop()
    gmsh.logger.start()
    try:
        gmsh.open(path)
    except Exception as e:  # Gmsh raises on a read error
        return {"file": path, "error": str(e), "log": gmsh.logger.get()}
    log = gmsh.logger.get()
    errors = [l for l in log if l.startswith("Error")]
    if errors:
        return {"file": path, "error": errors}

    node_tags, _, _ = gmsh.model.mesh.getNodes()
    counts, types = {}, []
    min_sj, area, unmeasured = None, 0.0, []
    top = max((d for d in (1, 2, 3) if len(gmsh.model.mesh.getElements(d)[0])), default=0)
    for dim in (1, 2, 3):
        etypes, tags, _ = gmsh.model.mesh.getElements(dim)
        for t, ts in zip(etypes, tags):
            if t in UNMEASURED:
                name, order, nodes = UNMEASURED[t]
                unmeasured.append(name)
            else:
                name, _, order, nodes, _, _ = gmsh.model.mesh.getElementProperties(t)
            counts[name] = counts.get(name, 0) + len(ts)
            types.append({"name": name, "dim": dim, "order": order, "nodes": nodes,
                          "count": len(ts)})
            if t in UNMEASURED:
                continue
            if dim >= 2 and len(ts):
                q = gmsh.model.mesh.getElementQualities(ts, "minSJ")
                m = float(min(q))
                min_sj = m if min_sj is None else min(min_sj, m)
            if dim == top and dim >= 2:
                area += measure(t, order)
    groups = []
    for dim, tag in gmsh.model.getPhysicalGroups():
        n = 0
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            _, tags, _ = gmsh.model.mesh.getElements(dim, ent)
            n += sum(len(t) for t in tags)
        groups.append({"dim": dim, "tag": tag,
                       "name": gmsh.model.getPhysicalName(dim, tag), "elements": n})
    warnings = [l for l in log if l.startswith("Warning")]
    measured = {} if unmeasured else {"area" if top == 2 else "volume": area}
    return {"file": path, "nodes": len(node_tags), "elements": counts, "element_types": types,
            "physical_groups": groups, "min_scaled_jacobian": min_sj, "unmeasured": unmeasured,
            **measured, "warnings": warnings}


def main(paths):
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    status = 0
    for path in paths:
        out = read(path)
        status |= "error" in out
        print(json.dumps(out), flush=True)
    gmsh.finalize()
    return int(status)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1:]))
