#!/usr/bin/env bash
# The project's test command (README): installs the independent checkers (Gmsh's Python package
# and the system libraries it loads), runs every Rust test, then has Gmsh read the meshes our
# pipeline writes for every built-in case.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tests/python/install.sh

echo "== cargo test"
cargo test --workspace --quiet

echo "== end-to-end: Gmsh reads what we write"
bash tests/python/e2e.sh
