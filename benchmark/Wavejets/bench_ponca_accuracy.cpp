// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// Accuracy of Wavejet curvature (plain and Hermite fits, constant and compact weights) against CGAL's
// jets and Ponca's APSS (OrientedSphereFit, positions and normals; constant and smooth weights) and
// ASO (APSS differentiated in space: Weingarten map of the normal field), on the same k-nearest
// neighborhoods, on analytic surfaces with exact curvature, with Gaussian position noise.
//
// Usage: bench_ponca_accuracy [--points N] [--eval M] [--csv-dir DIR] [--quick]
//   N points per surface (default 20000), M evaluation points (default 1000). Writes its tables as
//   DIR/accuracy_ponca.*.csv (default: csv/ next to this source); make_reports.py writes accuracy_ponca.md and
//   accuracy_ponca.png from them. --quick: sphere and torus, noise {0, 0.5%}, k {20, 100}.
//
// Ponca (https://github.com/poncateam/ponca, MPL-2.0) is used here only, never by the package. CMake
// unpacks the release tarball WAVEJETS_PONCA_TARBALL (CMakeLists.txt) or takes WAVEJETS_PONCA_DIR;
// without it this program still builds and runs, without the Ponca rows (WAVEJETS_HAVE_PONCA undefined).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Real_timer.h>
#include <CGAL/for_each.h>
#include <CGAL/property_map.h>
#include <CGAL/Wavejet_fitting.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/Wavejets/internal/neighbor_query.h>

#include "analytic_surfaces.h"

#include "ponca_types.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench_common.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Wavejet_fitting<Kernel> WJ_fitting;
typedef CGAL::Monge_via_jet_fitting<Kernel> Monge_fitting;
typedef CGAL::Parallel_if_available_tag Tag;
namespace WB = wavejets_bench;
namespace WP = CGAL::Wavejets::parameters;


// ---------------------------------------------------------------------------------------------
// Estimators (columns).

enum Estimator
{
  CGAL2, CGAL3, CGAL4,       // CGAL jets of degree 2..4 (Monge degree 2), PCA frame
  WJ2, WJ3, WJ4,             // Wavejets K = 2..4, plain (wavejet_estimate_curvatures' defaults)
  WJH2, WJH3, WJH4,          // Hermite: heights and the neighbors' Wavejet normals (use_neighbor_normals)
  WJH2P,                     // Hermite K = 2 with the PCA normals APSS gets
  WJH2_W3, WJH2_W10,         // Hermite K = 2, neighbor_normal_weight 3 and 10
  WJ2C, WJ4C, WJH2C, WJH4C,  // compact weights (1 - (d/Rf)^2)^2
  APSS_C, APSS_S, ASO_S,     // Ponca: APSS constant and smooth weights, ASO smooth weights
  NUM_ESTIMATORS
};
static const char* estimator_name[NUM_ESTIMATORS] = {
  "CGAL-2", "CGAL-3", "CGAL-4", "WJ-2", "WJ-3", "WJ-4", "WJH-2", "WJH-3", "WJH-4", "WJH-2-pca", "WJH-2-w3", "WJH-2-w10",
  "WJ-2-c", "WJ-4-c", "WJH-2-c", "WJH-4-c", "APSS", "APSS-s", "ASO-s"};
static bool is_ponca(int e) { return e == APSS_C || e == APSS_S || e == ASO_S; }
#ifdef WAVEJETS_HAVE_PONCA
static const bool have_ponca = true;
#else
static const bool have_ponca = false;
#endif

struct Options
{
  std::size_t points = 20000, eval = 1000;
  std::string csv_dir = wavejets_bench::source_dir() + "/csv";
  bool quick = false;
};

/// Per-point estimate.
struct Estimate
{
  bool ok = false;
  double H = 0, K = 0, k1 = 0, k2 = 0;
  WB::V3 n = WB::V3::Zero();
};

/// Errors of one estimator on one configuration.
struct Result
{
  double relH = 0, H = 0, K = 0, k1 = 0, k2 = 0, angle = 0;
  // scale: least-squares factor s of H = s H* (1: unbiased, below 1: shrunk toward 0);
  // relH_rescaled: relative RMSE of H / s (the error left once the shrinkage is undone)
  double scale = 1, relH_rescaled = 0;
  std::size_t failed = 0;
  bool present = false;
};

struct Dataset
{
  std::vector<WB::Sample> samples;
  std::vector<Point> points;
  std::vector<std::size_t> eval;
  std::vector<std::vector<std::size_t> > hoods; // per evaluation point: query, then its k neighbors
  std::vector<WB::V3> pca;                       // per point: PCA normal of its k neighbors, oriented by the truth
};

static Dataset make_dataset(const WB::Surface& S, std::size_t s_index, const Options& o, double sigma_pct)
{
  Dataset d;
  d.samples = S.sample(o.points, 1000 + s_index);
  const double diagonal = WB::bounding_box_diagonal(d.samples);
  WB::add_position_noise(d.samples, sigma_pct / 100. * diagonal, 2000 + s_index + std::size_t(sigma_pct * 1000));
  for(const WB::Sample& s : d.samples) d.points.emplace_back(s.p.x(), s.p.y(), s.p.z());
  std::mt19937_64 rng(4000 + s_index);
  std::vector<std::size_t> candidates;
  for(std::size_t i = 0; i < d.samples.size(); ++i)
    if(d.samples[i].boundary_distance > 0.3) candidates.push_back(i);
  std::shuffle(candidates.begin(), candidates.end(), rng);
  candidates.resize(std::min(candidates.size(), o.eval));
  std::sort(candidates.begin(), candidates.end());
  d.eval = candidates;
  return d;
}

/// kNN of every point (the package's query, the one the functions use): PCA normals of all points,
/// and the neighborhoods of the evaluation points.
static void gather(Dataset& d, unsigned int k)
{
  typedef CGAL::Wavejets::internal::Neighbor_query Q;
  std::vector<Q::Point> p;
  for(const Point& q : d.points) p.emplace_back(q.x(), q.y(), q.z());
  std::vector<unsigned char> in_tree(p.size(), 1);
  const Q query(p, in_tree);
  const std::size_t N = d.points.size();
  d.pca.assign(N, WB::V3::Zero());
  d.hoods.assign(d.eval.size(), {});
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < N; b += 256) chunks.push_back(b);
  CGAL::for_each<Tag>(chunks, [&](std::size_t b) -> bool {
    std::vector<std::size_t> nb;
    Q::Scratch scratch;
    for(std::size_t i = b; i < std::min(b + 256, N); ++i)
    {
      query.neighbors(i, k, 0., nb, scratch);
      WB::V3 mean = WB::V3(p[i].x(), p[i].y(), p[i].z());
      for(std::size_t j : nb) mean += WB::V3(p[j].x(), p[j].y(), p[j].z());
      mean /= double(nb.size() + 1);
      WB::M3 C = WB::M3::Zero();
      auto add = [&](std::size_t j) { const WB::V3 q = WB::V3(p[j].x(), p[j].y(), p[j].z()) - mean; C += q * q.transpose(); };
      add(i);
      for(std::size_t j : nb) add(j);
      WB::V3 n = Eigen::SelfAdjointEigenSolver<WB::M3>(C).eigenvectors().col(0);
      if(n.dot(d.samples[i].truth.normal) < 0) n = -n;
      d.pca[i] = n;
    }
    return true;
  });
  for(std::size_t e = 0; e < d.eval.size(); ++e)
  {
    Q::Scratch scratch;
    std::vector<std::size_t> nb;
    query.neighbors(d.eval[e], k, 0., nb, scratch);
    d.hoods[e].assign(1, d.eval[e]);
    d.hoods[e].insert(d.hoods[e].end(), nb.begin(), nb.end());
  }
}

/// Wavejet normals of all points (wavejet_estimate_normals, order K, the same k), oriented by the truth
/// (for the orientation of the curvature signs only: the slope equations do not depend on it).
static std::vector<WB::V3> wavejet_normals(const Dataset& d, unsigned int k, std::size_t K)
{
  std::vector<Vector> n(d.points.size(), CGAL::NULL_VECTOR);
  std::vector<std::size_t> idx(d.points.size());
  for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  CGAL::wavejet_estimate_normals<Tag>(idx, k, WP::order(K).point_map(CGAL::make_property_map(d.points))
                                                 .normal_map(CGAL::make_property_map(n)));
  std::vector<WB::V3> out(n.size());
  for(std::size_t i = 0; i < n.size(); ++i)
  {
    out[i] = WB::V3(n[i].x(), n[i].y(), n[i].z());
    if(out[i].dot(d.samples[i].truth.normal) < 0) out[i] = -out[i];
  }
  return out;
}

static std::size_t order_of(int e)
{
  switch(e) {
    case CGAL2: case WJ2: case WJH2: case WJH2P: case WJH2_W3: case WJH2_W10: case WJ2C: case WJH2C: return 2;
    case CGAL3: case WJ3: case WJH3: return 3;
    default: return 4;
  }
}

/// Runs estimator e on every evaluation point. `wj_normals[K]`: Wavejet normals of order K.
static std::vector<Estimate> run(int e, const Dataset& d, const std::map<std::size_t, std::vector<WB::V3> >& wj_normals)
{
  std::vector<Estimate> out(d.eval.size());
  const std::size_t K = order_of(e);
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < d.eval.size(); b += 32) chunks.push_back(b);
  CGAL::for_each<Tag>(chunks, [&](std::size_t b) -> bool {
    // The options of wavejet_estimate_curvatures: first fit in the PCA frame, no tangent-plane re-fits.
    CGAL::Wavejets::Fitting_options fo;
    fo.correction_iterations = 0;
    fo.compute_condition_number = false;
    fo.compact_weights = e == WJ2C || e == WJ4C || e == WJH2C || e == WJH4C;
    fo.neighbor_normal_weight = e == WJH2_W3 ? 3. : e == WJH2_W10 ? 10. : 1.;
    WJ_fitting wj(fo);
    Monge_fitting monge;
    std::vector<Point> pts;
    std::vector<Vector> nrm;
    for(std::size_t i = b; i < std::min(b + 32, d.eval.size()); ++i)
    {
      const std::vector<std::size_t>& hood = d.hoods[i];
      const WB::Truth& t = d.samples[d.eval[i]].truth;
      Estimate& r = out[i];
      pts.clear();
      for(std::size_t j : hood) pts.push_back(d.points[j]);
      if(e == CGAL2 || e == CGAL3 || e == CGAL4)
      {
        WB::jet_estimate(monge, pts, K, Vector(t.normal.x(), t.normal.y(), t.normal.z()), r);
      }
      else if(!is_ponca(e))
      {
        const bool hermite = e == WJH2 || e == WJH3 || e == WJH4 || e == WJH2P || e == WJH2_W3 || e == WJH2_W10 ||
                             e == WJH2C || e == WJH4C;
        const std::vector<WB::V3>& normals = e == WJH2P ? d.pca : wj_normals.at(K);
        WJ_fitting::Wavejet_form f;
        if(hermite)
        {
          nrm.clear();
          for(std::size_t j : hood) nrm.emplace_back(normals[j].x(), normals[j].y(), normals[j].z());
          f = wj(pts.begin(), pts.end(), nrm.begin(), K);
        }
        else
        {
          const WB::V3& o = d.pca[hood[0]]; // orients the frame (signs), as a normal map would
          f = wj(pts.begin(), pts.end(), K, Vector(o.x(), o.y(), o.z()));
        }
        if(!f.is_valid()) continue;
        r.H = f.mean_curvature();
        r.K = f.gaussian_curvature();
        r.k1 = f.principal_curvatures(0);
        r.k2 = f.principal_curvatures(1);
        // normal: the Wavejet normal the plain estimator's normals are (wavejet_estimate_normals);
        // for the Hermite rows, the normal of the Hermite fit
        const WB::V3& wn = wj_normals.at(K)[hood[0]];
        const Vector n = f.normal_direction();
        r.n = hermite ? WB::V3(n.x(), n.y(), n.z()) : wn;
        r.ok = true;
      }
#ifdef WAVEJETS_HAVE_PONCA
      else
      {
        std::vector<Ponca_point> pp;
        double Rf = 0.;
        const WB::V3 c(pts[0].x(), pts[0].y(), pts[0].z());
        for(std::size_t j : hood)
        {
          const WB::V3 q(d.points[j].x(), d.points[j].y(), d.points[j].z());
          pp.emplace_back(q, d.pca[j]);
          Rf = std::max(Rf, (q - c).norm());
        }
        const double scale = Rf * (1. + 1e-9) + 1e-300; // every neighbor inside the (compact) kernel
        auto read_sphere = [&](const auto& fit) {
          // kappa: curvature of the Pratt-normalized algebraic sphere, positive when it bends
          // toward its gradient, which the oriented input normals orient outward: the package's sign
          // convention (bending toward the normal is positive) is the opposite.
          r.H = -fit.kappa();
          r.k1 = r.k2 = r.H;
          r.K = r.H * r.H;
          r.n = fit.primitiveGradient(c).normalized();
          r.ok = std::isfinite(r.H) && r.n.allFinite();
        };
        if(e == APSS_C)
        {
          APSS_constant fit;
          fit.setNeighborFilter(Constant_weight(c, scale));
          if(fit.compute(pp.begin(), pp.end()) == Ponca::STABLE) read_sphere(fit);
        }
        else if(e == APSS_S)
        {
          APSS_smooth fit;
          fit.setNeighborFilter(Smooth_weight(c, scale));
          if(fit.compute(pp.begin(), pp.end()) == Ponca::STABLE) read_sphere(fit);
        }
        else
        {
          ASO_smooth fit;
          fit.setNeighborFilter(Smooth_weight(c, scale));
          if(fit.compute(pp.begin(), pp.end()) == Ponca::STABLE)
          {
            // Ponca's principal curvatures are relative to the sphere's gradient (outward): negate.
            r.k1 = -fit.kmin();
            r.k2 = -fit.kmax();
            if(r.k1 < r.k2) std::swap(r.k1, r.k2);
            r.H = 0.5 * (r.k1 + r.k2);
            r.K = r.k1 * r.k2;
            r.n = fit.primitiveGradient().normalized(); // at the evaluation point, the query
            r.ok = std::isfinite(r.H) && std::isfinite(r.K) && r.n.allFinite();
          }
        }
      }
#endif
    }
    return true;
  });
  return out;
}

static Result evaluate(const std::vector<Estimate>& est, const Dataset& d)
{
  WB::Error_accumulator a;
  double sH = 0., sT = 0., sHT = 0.;
  Result r;
  r.present = true;
  for(std::size_t i = 0; i < est.size(); ++i)
  {
    const WB::Truth& t = d.samples[d.eval[i]].truth;
    if(!est[i].ok) { ++r.failed; continue; }
    a.add_curvature(est[i].H, est[i].K, est[i].k1, est[i].k2, t);
    a.add_normal(est[i].n, t);
    sH += (est[i].H - t.H) * (est[i].H - t.H);
    sT += t.H * t.H;
    sHT += est[i].H * t.H;
  }
  r.relH = sT > 0 ? std::sqrt(sH / sT) : 0.;
  if(sT > 0 && sHT > 0)
  {
    r.scale = sHT / sT;
    double sR = 0.;
    for(std::size_t i = 0; i < est.size(); ++i)
      if(est[i].ok)
      {
        const double t = d.samples[d.eval[i]].truth.H, u = est[i].H / r.scale - t;
        sR += u * u;
      }
    r.relH_rescaled = std::sqrt(sR / sT);
  }
  r.H = a.rmse_H();
  r.K = a.rmse_K();
  r.k1 = a.rmse_k1();
  r.k2 = a.rmse_k2();
  r.angle = a.mean_angle();
  return r;
}

static std::string fmt(double v, int prec = 3)
{
  std::ostringstream s;
  s.precision(prec);
  s << v;
  return s.str();
}

/// Reads the options; false on a usage error.
static bool parse_command_line(int argc, char** argv, Options& o)
{
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--quick") o.quick = true;
    else if(a == "--points" && i + 1 < argc) o.points = std::strtoul(argv[++i], nullptr, 10);
    else if(a == "--eval" && i + 1 < argc) o.eval = std::strtoul(argv[++i], nullptr, 10);
    else if(a == "--csv-dir" && i + 1 < argc) o.csv_dir = argv[++i];
    else
    {
      std::cerr << "usage: bench_ponca_accuracy [--points N] [--eval M] [--csv-dir DIR] [--quick]\n";
      return false;
    }
  }
  return true;
}

static std::vector<std::unique_ptr<WB::Surface> > benchmark_surfaces(bool quick)
{
  std::vector<std::unique_ptr<WB::Surface> > surfaces;
  surfaces.emplace_back(new WB::Sphere);
  surfaces.emplace_back(new WB::Ellipsoid);
  surfaces.emplace_back(new WB::Torus);
  surfaces.emplace_back(new WB::Goursat);
  surfaces.emplace_back(new WB::Cylinder);
  if(quick) { surfaces.erase(surfaces.begin() + 3, surfaces.end()); surfaces.erase(surfaces.begin() + 1); }
  return surfaces;
}

/// The noise x k grid and its results[surface][noise][k][estimator].
struct Grid
{
  std::vector<double> noises;
  std::vector<unsigned int> ks;
  std::map<std::string, std::map<double, std::map<unsigned int, std::vector<Result> > > > results;
};

static const std::vector<Result>& row_of(const Grid& g, const std::string& surface, double noise, unsigned int k)
{
  return g.results.at(surface).at(noise).at(k);
}

/// Every estimator on every (surface, noise, k).
static Grid run_grid(const Options& o, const std::vector<std::unique_ptr<WB::Surface> >& surfaces, CGAL::Real_timer& total)
{
  Grid g;
  g.noises = o.quick ? std::vector<double>{0., 0.5} : std::vector<double>{0., 0.25, 0.5, 1.};
  g.ks = o.quick ? std::vector<unsigned int>{20, 100} : std::vector<unsigned int>{20, 50, 100, 200};
  for(std::size_t s = 0; s < surfaces.size(); ++s)
    for(double noise : g.noises)
    {
      Dataset d = make_dataset(*surfaces[s], s, o, noise);
      for(unsigned int k : g.ks)
      {
        gather(d, k);
        std::map<std::size_t, std::vector<WB::V3> > wj_normals;
        for(std::size_t K = 2; K <= 4; ++K) wj_normals[K] = wavejet_normals(d, k, K);
        std::vector<Result>& row = g.results[surfaces[s]->name()][noise][k];
        row.assign(NUM_ESTIMATORS, Result());
        for(int e = 0; e < NUM_ESTIMATORS; ++e)
          if(!is_ponca(e) || have_ponca) row[e] = evaluate(run(e, d, wj_normals), d);
        std::cerr << surfaces[s]->name() << " noise " << noise << "% k " << k << ": rel H RMSE WJ-2 " << fmt(row[WJ2].relH)
                  << " WJH-2 " << fmt(row[WJH2].relH) << " APSS " << fmt(row[APSS_C].relH) << " (" << fmt(total.time(), 3)
                  << " s)\n";
      }
    }
  return g;
}

/// Check once that the Hermite rows are what the one-call pipeline computes:
/// wavejet_estimate_curvatures(order(2).use_neighbor_normals(true)) without a normal map.
static double one_call_pipeline_difference(const Options& o, const std::vector<std::unique_ptr<WB::Surface> >& surfaces)
{
  double pipeline_difference = 0.;
  Dataset d = make_dataset(*surfaces.back(), surfaces.size() - 1, o, o.quick ? 0.5 : 0.25);
  gather(d, 50);
  std::map<std::size_t, std::vector<WB::V3> > wj_normals;
  wj_normals[2] = wavejet_normals(d, 50, 2);
  const std::vector<Estimate> est = run(WJH2, d, wj_normals);
  std::vector<double> H(d.points.size(), 0.);
  std::vector<std::size_t> idx(d.points.size());
  for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  CGAL::wavejet_estimate_curvatures<Tag>(idx, 50, WP::order(2).use_neighbor_normals(true)
    .mean_curvature_map(CGAL::make_property_map(H)).point_map(CGAL::make_property_map(d.points)));
  for(std::size_t e = 0; e < d.eval.size(); ++e)
    pipeline_difference = std::max(pipeline_difference, std::abs(std::abs(H[d.eval[e]]) - std::abs(est[e].H)) /
                                                           (1e-12 + std::abs(est[e].H)));
  return pipeline_difference;
}

/// Speed of the Hermite fit: wavejet_estimate_curvatures, Sequential_tag, torus, noise 0.25%, k = 50 (a table).
static wavejets_bench::Csv_table hermite_speed_table(const Options& o)
{
  wavejets_bench::Csv_table speed({"K", "plain fit (s)", "Hermite fit, normals given (s)", "ratio", "one-call pipeline (s)"});
  WB::Torus T;
  Dataset d = make_dataset(T, 2, o, 0.25);
  std::vector<std::size_t> idx(d.points.size());
  for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::vector<Vector> normals(d.points.size());
  const std::vector<WB::V3> wn = wavejet_normals(d, 50, 2);
  for(std::size_t i = 0; i < wn.size(); ++i) normals[i] = Vector(wn[i].x(), wn[i].y(), wn[i].z());
  std::vector<double> H(d.points.size());
  for(std::size_t K = 2; K <= 4; K += 2)
  {
    auto time_it = [&](auto np) {
      double best = 1e300;
      for(int rep = 0; rep < 3; ++rep)
      {
        CGAL::Real_timer t;
        t.start();
        CGAL::wavejet_estimate_curvatures<CGAL::Sequential_tag>(idx, 50, np.mean_curvature_map(CGAL::make_property_map(H))
          .point_map(CGAL::make_property_map(d.points)).normal_map(CGAL::make_property_map(normals)));
        best = std::min(best, t.time());
      }
      return best;
    };
    const double plain = time_it(WP::order(K));
    const double hermite = time_it(WP::order(K).use_neighbor_normals(true));
    double pipeline = 1e300;
    for(int rep = 0; rep < 3; ++rep)
    {
      CGAL::Real_timer t;
      t.start();
      CGAL::wavejet_estimate_curvatures<CGAL::Sequential_tag>(idx, 50, WP::order(K).use_neighbor_normals(true)
        .mean_curvature_map(CGAL::make_property_map(H)).point_map(CGAL::make_property_map(d.points)));
      pipeline = std::min(pipeline, t.time());
    }
    speed.add_row({std::to_string(K), fmt(plain), fmt(hermite), fmt(hermite / plain, 3), fmt(pipeline)});
  }
  return speed;
}

/// Outliers: sphere, 5% outliers (moved by up to 2.5% of the diagonal), K = 4, radius 0.2, Tukey IRLS (3 passes).
struct Outlier_errors
{
  double plain = 0., robust = 0., hermite = 0.;
};

static Outlier_errors outlier_experiment(const Options& o)
{
  Outlier_errors r;
  WB::Sphere S;
  std::vector<WB::Sample> smp = S.sample(o.points, 77);
  WB::add_outliers(smp, 0.05, 0.025 * WB::bounding_box_diagonal(smp), 78);
  std::vector<Point> pts;
  for(const WB::Sample& x : smp) pts.emplace_back(x.p.x(), x.p.y(), x.p.z());
  std::vector<std::size_t> idx(pts.size());
  for(std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  auto error = [&](std::size_t robust, bool hermite) {
    std::vector<double> H(pts.size(), 0.);
    CGAL::wavejet_estimate_curvatures<Tag>(idx, 0, WP::order(4).robust_iterations(robust).use_neighbor_normals(hermite)
      .mean_curvature_map(CGAL::make_property_map(H)).neighbor_radius(0.2).point_map(CGAL::make_property_map(pts)));
    double e = 0.;
    std::size_t n = 0;
    for(std::size_t i = 0; i < pts.size(); ++i)
      if(smp[i].inlier) { e += (std::abs(H[i]) - 1.) * (std::abs(H[i]) - 1.); ++n; } // unit sphere: |H| = 1
    return std::sqrt(e / double(n));
  };
  r.plain = error(0, false);
  r.robust = error(3, false);
  r.hermite = error(3, true);
  return r;
}

// ---------------------------------------------------------------------------------------------
// Tables, as CSV: make_reports.py writes accuracy_ponca.md and accuracy_ponca.png from them

typedef std::vector<std::pair<std::string, wavejets_bench::Csv_table> > Tables;

static std::vector<std::string> header(const std::vector<int>& cols, const std::string& first)
{
  std::vector<std::string> h{first};
  for(int e : cols) h.push_back(estimator_name[e]);
  return h;
}

static std::string noise_and_k(double noise, unsigned int k)
{
  std::ostringstream s;
  s << noise << "%, " << k;
  return s.str();
}

/// Per surface: the relative RMSE of H of the main estimators, per noise and k ('*': some points failed).
static void add_relative_H_tables(Tables& tables, const std::vector<std::unique_ptr<WB::Surface> >& surfaces,
                                  const Grid& g)
{
  const std::vector<int> main_cols = {CGAL2, WJ2, WJ3, WJ4, WJH2, WJH3, WJH4, WJH2P, WJH2_W3, WJH2_W10, APSS_C, APSS_S,
                                      ASO_S};
  for(const auto& S : surfaces)
  {
    wavejets_bench::Csv_table table(header(main_cols, "noise, k"));
    for(double noise : g.noises)
      for(unsigned int k : g.ks)
      {
        const std::vector<Result>& row = row_of(g, S->name(), noise, k);
        std::vector<std::string> cells{noise_and_k(noise, k)};
        for(int e : main_cols)
          cells.push_back(row[e].present ? fmt(row[e].relH) + (row[e].failed ? "*" : "") : std::string("-"));
        table.add_row(cells);
      }
    tables.emplace_back("accuracy_ponca.h_rmse_" + S->name(), table);
  }
}

/// Per surface: every error of every estimator at one noise level and k (0.25% and 50; --quick: 0.5% and 20).
static void add_all_errors(Tables& tables, const Options& o, const std::vector<std::unique_ptr<WB::Surface> >& surfaces,
                           const Grid& g)
{
  const double ref_noise = o.quick ? 0.5 : 0.25;
  const unsigned int ref_k = o.quick ? 20 : 50;
  for(const auto& S : surfaces)
  {
    wavejets_bench::Csv_table table({"estimator", "rel. H", "H", "K_G", "k1", "k2", "normal (deg)", "failed"});
    const std::vector<Result>& row = row_of(g, S->name(), ref_noise, ref_k);
    for(int e = 0; e < NUM_ESTIMATORS; ++e)
      if(row[e].present)
        table.add_row({estimator_name[e], fmt(row[e].relH), fmt(row[e].H), fmt(row[e].K), fmt(row[e].k1), fmt(row[e].k2),
                       fmt(row[e].angle), std::to_string(row[e].failed)});
    tables.emplace_back("accuracy_ponca.all_errors_" + S->name(), table);
  }
}

/// Compact against constant weights: geometric mean over the surfaces of the ratio of the relative H RMSE.
static wavejets_bench::Csv_table weights_table(const std::vector<std::unique_ptr<WB::Surface> >& surfaces, const Grid& g)
{
  wavejets_bench::Csv_table table({"noise, k", "WJ-2", "WJ-4", "WJH-2", "WJH-4", "APSS"});
  for(double noise : g.noises)
    for(unsigned int k : g.ks)
    {
      std::vector<std::string> cells{noise_and_k(noise, k)};
      const int pairs[5][2] = {{WJ2C, WJ2}, {WJ4C, WJ4}, {WJH2C, WJH2}, {WJH4C, WJH4}, {APSS_S, APSS_C}};
      for(const auto& p : pairs)
      {
        double log_sum = 0.;
        int n = 0;
        for(const auto& S : surfaces)
        {
          const std::vector<Result>& row = row_of(g, S->name(), noise, k);
          if(!row[p[0]].present || !row[p[1]].present || !(row[p[1]].relH > 0)) continue;
          log_sum += std::log(row[p[0]].relH / row[p[1]].relH);
          ++n;
        }
        cells.push_back(n ? fmt(std::exp(log_sum / n)) : std::string("-"));
      }
      table.add_row(cells);
    }
  return table;
}

/// Scale of the estimates (shrinkage toward 0) and the errors once it is undone: WJH-2-w10 against APSS.
static wavejets_bench::Csv_table shrinkage_table(const Grid& g)
{
  wavejets_bench::Csv_table table({"surface, noise, k", "APSS scale", "WJH-2-w10 scale", "rel. H RMSE WJH-2-w10 / APSS",
             "rescaled WJH-2-w10 / APSS"});
  for(const std::string s : {"torus", "ellipsoid", "sphere"})
    for(double n : {0.25, 0.5})
      for(unsigned int k : g.ks)
      {
        const std::vector<Result>& row = row_of(g, s, n, k);
        if(!row[APSS_C].present) continue;
        table.add_row({s + ", " + noise_and_k(n, k), fmt(row[APSS_C].scale), fmt(row[WJH2_W10].scale),
                       fmt(row[WJH2_W10].relH / row[APSS_C].relH),
                       fmt(row[WJH2_W10].relH_rescaled / row[APSS_C].relH_rescaled)});
      }
  return table;
}

/// The targets, checked on the tables above: noisy (WJH-2-w10 against APSS), clean (Hermite against plain, APSS
/// against Hermite), k1 and k2 (CGAL's best jet against WJH-2).
static void add_targets(Tables& tables, const std::vector<std::unique_ptr<WB::Surface> >& surfaces, const Grid& g)
{
  auto rel = [&](const std::string& s, double n, unsigned int k, int e) { return row_of(g, s, n, k)[e].relH; };
  std::vector<std::string> noisy_header{"surface, noise"};
  for(unsigned int k : g.ks) noisy_header.push_back("k = " + std::to_string(k));
  noisy_header.push_back("target");
  wavejets_bench::Csv_table noisy(noisy_header);
  for(const std::string s : {"torus", "ellipsoid", "sphere"})
    for(double n : {0.25, 0.5})
    {
      std::ostringstream label;
      label << s << ", " << n << "%";
      std::vector<std::string> cells{label.str()};
      bool ok = true;
      const double limit = s == "sphere" ? 1.1 : 1.;
      for(unsigned int k : g.ks)
      {
        const double r = rel(s, n, k, WJH2_W10) / rel(s, n, k, APSS_C);
        ok = ok && r < limit;
        int best = WJ2;
        for(int e = WJ2; e <= WJH4C; ++e) if(rel(s, n, k, e) < rel(s, n, k, best)) best = e;
        cells.push_back(fmt(r) + " (best " + estimator_name[best] + ": " +
                        fmt(rel(s, n, k, best) / rel(s, n, k, APSS_C)) + ")");
      }
      cells.push_back(std::string(s == "sphere" ? "< 1.1" : "< 1") + ": " + (ok ? "holds" : "fails"));
      noisy.add_row(cells);
    }
  tables.emplace_back("accuracy_ponca.targets", noisy);
  wavejets_bench::Csv_table clean({"surface", "k", "WJH-2/WJ-2", "WJH-3/WJ-3", "WJH-4/WJ-4", "APSS/WJH-4"});
  for(const std::string s : {"torus", "ellipsoid", "sphere", "goursat", "cylinder"})
    for(unsigned int k : g.ks)
      clean.add_row({s, std::to_string(k), fmt(rel(s, 0., k, WJH2) / rel(s, 0., k, WJ2)),
                     fmt(rel(s, 0., k, WJH3) / rel(s, 0., k, WJ3)), fmt(rel(s, 0., k, WJH4) / rel(s, 0., k, WJ4)),
                     fmt(rel(s, 0., k, APSS_C) / rel(s, 0., k, WJH4))});
  tables.emplace_back("accuracy_ponca.targets_2", clean);
  wavejets_bench::Csv_table principal({"surface", "k1", "k2"});
  for(const auto& S : surfaces)
  {
    const std::vector<Result>& row = row_of(g, S->name(), 0.25, 50);
    const double c1 = std::min({row[CGAL2].k1, row[CGAL3].k1, row[CGAL4].k1});
    const double c2 = std::min({row[CGAL2].k2, row[CGAL3].k2, row[CGAL4].k2});
    principal.add_row({S->name(), fmt(c1 / row[WJH2].k1), fmt(c2 / row[WJH2].k2)});
  }
  tables.emplace_back("accuracy_ponca.targets_3", principal);
}

/// The relative H RMSE of every estimator against k, each surface and noise level (-1: not run); the plot's data.
static wavejets_bench::Csv_table relative_H_grid(const std::vector<std::unique_ptr<WB::Surface> >& surfaces, const Grid& g)
{
  std::vector<std::string> h{"surface", "noise", "k"};
  for(int e = 0; e < NUM_ESTIMATORS; ++e) h.push_back(estimator_name[e]);
  wavejets_bench::Csv_table table(h);
  auto number = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  for(const auto& S : surfaces)
    for(double noise : g.noises)
      for(unsigned int k : g.ks)
      {
        std::vector<std::string> cells{S->name(), number(noise), std::to_string(k)};
        for(const Result& r : row_of(g, S->name(), noise, k)) cells.push_back(number(r.present ? r.relH : -1.));
        table.add_row(cells);
      }
  return table;
}

int main(int argc, char** argv)
{
  Options o;
  if(!parse_command_line(argc, argv, o)) return 2;
  if(!have_ponca)
    std::cerr << "Ponca not found at configure time (see benchmark/Wavejets/CMakeLists.txt): the APSS and ASO "
                 "columns are skipped.\n";

  const std::vector<std::unique_ptr<WB::Surface> > surfaces = benchmark_surfaces(o.quick);
  CGAL::Real_timer total;
  total.start();
  const Grid g = run_grid(o, surfaces, total);
  total.stop();
  const double pipeline_difference = one_call_pipeline_difference(o, surfaces);
  const wavejets_bench::Csv_table speed = hermite_speed_table(o);
  const Outlier_errors outl = outlier_experiment(o);

  Tables tables;
  add_relative_H_tables(tables, surfaces, g);
  add_all_errors(tables, o, surfaces, g);
  tables.emplace_back("accuracy_ponca.weights", weights_table(surfaces, g));
  wavejets_bench::Csv_table outliers({"estimator", "H RMSE"});
  outliers.add_row({"WJ-4", fmt(outl.plain)});
  outliers.add_row({"WJ-4, robust_iterations(3)", fmt(outl.robust)});
  outliers.add_row({"WJH-4 (one-call Hermite pipeline), robust_iterations(3)", fmt(outl.hermite)});
  tables.emplace_back("accuracy_ponca.outliers", outliers);
  tables.emplace_back("accuracy_ponca.hermite_speed", speed);
  if(!o.quick && have_ponca)
  {
    tables.emplace_back("accuracy_ponca.shrinkage", shrinkage_table(g));
    add_targets(tables, surfaces, g);
  }
  tables.emplace_back("accuracy_ponca.h_rmse_grid", relative_H_grid(surfaces, g));
  wavejets_bench::Csv_table context = wavejets_bench::context_table();
  context.add_row({"machine", WB::machine_description(false)});
  context.add_row({"run time (s)", fmt(total.time(), 3)});
  context.add_row({"points", std::to_string(o.points)});
  context.add_row({"evaluation points", std::to_string(o.eval)});
  context.add_row({"one-call pipeline difference", fmt(pipeline_difference, 2)});
  if(!have_ponca) context.add_row({"Ponca", "not found when this program was configured: its columns are missing"});
  tables.emplace_back("accuracy_ponca.context", context);
  for(const auto& t : tables)
  {
    std::cout << "\n" << t.first << "\n" << t.second.str();
    t.second.write(o.csv_dir, t.first);
  }
  return 0;
}
