#!/usr/bin/env bash
# The project's test command (README): installs the independent checkers (Gmsh's and VTK's
# Python packages, PyFR, and the system libraries they load), runs every Rust test, then has
# Gmsh, VTK and PyFR read the meshes our pipeline writes for every built-in case at orders 1-3.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tests/python/install.sh

echo "== cargo test"
cargo test --workspace --quiet

echo "== end-to-end: Gmsh, VTK and PyFR read what we write"
bash tests/python/e2e.sh
