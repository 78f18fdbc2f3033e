// Tests of tiled runs (the named parameter tile_size; doc/Wavejets/Mathematics.txt §12): every
// function, run tile by tile, gives the in-core results bit for bit (outputs, fitted maps and
// report counts), on real scans (data/kitten.xyz, 100,000 points sampled on data/bunny00.off) and
// on the inputs where tiles are hard: duplicate points, a dense cluster across a tile corner, k
// larger than a tile's population, radius neighborhoods, the Hermite fit's two passes, non-finite
// points, a first halo far too small (detected and repaired), an interruption.
// Run from test/Wavejets; the argument names a case or a group of cases (--list).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_enhance_normals.h>

#include <cmath>
#include <complex>
#include <iostream>
#include <algorithm>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavejets_test_data.h"
#include "wavejets_test_support.h"
#include "wavejets_test_types.h"

using namespace wavejets_test;
using namespace wavejets_test::types;
namespace WJP = CGAL::Wavejets::parameters;
typedef CGAL::Wavejets::Processing_report Report;

static const Point_map pm;
static const Normal_map nm;

/// How the functions are called: neighborhood, order, Hermite fit, tiles.
struct Setup
{
  unsigned int k = 18;
  double radius = 0.;
  std::size_t order = 2;
  bool hermite = false;
  std::size_t tile_size = 0; // 0: in core
  double tile_halo = 0.;     // 0: estimated
};

/// The outputs of the four functions on one input, and their reports.
struct Outputs
{
  PV_range normals, moved, filtered;
  std::vector<double> H, KG, k1, k2;
  std::vector<Vector> d1, d2;
  std::vector<unsigned char> fitted[4];
  Report reports[4];
};

/// The parameters of a call as they are (`extend(range, function, np)` may add some).
struct No_extension
{
  template <class NP> const NP& operator()(const PV_range&, int, const NP& np) const { return np; }
};

template <class Tag, class Extend = No_extension>
Outputs run_functions(const PV_range& input, const Setup& s, const Extend& extend = Extend())
{
  Outputs o;
  auto common = [&](std::size_t order, PV_range& range, int f) {
    return extend(range, f, WJP::order(order).tile_size(s.tile_size).tile_halo(s.tile_halo)
      .use_neighbor_normals(s.hermite).fitted_map(slot_map(range, o.fitted[f])).neighbor_radius(s.radius)
      .point_map(pm).normal_map(nm));
  };
  o.normals = input;
  o.reports[0] = CGAL::wavejet_estimate_normals<Tag>(o.normals, s.k, common(s.order, o.normals, 0));
  PV_range c = input;
  o.H.assign(input.size(), 0.);
  o.d1.assign(input.size(), CGAL::NULL_VECTOR); // unfitted points keep these (a Vector_3 is not
  o.d2.assign(input.size(), CGAL::NULL_VECTOR); // initialized by its default constructor)
  o.reports[1] = CGAL::wavejet_estimate_curvatures<Tag>(c, s.k,
    WJP::mean_curvature_map(slot_map(c, o.H), common(s.order, c, 1))
      .gaussian_curvature_map(slot_map(c, o.KG)).maximal_principal_curvature_map(slot_map(c, o.k1))
      .minimal_principal_curvature_map(slot_map(c, o.k2)).maximal_principal_direction_map(slot_map(c, o.d1))
      .minimal_principal_direction_map(slot_map(c, o.d2)));
  o.moved = input;
  o.reports[2] = CGAL::wavejet_enhance_positions<Tag>(o.moved, s.k, 2.,
    WJP::write_normals(true, common(s.order + 2, o.moved, 2)));
  o.filtered = input;
  o.reports[3] = CGAL::wavejet_enhance_normals<Tag>(o.filtered, s.k, std::complex<double>(2., 0.5),
    WJP::restrict_to_consistent_normals(true, common(s.order + 2, o.filtered, 3)));
  return o;
}

bool same_counts(const Report& a, const Report& b)
{
  return a.number_of_points == b.number_of_points && a.number_of_fitted_points == b.number_of_fitted_points &&
         a.number_of_unfitted_points == b.number_of_unfitted_points &&
         a.number_of_non_finite_points == b.number_of_non_finite_points &&
         a.number_of_reduced_order_points == b.number_of_reduced_order_points &&
         a.number_of_clamped_points == b.number_of_clamped_points && a.interrupted == b.interrupted;
}

/// Checks that the tiled run `t` equals the in-core run `c` bit for bit; prints the tiles and repairs.
bool check_equal(const std::string& what, const Outputs& c, const Outputs& t)
{
  static const char* names[4] = {"estimate_normals", "estimate_curvatures", "enhance_positions", "enhance_normals"};
  bool ok = true;
  ok &= check(same_bits(c.normals, t.normals), what + ": normals bitwise");
  ok &= check(same_bits(c.H, t.H) && same_bits(c.KG, t.KG) && same_bits(c.k1, t.k1) && same_bits(c.k2, t.k2) &&
                same_bits(c.d1, t.d1) && same_bits(c.d2, t.d2), what + ": curvatures bitwise");
  ok &= check(same_bits(c.moved, t.moved), what + ": moved points and written normals bitwise");
  ok &= check(same_bits(c.filtered, t.filtered), what + ": filtered normals bitwise");
  std::string counts;
  for(int f = 0; f < 4; ++f)
  {
    ok &= check(c.fitted[f] == t.fitted[f], what + ": fitted map of " + names[f]);
    ok &= check(same_counts(c.reports[f], t.reports[f]), what + ": report counts of " + names[f]);
    ok &= check(c.reports[f].number_of_tiles <= 1, what + ": in core, one tile");
    counts += std::string(f ? "; " : "") + names[f] + " " + std::to_string(t.reports[f].number_of_tiles) + " tiles, " +
              std::to_string(t.reports[f].number_of_repaired_points) + " repaired";
  }
  ok &= check(t.reports[0].number_of_fitted_points > t.reports[0].number_of_points / 2, what + ": most points fitted");
  report(what, ok, std::to_string(t.reports[0].number_of_points) + " points, " +
                     std::to_string(t.reports[0].number_of_fitted_points) + " fitted; " + counts);
  return ok;
}

/// In core against tiled (sequential and parallel) on `input`.
void compare_tiled(const std::string& what, const PV_range& input, Setup s, std::size_t tile_size)
{
  const Outputs in_core = run_functions<Par>(input, s);
  s.tile_size = tile_size;
  const Outputs tiled = run_functions<Seq>(input, s);
  check_equal(what + ", " + std::to_string(tile_size) + "-point tiles, sequential", in_core, tiled);
  check(tiled.reports[0].number_of_tiles >= input.size() / tile_size, what + ": as many tiles as asked");
  const Outputs parallel = run_functions<Par>(input, s);
  check_equal(what + ", " + std::to_string(tile_size) + "-point tiles, parallel", in_core, parallel);
}

/// 100,000 random points on data/bunny00.off, with unoriented normals estimated in core (k 18).
static const PV_range& bunny_sample()
{
  static const PV_range pts = [] {
    PV_range v = sample_mesh("data/bunny00.off", 100000, 7, CGAL::NULL_VECTOR);
    CGAL::wavejet_estimate_normals<Par>(v, 18, WJP::order(std::size_t(2)).point_map(pm).normal_map(nm));
    return v;
  }();
  return pts;
}

/// A wavy sheet of 20,000 points with hard cases: 40 points repeated 50 times each, a cluster of
/// 5,000 points in a disk of radius 0.01 at the origin (where the first two median splits cross:
/// a tile corner), and 3 points with NaN or infinite coordinates.
static PV_range hard_sheet()
{
  PV_range v;
  Gauss g(11);
  auto sheet = [](double x, double y) {
    return Point(x, y, 0.1 * std::sin(3. * x) * std::cos(2. * y));
  };
  for(int i = 0; i < 20000; ++i) v.emplace_back(sheet(2. * g.uniform() - 1., 2. * g.uniform() - 1.), Vector(0, 0, 1));
  for(int i = 0; i < 5000; ++i)
  {
    const double r = 0.01 * std::sqrt(g.uniform()), a = 6.283185307179586 * g.uniform();
    v.emplace_back(sheet(r * std::cos(a), r * std::sin(a)), Vector(0, 0, 1));
  }
  for(int i = 0; i < 40; ++i)
    for(int copy = 0; copy < 50; ++copy) v.push_back(v[std::size_t(i) * 97]);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  v.emplace_back(Point(nan, 0, 0), Vector(0, 0, 1));
  v.emplace_back(Point(0, inf, 0), Vector(0, 0, 1));
  v.emplace_back(Point(0.5, 0.5, -inf), Vector(0, 0, 1));
  return v;
}

void test_kitten()
{
  Setup s;
  compare_tiled("kitten, k 18", kitten(), s, 300);
}

void test_bunny_sample()
{
  Setup s;
  compare_tiled("bunny 100k sample, k 18", bunny_sample(), s, 4000);
}

void test_hard_inputs()
{
  const PV_range sheet = hard_sheet();
  // The cluster lies across several tiles (a tile corner runs through it).
  {
    std::vector<CGAL::Wavejets::internal::Neighbor_query::Point> points;
    std::vector<unsigned char> finite;
    for(const PV& p : sheet)
    {
      points.emplace_back(p.first.x(), p.first.y(), p.first.z());
      finite.push_back(std::isfinite(p.first.x()) && std::isfinite(p.first.y()) && std::isfinite(p.first.z()));
    }
    const CGAL::Wavejets::internal::Tiling tiling(points, finite, 300);
    std::set<std::size_t> tiles_of_cluster;
    for(std::size_t t = 0; t < tiling.size(); ++t)
      for(std::size_t i : tiling.points_of(t))
        if(i >= 20000 && i < 25000) tiles_of_cluster.insert(t);
    report("dense cluster across a tile corner", check(tiles_of_cluster.size() >= 4, "the cluster spans 4 tiles or more"),
           "the 5,000 points of the cluster lie in " + std::to_string(tiles_of_cluster.size()) + " of " +
             std::to_string(tiling.size()) + " tiles of at most 300 points");
  }
  Setup s;
  compare_tiled("hard sheet (duplicates, cluster, non-finite), k 18", sheet, s, 300);
  s.k = 40;
  compare_tiled("hard sheet, k 40 larger than the tiles", sheet, s, 16);
}

void test_radius_and_hermite()
{
  const PV_range& pts = kitten();
  Setup s;
  s.k = 0;
  s.radius = 0.03;
  compare_tiled("kitten, radius 0.03", pts, s, 500);
  s.k = 12;
  compare_tiled("kitten, radius 0.03 and at most 12 neighbors", pts, s, 500);
  s = Setup();
  s.hermite = true;
  compare_tiled("kitten, Hermite fit on the input normals", pts, s, 500);

  // Hermite fit with estimated neighbors' normals (two passes: two rings of neighbors): a range
  // without normals, curvatures only.
  std::vector<Point> points;
  for(const PV& p : pts) points.push_back(p.first);
  auto curvatures = [&](std::size_t tile_size, double halo, std::vector<double>& H, std::vector<unsigned char>& fitted) {
    std::vector<Point> copy = points;
    return CGAL::wavejet_estimate_curvatures<Par>(copy, 18,
      WJP::use_neighbor_normals(true).tile_size(tile_size).tile_halo(halo).mean_curvature_map(slot_map(copy, H))
        .fitted_map(slot_map(copy, fitted)));
  };
  std::vector<double> H_core;
  std::vector<unsigned char> f_core;
  const Report rc = curvatures(0, 0., H_core, f_core);
  // The estimated first halo (two neighborhoods wide), then one of 0.03, about one neighborhood:
  // the normals of the neighbors near its edge were fitted on incomplete neighborhoods, which only
  // the second ring of the reach detects.
  for(double halo : {0., 0.03})
  {
    std::vector<double> H_tiled;
    std::vector<unsigned char> f_tiled;
    const Report rt = curvatures(400, halo, H_tiled, f_tiled);
    report("kitten, Hermite fit with estimated normals (no normal map), 400-point tiles, first halo " +
             (halo > 0 ? significant_digits(halo, 3) : std::string("estimated")),
           check(same_bits(H_core, H_tiled) && f_core == f_tiled && same_counts(rc, rt), "H bitwise, fitted, counts"),
           std::to_string(rt.number_of_tiles) + " tiles, " + std::to_string(rt.number_of_repaired_points) + " repaired");
  }
}

void test_small_halo_repaired()
{
  // A first halo of 1e-9: nearly every neighborhood leaves it, is detected and fitted again.
  const PV_range& pts = kitten();
  Setup s;
  const Outputs in_core = run_functions<Par>(pts, s);
  s.tile_size = 500;
  s.tile_halo = 1e-9;
  const Outputs tiled = run_functions<Par>(pts, s);
  check_equal("kitten, first halo 1e-9 (repaired)", in_core, tiled);
  report("too small a halo is detected and repaired",
         check(tiled.reports[0].number_of_repaired_points > pts.size() / 2, "most points repaired"),
         std::to_string(tiled.reports[0].number_of_repaired_points) + " of " + std::to_string(pts.size()) +
           " points fitted again with a larger halo");
}

void test_contract()
{
  const PV_range& pts = kitten();
  // Interruption: nothing written.
  PV_range copy = pts;
  int calls = 0;
  std::vector<unsigned char> fitted(pts.size(), 7);
  const Report r = CGAL::wavejet_estimate_normals<Par>(copy, 18,
    WJP::tile_size(200).fitted_map(slot_map(copy, fitted)).callback([&](double) { return ++calls < 3; })
      .point_map(pm).normal_map(nm));
  check(r.interrupted, "interrupted");
  check(same_bits(copy, pts) && fitted == std::vector<unsigned char>(pts.size(), 7), "nothing written");
  // The callback sees the whole run once, from 0 to 1.
  copy = pts;
  double last = -1.;
  bool increasing = true;
  CGAL::wavejet_estimate_normals<Seq>(copy, 18, WJP::tile_size(200).callback([&](double x) {
    increasing &= x >= last && x <= 1.;
    last = x;
    return true;
  }).point_map(pm).normal_map(nm));
  check(increasing && last == 1., "progress from 0 to 1");
  // An empty range, a range within one tile, a bad parameter.
  PV_range empty;
  const Report re = CGAL::wavejet_estimate_normals<Par>(empty, 18, WJP::tile_size(10).point_map(pm).normal_map(nm));
  check(re.number_of_points == 0 && re.number_of_tiles == 0, "empty range: no tile");
  copy = pts;
  const Report r1 = CGAL::wavejet_estimate_normals<Par>(copy, 18, WJP::tile_size(pts.size()).point_map(pm).normal_map(nm));
  check(r1.number_of_tiles == 1, "a range within one tile runs in core");
  bool thrown = false;
  try { CGAL::wavejet_estimate_normals<Par>(copy, 18, WJP::tile_size(-1).point_map(pm).normal_map(nm)); }
  catch(const std::invalid_argument&) { thrown = true; }
  check(thrown, "tile_size < 0 rejected");
  thrown = false;
  try { CGAL::wavejet_estimate_normals<Par>(copy, 18, WJP::tile_size(10).tile_halo(-1.).point_map(pm).normal_map(nm)); }
  catch(const std::invalid_argument&) { thrown = true; }
  check(thrown, "tile_halo < 0 rejected");
  report("interruption, progress, empty range, parameters", true, std::to_string(calls) + " callback calls before the stop");
}

/// The unit of work of an out-of-core run, through the public interface (Wavejets::Tile): the
/// kitten cut in two tiles at the median x; each tile is run on the points within its halo only
/// (in range order), with `tile`, `owned_map` and `outside_map`; the points whose fits reach past the
/// halo are run again with a halo 4 times as wide. Put together, the results are the in-core ones.
void test_tile_unit()
{
  const PV_range& pts = kitten();
  const Setup s;
  const Outputs in_core = run_functions<Par>(pts, s);
  std::vector<double> x;
  CGAL::Bbox_3 bounds;
  for(const PV& p : pts) { x.push_back(p.first.x()); bounds += p.first.bbox(); }
  std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
  const double median = x[x.size() / 2];

  // The results put together, zero until written.
  const PV zero(CGAL::ORIGIN, CGAL::NULL_VECTOR);
  Outputs joined;
  joined.normals.assign(pts.size(), zero);
  joined.moved = joined.filtered = joined.normals;
  joined.H.assign(pts.size(), 0.);
  joined.KG = joined.k1 = joined.k2 = joined.H;
  joined.d1.assign(pts.size(), CGAL::NULL_VECTOR);
  joined.d2 = joined.d1;
  for(int f = 0; f < 4; ++f) joined.fitted[f].assign(pts.size(), 0);
  std::size_t rounds = 0, outside_points = 0, pending_total = 0;
  for(int side = 0; side < 2; ++side)
  {
    std::vector<std::size_t> pending;
    for(std::size_t i = 0; i < pts.size(); ++i)
      if((pts[i].first.x() < median) == (side == 0)) pending.push_back(i);
    pending_total += pending.size();
    for(double halo = 0.005; !pending.empty(); halo *= 4, ++rounds)
    {
      CGAL::Bbox_3 box;
      for(std::size_t i : pending) box += pts[i].first.bbox();
      const CGAL::Bbox_3 extent(box.xmin() - halo, box.ymin() - halo, box.zmin() - halo, box.xmax() + halo,
                                box.ymax() + halo, box.zmax() + halo);
      PV_range local;
      std::vector<std::size_t> global;
      std::vector<unsigned char> owned;
      for(std::size_t i = 0, next = 0; i < pts.size(); ++i)
      {
        const bool is_pending = next < pending.size() && pending[next] == i;
        next += is_pending;
        if(!CGAL::do_overlap(extent, pts[i].first.bbox())) continue;
        local.push_back(pts[i]);
        global.push_back(i);
        owned.push_back(is_pending);
      }
      std::vector<unsigned char> outside[4];
      const CGAL::Wavejets::Tile tile{extent, bounds};
      const Outputs o = run_functions<Par>(local, s, [&](const PV_range& range, int f, const auto& np) {
        return WJP::tile(tile, WJP::owned_map(slot_map(range, owned), WJP::outside_map(slot_map(range, outside[f]), np)));
      });
      std::vector<std::size_t> still;
      for(std::size_t j = 0; j < local.size(); ++j)
      {
        if(!owned[j]) continue;
        check(outside[0][j] == outside[1][j] && outside[0][j] == outside[3][j], "same reach for the same neighborhoods");
        bool any_outside = false;
        for(int f = 0; f < 4; ++f) any_outside |= outside[f][j] != 0;
        if(any_outside) { still.push_back(global[j]); continue; }
        const std::size_t g = global[j];
        joined.normals[g] = o.normals[j];
        joined.H[g] = o.H[j]; joined.KG[g] = o.KG[j]; joined.k1[g] = o.k1[j]; joined.k2[g] = o.k2[j];
        joined.d1[g] = o.d1[j]; joined.d2[g] = o.d2[j];
        joined.moved[g] = o.moved[j];
        joined.filtered[g] = o.filtered[j];
        for(int f = 0; f < 4; ++f) joined.fitted[f][g] = o.fitted[f][j];
      }
      for(int f = 0; f < 4; ++f)
        check(o.reports[f].number_of_points == std::size_t(std::count(owned.begin(), owned.end(), 1)) &&
                o.reports[f].number_of_outside_points ==
                  std::size_t(std::count(outside[f].begin(), outside[f].end(), 1)),
              "report: the owned points, those outside");
      outside_points += still.size();
      pending = still;
    }
  }
  for(int f = 0; f < 4; ++f) joined.reports[f] = in_core.reports[f]; // counts are per tile here
  check_equal("kitten in two tiles through Wavejets::Tile", in_core, joined);
  report("the tile unit", check(outside_points > 0 && pending_total == pts.size(), "some fits reached past the first halo"),
         std::to_string(rounds) + " tile runs, " + std::to_string(outside_points) + " points run again with a wider halo");
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"real.kitten", test_kitten},
    Case{"real.bunny_sample", test_bunny_sample},
    Case{"hard.duplicates_cluster_large_k", test_hard_inputs},
    Case{"hard.radius_and_hermite", test_radius_and_hermite},
    Case{"hard.small_halo_repaired", test_small_halo_repaired},
    Case{"contract.interruption_progress_parameters", test_contract},
    Case{"contract.tile_unit", test_tile_unit},
  });
}
