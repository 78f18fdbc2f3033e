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

// Dense least squares min ||A c - b|| by Householder QR, in place on caller-owned scratch
// (row-major, right-hand side as an extra column), without heap allocation. The normal
// equations are not used: the Wavejet systems are too ill-conditioned for them.
// The reflections are applied row by row so that the dot products of one reflection with all the
// trailing columns run side by side (vectorizable), each still summed in increasing row order.

#include <algorithm>
#include <cmath>
#include <cstddef>

#if defined(__GNUC__) || defined(__clang__) || defined(_MSC_VER)
#define CGAL_WAVEJETS_RESTRICT __restrict
#else
#define CGAL_WAVEJETS_RESTRICT
#endif

// x86 with GCC or Clang: the row-major solver is also compiled for AVX (without FMA, so the
// arithmetic, hence the result, is bitwise the same as the SSE2 code) and picked at run time.
// Define CGAL_WAVEJETS_NO_AVX_DISPATCH to switch this off.
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

/// Extra doubles after the matrix and the scratch of householder_least_squares_rows().
constexpr std::size_t householder_padding = 16;

/// w[t] = sum_{i = j}^{rows-1} M(i, j) M(i, l + t), t < W, summed in increasing i (each in its own
/// register: no latency-bound chain through memory). Row-major M with row stride S.
template <int W>
CGAL_WAVEJETS_KERNEL_INLINE void householder_dots(const double* M, std::size_t S, std::size_t j, std::size_t rows, std::size_t l,
                             double* w)
{
  double acc[W];
  for(int t = 0; t < W; ++t) acc[t] = 0.;
  for(std::size_t i = j; i < rows; ++i)
  {
    const double vi = M[i * S + j];
    const double* row = M + i * S + l;
    for(int t = 0; t < W; ++t) acc[t] += vi * row[t];
  }
  for(int t = 0; t < W; ++t) w[t] = acc[t];
}

/// Kernel of householder_least_squares_rows(). Column j's reflection v = x - alpha e_j
/// (alpha = -sign(x_j)|x|) is applied to the trailing columns; a column whose part orthogonal to
/// the previous ones is below rank_tolerance of its norm makes the solve fail. The dot products
/// of a reflection with all trailing columns are accumulated together (vectorizable across
/// columns) instead of one latency-bound reduction per column. On return M holds R in its upper
/// triangle and c the solution (back substitution).
CGAL_WAVEJETS_KERNEL_INLINE bool householder_rows_kernel(double* M, std::size_t rows, std::size_t cols, double* w,
                                                     double* c)
{
  if(rows < cols)
    return false;
  const std::size_t S = cols + 1;
  double tail2 = 0.; // of column 0, then of the next column (accumulated during each update)
  for(std::size_t i = 0; i < rows; ++i) tail2 += M[i * S] * M[i * S];
  for(std::size_t j = 0; j < cols; ++j)
  {
    double full2 = 0.;
    for(std::size_t i = 0; i < j; ++i) full2 += M[i * S + j] * M[i * S + j];
    full2 += tail2;
    const double tail = std::sqrt(tail2);
    if(!(tail > rank_tolerance * std::sqrt(full2)))
      return false; // also catches a zero column and NaN
    const double ajj = M[j * S + j];
    const double alpha = ajj >= 0 ? -tail : tail;
    const double v0 = ajj - alpha;
    const double vtv = tail2 - ajj * ajj + v0 * v0;
    M[j * S + j] = v0;
    const double beta = 2. / vtv;
    const std::size_t l0 = j + 1, n = S - l0; // trailing columns, right-hand side included
    double* CGAL_WAVEJETS_RESTRICT wl = w + l0;
    // All the column sums of a block run side by side (independent chains); the last block is
    // rounded up to a power of two, its extra sums (read from the padding) are ignored.
    std::size_t l = 0;
    for(; l + 16 <= n; l += 16) householder_dots<16>(M, S, j, rows, l0 + l, wl + l);
    const std::size_t r = n - l;
    if(r > 8) householder_dots<16>(M, S, j, rows, l0 + l, wl + l);
    else if(r > 4) householder_dots<8>(M, S, j, rows, l0 + l, wl + l);
    else if(r > 2) householder_dots<4>(M, S, j, rows, l0 + l, wl + l);
    else if(r == 2) householder_dots<2>(M, S, j, rows, l0 + l, wl + l);
    else if(r == 1) householder_dots<1>(M, S, j, rows, l0 + l, wl + l);
    for(std::size_t l = 0; l < n; ++l) wl[l] *= beta;
    {
      const double vi = M[j * S + j];
      double* CGAL_WAVEJETS_RESTRICT row = M + j * S + l0;
      for(std::size_t l = 0; l < n; ++l) row[l] -= wl[l] * vi;
    }
    tail2 = 0.;
    for(std::size_t i = j + 1; i < rows; ++i)
    {
      const double vi = M[i * S + j];
      double* CGAL_WAVEJETS_RESTRICT row = M + i * S + l0;
      for(std::size_t l = 0; l < n; ++l) row[l] -= wl[l] * vi;
      tail2 += row[0] * row[0]; // column j + 1 (the right-hand side when j + 1 == cols: unused)
    }
    M[j * S + j] = alpha;
  }
  for(std::size_t jj = cols; jj-- > 0;)
  {
    double s = M[jj * S + cols];
    for(std::size_t l = jj + 1; l < cols; ++l) s -= M[jj * S + l] * c[l];
    c[jj] = s / M[jj * S + jj];
  }
  return true;
}

#ifdef CGAL_WAVEJETS_AVX_DISPATCH
__attribute__((target("avx"))) inline bool householder_rows_avx(double* M, std::size_t rows, std::size_t cols,
                                                                double* w, double* c)
{
  return householder_rows_kernel(M, rows, cols, w, c);
}
#endif

/// Same solver on a row-major system: `M` is rows x (cols + 1) with row stride cols + 1, the
/// right-hand side in its last column; `w` is scratch of cols + 1 doubles. Both arrays need
/// `householder_padding` more readable doubles after their end (read and ignored). Returns false
/// if the system has fewer rows than columns or is numerically rank-deficient.
inline bool householder_least_squares_rows(double* M, std::size_t rows, std::size_t cols, double* w, double* c)
{
#ifdef CGAL_WAVEJETS_AVX_DISPATCH
  static const bool avx = __builtin_cpu_supports("avx");
  if(avx)
    return householder_rows_avx(M, rows, cols, w, c);
#endif
  return householder_rows_kernel(M, rows, cols, w, c);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H
