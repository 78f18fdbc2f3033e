// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// The settings of a call, the checks of its arrays, and the interruptible runner (bindings.h).
#include "bindings.h"

#include <pybind11/stl.h>

#include <CGAL/Wavejets/Function_defaults.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/info.h>
#include <tbb/task_arena.h>
#endif

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

namespace wavejets_python {

namespace {

template <class T>
void read_if_given(const py::dict& d, const char* key, T& value)
{
  if(d.contains(key) && !d[key].is_none()) value = d[key].cast<T>();
}

} // namespace

Call read_call(const py::dict& d, CGAL::Wavejets::Point_set_function function, std::size_t number_of_points)
{
  const CGAL::Wavejets::Function_defaults defaults = CGAL::Wavejets::function_defaults(function);
  Call c;
  c.number_of_points = number_of_points;
  c.order = defaults.order;
  c.fitting = defaults.fitting;
  read_if_given(d, "order", c.order);
  long k = long(CGAL::Wavejets::default_number_of_neighbors(c.order));
  read_if_given(d, "k", k);
  if(k < 0 || k > long(std::numeric_limits<unsigned int>::max())) throw py::value_error("k: out of range");
  c.k = unsigned(k);
  // Per-point k, order and radius: uint32 and float64 arrays of N values, checked by the Python layer.
  auto read_per_point = [&](const char* key, auto& out) {
    if(!d.contains(key) || d[key].is_none()) return;
    out = d[key].cast<typename std::decay_t<decltype(out)>::value_type>();
    if(out->ndim() != 1 || std::size_t(out->shape(0)) != number_of_points)
      throw py::value_error(std::string(key) + ": expected one value per point");
  };
  read_per_point("k_per_point", c.k_per_point);
  read_per_point("order_per_point", c.order_per_point);
  read_per_point("radius_per_point", c.radius_per_point);
  read_if_given(d, "neighborhood_sizes", c.neighborhood_sizes);
  read_if_given(d, "neighbor_radius", c.neighbor_radius);
  read_if_given(d, "neighbors_per_coefficient", c.fitting.neighbors_per_coefficient);
  read_if_given(d, "minimum_order", c.fitting.minimum_order);
  read_if_given(d, "correction_iterations", c.fitting.correction_iterations);
  read_if_given(d, "tangent_plane_order", c.fitting.tangent_plane_order);
  read_if_given(d, "robust_iterations", c.fitting.robust_iterations);
  read_if_given(d, "neighbor_normal_weight", c.fitting.neighbor_normal_weight);
  read_if_given(d, "compact_weights", c.fitting.compact_weights);
  std::string frame = "initial";
  read_if_given(d, "curvature_frame", frame);
  if(frame != "initial" && frame != "tangent")
    throw py::value_error("curvature_frame: expected 'initial' or 'tangent', got '" + frame + "'");
  c.fitting.curvature_frame = frame == "initial" ? CGAL::Wavejets::Curvature_frame::INITIAL_FRAME
                                                 : CGAL::Wavejets::Curvature_frame::TANGENT_FRAME;
  read_if_given(d, "orient_with_input_normals", c.orient_with_input_normals);
  read_if_given(d, "seed_with_input_normals", c.seed_with_input_normals);
  read_if_given(d, "restrict_to_consistent_normals", c.restrict_to_consistent_normals);
  read_if_given(d, "use_neighbor_normals", c.use_neighbor_normals);
  read_if_given(d, "gain", c.gain);
  read_if_given(d, "evaluation_radius", c.evaluation_radius);
  if(d.contains("maximum_displacement") && !d["maximum_displacement"].is_none())
    c.maximum_displacement = d["maximum_displacement"].cast<double>();
  read_if_given(d, "write_normals", c.write_normals);
  read_if_given(d, "move_along_input_normals", c.move_along_input_normals);
  read_if_given(d, "threads", c.threads);
  if(c.threads < 0) throw py::value_error("threads: must be >= 1 (or None: all cores)");
  c.progress = d.contains("progress") ? py::object(d["progress"]) : py::object(py::none());
  return c;
}

void check_coordinates(const Coordinates& a, const char* name, long rows)
{
  if(a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for(py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    throw py::value_error(std::string(name) + ": expected an (N, 3) array, got shape " + shape +
                          (a.ndim() == 1 ? ",)" : ")"));
  }
  if(rows >= 0 && a.shape(0) != rows)
    throw py::value_error(std::string(name) + ": expected " + std::to_string(rows) + " rows (one per point), got " +
                          std::to_string(a.shape(0)));
  const double* v = a.data();
  for(py::ssize_t i = 0; i < 3 * a.shape(0); ++i)
    if(!std::isfinite(v[i]))
      throw py::value_error(std::string(name) + ": row " + std::to_string(i / 3) +
                            " has a NaN or infinite coordinate");
}

Coordinates copy_or_zeros(const py::object& source, std::size_t n)
{
  if(source.is_none() || n == 0) return zeros<double>({py::ssize_t(n), 3});
  Coordinates out({py::ssize_t(n), py::ssize_t(3)});
  std::memcpy(out.mutable_data(), source.cast<Coordinates>().data(), 3 * n * sizeof(double));
  return out;
}

CGAL::Wavejets::Processing_report
run_interruptibly(const Call& call,
                  const std::function<CGAL::Wavejets::Processing_report(const std::function<bool(double)>&)>& compute)
{
  std::atomic<double> fraction(0.);
  std::atomic<bool> stop(false);
  const std::function<bool(double)> callback = [&](double x) {
    fraction = x;
    return !stop.load();
  };
  CGAL::Wavejets::Processing_report report;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  bool python_error = false;   // a signal handler or the progress callable raised
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
#ifdef CGAL_LINKED_WITH_TBB
        tbb::task_arena arena(call.threads > 0 ? call.threads : tbb::info::default_concurrency());
        arena.execute([&] { report = compute(callback); });
#else
        report = compute(callback);
#endif
      } catch(...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      done = true;
      finished.notify_all();
    });
    for(;;) {
      {
        std::unique_lock<std::mutex> lock(mutex);
        if(finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; })) break;
      }
      if(python_error) continue;   // stopping: wait for the worker
      py::gil_scoped_acquire acquire;
      if(PyErr_CheckSignals() != 0) {   // e.g. KeyboardInterrupt, left pending until the worker stops
        python_error = true;
        stop = true;
        continue;
      }
      if(!call.progress.is_none()) {
        try {
          call.progress(fraction.load());
        } catch(py::error_already_set& e) {
          e.restore();
          python_error = true;
          stop = true;
        }
      }
    }
    worker.join();
  }
  if(python_error) throw py::error_already_set();
  if(failure) std::rethrow_exception(failure);
  if(!call.progress.is_none()) call.progress(1.);
  return report;
}

py::object make_report(const CGAL::Wavejets::Processing_report& r, const py::array_t<bool>& fitted)
{
  py::object report_class = py::module_::import("wavejets._report").attr("Report");
  return report_class(py::arg("number_of_points") = r.number_of_points,
                      py::arg("number_of_fitted_points") = r.number_of_fitted_points,
                      py::arg("number_of_unfitted_points") = r.number_of_unfitted_points,
                      py::arg("number_of_non_finite_points") = r.number_of_non_finite_points,
                      py::arg("number_of_reduced_order_points") = r.number_of_reduced_order_points,
                      py::arg("number_of_clamped_points") = r.number_of_clamped_points,
                      py::arg("moves_points") = r.moves_points, py::arg("fitted") = fitted);
}

} // namespace wavejets_python
