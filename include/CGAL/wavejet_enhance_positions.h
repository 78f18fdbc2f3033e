// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers
#ifndef CGAL_WAVEJET_ENHANCE_POSITIONS_H
#define CGAL_WAVEJET_ENHANCE_POSITIONS_H

#include <CGAL/Wavejets/internal/point_set_driver.h>
#include <CGAL/Wavejets/internal/basis.h>

#include <CGAL/disable_warnings.h>

#include <cmath>
#include <limits>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The settings of `wavejet_enhance_positions()`: the driver's and the filter's own.
struct Enhance_positions_settings
{
  Driver_settings driver;
  double evaluation_radius = 0.;           // s of a_0(s), world units; 0: Rf of each point
  double maximum_displacement = 0.;        // clamp, world units; 0: maximum_displacement_in_radii * Rf
  double maximum_displacement_in_radii = 0.;
  bool write_normals = false;              // also write the Wavejet normals
  bool move_along_input_normals = false;   // move along the input normals
};

/// Reads and checks the named parameters of `wavejet_enhance_positions()`.
template <class PointRange, class NP>
Enhance_positions_settings enhance_positions_settings(PointRange& points, unsigned int k, const NP& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  namespace wnp = Wavejets::internal_np;
  const Function_defaults d = function_defaults(Point_set_function::ENHANCE_POSITIONS);
  const char* fn = d.name;
  Enhance_positions_settings s;
  s.driver = read_settings(points, k, np, d);
  s.write_normals = choose_parameter(get_parameter(np, wnp::write_normals), false);
  s.move_along_input_normals = choose_parameter(get_parameter(np, wnp::move_along_input_normals), false);
  const bool has_normals = has_normal_map(points, np);
  require(!s.write_normals || has_normals, fn, "write_normals needs a normal map");
  require(!s.move_along_input_normals || has_normals, fn, "move_along_input_normals needs a normal map");
  s.evaluation_radius = read_evaluation_radius(np, fn);
  s.maximum_displacement_in_radii = d.maximum_displacement_in_radii;
  if constexpr(!CGAL::parameters::is_default_parameter<NP, wnp::maximum_displacement_t>::value)
  {
    s.maximum_displacement = to_double(get_parameter(np, wnp::maximum_displacement));
    require(s.maximum_displacement > 0, fn, "maximum_displacement must be > 0 (infinity switches the clamp off)");
  }
  return s;
}

/// Direction along which the position filter moves a fitted point: its Wavejet normal (the final
/// frame's n), or with `along_input` its normalized input normal turned to the side of n (so that the
/// height d, measured along n, keeps its meaning whatever the input orientation). A zero or
/// non-finite input normal falls back to n.
inline Eigen::Vector3d motion_direction(const Fitted_point& fp, const std::vector<Eigen::Vector3d>& input_normals,
                                        bool along_input)
{
  const Eigen::Vector3d& n = fp.fit.frame.n;
  if(!along_input) return n;
  const Eigen::Vector3d& m = input_normals[fp.index];
  const double length = m.stableNorm();
  if(!(length > 0) || !std::isfinite(length)) return n;
  return (m.dot(n) < 0 ? -1. / length : 1. / length) * m;
}

} // namespace internal
} // namespace Wavejets

/*!
\ingroup PkgWavejetsRef

Enhances, flattens or inverts the surface details of a point set by moving every point along its
Wavejet normal (Béarzi et al.\ 2018, Algorithm 1; see \ref Wavejets_filters in the user manual):

    p' = p + ( f_{0,0} - 2 pi (gain - 1) a_0(s) / Rf^2 ) n,    a_0(s) = sum_{k = 2, 4, ..} f_{k,0} s^{k+2}/(k+2),

in the final tangent frame of p. `gain == 1` only projects p onto its Wavejet (denoising),
`gain > 1` amplifies details, `0 <= gain < 1` flattens them, `gain < 0` inverts them. The
result does not depend on the sign of n. Every displacement is computed from the original
input, then all points move at once (no drift); a point that cannot be fitted does not move.

The motion |p' - p| is clamped to `maximum_displacement` (default Rf/2, per point), keeping
its direction, where the height-field assumption breaks; pass
`std::numeric_limits<double>::infinity()` to switch the clamp off. The number of clamped
points is reported.

\tparam ConcurrencyTag `Sequential_tag`, `Parallel_tag` or `Parallel_if_available_tag`; both give bitwise identical results.
\tparam PointRange a model of `Range`.

\param points input points; `point_map` must be read-write.
\param k number of neighbors, as in `wavejet_estimate_normals()`.
\param gain the gain alpha_0: finite, |gain| <= 1e100 (a larger gain overflows the motion to
       infinity or NaN; it is rejected rather than producing non-finite points when the clamp is off).
\param np the named parameters of `wavejet_estimate_normals()` (`normal_map` optional here: when
       given it orients the frames, which does not change the result), with the default 0 for
       `tangent_plane_order` (the re-fits of the tangent-plane search are full-order fits: the filter is
       defined over the full-order Wavejet's tangent plane), plus:

\cgalNamedParamsBegin
  \wavejetsOrderParameter{4}
  \wavejetsDegreeFittingParameter{4}
  \cgalParamNBegin{Wavejets::parameters::evaluation_radius}
    \cgalParamDescription{the radius s of a_0(s), in world units; clamped to Rf per point (0: Rf)}
    \cgalParamType{`double` (or `geom_traits::FT`), finite and `>= 0`}
    \cgalParamDefault{Rf of each point}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::maximum_displacement}
    \cgalParamDescription{the largest motion of a point, in world units; larger motions are clamped to it,
                          keeping their direction. `std::numeric_limits<double>::infinity()` switches the clamp off}
    \cgalParamType{`double`, `> 0`}
    \cgalParamDefault{Rf/2 of each point}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::write_normals}
    \cgalParamDescription{also write the Wavejet normals (at the input points, before they move) to `normal_map`,
                          oriented like the input normals}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`}
    \cgalParamExtra{needs a `normal_map` (read-write)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::move_along_input_normals}
    \cgalParamDescription{move each point along its input normal m (normalized; its orientation does not
                          matter) instead of its Wavejet normal n, by the same signed height:
                          p' = p + d m', with d = f_{0,0} - 2 pi (gain - 1) a_0(s) / Rf^2 as above and
                          m' = m / |m| turned to the side of n (m'.n >= 0), so |p' - p| and the clamp are
                          those of the default mode and m = n gives the default result. This is the
                          paper's pipeline for noisy inputs (Figure 12): filter the normals first with
                          `wavejet_enhance_normals()` at gain 0, then move the points along them, for a
                          stable motion direction. A point whose input normal is zero or not finite moves
                          along n}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`}
    \cgalParamExtra{needs a `normal_map`}
  \cgalParamNEnd
\cgalNamedParamsEnd

\return a `Wavejets::Processing_report`, with the number of clamped points.
\throws std::invalid_argument on the conditions of `wavejet_estimate_normals()`, a non-finite gain or |gain| > 1e100,
a `maximum_displacement` that is not positive, or `write_normals` or `move_along_input_normals`
without a normal map.
*/
template <typename ConcurrencyTag, typename PointRange,
          typename NamedParameters = parameters::Default_named_parameters>
Wavejets::Processing_report wavejet_enhance_positions(PointRange& points, unsigned int k, double gain,
                                                      const NamedParameters& np = parameters::default_values())
{
  using namespace Wavejets::internal;
  typedef Point_set_input<PointRange, NamedParameters> Input;
  const Enhance_positions_settings settings = enhance_positions_settings(points, k, np);
  require(std::isfinite(gain) && std::abs(gain) <= 1e100, settings.driver.function,
          "the gain must be finite, |gain| <= 1e100");
  const Input input(points, np, settings.driver.read_input_normals);

  const double two_pi = 2. * 3.14159265358979323846;
  std::vector<Eigen::Vector3d> motion(input.size(), Eigen::Vector3d::Zero()), normals;
  if(settings.write_normals) normals.resize(input.size());
  std::vector<unsigned char> clamped(input.size(), 0);
  const Driver_run run = fit_each_point<ConcurrencyTag>(input, settings.driver,
    [&](const Fitted_point& fp) {
      const double sigma = fp.evaluation_radius_in_radii(settings.evaluation_radius);
      const double a0 = enclosed_area(fp.coefficients, fp.fit.order, 0, sigma, 2).real(); // rescaled units
      double d = fp.world_length(fp.coefficients[0] - two_pi * (gain - 1.) * a0);
      const double limit = settings.maximum_displacement > 0 ? settings.maximum_displacement
                                                             : fp.world_length(settings.maximum_displacement_in_radii);
      if(std::abs(d) > limit) { d = d > 0 ? limit : -limit; clamped[fp.index] = 1; }
      motion[fp.index] = d * motion_direction(fp, input.normals, settings.move_along_input_normals);
      if(settings.write_normals) normals[fp.index] = surface_normal(fp);
    });

  Wavejets::Processing_report report = run.report;
  report.moves_points = true;
  commit(input, run, [&](std::size_t i, auto&& key) {
    put(input.point_map, key, get(input.point_map, key) + Input::to_vector(motion[i]));
    if(settings.write_normals) put(input.normal_map, key, Input::to_vector(normals[i]));
    report.number_of_clamped_points += clamped[i];
  });
  return report;
}

} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_WAVEJET_ENHANCE_POSITIONS_H
