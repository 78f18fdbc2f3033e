// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_ORDER2_MOMENTS_H
#define CGAL_WAVEJETS_INTERNAL_ORDER2_MOMENTS_H

// The order-2 Wavejet fit from the moments of the points, without building the system:
// order2_moments_kernel(), the corrected semi-normal equations at a size known at compile time
// (Small_semi_normal) with the guards of semi_normal.h.

#include <CGAL/Wavejets/internal/instruction_sets.h>
#include <CGAL/Wavejets/internal/least_squares_lanes.h>
#include <CGAL/Wavejets/internal/semi_normal.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Wavejets {
namespace internal {

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

/// The moments of the points of an order-2 fit: sum x^p y^q for 0 < p + q <= 4
/// (order2_point_moments()).
struct Order2_point_moments
{
  double x1, y1, x2, xy, y2, x3, x2y, xy2, y3, x4, x3y, x2y2, xy3, y4;
};

/// The moments of the points (x_l, y_l, h_l) over the P padded rows (zero on the padding rows), one
/// named accumulator each (two passes, so that each pass's accumulators stay in registers): sum
/// x^p y^q for p + q <= 4 into `moments`, and sum x^p y^q h for p + q <= 2 into `heights` (zero on
/// entry).
template <class Lanes>
CGAL_WAVEJETS_KERNEL_INLINE void order2_point_moments(const double* x, const double* y, const double* h, std::size_t P,
                                                     Order2_point_moments& moments, Quadratic_moments<Lanes>& heights)
{
  constexpr std::size_t W = lane_count<Lanes>();
  const Lanes zero = Lanes{};
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
  moments = {reduce_lanes(sx),   reduce_lanes(sy),    reduce_lanes(sxx),   reduce_lanes(sxy),   reduce_lanes(syy),
             reduce_lanes(sxxx), reduce_lanes(sxxy),  reduce_lanes(sxyy),  reduce_lanes(syyy),  reduce_lanes(sxxxx),
             reduce_lanes(sxxxy), reduce_lanes(sxxyy), reduce_lanes(sxyyy), reduce_lanes(syyyy)};
}

/// The Gram matrix of an order-2 fit (order2_gram()).
struct Order2_gram
{
  double entries[order2_columns][order2_columns];
};

/// Gram matrix of the columns (1, x, y, x^2 + y^2, x^2 - y^2, 2xy) of L points, upper triangle, from
/// their moments.
CGAL_WAVEJETS_KERNEL_INLINE Order2_gram order2_gram(const Order2_point_moments& s, std::size_t L)
{
  const double x1 = s.x1, y1 = s.y1, x2 = s.x2, xy = s.xy, y2 = s.y2, x3 = s.x3, x2y = s.x2y, xy2 = s.xy2, y3 = s.y3,
               x4 = s.x4, x3y = s.x3y, x2y2 = s.x2y2, xy3 = s.xy3, y4 = s.y4;
  return Order2_gram{{{double(L), x1, y1, x2 + y2, x2 - y2, 2. * xy},
                      {0., x2, xy, x3 + xy2, x3 - xy2, 2. * x2y},
                      {0., 0., y2, x2y + y3, x2y - y3, 2. * xy2},
                      {0., 0., 0., x4 + 2. * x2y2 + y4, x4 - y4, 2. * (x3y + xy3)},
                      {0., 0., 0., 0., x4 - 2. * x2y2 + y4, 2. * (x3y - xy3)},
                      {0., 0., 0., 0., 0., 4. * x2y2}}};
}

/// The refinement's pass: r = h - M c for the L points (x_l, y_l, h_l) over the P padded rows, and
/// M^T r gathered into `residuals` (zero on entry).
template <class Lanes>
CGAL_WAVEJETS_KERNEL_INLINE void order2_residual_moments(const double* x, const double* y, const double* h,
                                                        std::size_t P, std::size_t L, const double* c,
                                                        Quadratic_moments<Lanes>& residuals)
{
  constexpr std::size_t W = lane_count<Lanes>();
  const Lanes zero = Lanes{};
  const Lanes c0 = zero + c[0], c1 = zero + c[1], c2 = zero + c[2], cxx = zero + (c[3] + c[4]),
              cyy = zero + (c[3] - c[4]), cxy = zero + 2. * c[5];
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
}

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
  static_assert(householder_block % lane_count<Lanes>() == 0, "whole vectors per padded column");
  constexpr std::size_t n = order2_columns;
  if(L < n)
    return false;
  const std::size_t P = padded_rows(L);
  const double* x = X;
  const double* y = X + P;
  const double* h = X + 2 * P;
  const Lanes zero = Lanes{};
  Order2_point_moments moments;
  Quadratic_moments<Lanes> heights = {zero, zero, zero, zero, zero, zero};
  order2_point_moments(x, y, h, P, moments, heights);
  const Order2_gram gram = order2_gram(moments, L);
  double rhs[n];
  heights.basis_products(rhs);
  Small_semi_normal<n> solver;
  if(!solver.factor_and_solve(gram.entries, rhs, c))
    return false;
  // Refinement: r = h - M c in a third pass, M^T r, solve, c += dc.
  Quadratic_moments<Lanes> residuals = {zero, zero, zero, zero, zero, zero};
  order2_residual_moments(x, y, h, P, L, c, residuals);
  double correction[n];
  residuals.basis_products(correction);
  return solver.refine(correction, c);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_ORDER2_MOMENTS_H
