// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// The compiled part of the Python module `wavejets`: `wavejets._wavejets`. The public functions,
// their keyword arguments and their documentation are in wavejets/_functions.py; the defaults
// they show come from here (`defaults()`), that is from the C++ headers.
#include "bindings.h"

#include <pybind11/stl.h>

#include <CGAL/Wavejets/Function_defaults.h>
#include <CGAL/Wavejets/version.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/info.h>
#endif

namespace wavejets_python {

namespace {

/// The defaults of a point-set function (Function_defaults.h and Fitting_options.h) as a dict of
/// the Python keyword arguments.
py::dict defaults(const std::string& name)
{
  typedef CGAL::Wavejets::Point_set_function F;
  const F f = name == "estimate_normals" ? F::ESTIMATE_NORMALS
            : name == "estimate_curvatures" ? F::ESTIMATE_CURVATURES
            : name == "enhance_positions" ? F::ENHANCE_POSITIONS
            : name == "enhance_normals" ? F::ENHANCE_NORMALS
            : throw py::value_error("no point-set function named '" + name + "'");
  const CGAL::Wavejets::Function_defaults d = CGAL::Wavejets::function_defaults(f);
  const CGAL::Wavejets::Fitting_options& o = d.fitting;
  py::dict r;
  r["order"] = d.order;
  r["neighbor_radius"] = 0.;
  r["neighbors_per_coefficient"] = o.neighbors_per_coefficient;
  r["minimum_order"] = o.minimum_order;
  r["correction_iterations"] = o.correction_iterations;
  r["tangent_plane_order"] = o.tangent_plane_order;
  r["robust_iterations"] = o.robust_iterations;
  r["neighbor_normal_weight"] = o.neighbor_normal_weight;
  r["compact_weights"] = o.compact_weights;
  r["curvature_frame"] = o.curvature_frame == CGAL::Wavejets::Curvature_frame::INITIAL_FRAME ? "initial" : "tangent";
  r["gain"] = CGAL::Wavejets::default_filter_gain;
  r["evaluation_radius"] = 0.;
  r["maximum_displacement_in_radii"] = d.maximum_displacement_in_radii;
  return r;
}

} // namespace

} // namespace wavejets_python

namespace py = pybind11;

PYBIND11_MODULE(_wavejets, m)
{
  namespace wp = wavejets_python;
  m.doc() = "Compiled part of the wavejets module (CGAL Wavejets); use the functions of `wavejets`.";
  m.attr("__version__") = CGAL_WAVEJETS_VERSION_STR;
  m.def("defaults", &wp::defaults, py::arg("function"),
        "The defaults of a point-set function's keyword arguments, from the C++ headers.");
  m.def("default_neighborhood_sizes", [](std::size_t order) { return CGAL::Wavejets::default_neighborhood_sizes(order); },
        "The default ladder of wavejets.estimate_scales at this order.", py::arg("order"));
  m.def("default_k", [](std::size_t order) { return CGAL::Wavejets::default_number_of_neighbors(order); },
        py::arg("order"), "The number of neighbors used when k is not given, for a Wavejet order.");
  m.def("default_threads", [] {
#ifdef CGAL_LINKED_WITH_TBB
    return tbb::info::default_concurrency();
#else
    return 1;
#endif
  }, "The number of threads a call uses when threads is not given (all cores).");
  wp::bind_point_set_functions(m);
  wp::bind_fitting(m);
  wp::bind_io(m);
  wp::bind_tool(m);
}
