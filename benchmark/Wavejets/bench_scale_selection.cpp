// Per-point scale selection (wavejet_estimate_scales) against one k for the whole surface:
// benchmark/Wavejets/scale_selection.md (its tables: csv/scale_selection.*.csv).
//
// Three height fields over [0,1]^2 whose y bands hold features of several sizes (flat, a large bend,
// medium bumps, fine bumps, a crease): with noise growing along x from 0 to 1% of the diagonal
// ("noise"), with the density falling 10x along x and noise 0.25% of the diagonal ("density"), and
// uniform with noise 0.1% ("features"). Regions: 4 bands of x times the 5 bands of y. Exact normals
// and mean curvature from the height field (central differences of the analytic function).
// Estimators, order 2: Wavejets at each k of the ladder (the best single k; the per-region oracle,
// each region's best k chosen with the truth; the per-point oracle, each point's smallest error over
// the ladder, a bound for any choice from the ladder); automatic (wavejet_estimate_scales, then the functions
// with neighborhood_size_map); CGAL's estimate_local_k_neighbor_scales feeding degree-2 jets
// (Monge_via_jet_fitting on each point's k nearest, CGAL's jet_estimate_normals there); PCA normals at
// their best single k; Ponca's APSS at its best single k (if built with Ponca).
//
//   bench_scale_selection [--points N] [--ladder K1,K2,...] [--name NAME] [--csv-dir DIR] [--no-write] [--quick]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/estimate_scale.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_scales.h>

#include "bench_common.h"
#include "ponca_types.h"
#include "wavejets_test_support.h"
#include "wavejets_test_types.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <iostream>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace wavejets_test::types;   // Kernel, Point, Vector, PV, PV_range, Point_map, Normal_map
typedef CGAL::Parallel_if_available_tag Tag;
namespace WJP = CGAL::Wavejets::parameters;

const double PI = 3.14159265358979323846;
const double DIAGONAL = std::sqrt(2.);
const int X_BANDS = 4, Y_BANDS = 5, REGIONS = X_BANDS * Y_BANDS;
const char* Y_BAND_NAMES[Y_BANDS] = {"flat", "bend", "medium bumps", "fine bumps", "crease"};

// A smooth step from 0 (t <= 0) to 1 (t >= 1).
double smoothstep(double t) { t = std::clamp(t, 0., 1.); return t * t * (3 - 2 * t); }
// 1 inside [a, b), 0 outside, with smooth transitions 0.03 wide.
double window(double y, double a, double b)
{
  return smoothstep((y - a) / 0.03 + 0.5) * (1 - smoothstep((y - b) / 0.03 + 0.5));
}
// The height field: y bands flat, a large bend, medium bumps (wavelength 1/8), fine bumps
// (wavelength 1/25), a crease (a ridge rounded over 0.002) along y = 0.9.
double height(double x, double y)
{
  return 0.15 * std::pow(std::sin(PI * (y - 0.2) / 0.2), 2) * window(y, 0.2, 0.4) +
         0.02 * std::sin(16 * PI * x) * std::sin(16 * PI * y) * window(y, 0.4, 0.6) +
         0.004 * std::sin(50 * PI * x) * std::sin(50 * PI * y) * window(y, 0.6, 0.8) +
         0.08 * std::sqrt(4e-6 + (y - 0.9) * (y - 0.9)) * window(y, 0.8, 2.);
}

struct Surface_data
{
  std::string name, description;
  PV_range points;               // noisy positions, exact normals (they orient the estimates only)
  std::vector<Vector> normal;    // exact
  std::vector<double> H;         // exact, positive where the surface bends toward its (upward) normal
  std::vector<int> region;       // -1: not evaluated (within 0.05 of the border)
};

Surface_data make_surface(const std::string& name, std::size_t N, unsigned seed)
{
  Surface_data d;
  d.name = name;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0., 1.);
  std::normal_distribution<double> g(0., 1.);
  while(d.points.size() < N)
  {
    const double x = u(rng), y = u(rng);
    if(name == "density" && u(rng) > 1. / (1. + 9. * x)) continue; // 10x denser at x = 0 than at x = 1
    const double e = 1e-4;
    const double f = height(x, y);
    const double fx = (height(x + e, y) - height(x - e, y)) / (2 * e), fy = (height(x, y + e) - height(x, y - e)) / (2 * e);
    const double fxx = (height(x + e, y) - 2 * f + height(x - e, y)) / (e * e);
    const double fyy = (height(x, y + e) - 2 * f + height(x, y - e)) / (e * e);
    const double fxy = (height(x + e, y + e) - height(x + e, y - e) - height(x - e, y + e) + height(x - e, y - e)) / (4 * e * e);
    const double w = std::sqrt(1 + fx * fx + fy * fy);
    const Vector n(-fx / w, -fy / w, 1. / w);
    const double sigma = name == "noise" ? 0.01 * DIAGONAL * x : name == "density" ? 0.0025 * DIAGONAL : 0.001 * DIAGONAL;
    d.points.emplace_back(Point(x, y, f) + sigma * g(rng) * n, n);
    d.normal.push_back(n);
    d.H.push_back(((1 + fy * fy) * fxx - 2 * fx * fy * fxy + (1 + fx * fx) * fyy) / (2 * w * w * w));
    const bool inside = x > 0.05 && x < 0.95 && y > 0.05 && y < 0.95;
    d.region.push_back(inside ? std::min(int(x * X_BANDS), X_BANDS - 1) * Y_BANDS + std::min(int(y * Y_BANDS), Y_BANDS - 1) : -1);
  }
  d.description = name == "noise" ? "noise from 0 to 1% of the diagonal along x"
                : name == "density" ? "density 10x higher at x = 0 than at x = 1, noise 0.25% of the diagonal"
                                    : "uniform density, noise 0.1% of the diagonal";
  return d;
}

/// Per-point normals and mean curvatures of one estimator (ok: estimated).
struct Estimate
{
  std::vector<Vector> n;
  std::vector<double> H;
  std::vector<unsigned char> ok;
  bool has_H = true;
  double seconds = 0.;
};

/// Errors per region: mean angle to the exact normal (degrees, unoriented) and mean |H error|.
struct Errors
{
  double angle[REGIONS] = {}, H[REGIONS] = {};
  double overall_angle = 0., overall_H = 0.;   // the mean over the regions (each weighs the same)
  std::size_t missing = 0;                     // evaluated points without an estimate
};

/// Each point's errors: angle to the exact normal (degrees, unoriented) and |H error|; ok: estimated.
struct Point_errors
{
  std::vector<double> angle, H;
  std::vector<unsigned char> ok;
};

Point_errors point_errors(const Surface_data& d, const Estimate& e)
{
  Point_errors r;
  for(std::size_t i = 0; i < d.points.size(); ++i)
  {
    const Vector& a = e.n[i];
    const Vector& b = d.normal[i];
    r.ok.push_back(e.ok[i]);
    r.angle.push_back(e.ok[i] ? std::atan2(std::sqrt(CGAL::cross_product(a, b).squared_length()), std::abs(a * b)) * 180. / PI : 0.);
    r.H.push_back(e.ok[i] && e.has_H ? std::abs(e.H[i] - d.H[i]) : 0.);
  }
  return r;
}

/// The means of each region, then over the regions.
Errors aggregate(const Surface_data& d, const Point_errors& p)
{
  Errors r;
  double count[REGIONS] = {};
  for(std::size_t i = 0; i < d.points.size(); ++i)
  {
    const int g = d.region[i];
    if(g < 0) continue;
    if(!p.ok[i]) { ++r.missing; continue; }
    r.angle[g] += p.angle[i];
    r.H[g] += p.H[i];
    ++count[g];
  }
  for(int g = 0; g < REGIONS; ++g)
  {
    r.angle[g] /= std::max(count[g], 1.);
    r.H[g] /= std::max(count[g], 1.);
    r.overall_angle += r.angle[g] / REGIONS;
    r.overall_H += r.H[g] / REGIONS;
  }
  return r;
}

Errors errors(const Surface_data& d, const Estimate& e) { return aggregate(d, point_errors(d, e)); }

/// The per-point oracle: each point's smallest error over the ladder (normals and H separately), a
/// bound that no choice of k from the ladder can beat.
Point_errors per_point_oracle(const std::vector<Point_errors>& single)
{
  Point_errors r = single.front();
  for(std::size_t j = 1; j < single.size(); ++j)
    for(std::size_t i = 0; i < r.ok.size(); ++i)
    {
      if(!single[j].ok[i]) continue;
      if(!r.ok[i]) { r.ok[i] = 1; r.angle[i] = single[j].angle[i]; r.H[i] = single[j].H[i]; continue; }
      r.angle[i] = std::min(r.angle[i], single[j].angle[i]);
      r.H[i] = std::min(r.H[i], single[j].H[i]);
    }
  return r;
}

double seconds_since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// Wavejets (order 2) at one k, or with a per-point k (`k_map`).
template <class Extra>
Estimate wavejets(const Surface_data& d, unsigned int k, const Extra& extra)
{
  Estimate e;
  const auto t = std::chrono::steady_clock::now();
  PV_range normals = d.points, curvatures = d.points;
  std::vector<double> H(d.points.size(), 0.);
  std::vector<unsigned char> fitted_n(d.points.size(), 0), fitted_c(d.points.size(), 0);
  auto H_map = wavejets_test::slot_map(curvatures, H);
  auto fn_map = wavejets_test::slot_map(normals, fitted_n);
  auto fc_map = wavejets_test::slot_map(curvatures, fitted_c);
  CGAL::wavejet_estimate_normals<Tag>(normals, k, extra(normals, WJP::orient_with_input_normals(true).fitted_map(fn_map)
                                                        .point_map(Point_map()).normal_map(Normal_map())));
  CGAL::wavejet_estimate_curvatures<Tag>(curvatures, k, extra(curvatures, WJP::mean_curvature_map(H_map).fitted_map(fc_map)
                                                              .point_map(Point_map()).normal_map(Normal_map())));
  e.seconds = seconds_since(t);
  for(std::size_t i = 0; i < d.points.size(); ++i)
  {
    e.n.push_back(normals[i].second);
    e.H.push_back(H[i]);
    e.ok.push_back(fitted_n[i] && fitted_c[i]);
  }
  return e;
}


/// No extra parameter: one k for every point.
struct One_k
{
  template <class NP> const NP& operator()(const PV_range&, const NP& np) const { return np; }
};
/// Each point's k from `k` (in the order of the points).
struct Per_point_k
{
  std::vector<unsigned int>* k;
  template <class NP> auto operator()(const PV_range& range, const NP& np) const
  {
    return WJP::neighborhood_size_map(wavejets_test::slot_map(range, *k), np);
  }
};

/// The package's k-nearest neighbors (the same definition as the functions'), for the other estimators.
struct Neighborhoods
{
  std::vector<CGAL::Wavejets::internal::Neighbor_query::Point> points;
  std::vector<unsigned char> finite;
  std::unique_ptr<CGAL::Wavejets::internal::Neighbor_query> query;
  explicit Neighborhoods(const PV_range& pts)
  {
    for(const PV& p : pts) points.emplace_back(p.first.x(), p.first.y(), p.first.z());
    finite.assign(points.size(), 1);
    query.reset(new CGAL::Wavejets::internal::Neighbor_query(points, finite, CGAL::Sequential_tag()));
  }
};

/// CGAL's degree-2 jets (Monge_via_jet_fitting, as jet_estimate_normals) on each point's own k nearest.
Estimate cgal_jets(const Surface_data& d, const Neighborhoods& hoods, const std::vector<unsigned int>& k)
{
  typedef CGAL::Monge_via_jet_fitting<Kernel> Monge;
  struct Jet { bool ok = false; double H = 0., K = 0., k1 = 0., k2 = 0.; Vector n = Vector(0, 0, 1); };
  Estimate e;
  const auto t = std::chrono::steady_clock::now();
  Monge monge;
  std::vector<std::size_t> nb;
  CGAL::Wavejets::internal::Neighbor_query::Scratch scratch;
  std::vector<Point> hood;
  for(std::size_t i = 0; i < d.points.size(); ++i)
  {
    hoods.query->neighbors(i, k[i], 0., nb, scratch);
    hood.assign(1, d.points[i].first);
    for(std::size_t j : nb) hood.push_back(d.points[j].first);
    Jet r;
    wavejets_bench::jet_estimate(monge, hood, 2, d.points[i].second, r);
    e.n.push_back(r.n);
    e.H.push_back(r.H);
    e.ok.push_back(r.ok);
  }
  e.seconds = seconds_since(t);
  return e;
}

/// CGAL's PCA normals at one k (pca_estimate_normals), oriented like the exact normals.
Estimate pca(const Surface_data& d, unsigned int k)
{
  Estimate e;
  e.has_H = false;
  PV_range pts = d.points;
  const auto t = std::chrono::steady_clock::now();
  CGAL::pca_estimate_normals<Tag>(pts, k, CGAL::parameters::point_map(Point_map()).normal_map(Normal_map()));
  e.seconds = seconds_since(t);
  for(std::size_t i = 0; i < pts.size(); ++i)
  {
    const Vector n = pts[i].second;
    e.n.push_back(n * d.normal[i] < 0 ? -n : n);
    e.H.push_back(0.);
    e.ok.push_back(1);
  }
  return e;
}

#ifdef WAVEJETS_HAVE_PONCA
/// Ponca's APSS (OrientedSphereFit, constant weights over the k nearest), with the PCA normals at the same k.
Estimate apss(const Surface_data& d, const Neighborhoods& hoods, unsigned int k)
{
  const Estimate normals = pca(d, k);
  Estimate e;
  const auto t = std::chrono::steady_clock::now();
  std::vector<std::size_t> nb;
  CGAL::Wavejets::internal::Neighbor_query::Scratch scratch;
  std::vector<Ponca_point> pp;
  for(std::size_t i = 0; i < d.points.size(); ++i)
  {
    hoods.query->neighbors(i, k, 0., nb, scratch);
    const Ponca_point::VectorType c(d.points[i].first.x(), d.points[i].first.y(), d.points[i].first.z());
    pp.clear();
    double Rf = 0.;
    auto add = [&](std::size_t j) {
      const Ponca_point::VectorType q(d.points[j].first.x(), d.points[j].first.y(), d.points[j].first.z());
      const Vector& n = normals.n[j];
      pp.emplace_back(q, Ponca_point::VectorType(n.x(), n.y(), n.z()));
      Rf = std::max(Rf, (q - c).norm());
    };
    add(i);
    for(std::size_t j : nb) add(j);
    APSS_constant fit;
    fit.setNeighborFilter(Constant_weight(c, Rf * (1. + 1e-9) + 1e-300));
    bool ok = fit.compute(pp.begin(), pp.end()) == Ponca::STABLE;
    Vector n(0, 0, 1);
    double H = 0.;
    if(ok)
    {
      const Ponca_point::VectorType g = fit.primitiveGradient(c).normalized();
      n = Vector(g.x(), g.y(), g.z());
      H = -fit.kappa(); // Ponca's kappa bends toward the gradient: the package's sign is the opposite
      ok = std::isfinite(H) && std::isfinite(n.x());
    }
    e.n.push_back(n);
    e.H.push_back(H);
    e.ok.push_back(ok);
  }
  e.seconds = seconds_since(t) + normals.seconds;
  return e;
}
#endif

std::string fixed(double x, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

/// What one surface gives: the rows of the summary, the regions, the targets.
struct Surface_result
{
  std::vector<std::vector<std::string> > summary, regions, targets;
};

Surface_result run_surface(const Surface_data& d, const std::vector<unsigned int>& ladder)
{
  Surface_result out;
  const std::size_t J = ladder.size();
  std::vector<Errors> single(J), single_pca(J), single_apss;
  std::vector<Point_errors> single_points(J);
  double single_seconds_at_largest = 0.;
  for(std::size_t j = 0; j < J; ++j)
  {
    const Estimate e = wavejets(d, ladder[j], One_k());
    single_points[j] = point_errors(d, e);
    single[j] = aggregate(d, single_points[j]);
    if(j + 1 == J) single_seconds_at_largest = e.seconds;
    single_pca[j] = errors(d, pca(d, ladder[j]));
  }
  const Neighborhoods hoods(d.points);
#ifdef WAVEJETS_HAVE_PONCA
  for(std::size_t j = 0; j < J; ++j) single_apss.push_back(errors(d, apss(d, hoods, ladder[j])));
#endif
  auto best_single = [&](const std::vector<Errors>& e, bool by_H) {
    std::size_t best = 0;
    for(std::size_t j = 1; j < e.size(); ++j)
      if((by_H ? e[j].overall_H : e[j].overall_angle) < (by_H ? e[best].overall_H : e[best].overall_angle)) best = j;
    return best;
  };
  // The per-region oracle: each region's best k, chosen with the truth (normals and H separately).
  Errors oracle;
  int oracle_k_angle[REGIONS], oracle_k_H[REGIONS];
  for(int g = 0; g < REGIONS; ++g)
  {
    std::size_t ba = 0, bh = 0;
    for(std::size_t j = 1; j < J; ++j)
    {
      if(single[j].angle[g] < single[ba].angle[g]) ba = j;
      if(single[j].H[g] < single[bh].H[g]) bh = j;
    }
    oracle.angle[g] = single[ba].angle[g];
    oracle.H[g] = single[bh].H[g];
    oracle.overall_angle += oracle.angle[g] / REGIONS;
    oracle.overall_H += oracle.H[g] / REGIONS;
    oracle_k_angle[g] = int(ladder[ba]);
    oracle_k_H[g] = int(ladder[bh]);
  }
  const Errors point_oracle = aggregate(d, per_point_oracle(single_points));
  single_points.clear();
  // Automatic: the scales, then the functions with them.
  std::vector<unsigned int> k_auto(d.points.size(), 0);
  PV_range pts = d.points;
  const auto t = std::chrono::steady_clock::now();
  std::vector<unsigned int> chosen(d.points.size(), 0);
  CGAL::wavejet_estimate_scales<Tag>(pts, WJP::neighborhood_size_map(wavejets_test::slot_map(pts, chosen))
                                            .neighborhood_sizes(ladder).point_map(Point_map()));
  const double scale_seconds = seconds_since(t);
  for(std::size_t i = 0; i < chosen.size(); ++i) k_auto[i] = chosen[i] ? chosen[i] : ladder.back();
  Estimate automatic = wavejets(d, ladder.back(), Per_point_k{&k_auto});
  const Errors autom = errors(d, automatic);
  const double auto_seconds = scale_seconds + automatic.seconds;
  double mean_k = 0., region_k[REGIONS] = {}, region_count[REGIONS] = {};
  for(std::size_t i = 0; i < k_auto.size(); ++i)
  {
    mean_k += double(k_auto[i]) / double(k_auto.size());
    if(d.region[i] >= 0) { region_k[d.region[i]] += k_auto[i]; ++region_count[d.region[i]]; }
  }
  // CGAL: local scales (estimate_local_k_neighbor_scales), then jets at each point's k.
  std::vector<std::size_t> cgal_scales;
  const auto tc = std::chrono::steady_clock::now();
  CGAL::estimate_local_k_neighbor_scales(d.points, d.points, std::back_inserter(cgal_scales),
                                         CGAL::parameters::point_map(Point_map()).query_point_map(Point_map()));
  const double cgal_scale_seconds = seconds_since(tc);
  std::vector<unsigned int> k_cgal;
  double mean_k_cgal = 0.;
  for(std::size_t s : cgal_scales)
  {
    k_cgal.push_back(unsigned(std::max<std::size_t>(s, 6)));
    mean_k_cgal += double(k_cgal.back()) / double(cgal_scales.size());
  }
  const Estimate cgal = cgal_jets(d, hoods, k_cgal);
  const Errors cgal_errors = errors(d, cgal);

  const std::size_t bs_a = best_single(single, false), bs_h = best_single(single, true);
  const std::size_t pca_a = best_single(single_pca, false);
  auto row = [&](const std::string& estimator, const std::string& k, const Errors& e, bool has_H, const std::string& time) {
    out.summary.push_back({d.name, estimator, k, fixed(e.overall_angle, 2), has_H ? fixed(e.overall_H, 3) : "-", time});
  };
  row("Wavejets, automatic", "per point, mean " + fixed(mean_k, 0), autom, true,
      fixed(auto_seconds / single_seconds_at_largest, 2) + "x");
  row("Wavejets, per-region oracle", "per region (truth)", oracle, true, "-");
  row("Wavejets, per-point oracle (a bound)", "per point (truth)", point_oracle, true, "-");
  row("Wavejets, best single k (normals)", std::to_string(ladder[bs_a]), single[bs_a], true, "1.00x at k " + std::to_string(ladder.back()));
  if(bs_h != bs_a) row("Wavejets, best single k (H)", std::to_string(ladder[bs_h]), single[bs_h], true, "-");
  row("CGAL local scales + jets", "per point, mean " + fixed(mean_k_cgal, 0), cgal_errors, true,
      fixed((cgal_scale_seconds + cgal.seconds) / single_seconds_at_largest, 2) + "x");
  row("PCA, best single k", std::to_string(ladder[pca_a]), single_pca[pca_a], false, "-");
#ifdef WAVEJETS_HAVE_PONCA
  const std::size_t ap_a = best_single(single_apss, false), ap_h = best_single(single_apss, true);
  row("APSS, best single k (normals)", std::to_string(ladder[ap_a]), single_apss[ap_a], true, "-");
  if(ap_h != ap_a) row("APSS, best single k (H)", std::to_string(ladder[ap_h]), single_apss[ap_h], true, "-");
#endif
  for(int g = 0; g < REGIONS; ++g)
    out.regions.push_back({d.name, std::string(Y_BAND_NAMES[g % Y_BANDS]) + ", x " + fixed(double(g / Y_BANDS) / X_BANDS, 2) +
                             "-" + fixed(double(g / Y_BANDS + 1) / X_BANDS, 2),
                           fixed(region_k[g] / std::max(region_count[g], 1.), 0),
                           fixed(autom.angle[g], 2), fixed(oracle.angle[g], 2) + " (k " + std::to_string(oracle_k_angle[g]) + ")",
                           fixed(single[bs_a].angle[g], 2), fixed(autom.H[g], 3),
                           fixed(oracle.H[g], 3) + " (k " + std::to_string(oracle_k_H[g]) + ")", fixed(single[bs_h].H[g], 3)});
  auto verdict = [](bool ok) { return std::string(ok ? "met" : "not met"); };
  const double ra = autom.overall_angle / oracle.overall_angle, rh = autom.overall_H / oracle.overall_H;
  out.targets.push_back({d.name, "automatic / oracle <= 1.15 (normals, H)", fixed(ra, 2) + ", " + fixed(rh, 2),
                         verdict(ra <= 1.15 && rh <= 1.15)});
  const double ga = single[bs_a].overall_angle / autom.overall_angle, gh = single[bs_h].overall_H / autom.overall_H;
  out.targets.push_back({d.name, "best single k / automatic >= 1.5 (normals, H)", fixed(ga, 2) + ", " + fixed(gh, 2),
                         verdict(ga >= 1.5 && gh >= 1.5)});
  const double ca = cgal_errors.overall_angle / autom.overall_angle, ch = cgal_errors.overall_H / autom.overall_H;
  out.targets.push_back({d.name, "CGAL local scales + jets / automatic > 1 (normals, H)", fixed(ca, 2) + ", " + fixed(ch, 2),
                         verdict(ca > 1 && ch > 1)});
#ifdef WAVEJETS_HAVE_PONCA
  const double pa = single_apss[ap_a].overall_angle / autom.overall_angle, ph = single_apss[ap_h].overall_H / autom.overall_H;
  out.targets.push_back({d.name, "APSS at its best single k / automatic > 1 (normals, H)", fixed(pa, 2) + ", " + fixed(ph, 2),
                         verdict(pa > 1 && ph > 1)});
#endif
  const double tr = auto_seconds / single_seconds_at_largest;
  out.targets.push_back({d.name, "automatic time / one run at the largest k <= 3", fixed(tr, 2), verdict(tr <= 3)});
  std::cout << d.name << ": automatic " << fixed(autom.overall_angle, 2) << " deg / H " << fixed(autom.overall_H, 3)
            << "; oracle " << fixed(oracle.overall_angle, 2) << " / " << fixed(oracle.overall_H, 3) << "; best single k "
            << ladder[bs_a] << ": " << fixed(single[bs_a].overall_angle, 2) << " / " << fixed(single[bs_h].overall_H, 3)
            << "; CGAL local scales + jets " << fixed(cgal_errors.overall_angle, 2) << " / " << fixed(cgal_errors.overall_H, 3)
            << "; time ratio " << fixed(tr, 2) << std::endl;
  return out;
}

/// "10,16,25": increasing sizes >= 2; empty if the text is not that.
std::vector<unsigned int> parse_ladder(const std::string& text)
{
  std::vector<unsigned int> ladder;
  std::istringstream in(text);
  std::string item;
  while(std::getline(in, item, ','))
  {
    char* end = nullptr;
    const long k = std::strtol(item.c_str(), &end, 10);
    if(item.empty() || *end != '\0' || k < 2 || (!ladder.empty() && k <= long(ladder.back()))) return {};
    ladder.push_back((unsigned int)k);
  }
  return ladder;
}

} // namespace

int main(int argc, char** argv)
{
  std::size_t N = 100000;
  std::string csv_dir = wavejets_bench::source_dir() + "/csv";
  bool write = true;
  std::vector<unsigned int> ladder = CGAL::Wavejets::default_neighborhood_sizes(2);
  std::string table_name = "scale_selection"; // the tables: csv/NAME.*.csv
  for(int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if(arg == "--points" && a + 1 < argc) N = std::size_t(std::atof(argv[++a]));
    else if(arg == "--csv-dir" && a + 1 < argc) csv_dir = argv[++a];
    else if(arg == "--ladder" && a + 1 < argc) ladder = parse_ladder(argv[++a]);
    else if(arg == "--name" && a + 1 < argc) table_name = argv[++a];
    else if(arg == "--no-write") write = false;
    else if(arg == "--quick") N = 5000;
    else
    {
      std::cerr << "usage: bench_scale_selection [--points N] [--ladder K1,K2,...] [--name NAME] [--csv-dir DIR] [--no-write] [--quick]\n";
      return EXIT_FAILURE;
    }
  }
  if(ladder.empty()) { std::cerr << "--ladder: increasing sizes >= 2, separated by commas\n"; return EXIT_FAILURE; }
  const auto t0 = std::chrono::steady_clock::now();
  wavejets_bench::Csv_table summary({"surface", "estimator", "k", "normal error (deg)", "|H error|", "time"});
  wavejets_bench::Csv_table regions({"surface", "region", "automatic: mean k", "normal: automatic", "normal: oracle", "normal: best single k",
                                     "H: automatic", "H: oracle", "H: best single k"});
  wavejets_bench::Csv_table targets({"surface", "target", "measured", "verdict"});
  wavejets_bench::Csv_table surfaces({"surface", "points", "description"});
  unsigned seed = 1;
  for(const std::string name : {"noise", "density", "features"})
  {
    const Surface_data d = make_surface(name, N, seed++);
    surfaces.add_row({name, std::to_string(d.points.size()), d.description});
    const Surface_result r = run_surface(d, ladder);
    for(const auto& row : r.summary) summary.add_row(row);
    for(const auto& row : r.regions) regions.add_row(row);
    for(const auto& row : r.targets) targets.add_row(row);
  }
  wavejets_bench::Csv_table context = wavejets_bench::context_table();
  context.add_row({"machine", wavejets_bench::machine_description()});
  context.add_row({"points per surface", std::to_string(N)});
  std::string sizes;
  for(unsigned int k : ladder) sizes += (sizes.empty() ? "" : ", ") + std::to_string(k);
  context.add_row({"ladder", sizes});
#ifdef WAVEJETS_HAVE_PONCA
  context.add_row({"ponca", "yes"});
#else
  context.add_row({"ponca", "not built with Ponca: no APSS rows"});
#endif
  context.add_row({"run time", fixed(seconds_since(t0), 0) + " s"});
  std::cout << summary.str() << "\n" << targets.str();
  if(write)
  {
    summary.write(csv_dir, table_name + ".summary");
    regions.write(csv_dir, table_name + ".regions");
    targets.write(csv_dir, table_name + ".targets");
    surfaces.write(csv_dir, table_name + ".surfaces");
    context.write(csv_dir, table_name + ".context");
  }
  return EXIT_SUCCESS;
}
