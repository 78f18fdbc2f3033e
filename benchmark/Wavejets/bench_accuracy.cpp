// Accuracy benchmark: curvature and normal error of Wavejets against CGAL jets (and PCA normals)
// on surfaces with exact answers (test/Wavejets/support/analytic_surfaces.h), clean and perturbed.
//
// Every surface is sampled uniformly (fixed seeds) with N points (default 20000; the report's run: 50000 points
// and 300 evaluation points, its run time in accuracy.md) in [-1, 1]^3.
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
// Usage: bench_accuracy [--quick] [--points N] [--eval M] [--csv-dir DIR]
//                       [--noisy-pipeline | --noisy-pipeline-only]
// Writes its tables as CSV only, DIR/accuracy.<table>.csv and DIR/accuracy.context.csv (machine, run times); DIR
// defaults to csv/ beside this source, --quick writes nothing unless --csv-dir is given. make_reports.py writes
// accuracy.md and accuracy.png from them (see README.md in this folder). Tables: summary, noise_best, targets,
// point_set_functions, outliers, noisy_seed_normals, full_grid; --noisy-pipeline adds the section "Noisy scans:
// denoise, then estimate" (accuracy.pipeline_*.csv; the target tables at sigma = 0.5% only when that noise level
// runs), --noisy-pipeline-only runs that section alone. accuracy.context.csv keeps the keys of an existing one that
// the run does not measure (the noisy-pipeline run time, or the machine and total run time).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Real_timer.h>
#include <CGAL/for_each.h>
#include <CGAL/property_map.h>
#include <CGAL/Wavejet_fitting.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/Wavejets/internal/neighbor_query.h>
#include <CGAL/Wavejets/internal/differential_quantities.h>

#include "analytic_surfaces.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bench_common.h"

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
  bool quick = false, csv_dir_given = false;
  bool pipeline = false, pipeline_only = false; // --noisy-pipeline, --noisy-pipeline-only
  std::size_t points = 20000, eval = 300;
  std::string csv_dir = wavejets_bench::source_dir() + "/csv";
  bool write() const { return !quick || csv_dir_given; } // --quick writes nothing unless --csv-dir
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
    Q::Scratch scratch;
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
    // The normal as wavejet_estimate_normals computes it: tangent plane found at order 2, then one
    // order-K fit (its curvature frame is irrelevant for the normal: TANGENT_FRAME skips a solve).
    CGAL::Wavejets::Fitting_options fo_normals = fo;
    fo_normals.tangent_plane_order = 2;
    fo_normals.curvature_frame = CGAL::Wavejets::Curvature_frame::TANGENT_FRAME;
    WJ_fitting wj_normals(fo_normals);
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
        WB::jet_estimate(monge, pts, K, Vector(t.normal.x(), t.normal.y(), t.normal.z()), r);
      }
      else
      {
        WJ_fitting::Wavejet_form f = wj(pts.begin(), pts.end(), K, Vector(hint.x(), hint.y(), hint.z()));
        if(!f.is_valid()) continue;
        r.H = f.mean_curvature();
        r.K = f.gaussian_curvature();
        r.k1 = f.principal_curvatures(0);
        r.k2 = f.principal_curvatures(1);
        const WJ_fitting::Wavejet_form fn = wj_normals(pts.begin(), pts.end(), K, Vector(hint.x(), hint.y(), hint.z()));
        if(!fn.is_valid()) continue;
        const Vector n = fn.normal_direction();
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

/// `v` as the default stream output writes it (6 significant digits).
static std::string num(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Noisy scans: denoise, then estimate (--noisy-pipeline / --noisy-pipeline-only)
//
// Pipelines compared on the same noisy data set and evaluation points:
//   plain   CGAL::Monge_via_jet_fitting on the noisy points, degree D2, radius r2 (the CGAL column of the main
//           tables; Wavejet_fitting with the default INITIAL_FRAME gives the same numbers)
//   WJ      passes x CGAL::wavejet_enhance_positions(points, 0, gain = 1, order(K1).neighbor_radius(r1)) (each
//           point projected onto its Wavejet), then Wavejet_fitting (the core of wavejet_estimate_curvatures,
//           defaults) of order K2 in radius r2 on the projected points; WJ-T: the same fit with
//           curvature_frame(TANGENT_FRAME)
//   CGAL-S  passes x CGAL jet smoothing of degree K1 in radius r1 (the computation of CGAL::jet_smooth_point_set:
//           Monge_via_jet_fitting(degree K1, Monge degree 2).origin() of the neighborhood, query point first), then
//           Monge_via_jet_fitting of degree K2 in radius r2 on the smoothed points.
// CGAL 5.5.1's jet_smooth_point_set itself is not usable with neighbor_radius: its sphere query does not return
// the query point first, and Monge_via_jet_fitting takes the first point as the origin, so every point is
// replaced by the projection of an arbitrary neighbor (clean unit sphere, 20000 points: mean motion 0.082 at
// r = 0.1, 0.18 at r = 0.2, instead of ~1e-6). The bench therefore runs the same computation on the package's
// radius query (query first), which is what jet_smooth_point_set does in k-nearest mode.
// Errors at the evaluation points' current positions (noisy, or projected) against the exact truth at
// Surface::surface_point() of that position (analytic closest point for sphere, cylinder, torus; the
// generators' Newton projection for ellipsoid and Goursat; radial projection for the paper shape).

enum Pipe_method { PIPE_PLAIN = 0, PIPE_WJ, PIPE_WJ_T, PIPE_CGAL_S, NUM_PIPE_METHODS };
static const char* pipe_name[NUM_PIPE_METHODS] = {"plain CGAL", "WJ", "WJ-T", "CGAL-S"};
static const char* pipe_short_name[NUM_PIPE_METHODS] = {"plain", "WJ", "WJ-T", "CGAL-S"};

struct Pipe_result
{
  std::string surface;
  double sigma = 0;
  int method = 0;
  std::size_t K1 = 0; double r1 = 0; int passes = 0; // denoising (0 passes: none)
  std::size_t K2 = 0; double r2 = 0;                 // estimation
  Result res;
  double residual = 0; // RMS distance of the inliers to the surface after denoising
};

/// `d` with the positions `pts`; the truth of every sample is re-read at the surface point of its position.
static Dataset moved_dataset(const Dataset& d, const std::vector<Point>& pts, const WB::Surface& S, double* residual)
{
  Dataset m = d;
  m.points = pts;
  double s2 = 0;
  std::size_t n = 0;
  for(std::size_t i = 0; i < m.samples.size(); ++i)
  {
    WB::Sample& x = m.samples[i];
    if(!x.inlier) continue;
    x.p = WB::V3(pts[i].x(), pts[i].y(), pts[i].z());
    const WB::V3 q = S.surface_point(x.p);
    s2 += (q - x.p).squaredNorm();
    ++n;
    if(std::binary_search(m.eval.begin(), m.eval.end(), i)) x.truth = S.truth(q);
  }
  if(residual) *residual = n ? std::sqrt(s2 / double(n)) : 0.;
  return m;
}

/// CGAL jet smoothing (jet_smooth_point_set's computation) on radius neighborhoods, query point first;
/// the degree is lowered where a neighborhood is below 1.1 (K+1)(K+2)/2 points (as for the CGAL estimator).
static std::vector<Point> cgal_jet_smooth(const std::vector<Point>& in, std::size_t D, double radius)
{
  typedef CGAL::Wavejets::internal::Neighbor_query Q;
  std::vector<Q::Point> p;
  p.reserve(in.size());
  for(const Point& q : in) p.emplace_back(q.x(), q.y(), q.z());
  std::vector<unsigned char> in_tree(p.size(), 1);
  const Q query(p, in_tree);
  std::vector<Point> out = in;
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < in.size(); b += 256) chunks.push_back(b);
  CGAL::for_each<Tag>(chunks, [&](std::size_t b) -> bool {
    std::vector<std::size_t> nb;
    Q::Scratch scratch;
    std::vector<Point> v;
    Monge_fitting monge;
    for(std::size_t i = b; i < std::min(b + 256, in.size()); ++i)
    {
      query.neighbors(i, 0, radius, nb, scratch);
      v.assign(1, in[i]);
      for(std::size_t j : nb) v.push_back(in[j]);
      const std::size_t deg = WB::adaptive_jet_degree(v.size(), D);
      if(deg < 2) continue;
      out[i] = monge(v.begin(), v.end(), deg, 2).origin();
    }
    return true;
  });
  return out;
}

/// The tables of the section "Noisy scans: denoise, then estimate", each with its name (accuracy.pipeline_*).
typedef std::vector<std::pair<std::string, WB::Csv_table> > Named_tables;
struct Pipe_output { Named_tables tables; double seconds = 0; };

typedef std::vector<std::unique_ptr<WB::Surface> > Surfaces;

/// Enough evaluation points estimated (at most 1% not fitted) for a result to compete for "best".
static bool usable(const Result& r) { return r.evaluated > 0 && r.failed * 100 <= r.evaluated + r.failed; }

/// The setting of a pipeline row, as the tables print it.
static std::string config(const Pipe_result& x)
{
  std::ostringstream c;
  if(x.method == PIPE_PLAIN) c << "D=" << x.K2 << ", r=" << x.r2;
  else c << x.passes << "x(K1=" << x.K1 << ", r1=" << x.r1 << ") + K2=" << x.K2 << ", r2=" << x.r2;
  return c.str();
}

static bool same_config(const Pipe_result& a, const Pipe_result& b)
{
  return a.method == b.method && a.K1 == b.K1 && a.r1 == b.r1 && a.passes == b.passes && a.K2 == b.K2 && a.r2 == b.r2;
}

static std::string H_of(const Pipe_result* x) { return x ? fmt(x->res.H) : std::string("-"); }

static std::string H_ratio(const Pipe_result* a, const Pipe_result* b)
{
  return a && b ? fmt(a->res.H / b->res.H) : std::string("-");
}

/// One denoising configuration: every pass runs, and is estimated after the passes listed (all, or the last),
/// on the (K2, r2) grid given.
struct Denoise_cfg
{
  int method; // PIPE_WJ or PIPE_CGAL_S
  std::size_t K1; double r1; int passes; bool all_passes;
  std::vector<std::size_t> K2s; std::vector<double> r2s;
};

/// The section "Noisy scans: denoise, then estimate": runs the pipelines on their grid, then makes its tables.
class Noisy_pipeline
{
public:
  Noisy_pipeline(const Options& options, const Surfaces& surfaces_) : o(options), surfaces(surfaces_) {}
  Pipe_output run();

private:
  /// The best setting common to every surface: its row on the first surface and its score (mean log ratio).
  struct Common { const Pipe_result* proto = nullptr; double score = 1e300; };
  /// On how many surfaces WJ reaches half of plain CGAL (a), of CGAL-S (b), of plain CGAL up to r = 0.4 (a').
  struct Targets_met { std::size_t a = 0, b = 0, a2 = 0; };
  static constexpr double target_sigma = 0.5;

  // experiments
  void run_target_grid();
  void run_other_noise_levels();
  void run_dataset(std::size_t s, double sigma, const std::vector<Denoise_cfg>& cfgs);
  void denoise_once(std::vector<Point>& pts, const Denoise_cfg& c);
  void estimate(const Dataset& m, Pipe_result proto, const std::vector<std::size_t>& K2list, const std::vector<double>& r2s);
  // selection
  const Pipe_result* best(const std::string& S, double sigma, const std::vector<int>& methods, double max_r2,
                          int passes = 0) const;
  Common common_best(int method, double sigma) const;
  const Pipe_result* find_config(const Pipe_result& proto, const std::string& S, double sigma) const;
  // tables (accuracy.pipeline_*.csv)
  WB::Csv_table best_per_surface_table(Targets_met& met) const;
  WB::Csv_table passes_table() const;
  WB::Csv_table common_setting_table(const Common& cw, const Common& cc) const;
  WB::Csv_table point_set_check_table(const Pipe_result& c) const;
  std::vector<std::string> point_set_check_row(std::size_t s, const Pipe_result& c) const;
  WB::Csv_table all_pipelines_table() const;
  WB::Csv_table grid_table() const;

  const Options& o;
  const Surfaces& surfaces;
  const std::vector<double> sigmas = o.quick ? std::vector<double>{0.5} : std::vector<double>{0., 0.25, 0.5, 1.};
  const std::vector<std::size_t> K1s = {2, 3, 4}, K2s = {2, 3};
  const std::vector<double> radii = {0.1, 0.15, 0.2};
  const std::vector<double> plain_radii = {0.1, 0.15, 0.2, 0.3, 0.4}; // 0.3, 0.4: extra comparator (a')
  const int max_passes = 2;
  CGAL::Real_timer total;
  std::vector<Pipe_result> rows;
  double seconds_wj = 0, seconds_cgal = 0, seconds_est = 0;
  std::size_t wj_unfitted = 0, wj_clamped = 0;
};

Pipe_output Noisy_pipeline::run()
{
  total.start();
  run_target_grid();
  run_other_noise_levels();

  Pipe_output out;
  out.seconds = total.time();
  if(std::find(sigmas.begin(), sigmas.end(), target_sigma) != sigmas.end())
  {
    Targets_met met;
    out.tables.emplace_back("accuracy.pipeline_best", best_per_surface_table(met));
    std::cout << "noisy pipeline, sigma = " << target_sigma << "%: WJ H RMSE <= half of plain CGAL (a) on " << met.a
              << " / " << surfaces.size() << " surfaces, of CGAL-S (b) on " << met.b
              << ", of plain CGAL r <= 0.4 (a') on " << met.a2 << "\n";
    out.tables.emplace_back("accuracy.pipeline_passes", passes_table());
    const Common cw = common_best(PIPE_WJ, target_sigma), cwt = common_best(PIPE_WJ_T, target_sigma),
                 cc = common_best(PIPE_CGAL_S, target_sigma);
    const Common& cbest = (cwt.proto && cwt.score < cw.score) ? cwt : cw;
    std::cout << "one setting for every surface: WJ "
              << (cbest.proto ? std::string(pipe_name[cbest.proto->method]) + ", " + config(*cbest.proto) : "-")
              << " (geometric mean ratio " << fmt(std::exp(cbest.score)) << "); CGAL-S "
              << (cc.proto ? config(*cc.proto) : "-") << " (" << fmt(std::exp(cc.score)) << ")\n";
    out.tables.emplace_back("accuracy.pipeline_one_setting", common_setting_table(cbest, cc));
    if(cbest.proto) out.tables.emplace_back("accuracy.pipeline_one_setting_2", point_set_check_table(*cbest.proto));
  }
  out.tables.emplace_back("accuracy.pipeline_all_best", all_pipelines_table());
  std::cout << "time: Wavejet denoising " << fmt(seconds_wj) << " s (" << wj_unfitted << " point-fits not fitted, "
            << wj_clamped << " clamped), CGAL jet smoothing " << fmt(seconds_cgal) << " s, estimation "
            << fmt(seconds_est) << " s\n";
  out.tables.emplace_back("accuracy.pipeline_grid", grid_table());
  return out;
}

// ---- Experiments --------------------------------------------------------------------------------

/// sigma = 0.5% (the target): the full grid.
void Noisy_pipeline::run_target_grid()
{
  std::vector<Denoise_cfg> grid;
  for(int method : {PIPE_WJ, PIPE_CGAL_S})
    for(std::size_t K1 : K1s)
      for(double r1 : radii) grid.push_back({method, K1, r1, max_passes, true, K2s, radii});
  for(std::size_t s = 0; s < surfaces.size(); ++s) run_dataset(s, target_sigma, grid);
}

/// The other noise levels (runtime): only the best common setting of each pipeline at sigma = 0.5%.
void Noisy_pipeline::run_other_noise_levels()
{
  const Common common_wj = common_best(PIPE_WJ, target_sigma), common_wjt = common_best(PIPE_WJ_T, target_sigma),
               common_cg = common_best(PIPE_CGAL_S, target_sigma);
  const Common common_w = (common_wjt.proto && common_wjt.score < common_wj.score) ? common_wjt : common_wj;
  if(!common_w.proto || !common_cg.proto) return;
  // copies: run_dataset appends to `rows`
  const Pipe_result proto_w = *common_w.proto, proto_c = *common_cg.proto;
  const std::vector<Denoise_cfg> cfgs = {
    {PIPE_WJ, proto_w.K1, proto_w.r1, proto_w.passes, false, {proto_w.K2}, {proto_w.r2}},
    {PIPE_CGAL_S, proto_c.K1, proto_c.r1, proto_c.passes, false, {proto_c.K2}, {proto_c.r2}}};
  for(std::size_t s = 0; s < surfaces.size(); ++s)
    for(double sigma : sigmas)
      if(sigma != target_sigma) run_dataset(s, sigma, cfgs);
}

/// One (surface, sigma) data set: plain CGAL on the noisy points, then every denoising configuration.
void Noisy_pipeline::run_dataset(std::size_t s, double sigma, const std::vector<Denoise_cfg>& cfgs)
{
  const WB::Surface& S = *surfaces[s];
  CGAL::Real_timer t;
  t.start();
  const Dataset d = make_dataset(S, s, o, sigma, 0.);
  Pipe_result proto;
  proto.surface = S.name();
  proto.sigma = sigma;
  double residual = 0;
  {
    const Dataset m = moved_dataset(d, d.points, S, &residual);
    proto.method = PIPE_PLAIN;
    proto.residual = residual;
    estimate(m, proto, K2s, plain_radii);
  }
  for(const Denoise_cfg& c : cfgs)
  {
    std::vector<Point> pts = d.points;
    for(int pass = 1; pass <= c.passes; ++pass)
    {
      denoise_once(pts, c);
      if(c.all_passes || pass == c.passes)
      {
        const Dataset m = moved_dataset(d, pts, S, &residual);
        proto.method = c.method; proto.K1 = c.K1; proto.r1 = c.r1; proto.passes = pass; proto.residual = residual;
        estimate(m, proto, c.K2s, c.r2s);
      }
    }
  }
  std::cerr << S.name() << " sigma " << sigma << "% pipeline: " << t.time() << " s (total " << total.time() << " s)\n";
}

/// One denoising pass of `c` on `pts`.
void Noisy_pipeline::denoise_once(std::vector<Point>& pts, const Denoise_cfg& c)
{
  CGAL::Real_timer tw;
  tw.start();
  if(c.method == PIPE_WJ)
  {
    const CGAL::Wavejets::Processing_report rep =
      CGAL::wavejet_enhance_positions<Tag>(pts, 0, 1.0, WP::order(c.K1).neighbor_radius(c.r1));
    seconds_wj += tw.time();
    wj_unfitted += rep.number_of_unfitted_points;
    wj_clamped += rep.number_of_clamped_points;
  }
  else
  {
    pts = cgal_jet_smooth(pts, c.K1, c.r1);
    seconds_cgal += tw.time();
  }
}

/// Estimates on `m` at every (r2, K2) and appends the rows; `proto` holds the rest of the setting (surface, sigma,
/// method, denoising, residual).
void Noisy_pipeline::estimate(const Dataset& m, Pipe_result proto, const std::vector<std::size_t>& K2list,
                              const std::vector<double>& r2s)
{
  CGAL::Real_timer te;
  te.start();
  for(double r2 : r2s)
  {
    const Neighborhoods nh = gather(m, r2);
    for(std::size_t K2 : K2list)
    {
      Pipe_result x = proto;
      x.K2 = K2;
      x.r2 = r2;
      if(proto.method == PIPE_WJ)
      {
        const std::vector<Estimate> est = run_estimator(WJ, m, nh, K2, r2);
        x.method = PIPE_WJ; x.res = evaluate(est, m, true); rows.push_back(x);
        x.method = PIPE_WJ_T; x.res = evaluate(est, m, true, true); rows.push_back(x);
      }
      else
      {
        x.res = evaluate(run_estimator(CGAL_JET, m, nh, K2, r2), m, true);
        rows.push_back(x);
      }
    }
  }
  seconds_est += te.time();
}

// ---- Selection ----------------------------------------------------------------------------------

/// Best row of (surface, sigma) among `methods`; max_r2: largest estimation radius allowed; passes: 0 = any.
const Pipe_result* Noisy_pipeline::best(const std::string& S, double sigma, const std::vector<int>& methods,
                                        double max_r2, int passes) const
{
  const Pipe_result* b = nullptr;
  for(const Pipe_result& x : rows)
    if(x.surface == S && x.sigma == sigma && x.r2 <= max_r2 + 1e-12 && (passes == 0 || x.passes == passes) &&
       std::find(methods.begin(), methods.end(), x.method) != methods.end() && usable(x.res) &&
       (!b || x.res.H < b->res.H))
      b = &x;
  return b;
}

/// Best common setting (same for every surface) of `method` at `sigma`: smallest geometric mean over the
/// surfaces of (H RMSE / best plain CGAL H RMSE at r <= 0.2).
Noisy_pipeline::Common Noisy_pipeline::common_best(int method, double sigma) const
{
  Common c;
  for(const Pipe_result& p : rows)
  {
    if(p.method != method || p.sigma != sigma || p.surface != surfaces[0]->name()) continue;
    double logsum = 0;
    std::size_t n = 0;
    for(const auto& S : surfaces)
      for(const Pipe_result& x : rows)
        if(x.surface == S->name() && x.sigma == sigma && same_config(x, p))
        {
          const Pipe_result* pl = best(S->name(), sigma, {PIPE_PLAIN}, 0.2);
          if(usable(x.res) && pl) { logsum += std::log(x.res.H / pl->res.H); ++n; }
          else logsum += 1e6;
        }
    if(n == surfaces.size() && logsum / double(n) < c.score) { c.score = logsum / double(n); c.proto = &p; }
  }
  return c;
}

const Pipe_result* Noisy_pipeline::find_config(const Pipe_result& proto, const std::string& S, double sigma) const
{
  for(const Pipe_result& x : rows)
    if(x.surface == S && x.sigma == sigma && same_config(x, proto)) return &x;
  return nullptr;
}

// ---- Tables -------------------------------------------------------------------------------------

/// "sigma = 0.5%: best setting per surface"; counts in `met` on how many surfaces each target is met.
WB::Csv_table Noisy_pipeline::best_per_surface_table(Targets_met& met) const
{
  WB::Csv_table table({"surface", "plain CGAL (a): H (setting)", "plain CGAL r <= 0.4 (a')", "CGAL-S (b)",
                       "WJ pipeline", "ratio a", "ratio b", "ratio a'", "WJ / (a) <= 0.5?"});
  for(const auto& S : surfaces)
  {
    const Pipe_result* a = best(S->name(), target_sigma, {PIPE_PLAIN}, 0.2);
    const Pipe_result* a2 = best(S->name(), target_sigma, {PIPE_PLAIN}, 0.4);
    const Pipe_result* b = best(S->name(), target_sigma, {PIPE_CGAL_S}, 0.2);
    const Pipe_result* w = best(S->name(), target_sigma, {PIPE_WJ, PIPE_WJ_T}, 0.2);
    const bool ok_a = a && w && w->res.H <= 0.5 * a->res.H, ok_b = b && w && w->res.H <= 0.5 * b->res.H,
               ok_a2 = a2 && w && w->res.H <= 0.5 * a2->res.H;
    met.a += ok_a; met.b += ok_b; met.a2 += ok_a2;
    table.add_row({S->name(), H_of(a) + " (" + (a ? config(*a) : "-") + ")",
                   H_of(a2) + " (" + (a2 ? config(*a2) : "-") + ")", H_of(b) + " (" + (b ? config(*b) : "-") + ")",
                   H_of(w) + " (" + (w ? std::string(pipe_name[w->method]) + ", " + config(*w) : "-") + ")",
                   H_ratio(w, a), H_ratio(w, b), H_ratio(w, a2), ok_a ? "yes" : "no"});
  }
  return table;
}

/// "sigma = 0.5%: one pass or two": best H RMSE with exactly 1 / 2 denoising passes.
WB::Csv_table Noisy_pipeline::passes_table() const
{
  WB::Csv_table table({"surface", "WJ 1 pass", "WJ 2 passes", "CGAL-S 1 pass", "CGAL-S 2 passes"});
  for(const auto& S : surfaces)
    table.add_row({S->name(), H_of(best(S->name(), target_sigma, {PIPE_WJ, PIPE_WJ_T}, 0.2, 1)),
                   H_of(best(S->name(), target_sigma, {PIPE_WJ, PIPE_WJ_T}, 0.2, 2)),
                   H_of(best(S->name(), target_sigma, {PIPE_CGAL_S}, 0.2, 1)),
                   H_of(best(S->name(), target_sigma, {PIPE_CGAL_S}, 0.2, 2))});
  return table;
}

/// "One setting for every surface": the common WJ setting `cw` and CGAL-S setting `cc` at every noise level.
WB::Csv_table Noisy_pipeline::common_setting_table(const Common& cw, const Common& cc) const
{
  WB::Csv_table table({"surface", "sigma %", "plain CGAL (a)", "residual input", "WJ", "residual WJ", "CGAL-S",
                       "residual CGAL-S", "WJ / (a)", "WJ / CGAL-S"});
  for(const auto& S : surfaces)
    for(double sigma : sigmas)
    {
      const Pipe_result* a = best(S->name(), sigma, {PIPE_PLAIN}, 0.2);
      const Pipe_result* w = cw.proto ? find_config(*cw.proto, S->name(), sigma) : nullptr;
      const Pipe_result* c = cc.proto ? find_config(*cc.proto, S->name(), sigma) : nullptr;
      table.add_row({S->name(), num(sigma), H_of(a), a ? fmt(a->residual) : "-", H_of(w), w ? fmt(w->residual) : "-",
                     H_of(c), c ? fmt(c->residual) : "-", H_ratio(w, a), H_ratio(w, c)});
    }
  return table;
}

/// The point-set functions themselves on all points at the common WJ setting `c` (sigma = 0.5%).
WB::Csv_table Noisy_pipeline::point_set_check_table(const Pipe_result& c) const
{
  WB::Csv_table table({"surface", "H RMSE (all points)", "H RMSE (grid, eval points)", "max diff", "time (s)"});
  for(std::size_t s = 0; s < surfaces.size(); ++s) table.add_row(point_set_check_row(s, c));
  return table;
}

std::vector<std::string> Noisy_pipeline::point_set_check_row(std::size_t s, const Pipe_result& c) const
{
  const WB::Surface& S = *surfaces[s];
  const Dataset d = make_dataset(S, s, o, target_sigma, 0.);
  CGAL::Real_timer t;
  t.start();
  std::vector<Point> pts = d.points;
  for(int pass = 0; pass < c.passes; ++pass)
    CGAL::wavejet_enhance_positions<Tag>(pts, 0, 1.0, WP::order(c.K1).neighbor_radius(c.r1));
  std::vector<Vector> normals;
  for(const WB::Sample& x : d.samples) normals.emplace_back(x.truth.normal.x(), x.truth.normal.y(), x.truth.normal.z());
  std::vector<std::size_t> idx(pts.size());
  for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::vector<double> H(pts.size(), std::numeric_limits<double>::quiet_NaN());
  const auto frame = c.method == PIPE_WJ_T ? CGAL::Wavejets::Curvature_frame::TANGENT_FRAME
                                           : CGAL::Wavejets::Curvature_frame::INITIAL_FRAME;
  CGAL::wavejet_estimate_curvatures<Tag>(idx, 0,
    WP::order(c.K2).curvature_frame(frame).mean_curvature_map(CGAL::make_property_map(H))
      .neighbor_radius(c.r2).point_map(CGAL::make_property_map(pts)).normal_map(CGAL::make_property_map(normals)));
  const double seconds = t.time();
  WB::Error_accumulator a;
  for(std::size_t i = 0; i < pts.size(); ++i)
  {
    if(!d.samples[i].inlier || d.samples[i].boundary_distance <= c.r2) continue;
    if(!std::isfinite(H[i])) { ++a.failed; continue; }
    const WB::Truth truth = S.truth(S.surface_point(WB::V3(pts[i].x(), pts[i].y(), pts[i].z())));
    a.add_curvature(H[i], 0., 0., 0., truth);
  }
  const Dataset m = moved_dataset(d, pts, S, nullptr);
  const std::vector<Estimate> ev = run_estimator(c.method == PIPE_WJ_T ? WJ_T : WJ, m, gather(m, c.r2), c.K2, c.r2);
  double max_diff = 0.;
  for(std::size_t i = 0; i < ev.size(); ++i)
    if(ev[i].ok) max_diff = std::max(max_diff, std::abs((c.method == PIPE_WJ_T ? ev[i].tH : ev[i].H) - H[d.eval[i]]));
  const Pipe_result* g = find_config(c, S.name(), target_sigma);
  return {S.name(), fmt(a.rmse_H()), H_of(g), fmt(max_diff, 2), fmt(seconds)};
}

/// "sigma = 0.5%: all pipelines, best setting per surface": WJ and WJ-T separately.
WB::Csv_table Noisy_pipeline::all_pipelines_table() const
{
  WB::Csv_table table({"surface", "sigma %", "plain CGAL (a)", "plain CGAL r <= 0.4 (a')", "CGAL-S (b)", "WJ", "WJ-T",
                       "WJ / (a)", "WJ / (b)"});
  auto cell = [&](const Pipe_result* x) { return x ? fmt(x->res.H) + " (" + config(*x) + ")" : std::string("-"); };
  for(const auto& S : surfaces)
  {
    const double sigma = target_sigma;
    const Pipe_result* a = best(S->name(), sigma, {PIPE_PLAIN}, 0.2);
    const Pipe_result* a2 = best(S->name(), sigma, {PIPE_PLAIN}, 0.4);
    const Pipe_result* b = best(S->name(), sigma, {PIPE_CGAL_S}, 0.2);
    const Pipe_result* w = best(S->name(), sigma, {PIPE_WJ}, 0.2);
    const Pipe_result* wt = best(S->name(), sigma, {PIPE_WJ_T}, 0.2);
    const Pipe_result* wb = (wt && (!w || wt->res.H < w->res.H)) ? wt : w;
    table.add_row({S->name(), num(sigma), cell(a), cell(a2), cell(b), cell(w), cell(wt), H_ratio(wb, a),
                   H_ratio(wb, b)});
  }
  return table;
}

/// Every row of the grid, full precision.
WB::Csv_table Noisy_pipeline::grid_table() const
{
  WB::Csv_table table({"surface", "sigma_pct", "method", "K1", "r1", "passes", "K2", "r2", "H_rmse", "K_rmse",
                       "k1_rmse", "k2_rmse", "angle_mean", "not_fitted", "residual"});
  for(const Pipe_result& x : rows)
    table.add_row({x.surface, num(x.sigma), pipe_short_name[x.method], std::to_string(x.K1), num(x.r1),
                   std::to_string(x.passes), std::to_string(x.K2), num(x.r2), num(x.res.H), num(x.res.K), num(x.res.k1),
                   num(x.res.k2), num(x.res.mean_angle), std::to_string(x.res.failed), num(x.residual)});
  return table;
}

// ---------------------------------------------------------------------------------------------
// Command line

/// Reads the options; returns false when the program should stop at once with `exit_code`.
static bool parse_command_line(int argc, char** argv, Options& o, int& exit_code)
{
  bool points_given = false, eval_given = false;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--quick") o.quick = true;
    else if(a == "--noisy-pipeline") o.pipeline = true;
    else if(a == "--noisy-pipeline-only") o.pipeline = o.pipeline_only = true;
    else if(a == "--points" && i + 1 < argc) { o.points = std::strtoul(argv[++i], nullptr, 10); points_given = true; }
    else if(a == "--eval" && i + 1 < argc) { o.eval = std::strtoul(argv[++i], nullptr, 10); eval_given = true; }
    else if(a == "--csv-dir" && i + 1 < argc) { o.csv_dir = argv[++i]; o.csv_dir_given = true; }
    else
    {
      std::cerr << "usage: bench_accuracy [--quick] [--points N] [--eval M] [--csv-dir DIR]\n"
                   "                      [--noisy-pipeline | --noisy-pipeline-only]\n"
                   "  --quick: 8000 points, 100 evaluation points, K in {2,4,6}, sigma in {0, 0.5%};\n"
                   "           writes nothing unless --csv-dir\n"
                   "  --csv-dir DIR: write the CSV files there (default: csv/ beside the source)\n"
                   "  --noisy-pipeline: also run the denoise-then-estimate section (sigma 0.5% only with --quick)\n"
                   "  --noisy-pipeline-only: run only that section (its CSV files and its run time in the context)\n";
      exit_code = a == "--help" || a == "-h" ? 0 : 1;
      return false;
    }
  }
  if(o.quick)
  {
    if(!points_given) o.points = 8000;
    if(!eval_given) o.eval = 100;
  }
  if(o.points < 1000 || o.eval < 10)
  {
    std::cerr << "need --points >= 1000 and --eval >= 10\n";
    exit_code = 1;
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Experiments 1-4

/// Best H RMSE of an estimator (set) over a (K, r) grid.
struct Best { double H = 1e300; std::size_t K = 0; int e = 0; double r = 0; };
struct Seed_row { std::string surface; double deg; Result orient, seed, seed_t, cgal; };
struct Ps_row { std::string surface, setting; double sigma; Result wj, cgal; double max_diff; std::size_t unfitted; double seconds; };

/// The grids of the experiments and everything they measured.
struct Experiments
{
  explicit Experiments(bool quick)
    : sigmas(quick ? std::vector<double>{0., 0.5} : std::vector<double>{0., 0.25, 0.5, 1.}),
      orders(quick ? std::vector<std::size_t>{2, 4, 6} : std::vector<std::size_t>{2, 3, 4, 5, 6, 7, 8})
  {}

  // experiment 1: position noise x radius x order x estimator
  const std::vector<double> sigmas, radii = {0.05, 0.1, 0.2};
  const std::vector<std::size_t> orders;
  // experiment 2: outliers (sigma = 0 and 0.5%, r = 0.1 and 0.2, K = 2 and 4)
  const std::vector<double> outlier_fractions = {0., 0.05, 0.1}, out_sigmas = {0., 0.5}, out_radii = {0.1, 0.2};
  const std::vector<std::size_t> out_orders = {2, 4};

  std::map<Key, Result> R;
  std::map<std::pair<std::string, double>, double> mean_neighbors; // (surface, r) -> mean L (clean)
  double seconds[NUM_ESTIMATORS] = {0, 0, 0, 0, 0, 0};
  std::vector<Seed_row> seed_rows; // experiment 3
  std::vector<Ps_row> ps_rows;     // experiment 4

  /// Result of experiment 1 (no outliers).
  const Result& get(const std::string& S, double sigma, double r, std::size_t K, int e) const
  {
    return R.at({S, sigma, 0., r, K, e});
  }
  Best best_of(const std::string& S, double sigma, const std::vector<double>& rs, const std::vector<int>& es) const
  {
    Best b;
    for(double r : rs)
      for(std::size_t K : orders)
        for(int e : es)
        {
          const Result& x = get(S, sigma, r, K, e);
          if(usable(x) && x.H < b.H) { b.H = x.H; b.K = K; b.e = e; b.r = r; }
        }
    return b;
  }
  /// Smallest mean normal angle of `e` over (K, r) in experiment 1, and where.
  double best_angle(const std::string& S, double sigma, int e, double* r_best = nullptr, std::size_t* K_best = nullptr) const
  {
    double best = 1e300, br = 0;
    std::size_t bk = 0;
    for(double r : radii)
      for(std::size_t K : (e == PCA ? std::vector<std::size_t>{0} : orders))
      {
        const Result& x = get(S, sigma, r, K, e);
        if(x.mean_angle < best) { best = x.mean_angle; br = r; bk = K; }
      }
    if(r_best) *r_best = br;
    if(K_best) *K_best = bk;
    return best;
  }
};

/// Experiment 1: position noise x radius x order x estimator.
static void run_position_noise(const Options& o, const Surfaces& surfaces, Experiments& ex, const CGAL::Real_timer& total)
{
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    const WB::Surface& S = *surfaces[s];
    for(double sigma : ex.sigmas)
    {
      CGAL::Real_timer t;
      t.start();
      const Dataset d = make_dataset(S, s, o, sigma, 0.);
      for(double r : ex.radii)
      {
        const Neighborhoods nh = gather(d, r);
        std::size_t minL = std::size_t(-1);
        double sumL = 0;
        for(const auto& v : nh.pts) { minL = std::min(minL, v.size()); sumL += double(v.size()); }
        if(sigma == 0.) ex.mean_neighbors[{S.name(), r}] = sumL / double(nh.pts.size());
        ex.R[{S.name(), sigma, 0., r, 0, PCA}] = evaluate(run_estimator(PCA, d, nh, 2, r), d, false);
        for(std::size_t K : ex.orders)
        {
          std::size_t reduced = 0;
          for(const auto& v : nh.pts) reduced += double(v.size()) < 1.1 * double(coefficients(K));
          for(int e : {WJ, WJ_R3, CGAL_JET})
          {
            CGAL::Real_timer te;
            te.start();
            const std::vector<Estimate> est = run_estimator(Estimator(e), d, nh, K, r);
            ex.seconds[e] += te.time();
            Result res = evaluate(est, d, true);
            res.reduced = reduced;
            ex.R[{S.name(), sigma, 0., r, K, e}] = res;
            if(e == WJ)
            {
              res = evaluate(est, d, true, true);
              res.reduced = reduced;
              ex.R[{S.name(), sigma, 0., r, K, WJ_T}] = res;
            }
          }
          // Adaptive order only acts where a neighborhood is too small for K; elsewhere WJ-fix == WJ.
          if(double(minL) < 1.1 * double(coefficients(K)))
            ex.R[{S.name(), sigma, 0., r, K, WJ_FIX}] = evaluate(run_estimator(WJ_FIX, d, nh, K, r), d, true);
          else
            ex.R[{S.name(), sigma, 0., r, K, WJ_FIX}] = ex.R[{S.name(), sigma, 0., r, K, WJ}];
        }
      }
      std::cerr << S.name() << " sigma " << sigma << "%: " << t.time() << " s (total " << total.time() << " s)\n";
    }
  }
}

/// Experiment 2: outliers.
static void run_outliers(const Options& o, const Surfaces& surfaces, Experiments& ex, const CGAL::Real_timer& total)
{
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    const WB::Surface& S = *surfaces[s];
    for(double sigma : ex.out_sigmas)
      for(double of : ex.outlier_fractions)
      {
        if(of == 0.) continue; // already in experiment 1
        const Dataset d = make_dataset(S, s, o, sigma, of);
        for(double r : ex.out_radii)
        {
          const Neighborhoods nh = gather(d, r);
          ex.R[{S.name(), sigma, of, r, 0, PCA}] = evaluate(run_estimator(PCA, d, nh, 2, r), d, false);
          for(std::size_t K : ex.out_orders)
            for(int e : {WJ, WJ_R3, CGAL_JET})
              ex.R[{S.name(), sigma, of, r, K, e}] = evaluate(run_estimator(Estimator(e), d, nh, K, r), d, true);
        }
      }
    std::cerr << S.name() << " outliers done (total " << total.time() << " s)\n";
  }
}

/// Experiment 3: noisy seed normals (sigma = 0, r = 0.1, K = 4).
static void run_seed_normals(const Options& o, const Surfaces& surfaces, Experiments& ex, const CGAL::Real_timer& total)
{
  const std::vector<double> normal_noise_deg = {0., 5., 15., 30.};
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
      row.cgal = ex.R[{S.name(), 0., 0., r, K, CGAL_JET}];
      ex.seed_rows.push_back(row);
    }
  }
  std::cerr << "seed normals done (total " << total.time() << " s)\n";
}

/// Outputs of the point-set functions on all points of a data set.
struct Point_set_outputs
{
  std::vector<double> H, KG, k1, k2;
  std::vector<Vector> normals;
  std::vector<unsigned char> fitted;
  std::size_t unfitted = 0;
  double seconds = 0;
};

/// wavejet_estimate_curvatures and wavejet_estimate_normals on all points of `d` at the setting `b`.
static Point_set_outputs run_point_set_functions_on(const Dataset& d, const Best& b)
{
  // The range is the point indices; positions, normals and outputs live in index-keyed maps.
  std::vector<std::size_t> idx(d.points.size());
  for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::vector<Vector> true_normals;
  for(const WB::Sample& x : d.samples) true_normals.emplace_back(x.truth.normal.x(), x.truth.normal.y(), x.truth.normal.z());
  Point_set_outputs out;
  out.normals = true_normals;
  const std::size_t N = idx.size();
  out.H.assign(N, 0.); out.KG.assign(N, 0.); out.k1.assign(N, 0.); out.k2.assign(N, 0.);
  out.fitted.assign(N, 0);
  CGAL::Real_timer t;
  t.start();
  const std::size_t rob = b.e == WJ_R3 ? 3 : 0;
  const double npc = b.e == WJ_FIX ? 1.0 : 1.1;
  const std::size_t mino = b.e == WJ_FIX ? b.K : 2;
  const auto frame = b.e == WJ_T ? CGAL::Wavejets::Curvature_frame::TANGENT_FRAME
                                 : CGAL::Wavejets::Curvature_frame::INITIAL_FRAME;
  CGAL::wavejet_estimate_curvatures<Tag>(idx, 0,
    WP::order(b.K).robust_iterations(rob).neighbors_per_coefficient(npc).minimum_order(mino).curvature_frame(frame)
      .mean_curvature_map(CGAL::make_property_map(out.H)).gaussian_curvature_map(CGAL::make_property_map(out.KG))
      .maximal_principal_curvature_map(CGAL::make_property_map(out.k1))
      .minimal_principal_curvature_map(CGAL::make_property_map(out.k2))
      .neighbor_radius(b.r).point_map(CGAL::make_property_map(d.points))
      .normal_map(CGAL::make_property_map(true_normals)));
  CGAL::Wavejets::Processing_report rep = CGAL::wavejet_estimate_normals<Tag>(idx, 0,
    WP::order(b.K).robust_iterations(rob).neighbors_per_coefficient(npc).minimum_order(mino)
      .orient_with_input_normals(true).fitted_map(CGAL::make_property_map(out.fitted))
      .neighbor_radius(b.r).point_map(CGAL::make_property_map(d.points))
      .normal_map(CGAL::make_property_map(out.normals)));
  out.seconds = t.time();
  out.unfitted = rep.number_of_unfitted_points;
  return out;
}

/// One row of experiment 4: the point-set functions on all points of surface `s` at noise `sigma`, their agreement
/// with Wavejet_fitting at the evaluation points, and CGAL jets on all points.
static Ps_row point_set_row(const Options& o, const WB::Surface& S, std::size_t s, double sigma)
{
  // recommended settings (section "Which settings to use"): clean WJ K = 6, r = 0.1; noisy WJ K = 2, r = 0.2
  Best b;
  b.e = WJ;
  b.K = sigma == 0. ? 6 : 2;
  b.r = sigma == 0. ? 0.1 : 0.2;
  const Dataset d = make_dataset(S, s, o, sigma, 0.);
  const Point_set_outputs ps = run_point_set_functions_on(d, b);
  const std::size_t N = d.points.size();
  WB::Error_accumulator a;
  for(std::size_t i = 0; i < N; ++i)
  {
    if(!d.samples[i].inlier || d.samples[i].boundary_distance <= b.r) continue;
    if(!ps.fitted[i]) { ++a.failed; continue; }
    const Vector n = ps.normals[i];
    a.add_normal(WB::V3(n.x(), n.y(), n.z()), d.samples[i].truth);
    a.add_curvature(ps.H[i], ps.KG[i], ps.k1[i], ps.k2[i], d.samples[i].truth);
  }
  Ps_row row;
  row.surface = S.name();
  row.sigma = sigma;
  std::ostringstream st;
  st << estimator_name[b.e] << " K=" << b.K << " r=" << b.r;
  row.setting = st.str();
  row.wj = summarize(a, true);
  row.unfitted = ps.unfitted;
  row.seconds = ps.seconds;
  // consistency with Wavejet_fitting at the evaluation points, and CGAL on all points
  const Neighborhoods nh = gather(d, b.r);
  const std::vector<Estimate> ev = run_estimator(Estimator(b.e), d, nh, b.K, b.r);
  row.max_diff = 0.;
  for(std::size_t i = 0; i < ev.size(); ++i)
    if(ev[i].ok)
    {
      const std::size_t j = d.eval[i];
      const Vector n = ps.normals[j];
      row.max_diff = std::max({row.max_diff, std::abs(ev[i].H - ps.H[j]), std::abs(ev[i].K - ps.KG[j]),
                               (ev[i].n - WB::V3(n.x(), n.y(), n.z())).norm()});
    }
  // CGAL on all points (same degree, same radius)
  Dataset all = d;
  all.eval.clear();
  for(std::size_t i = 0; i < N; ++i)
    if(d.samples[i].inlier && d.samples[i].boundary_distance > b.r) all.eval.push_back(i);
  const Neighborhoods nh_all = gather(all, b.r);
  row.cgal = evaluate(run_estimator(CGAL_JET, all, nh_all, b.K, b.r), all, true);
  return row;
}

/// Experiment 4: the point-set functions on all N points at recommended settings.
static void run_point_set_functions(const Options& o, const Surfaces& surfaces, Experiments& ex,
                                    const CGAL::Real_timer& total)
{
  for(std::size_t s = 0; s < surfaces.size(); ++s)
  {
    for(double sigma : {0., 0.5}) ex.ps_rows.push_back(point_set_row(o, *surfaces[s], s, sigma));
    std::cerr << surfaces[s]->name() << " point-set run done (total " << total.time() << " s)\n";
  }
}

// ---------------------------------------------------------------------------------------------
// Tables of experiments 1-4 (accuracy.*.csv)

/// "Summary": per surface and noise level, the best setting of each estimator.
static WB::Csv_table summary_table(const Surfaces& surfaces, const Experiments& ex)
{
  WB::Csv_table table({"surface", "sigma %", "WJ: H (K, r)", "WJ-R3", "WJ-T", "CGAL", "normal WJ (deg)", "WJ-R3", "CGAL",
                       "PCA"});
  for(const auto& S : surfaces)
    for(double sigma : ex.sigmas)
    {
      std::vector<std::string> row = {S->name(), num(sigma)};
      for(int e : {WJ, WJ_R3, WJ_T, CGAL_JET})
      {
        const Best b = ex.best_of(S->name(), sigma, ex.radii, {e});
        row.push_back(b.K == 0 ? std::string("-") : fmt(b.H) + " (" + std::to_string(b.K) + ", " + num(b.r) + ")");
      }
      for(int e : {WJ, WJ_R3, CGAL_JET, PCA})
      {
        double br = 0;
        std::size_t bk = 0;
        const double best = ex.best_angle(S->name(), sigma, e, &br, &bk);
        row.push_back(fmt(best) + " (" + (e == PCA ? std::string("-") : std::to_string(bk)) + ", " + num(br) + ")");
      }
      table.add_row(row);
    }
  return table;
}

/// The summary's minima at full precision, for the plot: best H RMSE over (K, r) of WJ, WJ-R3, WJ-T, CGAL (NaN where
/// more than 1% of the points are not fitted), best mean normal angle of WJ, WJ-R3, CGAL and PCA.
static WB::Csv_table noise_best_table(const Surfaces& surfaces, const Experiments& ex)
{
  WB::Csv_table table({"surface", "sigma %", "H WJ", "H WJ-R3", "H WJ-T", "H CGAL", "angle WJ", "angle WJ-R3",
                       "angle CGAL", "angle PCA"});
  for(const auto& S : surfaces)
    for(double sigma : ex.sigmas)
    {
      std::vector<std::string> row = {S->name(), num(sigma)};
      for(int e : {WJ, WJ_R3, WJ_T, CGAL_JET})
      {
        const Best b = ex.best_of(S->name(), sigma, ex.radii, {e});
        row.push_back(b.K == 0 ? std::string("NaN") : num(b.H));
      }
      for(int e : {WJ, WJ_R3, CGAL_JET, PCA}) row.push_back(num(ex.best_angle(S->name(), sigma, e)));
      table.add_row(row);
    }
  return table;
}

/// The numbers that the prose of accuracy.md quotes outside its tables, printed for its template: the mean
/// neighborhood sizes and the clean-data target (on how many (surface, r, K) WJ's H RMSE and mean normal angle are at
/// most CGAL's).
static void print_prose_numbers(const Surfaces& surfaces, const Experiments& ex)
{
  std::cout << "mean neighborhood sizes (clean, r =";
  for(double r : ex.radii) std::cout << " " << r;
  std::cout << "):";
  for(const auto& S : surfaces)
  {
    std::cout << " " << S->name() << " ";
    for(double r : ex.radii) std::cout << (r == ex.radii[0] ? "" : "/") << fmt(ex.mean_neighbors.at({S->name(), r}), 3);
  }
  std::cout << "\n";
  std::size_t clean_total = 0, clean_h_ok = 0, clean_n_ok = 0;
  double worst_rel = 0.;
  for(const auto& S : surfaces)
    for(double r : ex.radii)
      for(std::size_t K : ex.orders)
      {
        const Result& w = ex.get(S->name(), 0., r, K, WJ);
        const Result& c = ex.get(S->name(), 0., r, K, CGAL_JET);
        ++clean_total;
        const double tol = 1e-9 * (1. + c.H);
        if(w.H <= c.H + tol) ++clean_h_ok;
        else
          std::cout << "  clean data, WJ above CGAL: " << S->name() << " r=" << r << " K=" << K << ": H RMSE WJ "
                    << fmt(w.H, 6) << " vs CGAL " << fmt(c.H, 6) << "\n";
        worst_rel = std::max(worst_rel, std::abs(w.H - c.H) / std::max(c.H, 1e-300));
        if(w.mean_angle <= c.mean_angle * (1. + 1e-9) + 1e-12) ++clean_n_ok;
      }
  std::cout << "clean data: WJ H RMSE <= CGAL's in " << clean_h_ok << " / " << clean_total
            << " (surface, r, K); largest relative difference " << fmt(worst_rel, 2)
            << "; mean normal angle WJ <= CGAL in " << clean_n_ok << " / " << clean_total << "\n";
}

/// "Targets", noisy data (sigma = 0.5%): best WJ setting vs best CGAL setting, per radius and overall.
static WB::Csv_table targets_table(const Surfaces& surfaces, const Experiments& ex)
{
  const std::vector<int> wj_set = {WJ, WJ_R3, WJ_T, WJ_FIX};
  std::size_t half_met = 0, half_total = 0;
  WB::Csv_table table({"surface", "r", "best Wavejet (variant, K)", "H RMSE", "best CGAL (K)", "H RMSE", "ratio",
                       "<= 0.5?"});
  for(const auto& S : surfaces)
  {
    std::vector<std::vector<double> > groups;
    for(double r : ex.radii) groups.push_back({r});
    groups.push_back(ex.radii);
    for(const auto& g : groups)
    {
      const Best w = ex.best_of(S->name(), 0.5, g, wj_set), c = ex.best_of(S->name(), 0.5, g, {CGAL_JET});
      const bool all = g.size() > 1;
      if(w.K == 0 || c.K == 0)
      {
        table.add_row({S->name(), all ? std::string("best") : fmt(g[0]), "-", "-", "-", "-", "-",
                       "(more than 1% of the points not fitted)"});
        continue;
      }
      const double ratio = w.H / c.H;
      if(all) { ++half_total; half_met += ratio <= 0.5; }
      table.add_row({S->name(), all ? std::string("best: ") + fmt(w.r) + " / " + fmt(c.r) : fmt(g[0]),
                     std::string(estimator_name[w.e]) + ", K=" + std::to_string(w.K), fmt(w.H),
                     "K=" + std::to_string(c.K), fmt(c.H), fmt(ratio), ratio <= 0.5 ? "yes" : "no"});
    }
  }
  std::cout << "noisy data (sigma = 0.5%), best WJ <= half of best CGAL H RMSE (best over radii for both): met on "
            << half_met << " / " << half_total << " surfaces\n";
  return table;
}

/// "The point-set functions on all points" (experiment 4).
static WB::Csv_table point_set_table(const Experiments& ex)
{
  WB::Csv_table table({"surface", "sigma %", "setting", "WJ H", "CGAL H", "WJ K_G", "CGAL K_G", "WJ angle mean / p95",
                       "CGAL angle mean / p95", "not fitted", "max diff", "WJ time (s)"});
  for(const Ps_row& p : ex.ps_rows)
    table.add_row({p.surface, num(p.sigma), p.setting, fmt(p.wj.H), fmt(p.cgal.H), fmt(p.wj.K), fmt(p.cgal.K),
                   fmt(p.wj.mean_angle) + " / " + fmt(p.wj.p95_angle),
                   fmt(p.cgal.mean_angle) + " / " + fmt(p.cgal.p95_angle),
                   std::to_string(p.unfitted), fmt(p.max_diff, 2), fmt(p.seconds)});
  return table;
}

/// "Outliers" (experiment 2).
static WB::Csv_table outliers_table(const Surfaces& surfaces, const Experiments& ex)
{
  WB::Csv_table table({"surface", "sigma %", "outliers", "r", "K", "WJ H", "WJ-R3 H", "CGAL H", "WJ angle",
                       "WJ-R3 angle", "CGAL angle", "PCA angle"});
  for(const auto& S : surfaces)
    for(double sigma : ex.out_sigmas)
      for(double of : ex.outlier_fractions)
        for(double r : ex.out_radii)
          for(std::size_t K : ex.out_orders)
          {
            auto g = [&](int e, std::size_t k) -> const Result& { return ex.R.at({S->name(), sigma, of, r, k, e}); };
            table.add_row({S->name(), num(sigma), num(of * 100) + "%", num(r), std::to_string(K), fmt(g(WJ, K).H),
                           fmt(g(WJ_R3, K).H), fmt(g(CGAL_JET, K).H), fmt(g(WJ, K).mean_angle),
                           fmt(g(WJ_R3, K).mean_angle), fmt(g(CGAL_JET, K).mean_angle), fmt(g(PCA, 0).mean_angle)});
          }
  return table;
}

/// "Noisy seed normals" (experiment 3).
static WB::Csv_table seed_normals_table(const Experiments& ex)
{
  WB::Csv_table table({"surface", "s (deg)", "orient: H / angle", "seed: H / angle", "seed+T: H / angle",
                       "CGAL: H / angle"});
  auto cell = [](const Result& x) { return fmt(x.H) + " / " + fmt(x.mean_angle); };
  for(const Seed_row& x : ex.seed_rows)
    table.add_row({x.surface, num(x.deg), cell(x.orient), cell(x.seed), cell(x.seed_t), cell(x.cgal)});
  return table;
}

/// Every (noise level, surface, r, K, estimator) of experiment 1.
static WB::Csv_table full_grid_table(const Surfaces& surfaces, const Experiments& ex)
{
  WB::Csv_table table({"sigma %", "surface", "r", "K", "est.", "H", "K_G", "k1", "k2", "angle mean", "angle p95",
                       "not fitted", "reduced"});
  auto add = [&](double sigma, const std::string& S, double r, std::size_t K, int e) {
    const Result& x = ex.R.at({S, sigma, 0., r, K, e});
    const bool c = x.has_curvature;
    table.add_row({num(sigma), S, num(r), e == PCA ? std::string("-") : std::to_string(K), estimator_name[e],
                   c ? fmt(x.H) : "-", c ? fmt(x.K) : "-", c ? fmt(x.k1) : "-", c ? fmt(x.k2) : "-", fmt(x.mean_angle),
                   fmt(x.p95_angle), std::to_string(x.failed),
                   e == WJ || e == WJ_R3 || e == WJ_T ? std::to_string(x.reduced) : std::string("-")});
  };
  for(double sigma : ex.sigmas)
    for(const auto& S : surfaces)
      for(double r : ex.radii)
      {
        add(sigma, S->name(), r, 0, PCA);
        for(std::size_t K : ex.orders)
          for(int e : {WJ, WJ_R3, WJ_T, WJ_FIX, CGAL_JET}) add(sigma, S->name(), r, K, e);
      }
  return table;
}

/// Writes accuracy.context.csv into `dir`: the rows of an existing one, with the keys of `updates` replaced or added
/// (a run without the noisy-pipeline section keeps that section's run time, and the reverse).
static void write_context(const std::string& dir, const std::vector<std::pair<std::string, std::string> >& updates)
{
  WB::Csv_table fresh = WB::context_table();
  for(const auto& u : updates) fresh.add_row({u.first, u.second});
  std::string text = fresh.str();
  std::ifstream old(dir + "/accuracy.context.csv");
  std::string line;
  std::getline(old, line); // header
  while(std::getline(old, line))
  {
    const std::string key = line.substr(0, line.find(','));
    if(std::none_of(updates.begin(), updates.end(), [&](const auto& u) { return u.first == key; })) text += line + "\n";
  }
  const std::string path = dir + "/accuracy.context.csv";
  std::ofstream f(path);
  f << text;
  if(!f) { std::cerr << "cannot write " << path << "\n"; std::exit(EXIT_FAILURE); }
  std::cout << "wrote " << path << "\n";
}

// ---------------------------------------------------------------------------------------------

int main(int argc, char** argv)
{
  Options o;
  int exit_code = 0;
  if(!parse_command_line(argc, argv, o, exit_code)) return exit_code;

  CGAL::Real_timer total;
  total.start();
  const Surfaces surfaces = WB::all_surfaces();
  Named_tables tables;
  std::vector<std::pair<std::string, std::string> > context;
  if(o.pipeline)
  {
    Pipe_output pipe = Noisy_pipeline(o, surfaces).run();
    tables = pipe.tables;
    context.emplace_back("noisy-pipeline run time (s)", fmt(pipe.seconds, 3));
  }
  if(!o.pipeline_only)
  {
    Experiments ex(o.quick);
    run_position_noise(o, surfaces, ex, total);
    run_outliers(o, surfaces, ex, total);
    run_seed_normals(o, surfaces, ex, total);
    run_point_set_functions(o, surfaces, ex, total);
    const double total_seconds = total.time();
    print_prose_numbers(surfaces, ex);
    std::cout << "time per estimator in the position-noise sweep: WJ (also gives WJ-T) " << fmt(ex.seconds[WJ])
              << " s, WJ-R3 " << fmt(ex.seconds[WJ_R3]) << " s, CGAL " << fmt(ex.seconds[CGAL_JET]) << " s\n";
    tables.emplace_back("accuracy.summary", summary_table(surfaces, ex));
    tables.emplace_back("accuracy.noise_best", noise_best_table(surfaces, ex));
    tables.emplace_back("accuracy.targets", targets_table(surfaces, ex));
    tables.emplace_back("accuracy.point_set_functions", point_set_table(ex));
    tables.emplace_back("accuracy.outliers", outliers_table(surfaces, ex));
    tables.emplace_back("accuracy.noisy_seed_normals", seed_normals_table(ex));
    tables.emplace_back("accuracy.full_grid", full_grid_table(surfaces, ex));
    context.insert(context.begin(), {{"machine", WB::machine_description()}, {"run time (s)", fmt(total_seconds, 3)}});
  }
  if(!o.write()) return 0;
  for(const auto& table : tables) table.second.write(o.csv_dir, table.first);
  write_context(o.csv_dir, context);
  return 0;
}
