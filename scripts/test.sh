#!/usr/bin/env bash
# Installs what is missing, builds the tests and examples (assertions on), runs them with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
build=${WAVEJETS_TEST_BUILD_DIR:-build/test}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DWAVEJETS_BUILD_BENCHMARKS=OFF
cmake --build "$build" -j2
cd "$build" && ctest --output-on-failure
