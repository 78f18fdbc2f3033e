// Seeded random fuzzing of the Wavejets package (always built and run by CTest; the libFuzzer
// target in fuzz/ reuses the same harness when clang is available).
//
// Feeds CGAL::Wavejet_fitting random neighborhoods (sizes 0-200, random degenerate structures,
// tiny/huge scales, far translations, NaN/inf injection, orders 0-12, random options) and the four
// point-set functions random small point sets and parameters (see fuzz_harness.h). Asserts no
// crash, finite outputs or the documented failure state, and only the documented exceptions
// (CGAL::Precondition_exception for order 0 in the class, std::invalid_argument for invalid
// function parameters, thrown exactly when the parameters are invalid).
//
// Usage: test_fuzz [fits [seed]]; or environment WAVEJETS_FUZZ_FITS / WAVEJETS_FUZZ_SEED.
// Default: 1,000,000 fits (about 1 in 10 through the functions, counting one fit per point),
// 100,000 when built with a sanitizer. Deterministic for a given seed.

#include "fuzz_harness.h"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>

#if defined(__SANITIZE_ADDRESS__)
#define WAVEJETS_FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define WAVEJETS_FUZZ_SANITIZED 1
#endif
#endif

int main(int argc, char** argv)
{
#ifdef WAVEJETS_FUZZ_SANITIZED
  std::size_t target = 100000; // about 35 s under ASan + UBSan
#else
  std::size_t target = 1000000;
#endif
  unsigned long long seed = 20260101;
  if(const char* e = std::getenv("WAVEJETS_FUZZ_FITS")) target = std::strtoull(e, nullptr, 10);
  if(const char* e = std::getenv("WAVEJETS_FUZZ_SEED")) seed = std::strtoull(e, nullptr, 10);
  if(argc > 1) target = std::strtoull(argv[1], nullptr, 10);
  if(argc > 2) seed = std::strtoull(argv[2], nullptr, 10);

  using namespace wavejets_fuzz;
  Source<Splitmix> s{Splitmix{seed}};
  Stats st;
  Fitting fitting;
  std::vector<Point> pts;
  std::vector<Vector> normals;
  std::size_t function_fits = 0, report_every = target / 10 + 1, next_report = report_every;
  const auto t0 = std::chrono::steady_clock::now();
  while(st.fits + function_fits < target && st.failures == 0)
  {
    if(s.chance(0.01)) // ~ 1 in 10 fits (one per point, 30 points on average) through the functions
      function_fits += fuzz_function(s, st, pts, normals);
    else
      fuzz_fit(s, fitting, st, pts, normals);
    if(st.fits + function_fits >= next_report)
    {
      next_report += report_every;
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cout << "  " << st.fits + function_fits << " fits, " << secs << " s" << std::endl;
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "seed " << seed << ": " << st.fits + function_fits << " fits in " << secs << " s ("
            << (st.fits + function_fits) / (secs > 0 ? secs : 1) << " fits/s)\n"
            << "  Wavejet_fitting: " << st.fits << " calls, " << st.valid_fits << " valid, " << st.failed_fits
            << " failure states, " << st.precondition_exceptions << " Precondition_exception (order 0)\n"
            << "  functions: " << st.function_calls << " calls on " << function_fits << " points, " << st.fitted_points
            << " fitted, " << st.invalid_argument << " std::invalid_argument" << std::endl;
  if(st.failures)
  {
    std::cout << "FAIL: " << st.first_failure << " (at fit " << st.fits + function_fits << ", seed " << seed << ")" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "PASS fuzz: no crash, finite outputs or failure states, documented exceptions only" << std::endl;
  return EXIT_SUCCESS;
}
