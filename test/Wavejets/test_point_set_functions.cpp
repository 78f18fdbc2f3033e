// Tests of the four point-set functions of the Wavejets package against analytic truth
// (doc/Wavejets/Mathematics.txt §§5-8), against CGAL's jets, and for their CGAL-style contract
// (concurrency, input types, interruption, unfittable points, named parameters).
//
// Every check is an explicit `if` that accumulates failures (never `assert`); each group prints
// one line with its measured numbers. Run from test/Wavejets (reads data/kitten.xyz and
// data/fandisk.off); the argument names a case or a group of cases (--list).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/Surface_mesh/IO.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <sstream>
#include <CGAL/point_generators_3.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/property_map.h>
#include <CGAL/Random.h>
#include <CGAL/tags.h>

#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_estimate_scales.h>
#include <CGAL/Wavejet_fitting.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "analytic_surfaces.h"
#include "wavejets_test_data.h"
#include "wavejets_test_support.h"
#include "wavejets_test_types.h"

using namespace wavejets_test;
using namespace wavejets_test::types;
namespace WJP = CGAL::Wavejets::parameters;

static const double PI = 3.14159265358979323846;

static std::string fmt(double x) { return significant_digits(x, 6); }

// Angles by atan2(|a x b|, a.b): acos of a dot product cannot resolve angles below ~1.5e-8.
static double angle(const Vector& a, const Vector& b) // oriented angle in [0, pi]
{
  return std::atan2(std::sqrt(CGAL::cross_product(a, b).squared_length()), a * b);
}
static double unoriented_angle(const Vector& a, const Vector& b) // in [0, pi/2]
{
  return std::atan2(std::sqrt(CGAL::cross_product(a, b).squared_length()), std::abs(a * b));
}
// Fibonacci sampling of the unit sphere: point i of N (z decreasing from the north pole).
static Vector fibonacci(std::size_t i, std::size_t N)
{
  const double z = 1. - (2. * double(i) + 1.) / double(N);
  const double r = std::sqrt((std::max)(0., 1. - z * z));
  const double phi = double(i) * PI * (3. - std::sqrt(5.));
  return Vector(r * std::cos(phi), r * std::sin(phi), z);
}

// k nearest neighbors of every point, excluding itself, ties by index: the package's definition
// (neighbor_query.h). Brute force, O(N^2): fine for the few thousand points it is used on.
static std::vector<std::vector<std::size_t> > brute_knn(const PV_range& pts, std::size_t k)
{
  const std::size_t N = pts.size();
  std::vector<std::vector<std::size_t> > out(N);
  std::vector<std::pair<double, std::size_t> > d(N);
  for(std::size_t i = 0; i < N; ++i)
  {
    const Point& p = pts[i].first;
    d.clear();
    for(std::size_t j = 0; j < N; ++j)
    {
      if(j == i) continue;
      const Point& q = pts[j].first;
      const double dx = q.x() - p.x(), dy = q.y() - p.y(), dz = q.z() - p.z();
      d.emplace_back(dx * dx + dy * dy + dz * dz, j);
    }
    std::partial_sort(d.begin(), d.begin() + k, d.end());
    for(std::size_t j = 0; j < k; ++j) out[i].push_back(d[j].second);
  }
  return out;
}
static double knn_radius(const PV_range& pts, std::size_t i, const std::vector<std::size_t>& nb)
{
  double r2 = 0.;
  for(std::size_t j : nb) r2 = (std::max)(r2, CGAL::squared_distance(pts[i].first, pts[j].first));
  return std::sqrt(r2);
}

// Largest distance from a point to its k-th nearest neighbor, over every stride-th point.
static double max_knn_radius(const PV_range& pts, std::size_t k, std::size_t stride)
{
  double rho = 0.;
  std::vector<double> d;
  for(std::size_t i = 0; i < pts.size(); i += stride)
  {
    d.clear();
    for(std::size_t j = 0; j < pts.size(); ++j)
      if(j != i) d.push_back(CGAL::squared_distance(pts[i].first, pts[j].first));
    std::nth_element(d.begin(), d.begin() + (k - 1), d.end());
    rho = (std::max)(rho, std::sqrt(d[k - 1]));
  }
  return rho;
}

// ---------------------------------------------------------------------------------------------
// 1. Sphere growth with radius neighborhoods: analytic displacement.
// ---------------------------------------------------------------------------------------------
static void test_sphere_growth()
{
  // Fibonacci sampling of the unit sphere with N = 300000 (a ball of radius 0.03 holds
  // N * pi 0.03^2 / (4 pi) = 67 points >= 1.1 * 45 for K = 8), restricted to the polar cap of
  // angle 0.15: its first M points. Only the points at angle < 0.15 - 0.035 from the pole are
  // checked: their whole ball (chord 0.03 < angle 0.035) lies in the cap, so their neighborhoods
  // are those of the full sphere; the other points only serve as neighbors.
  const std::size_t N = 300000;
  const double cap = 0.15, R = 1., Rf = 0.03, s = 0.03, gain = 100.;
  const std::size_t M = std::size_t(double(N) * (1. - std::cos(cap)) / 2.) + 1;
  PV_range pts;
  for(std::size_t i = 0; i < M; ++i)
  {
    const Vector n = fibonacci(i, N);
    pts.emplace_back(CGAL::ORIGIN + R * n, n); // outward normals
  }
  const PV_range input = pts;

  // Analytic displacement (spec §6): tangent-frame height of the sphere z(r) = -(R - sqrt(R^2 - r^2)),
  // a0(s) = int_0^s z(r) r dr = -[R s^2/2 - (R^3 - (R^2 - s^2)^{3/2})/3], f00 = 0 (p is on the
  // sphere), d = -2 pi (gain - 1) a0(s) / Rf^2. (1 - (1-x)^{3/2}) = -expm1(1.5 log1p(-x)) avoids
  // the cancellation.
  const double x = s * s / (R * R);
  const double a0 = -(R * s * s / 2. + R * R * R * std::expm1(1.5 * std::log1p(-x)) / 3.);
  const double d_exact = -2. * PI * (gain - 1.) * a0 / (Rf * Rf);

  Point_map pm;
  Normal_map nm;
  const double dmax = std::numeric_limits<double>::infinity();
  // The chain of the issue (package parameters first, then CGAL's), plus the normal map.
  const CGAL::Wavejets::Processing_report rep = CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(
    pts, 0, gain,
    WJP::order(8).maximum_displacement(dmax).evaluation_radius(s).neighbor_radius(Rf).point_map(pm).normal_map(nm));

  // Truncation error: the sphere's height series -(r^2/2R + r^4/8R^3 + r^6/16R^5 + 5r^8/128R^7 +
  // 7r^10/256R^9 + ...) is cut after r^8; the first neglected term is 7/256 * 0.03^10 = 1.6e-17 in
  // height, against |a0| / s^2 = 1.1e-4: ~1e-13 relative. Floating point: coordinates carry 1e-16
  // of rounding (1e-16/Rf = 4e-15 in rescaled units), amplified by the conditioning of the K = 8
  // least-squares problem (a few 1e3 for K = 8 on ~67 points, estimated): a0 and d to ~1e-10
  // relative. Tolerance 1e-7 relative on the mean displacement and on the spread (max - min of the
  // new radius), i.e. >= 1000x that estimate; the motion must also be radial (lateral < 1e-7 d).
  double sum = 0., rmin = 1e300, rmax = -1e300, max_lateral = 0.;
  std::size_t n = 0;
  bool all_moved = true;
  for(std::size_t i = 0; i < M; ++i)
  {
    const Vector p0 = input[i].first - CGAL::ORIGIN;
    if(std::acos((std::min)(1., p0.z())) >= cap - 0.035) continue;
    const Vector p1 = pts[i].first - CGAL::ORIGIN;
    const double r = std::sqrt(p1.squared_length());
    sum += r;
    rmin = (std::min)(rmin, r);
    rmax = (std::max)(rmax, r);
    max_lateral = (std::max)(max_lateral, std::sqrt(CGAL::cross_product(p0, p1).squared_length()) / r);
    all_moved = all_moved && (p1 != p0);
    ++n;
  }
  const double mean_d = sum / double(n) - R;
  const double rel = std::abs(mean_d - d_exact) / d_exact;
  const double spread = (rmax - rmin) / d_exact;
  const bool ok = n > 500 && all_moved && rel < 1e-7 && spread < 1e-7 && max_lateral < 1e-7 * d_exact &&
                  rep.number_of_unfitted_points == 0 && rep.number_of_clamped_points == 0;
  report("1. sphere growth (K=8, Rf=s=0.03, gain 100, no clamp)", ok,
         std::to_string(n) + " interior points of " + std::to_string(M) + "; analytic d = " + fmt(d_exact) +
           ", mean d = " + fmt(mean_d) + ", rel err = " + fmt(rel) + ", spread/d = " + fmt(spread) +
           ", lateral = " + fmt(max_lateral));

  // Same cap, normals. (i) The chain of issue 3 verbatim,
  //   CGAL::Wavejets::parameters::order(6).neighbor_radius(0.03).point_map(pm).normal_map(nm),
  // with wavejet_estimate_normals: unoriented normals (the input normals are set to 0 first, so
  // every checked normal must have been written). (ii) The same chain with
  // orient_with_input_normals(true) inserted, input normals +z: the same normals, oriented to +z.
  // The Wavejet normal of a sphere is radial; with the polynomial truncation at r^8 (K = 6) the
  // tilt error is ~ r^7 / R^6 ~ 0.03^7 ~ 2e-11 rad: bound 1e-9. (ii) must be (i) up to the sign
  // and rounding (1e-14): orientation only flips the frame (same order, radius, neighborhoods).
  PV_range nv = input;
  for(PV& q : nv) q.second = Vector(0, 0, 0);
  const CGAL::Wavejets::Processing_report rv = CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(
    nv, 0, CGAL::Wavejets::parameters::order(6).neighbor_radius(0.03).point_map(pm).normal_map(nm));
  PV_range ns = input;
  for(PV& q : ns) q.second = Vector(0, 0, 1); // only oriented on the cap's side
  CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(
    ns, 0, WJP::order(6).orient_with_input_normals(true).neighbor_radius(0.03).point_map(pm).normal_map(nm));
  double max_err = 0., max_err_v = 0.;
  bool same_up_to_sign = true, oriented = true;
  for(std::size_t i = 0; i < M; ++i)
  {
    const Vector p0 = input[i].first - CGAL::ORIGIN;
    if(std::acos((std::min)(1., p0.z())) >= cap - 0.035) continue;
    max_err = (std::max)(max_err, angle(ns[i].second, p0));
    max_err_v = (std::max)(max_err_v, unoriented_angle(nv[i].second, p0)); // 0 normal: atan2(0, 0) = 0,
    if(nv[i].second.squared_length() < 0.5) max_err_v = 1e300;            // so check it was written
    same_up_to_sign = same_up_to_sign && (std::min)((nv[i].second - ns[i].second).squared_length(),
                                                    (nv[i].second + ns[i].second).squared_length()) <= 1e-28;
    oriented = oriented && ns[i].second.z() > 0;
  }
  report("1b. sphere normals, issue 3 chain verbatim: order(6).neighbor_radius(0.03).point_map(pm).normal_map(nm)",
         max_err_v < 1e-9 && rv.number_of_fitted_points > 0 && rv.number_of_points == M,
         "max unoriented angle to radial = " + fmt(max_err_v) + " rad, " + std::to_string(rv.number_of_fitted_points) +
           " of " + std::to_string(M) + " points fitted");
  report("1c. sphere normals, order(6).orient_with_input_normals(true).neighbor_radius(0.03).point_map.normal_map",
         max_err < 1e-9 && same_up_to_sign && oriented,
         "max angle to radial = " + fmt(max_err) + " rad; equal to 1b up to the sign (1e-14): " +
           (same_up_to_sign ? "yes" : "no") + ", all oriented to +z: " + (oriented ? "yes" : "no"));
}

// ---------------------------------------------------------------------------------------------
// 2. Gain semantics of the two filters.
// ---------------------------------------------------------------------------------------------
static void test_position_gains()
{
  Point_map pm;
  Normal_map nm;
  // 2a. gain 1 on a noisy unit sphere: projection only (denoising).
  {
    const std::size_t N = 20000;
    const double sigma = 0.002;
    Gauss g(12345);
    PV_range pts;
    for(std::size_t i = 0; i < N; ++i)
    {
      const Vector n = fibonacci(i, N);
      pts.emplace_back(CGAL::ORIGIN + (1. + sigma * g()) * n, n);
    }
    auto stats = [](const PV_range& r, double& mean, double& sd) {
      double s = 0., s2 = 0.;
      for(const PV& q : r) { const double l = std::sqrt((q.first - CGAL::ORIGIN).squared_length()); s += l; s2 += l * l; }
      mean = s / double(r.size());
      sd = std::sqrt((std::max)(0., s2 / double(r.size()) - mean * mean));
    };
    double m0, sd0, m1, sd1;
    stats(pts, m0, sd0);
    CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(pts, 40, 1.,
      WJP::order(2).point_map(pm).normal_map(nm));
    stats(pts, m1, sd1);
    // Projection onto a quadratic fitted to 41 points: the new height is the fitted value at the
    // origin, whose noise variance is sigma^2 times the leverage of the center (about B/L = 6/41,
    // more near the center: < 0.5), so the std must drop at least by sqrt(0.5) -> ratio < 0.71.
    // Mean: unbiased up to the sphere's quartic term r^4/8 (r <= 0.09: 8e-6) and the sampling
    // error of the mean sigma/sqrt(N) = 1.4e-5; bound sigma/20 = 1e-4.
    const bool ok = sd1 < 0.71 * sd0 && std::abs(m1 - 1.) < sigma / 20;
    report("2a. positions gain 1 denoises (noisy sphere, sigma 0.2%, k=40, K=2)", ok,
           "radius std " + fmt(sd0) + " -> " + fmt(sd1) + " (ratio " + fmt(sd1 / sd0) + "), mean " + fmt(m0) +
             " -> " + fmt(m1));
  }
  // 2b. sinusoid z = A sin(w x) on a grid: amplitude after the filter, for gains 0, 1, 2, -10.
  {
    const double A = 0.01, w = 4. * PI, h = 0.01, Rf = 0.06, s = 0.06;
    PV_range grid;
    for(int i = 0; i <= 100; ++i)
      for(int j = 0; j <= 100; ++j)
      {
        const double x = i * h, y = j * h;
        grid.emplace_back(Point(x, y, A * std::sin(w * x)), Vector(-A * w * std::cos(w * x), 0, 1));
      }
    // Predicted ratio (small slope A w = 0.126, flat frame): the theta-average of the height around
    // x0 is A sin(w x0) J0(w r), so a0(s) = A sin(w x0) [s J1(w s)/w - s^2/2] and the displacement
    // -2 pi (g-1) a0/Rf^2 scales the detail by 1 + (g-1) kappa, kappa = -2 pi [s J1(ws)/w - s^2/2]/Rf^2.
    // Error of the prediction: the tangent frame tilts with the slope, O((A w)^2) = 1.6%, plus
    // O((A w)^2/4) from the points' lateral motion and 0.1% from the K = 4 truncation of J0:
    // tolerance 5% of the predicted change (g-1) kappa.
    const double ws = w * s;
    double J1 = 0., term = ws / 2.; // series of J1
    for(int m = 0; m < 30; ++m) { J1 += term; term *= -(ws * ws / 4.) / double((m + 1) * (m + 2)); }
    const double kappa = -2. * PI * (s * J1 / w - s * s / 2.) / (Rf * Rf);
    std::string numbers = "kappa = " + fmt(kappa);
    bool ok = true;
    const double gains[] = {0., 1., 2., -10.};
    for(double gain : gains)
    {
      PV_range pts = grid;
      CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(pts, 0, gain,
        WJP::order(4).maximum_displacement(std::numeric_limits<double>::infinity()).neighbor_radius(Rf).point_map(pm));
      // amplitude: least-squares coefficient of z' on sin(w x') over the points away from the border
      double num = 0., den = 0.;
      for(const PV& q : pts)
      {
        const Point& p = q.first;
        if(p.x() < 0.1 || p.x() > 0.9 || p.y() < 0.1 || p.y() > 0.9) continue;
        const double b = std::sin(w * p.x());
        num += p.z() * b;
        den += b * b;
      }
      const double ratio = num / den / A, predicted = 1. + (gain - 1.) * kappa;
      numbers += "; gain " + fmt(gain) + ": amplitude ratio " + fmt(ratio) + " (predicted " + fmt(predicted) + ")";
      ok = ok && std::abs(ratio - predicted) <= 0.05 * std::abs(gain - 1.) * kappa + 1e-3;
      if(gain == 0.) ok = ok && ratio < 1. && ratio > 0.;   // flattened
      if(gain == 2.) ok = ok && ratio > 1.;                 // amplified
      if(gain == -10.) ok = ok && ratio < 0.;               // inverted
    }
    // (gain 1: the 1e-3 absolute term is the K = 4 truncation of the projection, ~ (w s)^6/2304 = 2e-4.)
    report("2b. positions gain 0 flattens, 2 amplifies, -10 inverts (sinusoid, Rf=s=0.06, K=4)", ok, numbers);
  }
}

static void test_normal_gains()
{
  Point_map pm;
  Normal_map nm;
  const double A = 0.01, w = 4. * PI, h = 0.01, Rf = 0.06;
  PV_range grid;
  for(int i = 0; i <= 100; ++i)
    for(int j = 0; j <= 100; ++j)
    {
      const double x = i * h, y = j * h;
      grid.emplace_back(Point(x, y, A * std::sin(w * x)), Vector(-A * w * std::cos(w * x), 0, 1));
    }
  // 2c. gain 1 == wavejet_estimate_normals(orient_with_input_normals(true)) at the same order and
  // the same tangent-plane search (tangent_plane_order(0): full-order re-fits, the filter's default;
  // wavejet_estimate_normals searches at order 2 by default): both write normalize(n - f_x u - f_y v)
  // of the final fit; (gain-1) a = 0 exactly.
  {
    PV_range a = grid, b = grid;
    CGAL::wavejet_enhance_normals<Seq>(a, 0, 1., WJP::order(4).neighbor_radius(Rf).point_map(pm).normal_map(nm));
    CGAL::wavejet_estimate_normals<Seq>(b, 0,
      WJP::order(4).tangent_plane_order(0).orient_with_input_normals(true).neighbor_radius(Rf).point_map(pm)
        .normal_map(nm));
    double maxd = 0.;
    for(std::size_t i = 0; i < a.size(); ++i)
      maxd = (std::max)(maxd, std::sqrt((a[i].second - b[i].second).squared_length()));
    report("2c. normals gain 1 == wavejet_estimate_normals (oriented, same tangent-plane search)",
           maxd <= 1e-15, "max |n_a - n_b| = " + fmt(maxd));
  }
  // 2d. gains 0, 1, 2 on the sinusoid: mean angle to the flat-plane normal +z (interior points).
  {
    auto mean_tilt = [&](const PV_range& r) {
      double s = 0.;
      std::size_t n = 0;
      for(const PV& q : r)
      {
        const Point& p = q.first;
        if(p.x() < 0.1 || p.x() > 0.9 || p.y() < 0.1 || p.y() > 0.9) continue;
        s += angle(q.second, Vector(0, 0, 1));
        ++n;
      }
      return s / double(n);
    };
    const double t_exact = mean_tilt(grid);
    double t[3];
    for(int g = 0; g <= 2; ++g)
    {
      PV_range r = grid;
      CGAL::wavejet_enhance_normals<CGAL::Parallel_if_available_tag>(r, 0, double(g),
        WJP::order(4).neighbor_radius(Rf).point_map(pm).normal_map(nm));
      t[g] = mean_tilt(r);
    }
    // gain 1 is the fitted surface's own normal: a noise-free sinusoid is reproduced to the K = 4
    // truncation, (w Rf)^4/... of the slope: 1% bound on the mean tilt.
    const bool ok = t[0] < t[1] && t[1] < t[2] && std::abs(t[1] - t_exact) < 0.01 * t_exact;
    report("2d. normals gain 0 blurs, 2 exaggerates (sinusoid)", ok,
           "mean tilt (rad): exact " + fmt(t_exact) + ", gain 0: " + fmt(t[0]) + ", gain 1: " + fmt(t[1]) +
             ", gain 2: " + fmt(t[2]));
  }
  // 2e. complex gain twists: z = c (x^3 + x y^2) = c r^3 cos(theta) at the origin, whose only
  // Wavejet coefficients are f_{3,+-1} = c/2 in the frame (x, y, z) (tangent plane z = 0). With a
  // radius neighborhood Rf and evaluation radius s:
  //   a_{-1}(s) = f_{3,-1} s^5/5 = c s^5/10,  f'_{1,-1} = 0 - pi (g-1) a_{-1}(s)/Rf^3,
  //   f'_x + i f'_y = 2 f'_{1,-1} = -pi (g-1) c s^5 / (5 Rf^3),
  //   n' = normalize(-f'_x, -f'_y, 1) = normalize(t Re(g-1), t Im(g-1), 1), t = pi c s^5/(5 Rf^3)
  // (frame-independent: a rotation of u by mu multiplies f_{1,-1} by e^{-i mu} and rotates u, v by mu).
  // The tilt direction is arg(g-1). The surface is a cubic, so a K = 4 fit in the seeded frame
  // (exact normal +z) reproduces it to fp: bound 1e-9 rad.
  {
    const double c = 5., h2 = 0.01, R2 = 0.1, s2 = 0.08;
    PV_range pts;
    std::size_t origin = 0;
    for(int i = -20; i <= 20; ++i)
      for(int j = -20; j <= 20; ++j)
      {
        const double x = i * h2, y = j * h2;
        if(i == 0 && j == 0) origin = pts.size();
        pts.emplace_back(Point(x, y, c * (x * x * x + x * y * y)), Vector(-c * (3 * x * x + y * y), -c * 2 * x * y, 1));
      }
    const double t = PI * c * std::pow(s2, 5) / (5. * std::pow(R2, 3));
    const std::complex<double> gains[] = {{1., 2.}, {1. + 2. * std::cos(2 * PI / 3), 2. * std::sin(2 * PI / 3)},
                                          {-1., 0.}, {1., -3.}, {3., 0.}, {0.5, 1.5}};
    double max_err = 0.;
    std::string numbers;
    for(const std::complex<double>& g : gains)
    {
      PV_range r = pts;
      CGAL::wavejet_enhance_normals<Seq>(r, 0, g,
        WJP::order(4).seed_with_input_normals(true).evaluation_radius(s2).neighbor_radius(R2).point_map(pm).normal_map(nm));
      const std::complex<double> gm1 = g - 1.;
      const Vector expected(t * gm1.real(), t * gm1.imag(), 1.);
      const Vector& got = r[origin].second;
      max_err = (std::max)(max_err, angle(got, expected));
      numbers += "arg(g-1) " + fmt(std::arg(gm1)) + " tilt dir " + fmt(std::atan2(got.y(), got.x())) + "; ";
    }
    report("2e. complex gain twists (z = 5(x^3 + x y^2), Rf=0.1, s=0.08)", max_err < 1e-9,
           numbers + "max angle to formula = " + fmt(max_err) + " rad");
  }
}

// ---------------------------------------------------------------------------------------------
// 3. Normals against CGAL's jet_estimate_normals.
// ---------------------------------------------------------------------------------------------
static double mean_unoriented_deviation(const PV_range& a, const PV_range& b)
{
  double s = 0.;
  for(std::size_t i = 0; i < a.size(); ++i) s += unoriented_angle(a[i].second, b[i].second);
  return s / double(a.size());
}

static void compare_with_jets(const std::string& name, const PV_range& input, double bound_deg)
{
  Point_map pm;
  Normal_map nm;
  PV_range w = input, j = input;
  CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(w, 18, WJP::order(2).point_map(pm).normal_map(nm));
  CGAL::jet_estimate_normals<CGAL::Parallel_if_available_tag>(
    j, 18, CGAL::parameters::point_map(pm).normal_map(nm).degree_fitting(2));
  const double dev = mean_unoriented_deviation(w, j) * 180. / PI;
  report("3. normals vs jet_estimate_normals on " + name + " (k=18, order 2)", dev < bound_deg,
         "mean unoriented deviation = " + fmt(dev) + " deg (bound " + fmt(bound_deg) + ")");
}

static void accuracy_vs_jets(const std::string& name, const PV_range& truth, unsigned int k, unsigned int degree,
                             double factor)
{
  Point_map pm;
  Normal_map nm;
  PV_range w = truth, j = truth;
  CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(w, k, WJP::order(degree).point_map(pm).normal_map(nm));
  CGAL::jet_estimate_normals<CGAL::Parallel_if_available_tag>(
    j, k, CGAL::parameters::point_map(pm).normal_map(nm).degree_fitting(degree));
  const double ew = mean_unoriented_deviation(w, truth), ej = mean_unoriented_deviation(j, truth);
  report("3. normal accuracy on " + name + " (k=" + std::to_string(k) + ", order " + std::to_string(degree) + ")",
         ew <= ej * factor,
         "mean angle error: Wavejet " + fmt(ew) + " rad, CGAL jet " + fmt(ej) + " rad (ratio " + fmt(ew / ej) +
           ", bound " + fmt(factor) + ")");
}

static PV_range make_sphere(std::size_t N, double R)
{
  PV_range pts;
  for(std::size_t i = 0; i < N; ++i)
  {
    const Vector n = fibonacci(i, N);
    pts.emplace_back(CGAL::ORIGIN + R * n, n);
  }
  return pts;
}
// Torus (R, r) on a golden-ratio lattice in (u, v); outward normals, and (if `t`) its exact
// curvatures and principal directions (Parametric_torus, support/analytic_surfaces.h):
// k1 = -cos v/(R + r cos v) along the parallel (d/du), k2 = -1/r along the meridian (d/dv); with
// R > 2r, k1 >= -1/(R + r) > -1/r = k2 everywhere (no umbilic: gap k1 - k2 >= 1/r - 1/(R + r)).
struct Torus_truth
{
  std::vector<double> H, KG, k1, k2;
  std::vector<Vector> d1, d2;
};
static PV_range make_torus(std::size_t N, double R, double r, Torus_truth* t = nullptr)
{
  const wavejets_bench::Parametric_torus torus{R, r};
  PV_range pts;
  const double phi = (std::sqrt(5.) - 1.) / 2.;
  for(std::size_t i = 0; i < N; ++i)
  {
    const double u = 2. * PI * (double(i) + 0.5) / double(N);
    const double v = 2. * PI * std::fmod(double(i) * phi, 1.);
    const Eigen::Vector3d p = torus.point(u, v), n = torus.outward_normal(u, v);
    pts.emplace_back(Point(p.x(), p.y(), p.z()), Vector(n.x(), n.y(), n.z()));
    if(!t) continue;
    t->H.push_back(torus.mean_curvature(v));
    t->KG.push_back(torus.gaussian_curvature(v));
    t->k1.push_back(torus.parallel_curvature(v));
    t->k2.push_back(torus.meridian_curvature());
    const Eigen::Vector3d d1 = torus.parallel_direction(u), d2 = torus.meridian_direction(u, v);
    t->d1.push_back(Vector(d1.x(), d1.y(), d1.z()));
    t->d2.push_back(Vector(d2.x(), d2.y(), d2.z()));
  }
  return pts;
}

static void test_normals_vs_jets(const PV_range& kitten, const PV_range& fandisk)
{
  // With equal neighborhoods and degree, the two estimators differ only by the Wavejet's
  // tangent-plane re-fit, which tilts the normal by the change of the fitted gradient: on a
  // scan with 19-point neighborhoods that is a fraction of a degree on average; sharp edges of
  // fandisk add a few larger deviations. Bound: 1 degree (kitten), 2 degrees (fandisk).
  compare_with_jets("kitten.xyz", kitten, 1.);
  compare_with_jets("fandisk (20k samples)", fandisk, 2.);
  // Accuracy against the analytic normals, same k and degree ("at least as accurate", issue 3).
  // The Wavejet fits the same polynomial as the jet in the PCA frame, then re-fits in the
  // corrected tangent plane and takes the normal there. Tilting a graph by gamma turns its
  // degree-m terms into degree-(m+1) terms proportional to gamma; the PCA frame is tilted, the
  // corrected one (nearly) not. At an even degree d the tilt-induced term of degree d+1 is the
  // leading error of the jet's gradient and the correction removes it: the Wavejet is strictly
  // more accurate (measured mean-error ratio Wavejet/jet: sphere 0.32 (d = 2), 0.62 (d = 4);
  // torus 0.986 (d = 2), 0.936 (d = 4)), asserted as ew <= ej. At an odd degree d the
  // tilt-induced term of degree d+1 comes from the degree-d term, which both fits represent: the
  // leading error (the intrinsic degree-(d+1) term) is the same for both, and the correction only
  // removes a term of degree d+2; the two errors are equal up to sampling noise (measured at
  // d = 3: sphere 1.0004, torus 0.9988). There "at least as accurate" cannot be guaranteed; the
  // bound asserted is ew <= 1.01 ej (the two are equal to that precision).
  const PV_range sphere = make_sphere(10000, 1.);
  const PV_range torus = make_torus(20000, 1., 0.4);
  for(unsigned int d = 2; d <= 4; ++d)
  {
    const unsigned int kk = d == 2 ? 18 : 40;
    const double factor = d % 2 == 0 ? 1. : 1.01;
    accuracy_vs_jets("unit sphere (10k Fibonacci)", sphere, kk, d, factor);
    accuracy_vs_jets("torus R=1 r=0.4 (20k)", torus, kk, d, factor);
  }
}

// ---------------------------------------------------------------------------------------------
// 4. Curvatures: analytic surfaces, and CGAL's Monge_via_jet_fitting on the same neighborhoods.
// ---------------------------------------------------------------------------------------------
// Every curvature output of wavejet_estimate_curvatures at order 4 (Parallel_if_available_tag).
static void estimate_all_curvatures(PV_range& pts, std::size_t k, std::vector<double>& H, std::vector<double>& KG,
                                    std::vector<double>& k1, std::vector<double>& k2, std::vector<Vector>& d1,
                                    std::vector<Vector>& d2)
{
  CGAL::wavejet_estimate_curvatures<CGAL::Parallel_if_available_tag>(pts, k,
    WJP::order(4).mean_curvature_map(slot_map(pts, H)).gaussian_curvature_map(slot_map(pts, KG))
      .maximal_principal_curvature_map(slot_map(pts, k1)).minimal_principal_curvature_map(slot_map(pts, k2))
      .maximal_principal_direction_map(slot_map(pts, d1)).minimal_principal_direction_map(slot_map(pts, d2))
      .point_map(Point_map()).normal_map(Normal_map()));
}

static void test_curvatures(const PV_range& kitten)
{
  Point_map pm;
  Normal_map nm;
  const std::size_t k = 40;
  // 4a. Sphere R = 2 (outward normals): H = -1/R, K_G = 1/R^2, k1 = k2 = -1/R. Order 4 fits the
  // height series up to r^4; the first neglected term r^6/(16 R^5) changes the fitted second
  // derivatives by ~ rho^4/(16 R^5) (rho = neighborhood radius): bound (rho/R)^4/R on |H + 1/R|
  // and on |k1 + 1/R|, |k2 + 1/R| (eigenvalues of the fitted shape operator move at most by the
  // perturbation of its entries), 2 (rho/R)^4/R^2 on |K_G - 1/R^2| (K_G = k1 k2). The sphere is
  // umbilic: the principal directions are any tangent pair, so only their geometry is checked:
  // unit, orthogonal to each other (1e-12), and tangent to the sphere within the fitted frame's
  // tilt, bounded like the normal error of an order-4 fit: the neglected term r^6/(16 R^5) of the
  // height series tilts the fitted gradient by at most ~ rho^5/(16 R^5): bound (rho/R)^5/16
  // (measured ~20x below it: the sampling is nearly symmetric).
  {
    const double R = 2.;
    PV_range pts = make_sphere(10000, R);
    std::vector<double> Hm, Km, k1, k2;
    std::vector<Vector> d1, d2;
    estimate_all_curvatures(pts, k, Hm, Km, k1, k2, d1, d2);
    const double rho = max_knn_radius(pts, k, 100);
    double eH = 0., eK = 0., ek = 0., eorth = 0., etan = 0.;
    for(std::size_t i = 0; i < pts.size(); ++i)
    {
      eH = (std::max)(eH, std::abs(Hm[i] + 1. / R));
      eK = (std::max)(eK, std::abs(Km[i] - 1. / (R * R)));
      ek = (std::max)({ek, std::abs(k1[i] + 1. / R), std::abs(k2[i] + 1. / R), k1[i] >= k2[i] ? 0. : 1e300});
      const Vector n = pts[i].second;
      eorth = (std::max)({eorth, std::abs(d1[i] * d2[i]), std::abs(d1[i].squared_length() - 1.),
                          std::abs(d2[i].squared_length() - 1.)});
      etan = (std::max)({etan, std::abs(d1[i] * n), std::abs(d2[i] * n)});
    }
    const double bH = std::pow(rho / R, 4) / R, bK = 2. * std::pow(rho / R, 4) / (R * R), bt = std::pow(rho / R, 5) / 16.;
    report("4a. curvatures on sphere R=2 (k=40, K=4): H, K_G, k1, k2, directions", eH < bH && eK < bK && ek < bH &&
             eorth < 1e-12 && etan < bt,
           "max |H + 1/R| = " + fmt(eH) + " (bound " + fmt(bH) + "), max |K_G - 1/R^2| = " + fmt(eK) +
             " (bound " + fmt(bK) + "), max |k_i + 1/R| = " + fmt(ek) + " (bound " + fmt(bH) +
             "), directions: orthonormality " + fmt(eorth) + " (bound 1e-12), max |d_i . n| = " + fmt(etan) +
             " (bound " + fmt(bt) + ")");
  }
  // 4b. Torus R = 1, r = 0.4 (outward normals, known H, K_G, k1, k2 and directions). Its graph
  // over the tangent plane is not symmetric: the first term a K = 4 fit neglects is of degree 5,
  // ~ rho^5/r^4 in height, which shifts the fitted second derivatives by ~ rho^3/r^4: bound
  // (rho/r)^3/r on |dH|, |dk1|, |dk2| (eigenvalues, as in 4a), and (rho/r)^3 (|k1| + |k2|)/r on
  // |dK_G| (K_G = k1 k2), with |k1| + |k2| <= 1/r + 1/(R - r). Principal directions (up to sign):
  // an eigenvector of the shape operator turns by at most (perturbation) / (gap k1 - k2), so the
  // sine of its angle to the truth is bounded by (rho/r)^3/r / (k1 - k2) at each point.
  {
    const double R = 1., r = 0.4;
    Torus_truth tt;
    PV_range pts = make_torus(20000, R, r, &tt);
    std::vector<double> Hm, Km, k1, k2;
    std::vector<Vector> d1, d2;
    estimate_all_curvatures(pts, k, Hm, Km, k1, k2, d1, d2);
    const double rho = max_knn_radius(pts, k, 100);
    const double bH = std::pow(rho / r, 3) / r, bK = std::pow(rho / r, 3) * (1. / r + 1. / (R - r)) / r;
    double eH = 0., eK = 0., ek1 = 0., ek2 = 0., edir = 0., edir_ratio = 0.;
    for(std::size_t i = 0; i < pts.size(); ++i)
    {
      eH = (std::max)(eH, std::abs(Hm[i] - tt.H[i]));
      eK = (std::max)(eK, std::abs(Km[i] - tt.KG[i]));
      ek1 = (std::max)(ek1, std::abs(k1[i] - tt.k1[i]));
      ek2 = (std::max)(ek2, std::abs(k2[i] - tt.k2[i]));
      const double a = (std::max)(std::sin(unoriented_angle(d1[i], tt.d1[i])), std::sin(unoriented_angle(d2[i], tt.d2[i])));
      edir = (std::max)(edir, a);
      edir_ratio = (std::max)(edir_ratio, a / (bH / (tt.k1[i] - tt.k2[i])));
    }
    report("4b. curvatures on torus R=1 r=0.4 (k=40, K=4): H, K_G, k1, k2, directions",
           eH < bH && eK < bK && ek1 < bH && ek2 < bH && edir_ratio < 1.,
           "rho = " + fmt(rho) + ", max |dH| = " + fmt(eH) + " (bound " + fmt(bH) + "), max |dK_G| = " + fmt(eK) +
             " (bound " + fmt(bK) + "), max |dk1| = " + fmt(ek1) + ", max |dk2| = " + fmt(ek2) + " (bound " +
             fmt(bH) + "), max sin(direction error) = " + fmt(edir) + " (worst ratio to its bound " +
             fmt(edir_ratio) + ")");
  }
  // 4c. kitten vs CGAL::Monge_via_jet_fitting, degrees 2-4, k = 18: same points (query first,
  // then its k nearest, excluding itself, ties by index), same PCA frame (curvature from the
  // first fit, the default INITIAL_FRAME), same polynomial space, same least-squares problem
  // (spec §4): equal to floating-point error. Rescaled curvature k*Rf is O(1) and carries an
  // absolute fp error ~ eps * cond (cond < 1e6 on 19-point neighborhoods); so the test is
  // |dk| Rf <= 1e-8 max(|k| Rf, 1): 1e-8 relative, with the floor 1/Rf for near-zero curvatures.
  {
    const std::size_t kk = 18;
    const std::vector<std::vector<std::size_t> > nb = brute_knn(kitten, kk);
    typedef CGAL::Monge_via_jet_fitting<Kernel> Monge;
    std::string numbers;
    bool ok = true;
    for(unsigned int d = 2; d <= 4; ++d)
    {
      PV_range pts = kitten;
      std::vector<double> H, KG, k1, k2;
      const CGAL::Wavejets::Processing_report rep = CGAL::wavejet_estimate_curvatures<CGAL::Parallel_if_available_tag>(
        pts, (unsigned int)kk,
        WJP::order(d).mean_curvature_map(slot_map(pts, H)).gaussian_curvature_map(slot_map(pts, KG))
          .maximal_principal_curvature_map(slot_map(pts, k1)).minimal_principal_curvature_map(slot_map(pts, k2))
          .point_map(pm).normal_map(nm));
      double worst = 0.;
      std::size_t flipped = 0;
      for(std::size_t i = 0; i < pts.size(); ++i)
      {
        std::vector<Point> q(1, pts[i].first);
        for(std::size_t j : nb[i]) q.push_back(pts[j].first);
        Monge monge;
        Monge::Monge_form mf = monge(q.begin(), q.end(), d, 2);
        mf.comply_wrt_given_normal(pts[i].second);
        const double Rf = knn_radius(pts, i, nb[i]);
        const double c1 = mf.principal_curvatures(0), c2 = mf.principal_curvatures(1);
        const double ch = (c1 + c2) / 2., ck = c1 * c2;
        auto err = [&](double a, double b, double scale) { return std::abs(a - b) * scale / (std::max)(std::abs(b) * scale, 1.); };
        const double e = (std::max)((std::max)(err(k1[i], c1, Rf), err(k2[i], c2, Rf)),
                                    (std::max)(err(H[i], ch, Rf), err(KG[i], ck, Rf * Rf)));
        // An orientation disagreement (PCA normal vs jet normal on opposite sides of the input
        // normal) flips all signs; it can only happen where the input normal is ~orthogonal.
        if(e > 1e-8 && std::abs(k1[i] + c2) * Rf <= 1e-8 * (std::max)(std::abs(c2) * Rf, 1.)) { ++flipped; continue; }
        worst = (std::max)(worst, e);
      }
      numbers += "degree " + std::to_string(d) + ": max rel err " + fmt(worst) + " (" + std::to_string(flipped) +
                 " orientation flips); ";
      ok = ok && worst <= 1e-8 && flipped == 0 && rep.number_of_fitted_points == pts.size();
    }
    report("4c. curvatures vs Monge_via_jet_fitting on kitten (k=18)", ok, numbers);
  }
}

// ---------------------------------------------------------------------------------------------
// 5. Contract: concurrency, input types, interruption, unfittable points, named parameters.
// ---------------------------------------------------------------------------------------------
struct All_outputs
{
  PV_range normals, positions, enhanced_normals;
  std::vector<double> H, KG, k1, k2;
  std::vector<Vector> d1, d2;
  std::vector<char> fitted;
};

template <class Tag>
All_outputs run_all(const PV_range& input)
{
  Point_map pm;
  Normal_map nm;
  All_outputs o;
  o.normals = input;
  CGAL::wavejet_estimate_normals<Tag>(o.normals, 18, WJP::order(3).point_map(pm).normal_map(nm));
  PV_range c = input;
  CGAL::wavejet_estimate_curvatures<Tag>(c, 18,
    WJP::order(3).curvature_frame(CGAL::Wavejets::Curvature_frame::TANGENT_FRAME)
      .mean_curvature_map(slot_map(c, o.H)).gaussian_curvature_map(slot_map(c, o.KG))
      .maximal_principal_curvature_map(slot_map(c, o.k1)).minimal_principal_curvature_map(slot_map(c, o.k2))
      .maximal_principal_direction_map(slot_map(c, o.d1)).minimal_principal_direction_map(slot_map(c, o.d2))
      .fitted_map(slot_map(c, o.fitted)).point_map(pm).normal_map(nm));
  o.positions = input;
  CGAL::wavejet_enhance_positions<Tag>(o.positions, 40, 2., WJP::order(4).write_normals(true).point_map(pm).normal_map(nm));
  o.enhanced_normals = input;
  CGAL::wavejet_enhance_normals<Tag>(o.enhanced_normals, 40, std::complex<double>(2., 0.5),
                                     WJP::order(4).point_map(pm).normal_map(nm));
  return o;
}

static void test_contract(const PV_range& kitten)
{
  Point_map pm;
  Normal_map nm;
  // 5a. Sequential == Parallel, bitwise, for all outputs of the four functions.
  {
    const All_outputs a = run_all<Seq>(kitten), b = run_all<Par>(kitten);
    const bool ok = same_bits(a.normals, b.normals) && same_bits(a.positions, b.positions) &&
                    same_bits(a.enhanced_normals, b.enhanced_normals) && same_bits(a.H, b.H) && same_bits(a.KG, b.KG) &&
                    same_bits(a.k1, b.k1) && same_bits(a.k2, b.k2) && same_bits(a.d1, b.d1) && same_bits(a.d2, b.d2) &&
                    a.fitted == b.fitted;
#ifdef CGAL_LINKED_WITH_TBB
    report("5a. Sequential_tag == Parallel_tag (bitwise, 4 functions, kitten)", ok, "");
#else
    report("5a. Sequential_tag == Parallel_tag (TBB not linked: Sequential twice)", ok, "");
#endif
  }
  // 5b. Point_set_3 (ps.parameters(), and order(3, ps.parameters())) == vector<pair>.
  {
    typedef CGAL::Point_set_3<Point, Vector> Point_set;
    Point_set ps;
    ps.add_normal_map();
    for(const PV& q : kitten) ps.insert(q.first, q.second);
    bool ok = true;
    // normals, default order 2, ps.parameters()
    {
      Point_set a = ps;
      PV_range b = kitten;
      CGAL::wavejet_estimate_normals<Seq>(a, 18, a.parameters());
      CGAL::wavejet_estimate_normals<Seq>(b, 18, CGAL::parameters::point_map(pm).normal_map(nm));
      std::size_t i = 0;
      for(Point_set::const_iterator it = a.begin(); it != a.end(); ++it, ++i)
        ok = ok && same_bits(a.normal(*it), b[i].second);
    }
    // positions and curvature with the two-argument form
    {
      Point_set a = ps;
      PV_range b = kitten;
      CGAL::wavejet_enhance_positions<Seq>(a, 30, 1.5, WJP::order(3, a.parameters()));
      CGAL::wavejet_enhance_positions<Seq>(b, 30, 1.5, WJP::order(3).point_map(pm).normal_map(nm));
      std::size_t i = 0;
      for(Point_set::const_iterator it = a.begin(); it != a.end(); ++it, ++i)
        ok = ok && same_bits(a.point(*it), b[i].first);
      Point_set c = ps;
      Point_set::Property_map<double> hmap = c.add_property_map<double>("H", 0.).first;
      std::vector<double> H;
      PV_range d = kitten;
      CGAL::wavejet_estimate_curvatures<Seq>(c, 18, WJP::order(3, c.parameters()).mean_curvature_map(hmap));
      CGAL::wavejet_estimate_curvatures<Seq>(d, 18,
        WJP::order(3).mean_curvature_map(slot_map(d, H)).point_map(pm).normal_map(nm));
      i = 0;
      for(Point_set::const_iterator it = c.begin(); it != c.end(); ++it, ++i)
        ok = ok && same_bits(hmap[*it], H[i]);
      Point_set e = ps;
      PV_range f = kitten;
      CGAL::wavejet_enhance_normals<Seq>(e, 18, std::complex<double>(0., 1.), WJP::order(3, e.parameters()));
      CGAL::wavejet_enhance_normals<Seq>(f, 18, std::complex<double>(0., 1.), WJP::order(3).point_map(pm).normal_map(nm));
      i = 0;
      for(Point_set::const_iterator it = e.begin(); it != e.end(); ++it, ++i)
        ok = ok && same_bits(e.normal(*it), f[i].second);
    }
    report("5b. Point_set_3 == std::vector<pair> (4 functions)", ok, "");
  }
  // 5c. Interruption: the callback returns false at 30% progress: nothing written, reported.
  {
    bool ok = true;
    std::size_t calls = 0;
    double last = 0.;
    const std::function<bool(double)> cb = [&](double p) { ++calls; last = p; return p < 0.3; };
    PV_range a = kitten;
    CGAL::Wavejets::Processing_report r =
      CGAL::wavejet_enhance_positions<Seq>(a, 30, 2., WJP::order(3).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && calls > 1 && last >= 0.3 && same_bits(a, kitten);
    const std::size_t calls1 = calls;
    calls = 0;
    a = kitten;
    r = CGAL::wavejet_estimate_normals<Seq>(a, 18, WJP::order(2).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && calls > 1 && same_bits(a, kitten);
    std::vector<double> H(kitten.size(), 7.);
    a = kitten;
    r = CGAL::wavejet_estimate_curvatures<Seq>(a, 18,
          WJP::mean_curvature_map(slot_map(a, H)).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && std::all_of(H.begin(), H.end(), [](double h) { return h == 7.; });
    r = CGAL::wavejet_enhance_normals<Seq>(a, 18, 2., WJP::order(3).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && same_bits(a, kitten);
    report("5c. interrupted call changes nothing and reports interrupted", ok,
           std::to_string(calls1) + " callback calls before stopping");
  }
  // 5c'. The same under Parallel_tag. The callback then runs on the TBB workers, one call at a
  // time after each chunk of points, and they check its flag before each point; it returns false
  // from 30% on. Every output must be unchanged (points, normals, the curvature maps and
  // fitted_map preset to sentinels) and the report interrupted.
#ifdef CGAL_LINKED_WITH_TBB
  {
    bool ok = true;
    std::atomic<std::size_t> calls(0);
    const std::function<bool(double)> cb = [&](double p) { ++calls; return p < 0.3; };
    const std::size_t N = kitten.size();
    auto fitted_untouched = [N](const std::vector<char>& f) {
      return f.size() == N && std::all_of(f.begin(), f.end(), [](char c) { return c == 2; });
    };
    PV_range a = kitten;
    std::vector<char> fitted(N, 2);
    CGAL::Wavejets::Processing_report r = CGAL::wavejet_enhance_positions<Par>(a, 30, 2.,
      WJP::order(3).write_normals(true).fitted_map(slot_map(a, fitted)).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && same_bits(a, kitten) && fitted_untouched(fitted);
    std::string numbers = "enhance_positions " + std::to_string(calls.load()) + " callback calls";
    a = kitten;
    fitted.assign(N, 2);
    r = CGAL::wavejet_estimate_normals<Par>(a, 18,
          WJP::order(2).fitted_map(slot_map(a, fitted)).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && same_bits(a, kitten) && fitted_untouched(fitted);
    a = kitten;
    fitted.assign(N, 2);
    std::vector<double> H(N, 7.), k1(N, 7.);
    std::vector<Vector> d1(N, Vector(7., 7., 7.));
    r = CGAL::wavejet_estimate_curvatures<Par>(a, 18,
          WJP::mean_curvature_map(slot_map(a, H)).maximal_principal_curvature_map(slot_map(a, k1))
            .maximal_principal_direction_map(slot_map(a, d1)).fitted_map(slot_map(a, fitted))
            .point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && same_bits(a, kitten) && fitted_untouched(fitted) &&
         std::all_of(H.begin(), H.end(), [](double h) { return h == 7.; }) &&
         std::all_of(k1.begin(), k1.end(), [](double h) { return h == 7.; }) &&
         std::all_of(d1.begin(), d1.end(), [](const Vector& v) { return v == Vector(7., 7., 7.); });
    a = kitten;
    fitted.assign(N, 2);
    r = CGAL::wavejet_enhance_normals<Par>(a, 18, std::complex<double>(2., 1.),
          WJP::order(3).fitted_map(slot_map(a, fitted)).point_map(pm).normal_map(nm).callback(cb));
    ok = ok && r.interrupted && same_bits(a, kitten) && fitted_untouched(fitted);
    report("5c'. Parallel_tag: interrupted call changes nothing and reports interrupted (4 functions)", ok,
           numbers + ", " + std::to_string(calls.load()) + " in all");
  }
#else
  report("5c'. Parallel_tag interruption: skipped, TBB not linked", true, "");
#endif
  // 5d. Unfittable points with radius neighborhoods: an isolated far point and a NaN point.
  {
    PV_range pts = make_sphere(3000, 1.);
    const std::size_t far = pts.size(), nan = far + 1;
    pts.emplace_back(Point(10, 10, 10), Vector(1, 0, 0));
    const double q = std::numeric_limits<double>::quiet_NaN();
    pts.emplace_back(Point(q, 0, 0), Vector(0, 1, 0));
    const PV_range input = pts;
    const std::size_t N = pts.size();
    auto check_report = [&](const CGAL::Wavejets::Processing_report& r) {
      return r.number_of_points == N && r.number_of_fitted_points == N - 2 && r.number_of_unfitted_points == 2 &&
             r.number_of_non_finite_points == 1 && !r.interrupted;
    };
    auto untouched = [&](const PV_range& r) {
      return same_bits(r[far].first, input[far].first) && same_bits(r[far].second, input[far].second) && same_bits(r[nan].first, input[nan].first) &&
             same_bits(r[nan].second, input[nan].second);
    };
    auto fitted_ok = [&](const std::vector<char>& f) {
      for(std::size_t i = 0; i < N; ++i)
        if(bool(f[i]) != (i < far)) return false;
      return true;
    };
    bool ok = true;
    std::string numbers;
    // enhance_positions, with the chain of the issue (no normal map)
    {
      std::vector<char> fitted(N, 2);
      const double d = 0.05, s = 0.2, r = 0.2;
      CGAL::Wavejets::Processing_report rep = CGAL::wavejet_enhance_positions<Par>(pts, 0, 2.,
        WJP::fitted_map(slot_map(pts, fitted)).order(8).maximum_displacement(d).evaluation_radius(s).neighbor_radius(r).point_map(pm));
      ok = ok && check_report(rep) && untouched(pts) && fitted_ok(fitted);
      std::ostringstream os;
      os << rep;
      numbers = os.str();
      bool moved = false;
      for(std::size_t i = 0; i < far; ++i) moved = moved || !same_bits(pts[i].first, input[i].first);
      ok = ok && moved;
    }
    // estimate_normals, with the other chain of the issue
    {
      pts = input;
      std::vector<char> fitted(N, 2);
      CGAL::Wavejets::Processing_report rep = CGAL::wavejet_estimate_normals<Par>(pts, 0,
        WJP::fitted_map(slot_map(pts, fitted)).order(6).neighbor_radius(0.2).point_map(pm).normal_map(nm));
      ok = ok && check_report(rep) && untouched(pts) && fitted_ok(fitted);
    }
    // curvatures: the unfitted points keep the values their maps had
    {
      pts = input;
      std::vector<char> fitted(N, 2);
      std::vector<double> H(N, 7.);
      CGAL::Wavejets::Processing_report rep = CGAL::wavejet_estimate_curvatures<Par>(pts, 0,
        WJP::mean_curvature_map(slot_map(pts, H)).fitted_map(slot_map(pts, fitted)).neighbor_radius(0.2).point_map(pm).normal_map(nm));
      ok = ok && check_report(rep) && H[far] == 7. && H[nan] == 7. && H[0] != 7. && fitted_ok(fitted);
    }
    // enhance_normals
    {
      pts = input;
      std::vector<char> fitted(N, 2);
      CGAL::Wavejets::Processing_report rep = CGAL::wavejet_enhance_normals<Par>(pts, 0, 2.,
        WJP::fitted_map(slot_map(pts, fitted)).order(4).neighbor_radius(0.2).point_map(pm).normal_map(nm));
      ok = ok && check_report(rep) && untouched(pts) && fitted_ok(fitted);
    }
    report("5d. unfittable points (isolated, NaN) reported, unchanged, marked by fitted_map", ok, numbers);
  }
}

// ---------------------------------------------------------------------------------------------
// 6. Radius neighborhoods centred on the query point, and the normals written by
//    wavejet_enhance_positions.
// ---------------------------------------------------------------------------------------------
static void test_neighborhood_center_and_written_normals()
{
  Point_map pm;
  Normal_map nm;
  const double inf = std::numeric_limits<double>::infinity();
  Gauss g(777);
  // 6a. A clean tilted plane on a jittered grid, gain 1, neighbor_radius 0.035: a point is only
  // projected onto its own fitted plane, which contains it, so it must not move (rounding:
  // |motion| <= 1e-14, i.e. ~100 ulp of the coordinates ~1). CGAL 5.5.1's jet_smooth_point_set
  // with neighbor_radius returns the projection of another point of the ball (a motion of about
  // the spacing, 1e-2) - the failure this guards against. (Here points move along their own
  // normal only, so this cannot detect a wrongly centred fit by itself: 6b does.)
  {
    PV_range pts;
    for(int i = 0; i <= 40; ++i)
      for(int j = 0; j <= 40; ++j)
      {
        const double x = 0.01 * i + 0.002 * g(), y = 0.01 * j + 0.002 * g();
        pts.emplace_back(Point(x, y, 0.3 * x - 0.2 * y + 0.1), Vector(-0.3, 0.2, 1.));
      }
    const PV_range input = pts;
    CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(pts, 0, 1.,
      WJP::order(2).maximum_displacement(inf).neighbor_radius(0.035).point_map(pm).normal_map(nm));
    double worst = 0.;
    for(std::size_t i = 0; i < pts.size(); ++i)
      worst = (std::max)(worst, std::sqrt(CGAL::squared_distance(pts[i].first, input[i].first)));
    report("6a. gain 1 on a clean plane with neighbor_radius does not move points", worst <= 1e-14,
           "max motion = " + fmt(worst) + " (bound 1e-14)");
  }
  // 6b. A curved jittered grid z = A sin(w x) sin(w y), neighbor_radius r = 0.045 (~60 points):
  // every point's result must be that of CGAL::Wavejet_fitting on the ball of radius r around the
  // point, the point first (the definition of a radius neighborhood centred on the query), with
  // Rf = r and the input normal orienting the frame. Checked for wavejet_enhance_positions (gain 3,
  // clamp off: p' = p + (f00 - 2 pi (gain - 1) (a_0(Rf) - f00 Rf^2/2) / Rf^2) n, n the frame
  // normal), the normals it writes, wavejet_estimate_curvatures (H) and fitted_map. Same
  // computation on the same numbers (neighbors sorted by distance, ties by index, as the driver
  // does): equal to rounding; bounds 1e-12 Rf on positions, 1e-12 on normals, 1e-10 relative on H
  // (floor 1/Rf). A fit centred on any other point of the ball differs by ~ |grad a0| x spacing.
  {
    const double A = 0.02, w = 2. * PI / 0.3, r = 0.045, gain = 3.;
    PV_range pts;
    for(int i = 0; i <= 40; ++i)
      for(int j = 0; j <= 40; ++j)
      {
        const double x = 0.01 * i + 0.002 * g(), y = 0.01 * j + 0.002 * g();
        pts.emplace_back(Point(x, y, A * std::sin(w * x) * std::sin(w * y)),
                         Vector(-A * w * std::cos(w * x) * std::sin(w * y), -A * w * std::sin(w * x) * std::cos(w * y), 1.));
      }
    const PV_range input = pts;
    const std::size_t N = pts.size();
    std::vector<char> fitted(N, 2);
    CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(pts, 0, gain,
      WJP::order(4).maximum_displacement(inf).write_normals(true).fitted_map(slot_map(pts, fitted))
        .neighbor_radius(r).point_map(pm).normal_map(nm));
    PV_range c = input;
    std::vector<double> H;
    CGAL::wavejet_estimate_curvatures<CGAL::Parallel_if_available_tag>(c, 0,
      WJP::order(4).mean_curvature_map(slot_map(c, H)).neighbor_radius(r).point_map(pm).normal_map(nm));
    CGAL::Wavejets::Fitting_options opt;
    opt.neighborhood_radius = r;
    CGAL::Wavejet_fitting<Kernel> fitting(opt);
    double ep = 0., en = 0., eh = 0.;
    std::size_t compared = 0, skipped = 0, status_mismatch = 0, nfitted = 0;
    std::vector<std::pair<double, std::size_t> > d;
    for(std::size_t i = 0; i < N; ++i)
    {
      const Point& p = input[i].first;
      d.clear();
      bool ambiguous = false;
      for(std::size_t j = 0; j < N; ++j)
      {
        if(j == i) continue;
        const double s2 = CGAL::squared_distance(p, input[j].first);
        if(std::abs(s2 - r * r) <= 1e-9 * r * r) ambiguous = true; // too close to the sphere to tell
        if(s2 <= r * r) d.emplace_back(s2, j);
      }
      if(ambiguous) { ++skipped; continue; }
      std::sort(d.begin(), d.end());
      std::vector<Point> ball(1, p);
      for(const auto& e : d) ball.push_back(input[e.second].first);
      const CGAL::Wavejet_fitting<Kernel>::Wavejet_form f = fitting(ball.begin(), ball.end(), 4, input[i].second);
      ++compared;
      if(f.is_valid() != (fitted[i] == 1)) { ++status_mismatch; continue; }
      if(!f.is_valid()) { ep = (std::max)(ep, std::sqrt(CGAL::squared_distance(pts[i].first, p))); continue; }
      ++nfitted;
      const double Rf = f.radius(), f00 = f.coefficient(0, 0).real();
      const double a0 = f.enclosed_area_coefficient(0, Rf).real() - f00 * Rf * Rf / 2.;
      const Point expected = p + (f00 - 2. * PI * (gain - 1.) * a0 / (Rf * Rf)) * f.frame_normal_direction();
      ep = (std::max)(ep, std::sqrt(CGAL::squared_distance(pts[i].first, expected)) / Rf);
      en = (std::max)(en, std::sqrt((pts[i].second - f.normal_direction()).squared_length()));
      eh = (std::max)(eh, std::abs(H[i] - f.mean_curvature()) / (std::max)(std::abs(f.mean_curvature()), 1. / Rf));
    }
    const bool ok = status_mismatch == 0 && nfitted > N / 2 && compared + skipped == N && ep <= 1e-12 && en <= 1e-12 &&
                    eh <= 1e-10;
    report("6b. radius neighborhoods centred on the query (== Wavejet_fitting on its ball, r = 0.045)", ok,
           std::to_string(nfitted) + " fitted of " + std::to_string(compared) + " compared (" +
             std::to_string(skipped) + " skipped near the radius, " + std::to_string(status_mismatch) +
             " fitted-status mismatches); max |p' - expected| / Rf = " + fmt(ep) + ", written normal " +
             fmt(en) + ", H rel " + fmt(eh));
  }
  // 6c. write_normals: on the unit sphere (10k Fibonacci points, k = 40, K = 4, gain 2) the normals
  // written by wavejet_enhance_positions are those of the Wavejets at the input points: radial,
  // oriented like the input (outward) normals. Error of an order-4 normal: the neglected r^6/16
  // term of the height series tilts the fitted gradient by at most ~ rho^5/16 (rho = neighborhood
  // radius, ~0.13): bound (rho/R)^5/16 = 2.4e-6 (measured ~25x below: nearly symmetric sampling).
  // A normal taken at a neighbor instead of the point would be off by the spacing, ~0.02 rad.
  {
    const PV_range input = make_sphere(10000, 1.);
    PV_range pts = input;
    const CGAL::Wavejets::Processing_report rep = CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(
      pts, 40, 2., WJP::order(4).write_normals(true).point_map(pm).normal_map(nm));
    const double rho = max_knn_radius(input, 40, 100), bound = std::pow(rho, 5) / 16.;
    double worst = 0., mean = 0.;
    for(std::size_t i = 0; i < pts.size(); ++i)
    {
      const double a = angle(pts[i].second, input[i].first - CGAL::ORIGIN);
      worst = (std::max)(worst, a);
      mean += a / double(pts.size());
    }
    report("6c. wavejet_enhance_positions write_normals: radial and outward on a sphere (k=40, K=4)",
           worst <= bound && rep.number_of_fitted_points == pts.size(),
           "max angle to radial = " + fmt(worst) + " rad, mean " + fmt(mean) + " (bound (rho/R)^5/16 = " +
             fmt(bound) + ", rho = " + fmt(rho) + ")");
  }
}


// ---------------------------------------------------------------------------------------------
// 8. Per-point scales: neighborhood_size_map and order_map, wavejet_estimate_scales.
// ---------------------------------------------------------------------------------------------

// 8a. A point fitted with its own k, order and radius (the maps) gets, bitwise, what a run of the
// whole set at that k, order and radius gives it: normals and mean curvatures on the kitten. First
// three k (one given as 0, the positional k) and two orders spread over the points; then two radii
// (with k 0 there: all the neighbors in the radius) and k 20 spread over the points. In core, tiled
// (tile_size 500) and Parallel_tag alike. Bad map values are errors.
static void test_per_point_maps(const PV_range& kitten)
{
  Point_map pm;
  Normal_map nm;
  const std::size_t N = kitten.size();

  // The maps are keyed by the elements of the range they are given with (slot_map: by address).
  struct Outputs { PV_range normals; std::vector<double> H; };
  struct Maps { std::vector<unsigned int> k; std::vector<std::size_t> order; std::vector<double> radius; };
  struct Settings { std::size_t order; std::size_t tile_size; double radius; };
  // per_point: the maps (and the settings' tile size); else one run at the settings' order and radius.
  auto run = [&](auto tag, unsigned int k, const Settings& np, const Maps* per_point) {
    Outputs o{kitten, {}};
    PV_range with_normals = kitten;
    if(per_point)
    {
      Maps m1 = *per_point, m2 = *per_point;
      CGAL::wavejet_estimate_normals<decltype(tag)>(o.normals, k, WJP::neighborhood_size_map(slot_map(o.normals, m1.k))
        .order_map(slot_map(o.normals, m1.order)).neighbor_radius_map(slot_map(o.normals, m1.radius))
        .tile_size(np.tile_size).point_map(pm).normal_map(nm));
      CGAL::wavejet_estimate_curvatures<decltype(tag)>(with_normals, k, WJP::neighborhood_size_map(slot_map(with_normals, m2.k))
        .order_map(slot_map(with_normals, m2.order)).neighbor_radius_map(slot_map(with_normals, m2.radius))
        .tile_size(np.tile_size).mean_curvature_map(slot_map(with_normals, o.H)).point_map(pm).normal_map(nm));
    }
    else
    {
      CGAL::wavejet_estimate_normals<decltype(tag)>(o.normals, k, WJP::order(np.order).neighbor_radius(np.radius)
        .point_map(pm).normal_map(nm));
      CGAL::wavejet_estimate_curvatures<decltype(tag)>(with_normals, k, WJP::order(np.order)
        .mean_curvature_map(slot_map(with_normals, o.H)).neighbor_radius(np.radius).point_map(pm).normal_map(nm));
    }
    return o;
  };
  // Every point of `group` (group_of[i] == g) against one run at group g's settings.
  auto compare = [&](const Outputs& mixed, const std::vector<int>& group_of, const std::vector<Settings>& group_settings,
                     const std::vector<unsigned int>& group_k, const std::string& what) {
    std::size_t compared = 0, differ = 0;
    for(std::size_t g = 0; g < group_settings.size(); ++g)
    {
      const Outputs single = run(Seq(), group_k[g], group_settings[g], nullptr);
      for(std::size_t i = 0; i < N; ++i)
        if(group_of[i] == int(g))
        {
          ++compared;
          differ += !(same_bits(mixed.normals[i].second, single.normals[i].second) && same_bits(mixed.H[i], single.H[i]));
        }
    }
    report("8a. " + what + " == a run at those (bitwise, normals and H, kitten)",
           compared == N && differ == 0, std::to_string(differ) + " of " + std::to_string(compared) + " points differ");
  };
  auto same_as = [&](const Outputs& a, const Outputs& b) {
    bool same = true;
    for(std::size_t i = 0; i < N; ++i)
      same = same && same_bits(a.normals[i].second, b.normals[i].second) && same_bits(a.H[i], b.H[i]);
    return same;
  };

  // k and order per point.
  const unsigned int ks[3] = {12, 30, 0}, positional_k = 20;
  const std::size_t orders[2] = {3, 0}, default_order = 2;
  Maps by_k{std::vector<unsigned int>(N), std::vector<std::size_t>(N), std::vector<double>(N, 0.)};
  std::vector<int> group_of(N);
  for(std::size_t i = 0; i < N; ++i)
  {
    by_k.k[i] = ks[i % 3];
    by_k.order[i] = orders[(i / 3) % 2];
    group_of[i] = int(2 * (i % 3) + (i / 3) % 2);
  }
  std::vector<Settings> group_settings;
  std::vector<unsigned int> group_k;
  for(unsigned int kc = 0; kc < 3; ++kc)
    for(unsigned int oc = 0; oc < 2; ++oc)
    {
      group_settings.push_back({orders[oc] ? orders[oc] : default_order, 0, 0.});
      group_k.push_back(ks[kc] ? ks[kc] : positional_k);
    }
  const Outputs mixed = run(Seq(), positional_k, Settings{0, 0, 0.}, &by_k);
  compare(mixed, group_of, group_settings, group_k, "per-point k and order");
  report("8a. per-point k and order: Parallel_tag and tile_size(500) == in core, sequential (bitwise)",
         same_as(run(Par(), positional_k, Settings{0, 0, 0.}, &by_k), mixed) &&
         same_as(run(Seq(), positional_k, Settings{0, 500, 0.}, &by_k), mixed), "");

  // A radius per point: the median distance to the 20th nearest neighbor (over 64 points) and 1.5
  // times it, both with no limit on the count (the map's k 0 stands for the positional k 0), and the
  // 20 nearest (radius 0 stands for neighbor_radius 0).
  std::vector<double> kth;
  for(std::size_t s = 0; s < N; s += (std::max)(std::size_t(1), N / 64))
  {
    std::vector<double> d;
    for(const auto& q : kitten) d.push_back(std::sqrt(CGAL::squared_distance(q.first, kitten[s].first)));
    std::nth_element(d.begin(), d.begin() + 20, d.end());
    kth.push_back(d[20]);
  }
  std::nth_element(kth.begin(), kth.begin() + kth.size() / 2, kth.end());
  const double radii[3] = {kth[kth.size() / 2], 1.5 * kth[kth.size() / 2], 0.};
  Maps by_radius{std::vector<unsigned int>(N), std::vector<std::size_t>(N, 0), std::vector<double>(N)};
  for(std::size_t i = 0; i < N; ++i)
  {
    by_radius.radius[i] = radii[i % 3];
    by_radius.k[i] = i % 3 == 2 ? 20 : 0;
    group_of[i] = int(i % 3);
  }
  const Outputs by_radius_run = run(Seq(), 0, Settings{0, 0, 0.}, &by_radius);
  std::size_t fitted = 0; // a fitted point's normal differs from the input's
  for(std::size_t i = 0; i < N; ++i) fitted += !same_bits(by_radius_run.normals[i].second, kitten[i].second);
  report("8a. per-point radius: at least 95% of the points are fitted", fitted >= N * 95 / 100,
         std::to_string(fitted) + " of " + std::to_string(N));
  compare(by_radius_run, group_of, {{2, 0, radii[0]}, {2, 0, radii[1]}, {2, 0, 0.}}, {0, 0, 20}, "per-point radius");
  report("8a. per-point radius: Parallel_tag and tile_size(500) == in core, sequential (bitwise)",
         same_as(run(Par(), 0, Settings{0, 0, 0.}, &by_radius), by_radius_run) &&
         same_as(run(Seq(), 0, Settings{0, 500, 0.}, &by_radius), by_radius_run), "");

  auto rejects = [&](unsigned int k, std::vector<long long> sizes, std::vector<double> radius, const std::string& expected) {
    std::vector<long long> size_of(N);
    std::vector<double> radius_of(N);
    for(std::size_t i = 0; i < N; ++i) { size_of[i] = sizes[i % sizes.size()]; radius_of[i] = radius[i % radius.size()]; }
    PV_range pts = kitten;
    try
    {
      CGAL::wavejet_estimate_normals<Seq>(pts, k, WJP::neighborhood_size_map(slot_map(pts, size_of))
        .neighbor_radius_map(slot_map(pts, radius_of)).point_map(pm).normal_map(nm));
    }
    catch(const std::invalid_argument& e) { return std::string(e.what()).find(expected) != std::string::npos; }
    return false;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN(), r = radii[0];
  report("8a. neighborhood_size_map: a negative size, and 0 with k < 2, are errors",
         rejects(1, {20, -3}, {0.}, "negative") && rejects(1, {20, 0}, {0.}, "fewer than 2") &&
         !rejects(1, {20, 5}, {0.}, "neighborhood_size_map"), "");
  report("8a. neighbor_radius_map: a negative or NaN radius, and 0 with k < 2, are errors; a radius makes k 0 valid",
         rejects(20, {0}, {r, -r}, "negative or not finite") && rejects(20, {0}, {r, nan}, "negative or not finite") &&
         rejects(0, {0}, {r, 0.}, "fewer than 2") && !rejects(0, {0}, {r}, "neighbor") &&
         !rejects(0, {0, 20}, {r, 0.}, "neighbor"), "");
}

// A plane z = 0 over [0,1]^2 (uniform random) with Gaussian height noise of standard deviation sigma.
static PV_range noisy_plane(std::size_t N, double sigma, unsigned int seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0., 1.);
  std::normal_distribution<double> g(0., 1.);
  PV_range pts;
  for(std::size_t i = 0; i < N; ++i)
  {
    const double x = u(rng), y = u(rng);
    pts.emplace_back(Point(x, y, sigma * g(rng)), Vector(0, 0, 1));
  }
  return pts;
}

// 8b. wavejet_estimate_scales. Where the estimated error is known to be monotone, the choice is known:
// on a noisy plane (no bias at any size, the variance falls with k) the largest size; on a clean
// sphere (no noise, the order-2 fit's bias grows with the size) one of the two smallest (the noise
// estimate at the smallest, from 5 degrees of freedom, makes its variance term comparable). The descriptor on the
// unit sphere is |f_2| = 1/2 (height r^2/2) at every size. Sequential == Parallel; a NaN point is
// not fitted and is no one's neighbor; bad ladders are errors.
static void test_estimate_scales()
{
  Point_map pm;
  typedef CGAL::Wavejets::Processing_report Report;
  auto interior = [](const Point& p) { return p.x() > 0.2 && p.x() < 0.8 && p.y() > 0.2 && p.y() < 0.8; };
  {
    PV_range plane = noisy_plane(8000, 0.002, 3);
    std::vector<unsigned int> k;
    const Report r = CGAL::wavejet_estimate_scales<Seq>(plane, WJP::neighborhood_size_map(slot_map(plane, k)).point_map(pm));
    const std::vector<unsigned int> ladder = CGAL::Wavejets::default_neighborhood_sizes(2);
    std::size_t inside = 0, largest = 0;
    for(std::size_t i = 0; i < plane.size(); ++i)
      if(interior(plane[i].first)) { ++inside; largest += k[i] == ladder.back(); }
    report("8b. noisy plane (sigma 0.002, 8000 points): the largest size inside", r.number_of_fitted_points == plane.size() &&
           largest >= 0.9 * double(inside), std::to_string(largest) + " of " + std::to_string(inside) + " interior points at k " +
           std::to_string(ladder.back()));
  }
  {
    PV_range sphere = make_sphere(10000, 1.);
    std::vector<unsigned int> k, k_parallel;
    std::vector<std::vector<double> > descriptor;
    const Report r = CGAL::wavejet_estimate_scales<Seq>(sphere, WJP::neighborhood_size_map(slot_map(sphere, k))
                                                        .scale_descriptor_map(slot_map(sphere, descriptor)).point_map(pm));
    CGAL::wavejet_estimate_scales<Par>(sphere, WJP::neighborhood_size_map(slot_map(sphere, k_parallel)).point_map(pm));
    const std::vector<unsigned int> ladder = CGAL::Wavejets::default_neighborhood_sizes(2);
    std::size_t smallest = 0; // at one of the two smallest sizes
    double worst = 0.;
    bool sized = true;
    for(std::size_t i = 0; i < sphere.size(); ++i)
    {
      smallest += k[i] <= ladder[1];
      sized = sized && descriptor[i].size() == ladder.size();
      for(double d : descriptor[i]) worst = (std::max)(worst, std::abs(d - 0.5));
    }
    report("8b. clean unit sphere (10000 points): one of the two smallest sizes, descriptor 1/2 at every size",
           r.number_of_fitted_points == sphere.size() && smallest >= 0.9 * double(sphere.size()) && sized && worst < 0.01,
           std::to_string(smallest) + " of " + std::to_string(sphere.size()) + " at k <= " + std::to_string(ladder[1]) +
             "; max |descriptor - 1/2| = " + fmt(worst));
    report("8b. wavejet_estimate_scales: Sequential_tag == Parallel_tag", k == k_parallel, "");
  }
  {
    PV_range pts = noisy_plane(2000, 0.001, 5);
    pts[7].first = Point(std::nan(""), 0.5, 0.);
    std::vector<unsigned int> k(pts.size(), 0);
    std::vector<bool> fitted;
    const std::vector<unsigned int> ladder = {10, 20, 40};
    const Report r = CGAL::wavejet_estimate_scales<Seq>(pts, WJP::neighborhood_size_map(slot_map(pts, k))
                                                          .neighborhood_sizes(ladder).fitted_map(slot_map(pts, fitted)).point_map(pm));
    bool chosen_in_ladder = true;
    for(std::size_t i = 0; i < pts.size(); ++i)
      if(i != 7) chosen_in_ladder = chosen_in_ladder && std::find(ladder.begin(), ladder.end(), k[i]) != ladder.end();
    report("8b. a NaN point is not fitted (map untouched), the others choose in the given ladder",
           r.number_of_non_finite_points == 1 && r.number_of_fitted_points == pts.size() - 1 && !fitted[7] && k[7] == 0 &&
           chosen_in_ladder, "");
    auto rejects = [&](const std::vector<unsigned int>& bad, const std::string& expected) {
      try { CGAL::wavejet_estimate_scales<Seq>(pts, WJP::neighborhood_size_map(slot_map(pts, k)).neighborhood_sizes(bad).point_map(pm)); }
      catch(const std::invalid_argument& e) { return std::string(e.what()).find(expected) != std::string::npos; }
      return false;
    };
    report("8b. an empty, decreasing or too small ladder is an error",
           rejects({}, "empty") && rejects({20, 10}, "increase") && rejects({1, 10}, ">= 2"), "");
    PV_range none;
    std::vector<unsigned int> k_none;
    const Report e = CGAL::wavejet_estimate_scales<Seq>(none, WJP::neighborhood_size_map(slot_map(none, k_none)).point_map(pm));
    report("8b. empty range: nothing fitted, no error", e.number_of_points == 0 && e.number_of_fitted_points == 0, "");
  }
}

/// 20000 random points of data/fandisk.off (normals (0, 0, 1)), made once.
static const PV_range& fandisk()
{
  static const PV_range pts = sample_mesh("data/fandisk.off", 20000, 42, Vector(0, 0, 1));
  return pts;
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"analytic.sphere_growth", test_sphere_growth},
    Case{"analytic.position_gains", test_position_gains},
    Case{"analytic.normal_gains", test_normal_gains},
    Case{"versus_jets.normals", [] { test_normals_vs_jets(kitten(), fandisk()); }},
    Case{"versus_jets.curvatures", [] { test_curvatures(kitten()); }},
    Case{"contract.concurrency_inputs_interruption_parameters", [] { test_contract(kitten()); }},
    Case{"contract.neighborhood_center_and_written_normals", test_neighborhood_center_and_written_normals},
    Case{"scales.per_point_maps", [] { test_per_point_maps(kitten()); }},
    Case{"scales.estimate_scales", test_estimate_scales},
  });
}
