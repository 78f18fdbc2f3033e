// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_KD_TREE_H
#define CGAL_WAVEJETS_INTERNAL_KD_TREE_H

// The kd-tree behind Neighbor_query: exact k nearest and radius searches in 3D, double precision,
// with the neighbors ordered by (squared distance, index), so that the neighbor lists do not depend
// on the tree's shape. Built once, queried concurrently (queries are const).
//
// Layout: the points' coordinates are copied coordinate by coordinate (x, y, z arrays) in the
// tree's leaf order, so that a leaf is a contiguous run of at most bucket_size points whose
// distances are computed in one vectorizable loop. Nodes split their points at the median of the
// widest extent of their bounding box (a balanced tree: its shape, hence its node count, depends on
// the number of points only, which lets the two halves be built in parallel into fixed ranges of
// the node array) and keep that tight box: a subtree is visited only when its box is at most the
// current k-th distance away.
//
// Exactness: every squared distance is (qx - px)^2 + (qy - py)^2 + (qz - pz)^2, summed in that
// order, as CGAL's Euclidean_distance and squared_distance compute it. A box's distance is summed
// from the per-axis gaps to the box, each no larger than the gap to any point of the box; rounding
// is monotone, so the computed box distance never exceeds a computed point distance: a box is
// skipped only when none of its points could enter the result, ties (equal distance, smaller index)
// included.

#include <CGAL/tags.h>
#include <CGAL/Wavejets/internal/instruction_sets.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/parallel_invoke.h>
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// A neighbor as a search collects it: its squared distance and its index, ordered by distance,
/// then index. Where the compiler has a 128-bit integer (GCC, Clang) the two are packed into one:
/// the bits of a non-negative double order as the double does, so comparing two neighbors is one
/// integer comparison, without branches (sorting them: k-NN 1.15x faster at k 96, 1.09x at k 18
/// than with std::pair; the same order). Elsewhere, the std::pair.
#ifdef __SIZEOF_INT128__
__extension__ typedef unsigned __int128 Neighbor_candidate;
inline Neighbor_candidate make_candidate(double squared_distance, std::size_t index)
{
  static_assert(sizeof(std::size_t) <= sizeof(std::uint64_t), "the index takes the low 64 bits");
  std::uint64_t bits;
  std::memcpy(&bits, &squared_distance, sizeof bits);
  return (Neighbor_candidate(bits) << 64) | Neighbor_candidate(index);
}
inline std::size_t candidate_index(const Neighbor_candidate& c) { return std::size_t(std::uint64_t(c)); }
inline double candidate_squared_distance(const Neighbor_candidate& c)
{
  const std::uint64_t bits = std::uint64_t(c >> 64);
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
#else
typedef std::pair<double, std::size_t> Neighbor_candidate;
inline Neighbor_candidate make_candidate(double squared_distance, std::size_t index)
{
  return Neighbor_candidate(squared_distance, index);
}
inline std::size_t candidate_index(const Neighbor_candidate& c) { return c.second; }
inline double candidate_squared_distance(const Neighbor_candidate& c) { return c.first; }
#endif

/// x^2 + y^2 + z^2 summed in that order: every squared distance of the searches,
/// to a point or to a box, is this one expression (the exactness argument above relies on it).
inline double sum_of_squares(double x, double y, double z)
{
  double d = x * x;
  d += y * y;
  d += z * z;
  return d;
}

/// Kd-tree over a subset of a point array; its searches return Neighbor_candidate records.
class Kd_tree_3
{
public:
  typedef Neighbor_candidate Candidate;

  /// Points per leaf (8 to 16 in the balanced tree). Of 16, 24 and 32, 16 was the fastest or within
  /// the noise at k 18 and k 96 (100,000 points on a torus, one thread, two runs).
  static constexpr std::size_t bucket_size = 16;

  /// Builds the tree over the points `indices` of `points` (any type with x(), y(), z()). The tree
  /// (and its leaf order) is the same with Sequential_tag and Parallel_tag.
  template <class Point, class ConcurrencyTag>
  void build(const std::vector<Point>& points, std::vector<std::size_t> indices, ConcurrencyTag)
  {
    // The splits reorder the indices in place, reading the coordinates from `points`: no copy of the
    // coordinates exists until the final layout (the peak memory is that of the tree itself).
    m_index = std::move(indices);
    const std::size_t n = m_index.size();
    m_nodes.assign(n > 0 ? node_count(n) : 0, Node());
    if(n > 0)
      build_node(points, 0, 0, n, parallel(ConcurrencyTag()));
    // Coordinates in leaf order, padded by bucket_size (zeros): a leaf's distance loop always runs
    // over bucket_size slots.
    m_x.assign(n + bucket_size, 0.);
    m_y.assign(n + bucket_size, 0.);
    m_z.assign(n + bucket_size, 0.);
    for(std::size_t s = 0; s < n; ++s)
    {
      const Point& p = points[m_index[s]];
      m_x[s] = p.x();
      m_y[s] = p.y();
      m_z[s] = p.z();
    }
  }

  /// The indices of the tree's points in leaf order (neighbors in space are close in this order).
  const std::vector<std::size_t>& leaf_order() const { return m_index; }

  /// The min(k, size() - [exclude is in the tree]) points nearest to q, `exclude` left out, as
  /// candidates in `out` (in no particular order): the smallest by (squared distance, index).
  /// `bound`, if given: a squared distance known to hold at least k of them (points farther away
  /// are not looked at; a wrong bound gives a wrong result). With `select_k` false, `out` may also
  /// hold other points (fewer than k + max(k, bucket_size) in all): the caller then picks the k
  /// smallest, e.g. while putting them in order.
  void k_nearest(const double q[3], std::size_t k, std::size_t exclude, std::vector<Candidate>& out,
                 double bound = std::numeric_limits<double>::infinity(), bool select_k = true) const
  {
    out.clear();
    if(k == 0 || m_nodes.empty()) return;
    k = (std::min)(k, m_index.size()); // a larger k finds no more, and would size the scratch by k
    Knn_state state{q, k, exclude, k + (std::max)(k, bucket_size), 0, nullptr, bound};
    out.resize(state.capacity + bucket_size); // a leaf is scanned before the selection
    state.kept = out.data();
    k_nearest(0, state);
    if(select_k && state.count > k) select(state);
    out.resize(state.count);
  }

  /// Every point p with squared distance to q at most `squared_radius`, `exclude` left out, as
  /// candidates appended to `out` (in no particular order).
  void within(const double q[3], double squared_radius, std::size_t exclude, std::vector<Candidate>& out) const
  {
    if(!m_nodes.empty() && !(box_distance(m_nodes[0], q) > squared_radius))
      within(0, q, squared_radius, exclude, out);
  }

private:
  struct Node
  {
    double lo[3] = {0., 0., 0.}, hi[3] = {0., 0., 0.}; // tight bounding box of the node's points
    std::size_t begin = 0, end = 0;                     // its points: slots begin..end-1
    std::size_t right = 0;                              // right child (the left one is the next node); 0: a leaf
  };

  struct Knn_state
  {
    const double* q;
    std::size_t k, exclude;
    std::size_t capacity; // kept candidates that trigger a selection: k + max(k, bucket_size)
    std::size_t count;    // kept candidates
    Candidate* kept;      // the candidates so far at most `worst` away, in no order (room for capacity + bucket_size)
    double worst;         // the k-th smallest squared distance at the last selection (the bound before)
  };

  // Keeps the k smallest candidates (a selection, not a heap: amortized constant work per
  // candidate and no mispredicted branch per candidate) and lowers `worst` to the k-th distance.
  // Not inlined: where it runs often (every candidate ties, e.g. 20,000 copies of one point) the
  // search was up to 1.7x slower with it inlined into the recursion, depending on the caller.
  CGAL_WAVEJETS_NOINLINE static void select(Knn_state& state)
  {
    std::nth_element(state.kept, state.kept + (state.k - 1), state.kept + state.count);
    state.count = state.k;
    state.worst = candidate_squared_distance(state.kept[state.k - 1]);
  }

  template <class ConcurrencyTag>
  static bool parallel(ConcurrencyTag) { return std::is_same<ConcurrencyTag, Parallel_tag>::value; }

  // Nodes of the tree over n points: the same recursion as build_node().
  static std::size_t node_count(std::size_t n)
  {
    return n <= bucket_size ? 1 : 1 + node_count(n / 2) + node_count(n - n / 2);
  }

  template <class Point>
  static double coordinate(const Point& p, int axis)
  {
    return axis == 0 ? p.x() : axis == 1 ? p.y() : p.z();
  }

  // Node `id` over m_index[begin..end-1]: box, then (above bucket_size points) the split at the
  // median of the widest axis (ties by index), left half first in the node array.
  template <class Point>
  void build_node(const std::vector<Point>& points, std::size_t id, std::size_t begin, std::size_t end, bool in_parallel)
  {
    Node& node = m_nodes[id];
    node.begin = begin;
    node.end = end;
    for(int a = 0; a < 3; ++a)
    {
      node.lo[a] = std::numeric_limits<double>::infinity();
      node.hi[a] = -std::numeric_limits<double>::infinity();
    }
    for(std::size_t s = begin; s < end; ++s)
      for(int a = 0; a < 3; ++a)
      {
        const double c = coordinate(points[m_index[s]], a);
        node.lo[a] = (std::min)(node.lo[a], c);
        node.hi[a] = (std::max)(node.hi[a], c);
      }
    const std::size_t n = end - begin;
    if(n <= bucket_size) return;
    int axis = 0;
    for(int a = 1; a < 3; ++a)
      if(node.hi[a] - node.lo[a] > node.hi[axis] - node.lo[axis]) axis = a;
    const std::size_t middle = begin + n / 2;
    std::nth_element(m_index.begin() + begin, m_index.begin() + middle, m_index.begin() + end,
                     [&](std::size_t a, std::size_t b) {
                       const double ca = coordinate(points[a], axis), cb = coordinate(points[b], axis);
                       return ca < cb || (ca == cb && a < b);
                     });
    const std::size_t left = id + 1, right = left + node_count(n / 2);
    node.right = right;
#ifdef CGAL_LINKED_WITH_TBB
    constexpr std::size_t parallel_grain = 50000; // points below which a subtree is built sequentially
    if(in_parallel && n > parallel_grain)
    {
      tbb::parallel_invoke([&] { build_node(points, left, begin, middle, true); },
                           [&] { build_node(points, right, middle, end, true); });
      return;
    }
#endif
    build_node(points, left, begin, middle, in_parallel);
    build_node(points, right, middle, end, in_parallel);
  }

  // Squared distance from q to the node's box (0 inside), a lower bound of its points' distances.
  static double box_distance(const Node& node, const double* q)
  {
    double gap[3];
    for(int a = 0; a < 3; ++a) gap[a] = (std::max)((std::max)(node.lo[a] - q[a], q[a] - node.hi[a]), 0.);
    return sum_of_squares(gap[0], gap[1], gap[2]);
  }

  double squared_distance(const double* q, std::size_t s) const
  {
    return sum_of_squares(q[0] - m_x[s], q[1] - m_y[s], q[2] - m_z[s]);
  }

  void k_nearest(std::size_t id, Knn_state& state) const
  {
    const Node& node = m_nodes[id];
    if(node.right == 0)
    {
      // All bucket_size slots from the leaf's first (the arrays are padded): one vectorized loop.
      double distance[bucket_size];
      const double *x = m_x.data() + node.begin, *y = m_y.data() + node.begin, *z = m_z.data() + node.begin;
      const double qx = state.q[0], qy = state.q[1], qz = state.q[2];
      for(std::size_t j = 0; j < bucket_size; ++j) distance[j] = sum_of_squares(qx - x[j], qy - y[j], qz - z[j]);
      // Every candidate is written, and counted only if it may enter the result: no branch on it.
      const std::size_t* index = m_index.data() + node.begin;
      const std::size_t n = node.end - node.begin;
      std::size_t count = state.count;
      for(std::size_t j = 0; j < n; ++j)
      {
        state.kept[count] = make_candidate(distance[j], index[j]);
        count += std::size_t(distance[j] <= state.worst) & std::size_t(index[j] != state.exclude);
      }
      state.count = count;
      if(count >= state.capacity) select(state);
      return;
    }
    const std::size_t left = id + 1, right = node.right;
    const double to_left = box_distance(m_nodes[left], state.q), to_right = box_distance(m_nodes[right], state.q);
    const bool left_first = to_left <= to_right;
    const std::size_t near = left_first ? left : right, far = left_first ? right : left;
    const double to_far = left_first ? to_right : to_left;
    k_nearest(near, state);
    if(!(to_far > state.worst))
      k_nearest(far, state);
  }

  void within(std::size_t id, const double* q, double squared_radius, std::size_t exclude,
              std::vector<Candidate>& out) const
  {
    const Node& node = m_nodes[id];
    if(node.right == 0)
    {
      for(std::size_t s = node.begin; s < node.end; ++s)
      {
        const double d = squared_distance(q, s);
        if(d <= squared_radius && m_index[s] != exclude) out.push_back(make_candidate(d, m_index[s]));
      }
      return;
    }
    for(const std::size_t child : {id + 1, node.right})
      if(!(box_distance(m_nodes[child], q) > squared_radius))
        within(child, q, squared_radius, exclude, out);
  }

  std::vector<Node> m_nodes;
  std::vector<double> m_x, m_y, m_z;
  std::vector<std::size_t> m_index; // slot -> point index
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_KD_TREE_H
