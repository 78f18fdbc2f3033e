// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers
#ifndef CGAL_WAVEJET_ESTIMATE_CURVATURES_H
#define CGAL_WAVEJET_ESTIMATE_CURVATURES_H

#include <CGAL/Wavejets/internal/point_set_driver.h>
#include <CGAL/Wavejets/internal/differential_quantities.h>

#include <CGAL/disable_warnings.h>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The settings of `wavejet_estimate_curvatures()`: the driver's, with the function's own rules
/// (at least one output map; `degree_monge(2)` accepted).
template <class PointRange, class NP>
Driver_settings estimate_curvatures_settings(PointRange& points, unsigned int k, const NP& np)
{
  using CGAL::parameters::is_default_parameter;
  namespace wnp = Wavejets::internal_np;
  const Function_defaults d = function_defaults(Point_set_function::ESTIMATE_CURVATURES);
  const bool any_output = !is_default_parameter<NP, wnp::mean_curvature_map_t>::value ||
                          !is_default_parameter<NP, wnp::gaussian_curvature_map_t>::value ||
                          !is_default_parameter<NP, wnp::maximal_principal_curvature_map_t>::value ||
                          !is_default_parameter<NP, wnp::minimal_principal_curvature_map_t>::value ||
                          !is_default_parameter<NP, wnp::maximal_principal_direction_map_t>::value ||
                          !is_default_parameter<NP, wnp::minimal_principal_direction_map_t>::value;
  require(any_output, d.name, "no output map given (e.g. Wavejets::parameters::mean_curvature_map(m))");
  Driver_settings s = read_settings(points, k, np, d, true);
  // Curvatures read from the first fit (the default) do not use the corrected frame: no re-fits.
  if(s.fitting.curvature_frame == Curvature_frame::INITIAL_FRAME)
    s.fitting.correction_iterations = 0;
  return s;
}

} // namespace internal
} // namespace Wavejets

/*!
\ingroup PkgWavejetsRef

Estimates, at every point, the curvature of its Wavejet: signed mean curvature H, Gaussian
curvature K_G, principal curvatures k1 >= k2 and principal directions, each written to a
property map the caller names (only the requested ones are stored). CGAL has no such function
for point sets; at equal order and neighborhood, the values equal those of
`Monge_via_jet_fitting` (with the default `curvature_frame`, the curvature comes from the first
fit, in the PCA frame, which is the same least-squares problem as CGAL's jets).

Signs are relative to the normal: a surface bending toward the normal has H > 0 (a sphere with
outward normals has H = -1/R). When a normal map is given, the frames are oriented by its normals;
otherwise the PCA normal's sign is arbitrary, so the signs of H, k1, k2 are too (K_G is not affected).
The principal directions are lines: the sign of each unit vector is arbitrary (it follows the PCA frame).

\tparam ConcurrencyTag `Sequential_tag`, `Parallel_tag` or `Parallel_if_available_tag`; both give bitwise identical results.
\tparam PointRange a model of `Range`.

\param points input points (not modified).
\param k number of neighbors, as in `wavejet_estimate_normals()`.
\param np named parameters: all those of `wavejet_estimate_normals()` except `orient_with_input_normals` (a
       given normal map always orients), with the default 0 for `tangent_plane_order` (and with the default
       `curvature_frame` no tangent-plane search is done at all), plus the output maps below (at least one
       is required) and:

\cgalNamedParamsBegin
  \cgalParamNBegin{degree_monge}
    \cgalParamDescription{\cgal's degree of the Monge form (`Monge_via_jet_fitting`): only 2, the degree of the
                          curvatures computed here, is accepted}
    \cgalParamType{an integer, `== 2`}
    \cgalParamDefault{2}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::mean_curvature_map}
    \cgalParamDescription{a property map receiving the mean curvature H}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of `PointRange` and whose value type is `geom_traits::FT`}
    \cgalParamDefault{unused (at least one of the six maps is required)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::gaussian_curvature_map}
    \cgalParamDescription{a property map receiving the Gaussian curvature K_G}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of `PointRange` and whose value type is `geom_traits::FT`}
    \cgalParamDefault{unused (at least one of the six maps is required)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::maximal_principal_curvature_map}
    \cgalParamDescription{a property map receiving the maximal principal curvature k1}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of `PointRange` and whose value type is `geom_traits::FT`}
    \cgalParamDefault{unused (at least one of the six maps is required)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::minimal_principal_curvature_map}
    \cgalParamDescription{a property map receiving the minimal principal curvature k2 (k2 <= k1)}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of `PointRange` and whose value type is `geom_traits::FT`}
    \cgalParamDefault{unused (at least one of the six maps is required)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::maximal_principal_direction_map}
    \cgalParamDescription{a property map receiving the unit tangent direction of k1}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of `PointRange` and whose value type is `geom_traits::Vector_3`}
    \cgalParamDefault{unused (at least one of the six maps is required)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::minimal_principal_direction_map}
    \cgalParamDescription{a property map receiving the unit tangent direction of k2}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of `PointRange` and whose value type is `geom_traits::Vector_3`}
    \cgalParamDefault{unused (at least one of the six maps is required)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::curvature_frame}
    \cgalParamDescription{the fit the curvatures are read from: `Wavejets::Curvature_frame::INITIAL_FRAME` (the
                          first fit, in the PCA frame: the same least-squares problem as `Monge_via_jet_fitting`)
                          or `Wavejets::Curvature_frame::TANGENT_FRAME` (the fit in the corrected tangent frame)}
    \cgalParamType{`CGAL::Wavejets::Curvature_frame`}
    \cgalParamDefault{`Wavejets::Curvature_frame::INITIAL_FRAME`}
    \cgalParamExtra{with `INITIAL_FRAME` nothing written depends on the corrected frame, so the
                    tangent-plane re-fits are not done (`correction_iterations` is ignored)}
  \cgalParamNEnd
\cgalNamedParamsEnd

\return a `Wavejets::Processing_report`; unfitted points keep the values their maps had.
\throws std::invalid_argument on the conditions of `wavejet_estimate_normals()`, if no output map is given, or if
        `degree_monge` is not 2.
*/
template <typename ConcurrencyTag, typename PointRange,
          typename NamedParameters = parameters::Default_named_parameters>
Wavejets::Processing_report wavejet_estimate_curvatures(PointRange& points, unsigned int k,
                                                        const NamedParameters& np = parameters::default_values())
{
  using namespace Wavejets::internal;
  using parameters::get_parameter;
  namespace wnp = Wavejets::internal_np;
  typedef Point_set_input<PointRange, NamedParameters> Input;
  typedef typename Input::Geom_traits::FT FT;
  const Driver_settings settings = estimate_curvatures_settings(points, k, np);
  const Input input(points, np, settings.read_input_normals);

  std::vector<Curvature_info> curvatures(input.size());
  const Driver_run run = fit_each_point<ConcurrencyTag>(input, settings,
    [&](const Fitted_point& fp) {
      const Frame& frame = fp.fit.curvature_frame;
      curvatures[fp.index] = graph_curvature(fp.fit.curvature_derivatives, frame.u, frame.v, frame.n);
    });

  // The output maps are the function's own named parameters: read where they are written.
  commit(input, run, [&](std::size_t i, auto&& key) {
    const Curvature_info& c = curvatures[i];
    put_if_given(get_parameter(np, wnp::mean_curvature_map), key, FT(c.mean));
    put_if_given(get_parameter(np, wnp::gaussian_curvature_map), key, FT(c.gaussian));
    put_if_given(get_parameter(np, wnp::maximal_principal_curvature_map), key, FT(c.k1));
    put_if_given(get_parameter(np, wnp::minimal_principal_curvature_map), key, FT(c.k2));
    put_if_given(get_parameter(np, wnp::maximal_principal_direction_map), key, Input::to_vector(c.d1));
    put_if_given(get_parameter(np, wnp::minimal_principal_direction_map), key, Input::to_vector(c.d2));
  });
  return run.report;
}

} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_WAVEJET_ESTIMATE_CURVATURES_H
