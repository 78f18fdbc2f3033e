// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_HOUSEHOLDER_QR_H
#define CGAL_WAVEJETS_INTERNAL_HOUSEHOLDER_QR_H

// The Householder QR of the least-squares solvers (least_squares.h), in place on caller-owned
// scratch, without heap allocation: householder_kernel(). Each dot product runs over whole blocks
// with `householder_block` independent partial sums (one per row residue), so it is vectorized along
// the rows and not bound by the latency of one long chain of additions; reflections are applied to
// four trailing columns at a time so that the Householder vector is loaded once for four columns. A
// column's dot product (hence the result) does not depend on that grouping, nor on the vector width.

#include <CGAL/Wavejets/internal/least_squares_lanes.h>

#include <cmath>
#include <cstddef>
#include <utility>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// A column is taken as dependent on the previous ones when the part of it orthogonal to them
/// is below this fraction of its norm (numerical rank test of the non-pivoted QR).
constexpr double rank_tolerance = 1e-10;

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

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_HOUSEHOLDER_QR_H
