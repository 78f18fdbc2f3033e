// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_DIFFERENTIAL_QUANTITIES_H
#define CGAL_WAVEJETS_INTERNAL_DIFFERENTIAL_QUANTITIES_H

// Curvatures and principal directions of a height field z = f(x, y) over a frame (u, v, n),
// from its derivatives at the origin (exact graph formulas, valid in any frame; doc/Wavejets/Mathematics.txt §3).

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// First and second derivatives of the height at the origin of the parameterization plane.
struct Height_derivatives
{
  double fx = 0., fy = 0., fxx = 0., fxy = 0., fyy = 0.;
};

/// Reads the derivatives from the real unknowns (fx = alpha_{1,1}, fy = beta_{1,1},
/// fxx = 2(f_{2,0} + alpha_{2,2}), fyy = 2(f_{2,0} - alpha_{2,2}), fxy = 2 beta_{2,2}).
/// `inverse_radius` converts second derivatives from rescaled to world units (1/Rf).
inline Height_derivatives height_derivatives(const double* c, std::size_t order, double inverse_radius)
{
  Height_derivatives d;
  if(order >= 1) { d.fx = c[1]; d.fy = c[2]; }
  if(order >= 2)
  {
    d.fxx = 2. * (c[3] + c[4]) * inverse_radius;
    d.fyy = 2. * (c[3] - c[4]) * inverse_radius;
    d.fxy = 2. * c[5] * inverse_radius;
  }
  return d;
}

/// Curvature information at a point, signs relative to the frame normal n
/// (a surface bending toward +n has H > 0).
struct Curvature_info
{
  double mean = 0., gaussian = 0., k1 = 0., k2 = 0.; // k1 >= k2
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   // unit normal of the graph, n . normal > 0
  Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), d2 = Eigen::Vector3d::Zero(); // (d1, d2, normal) direct
};

/// Curvature of the graph z = f(x, y) over the orthonormal direct frame (u, v, n).
inline Curvature_info graph_curvature(const Height_derivatives& d,
                                      const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                                      const Eigen::Vector3d& n)
{
  Curvature_info ci;
  const double g = 1. + d.fx * d.fx + d.fy * d.fy;
  const double sg = std::sqrt(g);
  ci.gaussian = (d.fxx * d.fyy - d.fxy * d.fxy) / (g * g);
  ci.mean = ((1. + d.fy * d.fy) * d.fxx + (1. + d.fx * d.fx) * d.fyy - 2. * d.fx * d.fy * d.fxy) / (2. * g * sg);
  ci.normal = (n - d.fx * u - d.fy * v) / sg;

  // Principal curvatures and directions: the second fundamental form II = Hessian / sqrt(g) in an
  // orthonormal basis (e1, e2) of the tangent plane (Gram-Schmidt on the graph's tangents
  // t1 = u + fx n, t2 = v + fy n; first fundamental form E, F, G), a symmetric matrix [a b; b c].
  // Its eigenvalues are (a + c)/2 +- sqrt(((a - c)/2)^2 + b^2): no cancellation near umbilics,
  // unlike H +- sqrt(H^2 - K_G). (a + c)/2 is H.
  const double E = 1. + d.fx * d.fx, F = d.fx * d.fy;
  const double L = d.fxx / sg, M = d.fxy / sg, N = d.fyy / sg;
  const double a = L / E;
  const double b = (M - L * F / E) / sg;
  const double c = (E / g) * (L * F * F / (E * E) - 2. * M * F / E + N);
  const double disc = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  ci.k1 = ci.mean + disc;
  ci.k2 = ci.mean - disc;
  const Eigen::Vector3d t1 = u + d.fx * n, t2 = v + d.fy * n;
  const Eigen::Vector3d e1 = t1 / std::sqrt(E);
  const Eigen::Vector3d e2 = (t2 - (F / E) * t1) * std::sqrt(E / g);
  const double phi = 0.5 * std::atan2(2. * b, a - c); // eigenvector of the larger eigenvalue (0 at umbilics)
  ci.d1 = (std::cos(phi) * e1 + std::sin(phi) * e2).normalized();
  ci.d2 = ci.normal.cross(ci.d1).normalized();
  return ci;
}

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_DIFFERENTIAL_QUANTITIES_H
