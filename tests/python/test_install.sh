#!/usr/bin/env bash
# Shows that tests/python/install.sh works where pip refuses global installs (PEP 668, the
# `externally-managed-environment` error of Debian's and Ubuntu's own Python): with a python3
# that refuses them first on PATH — Debian's /usr/bin/python3 when it carries the
# EXTERNALLY-MANAGED marker, and PIP_REQUIRE_VIRTUALENV=1 for any Python — a global pip install
# fails, while install.sh makes a fresh virtual environment in a scratch folder, installs the
# pinned checkers there, and PyFR imports a Gmsh-written mesh through check_pyfr.sh.
# Usage: bash tests/python/test_install.sh   (about a minute; needs the network or pip's cache)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

python=$(command -v python3)
marked() {
  [ -f "$("$1" -c 'import sysconfig; print(sysconfig.get_path("stdlib"))')/EXTERNALLY-MANAGED" ]
}
if [ -x /usr/bin/python3 ] && marked /usr/bin/python3; then
  python=/usr/bin/python3
fi
mkdir "$scratch/bin"
ln -s "$python" "$scratch/bin/python3"
export PATH="$scratch/bin:$PATH" PIP_REQUIRE_VIRTUALENV=1
echo "== python3 is $python$(marked "$python" && echo ' (EXTERNALLY-MANAGED)')"

refuse=()
marked "$python" && refuse=(env -u PIP_REQUIRE_VIRTUALENV)
if "${refuse[@]}" python3 -m pip install --dry-run --quiet --disable-pip-version-check six >"$scratch/pip.log" 2>&1; then
  echo "error: pip accepted a global install: nothing refuses it here" >&2
  exit 1
fi
echo "== a global pip install is refused: $(grep -m1 -iE 'error|no module' "$scratch/pip.log")"

export CHECKERS_VENV="$scratch/venv"
bash "$root/tests/python/install.sh"
"$CHECKERS_VENV/bin/python" -c 'import gmsh, vtk, pyfr, sys; assert sys.prefix != sys.base_prefix'
bash "$root/tests/python/check_pyfr.sh" "$root/crates/mesh-io/tests/data/gmsh_ring_p3.msh"
echo "== install.sh works where pip refuses global installs"
