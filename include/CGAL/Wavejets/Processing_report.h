// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_PROCESSING_REPORT_H
#define CGAL_WAVEJETS_PROCESSING_REPORT_H

#include <cstddef>
#include <ostream>

namespace CGAL {
namespace Wavejets {

/// \ingroup PkgWavejetsRef
/// What a point-set function did; returned by every `wavejet_*` function.
/// Points that could not be fitted are left unchanged (their outputs are not written).
struct Processing_report
{
  /// Size of the input range.
  std::size_t number_of_points = 0;
  /// Points with a Wavejet (their outputs were written).
  std::size_t number_of_fitted_points = 0;
  /// Points left unchanged: too few neighbors, degenerate neighborhood or non-finite input.
  std::size_t number_of_unfitted_points = 0;
  /// Among the unfitted points, those with a NaN or infinite coordinate.
  std::size_t number_of_non_finite_points = 0;
  /// Fitted points whose order was lowered below the requested one (adaptive order).
  std::size_t number_of_reduced_order_points = 0;
  /// `wavejet_enhance_positions` only: points whose motion was clamped to `maximum_displacement`
  /// (0 for the other functions, which move no point; see `moves_points`).
  std::size_t number_of_clamped_points = 0;
  /// True for the reports of `wavejet_enhance_positions`, the one function that moves points (and
  /// so clamps motions): `number_of_clamped_points` is meaningful, and printed, only then.
  bool moves_points = false;
  /// The number of tiles the points were processed in: 1 in core, more with the named parameter
  /// `Wavejets::parameters::tile_size` (0 for an empty range).
  std::size_t number_of_tiles = 0;
  /// Tiled runs: the points whose neighborhood reached past the first halo of their tile, fitted again
  /// with a larger one (their results are exact like every other point's).
  std::size_t number_of_repaired_points = 0;
  /// With `Wavejets::parameters::tile`: the owned points whose neighborhood reaches past the tile's
  /// extent, neither fitted nor written (they are marked in `outside_map`; the other counts are those
  /// of the owned points).
  std::size_t number_of_outside_points = 0;
  /// True if the callback stopped the computation; then nothing at all was written.
  bool interrupted = false;
};

/// Prints the report on one line.
inline std::ostream& operator<<(std::ostream& os, const Processing_report& r)
{
  os << r.number_of_points << " points, " << r.number_of_fitted_points << " fitted, "
     << r.number_of_unfitted_points << " not fitted (" << r.number_of_non_finite_points << " non-finite), "
     << r.number_of_reduced_order_points << " at reduced order";
  if(r.moves_points) os << ", " << r.number_of_clamped_points << " clamped";
  if(r.number_of_outside_points > 0) os << ", " << r.number_of_outside_points << " reaching past the tile";
  if(r.number_of_tiles > 1)
    os << ", " << r.number_of_tiles << " tiles (" << r.number_of_repaired_points << " points with a larger halo)";
  os << (r.interrupted ? ", interrupted (nothing written)" : "");
  return os;
}

} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_PROCESSING_REPORT_H
