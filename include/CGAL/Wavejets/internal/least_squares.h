// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H
#define CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H

// Dense least squares min ||A c - b||, in place on caller-owned scratch, without heap allocation:
// least_squares() solves by the corrected semi-normal equations (doc/Wavejets/Mathematics.txt section 2, step 3),
// guarded, and hands the systems too ill-conditioned for them to the Householder QR
// (householder_least_squares()). Plain normal equations are not used: the Wavejet systems are too
// ill-conditioned for them. wavejet_least_squares() is the same solver for a system whose columns
// are the Wavejet basis (basis.h): it builds the Gram matrix M^T M from the polar moments of the
// neighborhood (polar_moment_gram_upper()) instead of from the dot products of M's columns.
//
// Layout: column-major, every column (the right-hand side is one more column) padded with zero
// rows to a multiple of `householder_block` rows. Each dot product runs over whole blocks with
// `householder_block` independent partial sums (one per row residue), so it is vectorized along
// the rows and not bound by the latency of one long chain of additions; reflections are applied
// to four trailing columns at a time so that the Householder vector is loaded once for four
// columns. A column's dot product (hence the result) does not depend on that grouping, nor on the
// vector width the compiler picked: the partial sums and their final reduction are always the
// same, so the SSE2 and AVX code give bitwise identical results.

#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/instruction_sets.h>

#include <boost/align/aligned_allocator.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

// The solver is also compiled for AVX, for AVX2 with FMA (the compiler fuses multiply-adds,
// ~1.3x faster; results differ in the last bits from the other two) and for AVX-512 (the order-2
// kernel eight rows per step: its results differ in the last bits from the AVX2 + FMA variant's,
// the other solvers' are bitwise the same), picked at run time (instruction_sets.h). The user's
// opt-out macros (documented in the manual's installation section; define them before including
// any header of the package), besides instruction_sets.h's:
//   CGAL_WAVEJETS_NO_FMA_DISPATCH        keep only the AVX variant (results bitwise equal to baseline);
//   CGAL_WAVEJETS_NO_AVX512_DISPATCH     no AVX-512 variant (AVX2 + FMA is the best);
//   CGAL_WAVEJETS_NO_SEMI_NORMAL         every system built and solved by the Householder QR (also the
//                                        order-2 fits, which are otherwise solved from their moments);
//   CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS   the kernels' four-lane type is a plain struct instead of the
//                                        GCC/Clang vector extension (what other compilers get): same
//                                        arithmetic per lane, so bitwise the same results, except that
//                                        there is no AVX-512 variant (its eight-lane order-2 fits).

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
  friend Double4 operator+(const Double4& a, const Double4& b)
  {
    return Double4{{a.lane[0] + b.lane[0], a.lane[1] + b.lane[1], a.lane[2] + b.lane[2], a.lane[3] + b.lane[3]}};
  }
  friend Double4 operator-(const Double4& a, const Double4& b)
  {
    return Double4{{a.lane[0] - b.lane[0], a.lane[1] - b.lane[1], a.lane[2] - b.lane[2], a.lane[3] - b.lane[3]}};
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

// The AVX-512 variant of the solver (dispatch_solver()): compiled where the AVX2 + FMA one is and the
// vector extension exists, unless CGAL_WAVEJETS_NO_AVX512_DISPATCH is defined.
#if defined(CGAL_WAVEJETS_AVX_DISPATCH) && !defined(CGAL_WAVEJETS_NO_FMA_DISPATCH) && \
    !defined(CGAL_WAVEJETS_NO_AVX512_DISPATCH) && !defined(CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS)
#define CGAL_WAVEJETS_AVX512_DISPATCH 1
/// Eight doubles (one AVX-512 register): the lanes of the order-2 kernel in the AVX-512 variant.
typedef double Double8 __attribute__((vector_size(64)));
#endif

/// Lanes in a vector of `Lanes` (Double4 or Double8).
template <class Lanes>
constexpr std::size_t lane_count()
{
  return sizeof(Lanes) / sizeof(double);
}

/// Loads lane_count<Lanes>() doubles from p (unaligned).
template <class Lanes>
CGAL_WAVEJETS_KERNEL_INLINE void load_lanes(Lanes& r, const double* p)
{
  std::memcpy(&r, p, sizeof r);
}

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

/// w[m] = (column m of X) . v for the columns first..last-1 of X (stride P, rows 0..P-1), four
/// columns per pass over v (householder_dots(): the same partial sums and reduction per column).
CGAL_WAVEJETS_KERNEL_INLINE void column_dots(const double* v, const double* X, std::size_t P, std::size_t first,
                                            std::size_t last, double* w)
{
  std::size_t m = first;
  for(; m + 4 <= last; m += 4) householder_dots<4>(v, X + m * P, P, 0, P, w + m);
  for(; m < last; ++m) householder_dots<1>(v, X + m * P, P, 0, P, w + m);
}

/// y[l] -= a[t] x[t * stride + l] for t = 0, 1, 2, 3 in that order (four multiply-adds per load and
/// store of y), l = begin, begin + 4, ... < end (whole blocks of four).
CGAL_WAVEJETS_KERNEL_INLINE void subtract_four_multiples(double* y, const double* x, std::size_t stride, const double* a,
                                                        std::size_t begin, std::size_t end)
{
  const Double4 zero = {0., 0., 0., 0.};
  const Double4 a0 = zero + a[0], a1 = zero + a[1], a2 = zero + a[2], a3 = zero + a[3];
  for(std::size_t l = begin; l < end; l += 4)
  {
    Double4 yv, x0, x1, x2, x3;
    load4(yv, y + l);
    load4(x0, x + l);
    load4(x1, x + stride + l);
    load4(x2, x + 2 * stride + l);
    load4(x3, x + 3 * stride + l);
    yv -= a0 * x0;
    yv -= a1 * x1;
    yv -= a2 * x2;
    yv -= a3 * x3;
    store4(y + l, yv);
  }
}

/// r = b - M c for the n columns of M (stride P, rows 0..P-1) and b = column n, four columns per
/// pass over r. Each row subtracts c[j] M(l, j) for j = 0, 1, ... in order: the values of
/// householder_updates<1>() column by column.
CGAL_WAVEJETS_KERNEL_INLINE void residual_of(const double* M, std::size_t P, std::size_t n, const double* c, double* r)
{
  std::memcpy(r, M + n * P, P * sizeof(double));
  std::size_t j = 0;
  for(; j + 4 <= n; j += 4) subtract_four_multiples(r, M + j * P, P, c + j, 0, P);
  for(; j < n; ++j) householder_updates<1>(M + j * P, r, P, 0, P, c + j);
}

/// Sum of the four lanes of x, in a fixed order.
CGAL_WAVEJETS_KERNEL_INLINE double reduce4(const Double4& x)
{
  double a[4];
  store4(a, x);
  return (a[0] + a[2]) + (a[1] + a[3]);
}

/// Sum of the lanes, in a fixed order (reduce4(), or reduce_block() of the eight lanes).
CGAL_WAVEJETS_KERNEL_INLINE double reduce_lanes(const Double4& x) { return reduce4(x); }
#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
CGAL_WAVEJETS_KERNEL_INLINE double reduce_lanes(const Double8& x)
{
  double a[8];
  std::memcpy(a, &x, sizeof a);
  return reduce_block(a);
}
#endif

/// The Gram block G(i + a, j + m) = column (i + a) . column (j + m) of X (stride P, rows 0..P-1) for
/// a < 2, m < 4: the two columns i, i+1 are loaded once for four columns j.., and each of the
/// eight dot products has its own four-lane accumulator (one partial sum per row residue mod 4).
CGAL_WAVEJETS_KERNEL_INLINE void gram_tile(const double* X, std::size_t P, std::size_t i, std::size_t j, double* G,
                                          std::size_t stride)
{
  const Double4 zero = {0., 0., 0., 0.};
  Double4 acc[2][4] = {{zero, zero, zero, zero}, {zero, zero, zero, zero}};
  const double* u0 = X + i * P;
  const double* u1 = u0 + P;
  const double* x = X + j * P;
  for(std::size_t r = 0; r < P; r += 4)
  {
    Double4 a0, a1, b;
    load4(a0, u0 + r);
    load4(a1, u1 + r);
    for(int m = 0; m < 4; ++m)
    {
      load4(b, x + m * P + r);
      acc[0][m] += a0 * b;
      acc[1][m] += a1 * b;
    }
  }
  for(int a = 0; a < 2; ++a)
    for(int m = 0; m < 4; ++m) G[(i + a) * stride + j + m] = reduce4(acc[a][m]);
}

/// G(i, j) = column i . column j of X (stride P, rows 0..P-1) for 0 <= i < n and i <= j <= n: the
/// upper triangle of the Gram matrix of the first n columns, and in column n their dots with column
/// n (b); row-major with row stride `stride` >= n + 1. Pairs of rows by 2 x 4 tiles (gram_tile(),
/// which may start left of the diagonal: those entries are computed and not read), the rest dot by
/// dot (householder_dots()).
CGAL_WAVEJETS_KERNEL_INLINE void gram_upper(const double* X, std::size_t P, std::size_t n, double* G, std::size_t stride)
{
  std::size_t i = 0;
  for(; i + 1 < n; i += 2)
  {
    std::size_t j = i / 4 * 4;
    for(; j + 4 <= n + 1; j += 4) gram_tile(X, P, i, j, G, stride);
    for(; j <= n; ++j)
      for(std::size_t a = 0; a < 2; ++a) householder_dots<1>(X + (i + a) * P, X + j * P, P, 0, P, G + (i + a) * stride + j);
  }
  if(i < n) column_dots(X + i * P, X, P, i, n + 1, G + i * stride);
}

/// Row stride of the semi-normal solvers' n x n triangular factors: at least n + 1 (column n holds
/// M^T b), a whole number of blocks of four.
inline std::size_t semi_normal_row_stride(std::size_t n) { return (n + 4) / 4 * 4; }

/// Largest order K whose Gram matrix polar_moment_gram_upper() builds from polar moments.
constexpr std::size_t polar_moment_maximum_order = 12;

/// Real columns of the powers z^m = (x + i y)^m, m = 0..2K, in polar_moment_gram_upper(): Re z^0,
/// then Re z^m, Im z^m for m = 1..2K; rounded up to whole tiles of four.
inline std::size_t polar_power_columns(std::size_t order) { return (4 * order + 1 + 3) / 4 * 4; }

/// The Gram matrix of the order-K Wavejet basis from its polar moments mu[a * polar_power_columns(K)
/// + c] = sum_l r_l^{2a} Z_c(l) (Z_c: the c-th real column of the powers z^m, see
/// polar_power_columns()): each entry G[i * S + j] of the upper triangle (S = semi_normal_row_stride(B))
/// is one moment, half of one, or the half-sum or half-difference
/// of two: lists of (entry, moment) and of (entry, moment, moment) indices.
struct Polar_moment_terms
{
  std::vector<unsigned short> single, half, half_sum, half_difference;
};

/// The terms of polar_moment_gram_upper() for every order up to polar_moment_maximum_order, built
/// once. Column b of the basis is r^k cos(n theta) or r^k sin(n theta); the product of two columns
/// is r^p (p = k + k') times cos cos = (cos(n - n') + cos(n + n')) / 2, sin sin = (cos(n - n') -
/// cos(n + n')) / 2, cos sin or sin cos = (sin(n + n') -+ sin(n - n')) / 2 (of theta), and
/// r^p cos(m theta) = r^{p - m} Re z^m, r^p sin(m theta) = r^{p - m} Im z^m, with p - m even
/// (n = k mod 2 in the basis) and m <= p.
inline const Polar_moment_terms& polar_moment_terms(std::size_t order)
{
  static const std::array<Polar_moment_terms, polar_moment_maximum_order + 1> tables = [] {
    std::array<Polar_moment_terms, polar_moment_maximum_order + 1> all;
    for(std::size_t K = 1; K <= polar_moment_maximum_order; ++K)
    {
      const std::size_t B = number_of_coefficients(K), S = semi_normal_row_stride(B), Z = polar_power_columns(K);
      std::vector<int> degree, frequency, is_sine; // of each column
      for(std::size_t k = 0; k <= K; ++k)
        for(std::size_t n = k % 2; n <= k; n += 2)
          for(int sine = 0; sine < (n > 0 ? 2 : 1); ++sine)
          {
            degree.push_back(int(k));
            frequency.push_back(int(n));
            is_sine.push_back(sine);
          }
      // Moment index of r^p cos(m theta) and of r^p sin(m theta), m >= 0.
      auto cosine = [Z](int p, int m) { return ((p - m) / 2) * Z + (m == 0 ? 0 : 2 * m - 1); };
      auto sine = [Z](int p, int m) { return ((p - m) / 2) * Z + 2 * m; };
      Polar_moment_terms& t = all[K];
      auto add = [](std::vector<unsigned short>& list, std::size_t entry, std::size_t first, std::size_t second) {
        list.push_back((unsigned short)(entry));
        list.push_back((unsigned short)(first));
        list.push_back((unsigned short)(second));
      };
      for(std::size_t i = 0; i < B; ++i)
        for(std::size_t j = i; j < B; ++j)
        {
          const int p = degree[i] + degree[j], n = frequency[i], m = frequency[j];
          const int difference = n > m ? n - m : m - n, sum = n + m;
          const std::size_t e = i * S + j;
          if(!is_sine[i] && !is_sine[j])
          {
            if(n == 0 || m == 0)
            {
              t.single.push_back((unsigned short)(e));
              t.single.push_back((unsigned short)(cosine(p, sum)));
            }
            else
              add(t.half_sum, e, cosine(p, difference), cosine(p, sum));
          }
          else if(is_sine[i] && is_sine[j])
            add(t.half_difference, e, cosine(p, difference), cosine(p, sum));
          else
          { // sin(n + n') / 2 - sin(d) / 2, d = (frequency of the cosine) - (frequency of the sine)
            const int d = is_sine[i] ? m - n : n - m;
            if(n == 0 || m == 0) // r^k times r^k' sin(n' theta): one moment
            {
              t.single.push_back((unsigned short)(e));
              t.single.push_back((unsigned short)(sine(p, sum)));
            }
            else if(d == 0) // cos(n theta) sin(n theta) = sin(2 n theta) / 2
            {
              t.half.push_back((unsigned short)(e));
              t.half.push_back((unsigned short)(sine(p, sum)));
            }
            else if(d > 0)
              add(t.half_difference, e, sine(p, sum), sine(p, d));
            else
              add(t.half_sum, e, sine(p, sum), sine(p, -d));
          }
        }
    }
    return all;
  }();
  return tables[order];
}

/// Scratch doubles of polar_moment_gram_upper() at order K, P rows: the powers z^m and r^{2a} that
/// are not columns of the basis, and the moments.
inline std::size_t polar_moment_scratch_size(std::size_t P, std::size_t order)
{
  return (2 * order + (order - order / 2)) * P + (order + 1) * polar_power_columns(order);
}

/// The Gram matrix of the order-K Wavejet basis columns of A (evaluate_basis_columns(); stride P,
/// zero padding rows, b in column B) from the polar moments sum_l r_l^{2a} z_l^m (2a + m <= 2K):
/// the same upper triangle and column B (M^T b, dot by dot) as gram_upper(), in about a quarter of
/// its multiply-adds (the moments are dot products of the columns r^{2a} with the real columns of
/// z^m, by 2 x 4 tiles of four-lane accumulators). The powers that are columns of the basis are read
/// there (z^m = r^m e^{i m theta} for m <= K, r^{2a} for 2a <= K), the others are built in `scratch`
/// (polar_moment_scratch_size()). Rounding: each moment is a sum of correctly signed terms, but the
/// entries of two moments (cos cos, sin sin...) lose digits when both are large and their half-sum
/// small; the semi-normal kernel's guards see that (its refinement step uses M itself).
CGAL_WAVEJETS_KERNEL_INLINE void polar_moment_gram_upper(const double* A, std::size_t P, std::size_t order,
                                                        double* scratch, double* G)
{
  const std::size_t K = order, B = number_of_coefficients(K), Z = polar_power_columns(K);
  const double* x = A + P;
  const double* y = A + 2 * P;
  const double* power[4 * polar_moment_maximum_order + 4]; // real columns of z^m
  const double* radial[polar_moment_maximum_order + 2];    // r^{2a}
  power[0] = A;
  for(std::size_t m = 1; m <= K; ++m)
  {
    power[2 * m - 1] = A + (order_offset(m) + m - 1) * P;
    power[2 * m] = A + (order_offset(m) + m) * P;
  }
  // The powers z^m, m = K+1..2K, then r^{2a}, 2a > K, into `scratch`, row block by row block: each
  // value is computed as evaluate_basis_columns() computes the basis (z^m = z^{m-1} z, r^{2a} =
  // (x^2 + y^2) r^{2a-2}), the chain kept in registers instead of re-read from the column before.
  const std::size_t first_built_radial = K / 2 + 1; // the first a with 2a > K
  double* const built_powers = scratch;
  double* const built_radials = scratch + 2 * K * P;
  for(std::size_t m = 1; m <= K; ++m)
  {
    power[2 * m - 1 + 2 * K] = built_powers + 2 * (m - 1) * P;
    power[2 * m + 2 * K] = built_powers + (2 * (m - 1) + 1) * P;
  }
  for(std::size_t a = 0; a <= K; ++a)
    radial[a] = a < first_built_radial ? A + order_offset(2 * a) * P : built_radials + (a - first_built_radial) * P;
  const double* last_basis_re = power[2 * K - 1];
  const double* last_basis_im = power[2 * K];
  const double* last_basis_radial = radial[first_built_radial - 1];
  for(std::size_t l = 0; l < P; l += 4)
  {
    Double4 xv, yv, re, im, r;
    load4(xv, x + l);
    load4(yv, y + l);
    load4(re, last_basis_re + l);
    load4(im, last_basis_im + l);
    for(std::size_t m = K + 1; m <= 2 * K; ++m)
    {
      const Double4 next_re = re * xv - im * yv;
      const Double4 next_im = re * yv + im * xv;
      re = next_re;
      im = next_im;
      store4(built_powers + 2 * (m - K - 1) * P + l, re);
      store4(built_powers + (2 * (m - K - 1) + 1) * P + l, im);
    }
    load4(r, last_basis_radial + l);
    for(std::size_t a = first_built_radial; a <= K; ++a)
    {
      r = (xv * xv + yv * yv) * r;
      store4(built_radials + (a - first_built_radial) * P + l, r);
    }
  }
  double* built = built_radials + (K - first_built_radial + 1) * P;
  radial[K + 1] = radial[K]; // the partner of row K when K is even: never read (row K has one column)
  // Moments mu[a * Z + c] = r^{2a} . (column c of the powers), for the c of z^m with 2a + m <= 2K:
  // row a needs the columns c < 4(K - a) + 1. Rows a, a + 1 together by tiles of four columns (row
  // a + 1 needs four columns fewer: its part of the last tile that starts below row a's last
  // column is computed and not read), then row a's last column, Im z^{2(K - a)}, alone.
  double* mu = built;
  const Double4 zero = {0., 0., 0., 0.};
  for(std::size_t a = 0; a <= K; a += 2)
  {
    const std::size_t last = 4 * (K - a); // row a's last column
    const double* u0 = radial[a];
    const double* u1 = radial[a + 1];
    for(std::size_t c = 0; c < last; c += 4)
    {
      Double4 acc[2][4] = {{zero, zero, zero, zero}, {zero, zero, zero, zero}};
      const double* z[4] = {power[c], power[c + 1], power[c + 2], power[c + 3]};
      for(std::size_t r = 0; r < P; r += 4)
      {
        Double4 a0, a1, b;
        load4(a0, u0 + r);
        load4(a1, u1 + r);
        for(int m = 0; m < 4; ++m)
        {
          load4(b, z[m] + r);
          acc[0][m] += a0 * b;
          acc[1][m] += a1 * b;
        }
      }
      for(int m = 0; m < 4; ++m)
      {
        mu[a * Z + c + m] = reduce4(acc[0][m]);
        mu[(a + 1) * Z + c + m] = reduce4(acc[1][m]);
      }
    }
    Double4 acc = zero, a0, b;
    for(std::size_t r = 0; r < P; r += 4)
    {
      load4(a0, u0 + r);
      load4(b, power[last] + r);
      acc += a0 * b;
    }
    mu[a * Z + last] = reduce4(acc);
  }
  // The entries (halving is exact: the same values whether or not the compiler fuses).
  const Polar_moment_terms& terms = polar_moment_terms(K);
  for(std::size_t t = 0; t < terms.single.size(); t += 2) G[terms.single[t]] = mu[terms.single[t + 1]];
  for(std::size_t t = 0; t < terms.half.size(); t += 2) G[terms.half[t]] = 0.5 * mu[terms.half[t + 1]];
  for(std::size_t t = 0; t < terms.half_sum.size(); t += 3)
    G[terms.half_sum[t]] = 0.5 * (mu[terms.half_sum[t + 1]] + mu[terms.half_sum[t + 2]]);
  for(std::size_t t = 0; t < terms.half_difference.size(); t += 3)
    G[terms.half_difference[t]] = 0.5 * (mu[terms.half_difference[t + 1]] - mu[terms.half_difference[t + 2]]);
  const std::size_t S = semi_normal_row_stride(B);
  double dots[(polar_moment_maximum_order + 1) * (polar_moment_maximum_order + 2) / 2];
  column_dots(A + B * P, A, P, 0, B, dots); // M^T b
  for(std::size_t i = 0; i < B; ++i) G[i * S + B] = dots[i];
}

/// y[l] -= a x[l] for l = begin, begin + 1, ... while a whole block of four fits before `end`,
/// four lanes at a time; returns the first l not done (`end` when end - begin is a multiple of four).
CGAL_WAVEJETS_KERNEL_INLINE std::size_t subtract_multiple_blocks(double* y, const double* x, double a, std::size_t begin,
                                                                std::size_t end)
{
  const Double4 zero = {0., 0., 0., 0.};
  const Double4 am = zero + a;
  std::size_t l = begin;
  for(; l + 4 <= end; l += 4)
  {
    Double4 xv, yv;
    load4(xv, x + l);
    load4(yv, y + l);
    yv -= am * xv;
    store4(y + l, yv);
  }
  return l;
}

/// y[l] -= a x[l] for l in [begin, end): the rows of a triangular factor and the right-hand side
/// are short, so the whole multiple-of-four part goes through subtract_multiple_blocks() (the head
/// and the tail lane by lane, with the same arithmetic).
CGAL_WAVEJETS_KERNEL_INLINE void subtract_multiple(double* y, const double* x, double a, std::size_t begin, std::size_t end)
{
  std::size_t l = begin;
  for(; l < end && l % 4 != 0; ++l) y[l] -= a * x[l];
  for(l = subtract_multiple_blocks(y, x, a, l, end); l < end; ++l) y[l] -= a * x[l];
}

/// Solves U^T E U x = y in place: U unit upper triangular n x n, row-major with row stride S in
/// `U` (row i: U(i, i+1..n-1); the diagonal is not read), `Ut` its transpose likewise (row i:
/// U(0..i-1, i)), `inverse_pivot` 1 / E(i). Both triangular solves subtract, per unknown, a multiple
/// of a row from the remaining right-hand side: independent multiply-adds that vectorize, instead of
/// one latency-bound dot product per unknown.
template <class Count, class Stride>
CGAL_WAVEJETS_KERNEL_INLINE void factored_solve(const double* U, const double* Ut, const double* inverse_pivot, Count n,
                                               Stride S, double* x)
{
  for(std::size_t i = 0; i < n; ++i) // U^T z = y
    subtract_multiple(x, U + i * S, x[i], i + 1, n);
  for(std::size_t i = 0; i < n; ++i) x[i] *= inverse_pivot[i];
  for(std::size_t i = n; i-- > 0;) // U x = E^-1 z
    subtract_multiple(x, Ut + i * S, x[i], 0, i);
}

/// Smallest Cholesky pivot of the column-scaled Gram matrix D M^T M D (unit diagonal) accepted by
/// the semi-normal solver: below it, cond(M D) is at least about 1 / semi_normal_pivot_guard, and
/// the QR solves the system instead.
constexpr double semi_normal_pivot_guard = 1e-3;
/// Largest relative correction of the refinement step accepted by the semi-normal solver: a larger
/// one says that the first solve was inaccurate, and the QR solves the system instead.
constexpr double semi_normal_correction_guard = 1e-6;

/// Scratch doubles needed by semi_normal_kernel() for a system of `cols` unknowns and `rows` rows.
inline std::size_t semi_normal_scratch_size(std::size_t rows, std::size_t cols)
{
  return padded_rows(rows) + (2 * cols + 1) * semi_normal_row_stride(cols) + 3 * cols + 1;
}

/// Where semi_normal_kernel() with a Wavejet order puts polar_moment_gram_upper()'s scratch: after its
/// own, at a whole block (the columns built there are as aligned as the scratch).
inline std::size_t polar_moment_scratch_offset(std::size_t rows, std::size_t cols)
{
  return padded_rows(semi_normal_scratch_size(rows, cols));
}

/// Scratch doubles needed by semi_normal_kernel() with a Wavejet order K > 0 (cols unknowns).
inline std::size_t wavejet_semi_normal_scratch_size(std::size_t rows, std::size_t cols, std::size_t order)
{
  return polar_moment_scratch_offset(rows, cols) + polar_moment_scratch_size(padded_rows(rows), order);
}

/// The solve shared by the semi-normal solvers, from the Gram matrix G = M^T M (upper triangle,
/// row-major with row stride S in `R`, S >= n + 1) and M^T b (in R's column n): the column scales
/// `scale` (D = diag(1 / sqrt(G(i, i))); room for S doubles, zero from n on), the factor U^T E U of
/// D G D (the Cholesky factor without its square roots: U unit upper triangular, E diagonal, E(i)
/// the squared Cholesky pivot), U overwriting G in `R` with E on its diagonal, its transpose in
/// `Rt`, 1 / E in `inverse_pivot`, and the first solution x into `c`. `rhs`: n scratch doubles.
/// Returns false if G has a non-positive or non-finite diagonal entry or a scaled Cholesky pivot is
/// below semi_normal_pivot_guard (E(i) below its square).
template <class Count, class Stride>
CGAL_WAVEJETS_KERNEL_INLINE bool semi_normal_factor_and_solve(double* R, double* Rt, double* scale, double* inverse_pivot,
                                                             double* rhs, Count n, Stride S, double* c)
{
  for(std::size_t i = 0; i < n; ++i)
    if(!(R[i * S + i] > 0.) || !std::isfinite(R[i * S + i]))
      return false;
  const std::size_t blocks_end = (n + 3) / 4 * 4; // <= S
  for(std::size_t i = 0; i < n; ++i)
  {
    scale[i] = 1. / std::sqrt(R[i * S + i]);
    rhs[i] = R[i * S + n] * scale[i];
  }
  for(std::size_t i = n; i < blocks_end; ++i) scale[i] = 0.;
  // D G D, by whole blocks of four columns from the block of the diagonal to the one of column
  // n - 1: the entries left of the diagonal and right of column n - 1 in those blocks are then set
  // to zero and never read, so the factor below is the one the element-wise updates give, bit for
  // bit, with no scalar head or tail.
  const Double4 zero = {0., 0., 0., 0.};
  for(std::size_t i = 0; i < n; ++i)
  {
    double* row = R + i * S;
    const Double4 row_scale = zero + scale[i];
    for(std::size_t j = i / 4 * 4; j < blocks_end; j += 4)
    {
      Double4 entries, column_scales;
      load4(entries, row + j);
      load4(column_scales, scale + j);
      entries = entries * (row_scale * column_scales);
      store4(row + j, entries);
    }
    for(std::size_t j = i / 4 * 4; j < i; ++j) row[j] = 0.;
    for(std::size_t j = n; j < blocks_end; ++j) row[j] = 0.; // M^T b, read above
  }
  // U^T E U, right-looking by panels of four pivot rows, no square root on the chain from one
  // pivot to the next (the Cholesky factor's would be). Every entry (j, k) receives the updates
  // -U(i, j) W(i, k) of the pivots i < j in increasing order (W: a pivot row before its division by
  // E(i)), as in the one-pivot-at-a-time elimination, bit for bit; a panel's four rows update each
  // row below them in one pass (four multiply-adds per load and store of a block).
  for(std::size_t i0 = 0; i0 < n; i0 += 4)
  {
    const std::size_t i1 = (std::min)(i0 + 4, std::size_t(n)); // the panel's rows i0..i1-1
    for(std::size_t i = i0; i < i1; ++i) // the panel's own rows
    {
      double* row = R + i * S;
      if(!(row[i] > semi_normal_pivot_guard * semi_normal_pivot_guard))
        return false;
      inverse_pivot[i] = 1. / row[i];
      for(std::size_t j = i + 1; j < i1; ++j)
        subtract_multiple_blocks(R + j * S, row, row[j] * inverse_pivot[i], i0, blocks_end);
    }
    const double* panel = R + i0 * S;
    for(std::size_t j = i1; j < n; ++j) // the rows below (none after a partial panel: the last)
    {
      double* multipliers = Rt + j * S + i0; // U(i0..i0+3, j), in U's transpose
      for(std::size_t t = 0; t < 4; ++t) multipliers[t] = panel[t * S + j] * inverse_pivot[i0 + t];
      subtract_four_multiples(R + j * S, panel, S, multipliers, j / 4 * 4, blocks_end);
    }
    for(std::size_t i = i0; i < i1; ++i) // divide the panel's rows by their pivots
    {
      double* row = R + i * S;
      Rt[i * S + i] = row[i];
      for(std::size_t j = i + 1; j < i1; ++j)
      {
        row[j] *= inverse_pivot[i];
        Rt[j * S + i] = row[j];
      }
      const Double4 inverse = zero + inverse_pivot[i];
      for(std::size_t k = (i1 + 3) / 4 * 4; k < blocks_end; k += 4)
      {
        Double4 entries;
        load4(entries, row + k);
        entries = entries * inverse;
        store4(row + k, entries);
      }
    }
  }
  factored_solve(R, Rt, inverse_pivot, n, S, rhs); // scaled solution D^-1 x
  for(std::size_t j = 0; j < n; ++j) c[j] = rhs[j] * scale[j];
  return true;
}

/// The refinement step shared by the semi-normal solvers: `correction` holds M^T r (r = b - M x)
/// on entry; solves for dx with the factor of semi_normal_factor_and_solve() and adds it to `c`.
/// Returns false if the correction exceeds semi_normal_correction_guard times the solution.
template <class Count, class Stride>
CGAL_WAVEJETS_KERNEL_INLINE bool semi_normal_refine(const double* R, const double* Rt, const double* scale,
                                                   const double* inverse_pivot, Count n, Stride S,
                                                   double* correction, double* c)
{
  for(std::size_t j = 0; j < n; ++j) correction[j] *= scale[j];
  factored_solve(R, Rt, inverse_pivot, n, S, correction);
  double largest_x = 0., largest_dx = 0.;
  for(std::size_t j = 0; j < n; ++j)
  {
    const double dx = correction[j] * scale[j];
    c[j] += dx;
    largest_x = (std::max)(largest_x, std::abs(c[j]));
    largest_dx = (std::max)(largest_dx, std::abs(dx));
  }
  return largest_dx <= semi_normal_correction_guard * largest_x && std::isfinite(largest_x);
}

/// Corrected semi-normal equations (doc/Wavejets/Mathematics.txt section 2, step 3; Bjorck): the Cholesky
/// factor of the column-scaled Gram matrix D M^T M D (D = diag(1 / |column of M|), factored as
/// U^T E U without square roots by semi_normal_factor_and_solve()), x from it and
/// M^T b, then one step of iterative refinement with M itself (r = b - M x, solve for dx with the
/// same factor, x += dx). Faster than the Householder QR for the larger Wavejet systems (1.3x at
/// 97 x 28, see semi_normal_minimum_columns): the Gram matrix is independent dot products, where
/// the QR is a chain of column steps.
/// The body of semi_normal_kernel() (`wavejet_order` 0: the Gram matrix dot by dot) and of
/// wavejet_semi_normal_kernel() (`wavejet_order` K > 0: from the polar moments of the order-K basis).
/// Guarded: returns false, leaving A unchanged, when a scaled pivot is below
/// semi_normal_pivot_guard or the correction exceeds semi_normal_correction_guard times the
/// solution (then the caller solves with the QR). On success, c[0..cols-1] holds the solution and,
/// if `with_R`, the upper triangle of A's first `cols` columns R (of M, unscaled; the QR's up to
/// the signs of its rows), as the QR; without it A is left unchanged (building R costs n(n+1)/2
/// divisions, 9% of a 97 x 28 solve, and only the condition number reads it).
CGAL_WAVEJETS_KERNEL_INLINE bool semi_normal_solve(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                  double* c, std::size_t wavejet_order, bool with_R)
{
  if(rows < cols || cols == 0)
    return false;
  const std::size_t P = padded_rows(rows), n = cols, S = semi_normal_row_stride(n);
  double* residual = scratch;      // P
  double* R = residual + P;        // n x n, row-major, row stride S
  double* Rt = R + n * S;          // its transpose, likewise
  double* scale = Rt + n * S;      // D, S doubles (zero padding)
  double* inverse_pivot = scale + S;
  double* rhs = inverse_pivot + n; // n + 1: the scaled M^T b (one spare slot)
  double* correction = rhs + n + 1;
  // Gram matrix, upper triangle, and M^T b (row i of R: column i's dots with columns i..n-1, then b).
  if(wavejet_order > 0)
    polar_moment_gram_upper(A, P, wavejet_order, scratch + polar_moment_scratch_offset(rows, n), R);
  else
    gram_upper(A, P, n, R, S);
  if(!semi_normal_factor_and_solve(R, Rt, scale, inverse_pivot, rhs, n, S, c))
    return false;
  // Refinement: r = b - M x, D M^T r, solve, x += D dx.
  residual_of(A, P, n, c, residual);
  column_dots(residual, A, P, 0, n, correction);
  if(!semi_normal_refine(R, Rt, scale, inverse_pivot, n, S, correction, c))
    return false;
  if(!with_R)
    return true;
  // R of M: the Cholesky factor of D M^T M D is E^(1/2) U (E on U's diagonal in R), its columns
  // scaled by D^-1. The square roots are off the factorization's chain.
  for(std::size_t i = 0; i < n; ++i) rhs[i] = std::sqrt(R[i * S + i]);
  for(std::size_t j = 0; j < n; ++j)
  {
    for(std::size_t i = 0; i < j; ++i) A[j * P + i] = R[i * S + j] * rhs[i] / scale[j];
    A[j * P + j] = rhs[j] / scale[j];
  }
  return true;
}

/// Corrected semi-normal equations, the Gram matrix M^T M dot by dot (gram_upper()): see
/// semi_normal_solve() above. `scratch`: semi_normal_scratch_size().
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool semi_normal_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                   double* c)
{
  return semi_normal_solve(A, rows, cols, scratch, c, 0, with_R);
}

/// Order K of a Wavejet system of `cols` = (K+1)(K+2)/2 unknowns whose Gram matrix
/// polar_moment_gram_upper() builds, else 0.
inline std::size_t polar_moment_order(std::size_t cols)
{
  for(std::size_t K = 1; K <= polar_moment_maximum_order; ++K)
    if(number_of_coefficients(K) == cols)
      return K;
  return 0;
}

/// The same for a Wavejet system: A's columns are the basis of evaluate_basis_columns() at the order
/// K of `cols` = (K+1)(K+2)/2 unknowns (polar_moment_order(cols) > 0), and the Gram matrix is built
/// from their polar moments (polar_moment_gram_upper()). The same guards, refusals and results up to
/// the rounding of the Gram matrix. `scratch`: wavejet_semi_normal_scratch_size().
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool wavejet_semi_normal_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                           double* c)
{
  return semi_normal_solve(A, rows, cols, scratch, c, polar_moment_order(cols), with_R);
}

/// Unknowns of an order-2 Wavejet: 1, x, y, x^2 + y^2, x^2 - y^2, 2 x y (basis.h's columns).
constexpr std::size_t order2_columns = 6;

/// The corrected semi-normal solve of a system of N unknowns given by its Gram matrix G, at sizes
/// known at compile time (the order-2 fit: N = 6), in scalar code the compiler unrolls (the
/// factor stays in registers; the generic kernels' vectorized row updates store and reload single
/// entries, which costs more than the arithmetic at this size). The factorization is G = U^T E U,
/// as in semi_normal_factor_and_solve() but without the column scaling D = diag(1 / sqrt(G(i, i))):
/// the same guards (a pivot E(i) of D G D below semi_normal_pivot_guard^2 refuses the system, i.e.
/// E(i) of G below that times G(i, i)) and the refinement of semi_normal_refine().
template <std::size_t N>
struct Small_semi_normal
{
  double U[N][N]; // row i: U(i, i+1..N-1)
  double inverse_pivot[N]; // 1 / E(i)

  /// Factors G (upper triangle of `gram`) and solves G c = `rhs` into `c`; false if a diagonal
  /// entry is not positive and finite or a scaled pivot is below semi_normal_pivot_guard^2.
  CGAL_WAVEJETS_KERNEL_INLINE bool factor_and_solve(const double (&gram)[N][N], const double* rhs, double* c)
  {
    double A[N][N];
    CGAL_WAVEJETS_UNROLL
    for(std::size_t i = 0; i < N; ++i)
    {
      if(!(gram[i][i] > 0.) || !std::isfinite(gram[i][i]))
        return false;
      CGAL_WAVEJETS_UNROLL
      for(std::size_t j = i; j < N; ++j) A[i][j] = gram[i][j];
    }
    CGAL_WAVEJETS_UNROLL
    for(std::size_t i = 0; i < N; ++i)
    {
      if(!(A[i][i] > (semi_normal_pivot_guard * semi_normal_pivot_guard) * gram[i][i]))
        return false;
      inverse_pivot[i] = 1. / A[i][i];
      CGAL_WAVEJETS_UNROLL
      for(std::size_t j = i + 1; j < N; ++j) U[i][j] = A[i][j] * inverse_pivot[i];
      CGAL_WAVEJETS_UNROLL
      for(std::size_t j = i + 1; j < N; ++j)
        CGAL_WAVEJETS_UNROLL
        for(std::size_t k = j; k < N; ++k) A[j][k] -= U[i][j] * A[i][k];
    }
    CGAL_WAVEJETS_UNROLL
    for(std::size_t i = 0; i < N; ++i) c[i] = rhs[i];
    solve(c);
    return true;
  }

  /// The refinement: `correction` holds M^T r (r = b - M c); adds the solution dx to `c`. False if
  /// dx exceeds semi_normal_correction_guard times c.
  CGAL_WAVEJETS_KERNEL_INLINE bool refine(const double* correction, double* c) const
  {
    double dx[N];
    CGAL_WAVEJETS_UNROLL
    for(std::size_t i = 0; i < N; ++i) dx[i] = correction[i];
    solve(dx);
    double largest_x = 0., largest_dx = 0.;
    CGAL_WAVEJETS_UNROLL
    for(std::size_t j = 0; j < N; ++j)
    {
      c[j] += dx[j];
      largest_x = (std::max)(largest_x, std::abs(c[j]));
      largest_dx = (std::max)(largest_dx, std::abs(dx[j]));
    }
    return largest_dx <= semi_normal_correction_guard * largest_x && std::isfinite(largest_x);
  }

private:
  /// x = (U^T E U)^-1 x.
  CGAL_WAVEJETS_KERNEL_INLINE void solve(double* x) const
  {
    CGAL_WAVEJETS_UNROLL
    for(std::size_t i = 0; i < N; ++i) // U^T z = x
      CGAL_WAVEJETS_UNROLL
      for(std::size_t j = i + 1; j < N; ++j) x[j] -= U[i][j] * x[i];
    CGAL_WAVEJETS_UNROLL
    for(std::size_t i = 0; i < N; ++i) x[i] *= inverse_pivot[i];
    CGAL_WAVEJETS_UNROLL
    for(std::size_t k = 0; k < N; ++k) // U x = E^-1 z
    {
      const std::size_t i = N - 1 - k;
      CGAL_WAVEJETS_UNROLL
      for(std::size_t j = 0; j < i; ++j) x[j] -= U[j][i] * x[i];
    }
  }
};

/// Sums over points of v, x v, y v, x^2 v, x y v and y^2 v, one vector of `Lanes` (Double4 or
/// Double8) each (named members: the compiler keeps them in registers): M^T v for the order-2 Wavejet
/// basis, from the monomials of degree at most 2 (basis_products()). Gathers M^T h, and M^T r in
/// the refinement.
template <class Lanes>
struct Quadratic_moments
{
  Lanes one, x, y, xx, xy, yy;

  CGAL_WAVEJETS_KERNEL_INLINE void add(const Lanes& xv, const Lanes& yv, const Lanes& xxv, const Lanes& xyv,
                                       const Lanes& yyv, const Lanes& v)
  {
    one += v;
    x += xv * v;
    y += yv * v;
    xx += xxv * v;
    xy += xyv * v;
    yy += yyv * v;
  }

  /// M^T v in the order of the basis (1, x, y, x^2 + y^2, x^2 - y^2, 2xy).
  CGAL_WAVEJETS_KERNEL_INLINE void basis_products(double* out) const
  {
    const double sxx = reduce_lanes(xx), syy = reduce_lanes(yy);
    out[0] = reduce_lanes(one);
    out[1] = reduce_lanes(x);
    out[2] = reduce_lanes(y);
    out[3] = sxx + syy;
    out[4] = sxx - syy;
    out[5] = 2. * reduce_lanes(xy);
  }
};

/// The order-2 Wavejet least squares min || M c - h || (M's rows: the basis above at (x_l, y_l),
/// l < L), by the corrected semi-normal equations (Small_semi_normal) without building M:
/// M^T M and M^T h are sums of the moments sum x^p y^q (p + q <= 4) and sum x^p y^q h (p + q <= 2),
/// gathered in two passes over the points; the refinement's residuals re-evaluate the rows in a
/// third pass. `X` holds three columns x, y, h of stride padded_rows(L), zero on the padding
/// rows. The same guards as semi_normal_kernel(): false (c undefined) sends the system to the
/// general solver. Measured in results.md's least-squares table (101 points: the moments against
/// the QR of the built system). `Lanes`: the rows per step, Double4, or Double8 in the AVX-512
/// variant (the partial sums then fall into eight residues of the row mod 8, not four: the same
/// moments up to rounding).
template <class Lanes = Double4>
CGAL_WAVEJETS_KERNEL_INLINE bool order2_moments_kernel(const double* X, std::size_t L, double* c)
{
  constexpr std::size_t W = lane_count<Lanes>();
  static_assert(householder_block % W == 0, "whole vectors per padded column");
  constexpr std::size_t n = order2_columns;
  if(L < n)
    return false;
  const std::size_t P = padded_rows(L);
  const double* x = X;
  const double* y = X + P;
  const double* h = X + 2 * P;
  const Lanes zero = Lanes{};
  // Moments, one named accumulator each (two passes, so that each pass's accumulators stay in
  // registers): sum x^p y^q for p + q <= 4 and sum x^p y^q h for p + q <= 2.
  Lanes sx = zero, sy = zero, sxx = zero, sxy = zero, syy = zero, sxxx = zero, sxxy = zero, sxyy = zero,
        syyy = zero;
  for(std::size_t l = 0; l < P; l += W)
  {
    Lanes xv, yv;
    load_lanes(xv, x + l);
    load_lanes(yv, y + l);
    const Lanes xxv = xv * xv, xyv = xv * yv, yyv = yv * yv;
    sx += xv;
    sy += yv;
    sxx += xxv;
    sxy += xyv;
    syy += yyv;
    sxxx += xxv * xv;
    sxxy += xxv * yv;
    sxyy += yyv * xv;
    syyy += yyv * yv;
  }
  Lanes sxxxx = zero, sxxxy = zero, sxxyy = zero, sxyyy = zero, syyyy = zero;
  Quadratic_moments<Lanes> heights = {zero, zero, zero, zero, zero, zero};
  for(std::size_t l = 0; l < P; l += W)
  {
    Lanes xv, yv, hv;
    load_lanes(xv, x + l);
    load_lanes(yv, y + l);
    load_lanes(hv, h + l);
    const Lanes xxv = xv * xv, xyv = xv * yv, yyv = yv * yv;
    sxxxx += xxv * xxv;
    sxxxy += xxv * xyv;
    sxxyy += xxv * yyv;
    sxyyy += yyv * xyv;
    syyyy += yyv * yyv;
    heights.add(xv, yv, xxv, xyv, yyv, hv);
  }
  const double x1 = reduce_lanes(sx), y1 = reduce_lanes(sy), x2 = reduce_lanes(sxx), xy = reduce_lanes(sxy),
               y2 = reduce_lanes(syy), x3 = reduce_lanes(sxxx), x2y = reduce_lanes(sxxy), xy2 = reduce_lanes(sxyy),
               y3 = reduce_lanes(syyy), x4 = reduce_lanes(sxxxx), x3y = reduce_lanes(sxxxy), x2y2 = reduce_lanes(sxxyy),
               xy3 = reduce_lanes(sxyyy), y4 = reduce_lanes(syyyy);
  // Gram matrix of the columns (1, x, y, x^2 + y^2, x^2 - y^2, 2xy), upper triangle, and M^T h.
  const double gram[n][n] = {{double(L), x1, y1, x2 + y2, x2 - y2, 2. * xy},
                             {0., x2, xy, x3 + xy2, x3 - xy2, 2. * x2y},
                             {0., 0., y2, x2y + y3, x2y - y3, 2. * xy2},
                             {0., 0., 0., x4 + 2. * x2y2 + y4, x4 - y4, 2. * (x3y + xy3)},
                             {0., 0., 0., 0., x4 - 2. * x2y2 + y4, 2. * (x3y - xy3)},
                             {0., 0., 0., 0., 0., 4. * x2y2}};
  double rhs[n];
  heights.basis_products(rhs);
  Small_semi_normal<n> solver;
  if(!solver.factor_and_solve(gram, rhs, c))
    return false;
  // Refinement: r = h - M c in a third pass, M^T r, solve, c += dc.
  const Lanes c0 = zero + c[0], c1 = zero + c[1], c2 = zero + c[2], cxx = zero + (c[3] + c[4]),
              cyy = zero + (c[3] - c[4]), cxy = zero + 2. * c[5];
  Quadratic_moments<Lanes> residuals = {zero, zero, zero, zero, zero, zero};
  const std::size_t whole = L / W * W; // rows where the constant column is 1 in every lane
  for(std::size_t l = 0; l < P; l += W)
  {
    Lanes xv, yv, r;
    load_lanes(xv, x + l);
    load_lanes(yv, y + l);
    load_lanes(r, h + l);
    const Lanes xxv = xv * xv, xyv = xv * yv, yyv = yv * yv;
    r -= c1 * xv;
    r -= c2 * yv;
    r -= cxx * xxv;
    r -= cyy * yyv;
    r -= cxy * xyv;
    if(l < whole)
      r -= c0;
    else // the constant column is 1 on the rows l < L only
    {
      double lanes[W];
      for(std::size_t k = 0; k < W; ++k) lanes[k] = l + k < L ? c[0] : 0.;
      Lanes ones;
      load_lanes(ones, lanes);
      r -= ones;
    }
    residuals.add(xv, yv, xxv, xyv, yyv, r);
  }
  double correction[n];
  residuals.basis_products(correction);
  return solver.refine(correction, c);
}

/// Fewest unknowns for which least_squares_kernel() tries the semi-normal equations: 21 (order 5).
/// Measured on one core (AVX2 + FMA, one Wavejet system in cache, copy included): 97 x 28 (order 6)
/// 5.2 us against 6.8 us for the QR; 33 x 15 (order 4) 1.39 against 1.26 us; 101 x 6 (order 2) 0.62
/// against 0.62 us. Below, the QR's column chain is short and the Gram matrix's reductions cost as
/// much; the QR solves those systems (their results are those of the QR alone, bit for bit).
constexpr std::size_t semi_normal_minimum_columns = 21;

/// The solver used for every Wavejet system: from semi_normal_minimum_columns unknowns the guarded
/// semi-normal equations, and the Householder QR for smaller systems and for those the semi-normal
/// equations refuse (ill conditioned, see semi_normal_kernel()). `scratch`: least_squares_scratch_size().
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool least_squares_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                     double* c)
{
  return (cols >= semi_normal_minimum_columns && semi_normal_kernel<with_R>(A, rows, cols, scratch, c)) ||
         householder_kernel(A, rows, cols, scratch, c);
}


/// Fewest rows per unknown for which wavejet_least_squares_kernel() builds the Gram matrix from polar
/// moments: their cost is mostly per unknown (the 3K power columns, the B(B+1)/2 entries), the dot
/// products' per row. Measured on one core (AVX2 + FMA, synthetic neighborhoods, the semi-normal solve
/// with the moments against dot by dot): 97 x 28 3.37-3.49 against 4.14-4.31 us, 80 x 36 4.65 against
/// 6.10, 70 x 21 2.41 against 2.71, 60 x 28 3.15 against 3.53; below: 45 x 28 3.17 against 3.09-3.15,
/// 40 x 21 2.25-2.27 against 2.03-2.12.
constexpr std::size_t polar_moment_minimum_rows_per_column = 2;

/// True if wavejet_least_squares_kernel() solves a Wavejet system of `rows` x `cols` by the
/// semi-normal equations with the Gram matrix from polar moments (before its guards decide).
inline bool uses_polar_moments(std::size_t rows, std::size_t cols)
{
  return cols >= semi_normal_minimum_columns && rows >= polar_moment_minimum_rows_per_column * cols &&
         polar_moment_order(cols) > 0;
}

/// least_squares_kernel() for the Wavejet systems of evaluate_basis_columns() (cols = (K+1)(K+2)/2
/// unknowns): the semi-normal equations' Gram matrix from polar moments where uses_polar_moments(),
/// dot by dot otherwise. `scratch`: wavejet_least_squares_scratch_size().
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool wavejet_least_squares_kernel(double* A, std::size_t rows, std::size_t cols,
                                                             double* scratch, double* c)
{
  if(!uses_polar_moments(rows, cols))
    return least_squares_kernel<with_R>(A, rows, cols, scratch, c);
  return wavejet_semi_normal_kernel<with_R>(A, rows, cols, scratch, c) || householder_kernel(A, rows, cols, scratch, c);
}

/// The solvers the dispatch below serves.
enum class Solver
{
  HOUSEHOLDER_QR,         ///< householder_kernel() only
  SEMI_NORMAL_ELSE_QR,    ///< least_squares_kernel(): the guarded semi-normal equations, else the QR
  WAVEJET_SEMI_NORMAL_ELSE_QR, ///< wavejet_least_squares_kernel(): the same, the Gram matrix from polar moments
  ORDER2_MOMENTS          ///< order2_moments_kernel(): A holds the columns x, y, h; cols and scratch unused
};

/// Solver S on A; `with_R` false: R need not be returned (the semi-normal solvers then skip it).
/// `Lanes`: the vector type of the order-2 kernel (the other solvers use Double4).
template <Solver S, bool with_R = true, class Lanes = Double4>
CGAL_WAVEJETS_KERNEL_INLINE bool solver_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch, double* c)
{
  switch(S)
  {
  case Solver::HOUSEHOLDER_QR: return householder_kernel(A, rows, cols, scratch, c);
  case Solver::SEMI_NORMAL_ELSE_QR: return least_squares_kernel<with_R>(A, rows, cols, scratch, c);
  case Solver::WAVEJET_SEMI_NORMAL_ELSE_QR: return wavejet_least_squares_kernel<with_R>(A, rows, cols, scratch, c);
  case Solver::ORDER2_MOMENTS: return order2_moments_kernel<Lanes>(A, rows, c);
  }
  return false;
}

/// The kernel compiled for AVX2 + FMA (run it only where the processor has both).
template <Solver S, bool with_R = true>
CGAL_WAVEJETS_TARGET("avx2,fma") inline bool solver_fma(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_kernel<S, with_R>(A, rows, cols, v, c);
}
/// The kernel compiled for AVX (run it only where the processor has it).
template <Solver S, bool with_R = true>
CGAL_WAVEJETS_TARGET("avx") inline bool solver_avx(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_kernel<S, with_R>(A, rows, cols, v, c);
}

/// True if the solver is also compiled for AVX-512 (with AVX2 + FMA) and picked at run time where
/// the processor has it.
#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
constexpr bool avx512_dispatch = true;
#else
constexpr bool avx512_dispatch = false;
#endif

/// True if the dispatch may run solver_fma(): the processor has AVX2 and FMA, and the variant is
/// compiled in (not CGAL_WAVEJETS_NO_FMA_DISPATCH). The same answer for the whole run.
inline bool processor_runs_fma()
{
#if defined(CGAL_WAVEJETS_AVX_DISPATCH) && !defined(CGAL_WAVEJETS_NO_FMA_DISPATCH)
  static const bool fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return fma;
#else
  return false;
#endif
}

/// True if the dispatch runs solver_avx512(): the processor has AVX-512 F, VL and DQ besides AVX2
/// and FMA, and the variant is compiled in. The same answer for the whole run.
inline bool processor_runs_avx512()
{
#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
  static const bool avx512 = processor_runs_fma() && __builtin_cpu_supports("avx512f") &&
                             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
  return avx512;
#else
  return false;
#endif
}

#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
/// The kernel compiled for AVX-512 (run it only where processor_runs_avx512()). The order-2 kernel
/// takes eight rows per step (Double8): its moments' partial sums differ, hence its solutions up to
/// rounding; the other solvers keep their four-lane code, which the compiler gives twice as many
/// registers (the same operations: bitwise the AVX2 + FMA variant's results, checked by
/// test_simd_kernels; fewer spills, most in the QR of orders 3 and 4).
template <Solver S, bool with_R = true>
CGAL_WAVEJETS_TARGET("avx512f,avx512vl,avx512dq,avx2,fma")
inline bool solver_avx512(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_kernel<S, with_R, Double8>(A, rows, cols, v, c);
}
#else
/// Not compiled in: the AVX2 + FMA variant (processor_runs_avx512() is false; never dispatched).
template <Solver S, bool with_R = true>
inline bool solver_avx512(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_fma<S, with_R>(A, rows, cols, v, c);
}
#endif

/// Runs solver S compiled for the best instruction set the processor has (the same for every call).
template <Solver S, bool with_R = true>
inline bool dispatch_solver(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
#ifdef CGAL_WAVEJETS_AVX_DISPATCH
  if(processor_runs_avx512())
    return solver_avx512<S, with_R>(A, rows, cols, v, c);
  if(processor_runs_fma())
    return solver_fma<S, with_R>(A, rows, cols, v, c);
  if(processor_runs_avx())
    return solver_avx<S, with_R>(A, rows, cols, v, c);
#endif
  return solver_kernel<S, with_R>(A, rows, cols, v, c);
}

/// Solves min ||A c - b|| for a rows x cols matrix `A` by Householder QR. `A` is column-major with
/// column stride padded_rows(rows), followed by `b` as column `cols`; rows `rows`..padded_rows(rows)-1
/// of every column must be zero. `v` is scratch of 2 padded_rows(rows) doubles. On return the upper
/// triangle of the first `cols` columns holds R (R(i, j) = A[j * padded_rows(rows) + i], i <= j) and
/// `c[0..cols-1]` the solution. Returns false if the system has fewer rows than columns or is
/// numerically rank-deficient.
inline bool householder_least_squares(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return dispatch_solver<Solver::HOUSEHOLDER_QR>(A, rows, cols, v, c);
}

/// The solver `s`, or the QR alone where CGAL_WAVEJETS_NO_SEMI_NORMAL is defined.
constexpr Solver semi_normal_unless_disabled(Solver s)
{
#ifdef CGAL_WAVEJETS_NO_SEMI_NORMAL
  (void)s;
  return Solver::HOUSEHOLDER_QR;
#else
  return s;
#endif
}

/// Scratch doubles needed by least_squares().
inline std::size_t least_squares_scratch_size(std::size_t rows, std::size_t cols)
{
  return (std::max)(2 * padded_rows(rows), semi_normal_scratch_size(rows, cols));
}

/// The same problem and layout as householder_least_squares(), solved by the guarded semi-normal
/// equations, or by the QR when they are not accurate enough (semi_normal_kernel()): the solver
/// of every Wavejet fit. `scratch`: least_squares_scratch_size(rows, cols) doubles.
inline bool least_squares(double* A, std::size_t rows, std::size_t cols, double* scratch, double* c)
{
  return dispatch_solver<semi_normal_unless_disabled(Solver::SEMI_NORMAL_ELSE_QR)>(A, rows, cols, scratch, c);
}

/// Scratch doubles needed by wavejet_least_squares().
inline std::size_t wavejet_least_squares_scratch_size(std::size_t rows, std::size_t cols)
{
  const std::size_t K = polar_moment_order(cols);
  return K > 0 ? (std::max)(2 * padded_rows(rows), wavejet_semi_normal_scratch_size(rows, cols, K))
               : least_squares_scratch_size(rows, cols);
}

/// least_squares() for a system whose columns are the Wavejet basis of evaluate_basis_columns() at
/// order K (cols = (K+1)(K+2)/2), in the same layout: the Gram matrix of the semi-normal equations
/// is built from polar moments (polar_moment_gram_upper()), the rest, the guards and the fallback
/// to the QR are least_squares()'s. `scratch`: wavejet_least_squares_scratch_size(rows, cols).
inline bool wavejet_least_squares(double* A, std::size_t rows, std::size_t cols, double* scratch, double* c)
{
  return dispatch_solver<semi_normal_unless_disabled(Solver::WAVEJET_SEMI_NORMAL_ELSE_QR)>(A, rows, cols, scratch, c);
}

/// The same solution c as least_squares() (`wavejet_basis` false) or wavejet_least_squares()
/// (true), bit for bit, without R: A is left unchanged or destroyed (the QR's work).
inline bool least_squares_solution(double* A, std::size_t rows, std::size_t cols, double* scratch, double* c,
                                   bool wavejet_basis)
{
  return wavejet_basis
           ? dispatch_solver<semi_normal_unless_disabled(Solver::WAVEJET_SEMI_NORMAL_ELSE_QR), false>(A, rows, cols, scratch, c)
           : dispatch_solver<semi_normal_unless_disabled(Solver::SEMI_NORMAL_ELSE_QR), false>(A, rows, cols, scratch, c);
}

/// The order-2 Wavejet fit of the points (x_l, y_l, h_l), l < L, by order2_moments_kernel():
/// `X` holds the columns x, y, h (stride padded_rows(L), zero padding rows). Returns false when
/// its guards refuse the system: then build M and call least_squares().
inline bool order2_least_squares(double* X, std::size_t L, double* c)
{
  return dispatch_solver<Solver::ORDER2_MOMENTS>(X, L, order2_columns, nullptr, c);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H
