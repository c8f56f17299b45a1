# Sourced by the scripts that run the checkers: sets CHECKERS_VENV (the virtual environment
# tests/python/install.sh makes, `.venv-checkers/` at the repository root unless the variable is
# set) and CHECKERS_PYTHON (its interpreter). The checkers never use a global Python, so the
# tests work where pip refuses global installs (PEP 668: Debian's and Ubuntu's own Python).
CHECKERS_VENV="${CHECKERS_VENV:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/.venv-checkers}"
CHECKERS_PYTHON="$CHECKERS_VENV/bin/python"
require_checkers() {
  if [ ! -x "$CHECKERS_PYTHON" ]; then
    echo "error: no checkers' virtual environment at $CHECKERS_VENV: run bash tests/python/install.sh" >&2
    exit 1
  fi
}
