// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_BENCH_CGAL_K_NEIGHBOR_SEARCH_H
#define WAVEJETS_BENCH_CGAL_K_NEIGHBOR_SEARCH_H

// Benchmark only: the neighbor lists of CGAL::Wavejets::internal::Neighbor_query (the k nearest of point i,
// i excluded, nearest first, ties by index) found with CGAL's own k-NN search, the alternative a user has:
// CGAL's kd-tree (sliding midpoint, 24 points per leaf) and Orthogonal_k_neighbor_search for k + 1 points, the
// query dropped, sorted by (distance, index). This was the package's search before its own kd-tree (kd_tree.h).
// Where several points tie at the k-th distance, CGAL keeps any of them, not the smallest indices (on a
// regular grid its lists differ; on a random sample they do not). bench_speed times it against
// Neighbor_query (results.md, section k-NN search).

#include <CGAL/Wavejets/internal/neighbor_query.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cstddef>
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
  Package_query::append_nearest_indices_in_order(candidates, (std::min)(std::size_t(k), candidates.size()), out,
                                                 buffer);
}

/// CGAL's kd-tree over all the points as the package built it before kd_tree.h (sliding midpoint,
/// 24 points per leaf, coordinates cached), searched by Cgal_k_neighbor_search below.
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
    Knn search(m_tree, m_points[i], (std::min<std::size_t>)(std::size_t(k) + 1, m_points.size()), 0., true, m_distance,
               false);
    for(typename Knn::iterator it = search.begin(); it != search.end(); ++it)
      if(it->first != i) candidates.push_back(Package_query::candidate(it->second, it->first));
    select_nearest(candidates, k, out);
  }

private:
  Distance m_distance;
};

} // namespace wavejets_bench

#endif // WAVEJETS_BENCH_CGAL_K_NEIGHBOR_SEARCH_H
