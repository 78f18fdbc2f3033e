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

// Neighborhoods by index over a copy of the positions (double precision): k nearest, all within
// a radius, or the k nearest within a radius. The query point itself is never returned: the
// caller puts it first, so every fit is centered on its query point (CGAL 5.5.1's
// jet_smooth_point_set is not, with neighbor_radius). Non-finite points are kept out of the tree.
//
// Algorithm: a static kd-tree built once in the constructor (replacing CGAL's Kd_tree and
// Orthogonal_k_neighbor_search, which allocates per query). The finite points are copied in tree
// order (contiguous leaves of at most `leaf_size` points); each inner node splits its points at
// the median of the axis of largest extent (std::nth_element). A query descends to the near child
// first, then visits the far child only if the distance from the query to the far side's box can
// still be within the current bound. That distance is the sum of the squared per-axis gaps to the
// split planes crossed, evaluated like the point distances (dx * dx + dy * dy + dz * dz), so in
// floating point it is never above the distance of a point inside the box: the pruning is exact.
// * k nearest (`radius == 0`): the candidates go into the caller's scratch vector (no allocation
//   per query once warm); whenever it holds 2k of them, std::nth_element keeps the k smallest
//   (squared distance, index) pairs and the k-th becomes the bound. A point enters only if its
//   pair is smaller than the bound pair, and far sides at a gap equal to the bound distance are
//   still visited, so ties at the k-th distance keep the smallest indices: the result is exactly
//   the first k of all pairs (squared distance, j), j != i, in increasing order.
// * radius: every point with squared distance <= radius * radius (as CGAL::Fuzzy_sphere).
// Queries are const and thread safe.

#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
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

  /// `points` must outlive the query; `in_tree[i]` false keeps point i out of every neighborhood.
  Neighbor_query(const std::vector<Point>& points, const std::vector<unsigned char>& in_tree)
    : m_points(points)
  {
    for(std::size_t i = 0; i < points.size(); ++i)
      if(in_tree[i]) m_index.push_back(i);
    if(!m_index.empty()) build(0, m_index.size());
    m_coords.reserve(m_index.size());
    for(std::size_t j : m_index) m_coords.push_back({{points[j].x(), points[j].y(), points[j].z()}});
  }

  Neighbor_query(const Neighbor_query&) = delete;
  Neighbor_query& operator=(const Neighbor_query&) = delete;

  /// Neighbors of point `i` (not `i` itself) into `out`: with `radius == 0` its `k` nearest
  /// (nearest first); otherwise all points within `radius`, nearest first, at most `k` if `k > 0`.
  /// Ties are broken by index, so the result does not depend on the tree's internal order.
  void neighbors(std::size_t i, unsigned int k, double radius, std::vector<std::size_t>& out,
                 std::vector<std::pair<double, std::size_t> >& scratch) const
  {
    out.clear();
    scratch.clear();
    if(m_index.empty() || (radius <= 0 && k == 0)) return;
    const double bound = radius > 0 ? radius * radius : std::numeric_limits<double>::infinity();
    Search s{{m_points[i].x(), m_points[i].y(), m_points[i].z()}, i, radius > 0 ? 0 : std::size_t(k), bound,
             {bound, (std::numeric_limits<std::size_t>::max)()}, {0., 0., 0.}, &scratch};
    search(0, s);
    if(k > 0 && scratch.size() > k)
    {
      std::nth_element(scratch.begin(), scratch.begin() + k, scratch.end());
      scratch.resize(k);
    }
    std::sort(scratch.begin(), scratch.end());
    for(const auto& c : scratch) out.push_back(c.second);
  }

private:
  static const std::size_t leaf_size = 16;

  struct Node
  {
    double cut;                // inner node: points [begin, mid) have coordinate <= cut, [mid, end) >= cut
    std::uint32_t begin, end;  // the node's range in m_index / m_coords
    std::uint32_t right;       // inner node: right child (the left child is the next node)
    int axis;                  // 0, 1, 2; -1 for a leaf
  };

  struct Search
  {
    double q[3];
    std::size_t query, k;                // k == 0: radius search
    double bound;                        // candidates have squared distance <= bound ...
    std::pair<double, std::size_t> last; // ... and, at distance == bound, are smaller than this pair
    double gap[3];                       // per-axis distance from q to the current node's box
    std::vector<std::pair<double, std::size_t> >* candidates;
  };

  std::size_t build(std::size_t begin, std::size_t end)
  {
    const std::size_t node = m_nodes.size();
    m_nodes.push_back(Node{0., std::uint32_t(begin), std::uint32_t(end), 0, -1});
    if(end - begin <= leaf_size) return node;
    double lo[3], hi[3];
    for(int a = 0; a < 3; ++a) lo[a] = hi[a] = coord(m_index[begin], a);
    for(std::size_t j = begin + 1; j < end; ++j)
      for(int a = 0; a < 3; ++a)
      {
        lo[a] = (std::min)(lo[a], coord(m_index[j], a));
        hi[a] = (std::max)(hi[a], coord(m_index[j], a));
      }
    int axis = 0;
    for(int a = 1; a < 3; ++a)
      if(hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(m_index.begin() + begin, m_index.begin() + mid, m_index.begin() + end,
                     [&](std::size_t a, std::size_t b) { return coord(a, axis) < coord(b, axis); });
    m_nodes[node].cut = coord(m_index[mid], axis);
    m_nodes[node].axis = axis;
    build(begin, mid);
    m_nodes[node].right = std::uint32_t(build(mid, end));
    return node;
  }

  double coord(std::size_t j, int axis) const
  {
    return axis == 0 ? m_points[j].x() : axis == 1 ? m_points[j].y() : m_points[j].z();
  }

  void search(std::size_t n, Search& s) const
  {
    const Node& node = m_nodes[n];
    if(node.axis < 0)
    {
      for(std::size_t j = node.begin; j < node.end; ++j)
      {
        const double dx = m_coords[j][0] - s.q[0], dy = m_coords[j][1] - s.q[1], dz = m_coords[j][2] - s.q[2];
        const std::pair<double, std::size_t> c(dx * dx + dy * dy + dz * dz, m_index[j]);
        if(c.first > s.bound || c.second == s.query || (c.first == s.bound && !(c < s.last))) continue;
        s.candidates->push_back(c);
        if(s.candidates->size() == 2 * s.k) // k nearest: keep the k smallest, the k-th is the new bound
        {
          std::nth_element(s.candidates->begin(), s.candidates->begin() + (s.k - 1), s.candidates->end());
          s.candidates->resize(s.k);
          s.last = s.candidates->back();
          s.bound = s.last.first;
        }
      }
      return;
    }
    const int a = node.axis;
    const double diff = s.q[a] - node.cut; // > 0: q is on the right side
    search(diff > 0 ? node.right : n + 1, s); // the near side first
    const double saved = s.gap[a];
    s.gap[a] = diff;
    if(s.gap[0] * s.gap[0] + s.gap[1] * s.gap[1] + s.gap[2] * s.gap[2] <= s.bound)
      search(diff > 0 ? n + 1 : node.right, s);
    s.gap[a] = saved;
  }

  const std::vector<Point>& m_points;
  std::vector<std::size_t> m_index;             // point indices, in tree order
  std::vector<std::array<double, 3> > m_coords; // their coordinates, in tree order
  std::vector<Node> m_nodes;                    // depth first, the root first
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_NEIGHBOR_QUERY_H
