// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// wavejets.read / wavejets.write: the `wavejets` tool's reading and writing (demo/Wavejets/
// point_set_io.h, through CGAL's IO), on NumPy arrays.
#include "bindings.h"

#include "point_set_io.h"

#include <pybind11/stl.h>

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
    std::tie(d, found) = in.points.property_map<double>(name);
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
    if(name == "x" || name == "y" || name == "z" || name == "nx" || name == "ny" || name == "nz" || !ps.add_property_map<double>(name, 0.).second)
      throw py::value_error("properties['" + name + "']: the name is taken (x, y, z, nx, ny, nz or a duplicate)");
    Point_set::Property_map<double> d = ps.property_map<double>(name).first;
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

} // namespace

void bind_io(py::module_& m)
{
  m.def("read", &read, "Low-level binding: use wavejets.read.", py::arg("path"));
  m.def("write", &write, "Low-level binding: use wavejets.write.", py::arg("path"), py::arg("points"), py::arg("normals"),
        py::arg("faces"), py::arg("properties"), py::arg("ascii"));
}

} // namespace wavejets_python
