// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_INSTRUCTION_SETS_H
#define CGAL_WAVEJETS_INTERNAL_INSTRUCTION_SETS_H

// Run-time choice of the instruction set of the package's vectorized kernels (x86 with GCC or
// Clang). A kernel is written once, as an always-inlined function, and compiled again inside
// wrappers with the target attribute: for AVX without FMA (the arithmetic, hence the result, is
// bitwise the same as the baseline SSE2 code: every operation is one correctly rounded IEEE
// operation, and the compiler may not fuse without FMA) and, for the least-squares solver, for
// AVX2 with FMA and for AVX-512 (solver_dispatch.h). The best variant the processor supports is
// picked at run time, the same for every call: results never depend on the thread or on the
// ConcurrencyTag. Code compiled with FMA enabled for the whole translation unit (-mfma,
// -march=native, ...) has no dispatch: the kernels are compiled once, for those flags. The user's
// opt-out macros (documented in the manual's installation section; define them before including
// any header of the package):
//   CGAL_WAVEJETS_NO_AVX_DISPATCH        baseline code only (no run-time dispatch);
//   CGAL_WAVEJETS_NO_FMA_DISPATCH        the solver keeps only the AVX variant (solver_dispatch.h);
//   CGAL_WAVEJETS_NO_AVX512_DISPATCH     the solver has no AVX-512 variant (solver_dispatch.h).
// Macros defined here: CGAL_WAVEJETS_AVX_DISPATCH (defined when the dispatch is compiled in),
// CGAL_WAVEJETS_KERNEL_INLINE (the kernels' inline specifier) and CGAL_WAVEJETS_TARGET(sets),
// CGAL_WAVEJETS_UNROLL and CGAL_WAVEJETS_NOINLINE.
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__)) && \
    !defined(CGAL_WAVEJETS_NO_AVX_DISPATCH) && !defined(__FMA__)
#define CGAL_WAVEJETS_AVX_DISPATCH 1
#define CGAL_WAVEJETS_KERNEL_INLINE __attribute__((always_inline)) inline
#define CGAL_WAVEJETS_TARGET(instruction_sets) __attribute__((target(instruction_sets)))
#else
#define CGAL_WAVEJETS_KERNEL_INLINE inline
#define CGAL_WAVEJETS_TARGET(instruction_sets)
#endif

/// Asks the compiler to unroll the next loop completely (loops of a size known at compile time,
/// whose arrays then live in registers instead of memory).
#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 8)
#define CGAL_WAVEJETS_UNROLL _Pragma("GCC unroll 16")
#else
#define CGAL_WAVEJETS_UNROLL
#endif

/// Keeps a function out of its callers (a rarely taken path whose inlined code slows its caller's
/// loop down).
#if defined(__GNUC__) || defined(__clang__)
#define CGAL_WAVEJETS_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define CGAL_WAVEJETS_NOINLINE __declspec(noinline)
#else
#define CGAL_WAVEJETS_NOINLINE
#endif

namespace CGAL {
namespace Wavejets {
namespace internal {

/// True if the kernels are also compiled for AVX (and the solver for AVX2 + FMA and AVX-512) and
/// picked at run time (else only the baseline code exists).
#ifdef CGAL_WAVEJETS_AVX_DISPATCH
constexpr bool avx_dispatch = true;
#else
constexpr bool avx_dispatch = false;
#endif

/// True if the processor runs the AVX variants (the same answer for the whole run).
inline bool processor_runs_avx()
{
#ifdef CGAL_WAVEJETS_AVX_DISPATCH
  static const bool avx = __builtin_cpu_supports("avx");
  return avx;
#else
  return false;
#endif
}

/// `Kernel::run(arguments...)` compiled for AVX (call it only where processor_runs_avx()).
template <class Kernel, class... Arguments>
CGAL_WAVEJETS_TARGET("avx") inline void run_avx(Arguments... arguments)
{
  Kernel::run(arguments...);
}

/// Runs `Kernel::run(arguments...)` (a static, CGAL_WAVEJETS_KERNEL_INLINE function without FMA
/// contractions of its own) in its AVX variant where the processor has AVX, else in the baseline
/// code: bitwise the same results, about twice the vector width.
template <class Kernel, class... Arguments>
inline void dispatch_avx(Arguments... arguments)
{
  if(processor_runs_avx())
    run_avx<Kernel>(arguments...);
  else
    Kernel::run(arguments...);
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_INSTRUCTION_SETS_H
