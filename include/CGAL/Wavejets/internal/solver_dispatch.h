// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_SOLVER_DISPATCH_H
#define CGAL_WAVEJETS_INTERNAL_SOLVER_DISPATCH_H

// The instruction-set variants of the least-squares solvers and their run-time dispatch:
// dispatch_solver<S>() runs solver S (solver_choice.h) compiled for the best instruction set the
// processor has, the same for every call (results never depend on the thread). A variant is kept
// where a measurement shows that it earns its code (ratios of the variant against the next one down,
// one core, g++ Release; the commands below; the machines' figures: benchmark/Wavejets/results.md):
//
//   variant        results                          gain over the variant one line up
//   baseline       the reference                    -
//   (SSE2)
//   AVX            bitwise the baseline's           (1) order-2 moments K 2 k 100 2.05x, QR K 4 k 32 2.73x,
//                                                   QR K 6 k 96 3.68x, polar-moment semi-normal K 6 k 96 2.10x
//   AVX2 + FMA     differ in the last bits (fused   (1) 1.00x, 1.04x, 0.99x, 1.04x: no gain of its own; kept
//                  multiply-adds)                   as the base of the AVX-512 variant (same FMA arithmetic,
//                                                   bitwise equal results outside order 2) and for processors
//                                                   with FMA and no AVX-512 (not measured on such a processor)
//   AVX-512        bitwise AVX2 + FMA's, except     (1) 1.02x, 1.22x, 1.17x, 1.05x; (2) Fitter::fit, 2000 bunny
//                  the order-2 fits (eight rows     neighborhoods: K 2 k 100 1.16x, K 2 k 18 1.18x, K 2 k 50
//                  per step: other partial sums,    1.09x, K 4 k 32 (tangent plane order 2) 1.25x, K 6 k 96
//                  last bits)                       normals 1.16x, K 6 k 96 1.0x; (3) K 2 fit 1.13x, K 6 1.05x
//
// (1) The solvers alone, one core, thread CPU time per solve (copy of the system included), 20,000
//     synthetic neighborhoods (points in the unit disk) per case, one binary per variant built with
//     the opt-out macros below (g++ -O3), five alternated runs, medians. (2) The fitter's harness,
//     alternated with the code before the AVX-512 variant. (3) bench_speed 100000 --mode all, the same
//     hour as the code before it (benchmark/Wavejets/results.md).
//
// The user's opt-out macros (documented in the manual's installation section; define them before
// including any header of the package), besides instruction_sets.h's CGAL_WAVEJETS_NO_AVX_DISPATCH:
//   CGAL_WAVEJETS_NO_FMA_DISPATCH        keep only the AVX variant (results bitwise equal to baseline);
//   CGAL_WAVEJETS_NO_AVX512_DISPATCH     no AVX-512 variant (AVX2 + FMA is the best).

#include <CGAL/Wavejets/internal/householder_qr.h>
#include <CGAL/Wavejets/internal/instruction_sets.h>
#include <CGAL/Wavejets/internal/least_squares_lanes.h>
#include <CGAL/Wavejets/internal/order2_moments.h>
#include <CGAL/Wavejets/internal/solver_choice.h>

#include <cstddef>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// Solver S on A; `with_R` false: R need not be returned (the semi-normal solvers then skip it).
/// SEMI_NORMAL_ELSE_QR and WAVEJET_SEMI_NORMAL_ELSE_QR run the solver solver_for() picks for a built
/// general or Wavejet system (chosen_solver_kernel(): the QR below semi_normal_minimum_columns).
/// ORDER2_MOMENTS: A holds the columns x, y, h of the points; cols and scratch are unused.
/// `Lanes`: the vector type of the order-2 kernel (the other solvers use Double4).
template <Solver S, bool with_R = true, class Lanes = Double4>
CGAL_WAVEJETS_KERNEL_INLINE bool solver_kernel(double* A, std::size_t rows, std::size_t cols, double* scratch,
                                              double* c)
{
  switch(S)
  {
  case Solver::HOUSEHOLDER_QR: return householder_kernel(A, rows, cols, scratch, c);
  case Solver::SEMI_NORMAL_ELSE_QR: return least_squares_kernel<with_R>(A, rows, cols, scratch, c);
  case Solver::WAVEJET_SEMI_NORMAL_ELSE_QR: return wavejet_least_squares_kernel<with_R>(A, rows, cols, scratch, c);
  case Solver::ORDER2_MOMENTS: return order2_moments_kernel<Lanes>(A, rows, c);
  }
  return false;
}

/// The kernel compiled for AVX2 + FMA (run it only where the processor has both).
template <Solver S, bool with_R = true>
CGAL_WAVEJETS_TARGET("avx2,fma")
inline bool solver_fma(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_kernel<S, with_R>(A, rows, cols, v, c);
}
/// The kernel compiled for AVX (run it only where the processor has it).
template <Solver S, bool with_R = true>
CGAL_WAVEJETS_TARGET("avx") inline bool solver_avx(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_kernel<S, with_R>(A, rows, cols, v, c);
}

/// True if the solver is also compiled for AVX-512 (with AVX2 + FMA) and picked at run time where
/// the processor has it.
#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
constexpr bool avx512_dispatch = true;
#else
constexpr bool avx512_dispatch = false;
#endif

/// True if the dispatch may run solver_fma(): the processor has AVX2 and FMA, and the variant is
/// compiled in (not CGAL_WAVEJETS_NO_FMA_DISPATCH). The same answer for the whole run.
inline bool processor_runs_fma()
{
#if defined(CGAL_WAVEJETS_AVX_DISPATCH) && !defined(CGAL_WAVEJETS_NO_FMA_DISPATCH)
  static const bool fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return fma;
#else
  return false;
#endif
}

/// True if the dispatch runs solver_avx512(): the processor has AVX-512 F, VL and DQ besides AVX2
/// and FMA, and the variant is compiled in. The same answer for the whole run.
inline bool processor_runs_avx512()
{
#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
  static const bool avx512 = processor_runs_fma() && __builtin_cpu_supports("avx512f") &&
                             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
  return avx512;
#else
  return false;
#endif
}

#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
/// The kernel compiled for AVX-512 (run it only where processor_runs_avx512()). The order-2 kernel
/// takes eight rows per step (Double8): its moments' partial sums differ, hence its solutions up to
/// rounding; the other solvers keep their four-lane code, which the compiler gives twice as many
/// registers (the same operations: bitwise the AVX2 + FMA variant's results, checked by
/// test_simd_kernels; fewer spills, most in the QR of orders 3 and 4).
template <Solver S, bool with_R = true>
CGAL_WAVEJETS_TARGET("avx512f,avx512vl,avx512dq,avx2,fma")
inline bool solver_avx512(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_kernel<S, with_R, Double8>(A, rows, cols, v, c);
}
#else
/// Not compiled in: the AVX2 + FMA variant (processor_runs_avx512() is false; never dispatched).
template <Solver S, bool with_R = true>
inline bool solver_avx512(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
  return solver_fma<S, with_R>(A, rows, cols, v, c);
}
#endif

/// Runs solver S compiled for the best instruction set the processor has (the same for every call).
template <Solver S, bool with_R = true>
inline bool dispatch_solver(double* A, std::size_t rows, std::size_t cols, double* v, double* c)
{
#ifdef CGAL_WAVEJETS_AVX_DISPATCH
  if(processor_runs_avx512())
    return solver_avx512<S, with_R>(A, rows, cols, v, c);
  if(processor_runs_fma())
    return solver_fma<S, with_R>(A, rows, cols, v, c);
  if(processor_runs_avx())
    return solver_avx<S, with_R>(A, rows, cols, v, c);
#endif
  return solver_kernel<S, with_R>(A, rows, cols, v, c);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_SOLVER_DISPATCH_H
