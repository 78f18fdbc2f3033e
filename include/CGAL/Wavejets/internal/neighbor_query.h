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

// Neighborhoods by index over a copy of the positions (double precision): k nearest, all within a
// radius, or the k nearest within a radius, searched in the package's kd-tree (kd_tree.h: exact,
// ties broken by index; on 100,000 bunny points, one thread, 1.25x faster than CGAL's kd-tree with
// Orthogonal_k_neighbor_search at k 18 and 1.8x at k 96, benchmark/Wavejets/results.md). The query
// point itself is never returned: the caller puts it first, so every fit is centered on its query
// point (CGAL 5.5.1's jet_smooth_point_set is not, with neighbor_radius). Non-finite points are kept
// out of the tree. The tree is built in the constructor; queries are const and thread safe.

#include <CGAL/Simple_cartesian.h>
#include <CGAL/tags.h>
#include <CGAL/Wavejets/internal/kd_tree.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

class Neighbor_query
{
public:
  typedef Simple_cartesian<double> SC;
  typedef SC::Point_3 Point;

  /// A neighbor as a search collects it (kd_tree.h's Neighbor_candidate): ordered by squared
  /// distance, then index.
  typedef Neighbor_candidate Candidate;
  static Candidate candidate(double squared_distance, std::size_t index) { return make_candidate(squared_distance, index); }
  static std::size_t index_of(const Candidate& c) { return candidate_index(c); }
  /// Per-thread scratch of neighbors(): the candidates, and the last k-NN query, whose k-th
  /// distance bounds the next one's (the drivers query in the tree's leaf order, where consecutive
  /// points are close: the search then skips every leaf beyond that bound; 1.15x faster at k 18 and
  /// 1.3x at k 96 than without it, 100,000 points on a torus, one thread).
  struct Scratch
  {
    std::vector<Candidate> candidates;
    const Neighbor_query* query = nullptr; // the query that ran the last k-NN search (null: none)
    std::size_t point = 0;                 // its point
    unsigned int k = 0;                    // its k, when it found k neighbors
    double kth_distance = 0.;              // the distance to its k-th neighbor
  };

  /// `points` must outlive the query; `in_tree[i]` false keeps point i out of every neighborhood.
  /// With `Parallel_tag` the kd-tree is built in parallel (the same tree, hence the same
  /// processing order).
  template <class ConcurrencyTag = Sequential_tag>
  Neighbor_query(const std::vector<Point>& points, const std::vector<unsigned char>& in_tree,
                 ConcurrencyTag tag = ConcurrencyTag())
    : m_points(points), m_in_tree(in_tree)
  {
    std::vector<std::size_t> indices;
    for(std::size_t i = 0; i < points.size(); ++i)
      if(in_tree[i]) indices.push_back(i);
    m_tree.build(points, std::move(indices), tag);
  }

  /// All indices 0..N-1 in an order that keeps neighbors close together: the points of the tree in
  /// the kd-tree's leaf order, then those left out of it by index. Processing the points in this
  /// order instead of the input's keeps the tree nodes and the neighbors' coordinates in cache from
  /// one point to the next (a random input order otherwise misses the cache on every neighborhood
  /// once N is large).
  std::vector<std::size_t> processing_order() const
  {
    std::vector<std::size_t> order = m_tree.leaf_order();
    order.reserve(m_points.size());
    for(std::size_t i = 0; i < m_points.size(); ++i)
      if(!m_in_tree[i]) order.push_back(i);
    return order;
  }

  Neighbor_query(const Neighbor_query&) = delete;
  Neighbor_query& operator=(const Neighbor_query&) = delete;

  /// Neighbors of point `i` (not `i` itself) into `out`: with `radius == 0` its `k` nearest
  /// (nearest first); otherwise all points at distance at most `radius`, nearest first, at most `k`
  /// if `k > 0`. Ties are broken by index (the smaller first, also at the k-th place), so the
  /// result does not depend on the tree's internal order.
  void neighbors(std::size_t i, unsigned int k, double radius, std::vector<std::size_t>& out, Scratch& scratch) const
  {
    out.clear();
    std::vector<Candidate>& candidates = scratch.candidates;
    candidates.clear();
    const Point& p = m_points[i];
    const double q[3] = {p.x(), p.y(), p.z()};
    if(radius > 0)
      m_tree.within(q, radius * radius, i, candidates);
    else
      m_tree.k_nearest(q, k, i, candidates, bound_from_previous(i, k, scratch)); // at most k
    std::size_t count = candidates.size();
    if(k > 0 && count > k) // a radius search's k nearest
    {
      std::nth_element(candidates.begin(), candidates.begin() + k, candidates.end());
      count = k;
    }
    const Candidate* farthest = append_indices_in_order(candidates.data(), count, out);
    if(radius == 0) // this search bounds the next one (bound_from_previous())
    {
      scratch.query = this;
      scratch.point = i;
      scratch.k = count == k ? k : 0;
      scratch.kth_distance = count == k && k > 0 ? std::sqrt(candidate_squared_distance(*farthest)) : 0.;
    }
  }

private:
  /// Neighbors up to which append_indices_in_order() ranks instead of sorting.
  static constexpr std::size_t rank_sort_limit = 32;

  // Appends the indices of the n candidates `c` to `out`, nearest first (ties by index), and
  // returns the last of them (null if n == 0); `c` may be reordered. Up to rank_sort_limit
  // candidates, each goes to its rank, the number of candidates before it: n^2 comparisons without
  // a branch, faster than a sort's mispredicted ones at these sizes (the same order: the candidates
  // are distinct, their ranks a permutation).
  static const Candidate* append_indices_in_order(Candidate* c, std::size_t n, std::vector<std::size_t>& out)
  {
    if(n == 0) return nullptr;
    if(n > rank_sort_limit)
    {
      std::sort(c, c + n);
      for(std::size_t j = 0; j < n; ++j) out.push_back(index_of(c[j]));
      return c + n - 1;
    }
    const std::size_t first = out.size();
    out.resize(first + n);
    const Candidate* last = c;
    for(std::size_t i = 0; i < n; ++i)
    {
      std::size_t rank = 0;
      for(std::size_t j = 0; j < n; ++j) rank += std::size_t(c[j] < c[i]);
      out[first + rank] = index_of(c[i]);
      last = rank == n - 1 ? c + i : last;
    }
    return last;
  }

  // A squared distance holding the k nearest of point i, from the previous k-NN search in
  // `scratch` (of point j, same k, j in the tree): the ball of radius |p_i - p_j| + d_k(j) around
  // p_i holds the k neighbors of j and j itself, so at least k points other than i (+infinity if
  // there is none).
  // The margin (1e-12 relative, far above the rounding of these few operations, plus a few
  // subnormals for underflowing distances) keeps every candidate the exact search would take.
  double bound_from_previous(std::size_t i, unsigned int k, const Scratch& scratch) const
  {
    const double none = std::numeric_limits<double>::infinity();
    if(scratch.query != this || scratch.k != k || scratch.point == i || k == 0 || !m_in_tree[scratch.point])
      return none;
    const double reach = std::sqrt(squared_distance(m_points[i], m_points[scratch.point])) + scratch.kth_distance;
    const double bound = reach * reach * (1. + 1e-12) + 16. * std::numeric_limits<double>::denorm_min();
    return bound < none ? bound : none; // a non-finite query point: no bound (NaN would drop every candidate)
  }

  const std::vector<Point>& m_points;
  std::vector<unsigned char> m_in_tree; // a copy: the previous point must be in the tree for its bound
  Kd_tree_3 m_tree;
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_NEIGHBOR_QUERY_H
