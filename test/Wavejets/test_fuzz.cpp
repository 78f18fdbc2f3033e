// Seeded random fuzzing of the Wavejets package (always built and run by CTest; the libFuzzer
// target in fuzz/ reuses the same harness when clang is available).
//
// Feeds CGAL::Wavejet_fitting random neighborhoods (sizes 0-200, random degenerate structures,
// tiny/huge scales, far translations, NaN/inf injection, orders 0-12, random options) and the four
// point-set functions random small point sets and parameters (see fuzz_harness.h). Asserts no
// crash, finite outputs or the documented failure state, and only the documented exceptions
// (std::invalid_argument for order 0 in the class and for invalid
// function parameters, thrown exactly when the parameters are invalid).
//
// The count is of real fits only: calls of the fitting core with order >= 1 on accepted
// parameters and finite input (Stats in fuzz_harness.h). Order-0 calls, calls with rejected
// parameters, empty ranges and NON_FINITE_INPUT rejections are run and checked too, but not
// counted; the run goes on until the real fits reach the target.
//
// Usage: test_fuzz [real_fits [seed]]; or environment WAVEJETS_FUZZ_FITS / WAVEJETS_FUZZ_SEED;
// or test_fuzz shard I N: shard I (0 <= I < N) of the default run, 1/N of its real fits (rounded
// up) from seed 20260101 + I (shard 0 is the first 1/N of the unsharded run). CTest runs the
// default in two shards (test/Wavejets/CMakeLists.txt), so that `ctest -j2` runs them side by side.
// Default: 1,000,000 real fits (about 1 in 5 through the functions, one per finite point);
// 100,000 when built with a sanitizer (ASan + UBSan at -O1 run the harness ~10x slower, and the
// sanitizer build is there to catch memory and UB errors, which 1e5 fits of the same generator
// exercise as well as 1e6). Deterministic for a given seed.

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
  std::size_t target = 100000; // real fits, see the header comment
#else
  std::size_t target = 1000000;
#endif
  unsigned long long seed = 20260101;
  if(const char* e = std::getenv("WAVEJETS_FUZZ_FITS")) target = std::strtoull(e, nullptr, 10);
  if(const char* e = std::getenv("WAVEJETS_FUZZ_SEED")) seed = std::strtoull(e, nullptr, 10);
  if(argc > 1 && std::string(argv[1]) == "shard")
  {
    const unsigned long long shard = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 0;
    const unsigned long long shards = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 0;
    if(argc != 4 || shards == 0 || shard >= shards)
    {
      std::cerr << "usage: test_fuzz shard I N (0 <= I < N)" << std::endl;
      return EXIT_FAILURE;
    }
    target = (target + shards - 1) / shards;
    seed += shard;
  }
  else
  {
    if(argc > 1) target = std::strtoull(argv[1], nullptr, 10);
    if(argc > 2) seed = std::strtoull(argv[2], nullptr, 10);
  }

  using namespace wavejets_fuzz;
  Source<Splitmix> s{Splitmix{seed}};
  Stats st;
  Fitting fitting;
  std::vector<Point> pts;
  std::vector<Vector> normals;
  std::size_t report_every = target / 10 + 1, next_report = report_every;
  auto real = [&] { return st.real_fits + st.function_real_fits; };
  const auto t0 = std::chrono::steady_clock::now();
  while(real() < target && st.failures == 0)
  {
    if(s.chance(0.01)) // ~ 1 in 5 real fits (one per finite point, ~30 points a call) through the functions
      fuzz_function(s, st, pts, normals);
    else
      fuzz_fit(s, fitting, st, pts, normals);
    if(real() >= next_report)
    {
      next_report += report_every;
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cout << "  " << real() << " real fits, " << secs << " s" << std::endl;
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "seed " << seed << ": " << real() << " real fits (target " << target << ") in " << secs << " s ("
            << real() / (secs > 0 ? secs : 1) << " real fits/s)\n"
            << "  Wavejet_fitting: " << st.fits << " calls: " << st.real_fits << " real fits (" << st.valid_fits
            << " valid forms in all, " << st.failed_fits << " failure states in all), " << st.order_zero_rejections
            << " order 0 (std::invalid_argument), " << st.non_finite_fits << " NON_FINITE_INPUT, "
            << st.fits - st.real_fits - st.order_zero_rejections - st.non_finite_fits << " empty ranges\n"
            << "  functions: " << st.function_calls << " calls: " << st.function_calls - st.invalid_argument
            << " accepted, with " << st.function_real_fits << " real fits (" << st.fitted_points << " fitted), "
            << st.invalid_argument << " rejected (std::invalid_argument)" << std::endl;
  if(st.failures)
  {
    std::cout << "FAIL: " << st.first_failure << " (at real fit " << real() << ", seed " << seed << ")" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "PASS fuzz: no crash, finite outputs or failure states, documented exceptions only" << std::endl;
  return EXIT_SUCCESS;
}
