// Tests of the Hermite fit (heights and the neighbors' normals, Fitting_options::neighbor_normal_weight,
// Wavejets::parameters::use_neighbor_normals) and of the compact weights (compact_weights):
// the basis gradient, exact recovery of polynomial height fields, that the slope equations are
// used, with the documented row weights, and are invariant under the normals' sign and length,
// analytic curvature of the sphere and the torus through the point-set functions (with input normals and with the one-call two-pass
// pipeline that estimates them), robustness to outliers, Sequential == Parallel bitwise, and the
// parameter checks.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>
#include <CGAL/Wavejet_fitting.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <Eigen/Dense>

#include "analytic_surfaces.h"
#include "wavejets_test_support.h"

#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <stdexcept>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
namespace WB = wavejets_bench;
namespace WP = CGAL::Wavejets::parameters;
namespace WI = CGAL::Wavejets::internal;

using wavejets_test::Case;
using wavejets_test::bitwise_equal;

// The analytic gradient of the basis against central differences of the basis values, K = 7.
static void test_basis_gradient()
{
  const std::size_t K = 7, B = WI::number_of_coefficients(K), M = 5, P = WI::padded_rows(M);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(-1., 1.);
  std::vector<double> x(P, 0.), y(P, 0.);
  for(std::size_t m = 0; m < M; ++m) { x[m] = U(rng); y[m] = U(rng); }
  std::vector<double> V(P * B), Gx(P * B), Gy(P * B), Vp(P * B), Vm(P * B);
  WI::evaluate_basis_columns(x.data(), y.data(), M, P, K, V.data());
  WI::evaluate_basis_gradient_columns(x.data(), y.data(), M, P, K, V.data(), Gx.data(), Gy.data());
  const double h = 1e-6;
  for(int axis = 0; axis < 2; ++axis)
  {
    std::vector<double> xp = x, xm = x, yp = y, ym = y;
    for(std::size_t m = 0; m < M; ++m)
      if(axis == 0) { xp[m] += h; xm[m] -= h; } else { yp[m] += h; ym[m] -= h; }
    WI::evaluate_basis_columns(xp.data(), yp.data(), M, P, K, Vp.data());
    WI::evaluate_basis_columns(xm.data(), ym.data(), M, P, K, Vm.data());
    const std::vector<double>& G = axis == 0 ? Gx : Gy;
    double worst = 0.;
    for(std::size_t b = 0; b < B; ++b)
      for(std::size_t m = 0; m < M; ++m)
        worst = std::max(worst, std::abs(G[b * P + m] - (Vp[b * P + m] - Vm[b * P + m]) / (2 * h)));
    CHECK(worst < 1e-7, "basis gradient along " << (axis == 0 ? "x" : "y") << " vs central differences: " << worst);
    for(std::size_t b = 0; b < B; ++b)
      for(std::size_t m = M; m < P; ++m) CHECK(G[b * P + m] == 0., "gradient padding rows are zero");
  }
}

// A polynomial height field z = sum a_ij x^i y^j, 2 <= i + j <= degree (horizontal tangent plane
// at the origin, so that a seed normal +z gives the frame over which it is a polynomial graph).
struct Polynomial
{
  std::vector<std::pair<std::pair<int, int>, double> > terms;
  Polynomial(int degree, std::uint64_t seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1., 1.);
    for(int d = 2; d <= degree; ++d)
      for(int i = 0; i <= d; ++i) terms.push_back({{i, d - i}, U(rng)});
  }
  double z(double x, double y) const
  {
    double s = 0.;
    for(const auto& t : terms) s += t.second * std::pow(x, t.first.first) * std::pow(y, t.first.second);
    return s;
  }
  // Unnormalized upward normal (-z_x, -z_y, 1).
  Vector normal(double x, double y) const
  {
    double zx = 0., zy = 0.;
    for(const auto& t : terms)
    {
      const int i = t.first.first, j = t.first.second;
      if(i > 0) zx += t.second * i * std::pow(x, i - 1) * std::pow(y, j);
      if(j > 0) zy += t.second * j * std::pow(x, i) * std::pow(y, j - 1);
    }
    return Vector(-zx, -zy, 1.);
  }
  double coefficient(int i, int j) const
  {
    for(const auto& t : terms)
      if(t.first.first == i && t.first.second == j) return t.second;
    return 0.;
  }
};

typedef CGAL::Wavejet_fitting<Kernel> Fitting;

// Height of a fitted form at world point q (over its frame, through its coefficients).
static double form_height(const Fitting::Wavejet_form& f, const Point& q)
{
  const Vector d = q - f.origin() + f.coefficient(0, 0).real() * f.frame_normal_direction();
  const double x = d * f.first_tangent_direction(), y = d * f.second_tangent_direction();
  const std::size_t P = WI::padded_rows(1), B = WI::number_of_coefficients(f.order());
  std::vector<double> xs(P, 0.), ys(P, 0.), A(P * B);
  xs[0] = x;
  ys[0] = y;
  WI::evaluate_basis_columns(xs.data(), ys.data(), 1, P, f.order(), A.data());
  double z = 0.;
  for(std::size_t b = 0; b < B; ++b) z += A[b * P] * f.coefficients()[b];
  return z;
}

// A polynomial of degree <= K with its exact normals (unoriented, of random lengths) is recovered
// exactly by the Hermite fit: heights at other points and curvatures at the origin to ~1e-10.
// Also with compact weights, and with IRLS (exact data: nothing to reweight).
static void test_exact_recovery()
{
  for(int K = 2; K <= 5; ++K)
    for(int variant = 0; variant < 3; ++variant)
    {
      const Polynomial poly(K, 100 + K);
      std::mt19937_64 rng(K);
      std::uniform_real_distribution<double> U(-0.5, 0.5), S(0.2, 3.);
      std::vector<Point> pts(1, Point(0., 0., 0.));
      std::vector<Vector> normals(1, Vector(0., 0., 1.));
      for(int l = 0; l < 80; ++l)
      {
        const double x = U(rng), y = U(rng);
        pts.emplace_back(x, y, poly.z(x, y));
        normals.push_back(poly.normal(x, y) * (S(rng) * (l % 3 == 0 ? -1. : 1.)));
      }
      CGAL::Wavejets::Fitting_options options;
      options.normal_use = CGAL::Wavejets::Normal_use::SEED_FRAME;
      options.correction_iterations = 0;
      options.compact_weights = variant == 1;
      options.robust_iterations = variant == 2 ? 3 : 0;
      Fitting fitting(options);
      const Fitting::Wavejet_form f = fitting(pts.begin(), pts.end(), normals.begin(), std::size_t(K));
      CHECK(f.is_valid() && f.order() == std::size_t(K), "Hermite fit of a degree-" << K << " polynomial");
      if(!f.is_valid()) continue;
      double worst = 0.;
      for(int t = 0; t < 20; ++t)
      {
        const double x = U(rng), y = U(rng);
        worst = std::max(worst, std::abs(form_height(f, Point(x, y, 0.)) - poly.z(x, y)));
      }
      const double a20 = poly.coefficient(2, 0), a11 = poly.coefficient(1, 1), a02 = poly.coefficient(0, 2);
      const double H = a20 + a02, KG = 4 * a20 * a02 - a11 * a11;
      CHECK(worst < 1e-10, "K=" << K << " variant " << variant << ": recovered heights, max error " << worst);
      CHECK(std::abs(f.mean_curvature() - H) < 1e-10 && std::abs(f.gaussian_curvature() - KG) < 1e-10,
            "K=" << K << " variant " << variant << ": exact curvature " << f.mean_curvature() << " vs " << H);
      CHECK(f.frame_normal_direction() * Vector(0, 0, 1) > 0.999999, "frame oriented by the first normal");
    }
}

// The slope equations are used, with the documented weight: positions with height noise and exact
// normals. With a large weight the slopes decide every coefficient but f_{0,0}: curvature exact
// even though the heights are noisy; the plain fit is off by the noise. Changing the sign or the
// length of neighbor normals changes nothing, bitwise.
static void test_slopes_are_used()
{
  const Polynomial poly(3, 7);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-0.3, 0.3), S(0.5, 2.);
  std::normal_distribution<double> G(0., 0.01);
  std::vector<Point> pts(1, Point(0., 0., G(rng)));
  std::vector<Vector> normals(1, Vector(0., 0., 1.)), flipped = normals, scaled = normals;
  for(int l = 0; l < 60; ++l)
  {
    const double x = U(rng), y = U(rng);
    pts.emplace_back(x, y, poly.z(x, y) + G(rng));
    normals.push_back(poly.normal(x, y));
    flipped.push_back(l % 2 ? -normals.back() : normals.back());
    scaled.push_back(normals.back() * S(rng));
  }
  const double H = poly.coefficient(2, 0) + poly.coefficient(0, 2);
  CGAL::Wavejets::Fitting_options options;
  options.normal_use = CGAL::Wavejets::Normal_use::SEED_FRAME;
  options.correction_iterations = 0;
  Fitting plain(options);
  const double plain_error = std::abs(plain(pts.begin(), pts.end(), std::size_t(3), Vector(0, 0, 1)).mean_curvature() - H);
  options.neighbor_normal_weight = 1e4;
  Fitting hermite(options);
  const double hermite_error = std::abs(hermite(pts.begin(), pts.end(), normals.begin(), std::size_t(3)).mean_curvature() - H);
  CHECK(plain_error > 1e-3, "height noise shows in the plain fit: " << plain_error);
  CHECK(hermite_error < 1e-6, "slopes of weight 1e4 decide the curvature: error " << hermite_error);

  options.neighbor_normal_weight = 1.;
  options.correction_iterations = 2;
  options.normal_use = CGAL::Wavejets::Normal_use::ORIENT;
  Fitting a(options), b(options);
  const Fitting::Wavejet_form fa = a(pts.begin(), pts.end(), normals.begin(), std::size_t(3));
  const Fitting::Wavejet_form fb = b(pts.begin(), pts.end(), flipped.begin(), std::size_t(3));
  CHECK(fa.is_valid() && bitwise_equal(fa.coefficients(), fb.coefficients()) &&
          fa.mean_curvature() == fb.mean_curvature(),
        "neighbor normals' signs do not matter (bitwise)");
  Fitting c(options);
  const Fitting::Wavejet_form fc = c(pts.begin(), pts.end(), scaled.begin(), std::size_t(3));
  CHECK(fc.is_valid() && std::abs(fc.mean_curvature() - fa.mean_curvature()) < 1e-12 * std::abs(fa.mean_curvature()),
        "neighbor normals' lengths do not matter (up to rounding)");
  // A weight of 0 is the plain fit, bitwise.
  options.neighbor_normal_weight = 0.;
  Fitting zero(options), reference(options);
  const Fitting::Wavejet_form fz = zero(pts.begin(), pts.end(), normals.begin(), std::size_t(3));
  const Fitting::Wavejet_form fr = reference(pts.begin(), pts.end(), std::size_t(3), normals.front());
  CHECK(bitwise_equal(fz.coefficients(), fr.coefficients()), "neighbor_normal_weight 0 is the plain fit");
}

// The slope rows are weighted as Fitting_options::neighbor_normal_weight documents, w cos^2 theta:
// heights of a quadric and normals tilted at random by up to 70 degrees (inconsistent data, so the
// weights decide the compromise), Rf = 1. The fitted height field equals an independent weighted
// least-squares quadric (monomial basis, Eigen's QR) to 1e-10, and differs from the one without the
// cos^2 theta factor.
static void test_slope_row_weights()
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-0.6, 0.6), A(0., 1.22), D(0., 6.283185307179586);
  std::vector<Point> pts;
  std::vector<Vector> normals;
  while(pts.size() < 40)
  {
    const double x = pts.empty() ? 0. : U(rng), y = pts.empty() ? 0. : U(rng);
    if(x * x + y * y > 0.9) continue;
    pts.emplace_back(x, y, 0.3 * x * x - 0.2 * x * y + 0.1 * y);
    const double tilt = normals.empty() ? 0. : A(rng), direction = D(rng); // the first one seeds the frame: (0, 0, 1)
    normals.emplace_back(std::sin(tilt) * std::cos(direction), std::sin(tilt) * std::sin(direction), std::cos(tilt));
  }
  const double w = 2.;
  // Independent fit: unknowns of p = a0 + a1 x + a2 y + a3 x^2 + a4 x y + a5 y^2.
  auto fit = [&](bool cos2) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(3 * pts.size(), 6);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * pts.size());
    for(std::size_t l = 0; l < pts.size(); ++l)
    {
      const double x = pts[l].x(), y = pts[l].y();
      const Vector& m = normals[l];
      const double c = w * (cos2 ? m.z() * m.z() / m.squared_length() : 1.);
      M.row(3 * l) << 1., x, y, x * x, x * y, y * y;
      b(3 * l) = pts[l].z();
      M.row(3 * l + 1) << 0., c, 0., 2 * c * x, c * y, 0.;
      b(3 * l + 1) = -c * m.x() / m.z();
      M.row(3 * l + 2) << 0., 0., c, 0., c * x, 2 * c * y;
      b(3 * l + 2) = -c * m.y() / m.z();
    }
    return Eigen::VectorXd(M.householderQr().solve(b));
  };
  const Eigen::VectorXd with = fit(true), without = fit(false);
  CGAL::Wavejets::Fitting_options options;
  options.normal_use = CGAL::Wavejets::Normal_use::SEED_FRAME;
  options.correction_iterations = 0;
  options.neighborhood_radius = 1.;
  options.neighbor_normal_weight = w;
  Fitting fitting(options);
  const Fitting::Wavejet_form f = fitting(pts.begin(), pts.end(), normals.begin(), std::size_t(2));
  CHECK(f.is_valid() && f.order() == 2, "Hermite fit of order 2");
  if(!f.is_valid()) return;
  double to_with = 0., to_without = 0.;
  for(int t = 0; t < 20; ++t)
  {
    const double x = U(rng), y = U(rng);
    const Eigen::Matrix<double, 6, 1> m = (Eigen::Matrix<double, 6, 1>() << 1., x, y, x * x, x * y, y * y).finished();
    const double z = form_height(f, Point(x, y, 0.));
    to_with = std::max(to_with, std::abs(z - m.dot(with)));
    to_without = std::max(to_without, std::abs(z - m.dot(without)));
  }
  CHECK(to_with < 1e-10, "the fit is the least-squares fit with slope rows weighted by w cos^2 theta: " << to_with);
  CHECK(to_without > 1e-3, "and not the one without cos^2 theta: " << to_without);
}

struct Cloud
{
  std::vector<WB::Sample> samples;
  std::vector<Point> pts;
  std::vector<Vector> normals; // exact, outward
  std::vector<std::size_t> idx;
  Cloud(const WB::Surface& S, std::size_t N, double noise, double outliers = 0.)
  {
    samples = S.sample(N, 5);
    WB::add_position_noise(samples, noise * WB::bounding_box_diagonal(samples), 6);
    WB::add_outliers(samples, outliers, 0.2, 8);
    for(const WB::Sample& s : samples)
    {
      pts.emplace_back(s.p.x(), s.p.y(), s.p.z());
      normals.emplace_back(s.truth.normal.x(), s.truth.normal.y(), s.truth.normal.z());
      idx.push_back(idx.size());
    }
  }
  // Relative RMSE of |H| (the signs of the pipeline without a normal map are arbitrary) over the inliers.
  double relative_H_error(const std::vector<double>& H) const
  {
    double e = 0., t = 0.;
    for(std::size_t i = 0; i < H.size(); ++i)
      if(samples[i].inlier)
      {
        e += (std::abs(H[i]) - std::abs(samples[i].truth.H)) * (std::abs(H[i]) - std::abs(samples[i].truth.H));
        t += samples[i].truth.H * samples[i].truth.H;
      }
    return std::sqrt(e / t);
  }
};

// The settings of a run, all as run-time values of one named-parameter type (fewer instantiations).
struct Settings
{
  std::size_t order = 2, robust = 0;
  bool hermite = false, compact = false;
  double weight = 1.;
  Settings(std::size_t K, bool h = false) : order(K), hermite(h) {}
  Settings& robust_iterations(std::size_t r) { robust = r; return *this; }
  Settings& compact_weights(bool b) { compact = b; return *this; }
  Settings& neighbor_normal_weight(double w) { weight = w; return *this; }
  auto parameters() const
  {
    return WP::order(order).use_neighbor_normals(hermite).compact_weights(compact).robust_iterations(robust)
      .neighbor_normal_weight(weight);
  }
};

template <class Tag, class NP>
static std::vector<double> curvatures_np(Cloud& c, unsigned int k, const NP& np, bool with_normals)
{
  std::vector<double> H(c.pts.size(), 0.);
  if(with_normals)
    CGAL::wavejet_estimate_curvatures<Tag>(c.idx, k, np.mean_curvature_map(CGAL::make_property_map(H))
      .point_map(CGAL::make_property_map(c.pts)).normal_map(CGAL::make_property_map(c.normals)));
  else
    CGAL::wavejet_estimate_curvatures<Tag>(c.idx, k, np.mean_curvature_map(CGAL::make_property_map(H))
      .point_map(CGAL::make_property_map(c.pts)));
  return H;
}

template <class Tag>
static std::vector<double> curvatures(Cloud& c, unsigned int k, const Settings& s, bool with_normals)
{
  return curvatures_np<Tag>(c, k, s.parameters(), with_normals);
}

// Sphere and torus through wavejet_estimate_curvatures: with the exact normals as input and with
// the one-call pipeline (no normal map: Wavejet normals estimated first). Clean data: the Hermite
// fit is close to the exact curvature (as precise as the plain fit, within 1.5x). Noisy data
// (0.25% of the diagonal): the Hermite pipeline is more precise than the plain fit.
static void test_analytic_surfaces()
{
  WB::Sphere sphere;
  WB::Torus torus;
  for(int which = 0; which < 2; ++which)
  {
    const WB::Surface& S = which == 0 ? static_cast<const WB::Surface&>(sphere) : torus;
    Cloud clean(S, 8000, 0.);
    const std::vector<double> plain = curvatures<CGAL::Sequential_tag>(clean, 40, Settings(2), false);
    const std::vector<double> given = curvatures<CGAL::Sequential_tag>(clean, 40, Settings(2, true), true);
    const std::vector<double> piped = curvatures<CGAL::Sequential_tag>(clean, 40, Settings(2, true), false);
    const double ep = clean.relative_H_error(plain), eg = clean.relative_H_error(given), ei = clean.relative_H_error(piped);
    std::cerr << S.name() << " clean, k 40, K 2: relative H RMSE plain " << ep << ", Hermite (exact normals) " << eg
              << ", Hermite pipeline " << ei << "\n";
    CHECK(eg <= 1.5 * ep && ei <= 1.5 * ep, S.name() << " clean Hermite within 1.5x of the plain fit");

    Cloud noisy(S, 8000, 0.0025);
    const std::vector<double> np = curvatures<CGAL::Sequential_tag>(noisy, 50, Settings(2), false);
    const std::vector<double> nh = curvatures<CGAL::Sequential_tag>(noisy, 50, Settings(2, true), false);
    const double enp = noisy.relative_H_error(np), enh = noisy.relative_H_error(nh);
    std::cerr << S.name() << " noise 0.25%, k 50, K 2: relative H RMSE plain " << enp << ", Hermite pipeline " << enh << "\n";
    CHECK(enh < 0.5 * enp, S.name() << " noisy: the Hermite pipeline halves the plain fit's H error");
  }
}

// 5% outliers on the sphere: the robust Hermite fit keeps the robust plain fit's precision.
static void test_outliers()
{
  WB::Sphere S;
  Cloud c(S, 6000, 0., 0.05);
  const std::vector<double> plain = curvatures<CGAL::Sequential_tag>(c, 60, Settings(4), false);
  const std::vector<double> robust = curvatures<CGAL::Sequential_tag>(c, 60, Settings(4).robust_iterations(3), false);
  const std::vector<double> hermite =
    curvatures<CGAL::Sequential_tag>(c, 60, Settings(4, true).robust_iterations(3), false);
  const double e0 = c.relative_H_error(plain), e1 = c.relative_H_error(robust), e2 = c.relative_H_error(hermite);
  std::cerr << "sphere 5% outliers, k 60, K 4: relative H RMSE plain " << e0 << ", robust " << e1 << ", robust Hermite " << e2 << "\n";
  CHECK(e1 < 0.1 * e0, "robust fit resists outliers");
  CHECK(e2 < 0.1 * e0 && e2 < 2. * e1 + 1e-4, "robust Hermite fit resists outliers like the robust fit");
}

// Sequential_tag and Parallel_tag: bitwise identical, for the four functions in Hermite mode
// (pipeline, input normals, compact weights, IRLS).
static void test_sequential_equals_parallel()
{
  WB::Torus S;
  Cloud c(S, 3000, 0.003);
  auto seq = curvatures<CGAL::Sequential_tag>(c, 30, Settings(3, true), false);
  auto par = curvatures<CGAL::Parallel_if_available_tag>(c, 30, Settings(3, true), false);
  CHECK(bitwise_equal(seq, par), "curvatures, pipeline: Sequential == Parallel");
  seq = curvatures<CGAL::Sequential_tag>(c, 30, Settings(3, true).compact_weights(true).robust_iterations(2), true);
  par = curvatures<CGAL::Parallel_if_available_tag>(c, 30, Settings(3, true).compact_weights(true).robust_iterations(2), true);
  CHECK(bitwise_equal(seq, par), "curvatures, input normals, compact weights, IRLS: Sequential == Parallel");

  std::vector<Vector> ns(c.pts.size(), CGAL::NULL_VECTOR), np = ns;
  CGAL::wavejet_estimate_normals<CGAL::Sequential_tag>(c.idx, 30, Settings(3, true).parameters()
    .point_map(CGAL::make_property_map(c.pts)).normal_map(CGAL::make_property_map(ns)));
  CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(c.idx, 30, Settings(3, true).parameters()
    .point_map(CGAL::make_property_map(c.pts)).normal_map(CGAL::make_property_map(np)));
  CHECK(bitwise_equal(ns, np), "normals: Sequential == Parallel");
  std::vector<Vector> plain(c.pts.size(), CGAL::NULL_VECTOR);
  CGAL::wavejet_estimate_normals<CGAL::Sequential_tag>(c.idx, 30, Settings(3).parameters()
    .point_map(CGAL::make_property_map(c.pts)).normal_map(CGAL::make_property_map(plain)));
  double mean_hermite = 0., mean_plain = 0.;
  for(std::size_t i = 0; i < ns.size(); ++i)
  {
    mean_hermite += WB::unoriented_angle_degrees(WB::V3(ns[i].x(), ns[i].y(), ns[i].z()), c.samples[i].truth.normal) / ns.size();
    mean_plain += WB::unoriented_angle_degrees(WB::V3(plain[i].x(), plain[i].y(), plain[i].z()), c.samples[i].truth.normal) / ns.size();
  }
  std::cerr << "torus noise 0.3%, k 30, K 3: mean normal angle plain " << mean_plain << ", Hermite pipeline " << mean_hermite << " degrees\n";
  CHECK(mean_hermite < mean_plain, "Hermite normals more precise than the plain ones");

  std::vector<Point> ps = c.pts, pp = c.pts;
  CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(c.idx, 30, 2.0, Settings(3, true).parameters()
    .point_map(CGAL::make_property_map(ps)));
  CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(c.idx, 30, 2.0, Settings(3, true).parameters()
    .point_map(CGAL::make_property_map(pp)));
  CHECK(bitwise_equal(ps, pp), "enhance positions: Sequential == Parallel");
  CHECK(!bitwise_equal(ps, c.pts), "enhance positions moved the points");

  std::vector<Vector> es = c.normals, ep = c.normals;
  CGAL::wavejet_enhance_normals<CGAL::Sequential_tag>(c.idx, 30, 2.0, Settings(3, true).parameters()
    .point_map(CGAL::make_property_map(c.pts)).normal_map(CGAL::make_property_map(es)));
  CGAL::wavejet_enhance_normals<CGAL::Parallel_if_available_tag>(c.idx, 30, 2.0, Settings(3, true).parameters()
    .point_map(CGAL::make_property_map(c.pts)).normal_map(CGAL::make_property_map(ep)));
  CHECK(bitwise_equal(es, ep), "enhance normals: Sequential == Parallel");
}

// Off by default, bitwise; bad weights are rejected.
static void test_parameters()
{
  WB::Sphere S;
  Cloud c(S, 1000, 0.002);
  const auto a = curvatures_np<CGAL::Sequential_tag>(c, 20, WP::order(2), true);
  const auto b = curvatures<CGAL::Sequential_tag>(c, 20, Settings(2), true);
  CHECK(bitwise_equal(a, b), "use_neighbor_normals(false) and compact_weights(false) are the defaults");
  const auto w = curvatures<CGAL::Sequential_tag>(c, 20, Settings(2).compact_weights(true), true);
  CHECK(!bitwise_equal(a, w), "compact weights change the fit");
  for(double bad : {0., -1., std::nan("")})
  {
    bool thrown = false;
    try { curvatures<CGAL::Sequential_tag>(c, 20, Settings(2, true).neighbor_normal_weight(bad), true); }
    catch(const std::invalid_argument&) { thrown = true; }
    CHECK(thrown, "neighbor_normal_weight(" << bad << ") is rejected");
  }
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"fit.basis_gradient", test_basis_gradient},
    Case{"fit.exact_recovery_of_polynomials", test_exact_recovery},
    Case{"fit.slopes_are_used", test_slopes_are_used},
    Case{"fit.slope_row_weights", test_slope_row_weights},
    Case{"functions.analytic_sphere_and_torus", test_analytic_surfaces},
    Case{"functions.outliers", test_outliers},
    Case{"functions.sequential_equals_parallel", test_sequential_equals_parallel},
    Case{"functions.parameter_checks", test_parameters},
  });
}
