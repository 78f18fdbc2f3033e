// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// What the translation units of the Python module `wavejets._wavejets` share: NumPy arrays seen as
// CGAL property maps (no copy of the input), the settings of a call, and the runner that computes
// with the GIL released while the calling thread watches for Ctrl-C and draws the progress.
#ifndef WAVEJETS_PYTHON_BINDINGS_H
#define WAVEJETS_PYTHON_BINDINGS_H

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Wavejets/Fitting_options.h>
#include <CGAL/Wavejets/Function_defaults.h>
#include <CGAL/Wavejets/Processing_report.h>

#include <boost/iterator/counting_iterator.hpp>
#include <boost/property_map/property_map.hpp>
#include <boost/range/counting_range.hpp>

#include <algorithm>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace wavejets_python {

namespace py = pybind11;

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;

/// The (N, 3) float64 C-contiguous arrays the module reads in place (the Python layer converts
/// other dtypes and layouts once, with `numpy.ascontiguousarray`).
typedef py::array_t<double, py::array::c_style> Coordinates;

/// The range the functions run over: the indices 0..N-1, keys of the property maps below.
typedef boost::iterator_range<boost::counting_iterator<std::size_t> > Index_range;
inline Index_range index_range(std::size_t n) { return boost::counting_range(std::size_t(0), n); }

/// Points or vectors (`Value`: `Point` or `Vector`) read from one (N, 3) buffer and written to
/// another (the result; may be null when the function writes none).
template <class Value>
struct Triple_map
{
  typedef std::size_t key_type;
  typedef Value value_type;
  typedef Value reference;
  typedef boost::read_write_property_map_tag category;
  const double* in;
  double* out;
  friend Value get(const Triple_map& m, std::size_t i) { const double* p = m.in + 3 * i; return Value(p[0], p[1], p[2]); }
  friend void put(const Triple_map& m, std::size_t i, const Value& v)
  {
    double* q = m.out + 3 * i;
    q[0] = v.x(); q[1] = v.y(); q[2] = v.z();
  }
};
typedef Triple_map<Point> Point_map;    // the points (input), and the moved points (result)
typedef Triple_map<Vector> Vector_map;  // the input normals, and the result normals or directions

/// One value per point written into a buffer of N values (doubles; NumPy bools for the fitted flags).
template <class T, class Stored = T>
struct Output_map
{
  typedef std::size_t key_type;
  typedef T value_type;
  typedef T reference;
  typedef boost::writable_property_map_tag category;
  Stored* out;
  friend void put(const Output_map& m, std::size_t i, const T& v) { m.out[i] = Stored(v); }
};
typedef Output_map<double> Scalar_map;
typedef Output_map<bool> Flag_map;
typedef Output_map<unsigned int, std::int64_t> Count_output_map;   // wavejet_estimate_scales' sizes

/// One value per point read from a buffer of N (a per-point k, order or radius), or 0 for every
/// point when the buffer is null (0 stands for the function's k, order or neighbor_radius: no
/// per-point value).
template <class T, class Stored = T>
struct Per_point_map
{
  typedef std::size_t key_type;
  typedef T value_type;
  typedef T reference;
  typedef boost::readable_property_map_tag category;
  const Stored* in;
  friend T get(const Per_point_map& m, std::size_t i) { return m.in ? T(m.in[i]) : T(0); }
};
typedef Per_point_map<unsigned int, std::uint32_t> Count_map;
typedef Per_point_map<double> Radius_map;

/// Rows of a buffer of N x `columns` doubles, written from a `std::vector<double>` of that size (the
/// per-point values of a ladder of sizes).
struct Row_map
{
  typedef std::size_t key_type;
  typedef std::vector<double> value_type;
  typedef const std::vector<double>& reference;
  typedef boost::writable_property_map_tag category;
  double* out;
  std::size_t columns;
  friend void put(const Row_map& m, std::size_t i, const std::vector<double>& row)
  {
    std::copy(row.begin(), row.begin() + std::ptrdiff_t((std::min)(row.size(), m.columns)), m.out + i * m.columns);
  }
};
/// A per-point count array passed from Python: None, or a C-contiguous uint32 array of N values.
typedef py::array_t<std::uint32_t, py::array::c_style> Count_array;
/// A per-point radius array passed from Python: None, or a C-contiguous float64 array of N values.
typedef py::array_t<double, py::array::c_style> Radius_array;

/// The settings of one call, read from the keyword arguments the Python layer passes (every key is
/// optional: a missing one takes the C++ default, of `Fitting_options` or of the function).
struct Call
{
  std::size_t number_of_points = 0;
  unsigned int k = 0;
  std::optional<Count_array> k_per_point;        // each point's k (0: k), or none
  std::optional<Count_array> order_per_point;    // each point's order (0: order), or none
  std::vector<unsigned int> neighborhood_sizes;  // estimate_scales' ladder (empty: the default)
  double neighbor_radius = 0.;
  std::optional<Radius_array> radius_per_point;  // each point's radius (0: neighbor_radius), or none
  std::size_t order = 0;
  CGAL::Wavejets::Fitting_options fitting;
  bool orient_with_input_normals = false;
  bool seed_with_input_normals = false;
  bool restrict_to_consistent_normals = false;
  bool use_neighbor_normals = false;
  std::complex<double> gain = 2.;
  double evaluation_radius = 0.;
  std::optional<double> maximum_displacement;   // none: the function's default (Rf/2 per point)
  bool write_normals = false;
  bool move_along_input_normals = false;
  int threads = 0;                              // 0: all cores
  py::object progress;                          // None, or called with the fraction done

  Count_map k_map() const { return Count_map{k_per_point ? k_per_point->data() : nullptr}; }
  Count_map order_map() const { return Count_map{order_per_point ? order_per_point->data() : nullptr}; }
  Radius_map radius_map() const { return Radius_map{radius_per_point ? radius_per_point->data() : nullptr}; }
};

/// Reads the settings of a call of `function` (its defaults: `function_defaults()`).
Call read_call(const py::dict& kwargs, CGAL::Wavejets::Point_set_function function, std::size_t number_of_points);

/// Checks that `a` is an (N, 3) array of finite numbers (N = `rows` unless `rows` is -1); throws
/// ValueError naming `name` and the first bad row.
void check_coordinates(const Coordinates& a, const char* name, long rows = -1);

/// A new array of zeros. Allocated by NumPy (which asks for huge pages for large arrays) and filled
/// here: numpy.zeros leaves the zeroing to the system's page faults, one 4 KB page at a time, which
/// then happen in the functions' sequential writing pass (measured: estimate_curvatures on 10^6
/// points, 2 threads, took 1.13x as long as the C++ call with numpy.zeros, 1.02x with this).
template <class T>
py::array_t<T> zeros(const std::vector<py::ssize_t>& shape)
{
  py::array_t<T> a(shape);
  std::fill(a.mutable_data(), a.mutable_data() + a.size(), T(0));
  return a;
}

/// A new (N, 3) array: a copy of `source` when it is not None, else zeros.
Coordinates copy_or_zeros(const py::object& source, std::size_t n);

/// Runs `compute(callback)` on a worker thread, in a TBB arena of `call.threads` threads, with the
/// GIL released. Meanwhile the calling thread checks for signals (Ctrl-C: the callback then returns
/// false, the C++ function stops and writes nothing, and KeyboardInterrupt is raised) and calls
/// `call.progress` with the fraction done, a few times per second. C++ exceptions propagate.
CGAL::Wavejets::Processing_report
run_interruptibly(const Call& call,
                  const std::function<CGAL::Wavejets::Processing_report(const std::function<bool(double)>&)>& compute);

/// The report as a Python `wavejets.Report` (with the fitted flags).
py::object make_report(const CGAL::Wavejets::Processing_report& r, const py::array_t<bool>& fitted);

void bind_point_set_functions(py::module_& m);
void bind_fitting(py::module_& m);
void bind_io(py::module_& m);
/// _run_tool: the `wavejets` tool in this process (wavejets.distributed's steps; src/tool.cpp).
void bind_tool(py::module_& m);

} // namespace wavejets_python

#endif // WAVEJETS_PYTHON_BINDINGS_H
