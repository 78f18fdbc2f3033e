// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_SOLVER_CHOICE_H
#define CGAL_WAVEJETS_INTERNAL_SOLVER_CHOICE_H

// Which least-squares solver runs when, and why: the one place that decides is solver_for() below;
// the fitter (fitting_core.h) and the solver entry points (least_squares.h) only ask it. Figures:
// benchmark/Wavejets/results.md, section "Least squares" (command on its first lines).
//
//   case                                       solver                        why
//   ----------------------------------------   ---------------------------   ----------------------------------
//   CGAL_WAVEJETS_NO_SEMI_NORMAL defined       HOUSEHOLDER_QR, every system  the user's opt-out: the QR alone
//                                              (order 2 included)            (accuracy: no Gram matrix at all)
//   order-2 fit, system not yet built (the     ORDER2_MOMENTS; if its        speed: M^T M and M^T h from the
//     points' x, y, h), no IRLS, no R wanted   guards refuse, the rows       moments of the points, M never
//                                              below on the built system     built (results.md: 1.0x to 1.5x the QR)
//   built system, < semi_normal_minimum_       HOUSEHOLDER_QR                speed: the QR's column chain is
//     columns (21) unknowns (orders 1 to 4)                                  short, the Gram matrix costs as much
//   built Wavejet basis (unweighted, no        WAVEJET_SEMI_NORMAL_ELSE_QR   speed: the Gram matrix from polar
//     slope rows), >= 21 unknowns, >= 2 rows                                 moments, a quarter of the dot
//     per unknown, order <= 12                                               products' multiply-adds
//   any other built system, >= 21 unknowns     SEMI_NORMAL_ELSE_QR           speed: the Gram matrix is
//     (weighted, slope rows, fewer rows)                                     independent dot products where
//                                                                            the QR is a chain of column steps
//
// Accuracy: every semi-normal solver is guarded (semi_normal.h: the scaled Cholesky pivot and the
// size of the refinement step); a system it refuses is solved by the Householder QR, whose result
// it then is, bit for bit. Which instruction set each solver runs in: solver_dispatch.h.

#include <CGAL/Wavejets/internal/order2_moments.h>
#include <CGAL/Wavejets/internal/polar_moment_gram.h>

#include <cstddef>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The least-squares solvers, as solver_for() names them.
enum class Solver
{
  HOUSEHOLDER_QR,              ///< householder_kernel() (householder_qr.h)
  SEMI_NORMAL_ELSE_QR,         ///< semi_normal_kernel() (semi_normal.h), the QR where its guards refuse
  WAVEJET_SEMI_NORMAL_ELSE_QR, ///< wavejet_semi_normal_kernel(): the same, the Gram matrix from polar moments
  ORDER2_MOMENTS               ///< order2_moments_kernel() (order2_moments.h), on the points' x, y, h
};

/// Fewest unknowns for which the semi-normal equations run: 21 (order 5). Below, the QR's column
/// chain is short and the Gram matrix's reductions cost as much: measured on one core (AVX2 + FMA,
/// one Wavejet system in cache, copy included), the semi-normal equations against the QR: 97 x 28
/// (order 6) 1.31x faster, 33 x 15 (order 4) 0.91x, 101 x 6 (order 2) 1.0x (results.md's
/// least-squares table: the same at order 4 with the Gram matrix dot by dot).
constexpr std::size_t semi_normal_minimum_columns = 21;

/// Fewest rows per unknown for which the Wavejet systems' Gram matrix is built from polar moments:
/// their cost is mostly per unknown (the 3K power columns, the B(B+1)/2 entries), the dot products'
/// per row. Measured on one core (AVX2 + FMA, synthetic neighborhoods, the semi-normal solve with the
/// moments against dot by dot): 97 x 28 1.2x to 1.3x faster, 80 x 36 1.31x, 70 x 21 1.12x, 60 x 28
/// 1.12x; below, 45 x 28 0.97x to 0.99x, 40 x 21 0.89x to 0.94x.
constexpr std::size_t polar_moment_minimum_rows_per_column = 2;

/// True if the semi-normal solvers (and the order-2 moments) may run: not CGAL_WAVEJETS_NO_SEMI_NORMAL.
#ifdef CGAL_WAVEJETS_NO_SEMI_NORMAL
constexpr bool semi_normal_enabled = false;
#else
constexpr bool semi_normal_enabled = true;
#endif

/// A least-squares problem as solver_for() sees it.
struct Least_squares_case
{
  std::size_t rows;   ///< rows of M (the points, for an order-2 fit not yet built)
  std::size_t cols;   ///< unknowns
  bool wavejet_basis; ///< M's columns are the Wavejet basis of evaluate_basis_columns() (no weights, no slope rows)
  bool built;         ///< M is built; false: only the points' x, y and h are (order2_least_squares()'s input)
  bool reweighted;    ///< M is kept for reweighted (IRLS) passes
  bool wants_R;       ///< R is asked for (the condition number)
};

/// The solver of the table above for `s`: the one rule of which solver runs when.
inline Solver solver_for(const Least_squares_case& s)
{
  if(!semi_normal_enabled)
    return Solver::HOUSEHOLDER_QR;
  if(!s.built)
    return s.wavejet_basis && s.cols == order2_columns && !s.reweighted && !s.wants_R ? Solver::ORDER2_MOMENTS
                                                                                     : Solver::HOUSEHOLDER_QR;
  if(s.cols < semi_normal_minimum_columns)
    return Solver::HOUSEHOLDER_QR;
  if(s.wavejet_basis && s.rows >= polar_moment_minimum_rows_per_column * s.cols && polar_moment_order(s.cols) > 0)
    return Solver::WAVEJET_SEMI_NORMAL_ELSE_QR;
  return Solver::SEMI_NORMAL_ELSE_QR;
}

/// The solver of a built system of `rows` x `cols` (solver_for()); `wavejet_basis`: its columns are
/// the Wavejet basis.
inline Solver solver_for_built(std::size_t rows, std::size_t cols, bool wavejet_basis)
{
  return solver_for(Least_squares_case{rows, cols, wavejet_basis, true, false, false});
}

/// True if an order-2 fit of L points in a frame is solved from its moments before any system is
/// built (solver_for(): order 2, no IRLS, no R, semi-normal solvers enabled).
inline bool order2_from_moments(std::size_t order, std::size_t L, bool reweighted, bool wants_R)
{
  return order == 2 &&
         solver_for(Least_squares_case{L, order2_columns, true, false, reweighted, wants_R}) == Solver::ORDER2_MOMENTS;
}

/// True if solver_for() solves a built Wavejet system of `rows` x `cols` by the semi-normal equations
/// with the Gram matrix from polar moments (before their guards decide).
inline bool uses_polar_moments(std::size_t rows, std::size_t cols)
{
  return solver_for_built(rows, cols, true) == Solver::WAVEJET_SEMI_NORMAL_ELSE_QR;
}

/// The kernel of the solver solver_for_built() picks for a built system, compiled into the caller's
/// instruction set (solver_dispatch.h). `with_R` false: R need not be returned (the semi-normal
/// solvers then skip it and leave A unchanged). `scratch`: least_squares_scratch_size() or, for a
/// Wavejet basis, wavejet_least_squares_scratch_size() (least_squares.h).
template <bool wavejet_basis, bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool chosen_solver_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                     double* c)
{
  switch(solver_for_built(rows, cols, wavejet_basis))
  {
  case Solver::SEMI_NORMAL_ELSE_QR:
    return semi_normal_kernel<with_R>(A, rows, cols, scratch, c) || householder_kernel(A, rows, cols, scratch, c);
  case Solver::WAVEJET_SEMI_NORMAL_ELSE_QR:
    return wavejet_semi_normal_kernel<with_R>(A, rows, cols, scratch, c) ||
           householder_kernel(A, rows, cols, scratch, c);
  default:
    return householder_kernel(A, rows, cols, scratch, c);
  }
}

/// The solver of every built system that is not the unweighted Wavejet basis (weighted rows, slope
/// rows): chosen_solver_kernel() for a general matrix.
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool least_squares_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                                     double* c)
{
  return chosen_solver_kernel<false, with_R>(A, rows, cols, scratch, c);
}

/// The solver of the built Wavejet systems of evaluate_basis_columns() (cols = (K+1)(K+2)/2):
/// chosen_solver_kernel() for the Wavejet basis.
template <bool with_R = true>
CGAL_WAVEJETS_KERNEL_INLINE bool wavejet_least_squares_kernel(double* A, std::size_t rows, std::size_t cols,
                                                             double* scratch, double* c)
{
  return chosen_solver_kernel<true, with_R>(A, rows, cols, scratch, c);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_SOLVER_CHOICE_H
