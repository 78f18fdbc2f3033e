// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_FRAME_KERNELS_H
#define CGAL_WAVEJETS_INTERNAL_FRAME_KERNELS_H

// The fitting core's work on a neighborhood before any system is solved: the PCA of the rescaled
// offsets (their moments and the 3 x 3 eigen-decomposition) and their projection onto a frame.

#include <CGAL/Wavejets/internal/instruction_sets.h>
#include <CGAL/Wavejets/internal/least_squares.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cstddef>
#include <limits>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The coordinates along three axes of L points stored coordinate by coordinate (x, y, z columns
/// of stride padded_rows(L) from `coordinates`, zero padding rows): column i of the output (x, y,
/// h) is the dot product with axes[3i..3i+2], zero on the rows L..P-1. Four rows at a time, all
/// three outputs in one pass (dispatch_avx(): bitwise the same values in AVX and SSE2).
struct Projection_kernel
{
  static CGAL_WAVEJETS_KERNEL_INLINE void run(const double* coordinates, std::size_t L, std::size_t P,
                                              const double* axes, double* x, double* y, double* h)
  {
    const std::size_t stride = padded_rows(L);
    const double* sx = coordinates;
    const double* sy = sx + stride;
    const double* sz = sy + stride;
    double* out[3] = {x, y, h};
    const Double4 zero = {0., 0., 0., 0.};
    Double4 axis[3][3];
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 3; ++j) axis[i][j] = zero + axes[3 * i + j];
    std::size_t l = 0;
    for(; l + 4 <= L; l += 4)
    {
      Double4 a, b, c;
      load4(a, sx + l);
      load4(b, sy + l);
      load4(c, sz + l);
      for(int i = 0; i < 3; ++i)
      {
        Double4 p = a * axis[i][0]; // (a u0 + b u1) + c u2, as in the scalar tail below
        p += b * axis[i][1];
        p += c * axis[i][2];
        store4(out[i] + l, p);
      }
    }
    for(; l < L; ++l)
      for(int i = 0; i < 3; ++i) out[i][l] = sx[l] * axes[3 * i] + sy[l] * axes[3 * i + 1] + sz[l] * axes[3 * i + 2];
    for(; l < P; ++l)
      for(int i = 0; i < 3; ++i) out[i][l] = 0.;
  }
};

/// First and second moments of L points stored as in Projection_kernel: sums[0..2] = sum x, y, z
/// and sums[3..8] = sum xx, xy, xz, yy, yz, zz, each with one partial sum per row residue mod 4
/// (reduce4()), in one pass (dispatch_avx(): bitwise the same sums in AVX and SSE2).
struct Moments_kernel
{
  static CGAL_WAVEJETS_KERNEL_INLINE void run(const double* coordinates, std::size_t L, double* sums)
  {
    const std::size_t P = padded_rows(L);
    const double* coordinate[3] = {coordinates, coordinates + P, coordinates + 2 * P};
    const Double4 zero = {0., 0., 0., 0.};
    // One named accumulator per sum (arrays of them were kept in memory by g++: a store and a
    // reload per update).
    Double4 sx = zero, sy = zero, sz = zero, sxx = zero, sxy = zero, sxz = zero, syy = zero, syz = zero, szz = zero;
    for(std::size_t l = 0; l < P; l += 4)
    {
      Double4 x, y, z;
      load4(x, coordinate[0] + l);
      load4(y, coordinate[1] + l);
      load4(z, coordinate[2] + l);
      sx += x;
      sy += y;
      sz += z;
      sxx += x * x;
      sxy += x * y;
      sxz += x * z;
      syy += y * y;
      syz += y * z;
      szz += z * z;
    }
    const Double4 all[9] = {sx, sy, sz, sxx, sxy, sxz, syy, syz, szz};
    for(int k = 0; k < 9; ++k) sums[k] = reduce4(all[k]);
  }
};

/// Eigen-decomposition of the symmetric 3 x 3 matrix `A` (the PCA's covariance): eigenvalues in
/// ascending order, the eigenvectors in the matching columns. Eigen's closed form
/// (SelfAdjointEigenSolver::computeDirect, cheaper than the iterative QR) is kept when it is as
/// accurate as the iterative solver, which is backward stable: its columns orthonormal and each
/// residual |A v_i - lambda_i v_i| within pca_direct_residual_bound eps |A|_F. Then every eigenvalue is within that of one of A's, and
/// each eigenvector within that over its eigenvalue's gap (the bounds of the iterative solver,
/// up to the constant). Otherwise (close eigenvalues, on which the closed form loses digits) the
/// iterative solver's result. Returns false if neither succeeds.
constexpr double pca_direct_residual_bound = 16.;

inline bool symmetric_eigen_3(const Eigen::Matrix3d& A, Eigen::Vector3d& values, Eigen::Matrix3d& vectors)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(A);
  values = eig.eigenvalues();
  vectors = eig.eigenvectors();
  const double eps = std::numeric_limits<double>::epsilon();
  const double residual_bound = pca_direct_residual_bound * eps * A.norm();
  const Eigen::Matrix3d residuals = A * vectors - vectors * values.asDiagonal();
  const Eigen::Matrix3d gram = vectors.transpose() * vectors - Eigen::Matrix3d::Identity();
  bool accurate = values.allFinite() && vectors.allFinite() && gram.cwiseAbs().maxCoeff() <= 8. * eps;
  for(int i = 0; i < 3 && accurate; ++i)
    accurate = residuals.col(i).norm() <= residual_bound;
  if(accurate)
    return true;
  eig.compute(A);
  if(eig.info() != Eigen::Success)
    return false;
  values = eig.eigenvalues();
  vectors = eig.eigenvectors();
  return true;
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_FRAME_KERNELS_H
