// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_LANES_H
#define CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_LANES_H

// The vector types and memory layout shared by the least-squares solvers (least_squares.h): the
// column layout (column-major, every column padded with zero rows to a multiple of
// `householder_block` rows), the four-lane type Double4 the kernels are written for, the eight-lane
// Double8 of the order-2 kernel's AVX-512 variant, and the fixed-order reductions of partial sums
// (so that a result never depends on the vector width the compiler picked: the SSE2 and AVX code
// give bitwise identical results).
//
// CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS (define it before including any header of the package): the
// four-lane type is a plain struct instead of the GCC/Clang vector extension (what other compilers
// get): same arithmetic per lane, so bitwise the same results, except that there is no AVX-512
// variant (its eight-lane order-2 fits). CGAL_WAVEJETS_AVX512_DISPATCH is defined here when the
// AVX-512 variant is compiled in (solver_dispatch.h).

#include <CGAL/Wavejets/internal/instruction_sets.h>

#include <boost/align/aligned_allocator.hpp>

#include <cstddef>
#include <cstring>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// Allocator of cache-line aligned storage for the solver's scratch: the kernels read and write
/// 32-byte vectors at multiples of householder_block doubles from the start of a column, which
/// then never straddle two cache lines (measured: the K = 6 normals were up to 10% slower when
/// the heap happened to return storage that was only 16-byte aligned).
template <class T>
using Aligned_allocator = boost::alignment::aligned_allocator<T, 64>;

/// A vector of doubles in cache-line aligned storage.
typedef std::vector<double, Aligned_allocator<double> > Aligned_vector;

/// Row blocking of the solver: column strides are multiples of it.
constexpr std::size_t householder_block = 8;

/// Column stride for `rows` rows: `rows` rounded up to a multiple of householder_block.
inline std::size_t padded_rows(std::size_t rows)
{
  return (rows + householder_block - 1) / householder_block * householder_block;
}

/// Sum of the householder_block partial sums, in a fixed order.
CGAL_WAVEJETS_KERNEL_INLINE double reduce_block(const double* acc)
{
  return ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]));
}

#if (defined(__GNUC__) || defined(__clang__)) && !defined(CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS)
/// Four doubles (GCC/Clang vector extension: one AVX register, or two SSE2 registers with the same
/// per-lane arithmetic). Unaligned memory is read and written with memcpy.
typedef double Double4 __attribute__((vector_size(32)));
#else
/// Four doubles, for compilers without the vector extension: the same per-lane arithmetic (each
/// operator below is what the extension does lane by lane), so the kernels, written once for
/// `Double4`, give bitwise the same results; the compiler may vectorize the lanes.
struct Double4
{
  double lane[4];
  friend Double4 operator*(const Double4& a, const Double4& b)
  {
    return Double4{{a.lane[0] * b.lane[0], a.lane[1] * b.lane[1], a.lane[2] * b.lane[2], a.lane[3] * b.lane[3]}};
  }
  friend Double4 operator+(const Double4& a, const Double4& b)
  {
    return Double4{{a.lane[0] + b.lane[0], a.lane[1] + b.lane[1], a.lane[2] + b.lane[2], a.lane[3] + b.lane[3]}};
  }
  friend Double4 operator-(const Double4& a, const Double4& b)
  {
    return Double4{{a.lane[0] - b.lane[0], a.lane[1] - b.lane[1], a.lane[2] - b.lane[2], a.lane[3] - b.lane[3]}};
  }
  friend Double4 operator+(const Double4& a, double s) // broadcast
  {
    return Double4{{a.lane[0] + s, a.lane[1] + s, a.lane[2] + s, a.lane[3] + s}};
  }
  Double4& operator+=(const Double4& b)
  {
    for(int t = 0; t < 4; ++t) lane[t] += b.lane[t];
    return *this;
  }
  Double4& operator-=(const Double4& b)
  {
    for(int t = 0; t < 4; ++t) lane[t] -= b.lane[t];
    return *this;
  }
};
#endif

CGAL_WAVEJETS_KERNEL_INLINE void load4(Double4& r, const double* p) { std::memcpy(&r, p, sizeof r); }
CGAL_WAVEJETS_KERNEL_INLINE void store4(double* p, const Double4& x) { std::memcpy(p, &x, sizeof x); }

// The AVX-512 variant of the solver (dispatch_solver()): compiled where the AVX2 + FMA one is and the
// vector extension exists, unless CGAL_WAVEJETS_NO_AVX512_DISPATCH is defined.
#if defined(CGAL_WAVEJETS_AVX_DISPATCH) && !defined(CGAL_WAVEJETS_NO_FMA_DISPATCH) && \
    !defined(CGAL_WAVEJETS_NO_AVX512_DISPATCH) && !defined(CGAL_WAVEJETS_NO_VECTOR_EXTENSIONS)
#define CGAL_WAVEJETS_AVX512_DISPATCH 1
/// Eight doubles (one AVX-512 register): the lanes of the order-2 kernel in the AVX-512 variant.
typedef double Double8 __attribute__((vector_size(64)));
#endif

/// Lanes in a vector of `Lanes` (Double4 or Double8).
template <class Lanes>
constexpr std::size_t lane_count()
{
  return sizeof(Lanes) / sizeof(double);
}

/// Loads lane_count<Lanes>() doubles from p (unaligned).
template <class Lanes>
CGAL_WAVEJETS_KERNEL_INLINE void load_lanes(Lanes& r, const double* p)
{
  std::memcpy(&r, p, sizeof r);
}

/// Sum of the four lanes of x, in a fixed order.
CGAL_WAVEJETS_KERNEL_INLINE double reduce4(const Double4& x)
{
  double a[4];
  store4(a, x);
  return (a[0] + a[2]) + (a[1] + a[3]);
}

/// Sum of the lanes, in a fixed order (reduce4(), or reduce_block() of the eight lanes).
CGAL_WAVEJETS_KERNEL_INLINE double reduce_lanes(const Double4& x) { return reduce4(x); }
#ifdef CGAL_WAVEJETS_AVX512_DISPATCH
CGAL_WAVEJETS_KERNEL_INLINE double reduce_lanes(const Double8& x)
{
  double a[8];
  std::memcpy(a, &x, sizeof a);
  return reduce_block(a);
}
#endif

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_LEAST_SQUARES_LANES_H
