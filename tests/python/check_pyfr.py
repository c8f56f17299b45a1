#!/usr/bin/env python3
"""Independent check of .msh files with PyFR: `pyfr import` each file into PyFR's own mesh
format, then read what PyFR made of it with h5py.

Usage: python3 tests/python/check_pyfr.py MESH.msh...
Needs: apt-get install libopenmpi3 (Debian 12; libopenmpi3t64 on later releases), then
       pip install pyfr (h5py comes with it); tests/python/install.sh does both.

Prints one JSON line per file: per PyFR element kind ("tri", "quad", ...) the number of
elements, how many PyFR marks curved (their high-order nodes off the linear element by more
than its linearisation tolerance) and the nodes per element (6 for a P2 triangle, 16 for a P3
quadrilateral), and the number of faces on each boundary. Exits 1 if PyFR refuses a file, or
an imported mesh has no element or lacks a boundary (see `problems`: by default `farfield` and
at least one other, a wall body; e2e.py names every group of the report).
"""
import collections
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def read(path):
    """Imports one file with `pyfr import` and returns its summary as a dict; on failure, a dict
    with an "error" key holding PyFR's output."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "mesh.pyfrm")
        # `python -m pyfr`: the PyFR of this interpreter, found whether or not its script is on PATH
        r = subprocess.run([sys.executable, "-m", "pyfr", "import", path, out],
                           capture_output=True, text=True)
        if r.returncode != 0:
            return {"file": path, "error": f"pyfr import exit {r.returncode}: "
                                           f"{(r.stdout + r.stderr).strip()[-2000:]}"}
        with h5py.File(out, "r") as f:
            codec = [c.decode() for c in f["codec"][()]]
            faces = collections.Counter()
            elements = {}
            for kind in f["eles"]:
                e = f["eles"][kind][()]
                elements[kind] = {"count": len(e), "curved": int(e["curved"].sum()),
                                  "nodes_per_element": int(e["nodes"].shape[-1])}
                cidx, counts = np.unique(e["faces"]["cidx"], return_counts=True)
                for c, n in zip(cidx.tolist(), counts.tolist()):
                    faces[codec[c]] += n
    boundaries = {k[3:]: v for k, v in faces.items() if k.startswith("bc/")}
    return {"file": path, "elements": elements, "boundaries": boundaries}


def problems(summary, boundaries=None):
    """What makes an imported mesh unusable: PyFR refused it, it has no element, or no face on
    one of `boundaries` (each wall body and `farfield`; a mesh of the inside of a wall loop has
    no far field). Without `boundaries`: `farfield` and at least one wall boundary."""
    if "error" in summary:
        return [summary["error"]]
    out = [] if summary["elements"] else ["no element"]
    found = summary["boundaries"]
    if boundaries is None:
        out += [] if found.get("farfield") else ["no farfield boundary"]
        out += [] if any(n for b, n in found.items() if b != "farfield") else ["no wall boundary"]
    else:
        out += [f"no {b} boundary" for b in boundaries if not found.get(b)]
    return out


def main(paths):
    status = 0
    for path in paths:
        out = read(path)
        bad = problems(out)
        status |= bool(bad)
        print(json.dumps(out), flush=True)
        for p in bad:
            print(f"FAIL {path}: {p}", file=sys.stderr)
    return int(status)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1:]))
