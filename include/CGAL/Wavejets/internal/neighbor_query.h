// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
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
#include <cstdint>
#include <cstring>
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
    std::vector<Candidate> buffer;         // the candidates in order (bucket sort)
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
    else // above rank_sort_limit, the k nearest among more candidates: the sort below picks them
      m_tree.k_nearest(q, k, i, candidates, bound_from_previous(i, k, scratch), k <= rank_sort_limit);
    const std::size_t count = k > 0 ? (std::min)(candidates.size(), std::size_t(k)) : candidates.size();
    const Candidate* farthest = append_nearest_indices_in_order(candidates, count, out, scratch.buffer);
    if(radius == 0) // this search bounds the next one (bound_from_previous())
    {
      scratch.query = this;
      scratch.point = i;
      scratch.k = count == k ? k : 0;
      scratch.kth_distance = count == k && k > 0 ? std::sqrt(candidate_squared_distance(*farthest)) : 0.;
    }
  }

  /// Appends the indices of the `count` smallest of the (distinct) candidates `c` to `out`, nearest
  /// first (ties by index), and returns the last of them (null if count == 0); `c` may be
  /// reordered, `buffer` is scratch. The last step of neighbors() (public for the benchmark's other
  /// searches, which then order their lists at the same cost). Up to rank_sort_limit candidates,
  /// each goes to its rank, the number of candidates before it: n^2 comparisons without a branch,
  /// faster than a sort's mispredicted ones at these sizes (the same order: the candidates are
  /// distinct, their ranks a permutation); then bucket_sort(), else std::sort.
  static const Candidate* append_nearest_indices_in_order(std::vector<Candidate>& c, std::size_t count,
                                                          std::vector<std::size_t>& out, std::vector<Candidate>& buffer)
  {
    const std::size_t n = c.size();
    if(count == 0) return nullptr;
    const std::size_t first = out.size();
    if(n <= rank_sort_limit)
    {
      out.resize(first + count);
      const Candidate* last = c.data();
      for(std::size_t i = 0; i < n; ++i)
      {
        std::size_t rank = 0;
        for(std::size_t j = 0; j < n; ++j) rank += std::size_t(c[j] < c[i]);
        if(rank < count) out[first + rank] = index_of(c[i]);
        last = rank == count - 1 ? c.data() + i : last;
      }
      return last;
    }
    const Candidate* sorted = c.data();
    if(n <= bucket_sort_limit && bucket_sort(c.data(), n, buffer))
      sorted = buffer.data();
    else
    {
      if(n > count) std::nth_element(c.begin(), c.begin() + (count - 1), c.end());
      std::sort(c.begin(), c.begin() + count);
    }
    for(std::size_t j = 0; j < count; ++j) out.push_back(index_of(sorted[j]));
    return sorted + count - 1;
  }

private:
  /// Candidates up to which append_nearest_indices_in_order() ranks instead of sorting.
  static constexpr std::size_t rank_sort_limit = 32;
  /// Candidates up to which it sorts by buckets, the number of buckets, and the most candidates one
  /// bucket may hold (more: many equal or clustered distances, which std::sort handles better).
  static constexpr std::size_t bucket_sort_limit = 512;
  static constexpr std::size_t sort_buckets = 256;
  static constexpr std::size_t bucket_crowding_limit = 32;

  // The bits of a candidate's squared distance: an unsigned integer in the order of the distance
  // (non-negative doubles order as their bits do).
  static std::uint64_t distance_bits(const Candidate& c)
  {
    const double d = candidate_squared_distance(c);
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return bits;
  }

  // Puts the n candidates `c` in order into `sorted` (n <= bucket_sort_limit): a counting sort by
  // sort_buckets intervals of equal width of the distance bits (monotone in the candidates' order,
  // so only candidates of one bucket can be out of order afterwards), then an insertion sort, which
  // has almost nothing to do when the distances spread over the buckets (a neighborhood's squared
  // distances grow about linearly with their rank) and is exact whatever they are. Its cost is
  // quadratic in the candidates that share a bucket: returns false, sorting nothing, when a bucket
  // holds more than bucket_crowding_limit of them (equal or clustered distances). Replacing the
  // search's final std::nth_element and the std::sort of the k nearest, it made the whole k-NN
  // query 1.5x faster at k 96 and 1.4x at k 50 (bunny samples, leaf order, one thread), with the
  // same lists.
  static bool bucket_sort(const Candidate* c, std::size_t n, std::vector<Candidate>& sorted)
  {
    std::uint64_t lowest = distance_bits(c[0]), highest = lowest;
    for(std::size_t j = 1; j < n; ++j)
    {
      const std::uint64_t bits = distance_bits(c[j]);
      lowest = (std::min)(lowest, bits);
      highest = (std::max)(highest, bits);
    }
    unsigned int shift = 0;
    while(((highest - lowest) >> shift) >= sort_buckets) ++shift;
    std::size_t start[sort_buckets + 1] = {};
    for(std::size_t j = 0; j < n; ++j) ++start[((distance_bits(c[j]) - lowest) >> shift) + 1];
    std::size_t crowded = 0;
    for(std::size_t b = 1; b <= sort_buckets; ++b)
    {
      crowded = (std::max)(crowded, start[b]);
      start[b] += start[b - 1];
    }
    if(crowded > bucket_crowding_limit)
      return false;
    sorted.resize(n);
    for(std::size_t j = 0; j < n; ++j) sorted[start[(distance_bits(c[j]) - lowest) >> shift]++] = c[j];
    for(std::size_t i = 1; i < n; ++i)
    {
      const Candidate x = sorted[i];
      std::size_t j = i;
      for(; j > 0 && x < sorted[j - 1]; --j) sorted[j] = sorted[j - 1];
      sorted[j] = x;
    }
    return true;
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
