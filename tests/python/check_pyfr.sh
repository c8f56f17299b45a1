#!/usr/bin/env bash
# Imports .msh files with PyFR (`pyfr import`) and fails if PyFR refuses one, or if the
# imported mesh lacks a `wall` or `farfield` boundary or has no element.
#
# Usage: tests/python/check_pyfr.sh MESH.msh...
# Needs: apt-get install -y libopenmpi3 (Debian 12; the name may differ elsewhere, e.g.
#        libopenmpi3t64), then pip install pyfr (3.1 tested); h5py comes with PyFR.
set -euo pipefail
if [ "$#" -eq 0 ]; then
    sed -n '2,8p' "$0"
    exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0
for msh in "$@"; do
    out="$tmp/$(basename "${msh%.msh}").pyfrm"
    if ! pyfr import "$msh" "$out" >"$tmp/log" 2>&1; then
        echo "FAIL $msh: pyfr import failed:"
        cat "$tmp/log"
        status=1
        continue
    fi
    if ! python3 - "$out" <<'PY'
import collections, sys
import h5py
f = h5py.File(sys.argv[1], "r")
codec = [c.decode() for c in f["codec"][()]]
faces = collections.Counter()
elements = {}
for kind in f["eles"]:
    e = f["eles"][kind][()]
    elements[kind] = (len(e), int(e["curved"].sum()))
    for row in e["faces"]:
        for face in row:
            faces[codec[face["cidx"]]] += 1
bcs = {k[3:]: v for k, v in faces.items() if k.startswith("bc/")}
print(f"ok {sys.argv[1]}: elements (count, curved) {elements}, boundary faces {bcs}")
missing = [b for b in ("wall", "farfield") if not bcs.get(b)]
sys.exit(1 if missing or not elements else 0)
PY
    then
        echo "FAIL $msh: imported mesh lacks elements or a wall/farfield boundary"
        status=1
    fi
done
exit $status
