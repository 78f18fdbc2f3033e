// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_POLAR_MOMENT_GRAM_H
#define CGAL_WAVEJETS_INTERNAL_POLAR_MOMENT_GRAM_H

// The Gram matrix of the order-K Wavejet basis from the polar moments of the neighborhood,
// polar_moment_gram_upper(): the Gram matrix of the semi-normal solver of the unweighted Wavejet
// systems (semi_normal.h, wavejet_semi_normal_kernel()), about a quarter of the multiply-adds of the
// dot products (gram_matrix.h).

#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/gram_matrix.h>
#include <CGAL/Wavejets/internal/householder_qr.h>
#include <CGAL/Wavejets/internal/least_squares_lanes.h>

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

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

/// Where polar_moment_gram_upper() reads the real columns of the powers z^m, m = 0..2K (Re z^0, then
/// Re z^m, Im z^m), and r^{2a}, a = 0..K: the columns of the basis for z^m, m <= K, and r^{2a},
/// 2a <= K, the others built in its scratch (build_polar_powers()), followed there by the moments.
struct Polar_columns
{
  const double* power[4 * polar_moment_maximum_order + 4]; // real columns of z^m
  const double* radial[polar_moment_maximum_order + 2];    // r^{2a}
  std::size_t first_built_radial;                          // the first a with 2a > K
  double* built_powers;                                    // z^m, m = K+1..2K, in scratch
  double* built_radials;                                   // r^{2a}, 2a > K, in scratch
  double* moments;                                         // after them in scratch
};

/// Fills `columns` for the order-K basis columns of A (stride P) and `scratch`
/// (polar_moment_scratch_size()).
CGAL_WAVEJETS_KERNEL_INLINE void locate_polar_columns(const double* A, std::size_t P, std::size_t K, double* scratch,
                                                     Polar_columns& columns)
{
  const double** power = columns.power;
  const double** radial = columns.radial;
  power[0] = A;
  for(std::size_t m = 1; m <= K; ++m)
  {
    power[2 * m - 1] = A + (order_offset(m) + m - 1) * P;
    power[2 * m] = A + (order_offset(m) + m) * P;
  }
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
  radial[K + 1] = radial[K]; // the partner of row K when K is even: never read (row K has one column)
  columns.first_built_radial = first_built_radial;
  columns.built_powers = built_powers;
  columns.built_radials = built_radials;
  columns.moments = built_radials + (K - first_built_radial + 1) * P;
}

/// The powers z^m, m = K+1..2K, then r^{2a}, 2a > K, into their columns in scratch, row block by row
/// block: each value is computed as evaluate_basis_columns() computes the basis (z^m = z^{m-1} z,
/// r^{2a} = (x^2 + y^2) r^{2a-2}), the chain kept in registers instead of re-read from the column
/// before. `x`, `y`: the basis columns x and y (stride P).
CGAL_WAVEJETS_KERNEL_INLINE void build_polar_powers(const double* x, const double* y, std::size_t P, std::size_t K,
                                                   const Polar_columns& columns)
{
  const std::size_t first_built_radial = columns.first_built_radial;
  double* const built_powers = columns.built_powers;
  double* const built_radials = columns.built_radials;
  const double* last_basis_re = columns.power[2 * K - 1];
  const double* last_basis_im = columns.power[2 * K];
  const double* last_basis_radial = columns.radial[first_built_radial - 1];
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
}

/// The moments mu[a * Z + c] = r^{2a} . (column c of the powers), Z = polar_power_columns(K), for the
/// c of z^m with 2a + m <= 2K: row a needs the columns c < 4(K - a) + 1. Rows a, a + 1 together by
/// tiles of four columns (row a + 1 needs four columns fewer: its part of the last tile that starts
/// below row a's last column is computed and not read), then row a's last column, Im z^{2(K - a)},
/// alone.
CGAL_WAVEJETS_KERNEL_INLINE void polar_moments(const Polar_columns& columns, std::size_t P, std::size_t K, double* mu)
{
  const std::size_t Z = polar_power_columns(K);
  const double* const* power = columns.power;
  const Double4 zero = {0., 0., 0., 0.};
  for(std::size_t a = 0; a <= K; a += 2)
  {
    const std::size_t last = 4 * (K - a); // row a's last column
    const double* u0 = columns.radial[a];
    const double* u1 = columns.radial[a + 1];
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
}

/// The upper triangle of the order-K Gram matrix G from the moments `mu` (polar_moment_terms()), and
/// its column B, M^T b, dot by dot from A's columns (stride P).
CGAL_WAVEJETS_KERNEL_INLINE void gram_from_polar_moments(const double* A, std::size_t P, std::size_t K,
                                                        const double* mu, double* G)
{
  const std::size_t B = number_of_coefficients(K);
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
  Polar_columns columns;
  locate_polar_columns(A, P, order, scratch, columns);
  build_polar_powers(A + P, A + 2 * P, P, order, columns);
  polar_moments(columns, P, order, columns.moments);
  gram_from_polar_moments(A, P, order, columns.moments, G);
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

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_POLAR_MOMENT_GRAM_H
