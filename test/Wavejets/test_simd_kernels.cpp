// The least-squares kernel's three compilations (least_squares.h): the baseline code, the AVX
// clone and the AVX2 + FMA clone, run on the same systems, with whichever compiler built this test
// (g++ and clang++ both run it in scripts/test.sh). Checks the documented agreement:
//   - AVX == baseline, bitwise (same arithmetic, wider registers);
//   - AVX2 + FMA agrees with the baseline to 1e-12 relative, times the system's condition number;
//   - the baseline solves the system to 1e-13 relative (times the condition number) of Eigen's
//     HouseholderQR;
//   - the run-time dispatch (householder_least_squares) picks the best clone the processor
//     supports (bitwise equal to it), so a processor without AVX falls back to the baseline;
//   - a rank-deficient system is reported (false) by every variant.
// A clone the processor cannot run is reported as skipped, never run.
// The kernels are written once for a four-lane type: the GCC/Clang vector extension, or (built with
// CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS, as other compilers get) a plain struct: the case
// portable_build_bitwise saves the baseline kernel's solutions bit for bit in one build and compares
// them in the other (see test_portable_build_bitwise()).

#include <CGAL/Wavejets/internal/least_squares.h>

#include <Eigen/Dense>

#ifdef CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS
#define CGAL_WAVEJETS_FOUR_LANES "portable (struct)"
#else
#define CGAL_WAVEJETS_FOUR_LANES "vector-extension"
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "wavejets_test_support.h"

namespace WI = CGAL::Wavejets::internal;
using wavejets_test::Case;
using wavejets_test::check_printed;

typedef bool (*Kernel)(double*, std::size_t, std::size_t, double*, double*);

/// One system: the column-major padded layout the kernels take (b as the last column).
struct System
{
  std::size_t rows, cols;
  Eigen::MatrixXd M;
  Eigen::VectorXd b;
};

/// Solves `s` with `kernel`; false if the kernel reports a rank-deficient system.
static bool solve(Kernel kernel, const System& s, std::vector<double>& c)
{
  const std::size_t P = WI::padded_rows(s.rows);
  std::vector<double, WI::Aligned_allocator<double> > A(P * (s.cols + 1), 0.), v(2 * P, 0.);
  for(std::size_t j = 0; j < s.cols; ++j)
    for(std::size_t i = 0; i < s.rows; ++i) A[j * P + i] = s.M(i, j);
  for(std::size_t i = 0; i < s.rows; ++i) A[s.cols * P + i] = s.b(i);
  c.assign(s.cols, 0.);
  return kernel(A.data(), s.rows, s.cols, v.data(), c.data());
}

static std::string sci(double x)
{
  char b[32];
  std::snprintf(b, sizeof b, "%.2e", x);
  return b;
}

static double relative_difference(const std::vector<double>& a, const std::vector<double>& b)
{
  double d = 0., n = 0.;
  for(std::size_t i = 0; i < a.size(); ++i)
  {
    d = (std::max)(d, std::abs(a[i] - b[i]));
    n = (std::max)(n, std::abs(b[i]));
  }
  return n > 0 ? d / n : d;
}

/// The random full-rank systems: the sizes of the Wavejet systems and a few others.
static std::vector<System> random_systems()
{
  std::mt19937_64 random(20261201);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  // Sizes of the Wavejet systems (unknowns (K+1)(K+2)/2 for K = 1..6) and a few others.
  const std::size_t columns[] = {3, 6, 10, 15, 21, 28};
  std::vector<System> systems;
  for(std::size_t cols : columns)
    for(std::size_t rows : {cols, cols + 1, cols + 7, 2 * cols + 3, std::size_t(101)})
      if(rows >= cols)
      {
        System s{rows, cols, Eigen::MatrixXd(rows, cols), Eigen::VectorXd(rows)};
        for(std::size_t i = 0; i < rows; ++i)
        {
          for(std::size_t j = 0; j < cols; ++j) s.M(i, j) = uniform(random);
          s.b(i) = uniform(random);
        }
        systems.push_back(s);
      }
  return systems;
}

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
static bool processor_has_avx() { return WI::avx_dispatch && __builtin_cpu_supports("avx"); }
static bool processor_has_fma() { return WI::avx_dispatch && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }
#else
static bool processor_has_avx() { return false; }
static bool processor_has_fma() { return false; }
#endif

// Every variant on the same full-rank systems: the documented agreement, and the dispatch.
static void test_full_rank_agreement()
{
  const std::vector<System> systems = random_systems();
  const bool has_avx = processor_has_avx(), has_fma = processor_has_fma();
  if(!WI::avx_dispatch)
    std::cout << "this build has no AVX dispatch (not x86 with g++/clang++, or CGAL_WAVEJETS_NO_AVX_DISPATCH): "
                 "the baseline kernel alone is checked" << std::endl;

  double worst_baseline = 0., worst_fma = 0.;
  bool avx_bitwise = true, fma_close = true, dispatch_ok = true, all_solved = true;
  std::size_t fma_differs = 0; // systems where FMA changes bits (the comparison is not vacuous)
  for(const System& s : systems)
  {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.M);
    const double condition = svd.singularValues()(0) / svd.singularValues()(s.cols - 1);
    const Eigen::VectorXd reference = s.M.householderQr().solve(s.b);
    std::vector<double> ref(reference.data(), reference.data() + s.cols), base, avx, fma, dispatched;

    all_solved = all_solved && solve(&WI::householder_kernel, s, base);
    worst_baseline = (std::max)(worst_baseline, relative_difference(base, ref) / condition);
    all_solved = all_solved && solve(&WI::householder_least_squares, s, dispatched);
    if(has_avx)
    {
      all_solved = all_solved && solve(&WI::householder_avx, s, avx);
      avx_bitwise = avx_bitwise && avx == base;
    }
    if(has_fma)
    {
      all_solved = all_solved && solve(&WI::householder_fma, s, fma);
      const double d = relative_difference(fma, base);
      worst_fma = (std::max)(worst_fma, d / condition);
      fma_close = fma_close && d <= 1e-12 * condition;
      fma_differs += fma != base;
    }
    const std::vector<double>& best = has_fma ? fma : has_avx ? avx : base;
    dispatch_ok = dispatch_ok && dispatched == best;
  }
  const std::string n = std::to_string(systems.size()) + " systems";
  check_printed(all_solved, "every variant solves the " + n + " (full rank)");
  check_printed(worst_baseline <= 1e-13, "baseline vs Eigen HouseholderQR: " + sci(worst_baseline) +
                                   " relative / condition number (<= 1e-13)");
  if(has_avx) check_printed(avx_bitwise, "AVX clone == baseline, bitwise, on " + n);
  else std::cout << "[SKIP] AVX clone: the processor has no AVX" << std::endl;
  if(has_fma) check_printed(fma_close, "AVX2 + FMA clone vs baseline: " + sci(worst_fma) +
                                 " relative / condition number (<= 1e-12); bits differ on " +
                                 std::to_string(fma_differs) + " of " + n);
  else std::cout << "[SKIP] AVX2 + FMA clone: the processor has no AVX2 + FMA" << std::endl;
  check_printed(dispatch_ok, std::string("the dispatch picks the ") + (has_fma ? "AVX2 + FMA" : has_avx ? "AVX" : "baseline") +
                       " kernel (bitwise equal to it)");
}

// A rank-deficient system (two equal columns) is reported by every variant.
static void test_rank_deficient_reported()
{
  const bool has_avx = processor_has_avx(), has_fma = processor_has_fma();
  System deficient = random_systems().back();
  deficient.M.col(3) = deficient.M.col(1);
  std::vector<double> c;
  bool reported = !solve(&WI::householder_kernel, deficient, c) && !solve(&WI::householder_least_squares, deficient, c);
  if(has_avx) reported = reported && !solve(&WI::householder_avx, deficient, c);
  if(has_fma) reported = reported && !solve(&WI::householder_fma, deficient, c);
  check_printed(reported, "a rank-deficient system is reported by every variant");
}

/// Writes (`write`) or compares the baseline solutions, as exact hexadecimal doubles.
static void baseline_file(const std::vector<System>& systems, const std::string& mode, const std::string& path)
{
  std::vector<double> all, c;
  for(const System& s : systems)
  {
    solve(&WI::householder_kernel, s, c);
    all.insert(all.end(), c.begin(), c.end());
  }
  if(mode == "--write")
  {
    std::ofstream out(path);
    char b[64];
    for(double x : all) { std::snprintf(b, sizeof b, "%a\n", x); out << b; }
    check_printed(bool(out), "baseline solutions written to " + path);
    return;
  }
  std::ifstream in(path);
  std::vector<double> reference;
  std::string line;
  while(std::getline(in, line)) reference.push_back(std::strtod(line.c_str(), nullptr));
  std::size_t same = 0;
  for(std::size_t i = 0; i < all.size() && i < reference.size(); ++i)
    same += std::memcmp(&all[i], &reference[i], sizeof(double)) == 0;
  check_printed(reference.size() == all.size() && same == all.size(),
        std::string(CGAL_WAVEJETS_FOUR_LANES) + " build vs " + path + ": " + std::to_string(same) + " of " +
          std::to_string(reference.size()) + " baseline values bitwise equal");
}

// The baseline kernel's solutions, bit for bit, across the two builds of this file: CTest runs the
// vector-extension build with WAVEJETS_SIMD_BASELINE_WRITE=FILE and the portable build
// (test_simd_kernels_portable, CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS) with WAVEJETS_SIMD_BASELINE_COMPARE=FILE.
static void test_portable_build_bitwise()
{
  const char* write = std::getenv("WAVEJETS_SIMD_BASELINE_WRITE");
  const char* compare = std::getenv("WAVEJETS_SIMD_BASELINE_COMPARE");
  if(write && *write) baseline_file(random_systems(), "--write", write);
  else if(compare && *compare) baseline_file(random_systems(), "--compare", compare);
  else std::cout << "[SKIP] neither WAVEJETS_SIMD_BASELINE_WRITE nor WAVEJETS_SIMD_BASELINE_COMPARE is set" << std::endl;
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"kernels.full_rank_agreement", test_full_rank_agreement},
    Case{"kernels.rank_deficient_reported", test_rank_deficient_reported},
    Case{"kernels.portable_build_bitwise", test_portable_build_bitwise},
  });
}
