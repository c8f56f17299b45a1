#!/usr/bin/env bash
# Builds the Python package (python/: the pyo3 extension by maturin, release) into a virtual
# environment, `.venv-python/` at the repository root (git-ignored; PYTHON_VENV overrides the
# place), and runs its tests (python/tests, pytest): the 30P30N at P3 read back by Gmsh and
# meshio, dict cases, a flap move whose sensitivities are the command line's CSV, the errors, and
# the user guide's Python examples (the first imports its airfoil into PyFR).
#
# Usage: bash python/test.sh [PYTEST ARGUMENTS...]
# Needs: the Rust toolchain and python3. The system libraries Gmsh's and PyFR's wheels load come
# from tests/python/install.sh (idempotent; it also makes the checkers' environment), the Python
# packages from pip (python/requirements-test.txt, pinned). The extension is built in the
# workspace's target/ (CARGO_TARGET_DIR overrides it), so a later run compiles only what changed
# (seconds when nothing did). Its first build compiles the crates once more in release — pyo3's
# macros give the shared proc-macro crates other features than the command line's build, so
# almost none of its artifacts can be reused: 6 min 20 s on a busy two-core machine, where the
# command line's own cold release build took 11 min.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv="${PYTHON_VENV:-$root/.venv-python}"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"

bash tests/python/install.sh

if ! "$venv/bin/python" -c 'import pip' >/dev/null 2>&1; then
  echo "== python3 -m venv $venv"
  python3 -m venv --clear "$venv"
fi
echo "== pip install -r python/requirements-test.txt"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r python/requirements-test.txt

echo "== the curvemesh command the tests compare with (cargo build --release -p curvemesh-cli)"
cargo build --release --quiet -p curvemesh-cli --bin curvemesh

echo "== cargo fmt --check (python/, outside the workspace)"
cargo fmt --manifest-path python/Cargo.toml --check

echo "== pip install ./python (maturin, release)"
start=$SECONDS
# the pinned maturin of the environment (on PATH for pip's build backend), not one from PyPI
PATH="$venv/bin:$PATH" "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-build-isolation --force-reinstall --no-deps ./python
echo "   built and installed in $((SECONDS - start)) s"

echo "== pytest python/tests"
CURVEMESH_CLI="$CARGO_TARGET_DIR/release/curvemesh" "$venv/bin/python" -m pytest -q -rs \
    python/tests "$@"
