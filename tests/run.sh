#!/usr/bin/env bash
# The project's test command (README): installs the independent checkers (Gmsh's and VTK's
# Python packages, PyFR, and the system libraries they load), runs every Rust test (doctests
# included) and the standalone example project (examples/standalone), then has Gmsh, VTK and
# PyFR read the meshes our pipeline writes for every built-in case at orders 1-3, and builds and
# tests the Python package (python/test.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
# no incremental compilation caches: a run of the whole suite builds every crate once, and the
# caches would be the largest part of target/ (CARGO_INCREMENTAL=1 keeps them)
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"

bash tests/python/install.sh

# built first with cargo's progress shown (the first build of the test profile takes minutes),
# then run with one line per test binary
echo "== cargo test: building the tests"
cargo test --workspace --no-run
echo "== cargo test"
cargo test --workspace --quiet

# A project outside the workspace that uses the crates by path, with its own Cargo.lock: a crate
# that only works inside this workspace (a workspace-only dependency, a test helper, a fixture
# path) fails here. It meshes a NACA 0012, curves it to P3, certifies every cell, writes a .msh.
echo "== examples/standalone: the crates used from outside the workspace"
mkdir -p target/standalone
CARGO_TARGET_DIR="$PWD/target" cargo run --locked --quiet \
    --manifest-path examples/standalone/Cargo.toml -- \
    target/standalone/naca0012.msh

echo "== end-to-end: Gmsh, VTK and PyFR read what we write"
bash tests/python/e2e.sh

echo "== python: the Python package built into .venv-python/ and tested (python/test.sh)"
bash python/test.sh
