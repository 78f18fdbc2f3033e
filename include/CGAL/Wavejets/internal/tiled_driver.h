// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_TILED_DRIVER_H
#define CGAL_WAVEJETS_INTERNAL_TILED_DRIVER_H

// Tiled runs (the named parameter `tile_size`; doc/Wavejets/Mathematics.txt §12). The finite points
// are cut into spatial tiles of at most tile_size points (Tiling). Each tile is an independent task
// (process_tile()): its points, the targets, are fitted among the points within a halo around
// their bounding box, copied in range order so that equally distant neighbors are ranked as in core
// (by index). A fit whose reach (Point_fitter::reach()) leaves the halo is not kept: those points
// are fitted again with a halo that holds their reach. Every point thus gets the in-core result,
// bit for bit. The kd-tree and the fits' scratch are those of one tile.

#include <CGAL/Wavejets/internal/point_set_driver.h>

#include <CGAL/for_each.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// A closed axis-aligned box (empty until a point is added).
struct Box
{
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};

  void add(const Neighbor_query::Point& p)
  {
    for(int a = 0; a < 3; ++a) { lo[a] = (std::min)(lo[a], p[a]); hi[a] = (std::max)(hi[a], p[a]); }
  }
  Box grown(double h) const
  {
    Box b = *this;
    for(int a = 0; a < 3; ++a) { b.lo[a] -= h; b.hi[a] += h; }
    return b;
  }
  bool contains(const Neighbor_query::Point& p) const
  {
    return lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1] && lo[2] <= p[2] && p[2] <= hi[2];
  }
  bool contains(const Box& b) const
  {
    return lo[0] <= b.lo[0] && b.hi[0] <= hi[0] && lo[1] <= b.lo[1] && b.hi[1] <= hi[1] && lo[2] <= b.lo[2] &&
           b.hi[2] <= hi[2];
  }
  bool intersects(const Box& b) const
  {
    return lo[0] <= b.hi[0] && b.lo[0] <= hi[0] && lo[1] <= b.hi[1] && b.lo[1] <= hi[1] && lo[2] <= b.hi[2] &&
           b.lo[2] <= hi[2];
  }
  double extent(int a) const { return hi[a] - lo[a]; }
  double diagonal() const { return std::sqrt(extent(0) * extent(0) + extent(1) * extent(1) + extent(2) * extent(2)); }
};

/// The tiles of a point set: its finite points split at the median of the longest side of their
/// bounding box, recursively, until a part holds at most `tile_size` points (a dense cluster gets
/// small tiles). The split tree also finds the points within a box.
class Tiling
{
public:
  Tiling(const std::vector<Neighbor_query::Point>& points, const std::vector<unsigned char>& finite,
         std::size_t tile_size)
    : m_points(points)
  {
    for(std::size_t i = 0; i < points.size(); ++i)
      if(finite[i]) m_indices.push_back(i);
    if(!m_indices.empty()) build(0, m_indices.size(), (std::max)(tile_size, std::size_t(1)));
  }

  std::size_t size() const { return m_tiles.size(); }
  /// The points of tile t, in range order.
  std::vector<std::size_t> points_of(std::size_t t) const
  {
    const Node& n = m_nodes[m_tiles[t]];
    return std::vector<std::size_t>(m_indices.begin() + n.begin, m_indices.begin() + n.end);
  }
  /// The bounding box of every finite point.
  const Box& bounds() const { return m_nodes.front().box; }

  /// The indices of the points in the closed box `b`, in range order.
  void points_in(const Box& b, std::vector<std::size_t>& out) const
  {
    out.clear();
    std::vector<std::size_t> stack(1, 0);
    while(!stack.empty())
    {
      const Node& n = m_nodes[stack.back()];
      stack.pop_back();
      if(!b.intersects(n.box)) continue;
      if(n.left == 0 || b.contains(n.box))
      {
        for(std::size_t j = n.begin; j < n.end; ++j)
          if(b.contains(m_points[m_indices[j]])) out.push_back(m_indices[j]);
        continue;
      }
      stack.push_back(n.left);
      stack.push_back(n.left + 1);
    }
    std::sort(out.begin(), out.end());
  }

private:
  struct Node
  {
    Box box;                // of its points
    std::size_t begin, end; // its points: m_indices[begin, end)
    std::size_t left = 0;   // its children: left and left + 1 (0: a tile)
  };

  void build(std::size_t begin, std::size_t end, std::size_t tile_size)
  {
    // Breadth first, so that the two children of a node are consecutive.
    m_nodes.push_back(Node{box_of(begin, end), begin, end});
    for(std::size_t n = 0; n < m_nodes.size(); ++n)
    {
      const std::size_t b = m_nodes[n].begin, e = m_nodes[n].end;
      if(e - b <= tile_size) { m_tiles.push_back(n); std::sort(m_indices.begin() + b, m_indices.begin() + e); continue; }
      const Box& box = m_nodes[n].box;
      int axis = 0;
      for(int a = 1; a < 3; ++a) if(box.extent(a) > box.extent(axis)) axis = a;
      const std::size_t middle = b + (e - b) / 2;
      // Ordered by coordinate, then index: the split does not depend on the library's nth_element.
      std::nth_element(m_indices.begin() + b, m_indices.begin() + middle, m_indices.begin() + e,
                       [&](std::size_t i, std::size_t j) {
                         const double ci = m_points[i][axis], cj = m_points[j][axis];
                         return ci < cj || (ci == cj && i < j);
                       });
      m_nodes[n].left = m_nodes.size();
      m_nodes.push_back(Node{box_of(b, middle), b, middle});
      m_nodes.push_back(Node{box_of(middle, e), middle, e});
    }
  }

  Box box_of(std::size_t begin, std::size_t end) const
  {
    Box b;
    for(std::size_t j = begin; j < end; ++j) b.add(m_points[m_indices[j]]);
    return b;
  }

  const std::vector<Neighbor_query::Point>& m_points;
  std::vector<std::size_t> m_indices; // finite points; those of each node contiguous
  std::vector<Node> m_nodes;          // the root first
  std::vector<std::size_t> m_tiles;   // the leaves, in the tree's (spatial) order
};

/// The input of a pass over one tile (the interface of Point_set_input): the range's points within
/// the tile's halo, in range order, of which the targets are fitted.
struct Tile_input
{
  static constexpr bool checks_reach = true;
  std::vector<Neighbor_query::Point> points;
  std::vector<unsigned char> finite;    // all 1 in a tiled run (the tiling holds finite points only)
  std::vector<Eigen::Vector3d> normals; // their input normals, if the run reads them
  std::vector<std::size_t> indices;     // in the range
  std::vector<unsigned char> active;    // 1: a target
  Box extent;                           // every point of the range in this box is here
  Box bounds;                           // of every finite point of the range

  std::size_t size() const { return points.size(); }
  bool is_active(std::size_t i) const { return active[i]; }
  std::size_t index_in_range(std::size_t i) const { return indices[i]; }
  Eigen::Vector3d position(std::size_t i) const { return Eigen::Vector3d(points[i].x(), points[i].y(), points[i].z()); }

  /// Whether every point of the range within distance r of point i is here: the ball lies inside
  /// `extent`, but across the sides of `extent` that lie beyond `bounds` (no point is there). The
  /// margins, far above the rounding of distances, only make the test stricter.
  bool holds_ball(std::size_t i, double r) const
  {
    if(!(r < std::numeric_limits<double>::infinity())) return extent.contains(bounds);
    for(int a = 0; a < 3; ++a)
    {
      const double c = points[i][a];
      const double needed = r * (1. + 1e-9) + 1e-12 * (std::abs(c) + std::abs(extent.lo[a]) + std::abs(extent.hi[a]));
      if(extent.lo[a] > bounds.lo[a] && !(c - extent.lo[a] > needed)) return false;
      if(extent.hi[a] < bounds.hi[a] && !(extent.hi[a] - c > needed)) return false;
    }
    return true;
  }
};

/// The tile input of `targets` (indices in the range, increasing): the points of `input` within
/// `halo` of their bounding box.
template <class Input>
Tile_input make_tile_input(const Input& input, const Tiling& tiling, const std::vector<std::size_t>& targets, double halo)
{
  Box box;
  for(std::size_t t : targets) box.add(input.points[t]);
  Tile_input tile;
  tile.extent = box.grown(halo);
  tile.bounds = tiling.bounds();
  tiling.points_in(tile.extent, tile.indices);
  const std::size_t n = tile.indices.size();
  tile.points.reserve(n);
  tile.active.assign(n, 0);
  std::size_t next_target = 0;
  for(std::size_t i = 0; i < n; ++i)
  {
    const std::size_t g = tile.indices[i];
    tile.points.push_back(input.points[g]);
    if(!input.normals.empty()) tile.normals.push_back(input.normals[g]);
    if(next_target < targets.size() && targets[next_target] == g) { tile.active[i] = 1; ++next_target; }
  }
  CGAL_assertion(next_target == targets.size());
  tile.finite.assign(n, 1);
  return tile;
}

/// The halo that holds the neighborhoods of most of `count` points in a box of sides `extent`: with
/// a search radius, that radius (no reach exceeds it); else 1.5 times the radius of a disk holding
/// k + 1 points at their density, taking them as a surface across the two longest sides of the box
/// (0 if the box is a point). Also the first halo of the `wavejets` tool's streamed tiles.
inline double estimated_halo(const double extent[3], std::size_t count, unsigned int k, double neighbor_radius)
{
  if(neighbor_radius > 0) return neighbor_radius * (1. + 1e-6);
  double e[3] = {extent[0], extent[1], extent[2]};
  std::sort(e, e + 3);
  const double points = double(k + 1), pi = 3.14159265358979323846;
  if(e[1] > 0) return 1.5 * std::sqrt(points * e[2] * e[1] / (pi * double(count)));
  if(e[2] > 0) return 1.5 * e[2] * points / (2. * double(count));
  return 0.;
}

/// The first halo of a tile of `count` points in `box`: `tile_halo` if given, else estimated_halo();
/// twice that with `estimated_normals` (the neighbors' normals of a Hermite fit, whose fits reach one
/// neighborhood further).
inline double first_halo(const Box& box, std::size_t count, const Driver_settings& s, bool estimated_normals)
{
  if(s.tile_halo > 0) return s.tile_halo;
  const double extent[3] = {box.extent(0), box.extent(1), box.extent(2)};
  const double r = estimated_halo(extent, count, s.k, s.largest_radius);
  return estimated_normals ? 2. * r : r;
}

/// Per-point outcome of a tiled run (indexed like the range): each tile writes its own points.
struct Tiled_statuses
{
  std::vector<unsigned char> status, reduced, fitted;
};

/// The outcome of one pass over a tile: the targets whose reach left its halo (indices in the
/// range, increasing), and a halo for their next pass.
struct Tile_outcome
{
  std::vector<std::size_t> outside;
  double next_halo = 0.;
  bool interrupted = false;
};

/// One tile's task: fits `targets` among the points within `halo` of them, runs the kernel and
/// records the statuses of those whose reach the halo holds. The next halo holds the largest reach
/// left outside (refitted on more points, a fit reaches no further, but through the neighbors'
/// normals), and at least doubles (so that the rounds end, at the latest with every point in the
/// halo); a reach without bound (a k-nearest search that found fewer than k) doubles it.
template <class Input, class Kernel>
Tile_outcome process_tile(const Input& input, const Tiling& tiling, const std::vector<std::size_t>& targets,
                          double halo, const Driver_settings& settings, const Kernel& kernel,
                          Tiled_statuses& statuses, Pass_progress& progress)
{
  const Tile_input tile = make_tile_input(input, tiling, targets, halo);
  const Pass_result pass = fit_pass<Sequential_tag>(tile, settings, kernel, &progress, Pass_kind::MAIN);
  Tile_outcome outcome;
  outcome.interrupted = pass.interrupted;
  if(pass.interrupted) return outcome;
  double reach = 0.;
  for(std::size_t i = 0; i < tile.size(); ++i)
  {
    if(!tile.active[i]) continue;
    const std::size_t g = tile.indices[i];
    if(pass.outside[i])
    {
      outcome.outside.push_back(g);
      if(pass.reach[i] < std::numeric_limits<double>::infinity()) reach = (std::max)(reach, pass.reach[i]);
      else reach = std::numeric_limits<double>::infinity();
      continue;
    }
    statuses.status[g] = pass.status[i];
    statuses.reduced[g] = pass.reduced[i];
    statuses.fitted[g] = pass.fitted[i];
  }
  const double doubled = (std::max)(2. * halo, tiling.bounds().diagonal() / 64.);
  outcome.next_halo = reach < std::numeric_limits<double>::infinity() ? (std::max)(reach * (1. + 1e-6), doubled)
                                                                      : doubled;
  return outcome;
}

/// fit_each_point() tile by tile: the same results and report, plus the number of tiles and of the
/// points fitted again with a larger halo. Tiles run concurrently under Parallel_tag, each one
/// sequentially.
template <class ConcurrencyTag, class Input, class Kernel>
Driver_run fit_each_tile(const Input& input, const Driver_settings& settings, const Kernel& kernel)
{
  const std::size_t N = input.size();
  const Tiling tiling(input.points, input.finite, settings.tile_size);
  Tiled_statuses statuses;
  statuses.status.assign(N, (unsigned char)(Fit_status::TOO_FEW_POINTS));
  statuses.reduced.assign(N, 0);
  statuses.fitted.assign(N, 0);
  for(std::size_t i = 0; i < N; ++i)
    if(!input.finite[i]) statuses.status[i] = (unsigned char)(Fit_status::NON_FINITE_INPUT);

  // The callback sees the points of both passes of a Hermite fit with estimated normals, as in core.
  const bool estimated_normals = settings.use_neighbor_normals && input.normals.empty();
  const std::size_t passes = estimated_normals ? 2 : 1;
  Pass_progress progress(settings.callback, passes * N);
  progress.advance(passes * std::size_t(std::count(input.finite.begin(), input.finite.end(), 0)));
  std::atomic<std::size_t> repaired(0);
  std::atomic<bool> interrupted(false);
  std::vector<std::size_t> tiles(tiling.size());
  std::iota(tiles.begin(), tiles.end(), std::size_t(0));
  CGAL::for_each<ConcurrencyTag>(tiles, [&](const std::size_t t) -> bool {
    std::vector<std::size_t> targets = tiling.points_of(t);
    Box box;
    for(std::size_t i : targets) box.add(input.points[i]);
    double halo = first_halo(box, targets.size(), settings, estimated_normals);
    for(bool first_round = true; !targets.empty() && !interrupted; first_round = false)
    {
      Tile_outcome outcome = process_tile(input, tiling, targets, halo, settings, kernel, statuses, progress);
      if(outcome.interrupted) { interrupted = true; return false; }
      if(first_round) repaired += outcome.outside.size();
      targets = std::move(outcome.outside);
      halo = outcome.next_halo;
    }
    return !interrupted;
  });
  if(!interrupted) progress.finish();
  Driver_run run;
  run.report.number_of_points = N;
  run.report.number_of_tiles = tiling.size();
  run.report.number_of_repaired_points = repaired;
  run.report.interrupted = interrupted || progress.interrupted();
  run.fitted = std::move(statuses.fitted);
  count_points(run, statuses.status, statuses.reduced);
  return run;
}

/// fit_each_point() when the range is one tile of a larger point set (`tile`): fits its owned points
/// among all of its points, and keeps the fits whose reach the tile's extent holds. The report
/// counts the owned points.
template <class ConcurrencyTag, class Input, class Kernel>
Driver_run fit_one_tile(const Input& input, const Driver_settings& settings, const Kernel& kernel)
{
  const std::size_t N = input.size();
  Tile_input tile;
  tile.points = input.points;
  tile.finite = input.finite;
  tile.normals = input.normals;
  tile.indices.resize(N);
  std::iota(tile.indices.begin(), tile.indices.end(), std::size_t(0));
  tile.active = input.owned.empty() ? std::vector<unsigned char>(N, 1) : input.owned;
  const Bbox_3& e = settings.tile.extent;
  const Bbox_3& b = settings.tile.bounds;
  tile.extent = Box{{e.xmin(), e.ymin(), e.zmin()}, {e.xmax(), e.ymax(), e.zmax()}};
  tile.bounds = Box{{b.xmin(), b.ymin(), b.zmin()}, {b.xmax(), b.ymax(), b.zmax()}};
  Pass_result pass = fit_pass<ConcurrencyTag>(tile, settings, kernel, nullptr, Pass_kind::MAIN);

  Driver_run owned; // the counts over the owned points that the tile holds
  std::vector<unsigned char> status, reduced;
  std::size_t outside = 0;
  for(std::size_t i = 0; i < N; ++i)
  {
    if(!tile.active[i]) continue;
    if(!pass.outside.empty() && pass.outside[i]) { ++outside; continue; }
    owned.fitted.push_back(pass.fitted[i]);
    status.push_back(pass.status.empty() ? (unsigned char)(Fit_status::TOO_FEW_POINTS) : pass.status[i]);
    reduced.push_back(pass.reduced[i]);
  }
  if(!pass.status.empty()) count_points(owned, status, reduced);
  Driver_run run;
  run.report = owned.report;
  run.report.number_of_points = owned.fitted.size() + outside;
  run.report.number_of_outside_points = outside;
  run.report.number_of_tiles = 1;
  run.report.interrupted = pass.interrupted;
  run.fitted = std::move(pass.fitted);
  run.outside = std::move(pass.outside);
  return run;
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_TILED_DRIVER_H
