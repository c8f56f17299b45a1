#!/usr/bin/env bash
# Builds the release tool (the `curvemesh` binary) and runs the end-to-end checks with Gmsh's,
# VTK's, PyFR's and meshio's own readers (tests/python/e2e.py), and the 3D meshes cut by topo-cut (example cut3d), in the
# checkers' virtual environment (tests/python/install.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
source tests/python/venv.sh
require_checkers
cargo build --release --quiet -p curvemesh-cli --bin curvemesh
# the 3D meshes cut by topo-cut, written by an example of the end-to-end crate
cargo build --release --quiet -p end-to-end --example cut3d
target_dir=$(cargo metadata --format-version 1 --no-deps | "$CHECKERS_PYTHON" -c "import json,sys; print(json.load(sys.stdin)['target_directory'])")
"$CHECKERS_PYTHON" tests/python/e2e.py "$target_dir/release/curvemesh" "$target_dir/release/examples/cut3d"
