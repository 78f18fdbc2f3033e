// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// wavejets.read / wavejets.write / wavejets.render: the `wavejets` tool's reading and writing
// (demo/Wavejets/point_set_io.h, through CGAL's IO) and its renderer (demo/Wavejets/render.h), on
// NumPy arrays.
#include "bindings.h"

#include "point_set_io.h"
#include "render.h"

#include <CGAL/Wavejets/internal/cgal_compatibility.h>

#include <CGAL/compute_average_spacing.h>

#include <pybind11/stl.h>

#include <array>
#include <tuple>
#include <utility>
#include <string>
#include <vector>

namespace wavejets_python {

namespace {

using wavejets_demo::Point_set;

py::object faces_to_python(const wavejets_demo::Faces& faces)
{
  bool triangles = true;
  for(const std::vector<std::size_t>& f : faces) triangles = triangles && f.size() == 3;
  if(!triangles) return py::cast(faces);
  py::array_t<std::int64_t> a({py::ssize_t(faces.size()), py::ssize_t(3)});
  std::int64_t* p = a.mutable_data();
  for(const std::vector<std::size_t>& f : faces)
    for(std::size_t v : f) *p++ = std::int64_t(v);
  return a;
}

py::tuple read(const std::string& path)
{
  wavejets_demo::Input in;
  try {
    py::gil_scoped_release release;
    in = wavejets_demo::read_input(path);
  } catch(const wavejets_demo::File_error& e) {
    throw py::value_error(e.what());
  }
  const std::size_t n = in.points.size();
  Coordinates points({py::ssize_t(n), py::ssize_t(3)});
  double* p = points.mutable_data();
  for(Point_set::Index i : in.points) {
    const Point& q = in.points.point(i);
    *p++ = q.x(); *p++ = q.y(); *p++ = q.z();
  }
  py::object normals = py::none();
  if(in.points.has_normal_map()) {
    Coordinates m({py::ssize_t(n), py::ssize_t(3)});
    double* q = m.mutable_data();
    for(Point_set::Index i : in.points) {
      const Vector& v = in.points.normal(i);
      *q++ = v.x(); *q++ = v.y(); *q++ = v.z();
    }
    normals = m;
  }
  py::dict properties;
  for(const std::string& name : in.points.properties()) {
    Point_set::Property_map<double> d;
    bool found = false;
    std::tie(d, found) = CGAL::Wavejets::internal::find_property_map<double>(in.points, name);
    if(!found) continue;
    py::array_t<double> values{py::ssize_t(n)};
    double* v = values.mutable_data();
    for(Point_set::Index i : in.points) *v++ = d[i];
    properties[py::str(name)] = values;
  }
  return py::make_tuple(points, normals, in.is_mesh() ? faces_to_python(in.faces) : py::object(py::none()), properties);
}

void write(const std::string& path, const Coordinates& points, const py::object& normals, const py::object& faces,
           const py::dict& properties, bool ascii)
{
  check_coordinates(points, "points");
  const std::size_t n = std::size_t(points.shape(0));
  Point_set ps;
  ps.reserve(n);
  const double* p = points.data();
  for(std::size_t i = 0; i < n; ++i, p += 3) ps.insert(Point(p[0], p[1], p[2]));
  if(!normals.is_none()) {
    const Coordinates m = normals.cast<Coordinates>();
    check_coordinates(m, "normals", long(n));
    ps.add_normal_map();
    const double* q = m.data();
    for(Point_set::Index i : ps) { ps.normal(i) = Vector(q[0], q[1], q[2]); q += 3; }
  }
  for(const auto& item : properties) {
    const std::string name = py::str(item.first);
    const py::array_t<double, py::array::c_style | py::array::forcecast> values =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(item.second);
    if(!values || values.ndim() != 1 || std::size_t(values.shape(0)) != n)
      throw py::value_error("properties['" + name + "']: expected " + std::to_string(n) + " numbers (one per point)");
    const bool reserved = name == "x" || name == "y" || name == "z" || name == "nx" || name == "ny" || name == "nz";
    const std::pair<Point_set::Property_map<double>, bool> added =
      reserved ? std::make_pair(Point_set::Property_map<double>(), false) : ps.add_property_map<double>(name, 0.);
    if(!added.second)
      throw py::value_error("properties['" + name + "']: the name is taken (x, y, z, nx, ny, nz or a duplicate)");
    const Point_set::Property_map<double>& d = added.first;
    const double* v = values.data();
    for(Point_set::Index i : ps) d[i] = *v++;
  }
  wavejets_demo::Faces soup;
  if(!faces.is_none()) {
    soup = faces.cast<wavejets_demo::Faces>();
    for(std::size_t f = 0; f < soup.size(); ++f)
      for(std::size_t v : soup[f])
        if(v >= n)
          throw py::value_error("faces: face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + " but there are " +
                                std::to_string(n) + " points");
  }
  if(soup.empty() && wavejets_demo::output_format(path) != wavejets_demo::Output_format::PLY)
    throw py::value_error(path + ": a point set (no faces) is written as .ply");
  try {
    py::gil_scoped_release release;
    wavejets_demo::write_output(ps, soup, path, ascii, "written by the wavejets Python module");
  } catch(const wavejets_demo::File_error& e) {
    throw py::value_error(e.what());
  }
}

std::vector<wavejets_demo::Vec3> to_vec3(const Coordinates& a)
{
  std::vector<wavejets_demo::Vec3> v(std::size_t(a.shape(0)));
  const double* p = a.data();
  for(wavejets_demo::Vec3& x : v) { x = {{p[0], p[1], p[2]}}; p += 3; }
  return v;
}

/// Draws one point set (splats; `normals` required) or mesh (`faces`; without normals, the faces'
/// area-weighted vertex normals) into a PNG at `path`, written atomically. The Python layer checks
/// the arguments and supplies normals for a point set without.
void render(const std::string& path, const Coordinates& points, const py::object& normals, const py::object& faces,
            const py::object& values, int width, int height, const std::array<double, 3>& view,
            const std::array<double, 3>& up, double splat)
{
  check_coordinates(points, "points");
  if(!normals.is_none()) check_coordinates(normals.cast<Coordinates>(), "normals", long(points.shape(0)));
  wavejets_demo::Cloud cloud;
  cloud.points = to_vec3(points);
  if(!faces.is_none()) cloud.faces = faces.cast<wavejets_demo::Faces>();
  cloud.normals = normals.is_none() ? wavejets_demo::vertex_normals(cloud.points, cloud.faces)
                                    : to_vec3(normals.cast<Coordinates>());
  if(!values.is_none()) cloud.scalar = values.cast<std::vector<double> >();
  wavejets_demo::View_options options;
  options.width = width;
  options.height = height;
  options.view = view;
  options.up = up;
  options.splat = splat;
  py::gil_scoped_release release;
  if(cloud.points.size() >= 3) {   // the splat size (CGAL::compute_average_spacing needs 2 neighbors)
    const Index_range range = index_range(cloud.points.size());
    cloud.spacing = CGAL::compute_average_spacing<CGAL::Parallel_if_available_tag>(range, 6,
                      CGAL::parameters::point_map(Point_map{points.data(), nullptr}));
  }
  wavejets_demo::Image image;
  try {
    image = wavejets_demo::render({&cloud}, options);
  } catch(const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  try {
    wavejets_demo::Output_file out(path);
    try {
      wavejets_demo::write_png(image, out.temporary_path());
    } catch(const std::runtime_error& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
    out.commit();
  } catch(const std::runtime_error& e) {
    throw py::value_error(e.what());
  }
}

} // namespace

void bind_io(py::module_& m)
{
  m.def("read", &read, "Low-level binding: use wavejets.read.", py::arg("path"));
  m.def("write", &write, "Low-level binding: use wavejets.write.", py::arg("path"), py::arg("points"), py::arg("normals"),
        py::arg("faces"), py::arg("properties"), py::arg("ascii"));
  m.def("render", &render, "Low-level binding: use wavejets.render.", py::arg("path"), py::arg("points"), py::arg("normals"),
        py::arg("faces"), py::arg("values"), py::arg("width"), py::arg("height"), py::arg("view"), py::arg("up"),
        py::arg("splat"));
}

} // namespace wavejets_python
