// The named parameters that CGAL users pass to the jet functions (jet_estimate_normals,
// jet_smooth_point_set, Monge_via_jet_fitting), given to the four Wavejet functions: each one is
// honoured or rejected with a clear std::invalid_argument, never silently dropped.
//   degree_fitting   honoured as the order (same results as order(d)); order + degree_fitting must agree
//   degree_monge     2 accepted by wavejet_estimate_curvatures; rejected elsewhere and for other values
//   neighbor_radius  honoured (Rf = r)
//   point_map        honoured (a map into a user struct)
//   normal_map       honoured (read and written)
//   callback         honoured (called; false interrupts and nothing is written)
//   geom_traits      honoured (same results with an explicit kernel)
// Run from test/Wavejets (reads data/kitten.xyz).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <cstdlib>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wavejets_test_support.h"
#include "wavejets_test_types.h"

using namespace wavejets_test::types;
namespace WJP = CGAL::Wavejets::parameters;

using wavejets_test::Case;
using wavejets_test::check_printed;

/// Runs `f`; true if it threw std::invalid_argument whose message contains every word of `words`.
static bool throws_naming(const std::function<void()>& f, const std::vector<std::string>& words)
{
  try { f(); }
  catch(const std::invalid_argument& e)
  {
    for(const std::string& w : words)
      if(std::string(e.what()).find(w) == std::string::npos)
      {
        std::cout << "       message lacks '" << w << "': " << e.what() << std::endl;
        return false;
      }
    return true;
  }
  return false;
}

static bool same_points(const std::vector<PV>& a, const std::vector<PV>& b, bool normals)
{
  if(a.size() != b.size()) return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    if(a[i].first != b[i].first || (normals && a[i].second != b[i].second)) return false;
  return true;
}

// A user type with its own point and normal members, reached through member property maps.
struct Sample
{
  Point position;
  Vector normal;
};
struct Sample_point_map
{
  typedef Sample key_type;
  typedef Point value_type;
  typedef const Point& reference;
  typedef boost::readable_property_map_tag category;
  friend const Point& get(const Sample_point_map&, const Sample& s) { return s.position; }
};
struct Sample_normal_map
{
  typedef Sample key_type;
  typedef Vector value_type;
  typedef const Vector& reference;
  typedef boost::read_write_property_map_tag category;
  friend const Vector& get(const Sample_normal_map&, const Sample& s) { return s.normal; }
  friend void put(const Sample_normal_map&, Sample& s, const Vector& n) { s.normal = n; }
};

static void test_degree_fitting(const std::vector<PV>& input)
{
  const auto pm = CGAL::parameters::point_map(Point_map()).normal_map(Normal_map());
  // wavejet_estimate_normals: degree_fitting(4) == order(4), and differs from the default order 2.
  std::vector<PV> by_order = input, by_degree = input, by_default = input;
  CGAL::wavejet_estimate_normals<Seq>(by_order, 18, WJP::order(4, pm));
  CGAL::wavejet_estimate_normals<Seq>(by_degree, 18, pm.degree_fitting(4));
  CGAL::wavejet_estimate_normals<Seq>(by_default, 18, pm);
  check_printed(same_points(by_order, by_degree, true), "estimate_normals: degree_fitting(4) gives order(4)'s normals bitwise");
  check_printed(!same_points(by_order, by_default, true), "estimate_normals: degree_fitting(4) is not ignored (differs from the default order 2)");
  std::vector<PV> both = input;
  CGAL::wavejet_estimate_normals<Seq>(both, 18, WJP::order(4, pm.degree_fitting(4)));
  check_printed(same_points(by_order, both, true), "estimate_normals: order(4) with degree_fitting(4) is accepted");

  // wavejet_estimate_curvatures, on a range of indices with a point map into a vector (the output
  // maps are indexed the same way).
  {
    std::vector<Point> pts;
    for(const PV& p : input) pts.push_back(p.first);
    std::vector<std::size_t> idx(pts.size());
    for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    const auto by_index = CGAL::make_property_map(pts);
    std::vector<double> a(pts.size(), 0.), b(pts.size(), 0.), c(pts.size(), 0.), d(pts.size(), 0.);
    CGAL::wavejet_estimate_curvatures<Seq>(idx, 24, WJP::mean_curvature_map(CGAL::make_property_map(a)).order(3).point_map(by_index));
    CGAL::wavejet_estimate_curvatures<Seq>(idx, 24, WJP::mean_curvature_map(CGAL::make_property_map(b)).point_map(by_index).degree_fitting(3));
    CGAL::wavejet_estimate_curvatures<Seq>(idx, 24, WJP::mean_curvature_map(CGAL::make_property_map(c)).point_map(by_index));
    check_printed(a == b, "estimate_curvatures: degree_fitting(3) gives order(3)'s mean curvatures bitwise");
    check_printed(a != c, "estimate_curvatures: degree_fitting(3) is not ignored (differs from the default order 2)");
    CGAL::wavejet_estimate_curvatures<Seq>(idx, 24, WJP::mean_curvature_map(CGAL::make_property_map(d)).order(3).point_map(by_index).degree_monge(2));
    check_printed(a == d, "estimate_curvatures: degree_monge(2) is accepted and changes nothing");
    check_printed(throws_naming([&] {
            CGAL::wavejet_estimate_curvatures<Seq>(idx, 24, WJP::mean_curvature_map(CGAL::make_property_map(d)).point_map(by_index).degree_monge(3));
          }, {"wavejet_estimate_curvatures", "degree_monge"}),
          "estimate_curvatures: degree_monge(3) throws, naming degree_monge");
  }

  // wavejet_enhance_positions and wavejet_enhance_normals (default order 4)
  std::vector<PV> p_order = input, p_degree = input, p_default = input;
  CGAL::wavejet_enhance_positions<Seq>(p_order, 30, 2., WJP::order(3, pm));
  CGAL::wavejet_enhance_positions<Seq>(p_degree, 30, 2., pm.degree_fitting(3));
  CGAL::wavejet_enhance_positions<Seq>(p_default, 30, 2., pm);
  check_printed(same_points(p_order, p_degree, false), "enhance_positions: degree_fitting(3) gives order(3)'s positions bitwise");
  check_printed(!same_points(p_order, p_default, false), "enhance_positions: degree_fitting(3) is not ignored (differs from the default order 4)");
  std::vector<PV> n_order = input, n_degree = input, n_default = input;
  CGAL::wavejet_enhance_normals<Seq>(n_order, 40, 3., WJP::order(5, pm));
  CGAL::wavejet_enhance_normals<Seq>(n_degree, 40, 3., pm.degree_fitting(5));
  CGAL::wavejet_enhance_normals<Seq>(n_default, 40, 3., pm);
  check_printed(same_points(n_order, n_degree, true), "enhance_normals: degree_fitting(5) gives order(5)'s normals bitwise");
  check_printed(!same_points(n_order, n_default, true), "enhance_normals: degree_fitting(5) is not ignored (differs from the default order 4)");

  // Conflicts and bad values: a clear message naming both parameters.
  std::vector<PV> scratch = input;
  check_printed(throws_naming([&] { CGAL::wavejet_estimate_normals<Seq>(scratch, 18, WJP::order(3, pm.degree_fitting(4))); },
                      {"wavejet_estimate_normals", "order(3)", "degree_fitting(4)"}),
        "estimate_normals: order(3) with degree_fitting(4) throws, naming both");
  check_printed(throws_naming([&] { CGAL::wavejet_enhance_positions<Seq>(scratch, 18, 2., WJP::order(2, pm.degree_fitting(4))); },
                      {"wavejet_enhance_positions", "order(2)", "degree_fitting(4)"}),
        "enhance_positions: order(2) with degree_fitting(4) throws, naming both");
  check_printed(throws_naming([&] { CGAL::wavejet_enhance_normals<Seq>(scratch, 18, 2., pm.degree_fitting(0)); },
                      {"wavejet_enhance_normals", "degree_fitting must be >= 1"}),
        "enhance_normals: degree_fitting(0) throws");
  check_printed(throws_naming([&] { CGAL::wavejet_estimate_normals<Seq>(scratch, 18, pm.degree_fitting(-2)); },
                      {"degree_fitting must be >= 1"}),
        "estimate_normals: degree_fitting(-2) throws (no wrap-around to a huge order)");
  check_printed(throws_naming([&] { CGAL::wavejet_estimate_normals<Seq>(scratch, 18, pm.degree_monge(2)); },
                      {"wavejet_estimate_normals", "degree_monge has no meaning"}),
        "estimate_normals: degree_monge throws (no meaning there)");
  check_printed(throws_naming([&] { CGAL::wavejet_enhance_positions<Seq>(scratch, 18, 2., pm.degree_monge(2)); },
                      {"wavejet_enhance_positions", "degree_monge has no meaning"}),
        "enhance_positions: degree_monge throws (no meaning there)");
  check_printed(same_points(scratch, input, true), "rejected calls leave the points untouched");
}

static void test_other_cgal_names(const std::vector<PV>& input)
{
  const auto pm = CGAL::parameters::point_map(Point_map()).normal_map(Normal_map());

  // neighbor_radius: Rf = r, so a radius much larger than the k-NN radius changes the result.
  std::vector<PV> knn = input, radius = input;
  CGAL::wavejet_estimate_normals<Seq>(knn, 18, pm);
  const auto report = CGAL::wavejet_estimate_normals<Seq>(radius, 0, pm.neighbor_radius(0.08));
  check_printed(!same_points(knn, radius, true) && report.number_of_fitted_points > input.size() / 2,
        "neighbor_radius is honoured (radius neighborhoods differ from 18-NN)");

  // point_map / normal_map into a user struct: same normals as on pairs.
  std::vector<Sample> samples;
  for(const PV& p : input) samples.push_back(Sample{p.first, p.second});
  CGAL::wavejet_estimate_normals<Seq>(samples, 18, CGAL::parameters::point_map(Sample_point_map())
                                                      .normal_map(Sample_normal_map()));
  bool same = true;
  for(std::size_t i = 0; i < samples.size(); ++i) same = same && samples[i].normal == knn[i].second;
  check_printed(same, "point_map and normal_map on a user struct are honoured (same normals as on pairs)");

  // geom_traits: an explicit kernel gives the same result.
  std::vector<PV> traits = input;
  CGAL::wavejet_estimate_normals<Seq>(traits, 18, pm.geom_traits(Kernel()));
  check_printed(same_points(knn, traits, true), "geom_traits(Kernel()) is honoured (same result)");

  // callback: called with increasing progress; returning false interrupts and nothing is written.
  std::vector<PV> called = input;
  int calls = 0;
  double last = -1.;
  bool increasing = true;
  CGAL::wavejet_enhance_positions<Seq>(called, 18, 2., pm.callback(std::function<bool(double)>([&](double t) {
    ++calls;
    increasing = increasing && t >= last;
    last = t;
    return true;
  })));
  check_printed(calls > 0 && increasing, "callback is called with non-decreasing progress (" + std::to_string(calls) + " calls)");
  std::vector<PV> stopped = input;
  const auto interrupted = CGAL::wavejet_enhance_positions<Seq>(stopped, 18, 2.,
    pm.callback(std::function<bool(double)>([](double t) { return t < 0.5; })));
  check_printed(interrupted.interrupted && same_points(stopped, input, true), "callback returning false interrupts; nothing is written");
}

/// data/kitten.xyz with its normals, read once.
static const std::vector<PV>& kitten()
{
  static const std::vector<PV> input = [] {
    std::vector<PV> v;
    if(!CGAL::IO::read_points("data/kitten.xyz", std::back_inserter(v),
                              CGAL::parameters::point_map(Point_map()).normal_map(Normal_map())) ||
       v.size() < 100)
      throw std::runtime_error("cannot read data/kitten.xyz");
    return v;
  }();
  return input;
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"degree_fitting_and_degree_monge", [] { test_degree_fitting(kitten()); }},
    Case{"radius_maps_traits_callback", [] { test_other_cgal_names(kitten()); }},
  });
}
