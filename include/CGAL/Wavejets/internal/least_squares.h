// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the Wavejets package (https://github.com/cgal-wavejets/wavejets).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H
#define CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H

// Dense least squares min ||A c - b|| by Householder QR, in place on caller-owned scratch, without
// heap allocation. The normal equations are not used: the Wavejet systems are too ill-conditioned
// for them.
//
// Layout: column-major, every column (the right-hand side is one more column) padded with zero
// rows to a multiple of `householder_block` rows. Each dot product runs over whole blocks with
// `householder_block` independent partial sums (one per row residue), so it is vectorized along
// the rows and not bound by the latency of one long chain of additions; reflections are applied
// to four trailing columns at a time so that the Householder vector is loaded once for four
// columns. A column's dot product (hence the result) does not depend on that grouping, nor on the
// vector width the compiler picked: the partial sums and their final reduction are always the
// same, so the SSE2 and AVX code give bitwise identical results.

#include <boost/align/aligned_allocator.hpp>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <utility>
#include <vector>

// x86 with GCC or Clang: the solver is also compiled for AVX (without FMA, so the arithmetic,
// hence the result, is bitwise the same as the SSE2 code) and for AVX2 with FMA (the compiler fuses
// multiply-adds, ~1.3x faster; results differ in the last bits from the other two), and the best
// one the processor supports is picked at run time, the same for every call: results never depend
// on the thread or on the ConcurrencyTag. The user's opt-out macros (documented in the manual's
// installation section; define them before including any header of the package):
//   CGAL_WAVEJETS_NO_AVX_DISPATCH        baseline code only (no run-time dispatch);
//   CGAL_WAVEJETS_NO_FMA_DISPATCH        keep only the AVX variant (results bitwise equal to baseline);
//   CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS   the kernels' four-lane type is a plain struct instead of the
//                                        GCC/Clang vector extension (what other compilers get): same
//                                        arithmetic per lane, so bitwise the same results.
// The header's own macros (CGAL_WAVEJETS_AVX_DISPATCH, CGAL_WAVEJETS_KERNEL_INLINE,
// CGAL_WAVEJETS_TARGET) are #undef'd at its end; `avx_dispatch` says whether the dispatch is compiled in.
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__)) && \
    !defined(CGAL_WAVEJETS_NO_AVX_DISPATCH) && !defined(__FMA__)
#define CGAL_WAVEJETS_AVX_DISPATCH 1
#define CGAL_WAVEJETS_KERNEL_INLINE __attribute__((always_inline)) inline
#else
#define CGAL_WAVEJETS_KERNEL_INLINE inline
#endif

namespace CGAL {
namespace Wavejets {
namespace internal {

/// A column is taken as dependent on the previous ones when the part of it orthogonal to them
/// is below this fraction of its norm (numerical rank test of the non-pivoted QR).
constexpr double rank_tolerance = 1e-10;

/// Allocator of cache-line aligned storage for the solver's scratch: the kernels read and write
/// 32-byte vectors at multiples of householder_block doubles from the start of a column, which
/// then never straddle two cache lines (measured: the K = 6 normals were up to 10% slower when
/// the heap happened to return storage that was only 16-byte aligned).
template <class T>
using Aligned_allocator = boost::alignment::aligned_allocator<T, 64>;

/// A vector of doubles in cache-line aligned storage.
typedef std::vector<double, Aligned_allocator<double> > Aligned_vector;

/// Row blocking of the solver: column strides are multiples of it.
constexpr std::size_t householder_block = 8;

/// Column stride for `rows` rows: `rows` rounded up to a multiple of householder_block.
inline std::size_t padded_rows(std::size_t rows)
{
  return (rows + householder_block - 1) / householder_block * householder_block;
}

/// Sum of the householder_block partial sums, in a fixed order.
CGAL_WAVEJETS_KERNEL_INLINE double reduce_block(const double* acc)
{
  return ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]));
}

#if (defined(__GNUC__) || defined(__clang__)) && !defined(CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS)
/// Four doubles (GCC/Clang vector extension: one AVX register, or two SSE2 registers with the same
/// per-lane arithmetic). Unaligned memory is read and written with memcpy.
typedef double Double4 __attribute__((vector_size(32)));
#else
/// Four doubles, for compilers without the vector extension: the same per-lane arithmetic (each
/// operator below is what the extension does lane by lane), so the kernels, written once for
/// `Double4`, give bitwise the same results; the compiler may vectorize the lanes.
struct Double4
{
  double lane[4];
  friend Double4 operator*(const Double4& a, const Double4& b)
  {
    return Double4{{a.lane[0] * b.lane[0], a.lane[1] * b.lane[1], a.lane[2] * b.lane[2], a.lane[3] * b.lane[3]}};
  }
  friend Double4 operator+(const Double4& a, double s) // broadcast
  {
    return Double4{{a.lane[0] + s, a.lane[1] + s, a.lane[2] + s, a.lane[3] + s}};
  }
  Double4& operator+=(const Double4& b)
  {
    for(int t = 0; t < 4; ++t) lane[t] += b.lane[t];
    return *this;
  }
  Double4& operator-=(const Double4& b)
  {
    for(int t = 0; t < 4; ++t) lane[t] -= b.lane[t];
    return *this;
  }
};
#endif

CGAL_WAVEJETS_KERNEL_INLINE void load4(Double4& r, const double* p) { std::memcpy(&r, p, sizeof r); }
CGAL_WAVEJETS_KERNEL_INLINE void store4(double* p, const Double4& x) { std::memcpy(p, &x, sizeof x); }

/// w[m] = sum_{i = begin}^{end-1} v[i] x_m[i] for the M columns x_m = X + m * P (begin, end:
/// multiples of householder_block), with one partial sum per row residue (see reduce_block()).
template <int M>
CGAL_WAVEJETS_KERNEL_INLINE void householder_dots(const double* v, const double* X, std::size_t P,
                                                 std::size_t begin, std::size_t end, double* w)
{
  static_assert(householder_block == 8, "two Double4 per block");
  Double4 lo[M], hi[M]; // partial sums of the row residues 0..3 and 4..7
  for(int m = 0; m < M; ++m) { lo[m] = Double4{0., 0., 0., 0.}; hi[m] = lo[m]; }
  for(std::size_t i = begin; i < end; i += householder_block)
  {
    Double4 v_lo, v_hi, x_lo, x_hi;
    load4(v_lo, v + i);
    load4(v_hi, v + i + 4);
    for(int m = 0; m < M; ++m)
    {
      load4(x_lo, X + m * P + i);
      load4(x_hi, X + m * P + i + 4);
      lo[m] += v_lo * x_lo;
      hi[m] += v_hi * x_hi;
    }
  }
  for(int m = 0; m < M; ++m)
  {
    double acc[householder_block];
    store4(acc, lo[m]);
    store4(acc + 4, hi[m]);
    w[m] = reduce_block(acc);
  }
}

/// x_m[i] -= s[m] v[i] for the M columns x_m = X + m * P, rows begin..end-1 (multiples of
/// householder_block).
template <int M>
CGAL_WAVEJETS_KERNEL_INLINE void householder_updates(const double* v, double* X, std::size_t P, std::size_t begin,
                                                    std::size_t end, const double* s)
{
  Double4 sm[M];
  const Double4 zero = {0., 0., 0., 0.};
  for(int m = 0; m < M; ++m) sm[m] = zero + s[m]; // broadcast
  for(std::size_t i = begin; i < end; i += householder_block)
  {
    Double4 v_lo, v_hi, x_lo, x_hi;
    load4(v_lo, v + i);
    load4(v_hi, v + i + 4);
    for(int m = 0; m < M; ++m)
    {
      double* x = X + m * P + i;
      load4(x_lo, x);
      load4(x_hi, x + 4);
      x_lo -= sm[m] * v_lo;
      x_hi -= sm[m] * v_hi;
      store4(x, x_lo);
      store4(x + 4, x_hi);
    }
  }
}

/// x[i] -= s v[i] for rows begin..P-1 (the reflection of column j-1 applied to column j), and, in
/// the same pass, the start of column j's own Householder vector: vn[i] = x[i] for i >= j, 0 for
/// the rows of j's block above j; returns the sum of their squares, with the partial sums and
/// reduction of householder_dots() (the same value as householder_dots<1>(vn, vn, ...)).
CGAL_WAVEJETS_KERNEL_INLINE double householder_update_and_next(const double* v, double s, double* x, std::size_t begin,
                                                              std::size_t P, std::size_t j, double* vn)
{
  const std::size_t jb = j / householder_block * householder_block;
  const Double4 zero = {0., 0., 0., 0.};
  const Double4 sm = zero + s;
  Double4 lo = zero, hi = zero;
  for(std::size_t i = begin; i < P; i += householder_block)
  {
    Double4 v_lo, v_hi, x_lo, x_hi;
    load4(v_lo, v + i);
    load4(v_hi, v + i + 4);
    load4(x_lo, x + i);
    load4(x_hi, x + i + 4);
    x_lo -= sm * v_lo;
    x_hi -= sm * v_hi;
    store4(x + i, x_lo);
    store4(x + i + 4, x_hi);
    if(i < jb)
      continue; // rows above j's block: not part of column j's vector
    if(i == jb && j > jb)
    {
      double t[householder_block];
      store4(t, x_lo);
      store4(t + 4, x_hi);
      for(std::size_t r = 0; r < j - jb; ++r) t[r] = 0.;
      load4(x_lo, t);
      load4(x_hi, t + 4);
    }
    store4(vn + i, x_lo);
    store4(vn + i + 4, x_hi);
    lo += x_lo * x_lo;
    hi += x_hi * x_hi;
  }
  double acc[householder_block];
  store4(acc, lo);
  store4(acc + 4, hi);
  return reduce_block(acc);
}

/// Completes the Householder vector v of column j from the squared norm `tail2` of its rows j..:
/// `beta` = 2 / v.v and `alpha` = -sign(x_j)|x| (the diagonal entry of R). Returns false if the
/// part of the column orthogonal to the previous ones is below rank_tolerance of its norm.
CGAL_WAVEJETS_KERNEL_INLINE bool householder_finish(const double* a, std::size_t j, double tail2, double* v,
                                                   double& beta, double& alpha)
{
  double full2 = tail2;
  for(std::size_t i = 0; i < j; ++i) full2 += a[i] * a[i];
  const double tail = std::sqrt(tail2);
  if(!(tail > rank_tolerance * std::sqrt(full2)))
    return false; // also catches a zero column and NaN
  const double ajj = a[j];
  alpha = ajj >= 0 ? -tail : tail;
  const double v0 = ajj - alpha;
  beta = 2. / (tail2 - ajj * ajj + v0 * v0);
  v[j] = v0;
  return true;
}

/// Householder vector of column j (rows j.., j0 = the block of row j) into v, zero on rows j0..j-1
/// (see householder_finish()).
CGAL_WAVEJETS_KERNEL_INLINE bool householder_vector(const double* A, std::size_t P, std::size_t j, std::size_t j0,
                                                   double* v, double& beta, double& alpha)
{
  const double* a = A + j * P;
  for(std::size_t i = j0; i < j; ++i) v[i] = 0.;
  for(std::size_t i = j; i < P; ++i) v[i] = a[i];
  double tail2;
  householder_dots<1>(v, v, P, j0, P, &tail2);
  return householder_finish(a, j, tail2, v, beta, alpha);
}

/// Applies the reflection (v, beta) of a column whose block starts at row j0 to the columns
/// first..last of A, four at a time.
CGAL_WAVEJETS_KERNEL_INLINE void householder_reflect(const double* v, double beta, double* A, std::size_t P,
                                                    std::size_t j0, std::size_t first, std::size_t last)
{
  std::size_t l = first;
  double s[4] = {0., 0., 0., 0.};
  for(; l + 4 <= last + 1; l += 4)
  {
    householder_dots<4>(v, A + l * P, P, j0, P, s);
    for(int m = 0; m < 4; ++m) s[m] *= beta;
    householder_updates<4>(v, A + l * P, P, j0, P, s);
  }
  for(; l <= last; ++l)
  {
    householder_dots<1>(v, A + l * P, P, j0, P, s);
    s[0] *= beta;
    householder_updates<1>(v, A + l * P, P, j0, P, s);
  }
}

/// Kernel of householder_least_squares(). Column j's reflection is applied to the trailing columns;
/// every loop runs over whole blocks from the block that holds row j (the zeros of the Householder
/// vector above row j leave those rows unchanged). Column j+1 goes first, alone, and the same pass
/// starts its own Householder vector (see householder_update_and_next()): that vector is what the
/// next step waits for, and the processor builds it while it updates the other columns. Every
/// column sees the same operations in the same order as with one pass per column: the result does
/// not depend on this schedule.
CGAL_WAVEJETS_KERNEL_INLINE bool householder_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                   double* c)
{
  if(rows < cols || cols == 0)
    return false;
  const std::size_t P = padded_rows(rows);
  double* v = scratch;          // reflection of column j
  double* v_next = scratch + P; // reflection of column j+1
  double beta, alpha;
  if(!householder_vector(A, P, 0, 0, v, beta, alpha))
    return false;
  for(std::size_t j = 0; j < cols; ++j)
  {
    const std::size_t j0 = j / householder_block * householder_block;
    double* next = A + (j + 1) * P; // column j+1, or b
    double s;
    householder_dots<1>(v, next, P, j0, P, &s);
    s *= beta;
    double beta_next = 0., alpha_next = 0.;
    if(j + 1 < cols)
    {
      const double tail2 = householder_update_and_next(v, s, next, j0, P, j + 1, v_next);
      if(!householder_finish(next, j + 1, tail2, v_next, beta_next, alpha_next))
        return false;
    }
    else
      householder_updates<1>(v, next, P, j0, P, &s);
    householder_reflect(v, beta, A, P, j0, j + 2, cols); // columns j+2..cols-1 and b
    A[j * P + j] = alpha; // diagonal of R
    std::swap(v, v_next);
    beta = beta_next;
    alpha = alpha_next;
  }
  const double* b = A + cols * P;
  for(std::size_t jj = cols; jj-- > 0;)
  {
    double sum = b[jj];
    for(std::size_t l = jj + 1; l < cols; ++l) sum -= A[l * P + jj] * c[l];
    c[jj] = sum / A[jj * P + jj];
  }
  return true;
}

#ifdef CGAL_WAVEJETS_AVX_DISPATCH
/// True if `householder_fma()` and `householder_avx()` are compiled for those instruction sets and
/// picked at run time by `householder_least_squares()` (else they are the baseline code).
constexpr bool avx_dispatch = true;
#define CGAL_WAVEJETS_TARGET(instruction_sets) __attribute__((target(instruction_sets)))
#else
constexpr bool avx_dispatch = false;
#define CGAL_WAVEJETS_TARGET(instruction_sets)
#endif

/// The kernel compiled for AVX2 + FMA (run it only where the processor has both).
CGAL_WAVEJETS_TARGET("avx2,fma") inline bool householder_fma(double* A, std::size_t rows, std::size_t cols,
                                                             double* v, double* c)
{
  return householder_kernel(A, rows, cols, v, c);
}
/// The kernel compiled for AVX (run it only where the processor has it).
CGAL_WAVEJETS_TARGET("avx") inline bool householder_avx(double* A, std::size_t rows, std::size_t cols,
                                                        double* v, double* c)
{
  return householder_kernel(A, rows, cols, v, c);
}

/// Solves min ||A c - b|| for a rows x cols matrix `A`. `A` is column-major with column stride
/// padded_rows(rows), followed by `b` as column `cols`; rows `rows`..padded_rows(rows)-1 of every
/// column must be zero. `v` is scratch of 2 padded_rows(rows) doubles. On return the upper triangle
/// of the first `cols` columns holds R (R(i, j) = A[j * padded_rows(rows) + i], i <= j) and
/// `c[0..cols-1]` the solution. Returns false if the system has fewer rows than columns or is
/// numerically rank-deficient.
inline bool householder_least_squares(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
#ifdef CGAL_WAVEJETS_AVX_DISPATCH
#ifndef CGAL_WAVEJETS_NO_FMA_DISPATCH
  static const bool fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  const bool fma = false;
#endif
  static const bool avx = __builtin_cpu_supports("avx");
  if(fma)
    return householder_fma(A, rows, cols, v, c);
  if(avx)
    return householder_avx(A, rows, cols, v, c);
#endif
  return householder_kernel(A, rows, cols, v, c);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#undef CGAL_WAVEJETS_TARGET
#undef CGAL_WAVEJETS_KERNEL_INLINE
#undef CGAL_WAVEJETS_AVX_DISPATCH

#endif // CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H
