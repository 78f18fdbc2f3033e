// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers
#ifndef CGAL_WAVEJET_ENHANCE_NORMALS_H
#define CGAL_WAVEJET_ENHANCE_NORMALS_H

#include <CGAL/Wavejets/internal/point_set_driver.h>
#include <CGAL/Wavejets/internal/basis.h>

#include <CGAL/disable_warnings.h>

#include <complex>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The settings of `wavejet_enhance_normals()`: the driver's and the filter's own.
struct Enhance_normals_settings
{
  Driver_settings driver;
  double evaluation_radius = 0.; // s of a_{-1}(s), world units; 0: Rf of each point
};

/// Reads and checks the named parameters of `wavejet_enhance_normals()`.
template <class PointRange, class NP>
Enhance_normals_settings enhance_normals_settings(PointRange& points, unsigned int k, const NP& np)
{
  Enhance_normals_settings s;
  s.driver = read_settings(points, k, np, function_defaults(Point_set_function::ENHANCE_NORMALS));
  require_normal_map(points, np, s.driver.function);
  s.evaluation_radius = read_evaluation_radius(np, s.driver.function);
  return s;
}

} // namespace internal
} // namespace Wavejets

/*!
\ingroup PkgWavejetsRef

Enhances, blurs, inverts or twists the normals of a point set by tilting each one according to
its Wavejet's antisymmetric tendency a_{-1}(s) (Béarzi et al.\ 2018, Algorithm 2; see \ref Wavejets_filters
in the user manual).
In the final tangent frame (u, v, n) of each point:

    a_{-1}(s) = sum_{k = 3, 5, ..} f_{k,-1} s^{k+2}/(k+2)
    f'_{1,-1} = f_{1,-1} - pi (gain - 1) a_{-1}(s) / Rf^3,   f'_x + i f'_y = 2 f'_{1,-1}
    n'        = normalize(-f'_x u - f'_y v + n).

`gain == 1` gives the Wavejet's own normal (a denoised normal), 2 exaggerates normal variation,
0 blurs it, negative gains invert it, and a non-real gain twists the normals (its phase rotates
the tilt in the tangent plane). Positions are not changed. The output keeps the orientation of
the input normal (the frame is oriented by it; a zero or NaN input normal leaves that point's
orientation to PCA). Every new normal is computed from the original input before any is written.

\tparam ConcurrencyTag `Sequential_tag`, `Parallel_tag` or `Parallel_if_available_tag`; both give bitwise identical results.
\tparam PointRange a model of `Range`.

\param points input points with normals.
\param k number of neighbors, as in `wavejet_estimate_normals()`.
\param gain complex gain alpha_{-1} (a real number converts); finite, |gain| <= 1e100 (a larger gain
       overflows the tilt and gives non-finite normals: it is rejected).
\param np the named parameters of `wavejet_estimate_normals()` except `orient_with_input_normals` (the
       input normals always orient the output; `normal_map` is required and read-write), with different
       defaults for `order` and `tangent_plane_order` (0: the re-fits of the tangent-plane search are
       full-order fits, since the filter is defined over the full-order Wavejet's tangent plane), plus
       `evaluation_radius`:

\cgalNamedParamsBegin
  \cgalParamNBegin{Wavejets::parameters::order}
    \cgalParamDescription{the requested Wavejet order K (lowered per point by the adaptive order); the
                          filter needs K >= 3 to have an effect (a_{-1}(s) has no term below k = 3)}
    \cgalParamType{`std::size_t`, `>= 1`}
    \cgalParamDefault{4}
  \cgalParamNEnd
  \wavejetsDegreeFittingParameter{4}
  \cgalParamNBegin{Wavejets::parameters::evaluation_radius}
    \cgalParamDescription{the radius s of a_{-1}(s), in world units; clamped to Rf per point (0: Rf)}
    \cgalParamType{`double` (or `geom_traits::FT`), finite and `>= 0`}
    \cgalParamDefault{Rf of each point}
  \cgalParamNEnd
\cgalNamedParamsEnd

\return a `Wavejets::Processing_report`; unfitted points keep their normal.
\throws std::invalid_argument on the conditions of `wavejet_estimate_normals()`, a non-finite gain or |gain| > 1e100.
*/
template <typename ConcurrencyTag, typename PointRange,
          typename NamedParameters = parameters::Default_named_parameters>
Wavejets::Processing_report wavejet_enhance_normals(PointRange& points, unsigned int k,
                                                    const std::complex<double>& gain,
                                                    const NamedParameters& np = parameters::default_values())
{
  using namespace Wavejets::internal;
  typedef Point_set_input<PointRange, NamedParameters> Input;
  static_assert(may_have_normal_map<PointRange, NamedParameters>(), "Error: no normal map");
  const Enhance_normals_settings settings = enhance_normals_settings(points, k, np);
  require(std::isfinite(gain.real()) && std::isfinite(gain.imag()) && std::abs(gain) <= 1e100,
          settings.driver.function, "the gain must be finite, |gain| <= 1e100");
  const Input input(points, np, settings.driver.read_input_normals);

  const double pi = 3.14159265358979323846;
  std::vector<Eigen::Vector3d> normals(input.size());
  const Driver_run run = fit_each_point<ConcurrencyTag>(input, settings.driver,
    [&](const Fitted_point& fp) {
      const double sigma = fp.evaluation_radius_in_radii(settings.evaluation_radius);
      const std::complex<double> a = enclosed_area(fp.coefficients, fp.fit.order, -1, sigma, 3); // rescaled
      const std::complex<double> tilt = complex_coefficient(fp.coefficients, 1, -1) - pi * (gain - 1.) * a;
      normals[fp.index] = graph_normal(fp.fit.frame, 2. * tilt.real(), 2. * tilt.imag());
    });

  commit(input, run, [&](std::size_t i, auto&& key) {
    put(input.normal_map, key, Input::to_vector(normals[i]));
  });
  return run.report;
}

} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_WAVEJET_ENHANCE_NORMALS_H
