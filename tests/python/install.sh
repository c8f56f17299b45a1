#!/usr/bin/env bash
# Installs the independent checkers the end-to-end tests use: Gmsh's Python package (reads our
# .msh and measures its own scaled Jacobian) and the system libraries its wheel loads.
# Idempotent: a second run does nothing that is already done.
set -euo pipefail

libs="libglu1-mesa libgl1 libxrender1 libxcursor1 libxfixes3 libxext6 libxft2 libfontconfig1 libxinerama1 libx11-6 libgomp1"
missing=""
for p in $libs; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "== apt-get install$missing"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

if ! python3 -c "import gmsh" >/dev/null 2>&1; then
  echo "== pip install gmsh"
  python3 -m pip install --quiet --disable-pip-version-check -r tests/python/requirements.txt
fi
python3 -c "import gmsh; print('gmsh', gmsh.__version__)"
