// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJET_ESTIMATE_SCALES_H
#define CGAL_WAVEJET_ESTIMATE_SCALES_H

#include <CGAL/Wavejets/internal/point_set_driver.h>
#include <CGAL/Wavejets/internal/scale_selection.h>

#include <CGAL/disable_warnings.h>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// The ladder of `wavejet_estimate_scales()`: `neighborhood_sizes`, or the default of the order.
template <class NP>
std::vector<unsigned int> read_neighborhood_sizes(const NP& np, std::size_t order, const char* fn)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const std::vector<unsigned int> ladder = choose_parameter(
    get_parameter(np, Wavejets::internal_np::neighborhood_sizes), default_neighborhood_sizes(order));
  require(!ladder.empty(), fn, "neighborhood_sizes is empty");
  require(ladder.front() >= 2, fn, "neighborhood_sizes: every size must be >= 2");
  for(std::size_t j = 1; j < ladder.size(); ++j)
    require(ladder[j] > ladder[j - 1], fn, "neighborhood_sizes must increase");
  return ladder;
}

} // namespace internal
} // namespace Wavejets

/*!
\ingroup PkgWavejetsRef

Chooses, for every point, the number of neighbors of its Wavejet among a ladder of sizes, and writes
it to `neighborhood_size_map`: pass that map to any of the four functions (with the same `order`)
to fit each point at its own scale. Each point is fitted to the nested prefixes of its nearest
neighbors (one k-nearest query at the largest size); the size kept is the one whose estimated
squared normal error, a variance term (the noise, estimated as the smallest residual variance over
the ladder, over the neighborhood's size and radius) plus a bias term (the residual variance that the
noise does not explain, over the radius squared), is the smallest (user manual, "Choosing the scale
per point"). In a noisy part the larger sizes win, near fine details the smaller ones.

\tparam ConcurrencyTag `Sequential_tag`, `Parallel_tag` or `Parallel_if_available_tag`; both give bitwise identical results.
\tparam PointRange a model of `Range`.

\param points input points; the range itself is not modified.
\param np named parameters among those below; `neighborhood_size_map` is required.

\cgalNamedParamsBegin
  \cgalParamNBegin{point_map}
    \cgalParamDescription{a property map associating points to the elements of `points`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `geom_traits::Point_3`}
    \cgalParamDefault{`CGAL::Identity_property_map<geom_traits::Point_3>`}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::neighborhood_size_map}
    \cgalParamDescription{receives each fitted point's chosen number of neighbors (query excluded)}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is an integer type}
    \cgalParamDefault{none: required}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::neighborhood_sizes}
    \cgalParamDescription{the ladder: increasing numbers of neighbors, each `>= 2`}
    \cgalParamType{`std::vector<unsigned int>`}
    \cgalParamDefault{`Wavejets::default_neighborhood_sizes(order)`: 10, 16, 25, 40, 63, 101, 160 at order 2}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::scale_descriptor_map}
    \cgalParamDescription{receives, per fitted point, one value per size of the ladder: the magnitude of the
                          second-order part of the Wavejet at that size, world units (1/length); 0 where that
                          size could not be fitted. How the shape around a point changes across scales}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `std::vector<double>`}
    \cgalParamDefault{unused}
  \cgalParamNEnd
  \cgalParamNBegin{Wavejets::parameters::fitted_map}
    \cgalParamDescription{receives, for every point, whether a size was chosen for it}
    \cgalParamType{a model of `WritablePropertyMap` whose key type is the value type of the iterator of
                   `PointRange` and whose value type is `bool`}
    \cgalParamDefault{unused}
  \cgalParamNEnd
  \cgalParamNBegin{callback}
    \cgalParamDescription{called with the progress in [0,1]; returning `false` stops the computation, and then
                          nothing at all is written}
    \cgalParamType{an instance of `std::function<bool(double)>`}
    \cgalParamDefault{unused}
  \cgalParamNEnd
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `Kernel`}
    \cgalParamDefault{a \cgal kernel deduced from the point type, using `CGAL::Kernel_traits`}
  \cgalParamNEnd
  \wavejetsOrderParameter{2}
  \cgalParamNBegin{Wavejets::parameters::neighbors_per_coefficient, correction_iterations, tangent_plane_order, robust_iterations, minimum_order, compact_weights}
    \cgalParamDescription{the fit settings, as in `wavejet_estimate_normals()` (the fits of the ladder are its fits)}
    \cgalParamType{see `wavejet_estimate_normals()`}
    \cgalParamDefault{those of `wavejet_estimate_normals()`}
  \cgalParamNEnd
\cgalNamedParamsEnd

\return a `Wavejets::Processing_report`: a point is fitted when at least one size of the ladder could be fitted
        (its map entries are untouched otherwise); points with non-finite coordinates are not fitted and
        are no one's neighbors.
\throws std::invalid_argument if `neighborhood_sizes` is empty, not increasing or has a size below 2, if
        `order < 1`, or if `neighbors_per_coefficient < 1`.
*/
template <typename ConcurrencyTag, typename PointRange, typename NamedParameters>
Wavejets::Processing_report wavejet_estimate_scales(PointRange& points, const NamedParameters& np)
{
  using namespace Wavejets::internal;
  typedef Point_set_input<PointRange, NamedParameters> Input;
  static_assert(!CGAL::parameters::is_default_parameter<NamedParameters,
                                                        Wavejets::internal_np::neighborhood_size_map_t>::value,
                "Error: wavejet_estimate_scales() needs a neighborhood_size_map");
  const Wavejets::Function_defaults defaults =
    Wavejets::function_defaults(Wavejets::Point_set_function::ESTIMATE_NORMALS);
  const char* fn = "wavejet_estimate_scales";
  const std::size_t order = read_order(np, defaults.order, fn);
  const Wavejets::Fitting_options options = read_fitting_options(np, defaults.fitting, fn);
  const std::vector<unsigned int> ladder = read_neighborhood_sizes(np, order, fn);
  const std::function<bool(double)> callback = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, CGAL::internal_np::callback), std::function<bool(double)>());
  const Input input(points, np, false);
  const std::size_t N = input.size();
  const std::size_t J = ladder.size();

  std::vector<unsigned char> fitted(N, 0), status(N, (unsigned char)(Wavejets::Fit_status::TOO_FEW_POINTS));
  std::vector<unsigned int> chosen(N, 0);
  std::vector<double> descriptors(N * J, 0.);
  Wavejets::Processing_report report;
  report.number_of_points = N;
  report.number_of_tiles = N > 0 ? 1 : 0;
  if(N > 0)
  {
    const Neighbor_query query(input.points, input.finite, ConcurrencyTag());
    const std::vector<std::size_t> visit = query.processing_order();
    std::vector<std::size_t> chunks;
    const std::size_t chunk_size = 256;
    for(std::size_t b = 0; b < N; b += chunk_size) chunks.push_back(b);
    Pass_progress progress(callback, N);
    std::atomic<bool> interrupted(false);
    CGAL::for_each<ConcurrencyTag>(chunks, [&](const std::size_t begin) -> bool {
      Scale_chooser chooser;
      std::vector<std::size_t> neighbors;
      Neighbor_query::Scratch scratch;
      std::vector<Eigen::Vector3d> offsets;
      const std::size_t end = (std::min)(begin + chunk_size, N);
      for(std::size_t position = begin; position < end; ++position)
      {
        if(interrupted || progress.interrupted()) { interrupted = true; return false; }
        const std::size_t i = visit[position];
        if(!input.finite[i]) { status[i] = (unsigned char)(Wavejets::Fit_status::NON_FINITE_INPUT); continue; }
        query.neighbors(i, ladder.back(), 0., neighbors, scratch);
        const Eigen::Vector3d p = input.position(i);
        offsets.assign(1, Eigen::Vector3d::Zero());
        for(std::size_t j : neighbors) offsets.push_back(input.position(j) - p);
        const Scale_choice choice = chooser.choose(offsets.data(), offsets.size(), ladder, order, options, nullptr,
                                                   descriptors.data() + i * J);
        if(!choice.found) continue;
        chosen[i] = ladder[choice.rung];
        fitted[i] = 1;
        status[i] = (unsigned char)(Wavejets::Fit_status::SUCCESS);
      }
      progress.advance(end - begin);
      return true;
    });
    if(!interrupted) progress.finish();
    report.interrupted = interrupted || progress.interrupted();
  }
  if(report.interrupted) return report;

  Driver_run run;
  run.report = report;
  run.fitted = fitted;
  count_points(run, status, std::vector<unsigned char>(N, 0));
  const auto descriptor_map =
    CGAL::parameters::get_parameter(np, Wavejets::internal_np::scale_descriptor_map);
  const auto size_map = CGAL::parameters::get_parameter(np, Wavejets::internal_np::neighborhood_size_map);
  commit(input, run, [&](std::size_t i, auto&& key) {
    put(size_map, key, chosen[i]);
    put_if_given(descriptor_map, key, std::vector<double>(descriptors.begin() + i * J, descriptors.begin() + (i + 1) * J));
  });
  return run.report;
}

} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_WAVEJET_ESTIMATE_SCALES_H
