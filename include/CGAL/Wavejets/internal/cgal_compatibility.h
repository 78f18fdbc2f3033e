// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_CGAL_COMPATIBILITY_H
#define CGAL_WAVEJETS_INTERNAL_CGAL_COMPATIBILITY_H

// The one place where the package meets what differs between the CGAL releases it supports
// (5.5 to 6.1). Everything else calls these names, never the version-specific CGAL ones.
//
// - Whether a normal map is available. CGAL 5.5's Point_set_processing_3_np_helper has a
//   static constexpr `has_normal_map()` without arguments; CGAL 6 replaced it by
//   `has_normal_map(range, np)`, which is only constexpr for plain ranges and is a run-time
//   check for a Point_set_3. The package answers both questions itself, from public API only
//   (`is_default_parameter` and `Point_set_3::has_normal_map()`), identically on every version.
// - Looking up an existing property of a Point_set_3 by name: `property_map<T>(name)` returns a
//   std::pair<map, bool> in CGAL 5.5 and a std::optional<map> in CGAL 6 (used by the tool).

#include <CGAL/Named_function_parameters.h>
#include <CGAL/version.h>

#include <string>
#include <type_traits>
#include <utility>

#if CGAL_VERSION_NR < 1050501000
#error "CGAL Wavejets needs CGAL 5.5 or newer"
#endif

namespace CGAL {
template <class Point, class Vector> class Point_set_3;

namespace Wavejets {
namespace internal {

template <class PointRange>
struct Is_point_set_3 : std::false_type {};
template <class Point, class Vector>
struct Is_point_set_3<CGAL::Point_set_3<Point, Vector> > : std::true_type {};

/// Whether the named parameters name a normal map.
template <class NP>
constexpr bool has_normal_map_parameter()
{
  return !CGAL::parameters::is_default_parameter<NP, CGAL::internal_np::normal_t>::value;
}

/// Compile-time: whether a normal map can exist for this range and these parameters
/// (given in `np`, or the range is a `Point_set_3`, whose normal map is checked at run time).
template <class PointRange, class NP>
constexpr bool may_have_normal_map()
{
  return has_normal_map_parameter<NP>() || Is_point_set_3<std::remove_cv_t<PointRange> >::value;
}

/// Run time: whether a normal map is available (a `Point_set_3` counts only if it has normals).
template <class Point, class Vector, class NP>
bool has_normal_map(const CGAL::Point_set_3<Point, Vector>& ps, const NP&)
{
  return has_normal_map_parameter<NP>() || ps.has_normal_map();
}
template <class PointRange, class NP>
bool has_normal_map(const PointRange&, const NP&)
{
  return has_normal_map_parameter<NP>();
}

/// The property `name` of value type `T` of a `Point_set_3` (include `CGAL/Point_set_3.h` first), and
/// whether it exists, on every supported CGAL release.
template <class T, class Point, class Vector>
std::pair<typename CGAL::Point_set_3<Point, Vector>::template Property_map<T>, bool>
find_property_map(const CGAL::Point_set_3<Point, Vector>& points, const std::string& name)
{
#if CGAL_VERSION_NR >= 1060000000
  const auto map = points.template property_map<T>(name);
  if(map) return std::make_pair(*map, true);
  return std::make_pair(typename CGAL::Point_set_3<Point, Vector>::template Property_map<T>(), false);
#else
  return points.template property_map<T>(name);
#endif
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_CGAL_COMPATIBILITY_H
