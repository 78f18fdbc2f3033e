#!/usr/bin/env bash
# Installs the Python module `wavejets` offline on Debian: Debian's /usr/bin/python3 (not another
# python3 first on PATH), a virtual environment that sees Debian's NumPy and pybind11
# (--system-site-packages), and `pip install --no-build-isolation ./python` (no PyPI needed).
#   bash scripts/install_python.sh [VENV]      (default VENV: build/venv)
# then: VENV/bin/python -c "import wavejets". Where PyPI is reachable, `pip install ./python` works too.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="${1:-$root/build/venv}"
bash "$root/scripts/install_dependencies.sh"
/usr/bin/python3 -m venv --system-site-packages "$venv"
"$venv/bin/python" -m pip install --no-build-isolation --no-index --quiet "$root/python"
"$venv/bin/python" -c "import wavejets; print('wavejets', wavejets.__version__, 'installed in $venv')"
