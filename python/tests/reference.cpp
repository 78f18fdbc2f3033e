// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// The C++ side of the Python tests (test_against_cpp.py): calls one point-set function as a C++
// user does, on a CGAL::Point_set_3 read from a file, and writes its results as raw doubles, for
// the Python module's results to be compared with, bit for bit.
//
//   wavejets_python_reference FUNCTION IN OUT K ORDER [GAIN_RE GAIN_IM]
//
// FUNCTION: estimate_normals | estimate_curvatures | enhance_positions | enhance_normals |
// estimate_scales (K unused: the default ladder of ORDER; OUT: the chosen sizes, then the descriptor).
// IN: read by the `wavejets` tool's reader (a point set without normals gets none, except for the
// functions that need a normal map: zero normals then, as the Python module passes).
// OUT: the result arrays, in the order of the Python function's outputs, as little-endian doubles
// (N x 3 for vectors), then one byte per point: fitted or not.
#include "point_set_io.h"

#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_scales.h>

#include <chrono>
#include <complex>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using wavejets_demo::Point_set;
using wavejets_demo::Vector;
namespace WP = CGAL::Wavejets::parameters;

namespace {

std::vector<char> fitted_bytes;
std::chrono::steady_clock::time_point call_start;
double call_seconds = 0.;
void call_started() { call_start = std::chrono::steady_clock::now(); }
void call_done() { call_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - call_start).count(); }

struct Fitted_map
{
  typedef Point_set::Index key_type;
  typedef bool value_type;
  typedef bool reference;
  typedef boost::writable_property_map_tag category;
  friend void put(const Fitted_map&, key_type i, bool v) { fitted_bytes[std::size_t(i)] = v ? 1 : 0; }
};

void write_vectors(std::ofstream& os, const Point_set& ps, const Point_set::Property_map<Vector>& m)
{
  for(Point_set::Index i : ps) {
    const double v[3] = {m[i].x(), m[i].y(), m[i].z()};
    os.write(reinterpret_cast<const char*>(v), sizeof v);
  }
}

void write_scalars(std::ofstream& os, const Point_set& ps, const Point_set::Property_map<double>& m)
{
  for(Point_set::Index i : ps) os.write(reinterpret_cast<const char*>(&m[i]), sizeof(double));
}

} // namespace

int main(int argc, char** argv)
{
  if(argc < 6) {
    std::cerr << "usage: " << argv[0] << " FUNCTION IN OUT K ORDER [GAIN_RE GAIN_IM]\n";
    return 2;
  }
  const std::string function = argv[1];
  wavejets_demo::Input in = wavejets_demo::read_input(argv[2]);
  Point_set& ps = in.points;
  const unsigned k = unsigned(std::atol(argv[4]));
  const std::size_t order = std::size_t(std::atol(argv[5]));
  const std::complex<double> gain(argc > 6 ? std::atof(argv[6]) : 2., argc > 7 ? std::atof(argv[7]) : 0.);
  fitted_bytes.assign(ps.size(), 0);
  std::ofstream os(argv[3], std::ios::binary);
  const bool had_normals = ps.has_normal_map();

  if(function == "estimate_normals") {
    if(!had_normals) ps.add_normal_map(Vector(0, 0, 0));
    call_started();
    CGAL::wavejet_estimate_normals<CGAL::Parallel_tag>(ps, k,
      WP::order(order).orient_with_input_normals(had_normals).fitted_map(Fitted_map())
        .point_map(ps.point_map()).normal_map(ps.normal_map()));
    call_done();
    write_vectors(os, ps, ps.normal_map());
  } else if(function == "estimate_curvatures") {
    Point_set::Property_map<double> H = ps.add_property_map<double>("H", 0.).first, K = ps.add_property_map<double>("K", 0.).first,
                                    k1 = ps.add_property_map<double>("k1", 0.).first, k2 = ps.add_property_map<double>("k2", 0.).first;
    Point_set::Property_map<Vector> d1 = ps.add_property_map<Vector>("d1", Vector(0, 0, 0)).first,
                                    d2 = ps.add_property_map<Vector>("d2", Vector(0, 0, 0)).first;
    const auto np = WP::order(order).mean_curvature_map(H).gaussian_curvature_map(K).maximal_principal_curvature_map(k1)
                      .minimal_principal_curvature_map(k2).maximal_principal_direction_map(d1)
                      .minimal_principal_direction_map(d2).fitted_map(Fitted_map());
    call_started();
    if(had_normals)
      CGAL::wavejet_estimate_curvatures<CGAL::Parallel_tag>(ps, k, np.point_map(ps.point_map()).normal_map(ps.normal_map()));
    else
      CGAL::wavejet_estimate_curvatures<CGAL::Parallel_tag>(ps, k, np.point_map(ps.point_map()));
    call_done();
    for(const auto& m : {H, K, k1, k2}) write_scalars(os, ps, m);
    write_vectors(os, ps, d1);
    write_vectors(os, ps, d2);
  } else if(function == "enhance_positions") {
    const auto np = WP::order(order).write_normals(had_normals).fitted_map(Fitted_map());
    call_started();
    if(had_normals)
      CGAL::wavejet_enhance_positions<CGAL::Parallel_tag>(ps, k, gain.real(), np.point_map(ps.point_map()).normal_map(ps.normal_map()));
    else
      CGAL::wavejet_enhance_positions<CGAL::Parallel_tag>(ps, k, gain.real(), np.point_map(ps.point_map()));
    call_done();
    for(Point_set::Index i : ps) {
      const double p[3] = {ps.point(i).x(), ps.point(i).y(), ps.point(i).z()};
      os.write(reinterpret_cast<const char*>(p), sizeof p);
    }
    if(had_normals) write_vectors(os, ps, ps.normal_map());
  } else if(function == "enhance_normals") {
    if(!had_normals) ps.add_normal_map(Vector(0, 0, 0));
    call_started();
    CGAL::wavejet_enhance_normals<CGAL::Parallel_tag>(ps, k, gain,
      WP::order(order).fitted_map(Fitted_map()).point_map(ps.point_map()).normal_map(ps.normal_map()));
    call_done();
    write_vectors(os, ps, ps.normal_map());
  } else if(function == "estimate_scales") {
    Point_set::Property_map<unsigned int> sizes = ps.add_property_map<unsigned int>("scale_k", 0u).first;
    Point_set::Property_map<std::vector<double> > descriptor =
      ps.add_property_map<std::vector<double> >("descriptor", std::vector<double>()).first;
    call_started();
    CGAL::wavejet_estimate_scales<CGAL::Parallel_tag>(ps, WP::order(order).neighborhood_size_map(sizes)
      .scale_descriptor_map(descriptor).fitted_map(Fitted_map()).point_map(ps.point_map()));
    call_done();
    for(Point_set::Index i : ps) {
      const double size = sizes[i];
      os.write(reinterpret_cast<const char*>(&size), sizeof size);
    }
    const std::size_t J = CGAL::Wavejets::default_neighborhood_sizes(order).size();
    for(Point_set::Index i : ps)
      for(std::size_t j = 0; j < J; ++j) {
        const double value = j < descriptor[i].size() ? descriptor[i][j] : 0.;
        os.write(reinterpret_cast<const char*>(&value), sizeof value);
      }
  } else {
    std::cerr << "unknown function " << function << "\n";
    return 2;
  }
  os.write(fitted_bytes.data(), std::streamsize(fitted_bytes.size()));
  if(std::getenv("WAVEJETS_REFERENCE_TIME")) std::cout << "seconds " << call_seconds << std::endl;
  return os ? EXIT_SUCCESS : EXIT_FAILURE;
}
