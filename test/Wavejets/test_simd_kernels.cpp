// The least-squares solvers of least_squares.h, the Householder QR and the guarded semi-normal
// equations (each in four compilations: the baseline code, the AVX clone, the AVX2 + FMA clone and
// the AVX-512 clone), run on the same systems, with whichever compiler built this test (g++ and clang++ both
// run it in scripts/test.sh). Checks the documented agreement, for each solver:
//   - AVX == baseline, bitwise (same arithmetic, wider registers);
//   - AVX2 + FMA agrees with the baseline to 1e-12 relative, times the system's condition number;
//   - AVX-512 == AVX2 + FMA, bitwise, except the order-2 moments kernel (eight rows per step), which
//     agrees with the AVX2 + FMA clone to 1e-12 relative and differs from it in the last bits;
//   - the baseline solves the system to 1e-13 relative (times the condition number) of Eigen's
//     HouseholderQR;
//   - the run-time dispatch (householder_least_squares) picks the best clone the processor
//     supports (bitwise equal to it), so a processor without AVX falls back to the baseline;
//   - a rank-deficient system is reported (false) by every variant;
// and for the semi-normal solver (the one the fits use):
//   - it agrees with the QR to 1e-10 relative on Wavejet systems of real-looking neighborhoods
//     (orders 1 to 6; smooth, noisy, anisotropic and clustered samples), and solves most of them
//     itself;
//   - its guards hand ill-conditioned systems (nearly dependent columns, nearly collinear
//     neighborhoods) to the QR: then the result is the QR's, bit for bit;
// and for its Wavejet variant (wavejet_least_squares(), the Gram matrix from polar moments, the one
// the unweighted fits use): the Gram matrix matches the dot products, the solution agrees with the
// QR to 1e-10 relative (orders 1 to 10), the guards accept the same systems, AVX == baseline bitwise,
// it is least_squares() bit for bit where it does not use the moments, and it refuses nearly
// collinear neighborhoods as the other does.
// The fit's AVX-only kernels (dispatch_avx(): the basis columns, the projection onto a frame, the
// PCA moments) give bitwise the baseline's values, and the dispatch runs the AVX clone.
// A clone the processor cannot run is reported as skipped, never run.
// The kernels are written once for a four-lane type: the GCC/Clang vector extension, or (built with
// CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS, as other compilers get) a plain struct: the case
// portable_build_bitwise saves the baseline kernel's solutions bit for bit in one build and compares
// them in the other (see test_portable_build_bitwise()).

#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/fitting_core.h>
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

typedef std::vector<double, WI::Aligned_allocator<double> > Aligned;

/// `s` in the kernels' layout: [M | b], column-major, columns padded with zero rows.
static Aligned padded_layout(const System& s)
{
  const std::size_t P = WI::padded_rows(s.rows);
  Aligned A(P * (s.cols + 1), 0.);
  for(std::size_t j = 0; j < s.cols; ++j)
    for(std::size_t i = 0; i < s.rows; ++i) A[j * P + i] = s.M(i, j);
  for(std::size_t i = 0; i < s.rows; ++i) A[s.cols * P + i] = s.b(i);
  return A;
}

/// Solves `s` with `kernel`; false if the kernel reports a rank-deficient system.
static bool solve(Kernel kernel, const System& s, std::vector<double>& c)
{
  Aligned A = padded_layout(s), v(WI::wavejet_least_squares_scratch_size(s.rows, s.cols), 0.); // >= least_squares_scratch_size()
  c.assign(s.cols, 0.);
  return kernel(A.data(), s.rows, s.cols, v.data(), c.data());
}

/// The order-2 problem of L points (x, y, h) solved by `kernel` (a compilation of the
/// ORDER2_MOMENTS solver), which reads the columns x, y, h; false if its guards refuse it.
static bool solve_order2(Kernel kernel, const Eigen::VectorXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& h,
                         std::vector<double>& c)
{
  const std::size_t L = std::size_t(x.size()), P = WI::padded_rows(L);
  std::vector<double, WI::Aligned_allocator<double> > X(3 * P, 0.);
  for(std::size_t l = 0; l < L; ++l)
  {
    X[l] = x(l);
    X[P + l] = y(l);
    X[2 * P + l] = h(l);
  }
  c.assign(WI::order2_columns, 0.);
  return kernel(X.data(), L, WI::order2_columns, nullptr, c.data());
}

/// An order-2 Wavejet system (columns 1, x, y, ...: basis.h) solved from its points by `kernel`.
static bool solve_order2(Kernel kernel, const System& s, std::vector<double>& c)
{
  return solve_order2(kernel, s.M.col(1), s.M.col(2), s.b, c);
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
static bool processor_has_fma() { return WI::processor_runs_fma(); }
#else
static bool processor_has_avx() { return false; }
static bool processor_has_fma() { return false; }
#endif

/// True if this build has the AVX-512 clone and the processor runs it.
static bool processor_has_avx512() { return WI::processor_runs_avx512(); }

/// The compilations of solver S.
template <WI::Solver S>
struct Variants
{
  static constexpr Kernel baseline = &WI::solver_kernel<S>;
  static constexpr Kernel avx = &WI::solver_avx<S>;
  static constexpr Kernel fma = &WI::solver_fma<S>;
  static constexpr Kernel avx512 = &WI::solver_avx512<S>;
  static constexpr Kernel dispatched = &WI::dispatch_solver<S>;
  static const char* name()
  {
    return S == WI::Solver::HOUSEHOLDER_QR ? "QR" : S == WI::Solver::SEMI_NORMAL_ELSE_QR ? "semi-normal"
         : S == WI::Solver::WAVEJET_SEMI_NORMAL_ELSE_QR ? "semi-normal, polar moments" : "order-2 moments";
  }
};

// Every variant of solver S on the same full-rank systems: the documented agreement, and the dispatch.
template <WI::Solver S>
static void test_full_rank_agreement()
{
  typedef Variants<S> V;
  std::cout << "solver: " << V::name() << std::endl;
  const std::vector<System> systems = random_systems();
  const bool has_avx = processor_has_avx(), has_fma = processor_has_fma(), has_avx512 = processor_has_avx512();
  if(!WI::avx_dispatch)
    std::cout << "this build has no AVX dispatch (not x86 with g++/clang++, or CGAL_WAVEJETS_NO_AVX_DISPATCH): "
                 "the baseline kernel alone is checked" << std::endl;

  double worst_baseline = 0., worst_fma = 0.;
  bool avx_bitwise = true, fma_close = true, avx512_bitwise = true, dispatch_ok = true, all_solved = true;
  std::size_t fma_differs = 0; // systems where FMA changes bits (the comparison is not vacuous)
  for(const System& s : systems)
  {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.M);
    const double condition = svd.singularValues()(0) / svd.singularValues()(s.cols - 1);
    const Eigen::VectorXd reference = s.M.householderQr().solve(s.b);
    std::vector<double> ref(reference.data(), reference.data() + s.cols), base, avx, fma, avx512, dispatched;

    all_solved = all_solved && solve(V::baseline, s, base);
    worst_baseline = (std::max)(worst_baseline, relative_difference(base, ref) / condition);
    all_solved = all_solved && solve(V::dispatched, s, dispatched);
    if(has_avx)
    {
      all_solved = all_solved && solve(V::avx, s, avx);
      avx_bitwise = avx_bitwise && avx == base;
    }
    if(has_fma)
    {
      all_solved = all_solved && solve(V::fma, s, fma);
      const double d = relative_difference(fma, base);
      worst_fma = (std::max)(worst_fma, d / condition);
      fma_close = fma_close && d <= 1e-12 * condition;
      fma_differs += fma != base;
    }
    if(has_avx512) // the FMA clone's four-lane code (the order-2 kernel: test_order2_moments_...())
    {
      all_solved = all_solved && solve(V::avx512, s, avx512);
      avx512_bitwise = avx512_bitwise && avx512 == fma;
    }
    const std::vector<double>& best = has_avx512 ? avx512 : has_fma ? fma : has_avx ? avx : base;
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
  else std::cout << "[SKIP] AVX2 + FMA clone: not in this build or not on this processor" << std::endl;
  if(has_avx512)
    check_printed(avx512_bitwise, "AVX-512 clone == AVX2 + FMA clone, bitwise, on " + n);
  else
    std::cout << "[SKIP] AVX-512 clone: "
              << (WI::avx512_dispatch ? "the processor has no AVX-512" : "not in this build") << std::endl;
  check_printed(dispatch_ok, std::string("the dispatch picks the ") +
                               (has_avx512 ? "AVX-512" : has_fma ? "AVX2 + FMA" : has_avx ? "AVX" : "baseline") +
                               " kernel (bitwise equal to it)");
}

// A rank-deficient system (two equal columns) is reported by every variant.
template <WI::Solver S>
static void test_rank_deficient_reported()
{
  typedef Variants<S> V;
  const bool has_avx = processor_has_avx(), has_fma = processor_has_fma();
  System deficient = random_systems().back();
  deficient.M.col(3) = deficient.M.col(1);
  std::vector<double> c;
  bool reported = !solve(V::baseline, deficient, c) && !solve(V::dispatched, deficient, c);
  if(has_avx) reported = reported && !solve(V::avx, deficient, c);
  if(has_fma) reported = reported && !solve(V::fma, deficient, c);
  if(processor_has_avx512()) reported = reported && !solve(V::avx512, deficient, c);
  check_printed(reported, std::string(V::name()) + ": a rank-deficient system is reported by every variant");
}

/// Writes (`write`) or compares the baseline solutions, as exact hexadecimal doubles.
static void baseline_file(const std::vector<System>& systems, const std::string& mode, const std::string& path)
{
  std::vector<double> all, c;
  for(const System& s : systems)
  {
    solve(&WI::householder_kernel, s, c);
    all.insert(all.end(), c.begin(), c.end());
    solve(&WI::least_squares_kernel, s, c);
    all.insert(all.end(), c.begin(), c.end());
    if(s.rows >= WI::order2_columns) // points (column 0, column 1, b)
    {
      if(!solve_order2(&WI::solver_kernel<WI::Solver::ORDER2_MOMENTS>, s.M.col(0), s.M.col(1), s.b, c))
        c.assign(1, -1.); // refused: a marker
      all.insert(all.end(), c.begin(), c.end());
    }
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

/// The Wavejet system of order K of L points (x, y, z) of a neighborhood in its (rescaled) frame.
static System wavejet_system(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                             std::size_t order)
{
  const std::size_t L = x.size(), B = WI::number_of_coefficients(order), P = WI::padded_rows(L);
  std::vector<double> A(P * B), xs(x), ys(y);
  xs.resize(P, 0.); // evaluate_basis_columns() reads the padding rows too (they must be finite)
  ys.resize(P, 0.);
  WI::evaluate_basis_columns(xs.data(), ys.data(), L, P, order, A.data());
  System s{L, B, Eigen::MatrixXd(L, B), Eigen::VectorXd(L)};
  for(std::size_t l = 0; l < L; ++l)
  {
    for(std::size_t b = 0; b < B; ++b) s.M(l, b) = A[b * P + l];
    s.b(l) = z[l];
  }
  return s;
}

/// Neighborhoods like those the fits see, in the rescaled frame (r <= 1, the center first): a
/// uniform disc sample, an anisotropic strip, a cluster with a few far points; heights of a smooth
/// surface (saddle, bumps) plus noise; orders lowest_order to lowest_order + 5, lowest_ratio (1.1) to
/// 4 times as many points as unknowns.
static std::vector<System> wavejet_systems(std::size_t count, std::mt19937_64& random, std::size_t lowest_order = 1,
                                           double lowest_ratio = 1.1)
{
  std::uniform_real_distribution<double> uniform(-1., 1.);
  std::normal_distribution<double> gauss(0., 1.);
  std::vector<System> systems;
  for(std::size_t q = 0; q < count; ++q)
  {
    const std::size_t order = lowest_order + q % 6, B = WI::number_of_coefficients(order);
    const double ratio = lowest_ratio + (4. - lowest_ratio) * (0.5 + 0.5 * uniform(random));
    const std::size_t L = (std::max)(B, std::size_t(std::ceil(ratio * double(B))));
    const int shape = int(q / 6 % 3);
    const double noise = (q / 18 % 3) * 0.01, a = uniform(random), c = uniform(random);
    std::vector<double> x(1, 0.), y(1, 0.), z(1, 0.);
    while(x.size() < L)
    {
      double u = uniform(random), v = uniform(random);
      if(u * u + v * v > 1.) continue;
      if(shape == 1) v *= 0.2;                              // anisotropic strip
      if(shape == 2 && x.size() % 5 != 0) { u *= 0.1; v *= 0.1; } // cluster + a few far points
      x.push_back(u);
      y.push_back(v);
      z.push_back(a * u * u - c * v * v + 0.2 * std::sin(3 * u) * v + noise * gauss(random));
    }
    systems.push_back(wavejet_system(x, y, z, order));
  }
  return systems;
}

// The semi-normal solver agrees with the QR on Wavejet systems, and solves most of them itself.
static void test_semi_normal_on_wavejet_systems()
{
  std::mt19937_64 random(20261202);
  const std::vector<System> systems = wavejet_systems(3000, random);
  double worst = 0.;
  std::size_t own[3] = {0, 0, 0}, per_shape = 0;
  bool all_solved = true, small_is_qr = true;
  std::vector<double> qr, semi_normal, direct;
  for(std::size_t q = 0; q < systems.size(); ++q)
  {
    const System& s = systems[q];
    const bool solved = solve(&WI::householder_least_squares, s, qr) && solve(&WI::least_squares, s, semi_normal);
    all_solved = all_solved && solved;
    // least_squares() leaves the systems below semi_normal_minimum_columns unknowns to the QR.
    if(s.cols < WI::semi_normal_minimum_columns) small_is_qr = small_is_qr && semi_normal == qr;
    // The semi-normal equations themselves, at every order, where their guards accept the system.
    const bool accepted = solve(&WI::semi_normal_kernel, s, direct);
    if(solved && accepted) worst = (std::max)(worst, relative_difference(direct, qr));
    own[q / 6 % 3] += accepted;
    per_shape += q / 6 % 3 == 0;
  }
  const std::string n = std::to_string(systems.size()) + " Wavejet systems (orders 1 to 6)";
  check_printed(all_solved, "QR and least_squares() solve the " + n);
  check_printed(small_is_qr, "least_squares() == the QR, bitwise, below " + std::to_string(WI::semi_normal_minimum_columns) +
                               " unknowns");
  check_printed(worst <= 1e-10, "semi-normal vs QR: " + sci(worst) + " relative (<= 1e-10) on the " + n);
  // The uniform samples are what real neighborhoods look like (bench_speed: none of 20,000 bunny
  // neighborhoods per order goes to the QR); strips and clusters are harder and partly refused.
  check_printed(own[0] == per_shape, "the semi-normal equations solved " + std::to_string(own[0]) + " of the " +
                                     std::to_string(per_shape) + " uniform samples themselves (all), " +
                                     std::to_string(own[1]) + " of the strips and " + std::to_string(own[2]) +
                                     " of the clusters (the rest went to the QR)");
}

// The semi-normal solver of the Wavejet systems (Gram matrix from polar moments) agrees with the QR
// and with the dot-by-dot Gram matrix, solves the uniform samples itself, is least_squares() bit for
// bit where it does not use the moments, and its compilations agree as the other solvers' do.
static void test_wavejet_semi_normal_on_wavejet_systems()
{
  std::mt19937_64 random(20261203);
  std::vector<System> systems = wavejet_systems(1800, random);     // orders 1 to 6, 1.1 to 4 points per unknown
  const std::vector<System> high = wavejet_systems(1800, random, 5, 2.); // orders 5 to 10, 2 to 4 per unknown
  systems.insert(systems.end(), high.begin(), high.end());
  typedef Variants<WI::Solver::WAVEJET_SEMI_NORMAL_ELSE_QR> V;
  const bool has_avx = processor_has_avx(), has_fma = processor_has_fma(), has_avx512 = processor_has_avx512();
  double worst = 0., worst_gram = 0., worst_baseline = 0.;
  std::size_t polar = 0, own[3] = {0, 0, 0}, own_by_dots[3] = {0, 0, 0}, per_shape[3] = {0, 0, 0};
  bool all_solved = true, same_elsewhere = true, avx_bitwise = true, avx512_bitwise = true, dispatch_ok = true;
  bool solution_only_same = true, solution_only_keeps_A = true;
  std::size_t kept_checked = 0;
  std::vector<double> qr, mine, other, base, avx, fma, avx512, solution_only;
  // The solves without R (what the fits run unless the condition number is asked for).
  const Kernel wavejet_solution = [](double* A, std::size_t rows, std::size_t cols, double* v, double* c) {
    return WI::least_squares_solution(A, rows, cols, v, c, true);
  };
  const Kernel plain_solution = [](double* A, std::size_t rows, std::size_t cols, double* v, double* c) {
    return WI::least_squares_solution(A, rows, cols, v, c, false);
  };
  for(std::size_t q = 0; q < systems.size(); ++q)
  {
    const System& s = systems[q];
    const bool solved = solve(&WI::householder_least_squares, s, qr) && solve(&WI::wavejet_least_squares, s, mine);
    all_solved = all_solved && solved;
    solution_only_same = solution_only_same && solve(wavejet_solution, s, solution_only) && solution_only == mine;
    solve(&WI::least_squares, s, other);
    solution_only_same = solution_only_same && solve(plain_solution, s, solution_only) && solution_only == other;
    if(!WI::uses_polar_moments(s.rows, s.cols))
    {
      same_elsewhere = same_elsewhere && other == mine;
      continue;
    }
    ++polar;
    // The Gram matrix itself, against the dot products, scaled by the diagonal (the uniform samples).
    const std::size_t P = WI::padded_rows(s.rows), B = s.cols, S = WI::semi_normal_row_stride(B);
    const std::size_t K = WI::polar_moment_order(B);
    Aligned A = padded_layout(s), scratch(WI::polar_moment_scratch_size(P, K));
    std::vector<double> G_dots(B * S, 0.), G_moments(B * S, 0.);
    WI::gram_upper(A.data(), P, B, G_dots.data(), S);
    WI::polar_moment_gram_upper(A.data(), P, K, scratch.data(), G_moments.data());
    const int shape = int(q % 1800 / 6 % 3);
    if(shape == 0)
      for(std::size_t i = 0; i < B; ++i)
        for(std::size_t j = i; j <= B; ++j)
        {
          const double norm_j = j < B ? G_dots[j * S + j] : s.b.squaredNorm();
          worst_gram = (std::max)(worst_gram, std::abs(G_moments[i * S + j] - G_dots[i * S + j]) /
                                                std::sqrt(G_dots[i * S + i] * norm_j));
        }
    if(solved) worst = (std::max)(worst, relative_difference(mine, qr));
    // Whether the semi-normal equations with the moments solve it themselves (their guards accept it).
    ++per_shape[shape];
    std::vector<double> c(B, 0.);
    Aligned v(WI::wavejet_least_squares_scratch_size(s.rows, B));
    const Aligned system = A;
    own[shape] += WI::wavejet_semi_normal_kernel(A.data(), s.rows, B, v.data(), c.data());
    A = system;
    if(WI::wavejet_semi_normal_kernel<false>(A.data(), s.rows, B, v.data(), c.data())) // no R: A untouched
    {
      ++kept_checked;
      solution_only_keeps_A = solution_only_keeps_A && A == system;
    }
    A = system;
    own_by_dots[shape] += WI::semi_normal_kernel(A.data(), s.rows, B, v.data(), c.data());
    // The compilations: the baseline against the baseline QR (the FMA clone is `mine` when the
    // processor has it: checked against the dispatched QR above), AVX bitwise the baseline.
    solve(V::baseline, s, base);
    solve(&WI::householder_kernel, s, other);
    worst_baseline = (std::max)(worst_baseline, relative_difference(base, other));
    if(has_avx)
    {
      solve(V::avx, s, avx);
      avx_bitwise = avx_bitwise && avx == base;
    }
    if(has_fma)
      solve(V::fma, s, fma);
    if(has_avx512)
    {
      solve(V::avx512, s, avx512);
      avx512_bitwise = avx512_bitwise && avx512 == fma;
    }
    dispatch_ok = dispatch_ok && mine == (has_avx512 ? avx512 : has_fma ? fma : has_avx ? avx : base);
  }
  const std::string n = std::to_string(systems.size()) + " Wavejet systems (orders 1 to 10)";
  check_printed(all_solved, "QR and wavejet_least_squares() solve the " + n);
  check_printed(polar > 1000, std::to_string(polar) + " of them have enough unknowns and rows for the polar moments");
  check_printed(same_elsewhere, "wavejet_least_squares() == least_squares(), bitwise, on the others (fewer than " +
                                  std::to_string(WI::semi_normal_minimum_columns) + " unknowns or " +
                                  std::to_string(WI::polar_moment_minimum_rows_per_column) + " rows per unknown)");
  check_printed(solution_only_same, "least_squares_solution() (no R) == wavejet_least_squares() and least_squares(), "
                                    "bitwise, on the " + n);
  check_printed(kept_checked == own[0] + own[1] + own[2] && kept_checked > 500,
                "the semi-normal equations without R solve the same " + std::to_string(kept_checked) +
                  " systems as with R (their guards refuse the others)");
  check_printed(solution_only_keeps_A, "... and leave those systems unchanged");
  check_printed(worst_gram <= 1e-13, "Gram matrix from polar moments vs dot products: " + sci(worst_gram) +
                                       " relative to the diagonal (<= 1e-13) on the uniform samples");
  const std::string dispatched = has_avx512 ? "AVX-512" : has_fma ? "AVX2 + FMA" : has_avx ? "AVX" : "baseline";
  check_printed(worst <= 1e-10, "wavejet_least_squares() vs QR (dispatched: " + dispatched + "): " + sci(worst) +
                                  " relative (<= 1e-10) on the " + std::to_string(polar) + " systems that qualify for the moments (with "
                                  "those its guards hand to the QR)");
  check_printed(own[0] == per_shape[0], "the semi-normal equations with the moments solved " + std::to_string(own[0]) +
                                          " of the " + std::to_string(per_shape[0]) + " uniform samples themselves (all), " +
                                          std::to_string(own[1]) + " of " + std::to_string(per_shape[1]) + " strips and " +
                                          std::to_string(own[2]) + " of " + std::to_string(per_shape[2]) +
                                          " clusters (with the Gram matrix dot by dot: " + std::to_string(own_by_dots[0]) +
                                          ", " + std::to_string(own_by_dots[1]) + " and " + std::to_string(own_by_dots[2]) + ")");
  check_printed(worst_baseline <= 1e-10, "baseline compilation vs its QR: " + sci(worst_baseline) + " relative (<= 1e-10)");
  if(has_avx) check_printed(avx_bitwise, "AVX clone == baseline, bitwise");
  else std::cout << "[SKIP] AVX clone: the processor has no AVX" << std::endl;
  if(has_avx512) check_printed(avx512_bitwise, "AVX-512 clone == AVX2 + FMA clone, bitwise");
  else std::cout << "[SKIP] AVX-512 clone: not in this build or not on this processor" << std::endl;
  check_printed(dispatch_ok, "the dispatch picks the clone the processor supports (bitwise equal to it)");
}

// The order-2 solver from the moments (no M) agrees with the QR of the built system, in every
// compilation the processor runs, and solves the uniform samples itself.
static void test_order2_moments_on_wavejet_systems()
{
  std::mt19937_64 random(20261202);
  typedef Variants<WI::Solver::ORDER2_MOMENTS> V;
  const bool has_avx = processor_has_avx(), has_fma = processor_has_fma(), has_avx512 = processor_has_avx512();
  std::vector<std::pair<std::string, Kernel> > variants = {{"baseline", V::baseline}, {"dispatched", V::dispatched}};
  if(has_avx) variants.emplace_back("AVX", V::avx);
  if(has_fma) variants.emplace_back("AVX2 + FMA", V::fma);
  if(has_avx512) variants.emplace_back("AVX-512", V::avx512);
  const Kernel best = has_avx512 ? V::avx512 : has_fma ? V::fma : has_avx ? V::avx : V::baseline;
  std::size_t systems = 0, own[3] = {0, 0, 0}, per_shape[3] = {0, 0, 0}, avx512_differs = 0;
  double worst = 0., worst_avx512 = 0.;
  bool qr_solved = true, dispatch_ok = true;
  std::vector<double> qr, mine, dispatched, expected, fma, avx512;
  const std::vector<System> corpus = wavejet_systems(3000, random);
  for(std::size_t q = 0; q < corpus.size(); ++q)
  {
    const System& s = corpus[q];
    if(s.cols != WI::order2_columns) continue;
    ++systems;
    qr_solved = qr_solved && solve(&WI::householder_least_squares, s, qr);
    const int shape = int(q / 6 % 3);
    ++per_shape[shape];
    bool accepted_by_all = true;
    for(const auto& v : variants)
      if(solve_order2(v.second, s, mine)) worst = (std::max)(worst, relative_difference(mine, qr));
      else accepted_by_all = false;
    own[shape] += accepted_by_all;
    // The dispatch runs the best clone, bit for bit; the AVX-512 clone (eight rows per step) is the
    // FMA clone up to rounding, and not bitwise (else the eight lanes would not be checked at all).
    const bool solved = solve_order2(V::dispatched, s, dispatched); // a refusal leaves c undefined
    dispatch_ok = dispatch_ok && solved == solve_order2(best, s, expected) && (!solved || dispatched == expected);
    if(has_avx512 && solve_order2(V::fma, s, fma) && solve_order2(V::avx512, s, avx512))
    {
      worst_avx512 = (std::max)(worst_avx512, relative_difference(avx512, fma));
      avx512_differs += avx512 != fma;
    }
  }
  std::string names;
  for(const auto& v : variants) names += (names.empty() ? "" : ", ") + v.first;
  const std::string n = std::to_string(systems) + " order-2 Wavejet systems";
  check_printed(qr_solved && systems > 400, "the QR solves the " + n);
  check_printed(worst <= 1e-10, "order-2 moments vs QR: " + sci(worst) + " relative (<= 1e-10) on the " + n + " (" +
                                  names + ")");
  check_printed(dispatch_ok, std::string("the dispatch runs the ") +
                               (has_avx512 ? "AVX-512" : has_fma ? "AVX2 + FMA" : has_avx ? "AVX" : "baseline") +
                               " clone (bitwise equal to it)");
  if(has_avx512)
    check_printed(worst_avx512 <= 1e-12 && avx512_differs > 0,
                  "AVX-512 clone vs AVX2 + FMA clone: " + sci(worst_avx512) + " relative (<= 1e-12); bits differ on " +
                    std::to_string(avx512_differs) + " of the " + n);
  else
    std::cout << "[SKIP] AVX-512 clone: not in this build or not on this processor" << std::endl;
  check_printed(own[0] == per_shape[0], "the moments solved " + std::to_string(own[0]) + " of the " +
                                          std::to_string(per_shape[0]) + " uniform samples themselves (all), " +
                                          std::to_string(own[1]) + " of " + std::to_string(per_shape[1]) +
                                          " strips and " + std::to_string(own[2]) + " of " +
                                          std::to_string(per_shape[2]) + " clusters");
}

/// What a semi-normal kernel and the solver around it do with system t: whether the kernel accepts
/// it, leaves it unchanged when it refuses it, and whether the solver's result is the QR's bit for bit.
struct Fallback
{
  bool accepted, unchanged, solved_by_qr, same_as_qr;
};

static Fallback semi_normal_fallback(const System& t, Kernel semi_normal, Kernel solver)
{
  Aligned A = padded_layout(t), v(WI::wavejet_least_squares_scratch_size(t.rows, t.cols));
  const Aligned before = A;
  std::vector<double> c(t.cols), qr, mine;
  Fallback f;
  f.accepted = semi_normal(A.data(), t.rows, t.cols, v.data(), c.data());
  f.unchanged = f.accepted || A == before;
  f.solved_by_qr = solve(&WI::householder_least_squares, t, qr);
  const bool solved = solve(solver, t, mine);
  f.same_as_qr = solved == f.solved_by_qr && (!solved || mine == qr);
  return f;
}

// Ill-conditioned systems go to the QR: the guards refuse them, leave A unchanged, and the result
// is the QR's, bit for bit.
static void test_semi_normal_fallback()
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  std::vector<System> ill;
  // Nearly dependent columns: column 3 = column 1 + 1e-7 noise (cond ~ 1e7).
  System s = random_systems().back();
  for(std::size_t i = 0; i < s.rows; ++i) s.M(i, 3) = s.M(i, 1) + 1e-7 * uniform(random);
  ill.push_back(s);
  // Nearly collinear neighborhoods (points within 1e-4 of a line): order 2 and 4.
  for(std::size_t order : {std::size_t(2), std::size_t(4)})
  {
    std::vector<double> x, y, z;
    for(std::size_t l = 0; l < 60; ++l)
    {
      x.push_back(uniform(random));
      y.push_back(1e-4 * uniform(random));
      z.push_back(x.back() * x.back());
    }
    ill.push_back(wavejet_system(x, y, z, order));
  }
  std::size_t refused = 0, same_as_qr = 0, qr_solved = 0, order2_systems = 0, order2_refused = 0;
  bool unchanged = true;
  for(const System& t : ill)
  {
    const Fallback f = semi_normal_fallback(t, &WI::semi_normal_kernel, &WI::least_squares);
    refused += !f.accepted;
    unchanged = unchanged && f.unchanged;
    qr_solved += f.solved_by_qr;
    same_as_qr += f.same_as_qr;
    std::vector<double> mine;
    if(t.cols == WI::order2_columns && t.M.col(0).isOnes()) // a Wavejet system: the moments refuse it too
    {
      ++order2_systems;
      order2_refused += !solve_order2(&WI::dispatch_solver<WI::Solver::ORDER2_MOMENTS>, t, mine);
    }
  }
  // The Wavejet solver with the polar moments: nearly collinear neighborhoods at orders 5 and 6, with
  // 100 points (enough per unknown for the moments).
  std::size_t wavejet_refused = 0, wavejet_same_as_qr = 0, wavejet_systems_count = 0;
  for(std::size_t order : {std::size_t(5), std::size_t(6)})
  {
    std::vector<double> x, y, z;
    for(std::size_t l = 0; l < 100; ++l)
    {
      x.push_back(uniform(random));
      y.push_back(1e-4 * uniform(random));
      z.push_back(x.back() * x.back() + 0.3 * x.back() * y.back());
    }
    ++wavejet_systems_count;
    const Fallback f = semi_normal_fallback(wavejet_system(x, y, z, order), &WI::wavejet_semi_normal_kernel,
                                            &WI::wavejet_least_squares);
    wavejet_refused += !f.accepted;
    unchanged = unchanged && f.unchanged;
    wavejet_same_as_qr += f.same_as_qr;
  }
  const std::string n = std::to_string(ill.size()) + " ill-conditioned systems";
  check_printed(refused == ill.size(), "the semi-normal guards refused " + std::to_string(refused) + " of the " + n);
  check_printed(wavejet_refused == wavejet_systems_count && wavejet_same_as_qr == wavejet_systems_count,
                "with the polar moments, the guards refused " + std::to_string(wavejet_refused) + " of " +
                  std::to_string(wavejet_systems_count) + " nearly collinear neighborhoods (orders 5, 6; 100 points), "
                  "and wavejet_least_squares() == the QR, bitwise, on " + std::to_string(wavejet_same_as_qr));
  check_printed(unchanged, "a refused system is left unchanged for the QR");
  check_printed(order2_systems == 1 && order2_refused == order2_systems,
                "the order-2 moments refused " + std::to_string(order2_refused) + " of the " +
                  std::to_string(order2_systems) + " nearly collinear order-2 neighborhood(s)");
  check_printed(same_as_qr == ill.size(), "least_squares() == the QR, bitwise, on the " + n + " (" +
                                            std::to_string(qr_solved) + " solved, the others reported rank-deficient)");
}

// The kernels run through dispatch_avx() (instruction_sets.h): their AVX clone gives bitwise the
// baseline's values, the dispatch gives the clone's where the processor has AVX, and the values
// are the right ones (the basis against cos / sin, the projection and moments against Eigen).
static void test_avx_only_kernels_bitwise()
{
  const bool has_avx = processor_has_avx();
  if(!has_avx)
    std::cout << "no AVX clone to run (processor or build): the baseline kernels alone are checked" << std::endl;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  bool basis_bitwise = true, projection_bitwise = true, moments_bitwise = true, dispatch_ok = true;
  double basis_error = 0., projection_error = 0., moments_error = 0.;
  for(std::size_t L : {std::size_t(1), std::size_t(7), std::size_t(33), std::size_t(97), std::size_t(101)})
  {
    const std::size_t P = WI::padded_rows(L);
    std::vector<double> coordinates(3 * P, 0.);
    for(std::size_t i = 0; i < 3; ++i)
      for(std::size_t l = 0; l < L; ++l) coordinates[i * P + l] = uniform(random) / std::sqrt(3.);
    const double* x = coordinates.data();
    const double* y = x + P;
    for(std::size_t order = 1; order <= 8; ++order)
    {
      const std::size_t B = WI::number_of_coefficients(order);
      std::vector<double> base(B * P, -1.), avx(B * P, -2.), dispatched(B * P, -3.);
      WI::Basis_columns_kernel::run(x, y, L, P, order, base.data());
      if(has_avx) WI::run_avx<WI::Basis_columns_kernel>(x, y, L, P, order, avx.data());
      WI::evaluate_basis_columns(x, y, L, P, order, dispatched.data());
      basis_bitwise = basis_bitwise && (!has_avx || avx == base);
      dispatch_ok = dispatch_ok && dispatched == (has_avx ? avx : base);
      for(std::size_t k = 0; k <= order; ++k)
        for(std::size_t l = 0; l < P; ++l)
        {
          const double r = std::hypot(x[l], y[l]), theta = std::atan2(y[l], x[l]), rk = l < L ? std::pow(r, double(k)) : 0.;
          for(std::size_t n = k % 2; n <= k; n += 2)
          {
            const std::size_t column = WI::order_offset(k) + (n == 0 ? 0 : n - 1);
            basis_error = (std::max)(basis_error, std::abs(base[column * P + l] - rk * std::cos(double(n) * theta)));
            if(n > 0)
              basis_error = (std::max)(basis_error, std::abs(base[(column + 1) * P + l] - rk * std::sin(double(n) * theta)));
          }
        }
    }
    Eigen::Matrix3d axes = Eigen::Quaterniond(uniform(random), uniform(random), uniform(random), uniform(random))
                             .normalized().toRotationMatrix();
    const double rows[9] = {axes(0, 0), axes(0, 1), axes(0, 2), axes(1, 0), axes(1, 1), axes(1, 2), axes(2, 0), axes(2, 1), axes(2, 2)};
    std::vector<double> base(3 * P, -1.), avx(3 * P, -2.), dispatched(3 * P, -3.);
    WI::Projection_kernel::run(coordinates.data(), L, P, rows, base.data(), base.data() + P, base.data() + 2 * P);
    if(has_avx) WI::run_avx<WI::Projection_kernel>(static_cast<const double*>(coordinates.data()), L, P,
                                                    static_cast<const double*>(rows), avx.data(), avx.data() + P, avx.data() + 2 * P);
    WI::dispatch_avx<WI::Projection_kernel>(static_cast<const double*>(coordinates.data()), L, P,
                                            static_cast<const double*>(rows), dispatched.data(), dispatched.data() + P,
                                            dispatched.data() + 2 * P);
    projection_bitwise = projection_bitwise && (!has_avx || avx == base);
    dispatch_ok = dispatch_ok && dispatched == (has_avx ? avx : base);
    for(std::size_t l = 0; l < P; ++l)
    {
      const Eigen::Vector3d p(x[l], y[l], coordinates[2 * P + l]), q = axes * p;
      for(int i = 0; i < 3; ++i) projection_error = (std::max)(projection_error, std::abs(base[i * P + l] - q(i)));
    }
    double sums[9], sums_avx[9] = {0.}, sums_dispatched[9];
    WI::Moments_kernel::run(coordinates.data(), L, sums);
    if(has_avx) WI::run_avx<WI::Moments_kernel>(static_cast<const double*>(coordinates.data()), L, static_cast<double*>(sums_avx));
    WI::dispatch_avx<WI::Moments_kernel>(static_cast<const double*>(coordinates.data()), L, static_cast<double*>(sums_dispatched));
    moments_bitwise = moments_bitwise && (!has_avx || std::memcmp(sums, sums_avx, sizeof sums) == 0);
    dispatch_ok = dispatch_ok && std::memcmp(sums_dispatched, has_avx ? sums_avx : sums, sizeof sums) == 0;
    Eigen::MatrixXd X(L, 3);
    for(std::size_t l = 0; l < L; ++l)
      for(int i = 0; i < 3; ++i) X(l, i) = coordinates[i * P + l];
    const Eigen::Vector3d first = X.colwise().sum().transpose();
    const Eigen::Matrix3d second = X.transpose() * X;
    for(int i = 0, k = 0; i < 3; ++i)
    {
      moments_error = (std::max)(moments_error, std::abs(sums[i] - first(i)));
      for(int j = i; j < 3; ++j, ++k) moments_error = (std::max)(moments_error, std::abs(sums[3 + k] - second(i, j)));
    }
  }
  check_printed(basis_bitwise, std::string("basis columns, orders 1 to 8: AVX clone == baseline, bitwise") + (has_avx ? "" : " (skipped)"));
  check_printed(projection_bitwise, std::string("projection onto a frame: AVX clone == baseline, bitwise") + (has_avx ? "" : " (skipped)"));
  check_printed(moments_bitwise, std::string("PCA moments: AVX clone == baseline, bitwise") + (has_avx ? "" : " (skipped)"));
  check_printed(dispatch_ok, "dispatch_avx() runs the clone the processor supports (bitwise equal to it)");
  check_printed(basis_error <= 1e-14, "basis columns against r^k cos / sin (n theta): max error " + sci(basis_error));
  check_printed(projection_error <= 1e-15, "projection against Eigen's rotation: max error " + sci(projection_error));
  check_printed(moments_error <= 1e-13, "moments against Eigen's sums: max error " + sci(moments_error));
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"kernels.full_rank_agreement", test_full_rank_agreement<WI::Solver::HOUSEHOLDER_QR>},
    Case{"kernels.rank_deficient_reported", test_rank_deficient_reported<WI::Solver::HOUSEHOLDER_QR>},
    Case{"kernels.semi_normal_full_rank_agreement", test_full_rank_agreement<WI::Solver::SEMI_NORMAL_ELSE_QR>},
    Case{"kernels.semi_normal_rank_deficient_reported", test_rank_deficient_reported<WI::Solver::SEMI_NORMAL_ELSE_QR>},
    Case{"kernels.semi_normal_agrees_with_qr_on_wavejet_systems", test_semi_normal_on_wavejet_systems},
    Case{"kernels.semi_normal_falls_back_to_qr", test_semi_normal_fallback},
    Case{"kernels.wavejet_semi_normal_agrees_with_qr_on_wavejet_systems", test_wavejet_semi_normal_on_wavejet_systems},
    Case{"kernels.order2_moments_agree_with_qr_on_wavejet_systems", test_order2_moments_on_wavejet_systems},
    Case{"kernels.portable_build_bitwise", test_portable_build_bitwise},
    Case{"kernels.avx_only_kernels_bitwise", test_avx_only_kernels_bitwise},
  });
}
