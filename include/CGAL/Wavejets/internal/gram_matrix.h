// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_GRAM_MATRIX_H
#define CGAL_WAVEJETS_INTERNAL_GRAM_MATRIX_H

// The Gram matrix M^T M (upper triangle) and M^T b of the semi-normal solvers (semi_normal.h), dot by
// dot, by 2 x 4 tiles of four-lane accumulators: gram_upper(). polar_moment_gram.h builds the same
// matrix for the Wavejet basis from polar moments.

#include <CGAL/Wavejets/internal/householder_qr.h>
#include <CGAL/Wavejets/internal/least_squares_lanes.h>

#include <cstddef>

namespace CGAL {
namespace Wavejets {
namespace internal {

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
CGAL_WAVEJETS_KERNEL_INLINE void gram_upper(const double* X, std::size_t P, std::size_t n, double* G,
                                           std::size_t stride)
{
  std::size_t i = 0;
  for(; i + 1 < n; i += 2)
  {
    std::size_t j = i / 4 * 4;
    for(; j + 4 <= n + 1; j += 4) gram_tile(X, P, i, j, G, stride);
    for(; j <= n; ++j)
      for(std::size_t a = 0; a < 2; ++a)
        householder_dots<1>(X + (i + a) * P, X + j * P, P, 0, P, G + (i + a) * stride + j);
  }
  if(i < n) column_dots(X + i * P, X, P, i, n + 1, G + i * stride);
}

/// Row stride of the semi-normal solvers' n x n triangular factors: at least n + 1 (column n holds
/// M^T b), a whole number of blocks of four.
inline std::size_t semi_normal_row_stride(std::size_t n) { return (n + 4) / 4 * 4; }

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_GRAM_MATRIX_H
