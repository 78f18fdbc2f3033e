// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_BENCH_KNN_ALTERNATIVES_H
#define WAVEJETS_BENCH_KNN_ALTERNATIVES_H

// Benchmark only: three other ways to get the neighbor lists of CGAL::Wavejets::internal::Neighbor_query
// (the k nearest of point i, i excluded, nearest first, ties by index), to measure how far the
// package's k-NN search is from the fastest one found (bench_speed's k-NN table).
//   Cgal_k_neighbor_search: CGAL's kd-tree (sliding midpoint, 24 points per leaf) and
//     Orthogonal_k_neighbor_search for k + 1 points, the query dropped, sorted by (distance, index):
//     the package's search before its own kd-tree (kd_tree.h). Where several points tie at the
//     k-th distance, CGAL keeps any of them, not the smallest indices (on a regular grid its lists
//     differ; on a random sample they do not).
// The next two are exact: they collect every point of a ball that holds at least k others, then
// select and sort.
//   Ball_from_previous: CGAL's kd-tree as the package builds it, searched with a sphere of 1.15
//     times the previous query's k-th distance (the queries come in the kd-tree's leaf order, so
//     the previous point is close), grown by 1.5 until it holds k points.
//   Uniform_grid: points sorted by cell of a uniform grid (coordinates stored by cell), every cell
//     that meets the ball's bounding box scanned. Fast when the density is uniform, as on the
//     bunny sample; not a candidate for the package: where the density varies 10x, the cells of the
//     dense parts hold 100 times too many points.

#include <CGAL/Wavejets/internal/neighbor_query.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/property_map.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace wavejets_bench {

typedef CGAL::Simple_cartesian<double>::Point_3 Knn_point;
// The package's neighbor record and its order (distance, then index), so that the selection and
// the sort below cost what they cost in the package.
typedef CGAL::Wavejets::internal::Neighbor_query Package_query;
typedef std::vector<Package_query::Candidate> Knn_candidates;

/// The k first of the candidates, by distance then index, into `out`, as the package orders its
/// own lists (Neighbor_query::append_nearest_indices_in_order()).
inline void select_nearest(Knn_candidates& candidates, unsigned int k, std::vector<std::size_t>& out)
{
  static thread_local Knn_candidates buffer;
  out.clear();
  Package_query::append_nearest_indices_in_order(candidates, (std::min)(std::size_t(k), candidates.size()), out, buffer);
}

/// CGAL's kd-tree over all the points as the package built it before kd_tree.h (sliding midpoint,
/// 24 points per leaf, coordinates cached), shared by the two CGAL searches below.
class Cgal_tree
{
protected:
  typedef CGAL::Search_traits_3<CGAL::Simple_cartesian<double> > Base_traits;
  typedef CGAL::Pointer_property_map<Knn_point>::const_type Index_map;
  typedef CGAL::Search_traits_adapter<std::size_t, Index_map, Base_traits> Traits;
  typedef CGAL::Sliding_midpoint<Traits> Splitter;
  typedef CGAL::Kd_tree<Traits, Splitter, CGAL::Tag_true, CGAL::Tag_true> Tree;

public:
  explicit Cgal_tree(const std::vector<Knn_point>& points)
    : m_points(points), m_map(CGAL::make_property_map(points)), m_traits(m_map), m_tree(Splitter(24), m_traits)
  {
    std::vector<std::size_t> indices(points.size());
    for(std::size_t i = 0; i < points.size(); ++i) indices[i] = i;
    m_tree.insert(indices.begin(), indices.end());
    m_tree.build();
  }

  /// The kd-tree's leaf order.
  std::vector<std::size_t> leaf_order() const
  {
    std::vector<std::size_t> order;
    m_tree.root()->tree_items(std::back_inserter(order));
    return order;
  }

protected:
  const std::vector<Knn_point>& m_points;
  Index_map m_map;
  Traits m_traits;
  Tree m_tree;
};

class Cgal_k_neighbor_search : public Cgal_tree
{
  typedef CGAL::Distance_adapter<std::size_t, Index_map, CGAL::Euclidean_distance<Base_traits> > Distance;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits, Distance, Splitter, Tree> Knn;

public:
  explicit Cgal_k_neighbor_search(const std::vector<Knn_point>& points) : Cgal_tree(points), m_distance(m_map) {}

  void neighbors(std::size_t i, unsigned int k, std::vector<std::size_t>& out, Knn_candidates& candidates) const
  {
    candidates.clear();
    Knn search(m_tree, m_points[i], (std::min<std::size_t>)(std::size_t(k) + 1, m_points.size()), 0., true, m_distance, false);
    for(typename Knn::iterator it = search.begin(); it != search.end(); ++it)
      if(it->first != i) candidates.push_back(Package_query::candidate(it->second, it->first));
    select_nearest(candidates, k, out);
  }

private:
  Distance m_distance;
};

class Ball_from_previous : public Cgal_tree
{
  typedef CGAL::Fuzzy_sphere<Traits> Sphere;

  struct Collector
  {
    const std::vector<Knn_point>* points;
    Knn_candidates* out;
    std::size_t query;
    void operator()(std::size_t j) const
    {
      if(j != query) out->push_back(Package_query::candidate(CGAL::squared_distance((*points)[query], (*points)[j]), j));
    }
  };

public:
  explicit Ball_from_previous(const std::vector<Knn_point>& points) : Cgal_tree(points) {}

  /// `radius`: the previous query's k-th distance (0 for the first query); updated to this one's.
  void neighbors(std::size_t i, unsigned int k, double& radius, std::vector<std::size_t>& out,
                 Knn_candidates& candidates) const
  {
    double r = radius > 0. ? 1.15 * radius : 0.;
    for(;;)
    {
      candidates.clear();
      if(r > 0.)
        m_tree.search(boost::make_function_output_iterator(Collector{&m_points, &candidates, i}),
                      Sphere(m_points[i], r, 0., m_traits));
      if(candidates.size() >= k || candidates.size() + 1 >= m_points.size())
        break;
      r = r > 0. ? 1.5 * r : first_radius(i, k);
    }
    select_nearest(candidates, k, out);
    if(!out.empty()) radius = std::sqrt(CGAL::squared_distance(m_points[i], m_points[out.back()]));
  }

private:
  // A radius that holds k points around i: that of k + 1 points of i's leaf region (bounding box).
  double first_radius(std::size_t i, unsigned int k) const
  {
    double r = 0.;
    for(std::size_t j = 0; j < m_points.size() && j <= k + 1; ++j)
      r = (std::max)(r, std::sqrt(CGAL::squared_distance(m_points[i], m_points[j])));
    return r > 0. ? r : 1.;
  }
};

class Uniform_grid
{
public:
  /// `cell`: the cell's side (bench_speed uses the mean k-th neighbor distance of a few points).
  Uniform_grid(const std::vector<Knn_point>& points, double cell) : m_points(points)
  {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for(const Knn_point& p : points)
      for(int a = 0; a < 3; ++a)
      {
        lo[a] = (std::min)(lo[a], p[a]);
        hi[a] = (std::max)(hi[a], p[a]);
      }
    m_inverse_cell = cell > 0. && std::isfinite(cell) ? 1. / cell : 1.; // all points equal: any cell
    for(int a = 0; a < 3; ++a)
    {
      m_origin[a] = lo[a];
      m_size[a] = long((hi[a] - lo[a]) * m_inverse_cell) + 1;
    }
    std::vector<std::uint32_t> cell_of(points.size());
    m_start.assign(std::size_t(m_size[0] * m_size[1] * m_size[2] + 1), 0);
    for(std::size_t i = 0; i < points.size(); ++i)
    {
      const long c[3] = {clamped_cell(points[i][0], 0), clamped_cell(points[i][1], 1), clamped_cell(points[i][2], 2)};
      cell_of[i] = std::uint32_t((c[2] * m_size[1] + c[1]) * m_size[0] + c[0]);
      ++m_start[cell_of[i] + 1];
    }
    for(std::size_t c = 0; c + 1 < m_start.size(); ++c) m_start[c + 1] += m_start[c];
    std::vector<std::uint32_t> next(m_start.begin(), m_start.end() - 1);
    for(int a = 0; a < 3; ++a) m_coordinates[a].resize(points.size());
    m_index.resize(points.size());
    for(std::size_t i = 0; i < points.size(); ++i)
    {
      const std::uint32_t s = next[cell_of[i]]++;
      for(int a = 0; a < 3; ++a) m_coordinates[a][s] = points[i][a];
      m_index[s] = std::uint32_t(i);
    }
  }

  /// `radius`: a guess of i's k-th distance (the previous query's), updated to this one's.
  void neighbors(std::size_t i, unsigned int k, double& radius, std::vector<std::size_t>& out,
                 Knn_candidates& candidates) const
  {
    const Knn_point& p = m_points[i];
    double r = radius > 0. ? 1.15 * radius : 1. / m_inverse_cell;
    for(;;)
    {
      candidates.clear();
      const double r2 = r * r;
      long first[3], last[3];
      for(int a = 0; a < 3; ++a)
      {
        first[a] = clamped_cell(p[a] - r, a);
        last[a] = clamped_cell(p[a] + r, a);
      }
      for(long z = first[2]; z <= last[2]; ++z)
        for(long y = first[1]; y <= last[1]; ++y)
        {
          const long row = (z * m_size[1] + y) * m_size[0];
          for(std::uint32_t s = m_start[std::size_t(row + first[0])], e = m_start[std::size_t(row + last[0] + 1)]; s < e; ++s)
          {
            const double dx = m_coordinates[0][s] - p[0], dy = m_coordinates[1][s] - p[1], dz = m_coordinates[2][s] - p[2];
            const double d2 = dx * dx + dy * dy + dz * dz;
            if(d2 <= r2 && m_index[s] != i) candidates.push_back(Package_query::candidate(d2, m_index[s]));
          }
        }
      if(candidates.size() >= k || candidates.size() + 1 >= m_points.size())
        break;
      r *= 1.5;
    }
    select_nearest(candidates, k, out);
    if(!out.empty()) radius = std::sqrt(CGAL::squared_distance(p, m_points[out.back()]));
  }

private:
  long clamped_cell(double coordinate, int axis) const
  {
    const long c = long(std::floor((coordinate - m_origin[axis]) * m_inverse_cell));
    return c < 0 ? 0 : (c >= m_size[axis] ? m_size[axis] - 1 : c);
  }

  const std::vector<Knn_point>& m_points;
  double m_origin[3], m_inverse_cell;
  long m_size[3];
  std::vector<std::uint32_t> m_start, m_index;
  std::vector<double> m_coordinates[3];
};

} // namespace wavejets_bench

#endif // WAVEJETS_BENCH_KNN_ALTERNATIVES_H
