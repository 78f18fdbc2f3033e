// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJET_ESTIMATE_NORMALS_H
#define CGAL_WAVEJET_ESTIMATE_NORMALS_H

#include <CGAL/Wavejets/internal/point_set_driver.h>

#include <CGAL/disable_warnings.h>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The settings of `wavejet_estimate_normals()`: the driver's, with the function's own rules.
template <class PointRange, class NP>
Driver_settings estimate_normals_settings(PointRange& points, unsigned int k, const NP& np)
{
  Driver_settings s = read_settings(points, k, np, function_defaults(Point_set_function::ESTIMATE_NORMALS));
  require_normal_map(points, np, s.function);
  // The normal estimation reads no curvature: no full-order fit in the initial frame (it only serves
  // INITIAL_FRAME curvatures).
  s.fitting.curvature_frame = Curvature_frame::TANGENT_FRAME;
  return s;
}

} // namespace internal
} // namespace Wavejets

/*!
\ingroup PkgWavejetsRef

Estimates the normal of every point as the normal of its Wavejet at the point: the drop-in
counterpart of `jet_estimate_normals()` (same signature, same neighborhoods), with the
Wavejet's tangent-plane correction. Normals are unoriented (their sign comes from PCA), unless
`orient_with_input_normals(true)`: then each output normal points to the same side as the
normal read from `normal_map`. The parameters that read the input normals for another purpose
(`seed_with_input_normals`, `restrict_to_consistent_normals`) orient the output the same way: input
normals that are read always orient the frames.

\tparam ConcurrencyTag `Sequential_tag`, `Parallel_tag` or `Parallel_if_available_tag`; both give bitwise identical results.
\tparam PointRange a model of `Range` (e.g. `std::vector`, `Point_set_3`).

\param points input points; the range itself is not modified.
\param k number of neighbors (query point excluded); with `neighbor_radius`, the maximum number
         of neighbors kept within the radius (nearest first; 0: no limit).
\param np optional named parameters among those below; the package's own (namespace
       `CGAL::Wavejets::parameters`) must come before CGAL's in a chain.

\cgalNamedParamsBegin
  \cgalParamNBegin{point_map}
    \cgalParamDescription{a property map associating points to the elements of `points`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `geom_traits::Point_3`}
    \cgalParamDefault{`CGAL::Identity_property_map<geom_traits::Point_3>` (`ps.point_map()` for a `Point_set_3`)}
  \cgalParamNEnd
  \cgalParamNBegin{normal_map}
    \cgalParamDescription{a property map where the normals are written (and read, with the parameters
                          that use the input normals)}
    \cgalParamType{a model of `ReadWritePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `geom_traits::Vector_3`}
    \cgalParamDefault{none (`ps.normal_map()` for a `Point_set_3`)}
    \cgalParamExtra{required: a static assertion fails without it; a `Point_set_3` must have a normal map}
  \cgalParamNEnd
  \cgalParamNBegin{neighbor_radius}
    \cgalParamDescription{radius Rf of the neighborhoods; 0 uses the `k` nearest neighbors and Rf = the
                          distance to the farthest one. There is no fallback: a point with too few
                          neighbors in the radius is not fitted (and is counted in the report)}
    \cgalParamType{`geom_traits::FT` (converted to `double`), finite and `>= 0`}
    \cgalParamDefault{0}
  \cgalParamNEnd
  \cgalParamNBegin{callback}
    \cgalParamDescription{a mechanism to get feedback on the advancement of the algorithm while it is
                          running and to interrupt it if needed: called with the progress in [0,1];
                          returning `false` stops the computation, and then nothing at all is written}
    \cgalParamType{an instance of `std::function<bool(double)>`}
    \cgalParamDefault{unused}
    \cgalParamExtra{called after every 256 points and once more with 1 at the end of each pass over
                    the points, never twice at the same time; under `Parallel_tag`, from the
                    threads that process the points}
  \cgalParamNEnd
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `Kernel`}
    \cgalParamDefault{a \cgal kernel deduced from the point type, using `CGAL::Kernel_traits`}
  \cgalParamNEnd
  \wavejetsOrderParameter{2}
  \wavejetsDegreeFittingParameter{2}
  \wavejetsPerPointScaleParameters
  \cgalParamNBegin{Wavejets::parameters::neighbors_per_coefficient}
    \cgalParamDescription{adaptive order: K is lowered until the neighborhood (query included) has at
                          least this many points per unknown, (K+1)(K+2)/2 unknowns (and the system has full rank)}
    \cgalParamType{`double`, `>= 1`}
    \cgalParamDefault{1.1}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::minimum_order}
    \cgalParamDescription{lowest acceptable order; a point that cannot be fitted at this order is not fitted}
    \cgalParamType{`std::size_t`}
    \cgalParamDefault{2 (clamped to `order`)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::correction_iterations}
    \cgalParamDescription{maximum number of re-fits in the corrected tangent plane (0: off); the frame with
                          the smallest residual tilt |f_{1,1}| is kept}
    \cgalParamType{`std::size_t`}
    \cgalParamDefault{2}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::tangent_plane_order}
    \cgalParamDescription{order of the fits that find the tangent plane (the first fit and the re-fits of
                          the correction); then one fit of order `order` is done in that plane, and the
                          output normal is that of this full-order Wavejet at the point (its residual tilt
                          included). A value >= `order`, or 0, makes every re-fit a full-order fit (the
                          default of the other functions, whose filters are defined over the tangent plane
                          of the full-order Wavejet): about three times slower at `order(6)`}
    \cgalParamType{`std::size_t`}
    \cgalParamDefault{2}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::robust_iterations}
    \cgalParamDescription{Tukey IRLS passes per fit, for noisy data with outliers (0: plain least squares)}
    \cgalParamType{`std::size_t`}
    \cgalParamDefault{0}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::orient_with_input_normals}
    \cgalParamDescription{orient each output normal like the input normal read from `normal_map`}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false` (the output normals are unoriented)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::seed_with_input_normals}
    \cgalParamDescription{do the first fit in the plane orthogonal to the input normal instead of the PCA plane
                          (the input normal also orients the frame)}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::restrict_to_consistent_normals}
    \cgalParamDescription{drop the neighbors whose input normal makes more than 90 degrees with the query's,
                          so that a neighborhood does not mix two sheets of the surface (needs oriented input normals)}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::use_neighbor_normals}
    \cgalParamDescription{Hermite fit: fit every Wavejet to the neighbors' heights and to the slopes their normals
                          give (two equations per neighbor normal; see `Wavejets::Fitting_options::neighbor_normal_weight`).
                          The normals are those read from `normal_map` when the function reads them (the
                          functions that take input normals; here, with `orient_with_input_normals`,
                          `seed_with_input_normals` or `restrict_to_consistent_normals`); otherwise the function
                          first estimates them itself, with a pass of this function's plain fit (same
                          neighborhoods, order and weights, order-2 tangent-plane search with 2 re-fits):
                          one call, two passes over the points (the `callback` sees both). Normals may be
                          unoriented (their sign does not change the equations) and noisy. On noisy scans
                          this makes curvature several times more precise than the plain fit (see the
                          accuracy tables against Ponca's APSS in benchmark/Wavejets/accuracy_ponca.md)}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::neighbor_normal_weight}
    \cgalParamDescription{weight w of the slope equations of the Hermite fit against the height equations: with
                          coordinates divided by the neighborhood radius Rf, the slope rows are multiplied by w (and by
                          cos^2 of the normal's angle to the fitting plane's normal, its error's growth), so
                          that a slope error of 1 (radian) weighs as much as a height error of w Rf. On noisy
                          data 10 is better than 1 (2.5% on average on the accuracy tables against Ponca's APSS)}
    \cgalParamType{`double`, finite and > 0}
    \cgalParamDefault{1}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::compact_weights}
    \cgalParamDescription{weight the equations of each neighbor q by the smooth compact kernel
                          (1 - |q - p|^2 / Rf^2)^2 instead of 1 (also in the Hermite fit)}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::fitted_map}
    \cgalParamDescription{a property map receiving, for every point, whether a Wavejet was fitted there
                          (not written if the `callback` interrupts the computation)}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `bool`}
    \cgalParamDefault{unused}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::tile_size}
    \cgalParamDescription{process the points in spatial tiles of at most this many points, each fitted among the
                          points of a halo around it, instead of all at once: the search structure and the
                          working memory are those of one tile. The results are those of the run without tiles,
                          bit for bit: a point whose neighborhood (or, in a Hermite fit on estimated normals, one
                          of its neighbors' neighborhoods) reaches past its tile's halo is fitted again with a
                          larger halo, and counted in the report (\ref Wavejets_tiles). 0: no tiles}
    \cgalParamType{an integer, `>= 0`}
    \cgalParamDefault{0}
    \cgalParamExtra{under `Parallel_tag` the tiles are processed side by side, one per thread}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::tile}
    \cgalParamDescription{the range is one tile of a larger point set (`Wavejets::Tile`: the points of that set in
                          `extent`, in their order in it): only the points of `owned_map` are fitted, and a result is
                          written only where it is that of the whole point set; the others are marked in `outside_map`
                          (\ref Wavejets_tiles)}
    \cgalParamType{`Wavejets::Tile`}
    \cgalParamDefault{unused}
    \cgalParamExtra{not with `tile_size`}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::owned_map}
    \cgalParamDescription{with `tile`: the points to fit (the others are neighbors only)}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `bool`}
    \cgalParamDefault{every point}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::outside_map}
    \cgalParamDescription{with `tile`: receives, for every point, whether it is an owned point whose neighborhood
                          reaches past the tile's extent (not fitted, not written: run it again in a larger tile)}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `bool`}
    \cgalParamDefault{unused (such points are only counted in the report)}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::tile_halo}
    \cgalParamDescription{the width of the first halo of every tile, world units (0: from each tile's density, or
                          the `neighbor_radius`). Too small a halo costs time, never exactness}
    \cgalParamType{`double`, finite and `>= 0`}
    \cgalParamDefault{0}
  \cgalParamNEnd
\cgalNamedParamsEnd

\return a `Wavejets::Processing_report`: points that could not be fitted keep their normal and are counted.
\throws std::invalid_argument if `k < 2` and no positive `neighbor_radius` (for a point whose
        `neighborhood_size_map` and `neighbor_radius_map` values are 0), if a `neighborhood_size_map` or `order_map`
        value is negative, if `neighbor_radius` or a `neighbor_radius_map` value is negative or not finite, if `order < 1` (or `degree_fitting < 1`), if `order` and `degree_fitting` are both given and
        differ, if `degree_monge` is given (it has no meaning here), if `neighbors_per_coefficient < 1`, or if a
        `Point_set_3` has no normal map.
*/
template <typename ConcurrencyTag, typename PointRange,
          typename NamedParameters = parameters::Default_named_parameters>
Wavejets::Processing_report wavejet_estimate_normals(PointRange& points, unsigned int k,
                                                     const NamedParameters& np = parameters::default_values())
{
  using namespace Wavejets::internal;
  typedef Point_set_input<PointRange, NamedParameters> Input;
  static_assert(may_have_normal_map<PointRange, NamedParameters>(), "Error: no normal map");
  // Only the normal is written, and it is the full-order surface's: by default the tangent plane is
  // found with order-2 fits (one full-order solve per point instead of three; see function_defaults()).
  const Driver_settings settings = estimate_normals_settings(points, k, np);
  const Input input(points, np, settings.read_input_normals);

  std::vector<Eigen::Vector3d> normals(input.size());
  const Driver_run run = fit_each_point<ConcurrencyTag>(input, settings,
    [&](const Fitted_point& fp) { normals[fp.index] = surface_normal(fp); });

  commit(input, run, [&](std::size_t i, auto&& key) {
    put(input.normal_map, key, Input::to_vector(normals[i]));
  });
  return run.report;
}

} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_WAVEJET_ESTIMATE_NORMALS_H
