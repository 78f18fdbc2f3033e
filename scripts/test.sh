#!/usr/bin/env bash
# The README's test command (and CI's, through .ci/run): installs what is missing, then builds and
# runs the whole CTest suite (tests, examples, the CLI tool's tests, the documentation, the header
# and install checks) and prints the time of each leg and the total.
#
# By default, one leg: g++ + Debian's CGAL 5.5, Release, benchmarks built too (the inner loop of a
# change). With CI=true (as .ci/run sets it) or WAVEJETS_FULL_MATRIX=1, the whole build matrix:
#   1. g++     + CGAL 5.5 (Debian 12's package; on a newer Debian, that package unpacked)  Release, benchmarks and the Python module (its pytest suite and
#      examples) built too
#   2. clang++ + CGAL 6.1.1         Release, the Python module built too (the benchmarks, not part of
#      the package, are built in leg 1 only); its results of every public function are compared
#      with leg 1's to 1e-12 relative (test_public_api_results); the libFuzzer target (not a test)
#      is built in leg 3 only
#   3. clang++ + CGAL 5.5 (Debian)  AddressSanitizer + UndefinedBehaviorSanitizer, Debug at -O1
#      (clang++ compiles these CGAL-heavy sanitized translation units about 3x faster than g++),
#      with line tables only as debug information (reports keep file:line; about 20% less compile
#      time than -g);
#      without the two compile-only tests of the headers and the installation, which legs 1 and 2 run,
#      and without the Python module (a sanitized extension needs the sanitizer runtimes preloaded
#      into the interpreter; the library functions it calls run sanitized in the C++ tests)
# Leg 2 needs the unmodified CGAL 6.1.1 release: an unpacked folder named by WAVEJETS_CGAL6_DIR, or
# the tarball named by WAVEJETS_CGAL6_TARBALL, or ../shared/deps/CGAL-6.1.1.tar.xz beside the
# clone (a build fallback of this project's own CI; unpacked into build/deps). Without it, leg 2 is
# skipped with a banner, except under CI=true where it is an error. WAVEJETS_SKIP_SANITIZERS=1
# skips leg 3.
# Where ccache is installed, every leg compiles through it (a re-run after a small change then
# recompiles only what the change touches); WAVEJETS_NO_CCACHE=1 turns that off.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
start=$(date +%s)
bash scripts/install_dependencies.sh
summary=""
full_matrix=0
if [ "${CI:-}" = true ] || [ "${WAVEJETS_FULL_MATRIX:-0}" = 1 ]; then full_matrix=1; fi
launcher=()
if [ "${WAVEJETS_NO_CCACHE:-0}" != 1 ] && command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # The tests and benchmarks use precompiled headers: ccache caches their compilations only with
  # these sloppiness settings (its manual, "Precompiled headers").
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
  # Paths below the clone hashed relative to it: two clones share their cached compilations.
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
  echo "ccache: $(command -v ccache) (WAVEJETS_NO_CCACHE=1 compiles without it)"
fi

# run_leg NAME BUILD_DIR [cmake arguments...]: configure, build with 2 jobs, run CTest with 2 jobs
# (without the tests matching $ctest_exclude, when set). The tests write only into their own build
# folders, and the one ordering they need (test_simd_kernels_portable after test_simd_kernels) is a
# CTest fixture, so they may run side by side.
ctest_exclude=""
run_leg() {
  local name="$1" build="$2"
  shift 2
  local leg_start
  leg_start=$(date +%s)
  echo
  echo "=================== $name ==================="
  cmake -S . -B "$build" -DBUILD_TESTING=ON -DWAVEJETS_REQUIRE_TBB=ON ${launcher[@]+"${launcher[@]}"} "$@"
  cmake --build "$build" -j2
  (cd "$build" && ctest --output-on-failure -j2 ${ctest_exclude:+-E "$ctest_exclude"})
  summary="$summary$(printf '%-55s %4d s' "$name" $(($(date +%s) - leg_start)))"$'\n'
}

# The CGAL 6.1.1 release, if at hand: prints the folder holding its CGALConfig.cmake.
find_cgal6() {
  if [ -n "${WAVEJETS_CGAL6_DIR:-}" ]; then
    [ -f "$WAVEJETS_CGAL6_DIR/CGALConfig.cmake" ] || { echo "WAVEJETS_CGAL6_DIR=$WAVEJETS_CGAL6_DIR has no CGALConfig.cmake" >&2; return 1; }
    echo "$WAVEJETS_CGAL6_DIR"; return 0
  fi
  local tarball="${WAVEJETS_CGAL6_TARBALL:-$root/../shared/deps/CGAL-6.1.1.tar.xz}"
  [ -f "$tarball" ] || return 1
  local dest="$root/build/deps"
  local unpacked="$dest/$(basename "$tarball" .tar.xz)"
  if [ ! -f "$unpacked/CGALConfig.cmake" ]; then
    mkdir -p "$dest"
    tar -xJf "$tarball" -C "$dest"
  fi
  [ -f "$unpacked/CGALConfig.cmake" ] || { echo "$tarball did not unpack to $unpacked" >&2; return 1; }
  echo "$unpacked"
}

# CGAL 5.5 for legs 1 and 3: Debian's package where it is 5.5 (Debian 12), else the Debian 12 package
# kept beside the clone (WAVEJETS_CGAL55_DEB, default ../shared/deps/libcgal-dev_5.5.1-2_amd64.deb;
# header-only, unpacked into build/deps with dpkg-deb -x). Sets cgal55_version and cgal55_args.
cgal55_args=()
debian_cgal=$(dpkg-query -W -f='${Version}' libcgal-dev 2>/dev/null | cut -d- -f1)
if [[ "$debian_cgal" == 5.5* ]]; then
  cgal55_version="$debian_cgal (Debian's package)"
else
  deb="${WAVEJETS_CGAL55_DEB:-$root/../shared/deps/libcgal-dev_5.5.1-2_amd64.deb}"
  if [ ! -f "$deb" ]; then
    echo "Debian's CGAL is ${debian_cgal:-missing}, and $deb (CGAL 5.5.1) is not at hand: legs 1 and 3 need CGAL 5.5" >&2
    exit 1
  fi
  unpacked="$root/build/deps/cgal-5.5.1"
  [ -f "$unpacked/usr/lib/x86_64-linux-gnu/cmake/CGAL/CGALConfig.cmake" ] || { mkdir -p "$unpacked" && dpkg-deb -x "$deb" "$unpacked"; }
  cgal55_args=(-DCGAL_DIR="$unpacked/usr/lib/x86_64-linux-gnu/cmake/CGAL")
  cgal55_version="5.5.1 (unpacked from $(basename "$deb"); Debian's is $debian_cgal)"
fi

gcc_build=${WAVEJETS_TEST_BUILD_DIR:-build/test}
run_leg "1. g++ + CGAL $cgal55_version, Release" "$gcc_build" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ -DWAVEJETS_BUILD_BENCHMARKS=ON -DWAVEJETS_REQUIRE_PYTHON=ON \
  ${cgal55_args[@]+"${cgal55_args[@]}"}

if [ $full_matrix = 0 ]; then
  echo
  echo "One leg run (the full matrix: CI=true or WAVEJETS_FULL_MATRIX=1)."
  summary="${summary}2. and 3. (clang++ + CGAL 6.1.1; sanitizers)            not run (one-leg run)"$'\n'
elif cgal6=$(find_cgal6); then
  run_leg "2. clang++ + CGAL $(cat "$cgal6/VERSION" 2>/dev/null || echo 6.1.1), Release" "${WAVEJETS_CLANG_BUILD_DIR:-build/clang-cgal6}" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DCGAL_DIR="$cgal6" -DWAVEJETS_BUILD_BENCHMARKS=OFF \
    -DWAVEJETS_BUILD_LIBFUZZER=OFF -DWAVEJETS_REQUIRE_PYTHON=ON \
    -DWAVEJETS_REFERENCE_RESULTS="$root/$gcc_build/test/Wavejets/public_api_results.txt"
else
  echo
  echo "##########################################################################################"
  echo "## SKIPPED: leg 2 (clang++ + CGAL 6.1.1). The CGAL 6.1.1 release is not at hand: set     ##"
  echo "## WAVEJETS_CGAL6_DIR (unpacked) or WAVEJETS_CGAL6_TARBALL, or put ../shared/deps beside. ##"
  echo "##########################################################################################"
  if [ "${CI:-}" = true ]; then echo "CI must run every leg of the matrix." >&2; exit 1; fi
  summary="${summary}2. clang++ + CGAL 6.1.1                                 SKIPPED (release not at hand)"$'\n'
fi

if [ $full_matrix = 0 ]; then
  :
elif [ "${WAVEJETS_SKIP_SANITIZERS:-0}" != 1 ]; then
  # Every UBSan finding and every leak is fatal, except the findings in third-party headers listed
  # (with the reason) in scripts/ubsan_suppressions.txt: UBSan checks are built recoverable so that
  # a suppression can skip a report, and halt_on_error=1 stops the run at any other one. Benchmarks
  # and the documentation are off (doxygen runs no code of the package), and of the examples only
  # the two workflows (each *_example.cpp calls one function that the tests run sanitized; the
  # six cost about 6 x 2 min of sanitized compilation). test_fuzz runs 100000 real fits instead
  # of 1e6 under sanitizers.
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$root/scripts/ubsan_suppressions.txt"
  ctest_exclude="^(wavejets_headers_self_contained|wavejets_install_and_consume)$"
  run_leg "3. clang++ + CGAL $cgal55_version, ASan + UBSan (Debug -O1)" "${WAVEJETS_ASAN_BUILD_DIR:-build/asan}" \
    ${cgal55_args[@]+"${cgal55_args[@]}"} \
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-gline-tables-only -DCMAKE_CXX_COMPILER=clang++ \
    -DWAVEJETS_TESTS_ONLY=OFF -DWAVEJETS_BUILD_BENCHMARKS=OFF \
    -DWAVEJETS_EXAMPLES=workflows -DWAVEJETS_BUILD_PYTHON=OFF \
    -DCMAKE_DISABLE_FIND_PACKAGE_Doxygen=ON \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fsanitize-recover=undefined -O1"
else
  summary="${summary}3. clang++ + CGAL 5.5, ASan + UBSan                     SKIPPED (WAVEJETS_SKIP_SANITIZERS=1)"$'\n'
fi

echo
echo "=================== all legs run passed ==================="
printf '%s' "$summary"
echo "total (with the installation check): $(($(date +%s) - start)) s"
