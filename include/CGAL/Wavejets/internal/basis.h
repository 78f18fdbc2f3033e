// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_BASIS_H
#define CGAL_WAVEJETS_INTERNAL_BASIS_H

// The real Wavejet basis r^k cos(n theta), r^k sin(n theta) (n <= k, n = k mod 2), its
// column layout, and the conversions between real unknowns and complex coefficients f_{k,n}.
//
// Column layout (also the documented layout of Wavejet_form::coefficients()): orders k = 0..K
// in turn, order k occupying the k+1 columns starting at k(k+1)/2:
//   k even: f_{k,0}, alpha_{k,2}, beta_{k,2}, ..., alpha_{k,k}, beta_{k,k}
//   k odd :          alpha_{k,1}, beta_{k,1}, ..., alpha_{k,k}, beta_{k,k}
// i.e. alpha_{k,n} at k(k+1)/2 + n - 1 and beta_{k,n} at k(k+1)/2 + n (n > 0), f_{k,0} at k(k+1)/2,
// with f_{k,n} = (alpha - i beta)/2 and f_{k,-n} = (alpha + i beta)/2.

#include <CGAL/Wavejets/internal/instruction_sets.h>

#include <complex>
#include <cstddef>
#include <cstdlib>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// Number of real unknowns of a K-Wavejet: (K+1)(K+2)/2.
inline std::size_t number_of_coefficients(std::size_t order)
{
  return (order + 1) * (order + 2) / 2;
}

/// First column of order k.
inline std::size_t order_offset(std::size_t k) { return k * (k + 1) / 2; }

/// True if (k, n) is a coefficient of a Wavejet (|n| <= k and n = k mod 2).
inline bool is_wavejet_index(int k, int n)
{
  return k >= 0 && std::abs(n) <= k && ((k - n) % 2 == 0);
}

/// Complex coefficient f_{k,n} from the real unknowns `c` (any unit system).
/// Precondition: is_wavejet_index(k, n).
inline std::complex<double> complex_coefficient(const double* c, int k, int n)
{
  const std::size_t o = order_offset(std::size_t(k));
  if(n == 0)
    return std::complex<double>(c[o], 0.);
  const std::size_t m = std::size_t(std::abs(n));
  const double alpha = c[o + m - 1], beta = c[o + m];
  return n > 0 ? std::complex<double>(alpha / 2, -beta / 2) : std::complex<double>(alpha / 2, beta / 2);
}

/// The B = (K+1)(K+2)/2 basis values at L points (x[l], y[l]), in the column layout above, column-major: column b starts at A + b * P (P >= L); rows L..P-1 (padding)
/// are set to zero. By recurrence along whole columns (vectorizable along the points):
/// r^k e^{i n theta} = (x^2 + y^2) r^{k-2} e^{i n theta} for n <= k-2, and (x + i y)^k for n = k.
/// No pow, atan2 or sqrt. (x^2 + y^2 is recomputed per column: measured faster than reading it
/// from a third array.) Compiled for AVX where the processor has it (dispatch_avx(): bitwise the
/// same values).
struct Basis_columns_kernel
{
  static CGAL_WAVEJETS_KERNEL_INLINE void run(const double* x, const double* y, std::size_t L, std::size_t P,
                                              std::size_t order, double* A)
  {
    for(std::size_t l = 0; l < L; ++l) A[l] = 1.;
    for(std::size_t l = L; l < P; ++l) A[l] = 0.;
    for(std::size_t k = 1; k <= order; ++k)
    {
      const std::size_t o = order_offset(k);
      if(k >= 2)
      {
        const std::size_t o2 = order_offset(k - 2);
        for(std::size_t j = 0; j + 1 < k; ++j)
        {
          const double* below = A + (o2 + j) * P;
          double* column = A + (o + j) * P;
          for(std::size_t l = 0; l < L; ++l) column[l] = (x[l] * x[l] + y[l] * y[l]) * below[l];
          for(std::size_t l = L; l < P; ++l) column[l] = 0.;
        }
      }
      // (x + i y)^k = (x + i y)^{k-1} (x + i y): from the last two columns of order k-1 (for k = 1,
      // column 0 and zero). Padding rows stay zero (they are zero in those columns; x and y must be
      // finite there).
      double* re = A + (o + k - 1) * P;
      double* im = A + (o + k) * P;
      if(k == 1)
      {
        for(std::size_t l = 0; l < P; ++l) { re[l] = A[l] * x[l]; im[l] = A[l] * y[l]; }
        continue;
      }
      const double* pre = A + (order_offset(k - 1) + k - 2) * P;
      const double* pim = A + (order_offset(k - 1) + k - 1) * P;
      for(std::size_t l = 0; l < P; ++l)
      {
        re[l] = pre[l] * x[l] - pim[l] * y[l];
        im[l] = pre[l] * y[l] + pim[l] * x[l];
      }
    }
  }
};

inline void evaluate_basis_columns(const double* x, const double* y, std::size_t L, std::size_t P,
                                   std::size_t order, double* A)
{
  dispatch_avx<Basis_columns_kernel>(x, y, L, P, order, A);
}

/// Gradient of the basis at M points: Gx and Gy receive d/dx and d/dy of the B columns of
/// evaluate_basis_columns(), in the same layout (column stride P >= M, padding rows set to zero);
/// V must hold the basis values at the same points (evaluate_basis_columns(x, y, M, P, order, V)).
/// Same recurrences, differentiated: d/dx (x + i y)^k = k (x + i y)^{k-1}, d/dy (x + i y)^k =
/// i k (x + i y)^{k-1}, and d/dx (r^2 g) = 2 x g + r^2 dg/dx (likewise for y).
inline void evaluate_basis_gradient_columns(const double* x, const double* y, std::size_t M, std::size_t P,
                                            std::size_t order, const double* V, double* Gx, double* Gy)
{
  for(std::size_t l = 0; l < P; ++l) Gx[l] = Gy[l] = 0.;
  for(std::size_t k = 1; k <= order; ++k)
  {
    const std::size_t o = order_offset(k);
    if(k >= 2)
    {
      const std::size_t o2 = order_offset(k - 2);
      for(std::size_t j = 0; j + 1 < k; ++j)
      {
        const double* g = V + (o2 + j) * P;
        const double* gx = Gx + (o2 + j) * P;
        const double* gy = Gy + (o2 + j) * P;
        double* cx = Gx + (o + j) * P;
        double* cy = Gy + (o + j) * P;
        for(std::size_t l = 0; l < M; ++l)
        {
          const double r2 = x[l] * x[l] + y[l] * y[l];
          cx[l] = 2. * x[l] * g[l] + r2 * gx[l];
          cy[l] = 2. * y[l] * g[l] + r2 * gy[l];
        }
        for(std::size_t l = M; l < P; ++l) cx[l] = cy[l] = 0.;
      }
    }
    // (x + i y)^{k-1}: the last two columns of order k-1, or 1 + 0 i for k = 1.
    const double* pre = k == 1 ? V : V + (order_offset(k - 1) + k - 2) * P;
    const double* pim = k == 1 ? nullptr : V + (order_offset(k - 1) + k - 1) * P;
    double* rx = Gx + (o + k - 1) * P;
    double* ix = Gx + (o + k) * P;
    double* ry = Gy + (o + k - 1) * P;
    double* iy = Gy + (o + k) * P;
    const double dk = double(k);
    for(std::size_t l = 0; l < M; ++l)
    {
      const double re = pre[l], im = pim ? pim[l] : 0.;
      rx[l] = dk * re;
      ix[l] = dk * im;
      ry[l] = -dk * im;
      iy[l] = dk * re;
    }
    for(std::size_t l = M; l < P; ++l) rx[l] = ix[l] = ry[l] = iy[l] = 0.;
  }
}

/// Enclosed-area coefficient a_n(s) = sum_{k >= max(|n|, k_min), k = n mod 2} f_{k,n} s^{k+2}/(k+2),
/// in the unit system of `c` and `s`. `k_min` lets the filters skip the k = 0 (offset) or k = 1 (tilt) term.
inline std::complex<double> enclosed_area(const double* c, std::size_t order, int n, double s, int k_min = 0)
{
  std::complex<double> a(0., 0.);
  const int K = int(order);
  int k = std::abs(n);
  while(k < k_min) k += 2;
  double sk2 = 1.; // s^{k+2}
  for(int j = 0; j < k + 2; ++j) sk2 *= s;
  for(; k <= K; k += 2)
  {
    a += complex_coefficient(c, k, n) * (sk2 / double(k + 2));
    sk2 *= s * s;
  }
  return a;
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_BASIS_H
