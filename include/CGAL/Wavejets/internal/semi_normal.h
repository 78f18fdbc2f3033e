// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_SEMI_NORMAL_H
#define CGAL_WAVEJETS_INTERNAL_SEMI_NORMAL_H

// The corrected semi-normal equations (doc/Wavejets/Mathematics.txt section 2, step 3), guarded:
// semi_normal_kernel() (the Gram matrix dot by dot, gram_matrix.h) and wavejet_semi_normal_kernel()
// (the Gram matrix of the Wavejet basis from polar moments, polar_moment_gram.h). Plain normal
// equations are not used: the Wavejet systems are too ill-conditioned for them. A system the guards
// refuse goes to the Householder QR (solver_choice.h says which solver runs when).

#include <CGAL/Wavejets/internal/gram_matrix.h>
#include <CGAL/Wavejets/internal/householder_qr.h>
#include <CGAL/Wavejets/internal/least_squares_lanes.h>
#include <CGAL/Wavejets/internal/polar_moment_gram.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// y[l] -= a[t] x[t * stride + l] for t = 0, 1, 2, 3 in that order (four multiply-adds per load and
/// store of y), l = begin, begin + 4, ... < end (whole blocks of four).
CGAL_WAVEJETS_KERNEL_INLINE void subtract_four_multiples(double* y, const double* x, std::size_t stride,
                                                        const double* a, std::size_t begin, std::size_t end)
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

/// y[l] -= a x[l] for l = begin, begin + 1, ... while a whole block of four fits before `end`,
/// four lanes at a time; returns the first l not done (`end` when end - begin is a multiple of four).
CGAL_WAVEJETS_KERNEL_INLINE std::size_t subtract_multiple_blocks(double* y, const double* x, double a,
                                                                std::size_t begin, std::size_t end)
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
CGAL_WAVEJETS_KERNEL_INLINE void subtract_multiple(double* y, const double* x, double a, std::size_t begin,
                                                  std::size_t end)
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
CGAL_WAVEJETS_KERNEL_INLINE bool semi_normal_factor_and_solve(double* R, double* Rt, double* scale,
                                                             double* inverse_pivot, double* rhs, Count n, Stride S,
                                                             double* c)
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

/// The same for a Wavejet system: A's columns are the basis of evaluate_basis_columns() at the order
/// K of `cols` = (K+1)(K+2)/2 unknowns (polar_moment_order(cols) > 0), and the Gram matrix is built
/// from their polar moments (polar_moment_gram_upper()). The same guards, refusals and results up to
/// the rounding of the Gram matrix. `scratch`: wavejet_semi_normal_scratch_size().
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool wavejet_semi_normal_kernel(double* A, std::size_t rows, std::size_t cols,
                                                           double* scratch, double* c)
{
  return semi_normal_solve(A, rows, cols, scratch, c, polar_moment_order(cols), with_R);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_SEMI_NORMAL_H
