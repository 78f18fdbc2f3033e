// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the Wavejets package (https://github.com/cgal-wavejets/wavejets).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_NEIGHBOR_QUERY_H
#define CGAL_WAVEJETS_INTERNAL_NEIGHBOR_QUERY_H

// Neighborhoods by index over a copy of the positions (double precision), with CGAL spatial
// searching: k nearest, all within a radius, or the k nearest within a radius. The query point
// itself is never returned: the caller puts it first, so every fit is centered on its query
// point (CGAL 5.5.1's jet_smooth_point_set is not, with neighbor_radius). Non-finite points are
// kept out of the tree. The tree is built in the constructor; queries are const and thread safe.

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <iterator>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

class Neighbor_query
{
public:
  typedef Simple_cartesian<double> SC;
  typedef SC::Point_3 Point;
  typedef Pointer_property_map<Point>::const_type Index_map; // index -> point

  /// A neighbor as a search collects it: its squared distance and its index, ordered by distance,
  /// then index. Where the compiler has a 128-bit integer (GCC, Clang) the two are packed into one:
  /// the bits of a non-negative double order as the double does, so sorting the neighbors is one
  /// integer comparison per step, without branches (k-NN 1.15x faster at k 96, 1.09x at k 18 than
  /// sorting std::pair; the same order). Elsewhere, the std::pair.
#ifdef __SIZEOF_INT128__
  __extension__ typedef unsigned __int128 Candidate;
  static Candidate candidate(double squared_distance, std::size_t index)
  {
    static_assert(sizeof(std::size_t) <= sizeof(std::uint64_t), "the index takes the low 64 bits");
    std::uint64_t bits;
    std::memcpy(&bits, &squared_distance, sizeof bits);
    return (Candidate(bits) << 64) | Candidate(index);
  }
  static std::size_t index_of(const Candidate& c) { return std::size_t(std::uint64_t(c)); }
#else
  typedef std::pair<double, std::size_t> Candidate;
  static Candidate candidate(double squared_distance, std::size_t index) { return Candidate(squared_distance, index); }
  static std::size_t index_of(const Candidate& c) { return c.second; }
#endif
  /// Per-thread scratch of neighbors().
  typedef std::vector<Candidate> Scratch;

private:
  typedef Search_traits_3<SC> Base_traits;
  typedef Search_traits_adapter<std::size_t, Index_map, Base_traits> Traits;
  typedef Sliding_midpoint<Traits> Splitter;
  // Points per kd-tree leaf. CGAL's default is 10; 24 measured faster for every k we use
  // (100k bunny points, one thread: k 96 7.8 -> 7.2 us, k 32 2.75 -> 2.53 us, k 18 1.70 -> 1.53 us
  // per query) and gives the same neighbors.
  static constexpr unsigned int bucket_size = 24;
  typedef Distance_adapter<std::size_t, Index_map, Euclidean_distance<Base_traits> > Distance;
  typedef Kd_tree<Traits, Splitter, Tag_true, Tag_true> Tree;
  typedef Orthogonal_k_neighbor_search<Traits, Distance, Splitter, Tree> Knn;
  typedef Fuzzy_sphere<Traits> Sphere;

public:
  /// `points` must outlive the query; `in_tree[i]` false keeps point i out of every neighborhood.
  /// With `Parallel_tag` the kd-tree is built in parallel (CGAL's TBB build: the same tree, hence
  /// the same neighbors and processing order).
  template <class ConcurrencyTag = Sequential_tag>
  Neighbor_query(const std::vector<Point>& points, const std::vector<unsigned char>& in_tree,
                 ConcurrencyTag tag = ConcurrencyTag())
    : m_points(points), m_map(make_property_map(points)), m_traits(m_map), m_tree(Splitter(bucket_size), m_traits),
      m_distance(m_map)
  {
    std::vector<std::size_t> indices;
    for(std::size_t i = 0; i < points.size(); ++i)
      if(in_tree[i]) indices.push_back(i);
    m_tree.insert(indices.begin(), indices.end());
    m_size = indices.size();
    if(m_size > 0) // Kd_tree::build() requires points (an input of only non-finite points has none)
      build(tag);
  }

  /// All indices 0..N-1 in an order that keeps neighbors close together: the points of the tree in
  /// the kd-tree's leaf order, then those left out of it by index. Processing the points in this
  /// order instead of the input's keeps the tree nodes and the neighbors' coordinates in cache from
  /// one point to the next (a random input order otherwise misses the cache on every neighborhood
  /// once N is large).
  std::vector<std::size_t> processing_order() const
  {
    std::vector<std::size_t> order;
    order.reserve(m_points.size());
    if(m_size > 0)
      m_tree.root()->tree_items(std::back_inserter(order));
    std::vector<unsigned char> in_tree(m_points.size(), 0);
    for(std::size_t i : order) in_tree[i] = 1;
    for(std::size_t i = 0; i < m_points.size(); ++i)
      if(!in_tree[i]) order.push_back(i);
    return order;
  }

  Neighbor_query(const Neighbor_query&) = delete;
  Neighbor_query& operator=(const Neighbor_query&) = delete;

  /// Neighbors of point `i` (not `i` itself) into `out`: with `radius == 0` its `k` nearest
  /// (nearest first); otherwise all points within `radius`, nearest first, at most `k` if `k > 0`.
  /// Ties are broken by index, so the result does not depend on the tree's internal order.
  void neighbors(std::size_t i, unsigned int k, double radius, std::vector<std::size_t>& out, Scratch& scratch) const
  {
    out.clear();
    scratch.clear();
    const Point& p = m_points[i];
    if(m_size == 0) return; // empty (unbuilt) tree
    if(radius > 0)
    {
      Sphere sphere(p, radius, 0., m_traits);
      m_tree.search(boost::make_function_output_iterator(Collector{&m_points, &scratch, i}), sphere);
    }
    else
    {
      if(k == 0 || m_size == 0) return;
      // one more than asked: the query point (or one of its duplicates) comes back too
      Knn search(m_tree, p, (std::min<std::size_t>)(std::size_t(k) + 1, m_size), 0., true, m_distance, false);
      for(typename Knn::iterator it = search.begin(); it != search.end(); ++it)
        if(it->first != i) scratch.push_back(candidate(it->second, it->first));
    }
    std::sort(scratch.begin(), scratch.end());
    std::size_t count = scratch.size();
    if(k > 0 && count > k) count = k;
    for(std::size_t j = 0; j < count; ++j) out.push_back(index_of(scratch[j]));
  }

private:
  void build(Sequential_tag) { m_tree.build(); }
#ifdef CGAL_LINKED_WITH_TBB
  void build(Parallel_tag) { m_tree.template build<Parallel_tag>(); }
#endif

  // Output of the sphere search (copy-assignable, as the kd-tree needs): candidate(squared distance, index).
  struct Collector
  {
    const std::vector<Point>* points;
    Scratch* out;
    std::size_t query;
    void operator()(std::size_t j) const
    {
      if(j != query) out->push_back(candidate(squared_distance((*points)[query], (*points)[j]), j));
    }
  };

  const std::vector<Point>& m_points;
  Index_map m_map;
  Traits m_traits;
  Tree m_tree;
  Distance m_distance;
  std::size_t m_size = 0;
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_NEIGHBOR_QUERY_H
