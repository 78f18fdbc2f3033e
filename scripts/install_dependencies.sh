#!/usr/bin/env bash
# Installs the Debian packages the package builds on, if any is missing (run as root).
# doxygen builds the documentation and runs its test (wavejets_documentation: no warning allowed), and
# libjs-mathjax typesets its formulas offline (its files are copied into the built manual);
# clang is the compiler of the CGAL 6.1.1 leg of scripts/test.sh; xz-utils unpacks that release;
# ccache lets a re-run of scripts/test.sh recompile only what changed.
# The Python module (python/) builds with pybind11 against Debian's python3 and NumPy; its tests run
# with pytest; python3-venv serves the offline install (scripts/install_python.sh); wavejets.distributed
# (the streamed steps as Dask tasks) and its tests use python3-dask and python3-distributed.
set -euo pipefail
packages="g++ clang cmake make ccache xz-utils libcgal-dev libeigen3-dev libtbb-dev libboost-dev libpng-dev doxygen
  libjs-mathjax python3-dev python3-venv python3-numpy pybind11-dev python3-pybind11 python3-pytest python3-dask
  python3-distributed"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "Installing missing Debian packages:$missing"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q $missing
fi
