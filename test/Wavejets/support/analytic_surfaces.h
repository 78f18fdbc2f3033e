// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_TEST_ANALYTIC_SURFACES_H
#define WAVEJETS_TEST_ANALYTIC_SURFACES_H

// Surfaces with exact normals and curvatures, uniform samplers, perturbations and error metrics,
// shared by the tests (test_accuracy, test_hermite) and the benchmarks (bench_accuracy,
// bench_ponca_accuracy: their CMake target has test/Wavejets/support on its include path).
// Header-only, depends on Eigen and the standard library only.
//
// Conventions (those of the package, doc/Wavejets/Mathematics.txt §3): normals point outward; curvature
// signs are relative to that normal, a surface bending toward the normal is positive, so a
// sphere of radius R has H = -1/R, K_G = 1/R^2, k1 = k2 = -1/R; k1 >= k2.
// Every surface lies in [-1, 1]^3 with its largest half-extent equal to 1.
//
// Uniform sampling (density constant per unit area):
// - sphere: normalized Gaussian vectors (exact);
// - cylinder: uniform angle and height (exact, the area element is constant);
// - torus and the paper's shape: area-weighted rejection sampling in their parametrization
//   (exact: a parameter sample is accepted with probability dA / max dA);
// - ellipsoid and Goursat surface (implicit, no convenient parametrization): thin-shell sampling.
//   Uniform points of the bounding box are kept when the first-order distance |F|/|grad F| is
//   below eps, then projected onto F = 0 by Newton steps along the gradient. The volume of a
//   symmetric shell of half-width eps over an area element dA is 2 eps dA (1 + K_G eps^2 / 3),
//   so the density is uniform up to a relative O(K_G eps^2) (< 1e-4 here, eps = 3e-3).

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace wavejets_bench {

typedef Eigen::Vector3d V3;
typedef Eigen::Matrix3d M3;

/// Exact differential quantities at a surface point (outward normal, package sign convention).
struct Truth
{
  V3 normal = V3::UnitZ();
  double H = 0., K = 0., k1 = 0., k2 = 0.;
};

/// A sample: position (possibly perturbed later), the exact quantities of the surface point it
/// came from, and whether it counts in the error statistics.
struct Sample
{
  V3 p = V3::Zero();
  Truth truth;
  double boundary_distance = std::numeric_limits<double>::infinity(); // to the surface's border
  bool inlier = true;                                                  // false for outliers
};

/// Any unit vector orthogonal to n.
inline V3 orthogonal_unit(const V3& n)
{
  V3 a = std::abs(n.x()) < 0.9 ? V3::UnitX() : V3::UnitY();
  return (a - a.dot(n) * n).normalized();
}

/// Curvatures from the second fundamental form II (2x2, in an orthonormal tangent basis),
/// II(t, t) = normal curvature along t (positive toward the normal).
inline Truth truth_from_second_form(const V3& normal, double II11, double II12, double II22)
{
  Truth t;
  t.normal = normal;
  t.H = 0.5 * (II11 + II22);
  t.K = II11 * II22 - II12 * II12;
  const double d = std::sqrt(0.25 * (II11 - II22) * (II11 - II22) + II12 * II12);
  t.k1 = t.H + d;
  t.k2 = t.H - d;
  return t;
}

/// Exact quantities of the implicit surface F = 0 (F < 0 inside) from grad F and Hess F:
/// n = grad/|grad|, and on the surface x''.n = -t^T Hess t / |grad| for a unit tangent t.
inline Truth implicit_truth(const V3& grad, const M3& hess)
{
  const double g = grad.norm();
  const V3 n = grad / g;
  const V3 t1 = orthogonal_unit(n), t2 = n.cross(t1);
  return truth_from_second_form(n, -t1.dot(hess * t1) / g, -t1.dot(hess * t2) / g, -t2.dot(hess * t2) / g);
}

/// Base class of the analytic surfaces.
class Surface
{
public:
  virtual ~Surface() {}
  virtual std::string name() const = 0;
  /// N samples with a uniform density per unit area (fixed seed: reproducible).
  virtual std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const = 0;
  /// Exact quantities at a point of the surface.
  virtual Truth truth(const V3& p) const = 0;
  /// A level function: 0 on the surface, negative inside, locally a defining function (used by
  /// the finite-difference checks).
  virtual double level(const V3& p) const = 0;
  /// Distance from a surface point to the surface's border (infinity for closed surfaces).
  virtual double boundary_distance(const V3&) const { return std::numeric_limits<double>::infinity(); }
  /// The surface point an off-surface point (e.g. a noisy or denoised sample) is compared with:
  /// the exact closest point for the sphere, cylinder and torus; the generators' Newton projection
  /// along the gradient for the other implicit surfaces (ellipsoid, Goursat: the closest point up
  /// to O(curvature * distance^2)); the radial projection for the paper's shape (its parametrization).
  virtual V3 surface_point(const V3& p) const = 0;

protected:
  Sample make_sample(const V3& p) const
  {
    Sample s;
    s.p = p;
    s.truth = truth(p);
    s.boundary_distance = boundary_distance(p);
    return s;
  }
};

/// Implicit surface with analytic gradient and Hessian.
class Implicit_surface : public Surface
{
public:
  virtual V3 gradient(const V3& p) const = 0;
  virtual M3 hessian(const V3& p) const = 0;
  Truth truth(const V3& p) const override { return implicit_truth(gradient(p), hessian(p)); }

  V3 surface_point(const V3& p) const override { return project(p); }

  /// Newton projection along the gradient onto F = 0.
  V3 project(V3 x) const
  {
    for(int it = 0; it < 60; ++it)
    {
      const double f = level(x);
      const V3 g = gradient(x);
      const double g2 = g.squaredNorm();
      if(!(g2 > 0.)) break;
      const V3 step = f / g2 * g;
      x -= step;
      if(step.norm() < 1e-15) break;
    }
    return x;
  }

  /// Thin-shell sampling (see the file comment) in the box [-h, h].
  std::vector<Sample> shell_sample(std::size_t N, std::uint64_t seed, const V3& h, double eps) const
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1., 1.);
    std::vector<Sample> out;
    out.reserve(N);
    while(out.size() < N)
    {
      const V3 x(h.x() * U(rng), h.y() * U(rng), h.z() * U(rng));
      const V3 g = gradient(x);
      const double gn = g.norm();
      if(!(gn > 0.) || std::abs(level(x)) >= eps * gn) continue;
      const V3 p = project(x);
      if(std::abs(level(p)) > 1e-12 * (1. + gradient(p).norm())) continue; // Newton did not converge
      out.push_back(make_sample(p));
    }
    return out;
  }
};

/// Unit sphere.
class Sphere : public Implicit_surface
{
public:
  std::string name() const override { return "sphere"; }
  double level(const V3& p) const override { return p.squaredNorm() - 1.; }
  V3 gradient(const V3& p) const override { return 2. * p; }
  M3 hessian(const V3&) const override { return 2. * M3::Identity(); }
  V3 surface_point(const V3& p) const override { return p.normalized(); }
  std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const override
  {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> G(0., 1.);
    std::vector<Sample> out;
    out.reserve(N);
    while(out.size() < N)
    {
      const V3 x(G(rng), G(rng), G(rng));
      if(x.norm() < 1e-6) continue;
      out.push_back(make_sample(x.normalized()));
    }
    return out;
  }
};

/// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1, semi-axes (1, 0.7, 0.5).
class Ellipsoid : public Implicit_surface
{
public:
  V3 axes = V3(1., 0.7, 0.5);
  std::string name() const override { return "ellipsoid"; }
  double level(const V3& p) const override { return p.cwiseQuotient(axes).squaredNorm() - 1.; }
  V3 gradient(const V3& p) const override { return 2. * p.cwiseQuotient(axes.cwiseProduct(axes)); }
  M3 hessian(const V3&) const override
  {
    return (2. * V3(1. / (axes.x() * axes.x()), 1. / (axes.y() * axes.y()), 1. / (axes.z() * axes.z()))).asDiagonal();
  }
  std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const override
  {
    return shell_sample(N, seed, axes * 1.01, 3e-3);
  }
};

/// The torus ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) of axis z in its
/// parametrization, with the outward normal and its exact curvatures and principal directions
/// (the one closed form of the torus of the tests and benchmarks). Curvatures w.r.t. the outward
/// normal (the torus bends away from it): along the parallel (d/du) -cos v / (R + r cos v), along
/// the meridian (d/dv) -1/r.
struct Parametric_torus
{
  double R = 3., r = 1.;
  V3 point(double u, double v) const
  {
    const double w = R + r * std::cos(v);
    return V3(w * std::cos(u), w * std::sin(u), r * std::sin(v));
  }
  V3 outward_normal(double u, double v) const
  {
    return V3(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
  }
  double parallel_curvature(double v) const { return -std::cos(v) / (R + r * std::cos(v)); }
  double meridian_curvature() const { return -1. / r; }
  double mean_curvature(double v) const { return 0.5 * (parallel_curvature(v) + meridian_curvature()); }
  double gaussian_curvature(double v) const { return parallel_curvature(v) * meridian_curvature(); }
  V3 parallel_direction(double u) const { return V3(-std::sin(u), std::cos(u), 0.); }
  V3 meridian_direction(double u, double v) const
  {
    return V3(-std::sin(v) * std::cos(u), -std::sin(v) * std::sin(u), std::cos(v));
  }
};

/// Torus of axis z: (sqrt(x^2+y^2) - R)^2 + z^2 = r^2, R = 0.7, r = 0.3.
class Torus : public Implicit_surface
{
public:
  double R = 0.7, r = 0.3;
  std::string name() const override { return "torus"; }
  double level(const V3& p) const override
  {
    const double rho = std::hypot(p.x(), p.y());
    return (rho - R) * (rho - R) + p.z() * p.z() - r * r;
  }
  V3 gradient(const V3& p) const override
  {
    const double rho = std::hypot(p.x(), p.y());
    const double s = 2. * (rho - R) / rho;
    return V3(s * p.x(), s * p.y(), 2. * p.z());
  }
  M3 hessian(const V3& p) const override
  {
    const double rho = std::hypot(p.x(), p.y());
    const double e[2] = {p.x() / rho, p.y() / rho};
    M3 H = M3::Zero();
    for(int i = 0; i < 2; ++i)
      for(int j = 0; j < 2; ++j)
        H(i, j) = 2. * e[i] * e[j] + 2. * (rho - R) * ((i == j ? 1. : 0.) - e[i] * e[j]) / rho;
    H(2, 2) = 2.;
    return H;
  }
  V3 surface_point(const V3& p) const override
  {
    const double rho = std::hypot(p.x(), p.y());
    const V3 c(R * p.x() / rho, R * p.y() / rho, 0.); // nearest point of the core circle
    return c + r * (p - c).normalized();
  }
  /// Exact area-weighted sampling: angle u uniform, tube angle v accepted with probability
  /// (R + r cos v) / (R + r) (the area element is r (R + r cos v) du dv).
  std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const override
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0., 1.);
    std::vector<Sample> out;
    out.reserve(N);
    while(out.size() < N)
    {
      const double u = 2. * M_PI * U(rng), v = 2. * M_PI * U(rng);
      if(U(rng) * (R + r) > R + r * std::cos(v)) continue;
      out.push_back(make_sample(Parametric_torus{R, r}.point(u, v)));
    }
    return out;
  }
};

/// Open cylinder x^2 + y^2 = r^2, r = 0.5, |z| <= 1 (no caps; points near the rims are excluded
/// from the statistics by the benchmark through boundary_distance()).
class Cylinder : public Implicit_surface
{
public:
  double r = 0.5, half_height = 1.;
  std::string name() const override { return "cylinder"; }
  double level(const V3& p) const override { return p.x() * p.x() + p.y() * p.y() - r * r; }
  V3 gradient(const V3& p) const override { return V3(2. * p.x(), 2. * p.y(), 0.); }
  M3 hessian(const V3&) const override { return V3(2., 2., 0.).asDiagonal(); }
  double boundary_distance(const V3& p) const override { return half_height - std::abs(p.z()); }
  V3 surface_point(const V3& p) const override
  {
    const double rho = std::hypot(p.x(), p.y());
    return V3(r * p.x() / rho, r * p.y() / rho, std::max(-half_height, std::min(half_height, p.z())));
  }
  std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const override
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0., 1.);
    std::vector<Sample> out;
    out.reserve(N);
    while(out.size() < N)
    {
      const double u = 2. * M_PI * U(rng), z = half_height * (2. * U(rng) - 1.);
      out.push_back(make_sample(V3(r * std::cos(u), r * std::sin(u), z)));
    }
    return out;
  }
};

/// Goursat's quartic x^4 + y^4 + z^4 + a (x^2+y^2+z^2)^2 + b (x^2+y^2+z^2) + c = 0 with
/// a = 0, b = -5, c = 11.8 (the "tanglecube": one smooth closed surface of genus 5 with elliptic,
/// hyperbolic (saddle) and parabolic regions), scaled by 1/s to fit [-1, 1]^3:
/// F(x) = G(s x), grad F = s grad G(s x), Hess F = s^2 Hess G(s x).
class Goursat : public Implicit_surface
{
public:
  double a = 0., b = -5., c = 11.8;
  double s; // scale: native half-extent
  Goursat()
  {
    // half-extent along x: the largest root of x^4 - 5 x^2 + 2 min_y(y^4 - 5 y^2) + c = 0 (a = 0)
    const double m = -b * b / 4.; // min of t^2 + b t
    const double q = 2. * m + c;
    s = std::sqrt((-b + std::sqrt(b * b - 4. * q)) / 2.);
  }
  std::string name() const override { return "goursat"; }
  double G(const V3& x) const
  {
    const double S = x.squaredNorm();
    return std::pow(x.x(), 4) + std::pow(x.y(), 4) + std::pow(x.z(), 4) + a * S * S + b * S + c;
  }
  double level(const V3& p) const override { return G(s * p); }
  V3 gradient(const V3& p) const override
  {
    const V3 x = s * p;
    const double S = x.squaredNorm();
    V3 g;
    for(int i = 0; i < 3; ++i) g(i) = 4. * x(i) * x(i) * x(i) + 4. * a * S * x(i) + 2. * b * x(i);
    return s * g;
  }
  M3 hessian(const V3& p) const override
  {
    const V3 x = s * p;
    const double S = x.squaredNorm();
    M3 H = 8. * a * x * x.transpose();
    for(int i = 0; i < 3; ++i) H(i, i) += 12. * x(i) * x(i) + 4. * a * S + 2. * b;
    return s * s * H;
  }
  std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const override
  {
    return shell_sample(N, seed, V3(1.01, 1.01, 1.01), 3e-3);
  }
};

/// The paper's test shape: r(phi) = 1 + A cos(w phi^2), A = 0.005, w = 100/pi, in spherical
/// coordinates with phi the polar angle (colatitude, 0 at +z) and theta the azimuth: a surface of
/// revolution about z with ripples whose frequency grows from 0 at the north pole to 200 rad/rad at
/// the south pole. Scaled by 1/(1 + A) into [-1, 1]^3. Exact quantities from the profile curve
/// (rho(phi), z(phi)) = r(phi) (sin phi, cos phi) with analytic first and second derivatives.
class Paper_shape : public Surface
{
public:
  double A = 0.005, w = 100. / M_PI;
  double scale() const { return 1. / (1. + A); }
  std::string name() const override { return "paper_shape"; }

  double radius(double phi) const { return scale() * (1. + A * std::cos(w * phi * phi)); }

  /// Position, normal and curvatures at (phi, theta).
  void evaluate(double phi, double theta, V3& p, Truth& t) const
  {
    const double sc = scale();
    const double arg = w * phi * phi;
    const double r = sc * (1. + A * std::cos(arg));
    const double r1 = -sc * A * std::sin(arg) * 2. * w * phi;
    const double r2 = -sc * A * (std::cos(arg) * 4. * w * w * phi * phi + std::sin(arg) * 2. * w);
    const double sp = std::sin(phi), cp = std::cos(phi);
    const double rho = r * sp, rho1 = r1 * sp + r * cp, rho2 = r2 * sp + 2. * r1 * cp - r * sp;
    const double z1 = r1 * cp - r * sp, z2 = r2 * cp - 2. * r1 * sp - r * cp;
    const double len = std::sqrt(rho1 * rho1 + z1 * z1);
    const double Nr = -z1 / len, Nz = rho1 / len; // outward normal in the (rho, z) half-plane
    const double ct = std::cos(theta), st = std::sin(theta);
    p = V3(rho * ct, rho * st, r * cp);
    const double km = (rho2 * Nr + z2 * Nz) / (len * len); // meridian normal curvature
    const double kp = -Nr / rho;                            // parallel normal curvature
    t.normal = V3(Nr * ct, Nr * st, Nz);
    t.H = 0.5 * (km + kp);
    t.K = km * kp;
    t.k1 = std::max(km, kp);
    t.k2 = std::min(km, kp);
  }
  double polar_angle(const V3& p) const { return std::atan2(std::hypot(p.x(), p.y()), p.z()); }
  Truth truth(const V3& p) const override
  {
    V3 q;
    Truth t;
    evaluate(polar_angle(p), std::atan2(p.y(), p.x()), q, t);
    return t;
  }
  double level(const V3& p) const override { return p.norm() - radius(polar_angle(p)); }
  V3 surface_point(const V3& p) const override { return radius(polar_angle(p)) * p.normalized(); }
  /// Exact area-weighted rejection: propose (phi, theta) uniform on the unit sphere (density
  /// sin phi), accept with probability (r |X'(phi)| sin phi / sin phi) / bound; r |X'| =
  /// r sqrt(r'^2 + r^2) <= bound.
  std::vector<Sample> sample(std::size_t N, std::uint64_t seed) const override
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0., 1.);
    const double sc = scale();
    const double rmax = sc * (1. + A), dr_max = sc * A * 2. * w * M_PI;
    const double bound = rmax * std::sqrt(rmax * rmax + dr_max * dr_max);
    std::vector<Sample> out;
    out.reserve(N);
    while(out.size() < N)
    {
      const double phi = std::acos(1. - 2. * U(rng)), theta = 2. * M_PI * U(rng);
      const double arg = w * phi * phi;
      const double r = sc * (1. + A * std::cos(arg)), r1 = -sc * A * std::sin(arg) * 2. * w * phi;
      if(U(rng) * bound > r * std::sqrt(r * r + r1 * r1)) continue;
      V3 p;
      Truth t;
      evaluate(phi, theta, p, t);
      Sample s;
      s.p = p;
      s.truth = t;
      out.push_back(s);
    }
    return out;
  }
};

/// All benchmark surfaces, in table order.
inline std::vector<std::unique_ptr<Surface> > all_surfaces()
{
  std::vector<std::unique_ptr<Surface> > s;
  s.emplace_back(new Sphere);
  s.emplace_back(new Ellipsoid);
  s.emplace_back(new Torus);
  s.emplace_back(new Cylinder);
  s.emplace_back(new Goursat);
  s.emplace_back(new Paper_shape);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Perturbations (each with its own seed; the truth stays that of the unperturbed surface point).

/// Axis-aligned bounding-box diagonal of the samples.
inline double bounding_box_diagonal(const std::vector<Sample>& s)
{
  V3 lo = V3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for(const Sample& x : s) { lo = lo.cwiseMin(x.p); hi = hi.cwiseMax(x.p); }
  return (hi - lo).norm();
}

/// Isotropic Gaussian position noise: every coordinate gets N(0, sigma^2).
inline void add_position_noise(std::vector<Sample>& s, double sigma, std::uint64_t seed)
{
  if(sigma <= 0.) return;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> G(0., sigma);
  for(Sample& x : s)
  {
    const double dx = G(rng), dy = G(rng), dz = G(rng);
    x.p += V3(dx, dy, dz);
  }
}

/// Turns a fraction of the samples into outliers: each is moved by a uniformly random vector of
/// the ball of radius `radius` and excluded from the statistics (it has no truth).
inline void add_outliers(std::vector<Sample>& s, double fraction, double radius, std::uint64_t seed)
{
  if(fraction <= 0.) return;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(-1., 1.), U01(0., 1.);
  for(Sample& x : s)
  {
    if(U01(rng) >= fraction) continue;
    V3 d;
    do { d = V3(U(rng), U(rng), U(rng)); } while(d.squaredNorm() > 1.);
    x.p += radius * d;
    x.inlier = false;
  }
}

/// Unit normal tilted from `n` by an angle |N(0, sigma)| * sqrt(2) in a uniformly random
/// direction (the tangent components are independent N(0, sigma^2), sigma in radians).
inline V3 perturb_normal(const V3& n, double sigma, std::mt19937_64& rng)
{
  if(sigma <= 0.) return n;
  std::normal_distribution<double> G(0., sigma);
  const V3 t1 = orthogonal_unit(n), t2 = n.cross(t1);
  const double a = G(rng), b = G(rng);
  const double angle = std::sqrt(a * a + b * b);
  if(angle == 0.) return n;
  const V3 dir = (a * t1 + b * t2) / angle;
  return std::cos(angle) * n + std::sin(angle) * dir;
}

// ---------------------------------------------------------------------------------------------
// Error metrics.

/// Unoriented angle between two directions, in degrees.
inline double unoriented_angle_degrees(const V3& a, const V3& b)
{
  const V3 u = a.normalized(), v = b.normalized();
  return std::atan2(u.cross(v).norm(), std::abs(u.dot(v))) * 180. / M_PI; // accurate for tiny angles too
}

/// Root mean square of the differences (0 for empty input).
inline double rmse(const std::vector<double>& estimate, const std::vector<double>& truth)
{
  if(estimate.empty()) return 0.;
  double s = 0.;
  for(std::size_t i = 0; i < estimate.size(); ++i) s += (estimate[i] - truth[i]) * (estimate[i] - truth[i]);
  return std::sqrt(s / double(estimate.size()));
}

/// q-quantile (0 <= q <= 1) by linear interpolation between order statistics.
inline double quantile(std::vector<double> v, double q)
{
  if(v.empty()) return 0.;
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const std::size_t i = std::size_t(pos);
  if(i + 1 >= v.size()) return v.back();
  return v[i] + (pos - double(i)) * (v[i + 1] - v[i]);
}

/// Accumulates per-point estimates against the truth.
struct Error_accumulator
{
  std::vector<double> H, K, k1, k2, tH, tK, tk1, tk2, angles;
  std::size_t failed = 0; // evaluation points where the estimator gave nothing

  void add_curvature(double h, double k, double a1, double a2, const Truth& t)
  {
    H.push_back(h); K.push_back(k); k1.push_back(a1); k2.push_back(a2);
    tH.push_back(t.H); tK.push_back(t.K); tk1.push_back(t.k1); tk2.push_back(t.k2);
  }
  void add_normal(const V3& n, const Truth& t) { angles.push_back(unoriented_angle_degrees(n, t.normal)); }
  double rmse_H() const { return rmse(H, tH); }
  double rmse_K() const { return rmse(K, tK); }
  double rmse_k1() const { return rmse(k1, tk1); }
  double rmse_k2() const { return rmse(k2, tk2); }
  double mean_angle() const
  {
    double s = 0.;
    for(double a : angles) s += a;
    return angles.empty() ? 0. : s / double(angles.size());
  }
  double p95_angle() const { return quantile(angles, 0.95); }
};

// ---------------------------------------------------------------------------------------------
// Finite-difference check of the exact quantities (used by the tests).

/// Height z(x, y) of the surface over the tangent plane at p (frame t1, t2, n): the root of
/// level(p + x t1 + y t2 + z n) = 0 nearest to 0, by secant steps.
inline double height_over_plane(const Surface& S, const V3& p, const V3& t1, const V3& t2, const V3& n,
                                double x, double y)
{
  const V3 base = p + x * t1 + y * t2;
  double z0 = 0., z1 = 1e-6;
  double f0 = S.level(base + z0 * n), f1 = S.level(base + z1 * n);
  for(int it = 0; it < 100 && f1 != f0; ++it)
  {
    const double z2 = z1 - f1 * (z1 - z0) / (f1 - f0);
    z0 = z1; f0 = f1;
    z1 = z2; f1 = S.level(base + z1 * n);
    if(std::abs(z1 - z0) < 1e-16) break;
  }
  return z1;
}

/// Curvatures by central finite differences (step h) of the height over the exact tangent plane;
/// also returns the height gradient (0 if the exact normal is right) in `gradient`.
inline Truth finite_difference_truth(const Surface& S, const V3& p, double h, double gradient[2])
{
  const Truth exact = S.truth(p);
  const V3 n = exact.normal, t1 = orthogonal_unit(n), t2 = n.cross(t1);
  auto z = [&](double x, double y) { return height_over_plane(S, p, t1, t2, n, x, y); };
  const double z00 = z(0, 0);
  const double fx = (z(h, 0) - z(-h, 0)) / (2. * h), fy = (z(0, h) - z(0, -h)) / (2. * h);
  const double fxx = (z(h, 0) - 2. * z00 + z(-h, 0)) / (h * h);
  const double fyy = (z(0, h) - 2. * z00 + z(0, -h)) / (h * h);
  const double fxy = (z(h, h) - z(h, -h) - z(-h, h) + z(-h, -h)) / (4. * h * h);
  gradient[0] = fx;
  gradient[1] = fy;
  return truth_from_second_form(n, fxx, fxy, fyy); // gradient ~ 0: II = Hessian of the height
}

} // namespace wavejets_bench

#endif // WAVEJETS_TEST_ANALYTIC_SURFACES_H
