#!/usr/bin/env bash
# Installs what is missing, builds the tests, examples and the CLI tool (assertions on in the tests)
# in Release, runs the whole CTest suite; then builds and runs the same suite (without the
# documentation test) with AddressSanitizer + UndefinedBehaviorSanitizer. Both require TBB
# (WAVEJETS_REQUIRE_TBB). WAVEJETS_SKIP_SANITIZERS=1 skips the second build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
build=${WAVEJETS_TEST_BUILD_DIR:-build/test}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DWAVEJETS_BUILD_BENCHMARKS=OFF -DWAVEJETS_REQUIRE_TBB=ON
cmake --build "$build" -j2
(cd "$build" && ctest --output-on-failure)

if [ "${WAVEJETS_SKIP_SANITIZERS:-0}" != 1 ]; then
  # The whole CTest suite again (tests, examples, the CLI tool's tests with its renderer), built
  # with AddressSanitizer + UndefinedBehaviorSanitizer, Debug at -O1; benchmarks off and the
  # documentation off (doxygen runs no code of the package). Every UBSan finding and every leak is
  # fatal. test_fuzz runs 100000 real fits instead of 1e6 under sanitizers (see test_fuzz.cpp).
  asan=${WAVEJETS_ASAN_BUILD_DIR:-build/asan}
  cmake -S . -B "$asan" -DCMAKE_BUILD_TYPE=Debug -DBUILD_TESTING=ON -DWAVEJETS_TESTS_ONLY=OFF \
    -DWAVEJETS_BUILD_BENCHMARKS=OFF -DCMAKE_DISABLE_FIND_PACKAGE_Doxygen=ON -DWAVEJETS_REQUIRE_TBB=ON \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -O1"
  cmake --build "$asan" -j2
  (cd "$asan" && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure)
fi
