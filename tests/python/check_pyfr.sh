#!/usr/bin/env bash
# Imports .msh files with PyFR (`pyfr import`) and fails if PyFR refuses one, or if the
# imported mesh lacks a `wall` or `farfield` boundary or has no element. The checks live in
# check_pyfr.py (also used by e2e.py); this is its command-line front.
#
# Usage: tests/python/check_pyfr.sh MESH.msh...
# Needs: what tests/python/install.sh installs (Debian's libopenmpi3, PyFR from PyPI in the
# checkers' virtual environment).
set -euo pipefail
if [ "$#" -eq 0 ]; then
    sed -n '2,8p' "$0"
    exit 2
fi
source "$(dirname "$0")/venv.sh"
require_checkers
exec "$CHECKERS_PYTHON" "$(dirname "$0")/check_pyfr.py" "$@"
