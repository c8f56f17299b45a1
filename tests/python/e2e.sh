#!/usr/bin/env bash
# Builds the release tool and runs the end-to-end checks with Gmsh's, VTK's and PyFR's own
# readers (tests/python/e2e.py).
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet -p xtask
target_dir=$(cargo metadata --format-version 1 --no-deps | python3 -c "import json,sys; print(json.load(sys.stdin)['target_directory'])")
python3 tests/python/e2e.py "$target_dir/release/xtask"
