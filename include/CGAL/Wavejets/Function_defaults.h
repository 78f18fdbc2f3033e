// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_FUNCTION_DEFAULTS_H
#define CGAL_WAVEJETS_FUNCTION_DEFAULTS_H

#include <CGAL/Wavejets/Fitting_options.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Wavejets {

/// \ingroup PkgWavejetsRef
/// The four point-set functions of the package (the key of `function_defaults()`).
enum class Point_set_function
{
  ESTIMATE_NORMALS,    ///< `wavejet_estimate_normals()`
  ESTIMATE_CURVATURES, ///< `wavejet_estimate_curvatures()`
  ENHANCE_POSITIONS,   ///< `wavejet_enhance_positions()`
  ENHANCE_NORMALS      ///< `wavejet_enhance_normals()`
};

/// \ingroup PkgWavejetsRef
/// Default settings of one point-set function: the one table of the defaults that the functions
/// read, and the `wavejets` tool too (the fit settings that all functions share are the defaults of
/// `Fitting_options`; only what differs per function is here).
struct Function_defaults
{
  /// Name of the function, e.g. `"wavejet_estimate_normals"` (used in its error messages).
  const char* name;
  /// The Wavejet order K when neither `Wavejets::parameters::order` nor `degree_fitting` is given.
  std::size_t order;
  /// The fit settings: the defaults of `Fitting_options`, with the function's `tangent_plane_order`
  /// (2 for the normal estimation, whose only output is the normal; 0, the full order, for the
  /// filters, which are defined over the tangent plane of the full-order Wavejet, and for the curvatures).
  Fitting_options fitting;
  /// `wavejet_enhance_positions()`: the default clamp of each point's motion, in units of its
  /// neighborhood radius Rf (0 for the functions that move no point).
  double maximum_displacement_in_radii;
  /// Whether the input normals orient the frames when the range has a normal map, without a named
  /// parameter asking for it (the functions whose outputs have a side: the curvatures' signs, the
  /// filters' heights and normals). `wavejet_estimate_normals()` orients only when asked.
  bool orients_with_input_normals;
};

/// \ingroup PkgWavejetsRef
/// The defaults of `f`.
inline Function_defaults function_defaults(Point_set_function f)
{
  Function_defaults d{"", 2, Fitting_options(), 0., true};
  switch(f)
  {
    case Point_set_function::ESTIMATE_NORMALS:
      d.name = "wavejet_estimate_normals";
      d.fitting.tangent_plane_order = 2;
      d.orients_with_input_normals = false;
      break;
    case Point_set_function::ESTIMATE_CURVATURES:
      d.name = "wavejet_estimate_curvatures";
      break;
    case Point_set_function::ENHANCE_POSITIONS:
      d.name = "wavejet_enhance_positions";
      d.order = 4;
      d.maximum_displacement_in_radii = 0.5;
      break;
    case Point_set_function::ENHANCE_NORMALS:
      d.name = "wavejet_enhance_normals";
      d.order = 4;
      break;
  }
  return d;
}

/// \ingroup PkgWavejetsRef
/// The neighborhood size that the `wavejets` tool and the Python module use when none is given: the
/// 40 nearest neighbors, or 1.5 times the (K+1)(K+2)/2 coefficients of order K when that is more
/// (order 7 and above), so that every point is fitted at full order. k nearest neighbors rather than
/// a radius from the average spacing, because the neighborhood radius Rf then follows the sampling
/// density: the sparse parts of a non-uniform mesh are fitted too (user manual, "Choosing the settings").
inline std::size_t default_number_of_neighbors(std::size_t order)
{
  const std::size_t coefficients = (order + 1) * (order + 2) / 2;
  return std::max<std::size_t>(40, 3 * coefficients / 2);
}

/// \ingroup PkgWavejetsRef
/// The ladder of neighborhood sizes that `wavejet_estimate_scales()` (and the tool's `--k auto`) try
/// when none is given: 7 numbers of neighbors from the smallest that fits order K with 1.5 points per
/// coefficient (at least 10) to 16 times that, each 2^(2/3) = 1.59 times the previous (the nested fits
/// then cost about 2.6 fits at the largest size).
inline std::vector<unsigned int> default_neighborhood_sizes(std::size_t order)
{
  const std::size_t coefficients = (order + 1) * (order + 2) / 2;
  const double smallest = double((std::max<std::size_t>)(10, (3 * coefficients + 1) / 2));
  std::vector<unsigned int> ladder;
  for(int j = 0; j < 7; ++j)
    ladder.push_back((unsigned int)(std::lround(smallest * std::exp2(2. * j / 3.))));
  return ladder;
}

/// \ingroup PkgWavejetsRef
/// The gain of the filters that the `wavejets` tool and the Python module use when none is given
/// (details doubled).
constexpr double default_filter_gain = 2.;

} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_FUNCTION_DEFAULTS_H
