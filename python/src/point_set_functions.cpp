// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// The four point-set functions and wavejet_estimate_scales on NumPy arrays: each calls the C++ function of the same name with
// Parallel_tag over the indices 0..N-1, the input arrays read in place through property maps, the
// results written into new arrays. The Python layer (wavejets/_functions.py) checks and documents
// the arguments; the C++ functions check them again (std::invalid_argument -> ValueError).
#include "bindings.h"

#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_scales.h>

#include <pybind11/stl.h>


namespace wavejets_python {

namespace {

namespace WP = CGAL::Wavejets::parameters;
typedef CGAL::Wavejets::Processing_report Report;
typedef std::function<bool(double)> Callback;

/// The fit settings, after `extra` (a pack of the package's parameters).
template <class Extra>
auto fitting_parameters(const Call& c, const Extra& extra)
{
  const CGAL::Wavejets::Fitting_options& f = c.fitting;
  return extra.neighbors_per_coefficient(f.neighbors_per_coefficient)
              .minimum_order(f.minimum_order)
              .correction_iterations(f.correction_iterations)
              .tangent_plane_order(f.tangent_plane_order)
              .robust_iterations(f.robust_iterations)
              .compact_weights(f.compact_weights);
}

/// The named parameters every function takes, after the function's own (`extra`, a pack of the
/// package's parameters, which must come before CGAL's). The per-point k, order and radius maps are
/// always given: without per-point values they read 0 (the function's k, order and neighbor_radius)
/// for every point, which gives the bits of a call without them.
template <class Extra>
auto shared_parameters(const Call& c, const Extra& extra, const Callback& callback, const Point_map& points)
{
  const CGAL::Wavejets::Fitting_options& f = c.fitting;
  return fitting_parameters(c, extra.neighborhood_size_map(c.k_map()).order_map(c.order_map())
                                    .neighbor_radius_map(c.radius_map()))
              .seed_with_input_normals(c.seed_with_input_normals)
              .restrict_to_consistent_normals(c.restrict_to_consistent_normals)
              .use_neighbor_normals(c.use_neighbor_normals)
              .neighbor_normal_weight(f.neighbor_normal_weight)
              .neighbor_radius(c.neighbor_radius)
              .callback(callback)
              .point_map(points);
}

/// The input points, checked, and the result arrays every function returns.
struct Arrays
{
  Coordinates points;
  py::object normals;          // None, or the checked (N, 3) input normals
  py::array_t<bool> fitted;
  std::size_t n;
  Index_range range;           // 0..N-1, the range the functions run over

  Arrays(const Coordinates& p, const py::object& input_normals)
    : points(p), normals(input_normals), fitted(zeros<bool>({p.ndim() == 2 ? p.shape(0) : 0})),
      n(p.ndim() == 2 ? std::size_t(p.shape(0)) : 0), range(index_range(n))
  {
    check_coordinates(points, "points");
    if(!normals.is_none())
      check_coordinates(normals.cast<Coordinates>(), "normals", long(n));
  }
  bool has_normals() const { return !normals.is_none(); }
  Point_map point_map(double* out = nullptr) const { return Point_map{points.data(), out}; }
  /// The normal map: reads the input normals (or `out`, zeros, without them) and writes `out`.
  Vector_map normal_map(Coordinates& out) const
  {
    return Vector_map{has_normals() ? normals.cast<Coordinates>().data() : out.data(), out.mutable_data()};
  }
  Flag_map fitted_map() { return Flag_map{fitted.mutable_data()}; }
};

py::tuple estimate_normals(const Coordinates& points, const py::object& normals, const py::dict& kwargs)
{
  Arrays a(points, normals);
  const Call c = read_call(kwargs, CGAL::Wavejets::Point_set_function::ESTIMATE_NORMALS, a.n);
  Coordinates out = copy_or_zeros(normals, a.n);
  const Vector_map normal_map = a.normal_map(out);
  const Flag_map fitted = a.fitted_map();
  const Report r = run_interruptibly(c, [&](const Callback& cb) {
    return CGAL::wavejet_estimate_normals<CGAL::Parallel_tag>(a.range, c.k,
      shared_parameters(c, WP::order(c.order).orient_with_input_normals(c.orient_with_input_normals).fitted_map(fitted),
                        cb, a.point_map()).normal_map(normal_map));
  });
  return py::make_tuple(out, make_report(r, a.fitted));
}

py::tuple estimate_curvatures(const Coordinates& points, const py::object& normals, const py::dict& kwargs)
{
  Arrays a(points, normals);
  const Call c = read_call(kwargs, CGAL::Wavejets::Point_set_function::ESTIMATE_CURVATURES, a.n);
  const py::ssize_t n = py::ssize_t(a.n);
  py::array_t<double> H = zeros<double>({n}), K = zeros<double>({n}), k1 = zeros<double>({n}), k2 = zeros<double>({n});
  Coordinates d1 = zeros<double>({n, 3}), d2 = zeros<double>({n, 3});
  const auto pack = WP::order(c.order).curvature_frame(c.fitting.curvature_frame)
                      .mean_curvature_map(Scalar_map{H.mutable_data()}).gaussian_curvature_map(Scalar_map{K.mutable_data()})
                      .maximal_principal_curvature_map(Scalar_map{k1.mutable_data()})
                      .minimal_principal_curvature_map(Scalar_map{k2.mutable_data()})
                      .maximal_principal_direction_map(Vector_map{nullptr, d1.mutable_data()})
                      .minimal_principal_direction_map(Vector_map{nullptr, d2.mutable_data()})
                      .fitted_map(a.fitted_map());
  Report r;
  if(a.has_normals()) {
    Coordinates unused = copy_or_zeros(normals, a.n);   // the normal map's output side: never written
    const Vector_map normal_map = a.normal_map(unused);
    r = run_interruptibly(c, [&](const Callback& cb) {
      return CGAL::wavejet_estimate_curvatures<CGAL::Parallel_tag>(a.range, c.k,
        shared_parameters(c, pack, cb, a.point_map()).normal_map(normal_map));
    });
  } else
    r = run_interruptibly(c, [&](const Callback& cb) {
      return CGAL::wavejet_estimate_curvatures<CGAL::Parallel_tag>(a.range, c.k,
        shared_parameters(c, pack, cb, a.point_map()));
    });
  py::dict result;
  result["mean_curvature"] = H;
  result["gaussian_curvature"] = K;
  result["k1"] = k1;
  result["k2"] = k2;
  result["d1"] = d1;
  result["d2"] = d2;
  return py::make_tuple(result, make_report(r, a.fitted));
}

/// wavejet_enhance_positions with or without a clamp given (`maximum_displacement`; without, the
/// function's default Rf/2 per point) and with or without a normal map.
template <class Pack>
Report enhance_positions_with(const Call& c, Arrays& a, Coordinates& moved, Coordinates* normals_out, const Pack& pack)
{
  const Point_map point_map = a.point_map(moved.mutable_data());
  const double gain = c.gain.real();
  if(normals_out) {
    const Vector_map normal_map = a.normal_map(*normals_out);
    return run_interruptibly(c, [&](const Callback& cb) {
      return CGAL::wavejet_enhance_positions<CGAL::Parallel_tag>(a.range, c.k, gain,
        shared_parameters(c, pack, cb, point_map).normal_map(normal_map));
    });
  }
  return run_interruptibly(c, [&](const Callback& cb) {
    return CGAL::wavejet_enhance_positions<CGAL::Parallel_tag>(a.range, c.k, gain,
      shared_parameters(c, pack, cb, point_map));
  });
}

py::tuple enhance_positions(const Coordinates& points, const py::object& normals, const py::dict& kwargs)
{
  Arrays a(points, normals);
  const Call c = read_call(kwargs, CGAL::Wavejets::Point_set_function::ENHANCE_POSITIONS, a.n);
  Coordinates moved = copy_or_zeros(points, a.n);
  // The normal map: the input normals, and the written ones with write_normals (zeros without input
  // normals: the frames then stay unoriented, which does not change the motion).
  const bool normal_map = a.has_normals() || c.write_normals;
  Coordinates normals_out = copy_or_zeros(normals, normal_map ? a.n : 0);
  const auto pack = WP::order(c.order).evaluation_radius(c.evaluation_radius).write_normals(c.write_normals)
                      .move_along_input_normals(c.move_along_input_normals).fitted_map(a.fitted_map());
  Coordinates* out = normal_map ? &normals_out : nullptr;
  const Report r = c.maximum_displacement
    ? enhance_positions_with(c, a, moved, out, pack.maximum_displacement(*c.maximum_displacement))
    : enhance_positions_with(c, a, moved, out, pack);
  return py::make_tuple(moved, c.write_normals ? py::object(normals_out) : py::object(py::none()), make_report(r, a.fitted));
}

py::tuple enhance_normals(const Coordinates& points, const py::object& normals, const py::dict& kwargs)
{
  Arrays a(points, normals);
  const Call c = read_call(kwargs, CGAL::Wavejets::Point_set_function::ENHANCE_NORMALS, a.n);
  Coordinates out = copy_or_zeros(normals, a.n);
  const Vector_map normal_map = a.normal_map(out);
  const Report r = run_interruptibly(c, [&](const Callback& cb) {
    return CGAL::wavejet_enhance_normals<CGAL::Parallel_tag>(a.range, c.k, c.gain,
      shared_parameters(c, WP::order(c.order).evaluation_radius(c.evaluation_radius).fitted_map(a.fitted_map()), cb,
                        a.point_map()).normal_map(normal_map));
  });
  return py::make_tuple(out, make_report(r, a.fitted));
}

py::tuple estimate_scales(const Coordinates& points, const py::dict& kwargs)
{
  Arrays a(points, py::none());
  const Call c = read_call(kwargs, CGAL::Wavejets::Point_set_function::ESTIMATE_NORMALS, a.n);
  const std::vector<unsigned int> ladder =
    c.neighborhood_sizes.empty() ? CGAL::Wavejets::default_neighborhood_sizes(c.order) : c.neighborhood_sizes;
  const py::ssize_t n = py::ssize_t(a.n), J = py::ssize_t(ladder.size());
  py::array_t<std::int64_t> k = zeros<std::int64_t>({n});
  py::array_t<double> descriptor = zeros<double>({n, J});
  const Report r = run_interruptibly(c, [&](const Callback& cb) {
    return CGAL::wavejet_estimate_scales<CGAL::Parallel_tag>(a.range,
      fitting_parameters(c, WP::order(c.order).neighborhood_sizes(ladder)
                              .neighborhood_size_map(Count_output_map{k.mutable_data()})
                              .scale_descriptor_map(Row_map{descriptor.mutable_data(), std::size_t(J)})
                              .fitted_map(a.fitted_map()))
        .callback(cb).point_map(a.point_map()));
  });
  py::array_t<std::int64_t> sizes({J});
  std::copy(ladder.begin(), ladder.end(), sizes.mutable_data());
  return py::make_tuple(k, sizes, descriptor, make_report(r, a.fitted));
}

} // namespace

void bind_point_set_functions(py::module_& m)
{
  const char* note = "Low-level binding: use the function of the same name in `wavejets`.";
  m.def("estimate_normals", &estimate_normals, note, py::arg("points"), py::arg("normals"), py::arg("kwargs"));
  m.def("estimate_curvatures", &estimate_curvatures, note, py::arg("points"), py::arg("normals"), py::arg("kwargs"));
  m.def("enhance_positions", &enhance_positions, note, py::arg("points"), py::arg("normals"), py::arg("kwargs"));
  m.def("enhance_normals", &enhance_normals, note, py::arg("points"), py::arg("normals"), py::arg("kwargs"));
  m.def("estimate_scales", &estimate_scales, note, py::arg("points"), py::arg("kwargs"));
}

} // namespace wavejets_python
