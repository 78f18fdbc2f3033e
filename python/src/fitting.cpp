// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// One Wavejet fit (CGAL::Wavejet_fitting) on an (L, 3) array of points, the first being the point
// where the Wavejet is computed; the result as the Python class wavejets.Wavejet.
#include "bindings.h"

#include <CGAL/Wavejet_fitting.h>

#include <pybind11/complex.h>

#include <vector>

namespace wavejets_python {

namespace {

typedef CGAL::Wavejet_fitting<Kernel> Fitting;
typedef Fitting::Wavejet_form Form;

/// A fitted form and what only the fitting object knows.
struct Fitted_wavejet
{
  Form form;
  double condition_number = 0.;
};

py::array_t<double> to_array(const Vector& v)
{
  py::array_t<double> a(3);
  double* p = a.mutable_data();
  p[0] = v.x(); p[1] = v.y(); p[2] = v.z();
  return a;
}

std::vector<Point> to_points(const Coordinates& a)
{
  std::vector<Point> points;
  points.reserve(std::size_t(a.shape(0)));
  for(py::ssize_t i = 0; i < a.shape(0); ++i) points.emplace_back(a.at(i, 0), a.at(i, 1), a.at(i, 2));
  return points;
}

Fitted_wavejet fit(const Coordinates& neighbors, std::size_t order, const py::object& normal,
                   const py::object& neighbor_normals, const py::dict& kwargs)
{
  check_coordinates(neighbors, "neighbors");
  if(neighbors.shape(0) == 0) throw py::value_error("neighbors: empty (the first row is the point where the Wavejet is computed)");
  if(order == 0) throw py::value_error("order: must be >= 1");
  // Fitting_options' defaults, with the keyword arguments given (read as a point-set function's are).
  const Call c = read_call(kwargs, CGAL::Wavejets::Point_set_function::ESTIMATE_CURVATURES, std::size_t(neighbors.shape(0)));
  CGAL::Wavejets::Fitting_options options = c.fitting;
  if(kwargs.contains("neighborhood_radius") && !kwargs["neighborhood_radius"].is_none())
    options.neighborhood_radius = kwargs["neighborhood_radius"].cast<double>();
  if(c.seed_with_input_normals) options.normal_use = CGAL::Wavejets::Normal_use::SEED_FRAME;
  const std::vector<Point> points = to_points(neighbors);
  Fitting fitting(options);
  Fitted_wavejet result;
  if(!neighbor_normals.is_none()) {
    const Coordinates m = neighbor_normals.cast<Coordinates>();
    check_coordinates(m, "neighbor_normals", long(points.size()));
    std::vector<Vector> normals;
    for(py::ssize_t i = 0; i < m.shape(0); ++i) normals.emplace_back(m.at(i, 0), m.at(i, 1), m.at(i, 2));
    result.form = fitting(points.begin(), points.end(), normals.begin(), order);
  } else if(!normal.is_none()) {
    const py::array_t<double, py::array::c_style> n = normal.cast<py::array_t<double, py::array::c_style> >();
    if(n.ndim() != 1 || n.shape(0) != 3) throw py::value_error("normal: expected 3 numbers");
    if(!std::isfinite(n.at(0)) || !std::isfinite(n.at(1)) || !std::isfinite(n.at(2)))
      throw py::value_error("normal: has a NaN or infinite coordinate");
    result.form = fitting(points.begin(), points.end(), order, Vector(n.at(0), n.at(1), n.at(2)));
  } else
    result.form = fitting(points.begin(), points.end(), order);
  result.condition_number = fitting.condition_number();
  return result;
}

} // namespace

void bind_fitting(py::module_& m)
{
  py::class_<Fitted_wavejet>(m, "Wavejet", R"doc(
A Wavejet fitted at one point (returned by `wavejets.fit`): the height field
z(r, theta) = sum f_{k,n} r^k e^{i n theta} over the tangent frame (u, v, n) of the point,
r and z in the input length unit, theta measured from u. Every quantity is meaningful only
when `is_valid`; `status` says why a fit failed. Curvature signs are relative to `normal`:
bending toward it is positive (a sphere with outward normals has H = -1/R).)doc")
    .def_property_readonly("status", [](const Fitted_wavejet& w) { return std::string(CGAL::Wavejets::fit_status_name(w.form.status())); },
                           "'success', or why no Wavejet could be fitted ('too few points', 'degenerate neighborhood', ...)")
    .def_property_readonly("is_valid", [](const Fitted_wavejet& w) { return w.form.is_valid(); })
    .def_property_readonly("order", [](const Fitted_wavejet& w) { return w.form.order(); },
                           "order K actually fitted (lowered when the points cannot support the requested one)")
    .def_property_readonly("radius", [](const Fitted_wavejet& w) { return w.form.radius(); }, "neighborhood radius Rf")
    .def_property_readonly("number_of_points", [](const Fitted_wavejet& w) { return w.form.number_of_points(); })
    .def_property_readonly("number_of_corrections", [](const Fitted_wavejet& w) { return w.form.number_of_corrections(); },
                           "accepted tangent-plane re-fits")
    .def_property_readonly("tangent_plane_residual", [](const Fitted_wavejet& w) { return w.form.tangent_plane_residual(); },
                           "|f_{1,1}| left in the final frame")
    .def_property_readonly("condition_number", [](const Fitted_wavejet& w) { return w.condition_number; })
    .def_property_readonly("origin", [](const Fitted_wavejet& w) {
        const Point p = w.form.origin();
        return to_array(p - CGAL::ORIGIN);
      }, "the point of the Wavejet surface above the query point")
    .def_property_readonly("normal", [](const Fitted_wavejet& w) { return to_array(w.form.normal_direction()); },
                           "unit normal of the Wavejet surface at the point")
    .def_property_readonly("u", [](const Fitted_wavejet& w) { return to_array(w.form.first_tangent_direction()); },
                           "first axis of the tangent frame (theta = 0)")
    .def_property_readonly("v", [](const Fitted_wavejet& w) { return to_array(w.form.second_tangent_direction()); },
                           "second axis of the tangent frame, n x u")
    .def_property_readonly("frame_normal", [](const Fitted_wavejet& w) { return to_array(w.form.frame_normal_direction()); },
                           "axis n of the tangent frame, along which heights are measured")
    .def_property_readonly("mean_curvature", [](const Fitted_wavejet& w) { return w.form.mean_curvature(); })
    .def_property_readonly("gaussian_curvature", [](const Fitted_wavejet& w) { return w.form.gaussian_curvature(); })
    .def_property_readonly("principal_curvatures", [](const Fitted_wavejet& w) {
        return w.form.is_valid() ? py::make_tuple(w.form.principal_curvatures(0), w.form.principal_curvatures(1))
                                 : py::make_tuple(0., 0.);
      }, "(k1, k2), k1 >= k2")
    .def_property_readonly("principal_directions", [](const Fitted_wavejet& w) {
        return py::make_tuple(to_array(w.form.maximal_principal_direction()), to_array(w.form.minimal_principal_direction()));
      }, "(d1, d2): unit tangent directions of k1 and k2")
    .def("coefficient", [](const Fitted_wavejet& w, int k, int n) { return w.form.coefficient(k, n); },
         py::arg("k"), py::arg("n"), "f_{k,n} (complex; 0 where (k, n) is not a coefficient of this Wavejet)")
    .def_property_readonly("coefficients", [](const Fitted_wavejet& w) {
        return py::array_t<double>(py::ssize_t(w.form.coefficients().size()), w.form.coefficients().data());
      }, "the (K+1)(K+2)/2 real unknowns: for each k, f_{k,0} (k even), then alpha_{k,n}, beta_{k,n}\n"
         "with f_{k,n} = (alpha_{k,n} - i beta_{k,n}) / 2")
    .def("enclosed_area_coefficient", [](const Fitted_wavejet& w, int n, const py::object& s) {
        return s.is_none() ? w.form.enclosed_area_coefficient(n) : w.form.enclosed_area_coefficient(n, s.cast<double>());
      }, py::arg("n"), py::arg("s") = py::none(),
         "a_n(s) = sum_k f_{k,n} s^(k+2)/(k+2) (length^3); s defaults to the radius Rf")
    .def("__repr__", [](const Fitted_wavejet& w) {
        if(!w.form.is_valid()) return std::string("<wavejets.Wavejet: ") + CGAL::Wavejets::fit_status_name(w.form.status()) + ">";
        return "<wavejets.Wavejet order " + std::to_string(w.form.order()) + ", " + std::to_string(w.form.number_of_points()) +
               " points, H " + std::to_string(w.form.mean_curvature()) + ">";
      });
  m.def("fit", &fit, "Low-level binding: use wavejets.fit.", py::arg("neighbors"), py::arg("order"), py::arg("normal"),
        py::arg("neighbor_normals"), py::arg("kwargs"));
}

} // namespace wavejets_python
