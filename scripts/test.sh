#!/usr/bin/env bash
# Installs what is missing, builds the tests and examples (assertions on), runs them with CTest;
# then builds the tests alone with AddressSanitizer + UndefinedBehaviorSanitizer and runs them.
# WAVEJETS_SKIP_SANITIZERS=1 skips the second build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
build=${WAVEJETS_TEST_BUILD_DIR:-build/test}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DWAVEJETS_BUILD_BENCHMARKS=OFF -DWAVEJETS_REQUIRE_TBB=ON
cmake --build "$build" -j2
(cd "$build" && ctest --output-on-failure)

if [ "${WAVEJETS_SKIP_SANITIZERS:-0}" != 1 ]; then
  # Tests only (WAVEJETS_TESTS_ONLY: no examples, demo or benchmarks), Debug at -O1. Every UBSan
  # finding is fatal; test_fuzz runs fewer fits under sanitizers (100000, see test_fuzz.cpp).
  asan=${WAVEJETS_ASAN_BUILD_DIR:-build/asan}
  cmake -S . -B "$asan" -DCMAKE_BUILD_TYPE=Debug -DBUILD_TESTING=ON -DWAVEJETS_TESTS_ONLY=ON \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -O1"
  cmake --build "$asan" -j2
  (cd "$asan" && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest -L wavejets_test --output-on-failure)
fi
