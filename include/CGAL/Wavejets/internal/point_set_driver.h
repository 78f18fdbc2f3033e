// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_POINT_SET_DRIVER_H
#define CGAL_WAVEJETS_INTERNAL_POINT_SET_DRIVER_H

// The one per-point driver behind every wavejet_* function:
//   named parameters -> copy of the input (double) -> kd-tree -> CGAL::for_each over chunks of
//   points (one Fitter and scratch per chunk, no allocation per point once warm) -> a small
//   per-function kernel writes into a buffer slot per point -> the function commits the buffers
//   after all points are done (never in place), or nothing at all if interrupted.
// Every point's result depends only on the unmodified input, so Sequential_tag and Parallel_tag
// give bitwise identical results. With the named parameter `tile_size`, the same passes run tile by
// tile over the points of each tile and a halo of neighbors (tiled_driver.h), with the same results.

#include <CGAL/Wavejets/Fitting_options.h>
#include <CGAL/Wavejets/Function_defaults.h>
#include <CGAL/Wavejets/Processing_report.h>
#include <CGAL/Wavejets/Tile.h>
#include <CGAL/Wavejets/parameters.h>
#include <CGAL/Wavejets/internal/cgal_compatibility.h>
#include <CGAL/Wavejets/internal/fitting_core.h>
#include <CGAL/Wavejets/internal/neighbor_query.h>
#include <CGAL/Wavejets/internal/progress.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/for_each.h>
#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <Eigen/Core>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// Precondition that stays checked in release builds: bad input gets a clear error, never a crash.
inline void require(bool condition, const char* function, const char* message)
{
  if(!condition)
    throw std::invalid_argument(std::string(function) + ": " + message);
}

/// What every point-set function reads from its named parameters, except the property maps (which
/// `Point_set_input` holds): read and checked once per call by `read_settings()`, then passed to the
/// per-point loop. A function's own parameters (its filter's, its output maps) are read in its header.
struct Driver_settings
{
  const char* function = "";               // name, for the error messages
  unsigned int k = 0;
  double neighbor_radius = 0.;
  std::size_t order = 2;
  Fitting_options fitting;                 // its neighborhood_radius is neighbor_radius
  bool read_input_normals = false;         // the range has normals and a setting uses them: they are copied,
                                           // and they orient (or seed) the frames
  bool restrict_to_consistent_normals = false;
  bool use_neighbor_normals = false;       // Hermite fit (normals: the input's, or estimated first)
  std::function<bool(double)> callback;    // empty if not given
  std::size_t tile_size = 0;               // tiled run: at most this many points per tile (0: in core)
  double tile_halo = 0.;                   // first halo of each tile, world units (0: estimated)
  bool is_tile = false;                    // the range is one tile of a larger point set: `tile`
  Tile tile;
  std::vector<unsigned int> k_of_point;    // `neighborhood_size_map`, by index in the range (empty: k everywhere);
                                           // then k is the largest of them (the tiles' halos)
  std::vector<std::size_t> order_of_point; // `order_map`, idem (empty: order everywhere)
  std::vector<double> radius_of_point;     // `neighbor_radius_map`, idem (empty: neighbor_radius everywhere)
  double largest_radius = 0.;              // of neighbor_radius and the radius map's (the tiles' halos)

  /// The number of neighbors, the order and the neighborhood radius (0: the k nearest) of the point
  /// of index `i` in the range.
  unsigned int k_at(std::size_t i) const { return k_of_point.empty() ? k : k_of_point[i]; }
  std::size_t order_at(std::size_t i) const { return order_of_point.empty() ? order : order_of_point[i]; }
  double radius_at(std::size_t i) const { return radius_of_point.empty() ? neighbor_radius : radius_of_point[i]; }
};

/// The requested order K: `Wavejets::parameters::order`, or \cgal's `degree_fitting` (the name the jet
/// functions use, so that a call to `jet_estimate_normals()` keeps its meaning when the function is
/// swapped). Both may be given only with the same value.
template <class NP>
std::size_t read_order(const NP& np, std::size_t default_order, const char* fn)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  constexpr bool has_order = !is_default_parameter<NP, Wavejets::internal_np::order_t>::value;
  constexpr bool has_degree = !is_default_parameter<NP, CGAL::internal_np::degree_fitting_t>::value;
  // Read as signed integers, so that a negative value is reported instead of wrapping around.
  const long long order = static_cast<long long>(choose_parameter(get_parameter(np, Wavejets::internal_np::order), 0));
  const long long degree = static_cast<long long>(choose_parameter(get_parameter(np, CGAL::internal_np::degree_fitting), 0));
  if(has_order && has_degree)
    require(order == degree, fn, ("order(" + std::to_string(order) + ") and degree_fitting(" + std::to_string(degree) +
                                  ") differ: give one of them").c_str());
  if(!has_order && !has_degree) return default_order;
  require((has_order ? order : degree) >= 1, fn, has_order ? "order must be >= 1" : "degree_fitting must be >= 1");
  return std::size_t(has_order ? order : degree);
}

/// \cgal's `degree_monge` (of `jet_smooth_point_set()` and `Monge_via_jet_fitting`): the package computes
/// second-order differential quantities only. Where curvatures are computed, `degree_monge(2)` is
/// what is done and is accepted; any other use is rejected rather than silently ignored.
template <class NP>
void check_degree_monge(const NP& np, const char* fn, bool computes_curvatures)
{
  using CGAL::parameters::is_default_parameter;
  if constexpr(!is_default_parameter<NP, CGAL::internal_np::degree_monge_t>::value)
  {
    const long long degree = static_cast<long long>(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::degree_monge));
    require(computes_curvatures, fn, "degree_monge has no meaning here (it is the degree of the Monge form, "
                                     "used by wavejet_estimate_curvatures only); the fitting order is `order`");
    require(degree == 2, fn, "degree_monge must be 2: curvatures are second-order quantities (higher Monge "
                             "coefficients are not computed)");
  }
}

/// The fit settings from the named parameters, with the defaults `d` of the function.
template <class NP>
Fitting_options read_fitting_options(const NP& np, const Fitting_options& d, const char* fn)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  namespace wnp = Wavejets::internal_np;
  Fitting_options o = d;
  o.neighbors_per_coefficient = choose_parameter(get_parameter(np, wnp::neighbors_per_coefficient), d.neighbors_per_coefficient);
  require(o.neighbors_per_coefficient >= 1., fn, "neighbors_per_coefficient must be >= 1");
  o.minimum_order = choose_parameter(get_parameter(np, wnp::minimum_order), d.minimum_order);
  o.correction_iterations = choose_parameter(get_parameter(np, wnp::correction_iterations), d.correction_iterations);
  o.tangent_plane_order = choose_parameter(get_parameter(np, wnp::tangent_plane_order), d.tangent_plane_order);
  o.robust_iterations = choose_parameter(get_parameter(np, wnp::robust_iterations), d.robust_iterations);
  o.curvature_frame = choose_parameter(get_parameter(np, wnp::curvature_frame), d.curvature_frame);
  o.normal_use = choose_parameter(get_parameter(np, wnp::seed_with_input_normals), false) ? Normal_use::SEED_FRAME
                                                                                            : Normal_use::ORIENT;
  o.compute_condition_number = false; // no function reports it
  o.neighbor_normal_weight = to_double(choose_parameter(get_parameter(np, wnp::neighbor_normal_weight), d.neighbor_normal_weight));
  require(std::isfinite(o.neighbor_normal_weight) && o.neighbor_normal_weight > 0, fn,
          "neighbor_normal_weight must be finite and > 0");
  o.compact_weights = choose_parameter(get_parameter(np, wnp::compact_weights), d.compact_weights);
  return o;
}

/// Reads and checks the named parameters that every point-set function shares, with the function's
/// defaults `d` (from `function_defaults()`). `computes_curvatures`: the function accepts
/// `degree_monge(2)`. The function's own parameters, checks and derived settings are in its header.
template <class PointRange, class NP>
Driver_settings read_settings(PointRange& points, unsigned int k, const NP& np, const Function_defaults& d,
                              bool computes_curvatures = false)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  namespace wnp = Wavejets::internal_np;
  const char* fn = d.name;
  Driver_settings s;
  s.function = fn;
  s.k = k;
  s.neighbor_radius = to_double(choose_parameter(get_parameter(np, CGAL::internal_np::neighbor_radius), 0.));
  s.order = read_order(np, d.order, fn);
  check_degree_monge(np, fn, computes_curvatures);
  require(std::isfinite(s.neighbor_radius) && s.neighbor_radius >= 0, fn, "neighbor_radius must be finite and >= 0");
  read_per_point_scales(points, np, s);
  require(s.k >= 2 || s.neighbor_radius > 0 || !s.radius_of_point.empty(), fn, "needs k >= 2 or neighbor_radius > 0");
  s.fitting = read_fitting_options(np, d.fitting, fn);
  s.fitting.neighborhood_radius = s.neighbor_radius;
  s.restrict_to_consistent_normals = choose_parameter(get_parameter(np, wnp::restrict_to_consistent_normals), false);
  s.use_neighbor_normals = choose_parameter(get_parameter(np, wnp::use_neighbor_normals), false);
  s.callback = choose_parameter(get_parameter(np, CGAL::internal_np::callback), std::function<bool(double)>());
  const long long tile_size = static_cast<long long>(choose_parameter(get_parameter(np, wnp::tile_size), 0));
  require(tile_size >= 0, fn, "tile_size must be >= 0");
  s.tile_size = std::size_t(tile_size);
  s.tile_halo = to_double(choose_parameter(get_parameter(np, wnp::tile_halo), 0.));
  require(std::isfinite(s.tile_halo) && s.tile_halo >= 0, fn, "tile_halo must be finite and >= 0");
  if constexpr(!CGAL::parameters::is_default_parameter<NP, wnp::tile_t>::value)
  {
    s.is_tile = true;
    s.tile = get_parameter(np, wnp::tile);
    require(s.tile_size == 0, fn, "tile (one tile of a larger point set) and tile_size (cut this range into tiles) "
                                  "exclude each other");
  }
  // The input normals are read when a setting uses them, and then they also orient the frames (the
  // functions whose outputs have a side use them whenever the range has them).
  const bool asked = choose_parameter(get_parameter(np, wnp::orient_with_input_normals), false) ||
                     s.restrict_to_consistent_normals || s.fitting.normal_use == Normal_use::SEED_FRAME;
  s.read_input_normals = has_normal_map(points, np) && (d.orients_with_input_normals || asked);
  return s;
}

/// The per-point neighborhood radii, sizes and orders (`neighbor_radius_map`, `neighborhood_size_map`,
/// `order_map`), read in range order into `s`. A value of 0 stands for the function's
/// `neighbor_radius` (or `k`, or order); the neighborhood sizes are numbers of neighbors (with a
/// radius, the most kept within it).
template <class PointRange, class NP>
void read_per_point_scales(PointRange& points, const NP& np, Driver_settings& s)
{
  namespace wnp = Wavejets::internal_np;
  using CGAL::parameters::is_default_parameter;
  const char* fn = s.function;
  s.largest_radius = s.neighbor_radius;
  if constexpr(!is_default_parameter<NP, wnp::neighbor_radius_map_t>::value)
  {
    const auto map = CGAL::parameters::get_parameter(np, wnp::neighbor_radius_map);
    for(auto it = points.begin(); it != points.end(); ++it)
    {
      const double r = to_double(get(map, *it));
      require(std::isfinite(r) && r >= 0, fn, "neighbor_radius_map: a radius is negative or not finite");
      s.radius_of_point.push_back(r > 0 ? r : s.neighbor_radius);
      s.largest_radius = (std::max)(s.largest_radius, r);
    }
  }
  if constexpr(!is_default_parameter<NP, wnp::neighborhood_size_map_t>::value)
  {
    const auto map = CGAL::parameters::get_parameter(np, wnp::neighborhood_size_map);
    unsigned int largest = 0;
    std::size_t index = 0;
    for(auto it = points.begin(); it != points.end(); ++it, ++index)
    {
      const long long k = static_cast<long long>(get(map, *it));
      require(k >= 0 && k <= (std::numeric_limits<unsigned int>::max)(), fn,
              "neighborhood_size_map: a number of neighbors is negative or too large");
      const unsigned int k_i = k > 0 ? (unsigned int)(k) : s.k;
      require(k_i >= 2 || s.radius_at(index) > 0, fn,
              "neighborhood_size_map: a point has fewer than 2 neighbors (0 stands for k, which is < 2)");
      s.k_of_point.push_back(k_i);
      largest = (std::max)(largest, k_i);
    }
    s.k = (std::max)(s.k, largest);
  }
  if constexpr(!is_default_parameter<NP, wnp::order_map_t>::value)
  {
    const auto map = CGAL::parameters::get_parameter(np, wnp::order_map);
    for(auto it = points.begin(); it != points.end(); ++it)
    {
      const long long order = static_cast<long long>(get(map, *it));
      require(order >= 0, fn, "order_map: an order is negative");
      s.order_of_point.push_back(order > 0 ? std::size_t(order) : s.order);
    }
  }
  if(s.k < 2)
    for(double r : s.radius_of_point)
      require(r > 0, fn, "neighbor_radius_map: a point has no radius (0 stands for neighbor_radius, which is 0) "
                         "and k < 2");
}

/// For the functions that read or write normals whatever their settings.
template <class PointRange, class NP>
void require_normal_map(PointRange& points, const NP& np, const char* fn)
{
  require(has_normal_map(points, np), fn, "the point set has no normal map (call add_normal_map() first)");
}

/// The filters' evaluation radius s of a_n(s) (`Wavejets::parameters::evaluation_radius`), world
/// units; 0 (the default): Rf of each point.
template <class NP>
double read_evaluation_radius(const NP& np, const char* fn)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const double s = to_double(choose_parameter(get_parameter(np, Wavejets::internal_np::evaluation_radius), 0.));
  require(std::isfinite(s) && s >= 0, fn, "evaluation_radius must be finite and >= 0");
  return s;
}

/// Input of a point-set function: the range's keys, its property maps (point, normal and the optional
/// `fitted_map`), and positions/normals copied to double.
template <class PointRange, class NP>
struct Point_set_input
{
  typedef Point_set_processing_3_np_helper<PointRange, NP> NP_helper;
  typedef typename NP_helper::Point_map Point_map;
  typedef typename NP_helper::Normal_map Normal_map;
  typedef typename NP_helper::Geom_traits Geom_traits;
  typedef typename Geom_traits::Point_3 Point_3;
  typedef typename Geom_traits::Vector_3 Vector_3;
  typedef typename PointRange::iterator iterator;
  typedef std::decay_t<decltype(CGAL::parameters::get_parameter(std::declval<const NP&>(),
                                                                Wavejets::internal_np::fitted_map))> Fitted_map;
  typedef std::decay_t<decltype(CGAL::parameters::get_parameter(std::declval<const NP&>(),
                                                                Wavejets::internal_np::outside_map))> Outside_map;

  Point_map point_map;
  Normal_map normal_map;
  Fitted_map fitted_map;                     // CGAL::internal_np::Param_not_found if not given
  Outside_map outside_map;                   // with `tile` (idem)
  bool has_normals;
  std::vector<iterator> items;               // range order
  std::vector<Neighbor_query::Point> points; // double copy (fed to the kd-tree)
  std::vector<unsigned char> finite;         // point i has finite coordinates
  std::vector<Eigen::Vector3d> normals;      // input normals (empty if none are read)
  std::vector<unsigned char> owned;          // with `tile`: the points to fit (empty: all)

  /// `read_normals`: copy the input normals (`Driver_settings::read_input_normals`).
  Point_set_input(PointRange& range, const NP& np, bool read_normals)
    : point_map(NP_helper::get_point_map(range, np)), normal_map(read_normal_map(range, np)),
      fitted_map(CGAL::parameters::get_parameter(np, Wavejets::internal_np::fitted_map)),
      outside_map(CGAL::parameters::get_parameter(np, Wavejets::internal_np::outside_map)),
      has_normals(has_normal_map(range, np))
  {
    for(iterator it = range.begin(); it != range.end(); ++it) items.push_back(it);
    points.reserve(items.size());
    finite.reserve(items.size());
    for(const iterator& it : items)
    {
      const Point_3& p = get(point_map, *it);
      points.emplace_back(to_double(p.x()), to_double(p.y()), to_double(p.z()));
      const Neighbor_query::Point& q = points.back();
      finite.push_back(std::isfinite(q.x()) && std::isfinite(q.y()) && std::isfinite(q.z()));
    }
    if constexpr(!CGAL::parameters::is_default_parameter<NP, Wavejets::internal_np::owned_map_t>::value)
    {
      const auto owned_map = CGAL::parameters::get_parameter(np, Wavejets::internal_np::owned_map);
      owned.reserve(items.size());
      for(const iterator& it : items) owned.push_back(get(owned_map, *it) ? 1 : 0);
    }
    if(read_normals && has_normals)
    {
      normals.reserve(items.size());
      for(const iterator& it : items)
      {
        const Vector_3 n = get(normal_map, *it);
        normals.emplace_back(to_double(n.x()), to_double(n.y()), to_double(n.z()));
      }
    }
  }

  /// The normal map, or without one CGAL's default map (a constant) built with a zero vector: its
  /// default constructor copies an uninitialized `Vector_3` (g++ 12 warns, -Wuninitialized). Never read then.
  static Normal_map read_normal_map(PointRange& range, const NP& np)
  {
    if constexpr(may_have_normal_map<PointRange, NP>())
      return NP_helper::get_normal_map(range, np);
    else
      return Normal_map(typename Normal_map::value_type(0., 0., 0.));
  }

  std::size_t size() const { return items.size(); }
  /// The pass's interface to its points (a tile's input, tiled_driver.h, has the same): every point
  /// is fitted, its index is its index in the range, and its neighbors are all there.
  static constexpr bool checks_reach = false;
  static bool is_active(std::size_t) { return true; }
  static std::size_t index_in_range(std::size_t i) { return i; }
  Eigen::Vector3d position(std::size_t i) const { return Eigen::Vector3d(points[i].x(), points[i].y(), points[i].z()); }
  static Vector_3 to_vector(const Eigen::Vector3d& v) { return Vector_3(v.x(), v.y(), v.z()); }
};

/// What a kernel sees of one fitted point.
/// The fit works in coordinates divided by the neighborhood radius Rf ("rescaled units"): the
/// coefficients are in those units, and the two conversions below are the only unit arithmetic the
/// functions' kernels do (the filters' formulas are written in rescaled units, doc/Wavejets/Mathematics.txt).
struct Fitted_point
{
  std::size_t index;          // in the range (and the function's per-point buffers)
  std::size_t local;          // in the pass's input (the index in the range, but in a tiled run)
  const Fit_result& fit;
  const double* coefficients; // rescaled units (see Fitter::coefficients())

  /// A length given in units of Rf, in world units.
  double world_length(double rescaled) const { return fit.radius * rescaled; }
  /// The evaluation radius s (world units; 0: Rf) in units of Rf, clamped to 1 (a_n(s) would
  /// extrapolate the polynomial beyond the points it was fitted to).
  double evaluation_radius_in_radii(double s) const { return s > 0 ? (std::min)(s / fit.radius, 1.) : 1.; }
};

/// Unit normal of the Wavejet surface at the origin, in the final frame (tilted by the residual f_{1,+-1}).
inline Eigen::Vector3d surface_normal(const Fitted_point& fp)
{
  const Frame& f = fp.fit.frame;
  if(fp.fit.order < 1) return f.n;
  return graph_normal(f, fp.coefficients[1], fp.coefficients[2]);
}

/// Kernel of the normal-estimation pass of the Hermite pipeline (a named type: a lambda in
/// fit_each_point would make every instantiation instantiate a new one, without end).
struct Normal_writer
{
  std::vector<Eigen::Vector3d>* normals;
  void operator()(const Fitted_point& fp) const { (*normals)[fp.local] = surface_normal(fp); }
};

/// Per-point statuses of a run, and the summary.
struct Driver_run
{
  std::vector<unsigned char> fitted;  // 1 where the kernel was called
  std::vector<unsigned char> outside; // with `tile`: 1 where the fit reached past the tile (else empty)
  Processing_report report;
};

/// Per-point outcome of one pass over the points of an input (indexed like the input).
struct Pass_result
{
  std::vector<unsigned char> status;  // Fit_status (TOO_FEW_POINTS where not fitted); empty if the
                                      // pass of the neighbors' normals was interrupted
  std::vector<unsigned char> reduced; // 1 where the order was lowered
  std::vector<unsigned char> fitted;  // 1 where the kernel was called
  std::vector<double> reach;          // Input::checks_reach only: Point_fitter::reach() of each fit
  std::vector<unsigned char> outside; // Input::checks_reach only: 1 where that ball leaves the input's
                                      // points (the point was not fitted)
  bool interrupted = false;
};

/// What a pass fits: the input's active points, their result checked against the input's extent
/// (MAIN), or every point without that check (NEIGHBOR_NORMALS, the first pass of the Hermite fit,
/// whose normals the main pass checks through its reach).
enum class Pass_kind { MAIN, NEIGHBOR_NORMALS };

template <class ConcurrencyTag, class Input, class Kernel>
Pass_result fit_pass(const Input& input, const Driver_settings& settings, const Kernel& kernel,
                     Pass_progress* parent, Pass_kind kind);

/// The neighbors' normals of the Hermite fit (use_neighbor_normals; null without it): the input normals
/// when they were read, else they are estimated first into `estimated` by a pass of
/// wavejet_estimate_normals' fit (same neighborhoods, order and weights; tangent-plane search at order 2
/// with 2 re-fits; unoriented, which the slope equations do not mind). Points without a normal
/// (unfitted) give no slope rows. `first_reach`: the reach of each estimated normal (tiled runs only).
/// `interrupted`: the callback stopped that pass.
template <class ConcurrencyTag, class Input>
const std::vector<Eigen::Vector3d>* hermite_normals(const Input& input, const Driver_settings& settings,
                                                    std::vector<Eigen::Vector3d>& estimated,
                                                    std::vector<double>& first_reach, Pass_progress* parent,
                                                    bool& interrupted)
{
  interrupted = false;
  if(!settings.use_neighbor_normals)
    return nullptr;
  if(!input.normals.empty())
    return &input.normals;
  Driver_settings first = settings;
  first.use_neighbor_normals = false;
  first.fitting.tangent_plane_order = 2;
  first.fitting.correction_iterations = 2;
  first.fitting.curvature_frame = Curvature_frame::TANGENT_FRAME;
  estimated.assign(input.size(), Eigen::Vector3d::Zero());
  Pass_result pass = fit_pass<ConcurrencyTag>(input, first, Normal_writer{&estimated}, parent,
                                              Pass_kind::NEIGHBOR_NORMALS);
  interrupted = pass.interrupted;
  first_reach = std::move(pass.reach);
  return &estimated;
}

/// Fits the Wavejet of one point of a point-set function's input, with scratch reused across the
/// points of a chunk (one instance per chunk).
class Point_fitter
{
public:
  /// Fits point i of `input` to its neighborhood; `neighbor_normals`: see hermite_normals().
  template <class Input>
  const Fit_result& fit(std::size_t i, const Input& input, const Driver_settings& settings, const Neighbor_query& query,
                        const std::vector<Eigen::Vector3d>* neighbor_normals)
  {
    const Eigen::Vector3d* hint = nullptr;
    Eigen::Vector3d normal;
    if(settings.read_input_normals) // the input normals orient the frame
    {
      normal = input.normals[i];
      if(normal.allFinite() && normal.squaredNorm() > 0) hint = &normal; // else: unoriented
    }
    const std::size_t in_range = input.index_in_range(i);
    k_ = settings.k_at(in_range);
    radius_ = settings.radius_at(in_range);
    query.neighbors(i, k_, radius_, neighbors_, scratch_);
    const Eigen::Vector3d p = input.position(i);
    offsets_.assign(1, Eigen::Vector3d::Zero()); // the query point, first
    if(neighbor_normals) normals_of_offsets_.assign(1, (*neighbor_normals)[i]);
    for(std::size_t j : neighbors_)
    {
      if(settings.restrict_to_consistent_normals && hint && !(input.normals[j].dot(normal) >= 0.))
        continue;
      offsets_.push_back(input.position(j) - p);
      if(neighbor_normals) normals_of_offsets_.push_back((*neighbor_normals)[j]);
    }
    const Fitting_options* options = &settings.fitting;
    if(radius_ != settings.fitting.neighborhood_radius) // this point's own radius (neighbor_radius_map)
    {
      options_ = settings.fitting;
      options_.neighborhood_radius = radius_;
      options = &options_;
    }
    fitter_.fit(offsets_.data(), offsets_.size(), settings.order_at(in_range), *options, hint, fit_,
                neighbor_normals ? normals_of_offsets_.data() : nullptr);
    return fit_;
  }

  /// The coefficients of the last fit (see Fitter::coefficients()).
  const double* coefficients() const { return fitter_.coefficients(); }

  /// The reach of the last fit, of point i: a radius around point i such that the fit depends only on
  /// the input's points in that ball (doc/Wavejets/Mathematics.txt §12). The distance to its last
  /// neighbor when the search found its k (its k nearest are then those of any larger point set that
  /// has no other point in that ball), else the search radius (infinite for a k-nearest search).
  /// With estimated neighbors' normals (`first_reach`: the reach of each), also the balls of their fits.
  template <class Input>
  double reach(std::size_t i, const Input& input, const std::vector<double>* first_reach) const
  {
    const Eigen::Vector3d p = input.position(i);
    double r = std::numeric_limits<double>::infinity();
    if(k_ > 0 && neighbors_.size() == k_) r = (input.position(neighbors_.back()) - p).norm();
    else if(radius_ > 0) r = radius_;
    if(first_reach)
    {
      r = (std::max)(r, (*first_reach)[i]);
      for(std::size_t j : neighbors_) r = (std::max)(r, (input.position(j) - p).norm() + (*first_reach)[j]);
    }
    return r;
  }

private:
  Fitter fitter_;
  Fit_result fit_;
  unsigned int k_ = 0;    // the k of the last fit
  double radius_ = 0.;    // and its neighborhood radius (0: the k nearest)
  Fitting_options options_; // the settings' fitting options with a point's own radius
  std::vector<std::size_t> neighbors_;
  Neighbor_query::Scratch scratch_;
  std::vector<Eigen::Vector3d> offsets_, normals_of_offsets_;
};

/// The report's counts from the per-point statuses of a run.
inline void count_points(Driver_run& run, const std::vector<unsigned char>& status,
                         const std::vector<unsigned char>& reduced)
{
  Processing_report& r = run.report;
  for(std::size_t i = 0; i < run.fitted.size(); ++i)
  {
    if(run.fitted[i]) { ++r.number_of_fitted_points; r.number_of_reduced_order_points += reduced[i]; }
    else
    {
      ++r.number_of_unfitted_points;
      r.number_of_non_finite_points += (status[i] == (unsigned char)(Fit_status::NON_FINITE_INPUT));
    }
  }
}

/// One pass over the points of `input` (see Pass_kind): runs `kernel(const Fitted_point&)` on every
/// point that is fitted. The kernel must only write to its own slot of per-point buffers (it runs
/// concurrently under Parallel_tag). `parent`: the progress of a tiled run (null: the pass reports
/// to the callback itself).
template <class ConcurrencyTag, class Input, class Kernel>
Pass_result fit_pass(const Input& input, const Driver_settings& settings, const Kernel& kernel,
                     Pass_progress* parent, Pass_kind kind)
{
  const std::size_t N = input.size();
  Pass_result result;
  result.status.assign(N, (unsigned char)(Fit_status::TOO_FEW_POINTS));
  result.reduced.assign(N, 0);
  result.fitted.assign(N, 0);
  if constexpr(Input::checks_reach)
  {
    result.reach.assign(N, std::numeric_limits<double>::infinity());
    result.outside.assign(N, 0);
  }
  if(N == 0) return result;

  std::vector<Eigen::Vector3d> estimated_normals;
  std::vector<double> first_reach;
  const std::vector<Eigen::Vector3d>* neighbor_normals =
    hermite_normals<ConcurrencyTag>(input, settings, estimated_normals, first_reach, parent, result.interrupted);
  if(result.interrupted) { result.status.clear(); return result; }
  const std::vector<double>* reach_of_neighbor_normals = first_reach.empty() ? nullptr : &first_reach;

  const Neighbor_query query(input.points, input.finite, ConcurrencyTag());
  // Points are visited in the tree's spatial order (each point's result does not depend on it).
  const std::vector<std::size_t> order = query.processing_order();
  CGAL_assertion(order.size() == N);

  const std::size_t chunk_size = 256;
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < N; b += chunk_size) chunks.push_back(b);

  static const std::function<bool(double)> no_callback;
  Pass_progress progress(parent ? no_callback : settings.callback, N, parent);
  std::atomic<bool> interrupted(false);
  const bool checked = kind == Pass_kind::MAIN;

  CGAL::for_each<ConcurrencyTag>(chunks, [&](const std::size_t begin) -> bool {
    Point_fitter fitter;
    const std::size_t end = (std::min)(begin + chunk_size, N);
    std::size_t done = 0;
    for(std::size_t position = begin; position < end; ++position)
    {
      const std::size_t i = order[position];
      if(interrupted || progress.interrupted()) { interrupted = true; return false; }
      if(!input.is_active(i) && checked) continue;
      done += input.is_active(i);
      if(!input.finite[i]) { result.status[i] = (unsigned char)(Fit_status::NON_FINITE_INPUT); continue; }
      const Fit_result& fit = fitter.fit(i, input, settings, query, neighbor_normals);
      if constexpr(Input::checks_reach)
      {
        result.reach[i] = fitter.reach(i, input, reach_of_neighbor_normals);
        if(checked && !input.holds_ball(i, result.reach[i])) { result.outside[i] = 1; continue; }
      }
      result.status[i] = (unsigned char)(fit.status);
      if(!fit.success()) continue;
      result.reduced[i] = fit.order < settings.order_at(input.index_in_range(i));
      kernel(Fitted_point{input.index_in_range(i), i, fit, fitter.coefficients()});
      result.fitted[i] = 1;
    }
    progress.advance(done);
    return true;
  });
  if(!interrupted) progress.finish();
  if(progress.interrupted()) interrupted = true;
  result.interrupted = interrupted;
  return result;
}

template <class ConcurrencyTag, class Input, class Kernel>
Driver_run fit_each_tile(const Input& input, const Driver_settings& settings, const Kernel& kernel);
template <class ConcurrencyTag, class Input, class Kernel>
Driver_run fit_one_tile(const Input& input, const Driver_settings& settings, const Kernel& kernel);

/// Runs `kernel(const Fitted_point&)` on every point that can be fitted: in one pass over all the
/// points, or tile by tile (the named parameter `tile_size`, tiled_driver.h), with the same results;
/// or, when the range is one tile of a larger point set (`tile`), on its owned points.
/// The kernel must only write to its own slot of per-point buffers (it runs concurrently under
/// Parallel_tag).
template <class ConcurrencyTag, class Input, class Kernel>
Driver_run fit_each_point(const Input& input, const Driver_settings& settings, const Kernel& kernel)
{
  if(settings.is_tile)
    return fit_one_tile<ConcurrencyTag>(input, settings, kernel);
  if(settings.tile_size > 0 && input.size() > settings.tile_size)
    return fit_each_tile<ConcurrencyTag>(input, settings, kernel);
  Pass_result pass = fit_pass<ConcurrencyTag>(input, settings, kernel, nullptr, Pass_kind::MAIN);
  Driver_run run;
  run.report.number_of_points = input.size();
  run.report.number_of_tiles = input.size() > 0 ? 1 : 0;
  run.report.interrupted = pass.interrupted;
  run.fitted = std::move(pass.fitted);
  if(!pass.status.empty()) count_points(run, pass.status, pass.reduced); // else: no count (interrupted)
  return run;
}

/// Writes a per-point flag of a run (`fitted`, `outside`: empty means false) to an optional map.
template <class Input>
void write_flag_map(const Input&, const std::vector<unsigned char>&, CGAL::internal_np::Param_not_found) {}
template <class Input, class FlagMap>
void write_flag_map(const Input& input, const std::vector<unsigned char>& flags, const FlagMap& map)
{
  for(std::size_t i = 0; i < input.size(); ++i)
    put(map, *input.items[i], !flags.empty() && bool(flags[i]));
}

/// Second pass of every function: unless the run was interrupted, calls `write(i, key)` for each
/// fitted point i (in range order) and fills the optional `fitted_map` and `outside_map`. Unfitted
/// points are untouched.
template <class Input, class Write>
void commit(const Input& input, const Driver_run& run, const Write& write)
{
  if(run.report.interrupted) return;
  for(std::size_t i = 0; i < input.size(); ++i)
    if(run.fitted[i]) write(i, *input.items[i]);
  write_flag_map(input, run.fitted, input.fitted_map);
  write_flag_map(input, run.outside, input.outside_map);
}

/// `put` for an optional output map (a named parameter that may be absent).
template <class Key, class Value>
void put_if_given(CGAL::internal_np::Param_not_found, const Key&, const Value&) {}
template <class Map, class Key, class Value>
void put_if_given(const Map& map, const Key& key, const Value& value) { put(map, key, value); }

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#include <CGAL/Wavejets/internal/tiled_driver.h>

#endif // CGAL_WAVEJETS_INTERNAL_POINT_SET_DRIVER_H
