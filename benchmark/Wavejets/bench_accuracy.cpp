// Accuracy benchmark: curvature and normal error of Wavejets against CGAL jets (and PCA normals)
// on surfaces with exact answers (benchmark/Wavejets/analytic_surfaces.h), clean and perturbed.
//
// Every surface is sampled uniformly (fixed seeds) with N points (default 20000; the full run with
// 50000 points and 300 evaluation points takes about 40 minutes on 2 cores) in [-1, 1]^3.
// Perturbations: Gaussian position noise sigma (percent of the bounding-box diagonal), outliers
// (a fraction of the points moved by a random vector of a ball of radius 2.5% of the diagonal;
// excluded from the statistics) and angular noise on the seed normals.
//
// Estimators run on identical neighborhoods: all points within the radius r of the query point
// (the package's own neighbor query, query point first, nearest first), at the same order K:
//   WJ      CGAL::Wavejet_fitting, defaults (adaptive order, neighbors_per_coefficient 1.1,
//           2 tangent-plane re-fits, curvature from the first fit = INITIAL_FRAME)
//   WJ-R3   + robust_iterations 3 (Tukey IRLS)
//   WJ-T    curvature read in the corrected tangent frame (curvature_frame TANGENT_FRAME)
//   WJ-fix  adaptive order off: neighbors_per_coefficient 1.0 and minimum_order K (a point with
//           fewer than (K+1)(K+2)/2 neighbors is not fitted rather than fitted at a lower order)
//   CGAL    CGAL::Monge_via_jet_fitting of degree K (Monge degree 2); where the neighborhood has
//           fewer than (K+1)(K+2)/2 points (CGAL's precondition), the largest degree it allows
//           (the same order WJ's adaptive rule would use with factor 1.0). Its normal is the one
//           CGAL::jet_estimate_normals computes (normal_direction() of the same fit).
//   PCA     smallest-eigenvalue eigenvector of the neighborhood (as CGAL::pca_estimate_normals)
// Curvatures are oriented by the true normals (Wavejets: passed as the seed normal, which only
// orients the PCA frame; CGAL: Monge_form::comply_wrt_given_normal). Errors: RMSE of H, K_G, k1,
// k2 (signed) and mean / 95th percentile of the unoriented normal angle, over M evaluation points
// per surface (default 300, random inliers, at least 0.2 from a border); the neighborhoods use all
// N points. Wavejet_fitting is the fitting core the point-set functions call per point; the last
// experiment runs CGAL::wavejet_estimate_curvatures / wavejet_estimate_normals on all N points at
// the recommended settings and checks that they give the same values at the evaluation points.
//
// Usage: bench_accuracy [--quick] [--points N] [--eval M] [--out DIR] [--no-plot]
// Writes DIR/accuracy.md, DIR/accuracy_*.dat, DIR/accuracy.gp and (with gnuplot) DIR/accuracy.png.
// DIR defaults to the directory of this source file.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Real_timer.h>
#include <CGAL/for_each.h>
#include <CGAL/property_map.h>
#include <CGAL/Wavejet_fitting.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/Wavejets/internal/neighbor_query.h>
#include <CGAL/Wavejets/internal/differential_quantities.h>

#include "analytic_surfaces.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/info.h>
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Wavejet_fitting<Kernel> WJ_fitting;
typedef CGAL::Monge_via_jet_fitting<Kernel> Monge_fitting;
namespace WB = wavejets_bench;
namespace WP = CGAL::Wavejets::parameters;
typedef CGAL::Parallel_if_available_tag Tag;

// ---------------------------------------------------------------------------------------------
// Settings

struct Options
{
  bool quick = false, plot = true;
  std::size_t points = 20000, eval = 300;
  std::string out;
  std::string command;
};

enum Estimator { WJ = 0, WJ_R3, WJ_T, WJ_FIX, CGAL_JET, PCA, NUM_ESTIMATORS };
static const char* estimator_name[NUM_ESTIMATORS] = {"WJ", "WJ-R3", "WJ-T", "WJ-fix", "CGAL", "PCA"};

/// Errors of one estimator in one configuration.
struct Result
{
  double H = 0, K = 0, k1 = 0, k2 = 0, mean_angle = 0, p95_angle = 0;
  std::size_t evaluated = 0, failed = 0, reduced = 0;
  bool has_curvature = true;
};

static Result summarize(const WB::Error_accumulator& a, bool curvature)
{
  Result r;
  r.H = a.rmse_H(); r.K = a.rmse_K(); r.k1 = a.rmse_k1(); r.k2 = a.rmse_k2();
  r.mean_angle = a.mean_angle(); r.p95_angle = a.p95_angle();
  r.evaluated = a.angles.size(); r.failed = a.failed;
  r.has_curvature = curvature;
  return r;
}

/// A perturbed data set and its evaluation points.
struct Dataset
{
  std::vector<WB::Sample> samples;
  std::vector<Point> points;
  std::vector<std::size_t> eval; // evaluation indices
  double diagonal = 0.;
};

static Dataset make_dataset(const WB::Surface& S, std::size_t surface_index, const Options& o, double sigma_pct,
                            double outlier_fraction)
{
  Dataset d;
  d.samples = S.sample(o.points, 1000 + surface_index);
  d.diagonal = WB::bounding_box_diagonal(d.samples);
  WB::add_position_noise(d.samples, sigma_pct / 100. * d.diagonal, 2000 + surface_index);
  WB::add_outliers(d.samples, outlier_fraction, 0.025 * d.diagonal, 3000 + surface_index);
  for(const WB::Sample& s : d.samples) d.points.emplace_back(s.p.x(), s.p.y(), s.p.z());
  // evaluation points: fixed random inliers at least 0.2 from a border (same for every radius)
  std::mt19937_64 rng(4000 + surface_index);
  std::vector<std::size_t> candidates;
  for(std::size_t i = 0; i < d.samples.size(); ++i)
    if(d.samples[i].inlier && d.samples[i].boundary_distance > 0.2) candidates.push_back(i);
  std::shuffle(candidates.begin(), candidates.end(), rng);
  candidates.resize(std::min(candidates.size(), o.eval));
  std::sort(candidates.begin(), candidates.end());
  d.eval = candidates;
  return d;
}

/// Neighborhoods (query first) of the evaluation points, with the package's neighbor query.
struct Neighborhoods
{
  std::vector<std::vector<Point> > pts; // per evaluation point: query, then neighbors nearest first
};

static Neighborhoods gather(const Dataset& d, double radius)
{
  typedef CGAL::Wavejets::internal::Neighbor_query Q;
  std::vector<Q::Point> p;
  p.reserve(d.points.size());
  for(const Point& q : d.points) p.emplace_back(q.x(), q.y(), q.z());
  std::vector<unsigned char> in_tree(p.size(), 1);
  const Q query(p, in_tree);
  Neighborhoods n;
  n.pts.resize(d.eval.size());
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < d.eval.size(); b += 64) chunks.push_back(b);
  CGAL::for_each<Tag>(chunks, [&](std::size_t b) -> bool {
    std::vector<std::size_t> nb;
    std::vector<std::pair<double, std::size_t> > scratch;
    for(std::size_t e = b; e < std::min(b + 64, d.eval.size()); ++e)
    {
      const std::size_t i = d.eval[e];
      query.neighbors(i, 0, radius, nb, scratch);
      std::vector<Point>& v = n.pts[e];
      v.clear();
      v.push_back(d.points[i]);
      for(std::size_t j : nb) v.push_back(d.points[j]);
    }
    return true;
  });
  return n;
}

static std::size_t coefficients(std::size_t K) { return (K + 1) * (K + 2) / 2; }

/// Per-point estimate.
struct Estimate
{
  bool ok = false;
  double H = 0, K = 0, k1 = 0, k2 = 0;
  WB::V3 n = WB::V3::Zero();
  double tH = 0, tK = 0, tk1 = 0, tk2 = 0; // Wavejets: curvature of the same fit read in the final tangent frame
};

/// Runs one estimator on every evaluation point. `seed_normals` (may be empty) replaces the true
/// normals as the orienting / seeding normal (Wavejets only).
static std::vector<Estimate> run_estimator(Estimator e, const Dataset& d, const Neighborhoods& nh, std::size_t K,
                                           double radius, const std::vector<WB::V3>& seed_normals = {},
                                           bool seed_frame = false)
{
  std::vector<Estimate> out(d.eval.size());
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < d.eval.size(); b += 32) chunks.push_back(b);
  CGAL::for_each<Tag>(chunks, [&](std::size_t b) -> bool {
    CGAL::Wavejets::Fitting_options fo;
    fo.neighborhood_radius = radius;
    fo.compute_condition_number = false;
    if(e == WJ_R3) fo.robust_iterations = 3;
    if(e == WJ_T) fo.curvature_frame = CGAL::Wavejets::Curvature_frame::TANGENT_FRAME;
    if(e == WJ_FIX) { fo.neighbors_per_coefficient = 1.0; fo.minimum_order = K; }
    if(seed_frame) fo.normal_use = CGAL::Wavejets::Normal_use::SEED_FRAME;
    WJ_fitting wj(fo);
    Monge_fitting monge;
    for(std::size_t i = b; i < std::min(b + 32, d.eval.size()); ++i)
    {
      const std::vector<Point>& pts = nh.pts[i];
      const WB::Truth& t = d.samples[d.eval[i]].truth;
      const WB::V3 hint = seed_normals.empty() ? t.normal : seed_normals[i];
      Estimate& r = out[i];
      if(e == PCA)
      {
        if(pts.size() < 3) continue;
        WB::V3 mean = WB::V3::Zero();
        for(const Point& p : pts) mean += WB::V3(p.x(), p.y(), p.z());
        mean /= double(pts.size());
        WB::M3 C = WB::M3::Zero();
        for(const Point& p : pts)
        {
          const WB::V3 q = WB::V3(p.x(), p.y(), p.z()) - mean;
          C += q * q.transpose();
        }
        Eigen::SelfAdjointEigenSolver<WB::M3> es(C);
        r.n = es.eigenvectors().col(0);
        r.ok = true;
      }
      else if(e == CGAL_JET)
      {
        std::size_t deg = K;
        while(deg >= 2 && double(pts.size()) < 1.1 * double(coefficients(deg))) --deg; // WJ's adaptive rule
        if(deg < 2) continue;
        Monge_fitting::Monge_form m = monge(pts.begin(), pts.end(), deg, 2);
        m.comply_wrt_given_normal(Vector(t.normal.x(), t.normal.y(), t.normal.z()));
        r.k1 = m.principal_curvatures(0);
        r.k2 = m.principal_curvatures(1);
        r.H = 0.5 * (r.k1 + r.k2);
        r.K = r.k1 * r.k2;
        const Vector n = m.normal_direction();
        r.n = WB::V3(n.x(), n.y(), n.z());
        r.ok = true;
      }
      else
      {
        WJ_fitting::Wavejet_form f = wj(pts.begin(), pts.end(), K, Vector(hint.x(), hint.y(), hint.z()));
        if(!f.is_valid()) continue;
        r.H = f.mean_curvature();
        r.K = f.gaussian_curvature();
        r.k1 = f.principal_curvatures(0);
        r.k2 = f.principal_curvatures(1);
        const Vector n = f.normal_direction();
        r.n = WB::V3(n.x(), n.y(), n.z());
        r.ok = true;
        // TANGENT_FRAME curvature (what curvature_frame(TANGENT_FRAME) computes): the graph formulas on the
        // final frame's coefficients (world units: fx = c1, fy = c2, fxx = 2(c3 + c4), fyy = 2(c3 - c4), fxy = 2 c5).
        if(f.order() >= 2)
        {
          const std::vector<double>& c = f.coefficients();
          CGAL::Wavejets::internal::Height_derivatives hd;
          hd.fx = c[1]; hd.fy = c[2];
          hd.fxx = 2. * (c[3] + c[4]); hd.fyy = 2. * (c[3] - c[4]); hd.fxy = 2. * c[5];
          const Vector u = f.first_tangent_direction(), v = f.second_tangent_direction(), fn = f.frame_normal_direction();
          const CGAL::Wavejets::internal::Curvature_info ci = CGAL::Wavejets::internal::graph_curvature(
            hd, WB::V3(u.x(), u.y(), u.z()), WB::V3(v.x(), v.y(), v.z()), WB::V3(fn.x(), fn.y(), fn.z()));
          r.tH = ci.mean; r.tK = ci.gaussian; r.tk1 = ci.k1; r.tk2 = ci.k2;
        }
      }
    }
    return true;
  });
  return out;
}

static Result evaluate(const std::vector<Estimate>& est, const Dataset& d, bool curvature, bool tangent_frame = false)
{
  WB::Error_accumulator a;
  for(std::size_t i = 0; i < est.size(); ++i)
  {
    const WB::Truth& t = d.samples[d.eval[i]].truth;
    if(!est[i].ok) { ++a.failed; continue; }
    a.add_normal(est[i].n, t);
    if(curvature && tangent_frame) a.add_curvature(est[i].tH, est[i].tK, est[i].tk1, est[i].tk2, t);
    else if(curvature) a.add_curvature(est[i].H, est[i].K, est[i].k1, est[i].k2, t);
  }
  return summarize(a, curvature);
}

// ---------------------------------------------------------------------------------------------
// Result store and formatting

struct Key
{
  std::string surface;
  double sigma, outliers, radius;
  std::size_t K;
  int estimator;
  bool operator<(const Key& o) const
  {
    return std::tie(surface, sigma, outliers, radius, K, estimator) <
           std::tie(o.surface, o.sigma, o.outliers, o.radius, o.K, o.estimator);
  }
};

static std::string fmt(double v, int prec = 3)
{
  std::ostringstream s;
  if(v != 0. && (std::abs(v) < 1e-3 || std::abs(v) >= 1e4)) s << std::scientific << std::setprecision(prec - 1) << v;
  else s << std::setprecision(prec) << v;
  return s.str();
}

static std::string machine_description()
{
  std::string cpu = "unknown CPU";
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while(std::getline(f, line))
    if(line.rfind("model name", 0) == 0) { cpu = line.substr(line.find(':') + 2); break; }
  std::ostringstream s;
  s << cpu << ", " << std::thread::hardware_concurrency() << " hardware threads";
#ifdef CGAL_LINKED_WITH_TBB
  s << ", TBB with " << tbb::info::default_concurrency() << " threads (Parallel_if_available_tag)";
#else
  s << ", no TBB (sequential)";
#endif
  return s.str();
}

// ---------------------------------------------------------------------------------------------

int main(int argc, char** argv)
{
  Options o;
  {
    std::string self = __FILE__;
    o.out = self.substr(0, self.find_last_of('/'));
    if(o.out == self) o.out = ".";
  }
  std::ostringstream cmd;
  cmd << "bench_accuracy";
  bool points_given = false, eval_given = false;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    cmd << " " << a;
    if(a == "--quick") o.quick = true;
    else if(a == "--no-plot") o.plot = false;
    else if(a == "--points" && i + 1 < argc) { o.points = std::strtoul(argv[++i], nullptr, 10); cmd << " " << argv[i]; points_given = true; }
    else if(a == "--eval" && i + 1 < argc) { o.eval = std::strtoul(argv[++i], nullptr, 10); cmd << " " << argv[i]; eval_given = true; }
    else if(a == "--out" && i + 1 < argc) { o.out = argv[++i]; cmd << " " << argv[i]; }
    else
    {
      std::cerr << "usage: bench_accuracy [--quick] [--points N] [--eval M] [--out DIR] [--no-plot]\n"
                   "  --quick: 8000 points, 100 evaluation points, K in {2,4,6}, sigma in {0, 0.5%}\n";
      return a == "--help" || a == "-h" ? 0 : 1;
    }
  }
  if(o.quick)
  {
    if(!points_given) o.points = 8000;
    if(!eval_given) o.eval = 100;
  }
  o.command = cmd.str();
  if(o.points < 1000 || o.eval < 10) { std::cerr << "need --points >= 1000 and --eval >= 10\n"; return 1; }

  CGAL::Real_timer total;
  total.start();
  const auto surfaces = WB::all_surfaces();
  const std::vector<double> sigmas = o.quick ? std::vector<double>{0., 0.5} : std::vector<double>{0., 0.25, 0.5, 1.};
  const std::vector<double> radii = {0.05, 0.1, 0.2};
  const std::vector<std::size_t> orders = o.quick ? std::vector<std::size_t>{2, 4, 6}
                                                  : std::vector<std::size_t>{2, 3, 4, 5, 6, 7, 8};
  std::map<Key, Result> R;
  std::map<std::pair<std::string, double>, double> mean_neighbors; // (surface, r) -> mean L (clean)
  double seconds[NUM_ESTIMATORS] = {0, 0, 0, 0, 0, 0};

  // ---- Experiment 1: position noise x radius x order x estimator --------------------------------
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    const WB::Surface& S = *surfaces[s];
    for(double sigma : sigmas)
    {
      CGAL::Real_timer t;
      t.start();
      const Dataset d = make_dataset(S, s, o, sigma, 0.);
      for(double r : radii)
      {
        const Neighborhoods nh = gather(d, r);
        std::size_t minL = std::size_t(-1);
        double sumL = 0;
        for(const auto& v : nh.pts) { minL = std::min(minL, v.size()); sumL += double(v.size()); }
        if(sigma == 0.) mean_neighbors[{S.name(), r}] = sumL / double(nh.pts.size());
        R[{S.name(), sigma, 0., r, 0, PCA}] = evaluate(run_estimator(PCA, d, nh, 2, r), d, false);
        for(std::size_t K : orders)
        {
          std::size_t reduced = 0;
          for(const auto& v : nh.pts) reduced += double(v.size()) < 1.1 * double(coefficients(K));
          for(int e : {WJ, WJ_R3, CGAL_JET})
          {
            CGAL::Real_timer te;
            te.start();
            const std::vector<Estimate> est = run_estimator(Estimator(e), d, nh, K, r);
            seconds[e] += te.time();
            Result res = evaluate(est, d, true);
            res.reduced = reduced;
            R[{S.name(), sigma, 0., r, K, e}] = res;
            if(e == WJ)
            {
              res = evaluate(est, d, true, true);
              res.reduced = reduced;
              R[{S.name(), sigma, 0., r, K, WJ_T}] = res;
            }
          }
          // Adaptive order only acts where a neighborhood is too small for K; elsewhere WJ-fix == WJ.
          if(double(minL) < 1.1 * double(coefficients(K)))
            R[{S.name(), sigma, 0., r, K, WJ_FIX}] = evaluate(run_estimator(WJ_FIX, d, nh, K, r), d, true);
          else
            R[{S.name(), sigma, 0., r, K, WJ_FIX}] = R[{S.name(), sigma, 0., r, K, WJ}];
        }
      }
      std::cerr << S.name() << " sigma " << sigma << "%: " << t.time() << " s (total " << total.time() << " s)\n";
    }
  }

  // ---- Experiment 2: outliers (sigma = 0 and 0.5%, r = 0.1 and 0.2, K = 2 and 4) -----------------
  const std::vector<double> outlier_fractions = {0., 0.05, 0.1};
  const std::vector<double> out_sigmas = {0., 0.5};
  const std::vector<double> out_radii = {0.1, 0.2};
  const std::vector<std::size_t> out_orders = {2, 4};
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    const WB::Surface& S = *surfaces[s];
    for(double sigma : out_sigmas)
      for(double of : outlier_fractions)
      {
        if(of == 0.) continue; // already in experiment 1
        const Dataset d = make_dataset(S, s, o, sigma, of);
        for(double r : out_radii)
        {
          const Neighborhoods nh = gather(d, r);
          R[{S.name(), sigma, of, r, 0, PCA}] = evaluate(run_estimator(PCA, d, nh, 2, r), d, false);
          for(std::size_t K : out_orders)
            for(int e : {WJ, WJ_R3, CGAL_JET})
              R[{S.name(), sigma, of, r, K, e}] = evaluate(run_estimator(Estimator(e), d, nh, K, r), d, true);
        }
      }
    std::cerr << S.name() << " outliers done (total " << total.time() << " s)\n";
  }

  // ---- Experiment 3: noisy seed normals (sigma = 0, r = 0.1, K = 4) ------------------------------
  const std::vector<double> normal_noise_deg = {0., 5., 15., 30.};
  struct Seed_row { std::string surface; double deg; Result orient, seed, seed_t, cgal; };
  std::vector<Seed_row> seed_rows;
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    const WB::Surface& S = *surfaces[s];
    const Dataset d = make_dataset(S, s, o, 0., 0.);
    const double r = 0.1;
    const std::size_t K = 4;
    const Neighborhoods nh = gather(d, r);
    for(double deg : normal_noise_deg)
    {
      std::mt19937_64 rng(5000 + s);
      std::vector<WB::V3> seeds;
      for(std::size_t i : d.eval) seeds.push_back(WB::perturb_normal(d.samples[i].truth.normal, deg * M_PI / 180., rng));
      Seed_row row;
      row.surface = S.name();
      row.deg = deg;
      row.orient = evaluate(run_estimator(WJ, d, nh, K, r, seeds, false), d, true);
      row.seed = evaluate(run_estimator(WJ, d, nh, K, r, seeds, true), d, true);
      row.seed_t = evaluate(run_estimator(WJ_T, d, nh, K, r, seeds, true), d, true);
      row.cgal = R[{S.name(), 0., 0., r, K, CGAL_JET}];
      seed_rows.push_back(row);
    }
  }
  std::cerr << "seed normals done (total " << total.time() << " s)\n";

  // ---- Targets and best settings -------------------------------------------------------------------
  auto get = [&](const std::string& S, double sigma, double r, std::size_t K, int e) -> const Result& {
    return R.at({S, sigma, 0., r, K, e});
  };
  // Clean: WJ (default) vs CGAL at every (surface, r, K).
  std::size_t clean_total = 0, clean_h_ok = 0, clean_n_ok = 0;
  std::ostringstream clean_violations;
  double worst_rel = 0.;
  for(const auto& S : surfaces)
    for(double r : radii)
      for(std::size_t K : orders)
      {
        const Result& w = get(S->name(), 0., r, K, WJ);
        const Result& c = get(S->name(), 0., r, K, CGAL_JET);
        ++clean_total;
        const double tol = 1e-9 * (1. + c.H);
        if(w.H <= c.H + tol) ++clean_h_ok;
        else
        {
          clean_violations << "  - " << S->name() << " r=" << r << " K=" << K << ": H RMSE WJ " << fmt(w.H, 6)
                           << " vs CGAL " << fmt(c.H, 6) << "\n";
        }
        worst_rel = std::max(worst_rel, std::abs(w.H - c.H) / std::max(c.H, 1e-300));
        if(w.mean_angle <= c.mean_angle * (1. + 1e-9) + 1e-12) ++clean_n_ok;
      }

  // Noisy (sigma = 0.5%): best WJ setting vs best CGAL setting, per radius and overall.
  struct Best { double H = 1e300; std::size_t K = 0; int e = 0; double r = 0; };
  auto best_of = [&](const std::string& S, double sigma, const std::vector<double>& rs, const std::vector<int>& es) {
    Best b;
    for(double r : rs)
      for(std::size_t K : orders)
        for(int e : es)
        {
          const Result& x = get(S, sigma, r, K, e);
          if(x.evaluated > 0 && x.failed * 100 <= x.evaluated + x.failed && x.H < b.H) { b.H = x.H; b.K = K; b.e = e; b.r = r; }
        }
    return b;
  };
  const std::vector<int> wj_set = {WJ, WJ_R3, WJ_T, WJ_FIX};

  // ---- Experiment 4: the point-set functions on all N points at recommended settings ---------------
  struct Ps_row { std::string surface, setting; double sigma; Result wj, cgal; double max_diff; std::size_t unfitted; double seconds; };
  std::vector<Ps_row> ps_rows;
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    const WB::Surface& S = *surfaces[s];
    for(double sigma : {0., 0.5})
    {
      // recommended settings (section "Which settings to use"): clean WJ K = 6, r = 0.1; noisy WJ K = 2, r = 0.2
      Best b;
      b.e = WJ;
      b.K = sigma == 0. ? 6 : 2;
      b.r = sigma == 0. ? 0.1 : 0.2;
      const Dataset d = make_dataset(S, s, o, sigma, 0.);
      // The range is the point indices; positions, normals and outputs live in index-keyed maps.
      std::vector<std::size_t> idx(d.points.size());
      for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
      std::vector<Vector> true_normals, out_normals;
      for(const WB::Sample& x : d.samples) true_normals.emplace_back(x.truth.normal.x(), x.truth.normal.y(), x.truth.normal.z());
      out_normals = true_normals;
      const std::size_t N = idx.size();
      std::vector<double> H(N, 0.), KG(N, 0.), k1(N, 0.), k2(N, 0.);
      std::vector<unsigned char> fitted_n(N, 0);
      CGAL::Real_timer t;
      t.start();
      const std::size_t rob = b.e == WJ_R3 ? 3 : 0;
      const double npc = b.e == WJ_FIX ? 1.0 : 1.1;
      const std::size_t mino = b.e == WJ_FIX ? b.K : 2;
      const auto frame = b.e == WJ_T ? CGAL::Wavejets::Curvature_frame::TANGENT_FRAME
                                     : CGAL::Wavejets::Curvature_frame::INITIAL_FRAME;
      CGAL::wavejet_estimate_curvatures<Tag>(idx, 0,
        WP::order(b.K).robust_iterations(rob).neighbors_per_coefficient(npc).minimum_order(mino).curvature_frame(frame)
          .mean_curvature_map(CGAL::make_property_map(H)).gaussian_curvature_map(CGAL::make_property_map(KG))
          .maximal_principal_curvature_map(CGAL::make_property_map(k1))
          .minimal_principal_curvature_map(CGAL::make_property_map(k2))
          .neighbor_radius(b.r).point_map(CGAL::make_property_map(d.points))
          .normal_map(CGAL::make_property_map(true_normals)));
      CGAL::Wavejets::Processing_report rep = CGAL::wavejet_estimate_normals<Tag>(idx, 0,
        WP::order(b.K).robust_iterations(rob).neighbors_per_coefficient(npc).minimum_order(mino)
          .orient_with_input_normals(true).fitted_map(CGAL::make_property_map(fitted_n))
          .neighbor_radius(b.r).point_map(CGAL::make_property_map(d.points))
          .normal_map(CGAL::make_property_map(out_normals)));
      const double seconds = t.time();
      WB::Error_accumulator a;
      for(std::size_t i = 0; i < N; ++i)
      {
        if(!d.samples[i].inlier || d.samples[i].boundary_distance <= b.r) continue;
        if(!fitted_n[i]) { ++a.failed; continue; }
        const Vector n = out_normals[i];
        a.add_normal(WB::V3(n.x(), n.y(), n.z()), d.samples[i].truth);
        a.add_curvature(H[i], KG[i], k1[i], k2[i], d.samples[i].truth);
      }
      Ps_row row;
      row.surface = S.name();
      row.sigma = sigma;
      std::ostringstream st;
      st << estimator_name[b.e] << " K=" << b.K << " r=" << b.r;
      row.setting = st.str();
      row.wj = summarize(a, true);
      row.unfitted = rep.number_of_unfitted_points;
      row.seconds = seconds;
      // consistency with Wavejet_fitting at the evaluation points, and CGAL on all points
      const Neighborhoods nh = gather(d, b.r);
      const std::vector<Estimate> ev = run_estimator(Estimator(b.e), d, nh, b.K, b.r);
      row.max_diff = 0.;
      for(std::size_t i = 0; i < ev.size(); ++i)
        if(ev[i].ok)
        {
          const std::size_t j = d.eval[i];
          const Vector n = out_normals[j];
          row.max_diff = std::max({row.max_diff, std::abs(ev[i].H - H[j]), std::abs(ev[i].K - KG[j]),
                                   (ev[i].n - WB::V3(n.x(), n.y(), n.z())).norm()});
        }
      // CGAL on all points (same degree, same radius)
      Dataset all = d;
      all.eval.clear();
      for(std::size_t i = 0; i < N; ++i)
        if(d.samples[i].inlier && d.samples[i].boundary_distance > b.r) all.eval.push_back(i);
      const Neighborhoods nh_all = gather(all, b.r);
      row.cgal = evaluate(run_estimator(CGAL_JET, all, nh_all, b.K, b.r), all, true);
      ps_rows.push_back(row);
    }
    std::cerr << S.name() << " point-set run done (total " << total.time() << " s)\n";
  }
  const double total_seconds = total.time();

  // ---- Data files and plot ------------------------------------------------------------------------
  // accuracy_noise.dat: per surface block, per sigma: best H RMSE over (K, r) of WJ, WJ-R3, WJ-T, CGAL,
  // best mean normal angle over (K, r) of WJ, WJ-R3, CGAL and PCA.
  const std::string dat = o.out + "/accuracy_noise.dat";
  {
    std::ofstream f(dat);
    f << "# sigma_pct  H_WJ H_WJ-R3 H_WJ-T H_CGAL  angle_WJ angle_WJ-R3 angle_CGAL angle_PCA  (best over K, r)\n";
    for(const auto& S : surfaces)
    {
      f << "# " << S->name() << "\n";
      for(double sigma : sigmas)
      {
        f << sigma;
        for(int e : {WJ, WJ_R3, WJ_T, CGAL_JET})
        {
          const Best b = best_of(S->name(), sigma, radii, {e});
          if(b.K == 0) f << " NaN";
          else f << " " << b.H;
        }
        for(int e : {WJ, WJ_R3, CGAL_JET, PCA})
        {
          double best = 1e300;
          for(double r : radii)
            for(std::size_t K : (e == PCA ? std::vector<std::size_t>{0} : orders))
              best = std::min(best, R.at({S->name(), sigma, 0., r, K, e}).mean_angle);
          f << " " << best;
        }
        f << "\n";
      }
      f << "\n\n";
    }
  }
  const std::string gp = o.out + "/accuracy.gp";
  const std::string png = o.out + "/accuracy.png";
  {
    std::ofstream f(gp);
    f << "# gnuplot script written by bench_accuracy; run: gnuplot accuracy.gp (from " << o.out << ")\n"
      << "set terminal pngcairo size 1800,1000 font 'DejaVu Sans,11'\n"
      << "set output '" << png << "'\n"
      << "set multiplot layout 2," << surfaces.size()
      << " title 'Wavejets vs CGAL jets: error against position noise (best over order K and radius r for each estimator)'\n"
      << "set termoption noenhanced\nset logscale y\nset format y '%.0e'\nset grid\nset key bottom right font ',9'\n"
      << "set xlabel 'noise sigma (% of bbox diagonal)'\n";
    for(std::size_t s = 0; s < surfaces.size(); ++s)
      f << "set title '" << surfaces[s]->name() << ": RMSE of H'\n"
        << "plot '" << dat << "' index " << s << " using 1:2 w lp lw 2 pt 7 title 'WJ', '' index " << s
        << " using 1:3 w lp lw 2 pt 5 title 'WJ-R3', '' index " << s << " using 1:4 w lp lw 2 pt 9 dt 2 title 'WJ-T', '' index "
        << s << " using 1:5 w lp lw 2 pt 4 dt 3 title 'CGAL jet'\n";
    for(std::size_t s = 0; s < surfaces.size(); ++s)
      f << "set title '" << surfaces[s]->name() << ": mean normal angle (deg)'\n"
        << "plot '" << dat << "' index " << s << " using 1:6 w lp lw 2 pt 7 title 'WJ', '' index " << s
        << " using 1:7 w lp lw 2 pt 5 title 'WJ-R3', '' index " << s << " using 1:8 w lp lw 2 pt 4 dt 3 title 'CGAL jet', '' index "
        << s << " using 1:9 w lp lw 2 pt 6 dt 4 title 'PCA'\n";
    f << "unset multiplot\n";
  }
  bool plotted = false;
  if(o.plot && std::system("command -v gnuplot >/dev/null 2>&1") == 0)
    plotted = std::system(("gnuplot '" + gp + "'").c_str()) == 0;

  // ---- Report -------------------------------------------------------------------------------------
  std::ostringstream md;
  std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  md << "# Accuracy of Wavejets against CGAL jets on surfaces with exact curvature\n\n"
     << "Generated by `benchmark/Wavejets/bench_accuracy.cpp` on " << date << ". Command (from the repository root):\n\n"
     << "    cmake -S . -B build/bench -DCMAKE_BUILD_TYPE=Release && cmake --build build/bench --target bench_accuracy -j1\n"
     << "    build/bench/benchmark/Wavejets/" << o.command << "\n\n"
     << "Machine: " << machine_description() << ". Total run time " << fmt(total_seconds, 3) << " s.\n\n";
  md << "## Setup\n\n"
     << "- Surfaces (`benchmark/Wavejets/analytic_surfaces.h`), all in [-1, 1]^3 with half-extent 1, " << o.points
     << " points each, fixed seeds:\n"
     << "  sphere (R = 1); ellipsoid (semi-axes 1, 0.7, 0.5); torus (R = 0.7, r = 0.3); open cylinder (radius 0.5,"
        " |z| <= 1); Goursat quartic x^4+y^4+z^4 + a(x^2+y^2+z^2)^2 + b(x^2+y^2+z^2) + c = 0 with a = 0, b = -5, c = 11.8"
        " (the genus-5 'tanglecube', with saddle regions), scaled by 1/2.266; the paper's shape r = 1 + 0.005 cos(100 phi^2/pi)"
        " (phi = polar angle; ripple frequency grows from 0 at the north pole to 200 rad/rad at the south pole), scaled by 1/1.005.\n"
     << "- Uniform density: exact for the sphere (normalized Gaussians), cylinder (uniform angle and height), torus and paper"
        " shape (area-weighted rejection in the parametrization); thin-shell sampling for the ellipsoid and Goursat surface"
        " (uniform points with |F|/|grad F| < 3e-3, then Newton projection onto F = 0: uniform up to a relative O(K_G eps^2) < 1e-4).\n"
     << "- Exact truth: implicit surfaces from the analytic gradient and Hessian (II(t,t) = -t^T Hess t / |grad F|);"
        " paper shape from the analytic first and second derivatives of its profile curve. Both checked against finite"
        " differences in `test/Wavejets/test_accuracy.cpp`.\n"
     << "- Signs: outward normals, curvature positive when bending toward the normal (sphere: H = -1). Estimates are"
        " oriented by the true normals (Wavejets: seed normal passed to the fit, which only orients the PCA frame;"
        " CGAL: `Monge_form::comply_wrt_given_normal`).\n"
     << "- Noise: Gaussian, each coordinate N(0, sigma^2), sigma in % of the bounding-box diagonal (sphere: 0.5% = 0.0173,"
        " about a third of the smallest radius r = 0.05). Outliers: a fraction of the points moved by a uniform vector of"
        " a ball of radius 2.5% of the diagonal, excluded from the statistics.\n"
     << "- Neighborhoods: all points within r (`neighbor_radius(r)`; CGAL gets the very same point list, query point"
        " first). Mean neighborhood sizes (clean):";
  for(const auto& S : surfaces)
  {
    md << " " << S->name() << " ";
    for(double r : radii) md << (r == radii[0] ? "" : "/") << fmt(mean_neighbors[{S->name(), r}], 3);
  }
  md << " (r = 0.05/0.1/0.2).\n"
     << "- Errors over " << o.eval << " evaluation points per surface (random inliers at least 0.2 from a border;"
        " neighborhoods use all points): RMSE of H, K_G, k1, k2 (signed) and mean / 95th percentile of the unoriented"
        " normal angle in degrees. Curvature unit: 1 / (half-extent).\n\n"
     << "Estimators (same neighborhoods, same order K):\n\n"
     << "| name | what |\n| --- | --- |\n"
     << "| WJ | `CGAL::Wavejet_fitting` with the defaults of the point-set functions: adaptive order (neighbors_per_coefficient 1.1),"
        " 2 tangent-plane re-fits, curvature from the first fit (INITIAL_FRAME, the PCA frame = CGAL's least-squares problem),"
        " normal of the corrected fit |\n"
     << "| WJ-R3 | WJ + `robust_iterations(3)` (Tukey IRLS, 3 passes) |\n"
     << "| WJ-T | WJ + `curvature_frame(TANGENT_FRAME)` (curvature from the corrected tangent-frame fit; normals as WJ) |\n"
     << "| WJ-fix | adaptive order off: `neighbors_per_coefficient(1.0).minimum_order(K)`: a point whose neighborhood is"
        " smaller than (K+1)(K+2)/2 is not fitted instead of being fitted at a lower order. It only differs from WJ where some"
        " neighborhood has fewer than 1.1 (K+1)(K+2)/2 points (here: r = 0.05 with K >= 6 or so); elsewhere it is WJ. |\n"
     << "| CGAL | `CGAL::Monge_via_jet_fitting`, degree K, Monge degree 2 (its normal is what `jet_estimate_normals` returns);"
        " where a neighborhood has fewer than (K+1)(K+2)/2 points, the largest degree CGAL accepts |\n"
     << "| PCA | normal = smallest principal axis of the neighborhood (`pca_estimate_normals`) |\n\n"
     << "The Wavejet numbers come from `Wavejet_fitting`, the fitting core that `wavejet_estimate_curvatures` and"
        " `wavejet_estimate_normals` run per point; the last section runs those functions on all points and checks that they"
        " give the same values.\n\n";

  // Targets
  md << "## Targets\n\n";
  md << "**Clean data, Wavejet error <= CGAL jet error at equal degree and neighborhood, every surface:** RMSE of H: "
     << clean_h_ok << " / " << clean_total << " (surface, r, K) configurations"
     << (clean_h_ok == clean_total ? " — **met**" : " — **not met** everywhere") << "; largest relative difference of the"
        " H RMSE between WJ and CGAL: " << fmt(worst_rel, 2)
     << " (the default curvature is, by design, CGAL's least-squares problem in the same PCA frame, so equality is the"
        " expected outcome, not an improvement). Mean normal angle: WJ <= CGAL in " << clean_n_ok << " / " << clean_total
     << " configurations (the WJ normal comes from the corrected tangent-plane fit, CGAL's from the first fit).\n";
  if(clean_h_ok != clean_total) md << "\nConfigurations where WJ's H RMSE is above CGAL's:\n\n" << clean_violations.str();
  md << "\n**Noisy data (sigma = 0.5%), best Wavejet setting <= half of CGAL jets' H RMSE:**\n\n"
     << "Best over order K in {" << orders.front() << ".." << orders.back() << "} and estimator variant, at each radius"
        " (CGAL at its own best degree at the same radius), and overall (best over radii too):\n\n"
     << "| surface | r | best Wavejet (variant, K) | H RMSE | best CGAL (K) | H RMSE | ratio | <= 0.5? |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::size_t half_met = 0, half_total = 0;
  for(const auto& S : surfaces)
  {
    std::vector<std::vector<double> > groups;
    for(double r : radii) groups.push_back({r});
    groups.push_back(radii);
    for(const auto& g : groups)
    {
      const Best w = best_of(S->name(), 0.5, g, wj_set), c = best_of(S->name(), 0.5, g, {CGAL_JET});
      const bool all = g.size() > 1;
      if(w.K == 0 || c.K == 0)
      {
        md << "| " << S->name() << " | " << (all ? std::string("best") : fmt(g[0]))
           << " | - | - | - | - | - | (more than 1% of the points not fitted) |\n";
        continue;
      }
      const double ratio = w.H / c.H;
      if(all) { ++half_total; half_met += ratio <= 0.5; }
      md << "| " << S->name() << " | " << (all ? std::string("best: ") + fmt(w.r) + " / " + fmt(c.r) : fmt(g[0])) << " | "
         << estimator_name[w.e] << ", K=" << w.K << " | " << fmt(w.H) << " | K=" << c.K << " | " << fmt(c.H) << " | "
         << fmt(ratio) << " | " << (ratio <= 0.5 ? "yes" : "no") << " |\n";
    }
  }
  md << "\nOverall (best over radii for both): met on " << half_met << " / " << half_total << " surfaces.\n\n";

  md << "Time spent per estimator in the position-noise sweep (all surfaces, noise levels, radii and orders; "
     << o.eval << " points each; both threads): WJ (also gives WJ-T) " << fmt(seconds[WJ]) << " s, WJ-R3 "
     << fmt(seconds[WJ_R3]) << " s, CGAL " << fmt(seconds[CGAL_JET]) << " s.\n\n";
  // Full tables
  auto table_header = [&](std::ostream& os) {
    os << "| surface | r | K | est. | H | K_G | k1 | k2 | angle mean | angle p95 | not fitted | reduced |\n"
       << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  };
  auto row = [&](std::ostream& os, const std::string& S, double r, std::size_t K, int e, const Result& x) {
    os << "| " << S << " | " << r << " | " << (e == PCA ? std::string("-") : std::to_string(K)) << " | " << estimator_name[e]
       << " | " << (x.has_curvature ? fmt(x.H) : "-") << " | " << (x.has_curvature ? fmt(x.K) : "-") << " | "
       << (x.has_curvature ? fmt(x.k1) : "-") << " | " << (x.has_curvature ? fmt(x.k2) : "-") << " | "
       << fmt(x.mean_angle) << " | " << fmt(x.p95_angle) << " | " << x.failed << " | "
       << (e == WJ || e == WJ_R3 || e == WJ_T ? std::to_string(x.reduced) : std::string("-")) << " |\n";
  };
  md << "## Summary: best setting per estimator\n\n"
     << "Per surface and noise level, the smallest H RMSE over (K, r) of each estimator, and the smallest mean normal angle"
        " over (K, r). Plot: `accuracy.png` (data `accuracy_noise.dat`, script `accuracy.gp`).\n\n"
     << "| surface | sigma % | WJ: H (K, r) | WJ-R3 | WJ-T | CGAL | normal WJ (deg) | WJ-R3 | CGAL | PCA |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for(const auto& S : surfaces)
    for(double sigma : sigmas)
    {
      md << "| " << S->name() << " | " << sigma;
      for(int e : {WJ, WJ_R3, WJ_T, CGAL_JET})
      {
        const Best b = best_of(S->name(), sigma, radii, {e});
        if(b.K == 0) md << " | -";
        else md << " | " << fmt(b.H) << " (" << b.K << ", " << b.r << ")";
      }
      for(int e : {WJ, WJ_R3, CGAL_JET, PCA})
      {
        double best = 1e300, br = 0;
        std::size_t bk = 0;
        for(double r : radii)
          for(std::size_t K : (e == PCA ? std::vector<std::size_t>{0} : orders))
          {
            const Result& x = R.at({S->name(), sigma, 0., r, K, e});
            if(x.mean_angle < best) { best = x.mean_angle; br = r; bk = K; }
          }
        md << " | " << fmt(best) << " (" << (e == PCA ? std::string("-") : std::to_string(bk)) << ", " << br << ")";
      }
      md << " |\n";
    }
  md << "\n";

  // Point-set functions
  md << "## The point-set functions on all points (recommended settings)\n\n"
     << "`wavejet_estimate_curvatures` (true normals as `normal_map`, orienting only) and `wavejet_estimate_normals` on all "
     << o.points << " points with `neighbor_radius(r)` at the recommended settings (clean: default WJ, K = 6, r = 0.1; sigma = 0.5%:"
        " default WJ, K = 2, r = 0.2; outputs oriented with the true normals);"
        " statistics over all inliers at least r from a border. CGAL jets on the same points and neighborhoods at the same"
        " degree. 'max diff' is the largest difference (H, K_G, normal) between the point-set functions and `Wavejet_fitting`"
        " at the evaluation points (identical neighborhoods: expected 0).\n\n"
     << "| surface | sigma % | setting | WJ H | CGAL H | WJ K_G | CGAL K_G | WJ angle mean / p95 | CGAL angle mean / p95 | not fitted | max diff | WJ time (s) |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for(const Ps_row& p : ps_rows)
    md << "| " << p.surface << " | " << p.sigma << " | " << p.setting << " | " << fmt(p.wj.H) << " | " << fmt(p.cgal.H) << " | "
       << fmt(p.wj.K) << " | " << fmt(p.cgal.K) << " | " << fmt(p.wj.mean_angle) << " / " << fmt(p.wj.p95_angle) << " | "
       << fmt(p.cgal.mean_angle) << " / " << fmt(p.cgal.p95_angle) << " | " << p.unfitted << " | " << fmt(p.max_diff, 2)
       << " | " << fmt(p.seconds) << " |\n";
  md << "\n";

  // Which settings
  md << "## Which settings to use\n\n@@SETTINGS@@\n\n";

  // Outliers
  md << "## Outliers\n\nsigma = 0 and 0.5%, outlier fraction 0/5/10%, r = 0.1 and 0.2, K = 2 and 4; H RMSE and mean normal"
        " angle (deg) at the inliers.\n\n"
     << "| surface | sigma % | outliers | r | K | WJ H | WJ-R3 H | CGAL H | WJ angle | WJ-R3 angle | CGAL angle | PCA angle |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for(const auto& S : surfaces)
    for(double sigma : out_sigmas)
      for(double of : outlier_fractions)
        for(double r : out_radii)
          for(std::size_t K : out_orders)
          {
            auto g = [&](int e, std::size_t k) -> const Result& { return R.at({S->name(), sigma, of, r, k, e}); };
            md << "| " << S->name() << " | " << sigma << " | " << of * 100 << "% | " << r << " | " << K << " | "
               << fmt(g(WJ, K).H) << " | " << fmt(g(WJ_R3, K).H) << " | " << fmt(g(CGAL_JET, K).H) << " | "
               << fmt(g(WJ, K).mean_angle) << " | " << fmt(g(WJ_R3, K).mean_angle) << " | " << fmt(g(CGAL_JET, K).mean_angle)
               << " | " << fmt(g(PCA, 0).mean_angle) << " |\n";
          }
  md << "\n";

  // Seed normals
  md << "## Noisy seed normals\n\nsigma = 0, r = 0.1, K = 4. The input normals are the true normals tilted by a random angle"
        " (tangent components N(0, s^2), s in degrees below; mean tilt = s sqrt(pi/2)). 'orient': the normal only orients the"
        " PCA frame (default); 'seed': first fit in the plane orthogonal to the noisy normal (`seed_with_input_normals(true)`),"
        " curvature from that first fit; 'seed+T': seed and curvature from the corrected tangent frame. CGAL (PCA frame) for"
        " reference.\n\n"
     << "| surface | s (deg) | orient: H / angle | seed: H / angle | seed+T: H / angle | CGAL: H / angle |\n"
     << "| --- | --- | --- | --- | --- | --- |\n";
  for(const Seed_row& x : seed_rows)
    md << "| " << x.surface << " | " << x.deg << " | " << fmt(x.orient.H) << " / " << fmt(x.orient.mean_angle) << " | "
       << fmt(x.seed.H) << " / " << fmt(x.seed.mean_angle) << " | " << fmt(x.seed_t.H) << " / " << fmt(x.seed_t.mean_angle)
       << " | " << fmt(x.cgal.H) << " / " << fmt(x.cgal.mean_angle) << " |\n";
  md << "\n";

  // Full table
  md << "## Full tables (position noise)\n\nRMSE of H, K_G, k1, k2; normal angle in degrees; 'not fitted': evaluation points"
        " without an estimate; 'reduced': evaluation points whose neighborhood is below 1.1 (K+1)(K+2)/2 points (adaptive"
        " order lowers K there).\n\n";
  for(double sigma : sigmas)
  {
    md << "### sigma = " << sigma << "%\n\n";
    table_header(md);
    for(const auto& S : surfaces)
      for(double r : radii)
      {
        row(md, S->name(), r, 0, PCA, R.at({S->name(), sigma, 0., r, 0, PCA}));
        for(std::size_t K : orders)
          for(int e : {WJ, WJ_R3, WJ_T, WJ_FIX, CGAL_JET})
            row(md, S->name(), r, K, e, R.at({S->name(), sigma, 0., r, K, e}));
      }
    md << "\n";
  }

  // Keep a hand-written settings section across runs: read it back from an existing report.
  std::string settings = "(to be written from the tables above)";
  {
    std::ifstream old(o.out + "/accuracy.md");
    std::stringstream buf;
    buf << old.rdbuf();
    const std::string s = buf.str();
    const std::string begin = "<!-- settings-begin -->", end = "<!-- settings-end -->";
    const std::size_t b = s.find(begin), e = s.find(end);
    if(b != std::string::npos && e != std::string::npos && e > b) settings = s.substr(b, e + end.size() - b);
    else settings = begin + "\n" + settings + "\n" + end;
  }
  std::string text = md.str();
  text.replace(text.find("@@SETTINGS@@"), 12, settings);
  std::ofstream(o.out + "/accuracy.md") << text;
  std::cout << "wrote " << o.out << "/accuracy.md" << (plotted ? ", " + png : std::string(", no plot (gnuplot not found)"))
            << " in " << total_seconds << " s\n";
  return 0;
}
