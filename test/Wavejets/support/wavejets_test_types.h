// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_TEST_TYPES_H
#define WAVEJETS_TEST_TYPES_H

// The kernel and the point-with-normal types that the tests of the point-set functions share
// (`using namespace wavejets_test::types;`).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace wavejets_test {
namespace types {

typedef CGAL::Epick Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef std::pair<Point, Vector> PV; ///< a point with its normal
typedef std::vector<PV> PV_range;
typedef CGAL::First_of_pair_property_map<PV> Point_map;
typedef CGAL::Second_of_pair_property_map<PV> Normal_map;
typedef CGAL::Sequential_tag Seq;
#ifdef CGAL_LINKED_WITH_TBB
typedef CGAL::Parallel_tag Par;
#else
typedef CGAL::Sequential_tag Par; ///< without TBB, the parallel runs are sequential
#endif

/// Reads a point set with normals (e.g. data/kitten.xyz); false if unreadable or empty.
inline bool read_xyz(const std::string& fname, PV_range& pts)
{
  return CGAL::IO::read_points(fname, std::back_inserter(pts),
                               CGAL::parameters::point_map(Point_map()).normal_map(Normal_map())) &&
         !pts.empty();
}

} // namespace types
} // namespace wavejets_test

#endif // WAVEJETS_TEST_TYPES_H
