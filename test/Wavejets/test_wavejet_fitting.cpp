// Tests of CGAL::Wavejet_fitting (the fitting core), against analytic truth, CGAL's
// Monge_via_jet_fitting, invariances, stability of the tangent-plane correction, and the
// adaptive order / failure states. See doc/Wavejets/Mathematics.txt for the conventions tested here.
//
// Every check is an explicit `if` (through wavejets_test::check): a failure is printed and
// counted, and main() returns EXIT_FAILURE if any check failed; the argument runs one case or
// group. Random inputs come from fixed seeds.
// Expected values are analytic (or come from CGAL for the cross-check); nothing is computed
// with the package's internals.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Wavejet_fitting.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "analytic_surfaces.h"
#include "wavejets_test_support.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel EK;
typedef CGAL::Simple_cartesian<double> SC;
typedef EK::Point_3 Point;
typedef EK::Vector_3 Vector;
typedef CGAL::Wavejet_fitting<EK> Fitting;
typedef Fitting::Wavejet_form Form;
typedef CGAL::Monge_via_jet_fitting<EK> Monge;
typedef Monge::Monge_form Monge_form;
typedef std::complex<double> cplx;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using CGAL::Wavejets::Fit_status;
using CGAL::Wavejets::Fitting_options;
using CGAL::Wavejets::Curvature_frame;
using CGAL::Wavejets::Normal_use;

// coefficient(k, n) and enclosed_area_coefficient(n, s) return std::complex<FT> for the kernels
// whose FT is double (Epick, Simple_cartesian<double>), as issue 2 asks; see Wavejet_form::Complex.
static_assert(std::is_same<Form::FT, double>::value && std::is_same<Form::Complex, std::complex<Form::FT>>::value &&
                std::is_same<decltype(std::declval<const Form&>().coefficient(0, 0)), std::complex<Form::FT>>::value &&
                std::is_same<decltype(std::declval<const Form&>().enclosed_area_coefficient(0, 1.)),
                             std::complex<Form::FT>>::value,
              "Epick: Wavejet_form::coefficient() must return std::complex<FT>");
static_assert(std::is_same<CGAL::Wavejet_fitting<SC>::Wavejet_form::Complex,
                           std::complex<CGAL::Wavejet_fitting<SC>::Wavejet_form::FT>>::value,
              "Simple_cartesian<double>: Wavejet_form::Complex must be std::complex<FT>");

namespace {

const double PI = 3.14159265358979323846;
using wavejets_test::begin_section;
using wavejets_test::check;
using wavejets_test::end_section;

// ---------------------------------------------------------------------------------------------
// Reporting

template <class... A>
std::string str(const A&... a)
{
  std::ostringstream o;
  o.precision(6);
  (o << ... << a);
  return o.str();
}

// |a - b| / max(|a|, |b|, floor); infinite if either is not finite.
double rel_err(double a, double b, double floor)
{
  if(!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  return std::abs(a - b) / (std::max)({std::abs(a), std::abs(b), floor});
}

template <class V> Vector3d E(const V& v) { return Vector3d(CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z())); }
Point P(const Vector3d& e) { return Point(e.x(), e.y(), e.z()); }
Vector V(const Vector3d& e) { return Vector(e.x(), e.y(), e.z()); }

// sin of the angle between two lines (directions up to sign).
double line_angle(const Vector3d& a, const Vector3d& b) { return a.normalized().cross(b.normalized()).norm(); }

Matrix3d random_rotation(std::mt19937_64& rng)
{
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q.toRotationMatrix();
}

// ---------------------------------------------------------------------------------------------
// Analytic truth for a graph z = f(x, y) over an orthonormal direct frame (u, v, n), computed
// independently of the package: principal curvatures are the generalized eigenvalues of the
// second fundamental form II = Hess f / sqrt(g) with respect to the first I (signs: bending
// toward +n is positive), principal directions the corresponding tangent vectors.

struct Truth
{
  double H = 0, K = 0, k1 = 0, k2 = 0;
  Vector3d d1 = Vector3d::Zero(), d2 = Vector3d::Zero(), normal = Vector3d::Zero();
};

Truth graph_truth(double fx, double fy, double fxx, double fxy, double fyy, const Vector3d& u, const Vector3d& v,
                  const Vector3d& n)
{
  const double g = 1 + fx * fx + fy * fy;
  Eigen::Matrix2d I, II;
  I << 1 + fx * fx, fx * fy, fx * fy, 1 + fy * fy;
  II << fxx, fxy, fxy, fyy;
  II /= std::sqrt(g);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(II, I); // ascending
  Truth t;
  t.k2 = es.eigenvalues()(0);
  t.k1 = es.eigenvalues()(1);
  t.H = 0.5 * (t.k1 + t.k2);
  t.K = t.k1 * t.k2;
  const Vector3d xu = u + fx * n, xv = v + fy * n;
  t.d1 = (es.eigenvectors()(0, 1) * xu + es.eigenvectors()(1, 1) * xv).normalized();
  t.d2 = (es.eigenvectors()(0, 0) * xu + es.eigenvectors()(1, 0) * xv).normalized();
  t.normal = (n - fx * u - fy * v).normalized();
  return t;
}

// Monomials c[a][b] x^a y^b (a + b <= K) to Wavejet coefficients g[k][n + k] in the same frame,
// by expanding cos^a(t) sin^b(t) = ((e^{it} + e^{-it})/2)^a ((e^{it} - e^{-it})/(2i))^b.
std::vector<std::vector<cplx>> monomials_to_wavejet(const std::vector<std::vector<double>>& c, int K)
{
  std::vector<std::vector<cplx>> g(K + 1);
  for(int k = 0; k <= K; ++k) g[k].assign(2 * k + 1, cplx(0, 0));
  for(int a = 0; a <= K; ++a)
    for(int b = 0; a + b <= K; ++b)
    {
      if(c[a][b] == 0) continue;
      const int k = a + b;
      std::vector<cplx> e(2 * k + 1, cplx(0, 0)); // e[j]: coefficient of e^{i (j - k) t}
      e[k] = 1;
      auto multiply = [&](cplx plus, cplx minus) {
        std::vector<cplx> r(2 * k + 1, cplx(0, 0));
        for(int j = 0; j <= 2 * k; ++j)
        {
          if(e[j] == cplx(0, 0)) continue;
          if(j + 1 <= 2 * k) r[j + 1] += plus * e[j];
          if(j >= 1) r[j - 1] += minus * e[j];
        }
        e = r;
      };
      for(int i = 0; i < a; ++i) multiply(cplx(0.5, 0), cplx(0.5, 0));
      for(int i = 0; i < b; ++i) multiply(cplx(0, -0.5), cplx(0, 0.5)); // 1/(2i) = -i/2
      for(int j = 0; j <= 2 * k; ++j) g[k][j] += c[a][b] * e[j];
    }
  return g;
}

double eval_poly(const std::vector<std::vector<double>>& c, int K, double x, double y)
{
  double z = 0;
  for(int a = 0; a <= K; ++a)
    for(int b = 0; a + b <= K; ++b)
      if(c[a][b] != 0) z += c[a][b] * std::pow(x, a) * std::pow(y, b);
  return z;
}

// ---------------------------------------------------------------------------------------------
// Samplers

struct Local_frame
{
  Vector3d o = Vector3d::Zero(), u = Vector3d::UnitX(), v = Vector3d::UnitY(), n = Vector3d::UnitZ();
  Vector3d world(double x, double y, double z) const { return o + x * u + y * v + z * n; }
};

Local_frame random_frame(std::mt19937_64& rng, const Vector3d& origin)
{
  const Matrix3d R = random_rotation(rng);
  Local_frame f;
  f.o = origin;
  f.u = R.col(0);
  f.v = R.col(1);
  f.n = R.col(0).cross(R.col(1));
  return f;
}

// Unit-disk pattern: N points, uniform; with fold m > 1, the pattern is invariant under rotations
// by 2 pi / m (and, if mirror, under y -> -y), so that PCA finds the symmetry axis.
std::vector<Eigen::Vector2d> disk_pattern(std::mt19937_64& rng, int N, int fold = 1, bool mirror = false)
{
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Eigen::Vector2d> base, out;
  const int copies = fold * (mirror ? 2 : 1);
  const int nb = (N + copies - 1) / copies;
  for(int i = 0; i < nb; ++i)
  {
    const double r = std::sqrt(0.05 + 0.95 * U(rng)), t = 2 * PI * U(rng);
    base.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  for(const Eigen::Vector2d& b : base)
    for(int j = 0; j < fold; ++j)
    {
      const double a = 2 * PI * j / fold, ca = std::cos(a), sa = std::sin(a);
      out.emplace_back(ca * b.x() - sa * b.y(), sa * b.x() + ca * b.y());
      if(mirror) out.emplace_back(ca * b.x() + sa * b.y(), sa * b.x() - ca * b.y());
    }
  return out;
}

// Query point (local (0, 0, z(0, 0))) first, then the graph over the pattern scaled by h.
std::vector<Point> sample_graph(const Local_frame& F, const std::function<double(double, double)>& z, double h,
                                const std::vector<Eigen::Vector2d>& pattern)
{
  std::vector<Point> pts;
  pts.push_back(P(F.world(0, 0, z(0, 0))));
  for(const Eigen::Vector2d& q : pattern)
    pts.push_back(P(F.world(h * q.x(), h * q.y(), z(h * q.x(), h * q.y()))));
  return pts;
}

// Torus ((R0 + r0 cos psi) cos phi, (R0 + r0 cos psi) sin phi, r0 sin psi), placed by (Rot, T);
// its exact quantities are those of Parametric_torus (support/analytic_surfaces.h).
struct Torus
{
  double R0 = 3, r0 = 1;
  Matrix3d Rot = Matrix3d::Identity();
  Vector3d T = Vector3d::Zero();
  wavejets_bench::Parametric_torus shape() const { return wavejets_bench::Parametric_torus{R0, r0}; }
  Vector3d point(double phi, double psi) const { return Rot * shape().point(phi, psi) + T; }
  Vector3d outward_normal(double phi, double psi) const { return Rot * shape().outward_normal(phi, psi); }
  Truth truth(double phi, double psi) const
  {
    const wavejets_bench::Parametric_torus S = shape();
    Truth t;
    const double kpar = S.parallel_curvature(psi), kmer = S.meridian_curvature();
    const Vector3d dphi = Rot * S.parallel_direction(phi);
    const Vector3d dpsi = Rot * S.meridian_direction(phi, psi);
    t.k1 = (std::max)(kpar, kmer);
    t.k2 = (std::min)(kpar, kmer);
    t.d1 = kpar >= kmer ? dphi : dpsi;
    t.d2 = kpar >= kmer ? dpsi : dphi;
    t.H = S.mean_curvature(psi);
    t.K = S.gaussian_curvature(psi);
    t.normal = outward_normal(phi, psi);
    return t;
  }
  // Query first, then a patch of (approximately geodesic) radius h around it from a unit-disk pattern.
  std::vector<Point> patch(double phi, double psi, double h, const std::vector<Eigen::Vector2d>& pattern) const
  {
    std::vector<Point> pts;
    pts.push_back(P(point(phi, psi)));
    const double a = h / (R0 + r0 * std::cos(psi)), b = h / r0;
    for(const Eigen::Vector2d& q : pattern) pts.push_back(P(point(phi + a * q.x(), psi + b * q.y())));
    return pts;
  }
};

// Kitten scan.
struct Kitten
{
  std::vector<Vector3d> pts;
  double spacing = 0;
  bool load(const std::string& file)
  {
    std::ifstream in(file);
    if(!in) return false;
    double x, y, z, nx, ny, nz;
    while(in >> x >> y >> z >> nx >> ny >> nz) pts.emplace_back(x, y, z);
    if(pts.size() < 1000) return false;
    // average nearest-neighbor distance over a subset
    double sum = 0;
    int cnt = 0;
    for(std::size_t i = 0; i < pts.size(); i += 10, ++cnt)
    {
      double best = std::numeric_limits<double>::infinity();
      for(std::size_t j = 0; j < pts.size(); ++j)
        if(j != i) best = (std::min)(best, (pts[i] - pts[j]).squaredNorm());
      sum += std::sqrt(best);
    }
    spacing = sum / cnt;
    return true;
  }
  // Query first, then its k-1 nearest other points (brute force).
  std::vector<Point> neighborhood(std::size_t q, std::size_t k) const
  {
    std::vector<std::pair<double, std::size_t>> d;
    d.reserve(pts.size());
    for(std::size_t j = 0; j < pts.size(); ++j)
      if(j != q) d.emplace_back((pts[j] - pts[q]).squaredNorm(), j);
    std::partial_sort(d.begin(), d.begin() + (k - 1), d.end());
    std::vector<Point> out;
    out.push_back(P(pts[q]));
    for(std::size_t i = 0; i + 1 < k; ++i) out.push_back(P(pts[d[i].second]));
    return out;
  }
};

/// data/kitten.xyz, read once (empty if it cannot be read: the cases that need it check that).
const Kitten& kitten()
{
  static const Kitten k = [] {
    Kitten kt;
    if(!kt.load("data/kitten.xyz")) std::cout << "cannot read data/kitten.xyz" << std::endl;
    return kt;
  }();
  return k;
}

std::size_t nb_coeffs(std::size_t K) { return (K + 1) * (K + 2) / 2; }

// Rescaled magnitude |f_{k,n}| Rf^{k-1} (heights over the unit disk).
double rescaled_abs(const Form& f, int k, int n) { return std::abs(f.coefficient(k, n)) * std::pow(CGAL::to_double(f.radius()), k - 1); }

bool form_has_nan(const Form& f)
{
  auto bad = [](const Vector3d& e) { return !e.allFinite(); };
  if(bad(E(f.origin() - CGAL::ORIGIN)) || bad(E(f.normal_direction())) || bad(E(f.first_tangent_direction())) ||
     bad(E(f.second_tangent_direction())) || bad(E(f.frame_normal_direction())) ||
     bad(E(f.maximal_principal_direction())) || bad(E(f.minimal_principal_direction())))
    return true;
  for(double c : f.coefficients())
    if(!std::isfinite(c)) return true;
  for(int k = 0; k <= 6; ++k)
    for(int n = -k; n <= k; n += 2)
      if(!std::isfinite(std::abs(f.coefficient(k, n)))) return true;
  for(int n = -3; n <= 3; ++n)
    if(!std::isfinite(std::abs(f.enclosed_area_coefficient(n, 1.0)))) return true;
  const double q[] = {CGAL::to_double(f.mean_curvature()), CGAL::to_double(f.gaussian_curvature()),
                      CGAL::to_double(f.principal_curvatures(0)), CGAL::to_double(f.principal_curvatures(1)),
                      CGAL::to_double(f.radius()), CGAL::to_double(f.tangent_plane_residual())};
  for(double x : q)
    if(!std::isfinite(x)) return true;
  return false;
}

struct Curv4
{
  double H, K, k1, k2;
};
template <class WForm>
Curv4 curv(const WForm& f)
{
  return {CGAL::to_double(f.mean_curvature()), CGAL::to_double(f.gaussian_curvature()),
          CGAL::to_double(f.principal_curvatures(0)), CGAL::to_double(f.principal_curvatures(1))};
}
inline Curv4 curv(const Truth& t) { return {t.H, t.K, t.k1, t.k2}; }
inline Curv4 curv(const Monge_form& m)
{
  const double k1 = m.principal_curvatures(0), k2 = m.principal_curvatures(1);
  return {0.5 * (k1 + k2), k1 * k2, k1, k2};
}
// Largest absolute curvature error (H, k1, k2).
double curv_abs_err(const Curv4& a, const Curv4& b)
{
  return (std::max)({std::abs(a.H - b.H), std::abs(a.k1 - b.k1), std::abs(a.k2 - b.k2)});
}

// ---------------------------------------------------------------------------------------------
// 1. Exact recovery of polynomial height fields

void test_exact_recovery()
{
  begin_section("1. exact recovery of polynomial height fields, K = 2..6 (SEED_FRAME, exact normal)");
  typedef CGAL::Wavejet_fitting<SC> SC_fitting;
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> U(-1, 1);
  double max_coef_err = 0, max_curv_err = 0, max_dir_err = 0;
  const double tol = 1e-9;
  // case 0: no linear terms (the seed frame is the tangent frame), default correction;
  // case 1: linear terms, correction off: coefficients and curvatures in the seed frame;
  // case 2: linear terms, default correction: the curvature (INITIAL_FRAME) is still exact.
  for(int K = 2; K <= 6; ++K)
    for(int cas = 0; cas < 3; ++cas)
    {
      const double rho = 1.7; // sampling radius (world units)
      std::vector<std::vector<double>> c(K + 1, std::vector<double>(K + 1, 0.));
      for(int a = 0; a <= K; ++a)
        for(int b = 0; a + b <= K; ++b)
        {
          if(a + b == 0 || (a + b == 1 && cas == 0)) continue;
          const double s = U(rng);
          c[a][b] = 0.6 * (s >= 0 ? 0.3 + 0.7 * s : -0.3 + 0.7 * s) * std::pow(rho, 1 - (a + b));
        }
      Local_frame F;
      if(K != 2) F = random_frame(rng, Vector3d(3.25, -1.75, 5.5)); // rotated and translated frame
      const std::vector<Eigen::Vector2d> pat = disk_pattern(rng, int(3 * nb_coeffs(K) + 15));
      std::vector<SC::Point_3> pts;
      pts.emplace_back(F.o.x(), F.o.y(), F.o.z());
      for(const Eigen::Vector2d& q : pat)
      {
        const Vector3d w = F.world(rho * q.x(), rho * q.y(), eval_poly(c, K, rho * q.x(), rho * q.y()));
        pts.emplace_back(w.x(), w.y(), w.z());
      }
      Fitting_options opt;
      opt.normal_use = Normal_use::SEED_FRAME;
      if(cas == 1) opt.correction_iterations = 0;
      SC_fitting fitting(opt);
      const auto form = fitting(pts.begin(), pts.end(), std::size_t(K), SC::Vector_3(F.n.x(), F.n.y(), F.n.z()));
      const std::string tag = str("K=", K, " case ", cas, ": ");
      if(!check(form.is_valid() && form.order() == std::size_t(K), tag + "fit failed or order lowered")) continue;

      const double Rf = form.radius();
      const Truth truth = graph_truth(c[1][0], c[0][1], 2 * c[2][0], c[1][1], 2 * c[0][2], F.u, F.v, F.n);
      const double kscale = (std::max)(std::abs(truth.k1), std::abs(truth.k2));
      const Curv4 got = curv(form);
      // Relative errors; near-zero values are compared against the natural scale of the
      // quantity (the largest principal curvature magnitude, or its square for K_G).
      const double e[4] = {rel_err(got.H, truth.H, kscale), rel_err(got.K, truth.K, kscale * kscale),
                           rel_err(got.k1, truth.k1, kscale), rel_err(got.k2, truth.k2, kscale)};
      for(int i = 0; i < 4; ++i)
      {
        max_curv_err = (std::max)(max_curv_err, e[i]);
        check(e[i] <= tol, tag + str("curvature #", i, " rel err ", e[i]));
      }
      // principal directions (when not umbilic)
      if(truth.k1 - truth.k2 > 1e-3 * kscale)
      {
        const double a1 = line_angle(E(form.maximal_principal_direction()), truth.d1);
        const double a2 = line_angle(E(form.minimal_principal_direction()), truth.d2);
        max_dir_err = (std::max)({max_dir_err, a1, a2});
        check(a1 <= tol && a2 <= tol, tag + str("principal directions off by ", a1, ", ", a2));
      }
      if(cas == 2) continue; // the final frame is the corrected one: coefficients are not exact there

      // Frame: n is the seed normal; theta = 0 along u at angle phi from the frame's x axis.
      const Vector3d u = E(form.first_tangent_direction()), fn = E(form.frame_normal_direction());
      check((fn - F.n).norm() <= tol && std::abs(u.dot(F.n)) <= tol && std::abs(u.norm() - 1) <= tol,
              tag + "frame normal is not the seed normal");
      const double phi = std::atan2(u.dot(F.v), u.dot(F.u));
      const std::vector<std::vector<cplx>> g = monomials_to_wavejet(c, K);
      // largest rescaled expected coefficient |g_{k,n}| Rf^{k-1}: the scale of the solution vector
      double gmax = 0;
      for(int k = 0; k <= K; ++k)
        for(const cplx& x : g[k]) gmax = (std::max)(gmax, std::abs(x) * std::pow(Rf, k - 1));
      for(int k = 0; k <= K; ++k)
      {
        double order_norm = 0;
        for(const cplx& x : g[k]) order_norm = (std::max)(order_norm, std::abs(x));
        // An order whose expected coefficients all vanish has no scale of its own: compare with
        // the largest coefficient of the solution vector, converted to this order's unit.
        const double floor = order_norm > 0 ? order_norm : gmax * std::pow(Rf, 1 - k);
        for(int n = -k; n <= k; n += 2)
        {
          // the phase law: rotating the first axis by +phi multiplies f_{k,n} by e^{i n phi}
          const cplx expected = g[k][n + k] * std::polar(1.0, n * phi);
          const cplx f = form.coefficient(k, n);
          const double err = std::abs(f - expected) / (std::max)(std::abs(expected), floor);
          max_coef_err = (std::max)(max_coef_err, std::isfinite(err) ? err : 1e300);
          check(err <= tol, tag + str("f(", k, ",", n, ") = ", f, " expected ", expected, " rel err ", err));
        }
        if(k >= 1) check(form.coefficient(k, k - 1) == cplx(0, 0), tag + "parity-mismatched coefficient not 0");
      }
      check(form.coefficient(K + 1, K + 1) == cplx(0, 0) && form.coefficient(K, K + 2) == cplx(0, 0),
              tag + "out-of-range coefficient not 0");
      // Symmetry of a real surface, and consistency of the real layout.
      for(int k = 1; k <= K; ++k)
        for(int n = 1; n <= k; ++n)
          if((k - n) % 2 == 0)
            check(form.coefficient(k, -n) == std::conj(form.coefficient(k, n)), tag + "f(k,-n) != conj f(k,n)");
    }
  std::cout << "  max relative error: coefficients " << max_coef_err << ", curvatures " << max_curv_err
            << ", principal directions (sin angle) " << max_dir_err << std::endl;
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 2. Analytic surfaces, default options

void test_analytic_surfaces()
{
  begin_section("2. analytic surfaces, default options (correction on)");
  std::mt19937_64 rng(42);
  Fitting fitting; // default options
  const int K = 4;
  const int N = 70;

  // A random-sample fit of order K on a patch of radius h has a curvature error
  // O((h/rho)^{K-1}) / rho, rho the smallest length scale of the surface (radius of curvature).
  // The tolerances below are that bound, (h/rho)^{K-1} / rho, with constant 1.
  {
    // Sphere of radius R, both orientations of the orienting normal.
    const double R = 2.0, h = 0.2;
    const double tol = std::pow(h / R, K - 1) / R;
    for(int orient = 0; orient < 2; ++orient)
    {
      const Local_frame F = random_frame(rng, Vector3d(-4.0, 1.0, 2.5)); // n = outward normal at the query
      auto z = [R](double x, double y) { return -(R - std::sqrt(R * R - x * x - y * y)); };
      const std::vector<Point> pts = sample_graph(F, z, h, disk_pattern(rng, N));
      const Vector3d given = orient == 0 ? F.n : Vector3d(-F.n);
      const Form f = fitting(pts.begin(), pts.end(), K, V(given));
      const double sgn = orient == 0 ? -1. : 1.; // H = -1/R with the outward normal
      const Curv4 c = curv(f);
      std::cout << "  sphere R=" << R << " h=" << h << (orient == 0 ? " outward" : " inward") << ": H=" << c.H
                << " (exact " << sgn / R << ") K=" << c.K << " k1=" << c.k1 << " k2=" << c.k2
                << "; |error| H " << std::abs(c.H - sgn / R) << " K " << std::abs(c.K - 1 / (R * R)) << " k1 "
                << std::abs(c.k1 - sgn / R) << " k2 " << std::abs(c.k2 - sgn / R) << " (tol " << tol << ")" << std::endl;
      check(f.is_valid() && f.order() == std::size_t(K), "sphere: fit failed");
      check(std::abs(c.H - sgn / R) <= tol && std::abs(c.k1 - sgn / R) <= tol && std::abs(c.k2 - sgn / R) <= tol,
              str("sphere: H/k1/k2 ", c.H, " ", c.k1, " ", c.k2, " vs ", sgn / R, " tol ", tol));
      check(std::abs(c.K - 1 / (R * R)) <= 2 * tol / R, str("sphere: K_G ", c.K));
      check(E(f.normal_direction()).dot(given) > 0 && line_angle(E(f.normal_direction()), F.n) <= (h / R) * tol * R,
              "sphere: normal not oriented like the given normal or inaccurate");
      // a_0(s) in the tangent frame: (1/2pi) x signed volume between surface and plane over the disc s.
      const double s = h;
      const double a0_exact = sgn * -(-R * s * s / 2 + (R * R * R - std::pow(R * R - s * s, 1.5)) / 3);
      const double a0 = f.enclosed_area_coefficient(0, s).real();
      std::cout << "    a0(" << s << ") = " << a0 << " (exact " << a0_exact << ")" << std::endl;
      check((orient == 0 ? a0 < 0 : a0 > 0), "sphere: sign of a0(s)");
      check(std::abs(a0 - a0_exact) <= std::abs(a0_exact) * tol * R, str("sphere: a0(s) ", a0, " vs ", a0_exact));
    }
  }
  {
    // Cylinder of radius R, outward normal: k1 = 0 along the axis, k2 = -1/R around it.
    const double R = 1.5, h = 0.15;
    const double tol = std::pow(h / R, K - 1) / R;
    const Local_frame F = random_frame(rng, Vector3d(0.5, 0.25, -3.0)); // u across the axis, v along it
    auto z = [R](double x, double) { return -(R - std::sqrt(R * R - x * x)); };
    const std::vector<Point> pts = sample_graph(F, z, h, disk_pattern(rng, N));
    const Form f = fitting(pts.begin(), pts.end(), K, V(F.n));
    const Curv4 c = curv(f);
    const double a1 = line_angle(E(f.maximal_principal_direction()), F.v);
    const double a2 = line_angle(E(f.minimal_principal_direction()), F.u);
    std::cout << "  cylinder R=" << R << ": H=" << c.H << " K=" << c.K << " k1=" << c.k1 << " k2=" << c.k2
              << " dir errors " << a1 << " " << a2 << std::endl;
    check(f.is_valid(), "cylinder: fit failed");
    check(std::abs(c.k1) <= tol && std::abs(c.k2 + 1 / R) <= tol && std::abs(c.H + 0.5 / R) <= tol &&
              std::abs(c.K) <= tol / R,
            "cylinder: curvatures");
    // principal directions: eigenvectors, perturbation <= curvature error / (k1 - k2)
    check(a1 <= tol * R && a2 <= tol * R, "cylinder: principal directions (max along the axis)");
    const Vector3d d1 = E(f.maximal_principal_direction()), d2 = E(f.minimal_principal_direction());
    check(std::abs(d1.cross(d2).dot(E(f.normal_direction())) - 1) <= 1e-12, "cylinder: (d1, d2, n) not direct");
  }
  {
    // Paraboloid z = a x^2 + b y^2 and saddle z = a (x^2 - y^2): polynomial, but the PCA frame is
    // not their tangent frame. rho = 1/(2 max(|a|,|b|)).
    struct Q { double a, b; const char* name; };
    for(const Q& q : {Q{0.7, 0.2, "paraboloid"}, Q{0.5, -0.5, "saddle"}})
    {
      const double h = 0.1, rho = 1 / (2 * (std::max)(std::abs(q.a), std::abs(q.b)));
      const double tol = std::pow(h / rho, K - 1) / rho;
      const Local_frame F = random_frame(rng, Vector3d(1.0, 2.0, 3.0));
      auto z = [q](double x, double y) { return q.a * x * x + q.b * y * y; };
      const std::vector<Point> pts = sample_graph(F, z, h, disk_pattern(rng, N));
      const Form f = fitting(pts.begin(), pts.end(), K, V(F.n));
      const Curv4 c = curv(f);
      const double k1 = 2 * (std::max)(q.a, q.b), k2 = 2 * (std::min)(q.a, q.b);
      const Vector3d e1 = q.a >= q.b ? F.u : F.v, e2 = q.a >= q.b ? F.v : F.u;
      const double a1 = line_angle(E(f.maximal_principal_direction()), e1);
      const double a2 = line_angle(E(f.minimal_principal_direction()), e2);
      std::cout << "  " << q.name << ": H=" << c.H << " (" << q.a + q.b << ") K=" << c.K << " (" << 4 * q.a * q.b
                << ") k1=" << c.k1 << " k2=" << c.k2 << " dir errors " << a1 << " " << a2 << std::endl;
      check(f.is_valid(), str(q.name, ": fit failed"));
      check(std::abs(c.H - (q.a + q.b)) <= tol && std::abs(c.k1 - k1) <= tol && std::abs(c.k2 - k2) <= tol &&
                std::abs(c.K - 4 * q.a * q.b) <= 2 * tol / rho,
              str(q.name, ": curvatures"));
      // an eigenvector moves by about (curvature error) / (gap k1 - k2)
      check(a1 <= tol / (k1 - k2) && a2 <= tol / (k1 - k2), str(q.name, ": principal directions"));
    }
  }
  {
    // Monkey saddle x^3 - 3 x y^2 = Re (x + i y)^3 = r^3 cos 3 theta: f_{3,+-3} = 1/2, every other
    // coefficient 0, H = K_G = 0. Samples with 3-fold symmetry and a mirror: PCA finds the z axis
    // exactly, the fit is exact (up to rounding).
    const double h = 0.4;
    const Local_frame F = random_frame(rng, Vector3d(-1.0, 0.0, 1.0));
    auto z = [](double x, double y) { return x * x * x - 3 * x * y * y; };
    const std::vector<Point> pts = sample_graph(F, z, h, disk_pattern(rng, 60, 3, true));
    const Form f = fitting(pts.begin(), pts.end(), 3, V(F.n));
    const Curv4 c = curv(f);
    const double f33 = std::abs(f.coefficient(3, 3)), f31 = std::abs(f.coefficient(3, 1));
    // phase: cos 3 theta has its maxima at theta = 0 along F.u, so f_{3,3} e^{3 i phi} is real positive
    const Vector3d u = E(f.first_tangent_direction());
    const double phi = std::atan2(u.dot(F.v), u.dot(F.u));
    const cplx f33_in_F = f.coefficient(3, 3) * std::polar(1.0, -3 * phi);
    std::cout << "  monkey saddle: H=" << c.H << " K=" << c.K << " |f33|=" << f33 << " |f31|=" << f31
              << " f33 in the sampling frame " << f33_in_F << std::endl;
    const double tol = 1e-9, scale = 6 * h; // |Hessian| at distance h
    check(f.is_valid() && f.order() == 3, "monkey saddle: fit failed");
    check(std::abs(c.H) <= tol * scale && std::abs(c.K) <= tol * scale * scale && std::abs(c.k1) <= tol * scale,
            "monkey saddle: H, K_G not 0");
    check(std::abs(f33 - 0.5) <= tol && f31 <= tol && std::abs(f.coefficient(2, 0)) <= tol * scale &&
              std::abs(f.coefficient(2, 2)) <= tol * scale,
            "monkey saddle: coefficients");
    check(std::abs(f33_in_F - cplx(0.5, 0)) <= tol, "monkey saddle: phase of f_{3,3}");
    check(std::abs(f.enclosed_area_coefficient(3, h)) > 0.9 * 0.5 * std::pow(h, 5) / 5 &&
              std::abs(f.enclosed_area_coefficient(0, h)) <= tol * std::pow(h, 5),
            "monkey saddle: a_3(s), a_0(s)");
  }
  {
    // x^4 + y^4 = r^4 (3/4 + cos(4 theta)/4): H = K_G = 0 at the origin but
    // a_0(s) = f_{4,0} s^6 / 6 = s^6 / 8 > 0. 4-fold symmetric samples: exact PCA frame.
    const double h = 0.5;
    const Local_frame F = random_frame(rng, Vector3d(2.0, 2.0, -2.0));
    auto z = [](double x, double y) { return x * x * x * x + y * y * y * y; };
    const std::vector<Point> pts = sample_graph(F, z, h, disk_pattern(rng, 64, 4, true));
    const Form f = fitting(pts.begin(), pts.end(), K, V(F.n));
    const Curv4 c = curv(f);
    const double a0 = f.enclosed_area_coefficient(0, h).real(), a0_exact = std::pow(h, 6) / 8;
    std::cout << "  x^4+y^4: H=" << c.H << " K=" << c.K << " a0(" << h << ")=" << a0 << " (exact " << a0_exact
              << ") |f40|=" << std::abs(f.coefficient(4, 0)) << " |f44|=" << std::abs(f.coefficient(4, 4)) << std::endl;
    const double tol = 1e-9, scale = 12 * h * h; // |Hessian| at distance h
    check(f.is_valid() && f.order() == std::size_t(K), "x^4+y^4: fit failed");
    check(std::abs(c.H) <= tol * scale && std::abs(c.K) <= tol * scale * scale, "x^4+y^4: H, K_G not 0");
    check(a0 > 0 && std::abs(a0 - a0_exact) <= tol * a0_exact, str("x^4+y^4: a0(s) ", a0, " vs ", a0_exact));
    check(std::abs(f.coefficient(4, 0).real() - 0.75) <= tol && std::abs(std::abs(f.coefficient(4, 4)) - 0.125) <= tol,
            "x^4+y^4: f_{4,0}, |f_{4,4}|");
  }
  {
    // (The convergence rate with the neighborhood size is group 2b, test_convergence.)
    Torus tor;
    tor.Rot = random_rotation(rng);
    tor.T = Vector3d(0.3, -0.2, 0.1);
    const double phi = 0.3, psi = 0.7;
    const Truth truth = tor.truth(phi, psi);
    // Orientation: comply_wrt_given_normal(-N) on the form oriented by N is the form oriented by
    // -N (same PCA axis u, v and n flipped): H -> -H, (k1, k2) -> (-k2, -k1), f_{k,n} -> -conj f_{k,n}.
    const std::vector<Point> pts = tor.patch(phi, psi, 0.5, disk_pattern(rng, 50));
    Form f = fitting(pts.begin(), pts.end(), K, V(truth.normal));
    const Form g = fitting(pts.begin(), pts.end(), K, V(-truth.normal));
    const Form f_before = f;
    f.comply_wrt_given_normal(V(-truth.normal));
    const Curv4 a = curv(f), b = curv(g), a0 = curv(f_before);
    const double tol = 1e-10, cs = 1 / tor.r0;
    check(a0.H < 0 && a.H == -a0.H && a.k1 == -a0.k2 && a.k2 == -a0.k1,
            "comply_wrt_given_normal: curvature signs");
    check(rel_err(a.H, b.H, cs) <= tol && rel_err(a.K, b.K, cs * cs) <= tol && rel_err(a.k1, b.k1, cs) <= tol &&
              rel_err(a.k2, b.k2, cs) <= tol,
            "comply_wrt_given_normal: curvatures differ from the fit oriented by -N");
    check((E(f.normal_direction()) - E(g.normal_direction())).norm() <= tol &&
              (E(f.second_tangent_direction()) - E(g.second_tangent_direction())).norm() <= tol &&
              (E(f.first_tangent_direction()) - E(g.first_tangent_direction())).norm() <= tol,
            "comply_wrt_given_normal: frame differs from the fit oriented by -N");
    check(line_angle(E(f.maximal_principal_direction()), E(g.maximal_principal_direction())) <= 1e-8 &&
              line_angle(E(f.maximal_principal_direction()), E(f_before.minimal_principal_direction())) == 0,
            "comply_wrt_given_normal: principal directions");
    const double Rf = f.radius();
    for(int k = 0; k <= K; ++k)
      for(int n = -k; n <= k; n += 2)
      {
        check(std::abs(f.coefficient(k, n) - g.coefficient(k, n)) * std::pow(Rf, k - 1) <= tol,
                str("comply_wrt_given_normal: f(", k, ",", n, ") ", f.coefficient(k, n), " vs ", g.coefficient(k, n)));
        check(f.coefficient(k, n) == -std::conj(f_before.coefficient(k, n)), "comply_wrt_given_normal: -conj");
      }
  }
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 2b. Convergence rate of the curvature error with the neighborhood size

// A graph z = f(x, y) over a local frame with its derivatives up to order 2, analytic.
struct Graph_surface
{
  const char* name;
  std::function<double(double, double)> z;
  // (f_x, f_y, f_xx, f_xy, f_yy) at (x, y)
  std::function<std::array<double, 5>(double, double)> d;
  double x0, y0; // the query point's (x, y): off the vertex, so the graph has terms of every degree
};

void test_convergence()
{
  begin_section("2b. convergence rate of the curvature error, h, h/2, h/4, orders 2..5");
  // For a fit of order K on samples of a smooth surface over a disc of radius h, the first term
  // the fit cannot represent has degree K+1: it perturbs the fitted second derivatives, hence the
  // curvatures, by O(h^{K-1}) (doc/Wavejets/Mathematics.txt section 2; the same argument as for jets).
  // Measurement: per surface and order, 6 random unit-disc patterns, each scaled to h0, h0/2,
  // h0/4 (h0 = 0.2 x the smallest radius of curvature at the query); E(h) = RMS over the patterns
  // of max(|dH|, |dk1|, |dk2|) against the analytic truth; observed order between two sizes
  // p = log2(E(h) / E(h/2)). (A single pattern is not enough: each signed error is a sum
  // a h^{K-1} + b h^K + ... whose terms can cancel at one size, which makes p locally anything;
  // measured with h0 = 0.1 x rho, torus K = 4: p = 4.2 then 1.97 on one pattern.)
  // Theory: p >= K - 1 as h -> 0. p is larger where the degree-(K+1) term does not reach the second derivatives (the even
  // graphs sphere and cylinder, and even K where the next even degree dominates); that is allowed.
  // At finite h the next term of the expansion lowers p by O(h), which halves with h: asserted
  // p >= K - 1 - 0.5 on the first halving and p >= K - 1 - 0.25 on the second (measured: all p
  // within [K - 1 - 0.07, K + 0.1], smallest margin to the bound 0.18, saddle K = 4 default:
  // p = 2.89, 2.93; the margin is printed). A fit that silently lost one order (adaptive order,
  // a wrong column) would drop p by >= 1 and fail.
  // Floors: coordinates of size ~3 carry eps ~ 4e-16 of rounding, i.e. ~1e-12 on curvatures at
  // h = 0.02; at the umbilic sphere k1, k2 = H +- sqrt(H^2 - K_G) carry ~sqrt(eps) |H| ~ 1.5e-8
  // (smallest E: 5e-7 on the sphere, 2.6e-8 overall, on the non-umbilic saddle).
  std::mt19937_64 rng(2718);
  const double slack[2] = {0.5, 0.25};
  const int npat = 6;
  auto sphere_z = [](double x, double y) { return std::sqrt(1. - x * x - y * y) - 1.; };
  auto sphere_d = [](double x, double y) {
    const double w = std::sqrt(1. - x * x - y * y), w3 = w * w * w;
    return std::array<double, 5>{-x / w, -y / w, -(1. - y * y) / w3, -x * y / w3, -(1. - x * x) / w3};
  };
  auto cyl_z = [](double x, double) { return std::sqrt(1. - x * x) - 1.; };
  auto cyl_d = [](double x, double) {
    const double w = std::sqrt(1. - x * x);
    return std::array<double, 5>{-x / w, 0., -1. / (w * w * w), 0., 0.};
  };
  const std::vector<Graph_surface> graphs = {
    {"sphere R=1", sphere_z, sphere_d, 0.25, -0.15},
    {"cylinder R=1", cyl_z, cyl_d, 0.3, 0.1},
    {"paraboloid 0.7x^2+0.2y^2", [](double x, double y) { return 0.7 * x * x + 0.2 * y * y; },
     [](double x, double y) { return std::array<double, 5>{1.4 * x, 0.4 * y, 1.4, 0., 0.4}; }, 0.3, -0.2},
    {"saddle 0.5(x^2-y^2)", [](double x, double y) { return 0.5 * (x * x - y * y); },
     [](double x, double y) { return std::array<double, 5>{x, -y, 1., 0., -1.}; }, 0.3, 0.2},
    {"monkey saddle x^3-3xy^2", [](double x, double y) { return x * x * x - 3 * x * y * y; },
     [](double x, double y) { return std::array<double, 5>{3 * x * x - 3 * y * y, -6 * x * y, 6 * x, -6 * y, -6 * x}; },
     0.3, 0.2},
    {"x^4+y^4", [](double x, double y) { return x * x * x * x + y * y * y * y; },
     [](double x, double y) { return std::array<double, 5>{4 * x * x * x, 4 * y * y * y, 12 * x * x, 0., 12 * y * y}; },
     0.4, 0.3}};
  Torus tor;
  tor.Rot = random_rotation(rng);
  tor.T = Vector3d(0.3, -0.2, 0.1);
  const double tphi = 0.3, tpsi = 0.7;

  Fitting_options topt;
  topt.curvature_frame = Curvature_frame::TANGENT_FRAME;
  double worst_margin[2] = {1e300, 1e300};
  for(std::size_t s = 0; s <= graphs.size(); ++s)
  {
    const bool is_torus = s == graphs.size();
    const std::string name = is_torus ? std::string("torus R0=3 r0=1") : std::string(graphs[s].name);
    const Local_frame F = random_frame(rng, Vector3d(0.7, -1.3, 2.1));
    Truth truth;
    if(is_torus)
      truth = tor.truth(tphi, tpsi);
    else
    {
      const std::array<double, 5> d = graphs[s].d(graphs[s].x0, graphs[s].y0);
      truth = graph_truth(d[0], d[1], d[2], d[3], d[4], F.u, F.v, F.n);
    }
    // length scale of the surface at the query: the smallest radius of curvature
    const double rho = 1. / (std::max)(std::abs(truth.k1), std::abs(truth.k2));
    for(int K = 2; K <= 5; ++K)
    {
      const double h0 = 0.2 * rho;
      double err[2][3] = {{0, 0, 0}, {0, 0, 0}};
      for(int pi = 0; pi < npat; ++pi)
      {
        const std::vector<Eigen::Vector2d> pat = disk_pattern(rng, int(3 * nb_coeffs(K)) + 10);
        for(int i = 0; i < 3; ++i)
        {
          const double h = h0 / (1 << i);
          std::vector<Point> pts;
          if(is_torus)
            pts = tor.patch(tphi, tpsi, h, pat);
          else
          {
            const Graph_surface& g = graphs[s];
            pts.push_back(P(F.world(g.x0, g.y0, g.z(g.x0, g.y0))));
            for(const Eigen::Vector2d& q : pat)
            {
              const double x = g.x0 + h * q.x(), y = g.y0 + h * q.y();
              pts.push_back(P(F.world(x, y, g.z(x, y))));
            }
          }
          for(int m = 0; m < 2; ++m)
          {
            Fitting fitting(m == 0 ? Fitting_options() : topt);
            const Form f = fitting(pts.begin(), pts.end(), std::size_t(K), V(truth.normal));
            check(f.is_valid() && f.order() == std::size_t(K), name + str(" K=", K, ": fit failed or order lowered"));
            const double e = curv_abs_err(curv(f), curv(truth));
            err[m][i] += e * e / npat;
          }
        }
      }
      for(int m = 0; m < 2; ++m)
      {
        for(int i = 0; i < 3; ++i) err[m][i] = std::sqrt(err[m][i]);
        const double p1 = std::log2(err[m][0] / err[m][1]), p2 = std::log2(err[m][1] / err[m][2]);
        worst_margin[m] = (std::min)({worst_margin[m], p1 - (K - 1) + slack[0], p2 - (K - 1) + slack[1]});
        std::cout << "  " << name << (m == 0 ? " default" : " TANGENT_FRAME") << " K=" << K << ": RMS error " << err[m][0]
                  << ", " << err[m][1] << ", " << err[m][2] << " at h=" << h0 << ", h/2, h/4; observed order " << p1
                  << ", " << p2 << " (theory >= " << K - 1 << ")" << std::endl;
        check(p1 >= K - 1 - slack[0] && p2 >= K - 1 - slack[1],
                str(name, m == 0 ? " default" : " TANGENT_FRAME", " K=", K, ": observed order ", p1, ", ", p2,
                    " < K - 1 - ", slack[0], ", K - 1 - ", slack[1]));
      }
    }
  }
  std::cout << "  smallest margin p - (K - 1 - slack): default " << worst_margin[0] << ", TANGENT_FRAME "
            << worst_margin[1] << " (must be >= 0)" << std::endl;
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 3. Cross-check with CGAL::Monge_via_jet_fitting

void test_cgal_cross_check(const Kitten& kitten)
{
  begin_section("3. cross-check with CGAL::Monge_via_jet_fitting, degrees 2..6");
  const double tol = 1e-8;
  auto compare = [&](const std::vector<Point>& pts, std::size_t d, double scale, const std::string& tag, double& max_err,
                     double& max_dir) {
    Fitting_options opt;
    opt.correction_iterations = 0;
    Fitting fitting(opt);
    const Form f = fitting(pts.begin(), pts.end(), d);
    Monge monge;
    Monge_form m = monge(pts.begin(), pts.end(), d, 2);
    if(!check(f.is_valid() && f.order() == d, tag + "Wavejet fit failed or order lowered")) return;
    m.comply_wrt_given_normal(f.normal_direction());
    const Curv4 a = curv(f), b = curv(m);
    // Floor: curvatures that are nearly 0 are differences of terms of size ~scale (the curvature
    // scale of the data, 1/(average spacing) on the kitten), so both fits can only agree on
    // them to ~eps * cond * scale; 1e-3 * scale keeps the comparison relative everywhere else.
    const double fl = 1e-3 * scale;
    const double kmax = (std::max)({std::abs(a.k1), std::abs(a.k2), fl});
    const double e[4] = {rel_err(a.H, b.H, fl), rel_err(a.K, b.K, fl * kmax), rel_err(a.k1, b.k1, fl),
                         rel_err(a.k2, b.k2, fl)};
    for(int i = 0; i < 4; ++i)
    {
      max_err = (std::max)(max_err, e[i]);
      check(e[i] <= tol, tag + str("curvature #", i, ": wavejet ", (i == 0 ? a.H : i == 1 ? a.K : i == 2 ? a.k1 : a.k2),
                                     " cgal ", (i == 0 ? b.H : i == 1 ? b.K : i == 2 ? b.k1 : b.k2), " rel err ", e[i]));
    }
    check(line_angle(E(f.normal_direction()), E(m.normal_direction())) <= tol, tag + "normals differ");
    // Principal directions: an eigenvector moves by about (eigenvalue error) / (eigenvalue gap).
    const double gap = a.k1 - a.k2;
    if(gap > fl)
    {
      const double ang = (std::max)(line_angle(E(f.maximal_principal_direction()), E(m.maximal_principal_direction())),
                                    line_angle(E(f.minimal_principal_direction()), E(m.minimal_principal_direction())));
      max_dir = (std::max)(max_dir, ang * gap / kmax);
      check(ang <= tol * kmax / gap, tag + str("principal directions differ by ", ang));
    }
  };

  if(check(!kitten.pts.empty(), "data/kitten.xyz not loaded"))
  {
    const double scale = 1 / kitten.spacing;
    std::cout << "  kitten: " << kitten.pts.size() << " points, average spacing " << kitten.spacing << std::endl;
    const std::size_t ks[7] = {0, 0, 40, 40, 50, 60, 80};
    for(std::size_t d = 2; d <= 6; ++d)
    {
      double max_err = 0, max_dir = 0;
      for(std::size_t i = 0; i < 300; ++i)
      {
        const std::size_t q = (i * 7919) % kitten.pts.size();
        compare(kitten.neighborhood(q, ks[d]), d, scale, str("kitten d=", d, " point ", q, ": "), max_err, max_dir);
      }
      std::cout << "  kitten d=" << d << " k=" << ks[d] << ": max relative curvature difference " << max_err
                << ", principal directions (scaled) " << max_dir << std::endl;
    }
  }
  {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0, 2 * PI);
    Torus tor;
    tor.Rot = random_rotation(rng);
    for(std::size_t d = 2; d <= 6; ++d)
    {
      double max_err = 0, max_dir = 0;
      for(int i = 0; i < 30; ++i)
      {
        const double phi = U(rng), psi = U(rng);
        const std::vector<Point> pts = tor.patch(phi, psi, 0.5, disk_pattern(rng, int(2 * nb_coeffs(d)) + 20));
        compare(pts, d, 1 / tor.r0, str("torus d=", d, ": "), max_err, max_dir);
      }
      std::cout << "  torus d=" << d << ": max relative curvature difference " << max_err << ", directions " << max_dir
                << std::endl;
    }
  }
  {
    // Accuracy against analytic truth with the correction on.
    // (a) Default options: the correction runs, but the curvature is read from the first fit, in
    //     the PCA frame (Curvature_frame::INITIAL_FRAME): that is CGAL's own least-squares problem,
    //     so "not worse than CGAL" holds by construction. It is kept as a consistency check (equal
    //     to CGAL up to rounding), not as an accuracy claim about the correction.
    // (b) The corrected path, Curvature_frame::TANGENT_FRAME: curvature read from the fit in the
    //     corrected tangent frame, a different least-squares problem. doc/Wavejets/Mathematics.txt section 4
    //     reports it 5-20% worse (RMSE of H) than the PCA-frame fit on a quartic implicit surface.
    //     Asserted: RMS curvature error <= 1.2 x CGAL's (the spec's worst figure; measured here:
    //     printed "ratio", at most ~1.04), and the corrected path really differs from (a) on most
    //     samples (otherwise (b) would be tautological too).
    // (c) The corrected normal (normal_direction(), the tangent-plane normal of the kept re-fit; the
    //     same for both curvature frames) against the analytic normal, compared with CGAL's Monge
    //     normal (the normal of the PCA-frame jet). Measured RMS ratio wavejet/CGAL: 0.22 and 0.37
    //     on the sphere at d = 2, 4, 0.94 on the torus at d = 2, and 1.00-1.014 elsewhere (d = 3, and
    //     the torus at d = 4): the re-fit is kept when it lowers the fitted tilt |f_{1,1}|, not the
    //     true normal error, so it is not better everywhere. Asserted: RMS angle <= 1.05 x CGAL's.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> U(0, 2 * PI);
    Torus tor;
    tor.Rot = random_rotation(rng);
    const double curvature_factor = 1.2, normal_factor = 1.05;
    double worst_curv_ratio = 0, worst_normal_ratio = 0;
    for(int s = 0; s < 2; ++s)
      for(std::size_t d = 2; d <= 4; ++d)
      {
        double rms_cgal = 0, rms_wj = 0, rms_tan = 0, rms_ncgal = 0, rms_nwj = 0;
        int differs = 0;
        const int M = 40;
        for(int i = 0; i < M; ++i)
        {
          std::vector<Point> pts;
          Truth truth;
          const std::vector<Eigen::Vector2d> pat = disk_pattern(rng, 60);
          if(s == 0)
          {
            const double R = 1.0, h = 0.3;
            const Local_frame F = random_frame(rng, Vector3d(1, 2, 3));
            pts = sample_graph(F, [R](double x, double y) { return -(R - std::sqrt(R * R - x * x - y * y)); }, h, pat);
            truth.H = truth.k1 = truth.k2 = -1 / R;
            truth.K = 1 / (R * R);
            truth.normal = F.n;
          }
          else
          {
            const double phi = U(rng), psi = U(rng);
            pts = tor.patch(phi, psi, 0.5, pat);
            truth = tor.truth(phi, psi);
          }
          Fitting fitting; // default options
          const Form f = fitting(pts.begin(), pts.end(), d, V(truth.normal));
          Fitting_options topt;
          topt.curvature_frame = Curvature_frame::TANGENT_FRAME;
          Fitting tfitting(topt);
          const Form ft = tfitting(pts.begin(), pts.end(), d, V(truth.normal));
          Monge monge;
          Monge_form m = monge(pts.begin(), pts.end(), d, 2);
          m.comply_wrt_given_normal(V(truth.normal));
          const double ec = curv_abs_err(curv(m), curv(truth)), ew = curv_abs_err(curv(f), curv(truth)),
                       et = curv_abs_err(curv(ft), curv(truth));
          const double nc = line_angle(E(m.normal_direction()), truth.normal),
                       nw = line_angle(E(ft.normal_direction()), truth.normal);
          rms_cgal += ec * ec;
          rms_wj += ew * ew;
          rms_tan += et * et;
          rms_ncgal += nc * nc;
          rms_nwj += nw * nw;
          check(f.is_valid() && ft.is_valid(), "fit failed");
          check(ft.number_of_corrections() >= 1, "TANGENT_FRAME: no re-fit was accepted");
          // (a) consistency: equal to CGAL's error up to rounding (same problem, see the cross-check above)
          check(ew <= ec + 1e-8 * std::abs(truth.k2),
                  str(s ? "torus" : "sphere", " d=", d, ": default (INITIAL_FRAME, CGAL's problem) error ", ew,
                      " != CGAL error ", ec));
          // by design, TANGENT_FRAME changes only where the curvature is read from
          check(ft.order() == f.order() && ft.coefficients() == f.coefficients() &&
                    E(ft.normal_direction()) == E(f.normal_direction()),
                  "TANGENT_FRAME changed the fit itself");
          if(curv_abs_err(curv(ft), curv(f)) > 1e-10 * std::abs(truth.k2)) ++differs;
        }
        const double cgal = std::sqrt(rms_cgal / M), wj = std::sqrt(rms_wj / M), tan = std::sqrt(rms_tan / M);
        const double ncgal = std::sqrt(rms_ncgal / M), nwj = std::sqrt(rms_nwj / M);
        worst_curv_ratio = (std::max)(worst_curv_ratio, tan / cgal);
        worst_normal_ratio = (std::max)(worst_normal_ratio, nwj / ncgal);
        const std::string tag = str(s ? "torus" : "sphere", " d=", d);
        std::cout << "  " << tag << ": RMS curvature error vs truth: CGAL " << cgal << ", wavejet default (INITIAL_FRAME) "
                  << wj << ", wavejet TANGENT_FRAME " << tan << " (ratio " << tan / cgal << ", " << differs << "/" << M
                  << " samples differ from the default); RMS normal angle: CGAL " << ncgal << ", wavejet corrected "
                  << nwj << " (ratio " << nwj / ncgal << ")" << std::endl;
        // (b)
        check(tan <= curvature_factor * cgal,
                tag + str(": TANGENT_FRAME RMS curvature error ", tan, " > ", curvature_factor, " x CGAL's ", cgal));
        check(differs >= M / 2, tag + str(": TANGENT_FRAME curvature differs from the default on only ", differs, "/", M));
        // (c)
        check(nwj <= normal_factor * ncgal,
                tag + str(": corrected normal RMS error ", nwj, " > ", normal_factor, " x CGAL's ", ncgal));
      }
    std::cout << "  worst ratio to CGAL: TANGENT_FRAME curvature " << worst_curv_ratio << " (bound " << curvature_factor
              << "), corrected normal " << worst_normal_ratio << " (bound " << normal_factor << ")" << std::endl;
  }
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 4. Invariances

void test_invariances(const Kitten& kitten)
{
  begin_section("4. invariances: translation, rotation, scaling, permutation, phase");
  if(!check(!kitten.pts.empty(), "data/kitten.xyz not loaded")) { end_section(); return; }
  std::mt19937_64 rng(2024);
  const std::size_t K = 4, k = 40;
  const double ulp_offset = std::nextafter(1e6, 2e6) - 1e6;
  const Matrix3d Q = random_rotation(rng);
  const double lambda = 3.7, mu = 0.9;
  double worst[6] = {0, 0, 0, 0, 0, 0}; // translation, rotation, scaling, permutation, phase (ratio to tol), |f| transl
  for(std::size_t i = 0; i < 40; ++i)
  {
    const std::size_t q = (i * 104729 + 11) % kitten.pts.size();
    const std::vector<Point> pts = kitten.neighborhood(q, k);
    // The reference fit is not oriented (plain PCA frame). Every transformed fit is oriented by the
    // transformed normal of the reference fit: a PCA eigenvector's sign is arbitrary, and two
    // unoriented forms may legitimately differ by comply_wrt_given_normal (H -> -H).
    Fitting fitting;
    const Form f = fitting(pts.begin(), pts.end(), K);
    if(!check(f.is_valid() && f.order() == K, "reference fit failed")) continue;
    const Vector nref = f.normal_direction();
    const double Rf = f.radius();
    const Curv4 c = curv(f);

    // Compares curvatures and |f_{k,n}| of g with those of f transformed by a scale factor `s`
    // (curvatures x 1/s, |f_{k,n}| x s^{1-k}). Curvatures are relative to max(|value|, 1/Rf) (1/Rf
    // is the curvature scale the fit resolves), coefficients are compared rescaled by Rf (heights
    // over the unit disk, where 1 is the natural scale). Returns the worst error / tol.
    auto compare = [&](const Form& g, double s, double tol, const std::string& tag) {
      if(!check(g.is_valid() && g.order() == K, tag + "fit failed")) return 0.;
      const Curv4 d = curv(g);
      const double cs = 1 / Rf;
      double w = (std::max)({rel_err(d.H * s, c.H, cs), rel_err(d.K * s * s, c.K, cs * cs), rel_err(d.k1 * s, c.k1, cs),
                             rel_err(d.k2 * s, c.k2, cs)});
      for(int kk = 0; kk <= int(K); ++kk)
        for(int n = -kk; n <= kk; n += 2)
          w = (std::max)(w, std::abs(rescaled_abs(g, kk, n) - rescaled_abs(f, kk, n)));
      w = (std::max)(w, std::abs(g.radius() / s - Rf) / Rf);
      check(w <= tol, tag + str("error ", w, " > tol ", tol));
      return w / tol;
    };

    // translation by (1e6, -1e6, 1e6): coordinates lose ~ulp(1e6), i.e. ulp(1e6)/Rf relative to the
    // neighborhood; allow 100 of them (doc/Wavejets/Mathematics.txt section 8).
    {
      const Vector t(1e6, -1e6, 1e6);
      std::vector<Point> moved;
      for(const Point& p : pts) moved.push_back(p + t);
      Fitting ft;
      const Form g = ft(moved.begin(), moved.end(), K, nref);
      const double tol = 100 * ulp_offset / Rf;
      worst[0] = (std::max)(worst[0], compare(g, 1, tol, str("translation point ", q, ": ")));
      check((E(g.origin() - t - f.origin())).norm() <= 100 * ulp_offset, "translation: origin");
      check(line_angle(E(g.normal_direction()), E(f.normal_direction())) <= tol, "translation: normal");
    }
    // rotation (about the world origin; the kitten lies within 0.5 of it): rounding of the rotated
    // coordinates is ~1e-16 * 0.5 / Rf relative to Rf; 1e-10 leaves room for the conditioning.
    {
      std::vector<Point> moved;
      for(const Point& p : pts) moved.push_back(P(Q * E(p - CGAL::ORIGIN)));
      Fitting ft;
      const Form g = ft(moved.begin(), moved.end(), K, V(Q * E(nref)));
      const double tol = 1e-10;
      worst[1] = (std::max)(worst[1], compare(g, 1, tol, str("rotation point ", q, ": ")));
      check((E(g.normal_direction()) - Q * E(f.normal_direction())).norm() <= tol, "rotation: normal");
      check((E(g.origin() - CGAL::ORIGIN) - Q * E(f.origin() - CGAL::ORIGIN)).norm() <= tol * Rf, "rotation: origin");
      // an eigenvector moves by about (eigenvalue error) / (eigenvalue gap)
      const double kmax = (std::max)({std::abs(c.k1), std::abs(c.k2), 1 / Rf});
      if(c.k1 - c.k2 > 1e-3 / Rf)
        check(line_angle(E(g.maximal_principal_direction()), Q * E(f.maximal_principal_direction())) <=
                  tol * kmax / (c.k1 - c.k2),
                "rotation: principal direction");
    }
    // uniform scaling by lambda: curvatures x 1/lambda, |f_{k,n}| x lambda^{1-k}, Rf x lambda.
    {
      std::vector<Point> moved;
      for(const Point& p : pts) moved.push_back(P(lambda * E(p - CGAL::ORIGIN)));
      Fitting ft;
      const Form g = ft(moved.begin(), moved.end(), K, nref);
      worst[2] = (std::max)(worst[2], compare(g, lambda, 1e-10, str("scaling point ", q, ": ")));
      for(int kk = 0; kk <= int(K); ++kk)
        for(int n = -kk; n <= kk; n += 2)
        {
          const double a = std::abs(g.coefficient(kk, n)), b = std::abs(f.coefficient(kk, n)) * std::pow(lambda, 1 - kk);
          check(std::abs(a - b) <= 1e-10 * std::pow(Rf * lambda, 1 - kk), "scaling: |f_{k,n}| x lambda^{1-k}");
        }
    }
    // permutation of the neighbors (query stays first): only rounding changes.
    {
      std::vector<Point> moved = pts;
      std::shuffle(moved.begin() + 1, moved.end(), rng);
      Fitting ft;
      const Form g = ft(moved.begin(), moved.end(), K, nref);
      worst[3] = (std::max)(worst[3], compare(g, 1, 1e-10, str("permutation point ", q, ": ")));
      check((E(g.first_tangent_direction()) - E(f.first_tangent_direction())).norm() <= 1e-8 ||
                (E(g.first_tangent_direction()) + E(f.first_tangent_direction())).norm() <= 1e-8,
              "permutation: first tangent axis moved");
    }
    // phase: rotate the set by mu about the frame normal through the query. The new fit's axis u'
    // rotated back by -mu makes an angle nu with u (about n): 0, or pi if the PCA eigenvector
    // changed sign; then f'_{k,n} = f_{k,n} e^{i n nu} (doc/Wavejets/Mathematics.txt section 1).
    {
      const Vector3d n = E(f.frame_normal_direction()), p0 = E(pts[0] - CGAL::ORIGIN);
      const Matrix3d Rm = Eigen::AngleAxisd(mu, n).toRotationMatrix();
      std::vector<Point> moved;
      for(const Point& p : pts) moved.push_back(P(p0 + Rm * (E(p - CGAL::ORIGIN) - p0)));
      Fitting ft;
      const Form g = ft(moved.begin(), moved.end(), K, V(Rm * E(nref)));
      compare(g, 1, 1e-10, str("phase rotation point ", q, ": "));
      const Vector3d u = E(f.first_tangent_direction()), v = E(f.second_tangent_direction());
      const Vector3d ub = Rm.transpose() * E(g.first_tangent_direction());
      const double nu = std::atan2(ub.dot(v), ub.dot(u));
      check(line_angle(Rm.transpose() * E(g.frame_normal_direction()), n) <= 1e-10, "phase: frame normal");
      double w = 0;
      for(int kk = 0; kk <= int(K); ++kk)
        for(int nn = -kk; nn <= kk; nn += 2)
          w = (std::max)(w, std::abs(g.coefficient(kk, nn) - f.coefficient(kk, nn) * std::polar(1.0, nn * nu)) *
                              std::pow(Rf, kk - 1));
      worst[4] = (std::max)(worst[4], w / 1e-10);
      check(w <= 1e-10, str("phase point ", q, ": f'_{k,n} != f_{k,n} e^{i n nu}, nu = ", nu, ", error ", w));
    }
  }
  std::cout << "  worst error / tolerance: translation " << worst[0] << " (tol 100 ulp(1e6)/Rf), rotation "
            << worst[1] << ", scaling " << worst[2] << ", permutation " << worst[3] << ", phase " << worst[4]
            << " (tol 1e-10)" << std::endl;
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 5. Stability of the corrected fit under a perturbed seed normal (paper Fig. 4)

void test_stability()
{
  begin_section("5. stability under seed-normal perturbation (SEED_FRAME, 3 corrections)");
  std::mt19937_64 rng(5);
  const std::size_t K = 4;
  struct Case { const char* name; double a, b, R, h; };
  // sphere of radius R (outward normal) and paraboloid z = a x^2 + b y^2
  for(const Case& cs : {Case{"sphere", 0, 0, 1.0, 0.3}, Case{"paraboloid", 0.8, 0.3, 0, 0.4}})
  {
    const Local_frame F = random_frame(rng, Vector3d(0.5, 1.5, -0.5));
    std::function<double(double, double)> z;
    Truth truth;
    if(cs.R > 0)
    {
      const double R = cs.R;
      z = [R](double x, double y) { return -(R - std::sqrt(R * R - x * x - y * y)); };
      truth.H = truth.k1 = truth.k2 = -1 / R;
      truth.K = 1 / (R * R);
    }
    else
    {
      const double a = cs.a, b = cs.b;
      z = [a, b](double x, double y) { return a * x * x + b * y * y; };
      truth.H = a + b;
      truth.K = 4 * a * b;
      truth.k1 = 2 * (std::max)(a, b);
      truth.k2 = 2 * (std::min)(a, b);
    }
    const double f20_true = truth.H / 2, f22_true = (truth.k1 - truth.k2) / 8; // k1 - k2 = 8 |f_{2,2}|
    const std::vector<Point> pts = sample_graph(F, z, cs.h, disk_pattern(rng, 60));
    Fitting_options opt;
    opt.normal_use = Normal_use::SEED_FRAME;
    opt.correction_iterations = 3;
    opt.curvature_frame = Curvature_frame::TANGENT_FRAME;
    Fitting fitting(opt);
    Fitting_options iopt = opt;
    iopt.curvature_frame = Curvature_frame::INITIAL_FRAME;
    Fitting ifitting(iopt);
    const Form f0 = fitting(pts.begin(), pts.end(), K, V(F.n));
    // The reference fit error: the unperturbed fit (seeded with the exact normal) vs the truth,
    // for the curvatures and |f_{2,0}|, |f_{2,2}|. A polynomial of degree <= K fitted in its own
    // frame is exact (error ~1e-16), so the error of the default fit (PCA frame, orienting normal)
    // is also measured and the larger one is used: that is the accuracy the fit offers anyway.
    Fitting dfit;
    const Form fd = dfit(pts.begin(), pts.end(), K, V(F.n));
    auto err_truth = [&](const Form& f) {
      return (std::max)({curv_abs_err(curv(f), curv(truth)), 4 * std::abs(std::abs(f.coefficient(2, 0)) - std::abs(f20_true)),
                         8 * std::abs(std::abs(f.coefficient(2, 2)) - f22_true)});
    };
    const double e0 = (std::max)(err_truth(f0), err_truth(fd));
    double worst_tan = 0, worst_init = 0, worst_tilt = 0;
    for(double deg : {5., 10., 15., 20.})
      for(int az = 0; az < 6; ++az)
      {
        const double g = deg * PI / 180, a = 2 * PI * az / 6;
        const Vector3d axis = std::cos(a) * F.u + std::sin(a) * F.v;
        const Vector3d seed = Eigen::AngleAxisd(g, axis) * F.n;
        const Form f = fitting(pts.begin(), pts.end(), K, V(seed));
        const Form fi = ifitting(pts.begin(), pts.end(), K, V(seed));
        check(f.is_valid() && f.order() == K, "fit failed");
        const double d = (std::max)({curv_abs_err(curv(f), curv(f0)),
                                     4 * std::abs(std::abs(f.coefficient(2, 0)) - std::abs(f0.coefficient(2, 0))),
                                     8 * std::abs(std::abs(f.coefficient(2, 2)) - std::abs(f0.coefficient(2, 2)))});
        worst_tan = (std::max)(worst_tan, d);
        worst_init = (std::max)(worst_init, curv_abs_err(curv(fi), curv(f0)));
        worst_tilt = (std::max)(worst_tilt, CGAL::to_double(f.tangent_plane_residual()));
        // within twice the reference fit error
        check(d <= 2 * e0, str(cs.name, " seed tilted ", deg, " deg azimuth ", az, ": change ", d, " > 2 x fit error ", e0));
      }
    std::cout << "  " << cs.name << ": reference fit error " << e0 << " (seeded exact: " << err_truth(f0)
              << ", default: " << err_truth(fd) << "); worst change with tilted seed: TANGENT_FRAME " << worst_tan
              << ", INITIAL_FRAME " << worst_init << "; worst residual |f11| " << worst_tilt << std::endl;
  }
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 6. Adaptive order and failure states

void test_adaptive_order_and_failures()
{
  begin_section("6. adaptive order and failure states");
  std::mt19937_64 rng(6);
  Torus tor;
  // largest K <= 6 with L >= 1.1 (K+1)(K+2)/2, in exact integer arithmetic: 10 L >= 11 B
  auto expected_order = [](std::size_t L) {
    for(std::size_t K = 6; K >= 2; --K)
      if(10 * L >= 11 * nb_coeffs(K)) return K;
    return std::size_t(0);
  };
  for(std::size_t L : {7, 8, 10, 11, 12, 16, 17, 23, 24, 30, 31, 45, 100})
  {
    const std::vector<Point> pts = tor.patch(0.4, 0.9, 0.6, disk_pattern(rng, int(L - 1)));
    Fitting fitting;
    const Form f = fitting(pts.begin(), pts.end(), 6);
    std::cout << "  L=" << L << ": order " << f.order() << " (expected " << expected_order(L) << ")" << std::endl;
    check(f.is_valid() && f.order() == expected_order(L) && f.number_of_points() == L,
            str("L=", L, ": order ", f.order(), " expected ", expected_order(L)));
  }
  {
    // a larger beta lowers the order; the requested order is an upper bound
    const std::vector<Point> pts = tor.patch(0.4, 0.9, 0.6, disk_pattern(rng, 39));
    Fitting_options opt;
    opt.neighbors_per_coefficient = 2.0; // 40 >= 2 * 15 (K=4), 40 < 2 * 21
    Fitting fitting(opt);
    check(fitting(pts.begin(), pts.end(), 6).order() == 4, "beta = 2: order");
    Fitting dflt;
    check(dflt(pts.begin(), pts.end(), 3).order() == 3, "requested order is an upper bound");
  }

  auto expect_failure = [&](const std::vector<Point>& pts, Fit_status st, const std::string& tag, bool origin_is_query,
                            const Vector* normal = nullptr, Fitting_options opt = Fitting_options()) {
    Fitting fitting(opt);
    const Form f = normal ? fitting(pts.begin(), pts.end(), 2, *normal) : fitting(pts.begin(), pts.end(), 2);
    check(!f.is_valid() && f.status() == st, tag + str(": status '", CGAL::Wavejets::fit_status_name(f.status()),
                                                         "' expected '", CGAL::Wavejets::fit_status_name(st), "'"));
    check(f.order() == 0, tag + ": order not 0");
    if(origin_is_query) check(!pts.empty() && f.origin() == pts[0], tag + ": origin is not the query point");
    check(!form_has_nan(f), tag + ": NaN or infinity in the form");
    check(f.coefficients().empty() || *std::max_element(f.coefficients().begin(), f.coefficients().end()) == 0,
            tag + ": coefficients not 0");
  };
  std::vector<Point> base = tor.patch(0.4, 0.9, 0.6, disk_pattern(rng, 30));
  for(std::size_t L = 0; L <= 6; ++L)
  {
    // 6 points: 6 < 1.1 * 6, still too few for K = 2
    const std::vector<Point> pts(base.begin(), base.begin() + L);
    expect_failure(pts, Fit_status::TOO_FEW_POINTS, str(L, " points"), L > 0);
  }
  expect_failure(std::vector<Point>(20, base[3]), Fit_status::DEGENERATE_NEIGHBORHOOD, "identical points", true);
  {
    std::vector<Point> line;
    for(int i = 0; i < 20; ++i) line.push_back(Point(1 + 0.1 * i, 2 - 0.05 * i, 0.5 + 0.2 * i));
    expect_failure(line, Fit_status::DEGENERATE_NEIGHBORHOOD, "collinear points", true);
    // 4 distinct points repeated: 20 points but rank 4 < 6 unknowns
    std::vector<Point> four;
    for(int i = 0; i < 20; ++i) four.push_back(base[i % 4]);
    expect_failure(four, Fit_status::DEGENERATE_NEIGHBORHOOD, "4 distinct points repeated", true);
  }
  {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    std::vector<Point> pts = base;
    pts[5] = Point(pts[5].x(), nan, pts[5].z());
    expect_failure(pts, Fit_status::NON_FINITE_INPUT, "NaN neighbor coordinate", true);
    pts = base;
    pts[7] = Point(inf, pts[7].y(), pts[7].z());
    expect_failure(pts, Fit_status::NON_FINITE_INPUT, "infinite neighbor coordinate", true);
    const Vector bad(nan, 0, 1);
    Fitting_options seed;
    seed.normal_use = Normal_use::SEED_FRAME;
    expect_failure(base, Fit_status::NON_FINITE_INPUT, "NaN seed normal", true, &bad, seed);
    expect_failure(base, Fit_status::NON_FINITE_INPUT, "NaN orienting normal", true, &bad);
    // NaN query: the status is right; origin() is the (non-finite) query point itself.
    pts = base;
    pts[0] = Point(nan, pts[0].y(), pts[0].z());
    Fitting fitting;
    const Form f = fitting(pts.begin(), pts.end(), 2);
    check(!f.is_valid() && f.status() == Fit_status::NON_FINITE_INPUT, "NaN query: status");
  }
  {
    // a default-constructed form is invalid and NaN-free; a planar neighborhood is fine (H = 0)
    const Form f;
    check(!f.is_valid() && f.order() == 0 && !form_has_nan(f), "default form");
    std::vector<Point> plane;
    for(const Eigen::Vector2d& q : disk_pattern(rng, 30)) plane.push_back(Point(q.x(), q.y(), 0.25 * q.x() - 0.5 * q.y()));
    Fitting fitting;
    const Form g = fitting(plane.begin(), plane.end(), 4);
    check(g.is_valid() && std::abs(curv(g).H) <= 1e-12 && std::abs(curv(g).K) <= 1e-12, "planar neighborhood");
  }
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 7. pca_basis(), condition_number(), operator<<

// The number written after `label` in `text` (first occurrence after position `from`).
template <class X>
bool read_after(const std::string& text, const std::string& label, X& x, std::size_t from = 0)
{
  const std::size_t at = text.find(label, from);
  if(at == std::string::npos) return false;
  std::istringstream in(text.substr(at + label.size()));
  return bool(in >> x);
}
bool read_vector_after(const std::string& text, const std::string& label, Vector3d& v)
{
  const std::size_t at = text.find(label);
  if(at == std::string::npos) return false;
  std::istringstream in(text.substr(at + label.size()));
  return bool(in >> v.x() >> v.y() >> v.z());
}

// operator<<: writes the status, order, number of points, Rf, corrections, |f11| residual,
// origin, normal, frame, H, K_G, k1, d1, k2, d2 and every f_{k,n}, as documented; read back
// with 17 digits, each value must be the accessor's exactly.
void check_stream_output(const Torus& tor, std::mt19937_64& rng)
{
  const std::vector<Point> pts = tor.patch(0.4, 1.1, 0.5, disk_pattern(rng, 40));
  Fitting fitting;
  const Form f = fitting(pts.begin(), pts.end(), 4);
  std::ostringstream os;
  os.precision(17);
  os << f;
  const std::string t = os.str();
  check(t.rfind("Wavejet form: success", 0) == 0, "operator<<: first line is not 'Wavejet form: success'");
  std::size_t order = 0, points = 0, corrections = 0;
  double radius = 0, residual = 0, H = 0, KG = 0, k1 = 0, k2 = 0;
  Vector3d o, n, u, v, fn, d1, d2;
  bool ok = read_after(t, "order: ", order) && read_after(t, "points: ", points) &&
            read_after(t, "radius Rf: ", radius) && read_after(t, "corrections: ", corrections) &&
            read_after(t, "|f11| residual: ", residual) && read_after(t, "mean curvature: ", H) &&
            read_after(t, "gaussian curvature: ", KG) && read_after(t, "k1: ", k1) && read_after(t, "k2: ", k2) &&
            read_vector_after(t, "origin: ", o) && read_vector_after(t, "normal: ", n) &&
            read_vector_after(t, "frame u: ", u) && read_vector_after(t, "frame v: ", v) &&
            read_vector_after(t, "frame n: ", fn) && read_vector_after(t, "d1: ", d1) &&
            read_vector_after(t, "d2: ", d2);
  check(ok, "operator<<: a documented field is missing:\n" + t);
  check(order == f.order() && points == f.number_of_points() && corrections == f.number_of_corrections() &&
            radius == f.radius() && residual == f.tangent_plane_residual(),
          "operator<<: order / points / Rf / corrections / residual differ from the accessors");
  check(H == f.mean_curvature() && KG == f.gaussian_curvature() && k1 == f.principal_curvatures(0) &&
            k2 == f.principal_curvatures(1),
          "operator<<: curvatures differ from the accessors");
  check(o == E(f.origin() - CGAL::ORIGIN) && n == E(f.normal_direction()) && u == E(f.first_tangent_direction()) &&
            v == E(f.second_tangent_direction()) && fn == E(f.frame_normal_direction()) &&
            d1 == E(f.maximal_principal_direction()) && d2 == E(f.minimal_principal_direction()),
          "operator<<: origin / normal / frame / principal directions differ from the accessors");
  int found = 0;
  for(int k = 0; k <= int(f.order()); ++k)
    for(int nn = -k; nn <= k; nn += 2)
    {
      cplx c;
      if(read_after(t, str("f(", k, ",", nn, ")="), c) && c == f.coefficient(k, nn)) ++found;
    }
  check(found == int(nb_coeffs(f.order())), str("operator<<: ", found, " of ", nb_coeffs(f.order()),
                                                  " coefficients f(k,n) written and equal to coefficient(k, n)"));
  check(t.find(str("f(", f.order() + 1, ",")) == std::string::npos, "operator<<: a coefficient beyond the order");
  // failed and default forms: the status name and order 0
  std::vector<Point> line;
  for(int i = 0; i < 20; ++i) line.push_back(Point(1 + 0.1 * i, 2 - 0.05 * i, 0.5 + 0.2 * i));
  std::ostringstream bad, none;
  bad << fitting(line.begin(), line.end(), 2);
  none << Form();
  check(bad.str().rfind(str("Wavejet form: ", CGAL::Wavejets::fit_status_name(Fit_status::DEGENERATE_NEIGHBORHOOD)), 0) == 0 &&
            bad.str().find("order: 0") != std::string::npos,
          "operator<<: failed form does not show its status and order 0:\n" + bad.str());
  check(none.str().rfind(str("Wavejet form: ", CGAL::Wavejets::fit_status_name(Fit_status::TOO_FEW_POINTS)), 0) == 0,
          "operator<<: default form does not show its status");
  std::cout << "  operator<< (17 digits), read back:\n" << t;
}

void test_accessors(const Kitten& kitten)
{
  begin_section("7. pca_basis(), condition_number(), operator<<");
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> U(0, 2 * PI);
  Torus tor;
  tor.Rot = random_rotation(rng);
  tor.T = Vector3d(10.0, -20.0, 5.0);
  std::vector<std::vector<Point>> hoods;
  for(std::size_t i = 0; i < 20 && !kitten.pts.empty(); ++i)
    hoods.push_back(kitten.neighborhood((i * 7919 + 3) % kitten.pts.size(), 40));
  for(int i = 0; i < 10; ++i)
  {
    const double phi = U(rng), psi = U(rng);
    hoods.push_back(tor.patch(phi, psi, 0.5, disk_pattern(rng, 40)));
  }

  double w_val = 0, w_vec = 0, w_cval = 0, w_cvec = 0, w_ortho = 0, w_frame = 0, w_cond = 0, max_cond = 0;
  for(const std::vector<Point>& pts : hoods)
    for(std::size_t corrections : {std::size_t(0), std::size_t(2)})
    {
      Fitting_options opt;
      opt.correction_iterations = corrections;
      Fitting fitting(opt);
      const Form f = fitting(pts.begin(), pts.end(), 4); // no normal: the frame is the PCA frame
      if(!check(f.is_valid() && f.order() == 4, "fit failed")) continue;
      const std::string tag = str(pts.size(), " points, ", corrections, " corrections: ");

      // pca_basis: eigenvalues descending, orthonormal direct eigenvectors.
      double lam[3];
      Vector3d vec[3];
      for(int i = 0; i < 3; ++i)
      {
        const std::pair<Fitting::FT, Fitting::Vector_3> b = fitting.pca_basis(std::size_t(i));
        lam[i] = b.first;
        vec[i] = E(b.second);
      }
      check(lam[0] >= lam[1] && lam[1] >= lam[2] && lam[2] >= 0, tag + str("eigenvalues not descending: ", lam[0], " ", lam[1], " ", lam[2]));
      double ortho = 0;
      for(int i = 0; i < 3; ++i)
      {
        ortho = (std::max)(ortho, std::abs(vec[i].norm() - 1));
        for(int j = i + 1; j < 3; ++j) ortho = (std::max)(ortho, std::abs(vec[i].dot(vec[j])));
      }
      w_ortho = (std::max)(w_ortho, ortho);
      check(ortho <= 1e-14, tag + str("eigenvectors not orthonormal: ", ortho));
      check(vec[0].cross(vec[1]).dot(vec[2]) > 0, tag + "eigenvector basis not direct");

      // Reference 1: Eigen on the covariance of the world coordinates about their mean, divided by
      // the number of points (CGAL's convention in Monge_via_jet_fitting::compute_PCA).
      Vector3d mean = Vector3d::Zero();
      for(const Point& p : pts) mean += E(p - CGAL::ORIGIN);
      mean /= double(pts.size());
      Matrix3d cov = Matrix3d::Zero();
      for(const Point& p : pts)
      {
        const Vector3d d = E(p - CGAL::ORIGIN) - mean;
        cov += d * d.transpose();
      }
      cov /= double(pts.size());
      Eigen::SelfAdjointEigenSolver<Matrix3d> eig(cov); // ascending
      // Reference 2: CGAL's Monge_via_jet_fitting::pca_basis on the same points.
      Monge monge;
      monge(pts.begin(), pts.end(), 4, 2);
      // Rounding. The reference above centers before squaring, like the package: agreement to a
      // few eps of lambda_0 (measured 8e-16): bound 1e-13. CGAL accumulates sum x^2/n - (sum x/n)^2
      // in world coordinates, which cancels: error ~ eps |x|^2 / lambda_0 with |x| ~ 23 (the torus
      // is translated by (10, -20, 5)) and lambda_0 ~ 0.06 (patches of radius 0.5): ~1e-12
      // (measured 2.9e-12): bound 1e-11. Eigenvalues are compared relative to lambda_0,
      // eigenvectors as angle x (gap to the other eigenvalues) / lambda_0 (Davis-Kahan), same bounds.
      for(int i = 0; i < 3; ++i)
      {
        const double ref = eig.eigenvalues()(2 - i), cref = monge.pca_basis(std::size_t(i)).first;
        const double gap = (std::min)(i == 0 ? 1e300 : lam[i - 1] - lam[i], i == 2 ? 1e300 : lam[i] - lam[i + 1]);
        const double dv = std::abs(lam[i] - ref) / lam[0], dc = std::abs(lam[i] - cref) / lam[0];
        const double av = line_angle(vec[i], eig.eigenvectors().col(2 - i)) * gap / lam[0];
        const double ac = line_angle(vec[i], E(monge.pca_basis(std::size_t(i)).second)) * gap / lam[0];
        w_val = (std::max)(w_val, dv);
        w_cval = (std::max)(w_cval, dc);
        w_vec = (std::max)(w_vec, av);
        w_cvec = (std::max)(w_cvec, ac);
        check(dv <= 1e-13 && dc <= 1e-11, tag + str("eigenvalue ", i, ": ", lam[i], " vs Eigen ", ref, ", CGAL ", cref));
        check(av <= 1e-13 && ac <= 1e-11, tag + str("eigenvector ", i, " off by (scaled) ", av, " / ", ac));
      }
      if(corrections == 0)
      {
        // Without re-fit and without a normal, the form's frame is the PCA basis itself.
        const double df = (std::max)({(E(f.first_tangent_direction()) - vec[0]).norm(),
                                      (E(f.second_tangent_direction()) - vec[1]).norm(),
                                      (E(f.frame_normal_direction()) - vec[2]).norm()});
        w_frame = (std::max)(w_frame, df);
        check(df <= 1e-15, tag + str("frame is not the PCA basis: ", df));
      }

      // condition_number: the ratio of extreme singular values of the kept fit's rescaled system.
      // Reference: the design matrix built here from the definition (doc/Wavejets/Mathematics.txt section 2),
      // in the form's final frame, coordinates (q - p) / Rf, columns r^k, r^k cos n theta,
      // r^k sin n theta (n = k mod 2, n <= k), and its JacobiSVD.
      {
        const Vector3d p = E(pts[0] - CGAL::ORIGIN), u = E(f.first_tangent_direction()),
                       v = E(f.second_tangent_direction());
        const double Rf = f.radius();
        const int K = int(f.order());
        Eigen::MatrixXd A(pts.size(), nb_coeffs(K));
        for(std::size_t l = 0; l < pts.size(); ++l)
        {
          const Vector3d d = (E(pts[l] - CGAL::ORIGIN) - p) / Rf;
          const double x = d.dot(u), y = d.dot(v), r = std::sqrt(x * x + y * y), t = std::atan2(y, x);
          int c = 0;
          for(int k = 0; k <= K; ++k)
            for(int n = k % 2; n <= k; n += 2)
            {
              A(Eigen::Index(l), c++) = std::pow(r, k) * (n == 0 ? 1. : std::cos(n * t));
              if(n > 0) A(Eigen::Index(l), c++) = std::pow(r, k) * std::sin(n * t);
            }
        }
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
        const Eigen::VectorXd sv = svd.singularValues();
        const double ref = sv(0) / sv(sv.size() - 1), got = fitting.condition_number();
        // Both are computed in double from the same points (QR then SVD of R, versus SVD of A):
        // they agree to ~eps x cond relative (measured 2.4e-16 x cond); bound 1e-14 x cond.
        const double e = std::abs(got - ref) / ref;
        w_cond = (std::max)(w_cond, e / ref);
        max_cond = (std::max)(max_cond, ref);
        check(got >= 1 && e <= 1e-14 * ref, tag + str("condition number ", got, " vs SVD of the design matrix ", ref));
      }
    }
  {
    // condition_number() is 0 before any fit and when compute_condition_number is false.
    const std::vector<Point>& pts = hoods.back();
    Fitting fresh;
    check(fresh.condition_number() == 0, "condition number before any fit");
    Fitting_options opt;
    opt.compute_condition_number = false;
    Fitting off(opt);
    check(off(pts.begin(), pts.end(), 4).is_valid() && off.condition_number() == 0,
            "condition number with compute_condition_number == false");
  }
  std::cout << "  pca_basis: worst eigenvalue difference / lambda_0: Eigen " << w_val << ", CGAL " << w_cval
            << " (bounds 1e-13, 1e-11; no scaling difference with CGAL: both divide the covariance by the number of points,"
            << " in world units); eigenvector angle x gap / lambda_0: Eigen " << w_vec << ", CGAL " << w_cvec
            << " (bounds 1e-13, 1e-11); orthonormality " << w_ortho << " (bound 1e-14); frame vs PCA basis " << w_frame
            << " (bound 1e-15)" << std::endl;
  std::cout << "  condition_number: worst relative difference to the SVD of the design matrix / cond " << w_cond
            << " (bound 1e-14), largest cond " << max_cond << std::endl;

  check_stream_output(tor, rng);
  end_section();
}

// ---------------------------------------------------------------------------------------------
// 9. Tangent-plane search at a lower order (Fitting_options::tangent_plane_order, the default 2 of
// wavejet_estimate_normals): the plane is found with order-2 fits, then one order-K fit in it.

bool same_form(const Form& a, const Form& b)
{
  if(a.is_valid() != b.is_valid() || a.order() != b.order() || a.number_of_corrections() != b.number_of_corrections())
    return false;
  return a.coefficients() == b.coefficients() && a.normal_direction() == b.normal_direction() &&
         a.frame_normal_direction() == b.frame_normal_direction() &&
         a.first_tangent_direction() == b.first_tangent_direction() && a.mean_curvature() == b.mean_curvature() &&
         a.gaussian_curvature() == b.gaussian_curvature() && a.tangent_plane_residual() == b.tangent_plane_residual();
}

void test_low_order_tangent_search(const Kitten& kitten)
{
  begin_section("9. tangent-plane search at order 2 (tangent_plane_order), then one order-K fit");
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<Eigen::Vector2d> pattern;
  while(pattern.size() < 96)
  {
    const Eigen::Vector2d q(U(rng), U(rng));
    if(q.squaredNorm() <= 1) pattern.push_back(q);
  }
  Torus torus;
  torus.Rot = random_rotation(rng);
  const double h = 0.3;
  Fitting_options full, low = full, low_tangent = full;
  low.tangent_plane_order = 2;
  low_tangent.tangent_plane_order = 2;
  low_tangent.curvature_frame = Curvature_frame::TANGENT_FRAME;
  Fitting_options high = full, no_correction = full, no_correction_low = full;
  no_correction.correction_iterations = 0;
  no_correction_low.correction_iterations = 0;
  no_correction_low.tangent_plane_order = 2;
  Fitting f_full(full), f_low(low), f_low_tangent(low_tangent), f_nc(no_correction), f_nc_low(no_correction_low);
  double se_full[2] = {0, 0}, se_low[2] = {0, 0}, se_monge[2] = {0, 0};
  double max_residual = 0;
  int n = 0;
  bool same_high = true, same_nc = true, same_curvature = true, valid = true;
  for(int s = 0; s < 40; ++s)
  {
    const double phi = 2 * PI * (s + 0.5) / 40, psi = 2 * PI * std::fmod(0.37 * s, 1.);
    const std::vector<Point> pts = torus.patch(phi, psi, h, pattern);
    const Truth t = torus.truth(phi, psi);
    for(int o = 0; o < 2; ++o)
    {
      const std::size_t K = o == 0 ? 4 : 6;
      high.tangent_plane_order = K; // >= the order: the full-order search
      Fitting f_high(high);
      const Form a = f_full(pts.begin(), pts.end(), K, V(t.normal));
      const Form b = f_low(pts.begin(), pts.end(), K, V(t.normal));
      const Form c = f_low_tangent(pts.begin(), pts.end(), K, V(t.normal));
      valid = valid && a.is_valid() && b.is_valid() && c.is_valid() && b.order() == K;
      if(!a.is_valid() || !b.is_valid() || !c.is_valid()) continue;
      same_high = same_high && same_form(a, f_high(pts.begin(), pts.end(), K, V(t.normal)));
      same_nc = same_nc && same_form(f_nc(pts.begin(), pts.end(), K, V(t.normal)),
                                     f_nc_low(pts.begin(), pts.end(), K, V(t.normal)));
      // INITIAL_FRAME curvature: the same full-order fit in the PCA frame in both searches.
      same_curvature = same_curvature && a.mean_curvature() == b.mean_curvature() &&
                       a.principal_curvatures(0) == b.principal_curvatures(0) &&
                       a.principal_curvatures(1) == b.principal_curvatures(1);
      // The normal (frame, coefficients) does not depend on the curvature frame.
      same_curvature = same_curvature && b.normal_direction() == c.normal_direction() && b.coefficients() == c.coefficients();
      const double ea = line_angle(E(a.normal_direction()), t.normal), eb = line_angle(E(b.normal_direction()), t.normal);
      Monge monge;
      const Monge_form m = monge(pts.begin(), pts.end(), K, 2);
      const double em = line_angle(E(m.normal_direction()), t.normal);
      se_full[o] += ea * ea;
      se_low[o] += eb * eb;
      se_monge[o] += em * em;
      max_residual = (std::max)(max_residual, CGAL::to_double(b.tangent_plane_residual()));
    }
    ++n;
  }
  check(valid && n == 40, "every fit valid at its order");
  check(same_high, "tangent_plane_order >= the order: the same form as the default search (bitwise)");
  check(same_nc, "correction_iterations 0: tangent_plane_order changes nothing (bitwise)");
  check(same_curvature, "INITIAL_FRAME curvatures equal the default search's, and the normal does not depend on the "
                          "curvature frame (bitwise)");
  for(int o = 0; o < 2; ++o)
  {
    const double rf = std::sqrt(se_full[o] / n), rl = std::sqrt(se_low[o] / n), rm = std::sqrt(se_monge[o] / n);
    std::cout << "  K = " << (o == 0 ? 4 : 6) << ": RMS normal error (sin) full-order search " << rf
              << ", order-2 search " << rl << ", CGAL jet " << rm << std::endl;
    // The order-2 search feeds an order-K fit whose normal keeps its residual tilt: its error is
    // that of an order-K fit in a plane close to the tangent plane, like the full-order search's
    // and CGAL's PCA-frame jet's (measured on these patches: 0.97 and 0.94 times the full-order
    // search's at K = 4 and 6, 0.96 and 0.64 times CGAL's). Bound: 1.2x both.
    check(rl <= 1.2 * rf && rl <= 1.2 * rm, str("K = ", o == 0 ? 4 : 6, ": order-2 search normal error ", rl,
                                                   " vs full-order ", rf, ", CGAL ", rm));
  }
  // The plane found at order 2 is close to the order-K tangent plane: the residual tilt |f_{1,1}|
  // of the order-K fit in it stays small (measured 1.7e-3 on these patches, h/r = 0.3; the bound
  // 1e-2 is a regression bound: a search that failed would leave tilts of the PCA plane, ~h/r).
  std::cout << "  largest residual tilt |f_{1,1}| of the order-K fit in the order-2 plane: " << max_residual << std::endl;
  check(max_residual <= 1e-2, str("residual tilt of the order-K fit in the order-2 plane: ", max_residual));

  // Adaptive order: with 25 points K 6 is lowered to 5 ((5+1)(5+2)/2 = 21 unknowns x 1.1 <= 25) and
  // the order-2 search still runs; with 8 points (order 2 only) the search order equals the order.
  if(check(!kitten.pts.empty(), "kitten not loaded"))
  {
    for(std::size_t q : {100u, 2000u, 4000u})
    {
      const std::vector<Point> pts25 = kitten.neighborhood(q, 25), pts8 = kitten.neighborhood(q, 8);
      const Form a = f_low(pts25.begin(), pts25.end(), 6), b = f_full(pts25.begin(), pts25.end(), 6);
      check(a.is_valid() && a.order() == 5 && b.order() == 5 && !form_has_nan(a),
              str("kitten point ", q, ", 25 points: order ", a.order()));
      const Form c = f_low(pts8.begin(), pts8.end(), 6), d = f_full(pts8.begin(), pts8.end(), 6);
      check(c.is_valid() && c.order() == 2 && same_form(c, d), str("kitten point ", q, ", 8 points: order 2, as the default"));
    }
  }
  end_section();
}

// Order-2 fits without a condition number (the point-set functions' setting) solve their systems
// from the moments, without building them (least_squares.h, order2_least_squares()); with it (the
// class's default), by the QR of the built system. Both agree on real neighborhoods; on nearly
// collinear ones the moments' guards refuse every system, and the QR's result comes out bit for bit.
void test_order2_moments(const Kitten& kitten)
{
  begin_section("10. order-2 fits from the moments vs the QR of the built system");
  Fitting_options moments_options, qr_options;
  moments_options.compute_condition_number = false;
  Fitting moments(moments_options), qr(qr_options);
  double worst_coefficient = 0., worst_normal = 0.;
  std::size_t compared = 0;
  if(check(!kitten.pts.empty(), "kitten not loaded"))
    for(std::size_t q = 0; q < kitten.pts.size(); q += 97)
      for(std::size_t size : {std::size_t(18), std::size_t(100)})
      {
        const std::vector<Point> pts = kitten.neighborhood(q, size);
        const Form a = moments(pts.begin(), pts.end(), 2), b = qr(pts.begin(), pts.end(), 2);
        if(!check(a.is_valid() && b.is_valid() && a.order() == b.order() &&
                    a.number_of_corrections() == b.number_of_corrections(),
                  str("kitten point ", q, ", ", size, " points: both fits valid, same order and re-fits")))
          continue;
        double largest = 0., difference = 0.;
        for(std::size_t j = 0; j < a.coefficients().size(); ++j)
        {
          largest = (std::max)(largest, std::abs(b.coefficients()[j]));
          difference = (std::max)(difference, std::abs(a.coefficients()[j] - b.coefficients()[j]));
        }
        worst_coefficient = (std::max)(worst_coefficient, difference / largest);
        worst_normal = (std::max)(worst_normal, std::sqrt(CGAL::squared_distance(CGAL::ORIGIN + a.normal_direction(),
                                                                                 CGAL::ORIGIN + b.normal_direction())));
        ++compared;
      }
  std::cout << "  " << compared << " kitten neighborhoods (18 and 100 points): coefficients within " << worst_coefficient
            << " relative, normals within " << worst_normal << std::endl;
  check(compared > 100 && worst_coefficient <= 1e-10 && worst_normal <= 1e-12,
        str("moments vs QR: coefficients ", worst_coefficient, " relative (<= 1e-10), normals ", worst_normal,
            " (<= 1e-12)"));

  // Nearly collinear neighborhoods (within 1e-4 of a line, on a parabola): refused, the QR decides.
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> U(-1, 1);
  bool same = true;
  for(int t = 0; t < 20; ++t)
  {
    std::vector<Point> pts(1, Point(0, 0, 0));
    for(int l = 0; l < 40; ++l)
    {
      const double x = U(rng);
      pts.push_back(Point(x, 1e-4 * U(rng), x * x));
    }
    same = same && same_form(moments(pts.begin(), pts.end(), 2), qr(pts.begin(), pts.end(), 2));
  }
  check(same, "nearly collinear neighborhoods: the same fit as the QR's, bit for bit (the moments refuse them)");
  end_section();
}

// The PCA's eigen-decomposition (fitting_core.h, symmetric_eigen_3()): Eigen's closed form where it
// is as accurate as the iterative QR, else the iterative QR. On matrices Q diag(lambda) Q^T of known
// spectrum, from well separated eigenvalues to equal ones (planes, isotropic disks, lines, a point):
// every result within the bounds of a backward-stable solver (eigenvalues within 32 eps |A|_F,
// each eigenvector within 32 eps |A|_F over its gap, orthonormal columns); well separated
// spectra keep the closed form (bit for bit computeDirect's), and close ones that the closed
// form gets wrong beyond those bounds take the iterative solver (bit for bit compute()'s).
void test_pca_eigen_decomposition()
{
  begin_section("11. the PCA's eigen-decomposition: closed form, guarded");
  namespace WI = CGAL::Wavejets::internal;
  const double eps = std::numeric_limits<double>::epsilon();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> G(0., 1.);
  std::size_t closed_form = 0, iterative = 0, separated = 0, separated_closed_form = 0, direct_beyond_bounds = 0;
  double worst_value = 0., worst_orthogonality = 0.;
  bool all_solved = true, one_or_the_other = true;
  // Spectra (ascending), times a scale: the relative gaps of the two largest (disks), of the two
  // smallest (lines) and exact repetitions.
  std::vector<Vector3d> spectra;
  for(double gap : {0.5, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 0.})
  {
    spectra.push_back(Vector3d(1e-3, 0.5, 0.5 * (1. + gap))); // a disk
    spectra.push_back(Vector3d(0., 0.3, 0.3 * (1. + gap)));   // a flat disk
    spectra.push_back(Vector3d(1e-4, 1e-4 * (1. + gap), 1.)); // a line
  }
  spectra.push_back(Vector3d(0., 0., 1.));
  spectra.push_back(Vector3d(1., 1., 1.));
  spectra.push_back(Vector3d(0., 0., 0.));
  spectra.push_back(Vector3d(1e-3, 0.2, 0.7));
  for(const Vector3d& spectrum : spectra)
    for(double scale : {1., 1e-20, 1e20})
      for(int t = 0; t < 50; ++t)
      {
        const Eigen::Quaterniond q(G(rng), G(rng), G(rng), G(rng));
        const Matrix3d Q = q.normalized().toRotationMatrix();
        const Vector3d lambda = scale * spectrum;
        const Matrix3d A = Q * lambda.asDiagonal() * Q.transpose();
        Vector3d values;
        Matrix3d vectors;
        if(!WI::symmetric_eigen_3(A, values, vectors)) { all_solved = false; continue; }
        Eigen::SelfAdjointEigenSolver<Matrix3d> direct, qr;
        direct.computeDirect(A);
        qr.compute(A);
        auto same = [&](const Eigen::SelfAdjointEigenSolver<Matrix3d>& e) {
          for(int i = 0; i < 3; ++i)
            for(int j = 0; j < 3; ++j)
              if(!wavejets_test::same_bits(vectors(i, j), e.eigenvectors()(i, j)) ||
                 !wavejets_test::same_bits(values(i), e.eigenvalues()(i)))
                return false;
          return true;
        };
        const bool took_direct = same(direct), took_qr = same(qr);
        closed_form += took_direct;
        iterative += took_qr && !took_direct;
        one_or_the_other = one_or_the_other && (took_direct || took_qr);
        // Within a backward-stable solver's bounds: |lambda_i - true| <= 32 eps |A|_F, eigenvector i
        // within 32 eps |A|_F / gap_i of the true one (Davis-Kahan; no bound for repeated eigenvalues).
        const double bound = 32. * eps * A.norm();
        auto beyond_bounds = [&](const Vector3d& vals, const Matrix3d& vecs) {
          double worst = 0.;
          for(int i = 0; i < 3; ++i)
          {
            worst = (std::max)(worst, std::abs(vals(i) - lambda(i)) / bound);
            const double gap = (std::min)(i > 0 ? lambda(i) - lambda(i - 1) : 1e300, i < 2 ? lambda(i + 1) - lambda(i) : 1e300);
            if(gap > 0.)
              worst = (std::max)(worst, line_angle(vecs.col(i), Q.col(i)) * gap / bound);
          }
          return worst;
        };
        const double worst = beyond_bounds(values, vectors);
        worst_value = (std::max)(worst_value, worst);
        worst_orthogonality =
          (std::max)(worst_orthogonality, (vectors.transpose() * vectors - Matrix3d::Identity()).cwiseAbs().maxCoeff());
        direct_beyond_bounds += beyond_bounds(direct.eigenvalues(), direct.eigenvectors()) > 1.;
        const double smallest_gap = (std::min)(lambda(1) - lambda(0), lambda(2) - lambda(1));
        if(smallest_gap > 1e-2 * lambda(2))
        {
          ++separated;
          separated_closed_form += took_direct;
        }
      }
  std::cout << "  " << closed_form + iterative << " matrices: closed form kept for " << closed_form << ", iterative for "
            << iterative << "; the closed form alone beyond the bounds on " << direct_beyond_bounds
            << "; worst error / bound " << worst_value << ", orthogonality " << worst_orthogonality << std::endl;
  check(all_solved, "every matrix decomposed");
  check(one_or_the_other, "the result is the closed form's or the iterative solver's, bit for bit");
  check(worst_value <= 1., str("eigenvalues and eigenvectors within the backward-stable bounds: worst ", worst_value,
                               " of the bound"));
  check(worst_orthogonality <= 8. * eps, str("orthonormal eigenvectors: ", worst_orthogonality));
  check(separated > 0 && separated_closed_form == separated,
        str("well separated spectra keep the closed form: ", separated_closed_form, " of ", separated));
  check(direct_beyond_bounds > 0 && iterative > 0,
        str("the guard matters: the closed form alone misses the bounds on ", direct_beyond_bounds,
            " matrices (close eigenvalues); ", iterative, " go to the iterative solver"));

  // Not finite: refused.
  Matrix3d A = Matrix3d::Identity();
  A(0, 1) = A(1, 0) = std::numeric_limits<double>::quiet_NaN();
  Vector3d values;
  Matrix3d vectors;
  check(!WI::symmetric_eigen_3(A, values, vectors), "a NaN entry: refused");
  end_section();
}

} // namespace

int main(int argc, char** argv)
{
  std::cout.precision(4);
  using wavejets_test::Case;
  return wavejets_test::run_cases(argc, argv, {
    Case{"analytic.exact_recovery", test_exact_recovery},
    Case{"analytic.surfaces", test_analytic_surfaces},
    Case{"analytic.convergence_rate", test_convergence},
    Case{"cgal.monge_cross_check", [] { test_cgal_cross_check(kitten()); }},
    Case{"invariances", [] { test_invariances(kitten()); }},
    Case{"stability.seed_normal_perturbation", test_stability},
    Case{"failures.adaptive_order_and_failure_states", test_adaptive_order_and_failures},
    Case{"accessors", [] { test_accessors(kitten()); }},
    Case{"tangent_plane_order", [] { test_low_order_tangent_search(kitten()); }},
    Case{"solver.order2_moments", [] { test_order2_moments(kitten()); }},
    Case{"solver.pca_eigen_decomposition", test_pca_eigen_decomposition},
  });
}
