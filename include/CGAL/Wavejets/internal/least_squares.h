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
// (column-major), without heap allocation. The normal equations are not used: the Wavejet
// systems are too ill-conditioned for them.

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// A column is taken as dependent on the previous ones when the part of it orthogonal to them
/// is below this fraction of its norm (numerical rank test of the non-pivoted QR).
constexpr double rank_tolerance = 1e-10;

/// Solves min ||A c - b|| for the rows x cols column-major matrix `A` (leading dimension `rows`).
/// On return `A` holds R in its upper triangle (and Householder vectors below), `b` holds Q^T b and
/// `c[0..cols-1]` the solution. Returns false (and leaves `c` unspecified) if a column is
/// numerically dependent on the previous ones or the system has fewer rows than columns.
inline bool householder_least_squares(double* A, std::size_t rows, std::size_t cols, double* b, double* c)
{
  if(rows < cols)
    return false;
  for(std::size_t j = 0; j < cols; ++j)
  {
    double* aj = A + j * rows;
    double full2 = 0., tail2 = 0.;
    for(std::size_t i = 0; i < j; ++i) full2 += aj[i] * aj[i];
    for(std::size_t i = j; i < rows; ++i) tail2 += aj[i] * aj[i];
    full2 += tail2;
    const double tail = std::sqrt(tail2);
    if(!(tail > rank_tolerance * std::sqrt(full2)))
      return false; // also catches a zero column and NaN
    // Householder vector v = x + sign(x0)|x| e0 stored in aj[j..]; beta = 2 / v.v
    const double alpha = aj[j] >= 0 ? -tail : tail;
    const double v0 = aj[j] - alpha;
    const double vtv = tail2 - aj[j] * aj[j] + v0 * v0;
    aj[j] = v0;
    const double beta = 2. / vtv;
    for(std::size_t l = j + 1; l < cols; ++l)
    {
      double* al = A + l * rows;
      double dot = 0.;
      for(std::size_t i = j; i < rows; ++i) dot += aj[i] * al[i];
      dot *= beta;
      for(std::size_t i = j; i < rows; ++i) al[i] -= dot * aj[i];
    }
    double dot = 0.;
    for(std::size_t i = j; i < rows; ++i) dot += aj[i] * b[i];
    dot *= beta;
    for(std::size_t i = j; i < rows; ++i) b[i] -= dot * aj[i];
    aj[j] = alpha; // diagonal of R (the Householder vector's head is no longer needed)
  }
  for(std::size_t jj = cols; jj-- > 0;)
  {
    double s = b[jj];
    for(std::size_t l = jj + 1; l < cols; ++l) s -= A[l * rows + jj] * c[l];
    c[jj] = s / A[jj * rows + jj];
  }
  return true;
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_H
