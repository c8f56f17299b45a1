#!/usr/bin/env bash
# Installs the independent checkers the end-to-end tests use (tests/python/requirements.txt):
# Gmsh's, VTK's and meshio's Python packages and PyFR, and the Debian libraries their wheels load (Gmsh's
# GUI libraries, Open MPI for PyFR's mpi4py). The Python packages go into a virtual environment,
# `.venv-checkers/` at the repository root (git-ignored; CHECKERS_VENV overrides the place), made
# with `python3 -m venv` — Debian's python3-venv is installed when venv or ensurepip is missing —
# so this works where pip refuses global installs (PEP 668). Idempotent: a second run installs
# nothing. A fresh install takes about 25 s here (apt about 5 s, pip about 20 s without its cache).
set -euo pipefail
cd "$(dirname "$0")"
source ./venv.sh

SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
updated=""
apt_update() {
  [ -n "$updated" ] || $SUDO apt-get update -qq
  updated=1
}

libs="libglu1-mesa libgl1 libxrender1 libxcursor1 libxfixes3 libxext6 libxft2 libfontconfig1 libxinerama1 libx11-6 libgomp1"
missing=""
for p in $libs; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
# Open MPI's runtime is libopenmpi3 on Debian 12; later releases renamed it libopenmpi3t64.
if ! dpkg -s libopenmpi3 >/dev/null 2>&1 && ! dpkg -s libopenmpi3t64 >/dev/null 2>&1; then
  apt_update
  # (captured first: grep -q closing the pipe early would fail the pipeline under pipefail)
  policy=$(apt-cache policy libopenmpi3 2>/dev/null || true)
  if [[ "$policy" == *"Candidate: "[0-9]* ]]; then
    missing="$missing libopenmpi3"
  else
    missing="$missing libopenmpi3t64"
  fi
fi
if [ -n "$missing" ]; then
  echo "== apt-get install$missing"
  apt_update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

# The virtual environment, made by the first python3 on PATH.
if ! "$CHECKERS_PYTHON" -c 'import pip' >/dev/null 2>&1; then
  if ! python3 -c 'import venv, ensurepip' >/dev/null 2>&1; then
    echo "== apt-get install python3-venv (python3 has no venv or ensurepip)"
    apt_update
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends python3-venv >/dev/null
  fi
  echo "== python3 -m venv $CHECKERS_VENV"
  python3 -m venv --clear "$CHECKERS_VENV"
fi

# pip only when some pinned package is missing or at another version.
if ! "$CHECKERS_PYTHON" - requirements.txt <<'PY'
import sys
from importlib.metadata import PackageNotFoundError, version

for line in open(sys.argv[1]):
    line = line.split("#")[0].strip()
    if not line:
        continue
    name, want = line.split("==")
    try:
        have = version(name)
    except PackageNotFoundError:
        have = None
    if have != want:
        sys.exit(1)
PY
then
  echo "== pip install -r tests/python/requirements.txt"
  "$CHECKERS_PYTHON" -m pip install --quiet --disable-pip-version-check -r requirements.txt
fi
"$CHECKERS_PYTHON" - <<'PY'
from importlib.metadata import version

import gmsh
import meshio
import vtk

print("checkers:", ", ".join(f"{n} {version(n)}" for n in
                             ("gmsh", "vtk", "meshio", "pyfr", "h5py", "numpy", "mpi4py")))
PY
"$CHECKERS_PYTHON" -m pyfr --version
