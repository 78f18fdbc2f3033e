// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_TEST_DATA_H
#define WAVEJETS_TEST_DATA_H

// The data files of the tests of the point-set functions (run from test/Wavejets: data/ is
// examples/Wavejets/data): the kitten scan, and random samples of the meshes.

#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/point_generators_3.h>

#include <stdexcept>
#include <string>

#include "wavejets_test_types.h"

namespace wavejets_test {

/// data/kitten.xyz with its normals, read once.
inline const types::PV_range& kitten()
{
  static const types::PV_range pts = [] {
    types::PV_range v;
    if(!types::read_xyz("data/kitten.xyz", v)) throw std::runtime_error("cannot read data/kitten.xyz");
    return v;
  }();
  return pts;
}

/// `n` random points on the mesh `path` (uniform over its area), each with the vector `normal`; the
/// same points for the same `seed`.
inline types::PV_range sample_mesh(const std::string& path, std::size_t n, int seed, const types::Vector& normal)
{
  CGAL::Surface_mesh<types::Point> mesh;
  if(!CGAL::IO::read_polygon_mesh(path, mesh) || mesh.number_of_faces() == 0)
    throw std::runtime_error("cannot read " + path);
  types::PV_range v;
  // The generator draws the triangle with `random` but the point inside it with
  // CGAL::get_default_random() (CGAL 5.5.1): seed both, or the sample changes from run to run.
  CGAL::Random random(seed);
  CGAL::get_default_random() = CGAL::Random(seed + 1);
  CGAL::Random_points_in_triangle_mesh_3<CGAL::Surface_mesh<types::Point> > gen(mesh, random);
  for(std::size_t i = 0; i < n; ++i, ++gen) v.emplace_back(*gen, normal);
  return v;
}

} // namespace wavejets_test

#endif // WAVEJETS_TEST_DATA_H
