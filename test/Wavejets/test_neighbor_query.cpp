// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// The neighbor search (internal/neighbor_query.h over internal/kd_tree.h) against a brute-force
// search: the k nearest of every point (itself left out), or all within a radius (at most k),
// nearest first, ties by index, must be exactly the brute force's lists, on point sets made to
// catch a wrong pruning or tie rule: random, a regular grid (many equal distances, also at the k-th
// place and at the radius), heavy duplicates, a flat and a thin slab, tiny, huge and off-origin
// coordinates, points kept out of the tree. The queries run in index order, in the tree's leaf
// order and in a random order, with one scratch reused across k and across two searches (the bound
// carried from the previous query must never change a list). Also: the tree and its leaf order
// do not depend on the concurrency tag; degenerate inputs (no point in the tree, one point, k above
// N, a non-finite query point) give the documented lists.

#include <CGAL/Wavejets/internal/neighbor_query.h>

#include "wavejets_test_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

using CGAL::Wavejets::internal::Neighbor_query;
using wavejets_test::check;
typedef Neighbor_query::Point Point;

namespace {

typedef std::vector<std::pair<double, std::size_t> > Sorted_points;

// Every other point of the tree, sorted by (squared distance to point i, index).
Sorted_points by_distance(const std::vector<Point>& points, const std::vector<unsigned char>& in_tree, std::size_t i)
{
  Sorted_points all;
  for(std::size_t j = 0; j < points.size(); ++j)
    if(j != i && in_tree[j]) all.emplace_back(CGAL::squared_distance(points[i], points[j]), j);
  std::sort(all.begin(), all.end());
  return all;
}

// The lists by definition: of the sorted points, those within `radius` (if > 0), the first k (if k > 0).
std::vector<std::size_t> brute_force(const Sorted_points& sorted, unsigned int k, double radius)
{
  std::vector<std::size_t> out;
  for(const auto& a : sorted)
  {
    if((k > 0 && out.size() == k) || (radius > 0. && !(a.first <= radius * radius))) break;
    out.push_back(a.second);
  }
  return out;
}

std::vector<std::size_t> brute_force(const std::vector<Point>& points, const std::vector<unsigned char>& in_tree,
                                     std::size_t i, unsigned int k, double radius)
{
  return brute_force(by_distance(points, in_tree, i), k, radius);
}

struct Point_set_case
{
  std::string name;
  std::vector<Point> points;
  std::vector<unsigned char> in_tree;
};

std::vector<Point_set_case> point_sets()
{
  std::mt19937 rng(20261202);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  std::vector<Point_set_case> sets;
  auto add = [&](const std::string& name, std::size_t n, auto make) {
    Point_set_case s;
    s.name = name;
    for(std::size_t i = 0; i < n; ++i) s.points.push_back(make(i));
    s.in_tree.assign(n, 1);
    sets.push_back(s);
  };
  add("random", 1500, [&](std::size_t) { return Point(uniform(rng), uniform(rng), uniform(rng)); });
  add("grid 12 x 12 x 8", 12 * 12 * 8, [&](std::size_t i) { return Point(double(i % 12), double(i / 12 % 12), double(i / 144)); });
  add("duplicates (27 positions)", 900, [&](std::size_t) {
    return Point(std::floor(1.5 * uniform(rng)), std::floor(1.5 * uniform(rng)), std::floor(1.5 * uniform(rng)));
  });
  add("flat slab", 1200, [&](std::size_t) { return Point(uniform(rng), uniform(rng), 1e-9 * uniform(rng)); });
  add("thin needle", 1000, [&](std::size_t) { return Point(uniform(rng), 1e-7 * uniform(rng), 1e-7 * uniform(rng)); });
  add("tiny coordinates (1e-150)", 800, [&](std::size_t) { return Point(1e-150 * uniform(rng), 1e-150 * uniform(rng), 1e-150 * uniform(rng)); });
  add("huge coordinates (1e150)", 800, [&](std::size_t) { return Point(1e150 * uniform(rng), 1e150 * uniform(rng), 1e150 * uniform(rng)); });
  add("far from the origin (1e7 + [0, 1e-3])", 1000, [&](std::size_t) {
    return Point(1e7 + 1e-3 * uniform(rng), -1e7 + 1e-3 * uniform(rng), 1e7 + 1e-3 * uniform(rng));
  });
  // Every seventh point of a random set kept out of the tree (as the functions keep non-finite ones).
  add("random, every 7th point out of the tree", 1400, [&](std::size_t) { return Point(uniform(rng), uniform(rng), uniform(rng)); });
  for(std::size_t i = 0; i < sets.back().in_tree.size(); i += 7) sets.back().in_tree[i] = 0;
  return sets;
}

void compare_with_brute_force(const Point_set_case& s, const std::vector<Sorted_points>& sorted, const Neighbor_query& query,
                              const std::vector<std::size_t>& order, const std::string& order_name, unsigned int k,
                              double radius, Neighbor_query::Scratch& scratch)
{
  std::size_t differences = 0, first = 0;
  std::vector<std::size_t> found;
  for(std::size_t i : order)
  {
    query.neighbors(i, k, radius, found, scratch);
    if(found != brute_force(sorted[i], k, radius) && differences++ == 0) first = i;
  }
  check(differences == 0, s.name + ", " + order_name + ", k " + std::to_string(k) + ", radius " + std::to_string(radius) +
                             ": " + std::to_string(differences) + " lists differ from the brute force (first: point " +
                             std::to_string(first) + ")");
}

void knn_and_radius_against_brute_force()
{
  for(const Point_set_case& s : point_sets())
  {
    const Neighbor_query query(s.points, s.in_tree);
    std::vector<std::size_t> index_order(s.points.size());
    std::iota(index_order.begin(), index_order.end(), std::size_t(0));
    std::vector<std::size_t> random_order = index_order;
    std::shuffle(random_order.begin(), random_order.end(), std::mt19937(7));
    const std::vector<std::size_t> leaf_order = query.processing_order();
    std::vector<Sorted_points> sorted(s.points.size());
    for(std::size_t i = 0; i < s.points.size(); ++i) sorted[i] = by_distance(s.points, s.in_tree, i);
    // The scale of the set: its grid step, or the mean spacing of a random set of this size.
    const double scale = s.name.find("tiny") != std::string::npos ? 1e-150
                         : s.name.find("huge") != std::string::npos ? 1e150
                         : s.name.find("far") != std::string::npos ? 1e-3 : 1.;
    Neighbor_query::Scratch scratch; // one for every query below: k changes, radius and k-NN mix
    // k up to 32: the search selects the k nearest and ranks them; above, the candidates (up to
    // 2k + 15) are put in order by buckets (k 40, 96, 200), or sorted where a bucket is crowded (the
    // duplicates) or above 512 candidates (k 300).
    for(unsigned int k : {1u, 6u, 18u, 32u, 33u, 40u, 96u, 200u, 300u})
    {
      compare_with_brute_force(s, sorted, query, leaf_order, "leaf order", k, 0., scratch);
      compare_with_brute_force(s, sorted, query, random_order, "random order", k, 0., scratch);
    }
    compare_with_brute_force(s, sorted, query, index_order, "index order", 18, 0., scratch);
    for(double r : {0.15, 1., 2.})
    {
      compare_with_brute_force(s, sorted, query, leaf_order, "leaf order", 0, r * scale, scratch);
      compare_with_brute_force(s, sorted, query, random_order, "random order, at most 10", 10, r * scale, scratch);
    }
  }
}

void scratch_shared_by_two_searches()
{
  // Two searches over different sets, one scratch, queries alternating: the bound of one search's
  // last query must not be used by the other.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(0., 1.);
  std::vector<Point> a, b;
  for(int i = 0; i < 600; ++i) a.emplace_back(uniform(rng), uniform(rng), 0.);
  for(int i = 0; i < 600; ++i) b.emplace_back(100. * uniform(rng), 100. * uniform(rng), 100. * uniform(rng));
  const std::vector<unsigned char> all(600, 1);
  const Neighbor_query qa(a, all), qb(b, all);
  Neighbor_query::Scratch scratch;
  std::size_t differences = 0;
  std::vector<std::size_t> found;
  for(std::size_t i = 0; i < 600; ++i)
  {
    qa.neighbors(i, 12, 0., found, scratch);
    differences += found != brute_force(a, all, i, 12, 0.);
    qb.neighbors(i, 12, 0., found, scratch);
    differences += found != brute_force(b, all, i, 12, 0.);
  }
  check(differences == 0, "alternating searches over two sets with one scratch: " + std::to_string(differences) + " lists differ");
}

void tree_independent_of_concurrency()
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  std::vector<Point> points;
  for(int i = 0; i < 120000; ++i) points.emplace_back(uniform(rng), uniform(rng), 0.1 * uniform(rng)); // above the parallel grain
  const std::vector<unsigned char> all(points.size(), 1);
  const Neighbor_query sequential(points, all, CGAL::Sequential_tag());
#ifdef CGAL_LINKED_WITH_TBB
  const Neighbor_query parallel(points, all, CGAL::Parallel_tag());
  check(sequential.processing_order() == parallel.processing_order(),
        "the tree's leaf order is the same with Sequential_tag and Parallel_tag");
#endif
  std::vector<std::size_t> order = sequential.processing_order();
  std::vector<std::size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::size_t> expected(points.size());
  std::iota(expected.begin(), expected.end(), std::size_t(0));
  check(sorted == expected, "the processing order is a permutation of all indices");
  std::size_t differences = 0;
  std::vector<std::size_t> found;
  Neighbor_query::Scratch scratch;
  for(std::size_t position = 0; position < points.size(); position += 997)
  {
    sequential.neighbors(order[position], 30, 0., found, scratch);
    differences += found != brute_force(points, all, order[position], 30, 0.);
  }
  check(differences == 0, "120,000 points, every 997th in leaf order, k 30: " + std::to_string(differences) + " lists differ");
}

void degenerate_inputs()
{
  std::vector<std::size_t> found;
  Neighbor_query::Scratch scratch;
  {
    const std::vector<Point> points(5, Point(1., 2., 3.));
    const Neighbor_query query(points, std::vector<unsigned char>(5, 0));
    query.neighbors(2, 3, 0., found, scratch);
    check(found.empty(), "no point in the tree: no neighbor");
    check(query.processing_order() == std::vector<std::size_t>({0, 1, 2, 3, 4}),
          "no point in the tree: the processing order is by index");
  }
  {
    const std::vector<Point> points(1, Point(0., 0., 0.));
    const Neighbor_query query(points, std::vector<unsigned char>(1, 1));
    query.neighbors(0, 5, 0., found, scratch);
    check(found.empty(), "one point: no neighbor (the query point is never returned)");
    query.neighbors(0, 0, 1., found, scratch);
    check(found.empty(), "one point, radius: no neighbor");
  }
  {
    const std::vector<Point> points = {Point(0., 0., 0.), Point(3., 0., 0.), Point(1., 0., 0.), Point(0., 2., 0.)};
    const Neighbor_query query(points, std::vector<unsigned char>(4, 1));
    query.neighbors(0, 10, 0., found, scratch);
    check(found == std::vector<std::size_t>({2, 3, 1}), "k above N: every other point, nearest first");
    query.neighbors(0, 4000000000u, 0., found, scratch); // must not size anything by k
    check(found == std::vector<std::size_t>({2, 3, 1}), "k = 4e9: every other point, nearest first");
    query.neighbors(0, 0, 2., found, scratch);
    check(found == std::vector<std::size_t>({2, 3}), "radius 2: the point at exactly distance 2 is included");
  }
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Point> points = {Point(0., 0., 0.), Point(1., 0., 0.), Point(nan, 0., 0.), Point(2., 0., 0.)};
    const std::vector<unsigned char> in_tree = {1, 1, 0, 1};
    const Neighbor_query query(points, in_tree);
    query.neighbors(2, 2, 0., found, scratch); // a non-finite point: no distance compares
    check(found.empty(), "a non-finite query point: no neighbor");
    query.neighbors(3, 2, 0., found, scratch); // after it: no bound carried from the non-finite point
    check(found == std::vector<std::size_t>({1, 0}), "the query after a non-finite one: its two nearest");
  }
}

} // namespace

int main(int argc, char** argv)
{
  using wavejets_test::Case;
  return wavejets_test::run_cases(argc, argv, {
    Case{"search.brute_force", knn_and_radius_against_brute_force},
    Case{"search.shared_scratch", scratch_shared_by_two_searches},
    Case{"search.concurrency", tree_independent_of_concurrency},
    Case{"search.degenerate", degenerate_inputs},
  });
}
