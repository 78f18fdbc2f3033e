// libFuzzer target for the Wavejets package (clang only; CMake builds it when the compiler accepts
// -fsanitize=fuzzer). The fuzzer's bytes drive the same harness as test_fuzz.cpp: the first byte
// picks Wavejet_fitting or a point-set function, the rest feeds the random choices (neighborhood
// structure, size, scale, NaN injection, order, options, parameters). Any check failure aborts.
//
//   cmake -S . -B build/fuzz -DCMAKE_CXX_COMPILER=clang++ -DWAVEJETS_TESTS_ONLY=ON
//   cmake --build build/fuzz --target wavejets_libfuzzer
//   build/fuzz/test/Wavejets/wavejets_libfuzzer -max_total_time=60 -rss_limit_mb=4096

#include "../fuzz_harness.h"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace wavejets_fuzz;
  if(size == 0) return 0;
  Source<Bytes> s{Bytes{data + 1, size - 1}};
  Stats st;
  std::vector<Point> pts;
  std::vector<Vector> normals;
  if(data[0] & 1)
    fuzz_function(s, st, pts, normals);
  else
  {
    Fitting fitting;
    fuzz_fit(s, fitting, st, pts, normals);
  }
  if(st.failures)
  {
    std::fprintf(stderr, "wavejets fuzz check failed: %s\n", st.first_failure.c_str());
    std::abort();
  }
  return 0;
}
