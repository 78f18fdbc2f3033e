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
// the entry points of the package's solvers. Which solver runs when, and why: solver_choice.h.
// The solvers, one file each: householder_qr.h (Householder QR), semi_normal.h (the guarded
// corrected semi-normal equations, their Gram matrix dot by dot, gram_matrix.h, or for the Wavejet
// basis from polar moments, polar_moment_gram.h), order2_moments.h (the order-2 fit from the moments
// of the points); their lane types and layout: least_squares_lanes.h; their instruction-set variants
// and run-time dispatch: solver_dispatch.h.
//
// Layout: column-major, every column (the right-hand side is one more column) padded with zero
// rows to a multiple of `householder_block` rows (padded_rows()).
//
// CGAL_WAVEJETS_NO_SEMI_NORMAL (documented in the manual's installation section; define it before
// including any header of the package): every system built and solved by the Householder QR (also
// the order-2 fits, which are otherwise solved from their moments): solver_for().

#include <CGAL/Wavejets/internal/householder_qr.h>
#include <CGAL/Wavejets/internal/least_squares_lanes.h>
#include <CGAL/Wavejets/internal/order2_moments.h>
#include <CGAL/Wavejets/internal/polar_moment_gram.h>
#include <CGAL/Wavejets/internal/semi_normal.h>
#include <CGAL/Wavejets/internal/solver_choice.h>
#include <CGAL/Wavejets/internal/solver_dispatch.h>

#include <algorithm>
#include <cstddef>

namespace CGAL {
namespace Wavejets {
namespace internal {

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
  return dispatch_solver<Solver::SEMI_NORMAL_ELSE_QR>(A, rows, cols, scratch, c);
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
  return dispatch_solver<Solver::WAVEJET_SEMI_NORMAL_ELSE_QR>(A, rows, cols, scratch, c);
}

/// The same solution c as least_squares() (`wavejet_basis` false) or wavejet_least_squares()
/// (true), bit for bit, without R: A is left unchanged or destroyed (the QR's work).
inline bool least_squares_solution(double* A, std::size_t rows, std::size_t cols, double* scratch, double* c,
                                   bool wavejet_basis)
{
  return wavejet_basis
           ? dispatch_solver<Solver::WAVEJET_SEMI_NORMAL_ELSE_QR, false>(A, rows, cols, scratch, c)
           : dispatch_solver<Solver::SEMI_NORMAL_ELSE_QR, false>(A, rows, cols, scratch, c);
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
