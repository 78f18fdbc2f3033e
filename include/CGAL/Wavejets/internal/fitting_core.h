// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_FITTING_CORE_H
#define CGAL_WAVEJETS_INTERNAL_FITTING_CORE_H

// The one Wavejet fitting core (doc/Wavejets/Mathematics.txt §2), shared by Wavejet_fitting and every
// point-set function. It works on neighbor offsets q_l - p in double precision, owns its
// scratch (grown, never shrunk: no heap allocation per point once warm) and is used by one
// thread at a time.

#include <CGAL/Wavejets/Fitting_options.h>
#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/differential_quantities.h>
#include <CGAL/Wavejets/internal/frame_kernels.h>
#include <CGAL/Wavejets/internal/least_squares.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// An orthonormal direct frame (u, v, n): theta = 0 along u, heights along n.
struct Frame
{
  Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = Eigen::Vector3d::UnitY(), n = Eigen::Vector3d::UnitZ();
};

/// Unit normal at the origin of the graph z(x, y) over `frame` whose slopes there are (fx, fy) =
/// (dz/dx, dz/dy): n - fx u - fy v, normalized. The one place of this formula (the tilted frame of
/// the correction, the normals the functions write, `Wavejet_form::normal_direction()`, the normal filter).
inline Eigen::Vector3d graph_normal(const Frame& frame, double fx, double fy)
{
  return (frame.n - fx * frame.u - fy * frame.v).normalized();
}

/// Result of Fitter::fit. The coefficients live in the Fitter (see Fitter::coefficients()).
struct Fit_result
{
  Fit_status status = Fit_status::TOO_FEW_POINTS;
  std::size_t order = 0;           // order actually fitted (after adaptive reduction)
  std::size_t number_of_points = 0;
  double radius = 0.;              // Rf
  Frame frame;                     // final (corrected) tangent frame
  Frame initial_frame;             // frame of the first fit (PCA or seed)
  Height_derivatives curvature_derivatives; // world units, in curvature_frame
  Frame curvature_frame;
  std::size_t corrections = 0;     // number of accepted re-fits
  double initial_tilt = 0., final_tilt = 0.; // |f_{1,1}| of the first and of the kept fit
  double condition_number = 0.;    // of the kept fit's (weighted, rescaled) system, if requested
  Eigen::Vector3d pca_values = Eigen::Vector3d::Zero(); // descending
  Eigen::Matrix3d pca_vectors = Eigen::Matrix3d::Identity(); // columns, matching pca_values

  bool success() const { return status == Fit_status::SUCCESS; }
};

/// The fitting core. One instance per thread; reuse it across points. Its members are scratch
/// buffers and the results of the last fit; the settings of a call are passed to each step.
class Fitter
{
public:
  /// Fits a Wavejet to the points `offsets[0..L-1]` given relative to the query point p (p itself,
  /// if part of the neighborhood, appears as a zero offset). `hint_normal` (may be null) orients
  /// the frame, or seeds it when `options.normal_use == SEED_FRAME`. `neighbor_normals` (may be
  /// null) holds a normal per offset (any length and sign; non-finite or zero ones are skipped):
  /// with `options.neighbor_normal_weight > 0`, every fit is the Hermite fit to heights and slopes.
  Fit_status fit(const Eigen::Vector3d* offsets, std::size_t L, std::size_t requested_order,
                 const Fitting_options& options, const Eigen::Vector3d* hint_normal, Fit_result& out,
                 const Eigen::Vector3d* neighbor_normals = nullptr)
  {
    out = Fit_result();
    out.number_of_points = L;
    const Fit_call call = make_call(options, L, neighbor_normals);
    Orders orders;
    double radius = 0.;
    const Fit_status admitted = admit(offsets, L, requested_order, options, hint_normal, orders, radius);
    if(admitted != Fit_status::SUCCESS)
      return fail(out, admitted);
    out.radius = radius;
    const double inv_radius = 1. / radius;
    rescale(offsets, L, inv_radius);
    Frame frame;
    if(!initial_frame(L, options, hint_normal, frame, out))
      return fail(out, Fit_status::DEGENERATE_NEIGHBORHOOD);
    out.initial_frame = frame;
    Frame_search search;
    Height_derivatives first_derivatives;
    if(!fit_and_search(call, orders, frame, hint_normal, inv_radius, out, search, first_derivatives))
      return fail(out, Fit_status::DEGENERATE_NEIGHBORHOOD);
    keep(search, orders.order, first_derivatives, inv_radius, options.curvature_frame, out);
    return out.status;
  }

  /// Real unknowns of the kept fit, in rescaled units (f^{rescaled}_{k,n} = f_{k,n} Rf^{k-1}),
  /// in the layout of basis.h. Valid until the next call of fit().
  const double* coefficients() const { return best_.data(); }

private:
  // The settings of one call of fit(), passed to the steps that read them (never stored).
  struct Fit_call
  {
    const Fitting_options& options;
    std::size_t L;                  // number of points
    double normal_weight;           // weight of the Hermite slope rows (0: none)
    const Eigen::Vector3d* normals; // the neighbors' normals, null without slope rows
    bool weighted() const { return normals || options.compact_weights; }
  };

  static Fit_call make_call(const Fitting_options& options, std::size_t L, const Eigen::Vector3d* neighbor_normals)
  {
    const double w = options.neighbor_normal_weight;
    const double normal_weight = w > 0. && std::isfinite(w) ? w : 0.;
    return Fit_call{options, L, normal_weight, normal_weight > 0. ? neighbor_normals : nullptr};
  }

  // The order to fit (lowered while the system is rank-deficient) and the lowest one accepted.
  struct Orders
  {
    std::size_t order = 0, minimum = 0;
  };

  struct Frame_search
  {
    Frame frame;
    double tilt = 0., condition = 0.;
    std::size_t corrections = 0;
  };

  Fit_status fail(Fit_result& out, Fit_status s)
  {
    out.status = s;
    out.order = 0;
    return s;
  }

  // Checks the input and chooses the orders and the radius Rf; SUCCESS or the reason of the failure.
  static Fit_status admit(const Eigen::Vector3d* offsets, std::size_t L, std::size_t requested_order,
                          const Fitting_options& options, const Eigen::Vector3d* hint_normal, Orders& orders,
                          double& radius)
  {
    if(requested_order < 1)
      return Fit_status::TOO_FEW_POINTS;
    if(hint_normal && !hint_normal->allFinite())
      return Fit_status::NON_FINITE_INPUT;
    // One pass without branches: `not_finite` stays 0 unless a coordinate is infinite or NaN
    // (x - x is NaN exactly then), and max2 is the largest squared norm.
    double max2 = 0., not_finite = 0.;
    for(std::size_t l = 0; l < L; ++l)
    {
      const Eigen::Vector3d& d = offsets[l];
      not_finite += (d.x() - d.x()) + (d.y() - d.y()) + (d.z() - d.z());
      const double d2 = d.squaredNorm();
      max2 = max2 < d2 ? d2 : max2;
    }
    if(not_finite != 0.)
      return Fit_status::NON_FINITE_INPUT;
    if(!choose_orders(L, requested_order, options, orders))
      return Fit_status::TOO_FEW_POINTS;
    radius = options.neighborhood_radius > 0 ? options.neighborhood_radius : std::sqrt(max2);
    if(!(radius > 0.) || !std::isfinite(radius))
      return Fit_status::DEGENERATE_NEIGHBORHOOD;
    if(radius < 1e-20 || radius > 1e20) // outputs in world units would overflow: Fit_status::OUT_OF_RANGE
      return Fit_status::OUT_OF_RANGE;
    return Fit_status::SUCCESS;
  }

  // Adaptive order: the largest order <= requested_order with at least beta points per unknown.
  // Returns false if it is below the minimum order.
  static bool choose_orders(std::size_t L, std::size_t requested_order, const Fitting_options& options, Orders& orders)
  {
    orders.minimum = (std::min)((std::max)(options.minimum_order, std::size_t(1)), requested_order);
    // Start from the largest order whose (K+1)(K+2)/2 unknowns fit in L points (beta >= 1): an
    // absurd requested order (e.g. 2^40) would overflow number_of_coefficients() and make the
    // one-by-one reduction below loop for ~2^40 steps. This cap changes no result.
    std::size_t max_order = 0;
    while(number_of_coefficients(max_order + 1) <= L) ++max_order;
    orders.order = (std::min)(requested_order, max_order);
    // beta < 1 or NaN (possible through Fitting_options; the functions reject it) reads as 1.
    const double beta = options.neighbors_per_coefficient >= 1. ? options.neighbors_per_coefficient : 1.;
    while(orders.order >= orders.minimum && double(L) < beta * double(number_of_coefficients(orders.order)))
      --orders.order;
    return orders.order >= orders.minimum && L > 0;
  }

  // Rescaled offsets into scaled_: all later work is in units of Rf. Stored coordinate by coordinate
  // (x, y, z columns of stride padded_rows(L), zero padding rows) for the vectorized loops.
  void rescale(const Eigen::Vector3d* offsets, std::size_t L, double inv_radius)
  {
    const std::size_t P = padded_rows(L);
    scaled_.resize(3 * P);
    for(std::size_t l = 0; l < L; ++l)
      for(int i = 0; i < 3; ++i) scaled_[i * P + l] = offsets[l][i] * inv_radius;
    for(std::size_t l = L; l < P; ++l)
      for(int i = 0; i < 3; ++i) scaled_[i * P + l] = 0.;
  }

  // The first fit and the tangent-plane search from `frame`; the kept fit goes to best_. The search
  // runs at the fit order, or at the lower tangent_plane_order: then one fit at the full order
  // follows, in the plane found (and, for the curvature of INITIAL_FRAME, one in the initial frame).
  // Returns false if no order >= orders.minimum can be fitted.
  bool fit_and_search(const Fit_call& call, Orders& orders, const Frame& frame, const Eigen::Vector3d* hint,
                      double inv_radius, Fit_result& out, Frame_search& search, Height_derivatives& first_derivatives)
  {
    const Fitting_options& options = call.options;
    std::size_t& order = orders.order;
    const std::size_t search_order =
      options.tangent_plane_order > 0 ? (std::min)(options.tangent_plane_order, order) : order;
    const bool low_order_search = search_order < order && options.correction_iterations > 0 &&
                                  fit_in_frame(call, search_order, frame, first_);
    if(!low_order_search)
    {
      // First fit, lowering the order while the system is rank-deficient, then the search.
      if(!fit_lowering_order(call, orders, frame, first_))
        return false;
      first_derivatives = height_derivatives(first_.data(), order, inv_radius);
      out.initial_tilt = tilt(first_.data(), order);
      search = search_tangent_frame(call, order, frame, hint);
      return true;
    }
    if(options.curvature_frame == Curvature_frame::INITIAL_FRAME)
    {
      if(!fit_lowering_order(call, orders, frame, trial_))
        return false;
      first_derivatives = height_derivatives(trial_.data(), order, inv_radius);
    }
    out.initial_tilt = tilt(first_.data(), search_order);
    search = search_tangent_frame(call, search_order, frame, hint);
    if(!fit_lowering_order(call, orders, search.frame, best_))
      return false;
    search.tilt = tilt(best_.data(), order);
    search.condition = condition_;
    return true;
  }

  // The shared tail of fit(): the kept frame, fit and curvature into `out`.
  void keep(const Frame_search& search, std::size_t order, const Height_derivatives& first_derivatives,
            double inv_radius, Curvature_frame curvature_frame, Fit_result& out) const
  {
    out.frame = search.frame;
    out.corrections = search.corrections;
    out.final_tilt = search.tilt;
    out.condition_number = search.condition;
    out.order = order;
    if(curvature_frame == Curvature_frame::INITIAL_FRAME)
    {
      out.curvature_derivatives = first_derivatives;
      out.curvature_frame = out.initial_frame;
    }
    else
    {
      out.curvature_derivatives = height_derivatives(best_.data(), order, inv_radius);
      out.curvature_frame = out.frame;
    }
    out.status = Fit_status::SUCCESS;
  }

  // Fits at orders.order in `frame`, lowering it (not below orders.minimum) while the system is
  // rank-deficient. Returns false if no order works.
  bool fit_lowering_order(const Fit_call& call, Orders& orders, const Frame& frame, std::vector<double>& c)
  {
    for(; orders.order >= orders.minimum; --orders.order) // minimum >= 1: no wrap-around
      if(fit_in_frame(call, orders.order, frame, c))
        return true;
    return false;
  }

  // Tangent-plane correction (doc/Wavejets/Mathematics.txt §2.5) from the fit first_ of order `order` in
  // `frame`: re-fit in the plane orthogonal to the fitted normal, at most
  // options.correction_iterations times, keep the fit with the smallest |f_{1,1}| (into best_),
  // stop as soon as a re-fit does not lower it. A corrected frame whose normal would point away
  // from the given normal `hint` (possible across sharp edges) is not taken: the frame keeps the
  // orientation the normal gave it.
  Frame_search search_tangent_frame(const Fit_call& call, std::size_t order, const Frame& frame,
                                    const Eigen::Vector3d* hint)
  {
    const std::size_t B = number_of_coefficients(order);
    Frame_search best;
    best_.assign(first_.begin(), first_.begin() + B);
    best.tilt = tilt(first_.data(), order);
    best.frame = frame;
    best.condition = condition_;
    for(std::size_t it = 0; it < call.options.correction_iterations && best.tilt > 0.; ++it)
    {
      const Frame corrected = tilted_frame(best.frame, best_.data(), order);
      if(hint && !(corrected.n.dot(*hint) > 0.))
        break;
      if(!fit_in_frame(call, order, corrected, trial_))
        break;
      const double t = tilt(trial_.data(), order);
      if(!(t < best.tilt))
        break;
      best_.assign(trial_.begin(), trial_.begin() + B);
      best.tilt = t;
      best.frame = corrected;
      best.condition = condition_;
      ++best.corrections;
    }
    return best;
  }

  static double tilt(const double* c, std::size_t order)
  {
    return order >= 1 ? 0.5 * std::sqrt(c[1] * c[1] + c[2] * c[2]) : 0.;
  }
  // PCA of the rescaled offsets (smallest eigenvalue: n), or the seed normal.
  bool initial_frame(std::size_t L, const Fitting_options& options, const Eigen::Vector3d* hint, Frame& f,
                     Fit_result& out)
  {
    // Covariance from the first and second moments, in one pass over the coordinates. The rescaled
    // offsets have norms at most 1: subtracting the mean's square costs about 1e-16 absolute.
    double sums[9];
    dispatch_avx<Moments_kernel>(static_cast<const double*>(scaled_.data()), L, static_cast<double*>(sums));
    Eigen::Vector3d mean;
    Eigen::Matrix3d cov;
    for(int i = 0, k = 0; i < 3; ++i)
    {
      mean(i) = sums[i] / double(L);
      for(int j = i; j < 3; ++j, ++k) cov(i, j) = sums[3 + k] / double(L);
    }
    for(int i = 0; i < 3; ++i)
      for(int j = i; j < 3; ++j) cov(j, i) = cov(i, j) = cov(i, j) - mean(i) * mean(j);
    Eigen::Vector3d values;  // ascending
    Eigen::Matrix3d vectors;
    if(!symmetric_eigen_3(cov, values, vectors))
      return false;
    const double s2 = out.radius * out.radius;
    out.pca_values = Eigen::Vector3d(values(2), values(1), values(0)) * s2;
    out.pca_vectors.col(0) = vectors.col(2);
    out.pca_vectors.col(1) = vectors.col(1);
    out.pca_vectors.col(2) = vectors.col(0);
    if(out.pca_vectors.determinant() < 0)
      out.pca_vectors.col(2) = -out.pca_vectors.col(2);

    if(hint && options.normal_use == Normal_use::SEED_FRAME)
    {
      const double len = hint->norm();
      if(!(len > 0.))
        return false;
      f.n = *hint / len;
      Eigen::Vector3d u = out.pca_vectors.col(0) - out.pca_vectors.col(0).dot(f.n) * f.n;
      if(u.norm() < 1e-6)
        u = f.n.unitOrthogonal();
      f.u = u.normalized();
      f.v = f.n.cross(f.u);
      return true;
    }
    f.u = out.pca_vectors.col(0);
    f.n = out.pca_vectors.col(2);
    if(hint && hint->dot(f.n) < 0.)
    {
      f.n = -f.n;
    }
    f.v = f.n.cross(f.u);
    return true;
  }

  // Frame rotated (minimal rotation) so that its normal is the fitted surface's normal at the origin.
  static Frame tilted_frame(const Frame& f, const double* c, std::size_t order)
  {
    if(order < 1) return f;
    const Eigen::Vector3d target = graph_normal(f, c[1], c[2]);
    const Eigen::Vector3d axis = f.n.cross(target);
    const double s = axis.norm(), co = f.n.dot(target);
    Frame r;
    r.n = target;
    if(s < 1e-300) return f;
    const Eigen::Vector3d k = axis / s;
    auto rotate = [&](const Eigen::Vector3d& x) {
      return Eigen::Vector3d(x * co + k.cross(x) * s + k * (k.dot(x)) * (1. - co));
    };
    r.u = rotate(f.u).normalized();
    r.v = r.n.cross(r.u);
    return r;
  }

  // Coordinates of the L rescaled offsets in `frame`: (x, y) into xs_, ys_ and the heights into h,
  // with zeros on the padding rows L..P-1.
  void project_onto_frame(std::size_t L, std::size_t P, const Frame& frame, double* h)
  {
    xs_.resize(P);
    ys_.resize(P);
    project_onto_frame(L, P, frame, xs_.data(), ys_.data(), h);
  }

  // The same into x, y and h (each with zeros on the rows L..P-1).
  void project_onto_frame(std::size_t L, std::size_t P, const Frame& frame, double* x, double* y, double* h) const
  {
    const double axes[9] = {frame.u.x(), frame.u.y(), frame.u.z(), frame.v.x(), frame.v.y(),
                            frame.v.z(), frame.n.x(), frame.n.y(), frame.n.z()};
    dispatch_avx<Projection_kernel>(scaled_.data(), L, P, static_cast<const double*>(axes), x, y, h);
  }

  // Builds the system [A | h] in `frame` (column-major, column stride padded_rows(L), zero
  // padding rows) and solves it (with optional IRLS passes) into `c`. Without IRLS the system is
  // built directly in the solver's scratch work_; IRLS keeps it in system_ for the reweighted passes.
  bool fit_in_frame(const Fit_call& call, std::size_t order, const Frame& frame, std::vector<double>& c)
  {
    if(call.weighted())
      return fit_in_frame_weighted(call, order, frame, c);
    const std::size_t L = call.L;
    const std::size_t B = number_of_coefficients(order);
    const std::size_t P = padded_rows(L);
    const bool keep_system = call.options.robust_iterations > 0;
    // Order 2 without IRLS nor condition number: the system is solved from its moments, not built
    // (solver_choice.h, order2_least_squares()); if its guards refuse it, it is built and solved below.
    if(order2_from_moments(order, L, keep_system, call.options.compute_condition_number))
    {
      coordinates_.resize(3 * P);
      double* X = coordinates_.data();
      project_onto_frame(L, P, frame, X, X + P, X + 2 * P);
      c.resize(B);
      if(order2_least_squares(X, L, c.data()) &&
         std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v); }))
        return true;
    }
    Aligned_vector& system = keep_system ? system_ : work_;
    system.resize(P * (B + 1));
    double* A = system.data();
    double* h = A + B * P;
    project_onto_frame(L, P, frame, h);
    evaluate_basis_columns(xs_.data(), ys_.data(), L, P, order, A);
    c.resize(B);
    if(keep_system ? !solve_weighted(call, L, B, nullptr, c) : !solve_work(call, L, B, c, true))
      return false;

    for(std::size_t it = 0; it < call.options.robust_iterations; ++it)
    {
      // Tukey biweight on residuals scaled by 1.4826 MAD.
      absolute_residuals(A, P, L, B, c);
      const double scale = 1.4826 * median(residual_.data(), L);
      if(!(scale > 1e-14))
        break; // (near) exact fit: nothing to reweight
      const double cutoff = 4.685 * scale;
      weights_.resize(L);
      for(std::size_t l = 0; l < L; ++l)
        weights_[l] = tukey(residual_[l], cutoff);
      if(!solve_weighted(call, L, B, weights_.data(), trial_solution_))
        break;
      c.assign(trial_solution_.begin(), trial_solution_.end());
    }
    return true;
  }

  // Square root of Tukey's biweight (1 - t^2)^2 of a residual, t = residual / cutoff.
  static double tukey(double residual, double cutoff)
  {
    const double t = residual / cutoff;
    return t < 1. ? 1. - t * t : 0.;
  }

  // Neighbors whose normal m is nearly parallel to the fitting plane give no slope rows: their
  // slope -(m.u)/(m.n) is huge and meaningless for a height field over the plane.
  static constexpr double minimum_normal_cosine = 0.2;

  // The Hermite slope rows of a fit (scratch, reused).
  struct Slope_rows
  {
    std::vector<std::size_t> points;                    // the neighbors that give slope rows
    std::vector<std::pair<double, double> > targets;    // their slopes (dz/dx, dz/dy) in the frame
    std::vector<double> weights;                        // cos^2 of their normal's angle to the frame normal
    Aligned_vector x, y, gradient;                      // their (x, y) and the basis with its gradient there
  };

  // fit_in_frame() with compact weights and/or the Hermite rows (Fitting_options::neighbor_normal_weight):
  // rows 0..L-1 are the heights, rows L..L+M-1 and L+M..L+2M-1 the slopes dz/dx and dz/dy at the M
  // points whose normal passes the test above. The (unweighted) system is kept in system_, each row r
  // is scaled by base_[r] (sqrt of the compact weight of its point, times the normal weight for slope
  // rows).
  bool fit_in_frame_weighted(const Fit_call& call, std::size_t order, const Frame& frame, std::vector<double>& c)
  {
    const std::size_t L = call.L;
    const std::size_t B = number_of_coefficients(order);
    collect_slope_rows(call, frame);
    const std::size_t M = slopes_.points.size(), R = L + 2 * M;
    const std::size_t P = padded_rows(R);
    system_.resize(P * (B + 1));
    double* A = system_.data();
    double* h = A + B * P;
    project_onto_frame(L, P, frame, h);
    base_.resize(R);
    const std::size_t PL = padded_rows(L); // column stride of scaled_
    for(std::size_t l = 0; l < L; ++l) // sqrt of the weight (1 - |d|^2)^2
    {
      const double* d = scaled_.data() + l;
      base_[l] = call.options.compact_weights
                   ? (std::max)(1. - (d[0] * d[0] + d[PL] * d[PL] + d[2 * PL] * d[2 * PL]), 0.) : 1.;
    }
    evaluate_basis_columns(xs_.data(), ys_.data(), L, P, order, A);
    if(M > 0)
      add_slope_rows(call, order, P, A);
    c.resize(B);
    if(!solve_weighted(call, R, B, base_.data(), c))
      return false;
    robust_passes_weighted(call, A, P, B, c);
    return true;
  }

  // The neighbors whose normal gives slope rows in `frame`, with their slopes and weights (into slopes_).
  void collect_slope_rows(const Fit_call& call, const Frame& frame)
  {
    slopes_.points.clear();
    slopes_.targets.clear();
    slopes_.weights.clear();
    if(!call.normals)
      return;
    for(std::size_t l = 0; l < call.L; ++l)
    {
      const Eigen::Vector3d& m = call.normals[l];
      if(!m.allFinite())
        continue;
      const double mn = m.dot(frame.n);
      if(!(std::abs(mn) >= minimum_normal_cosine * m.norm()) || mn == 0.)
        continue;
      slopes_.points.push_back(l);
      slopes_.targets.emplace_back(-m.dot(frame.u) / mn, -m.dot(frame.v) / mn);
      // The slope of a normal at angle theta from the frame normal moves by up to d theta / cos^2 theta
      // when the normal turns by d theta: its rows are multiplied by cos^2 theta, so that a tilted
      // noisy normal weighs no more than its angular error warrants.
      slopes_.weights.push_back(mn * mn / m.squaredNorm());
    }
  }

  // Writes the slope rows L..L+2M-1 of [A | h] (column stride P) and their weights into base_.
  void add_slope_rows(const Fit_call& call, std::size_t order, std::size_t P, double* A)
  {
    const std::size_t L = call.L, B = number_of_coefficients(order), M = slopes_.points.size();
    double* h = A + B * P;
    const std::size_t PM = padded_rows(M);
    slopes_.x.resize(PM);
    slopes_.y.resize(PM);
    for(std::size_t m = 0; m < M; ++m)
    {
      slopes_.x[m] = xs_[slopes_.points[m]];
      slopes_.y[m] = ys_[slopes_.points[m]];
    }
    for(std::size_t m = M; m < PM; ++m) slopes_.x[m] = slopes_.y[m] = 0.;
    slopes_.gradient.resize(3 * PM * B);
    double* V = slopes_.gradient.data();
    double* Gx = V + PM * B;
    double* Gy = Gx + PM * B;
    evaluate_basis_columns(slopes_.x.data(), slopes_.y.data(), M, PM, order, V);
    evaluate_basis_gradient_columns(slopes_.x.data(), slopes_.y.data(), M, PM, order, V, Gx, Gy);
    for(std::size_t b = 0; b < B; ++b)
      for(std::size_t m = 0; m < M; ++m)
      {
        A[b * P + L + m] = Gx[b * PM + m];
        A[b * P + L + M + m] = Gy[b * PM + m];
      }
    for(std::size_t m = 0; m < M; ++m)
    {
      h[L + m] = slopes_.targets[m].first;
      h[L + M + m] = slopes_.targets[m].second;
      base_[L + m] = base_[L + M + m] = call.normal_weight * slopes_.weights[m] * base_[slopes_.points[m]];
    }
  }

  // IRLS of fit_in_frame_weighted(): Tukey biweight on each kind of row with its own scale (1.4826
  // MAD); a point gets the smallest weight of its rows, on all of its rows (an outlier is one in
  // position and normal).
  void robust_passes_weighted(const Fit_call& call, const double* A, std::size_t P, std::size_t B,
                              std::vector<double>& c)
  {
    const std::size_t L = call.L, M = slopes_.points.size(), R = L + 2 * M;
    for(std::size_t it = 0; it < call.options.robust_iterations; ++it)
    {
      absolute_residuals(A, P, R, B, c);
      const double height_cutoff = 4.685 * 1.4826 * median(residual_.data(), L);
      const double slope_cutoff = M > 0 ? 4.685 * 1.4826 * median(residual_.data() + L, 2 * M) : 0.;
      const bool reweight_heights = height_cutoff > 4.685 * 1e-14, reweight_slopes = slope_cutoff > 4.685 * 1e-14;
      if(!reweight_heights && !reweight_slopes)
        break; // (near) exact fit: nothing to reweight
      weights_.resize(R);
      for(std::size_t l = 0; l < L; ++l)
        weights_[l] = reweight_heights ? tukey(residual_[l], height_cutoff) : 1.;
      if(reweight_slopes)
        for(std::size_t m = 0; m < M; ++m)
        {
          double& w = weights_[slopes_.points[m]];
          w = (std::min)(w, (std::min)(tukey(residual_[L + m], slope_cutoff), tukey(residual_[L + M + m], slope_cutoff)));
        }
      for(std::size_t m = 0; m < M; ++m) weights_[L + m] = weights_[L + M + m] = weights_[slopes_.points[m]];
      for(std::size_t r = 0; r < R; ++r) weights_[r] *= base_[r];
      if(!solve_weighted(call, R, B, weights_.data(), trial_solution_))
        break;
      c.assign(trial_solution_.begin(), trial_solution_.end());
    }
  }

  // residual_[r] = |h_r - (A c)_r| for the rows r < R of the system [A | h] (column stride P).
  void absolute_residuals(const double* A, std::size_t P, std::size_t R, std::size_t B, const std::vector<double>& c)
  {
    const double* h = A + B * P;
    residual_.assign(R, 0.);
    for(std::size_t b = 0; b < B; ++b)
    {
      const double* column = A + b * P;
      for(std::size_t r = 0; r < R; ++r) residual_[r] += column[r] * c[b];
    }
    for(std::size_t r = 0; r < R; ++r) residual_[r] = std::abs(h[r] - residual_[r]);
  }

  // Median of values[0..n-1] (the upper one for even n); n > 0.
  double median(const double* values, std::size_t n)
  {
    sorted_.assign(values, values + n);
    std::nth_element(sorted_.begin(), sorted_.begin() + n / 2, sorted_.end());
    return sorted_[n / 2];
  }

  // Least squares on a copy of system_ in work_, with rows scaled by sqrt_weights (null: unweighted).
  bool solve_weighted(const Fit_call& call, std::size_t L, std::size_t B, const double* sqrt_weights,
                      std::vector<double>& c)
  {
    const std::size_t P = padded_rows(L);
    work_.assign(system_.begin(), system_.begin() + P * (B + 1));
    if(!sqrt_weights) // the unweighted height rows of fit_in_frame(): the Wavejet basis itself
      return solve_work(call, L, B, c, true);
    for(std::size_t b = 0; b <= B; ++b)
    {
      double* column = work_.data() + b * P;
      for(std::size_t l = 0; l < L; ++l) column[l] *= sqrt_weights[l];
    }
    return solve_work(call, L, B, c, false);
  }

  // Least squares on the system [A | h] of L rows in work_ (destroyed; R on return if the condition
  // number is wanted, see least_squares.h).
  // `wavejet_basis`: A is the basis of evaluate_basis_columns() at the order of B unknowns (no
  // weights, no slope rows), solved by wavejet_least_squares(); else by least_squares().
  bool solve_work(const Fit_call& call, std::size_t L, std::size_t B, std::vector<double>& c, bool wavejet_basis)
  {
    const bool want_condition = call.options.compute_condition_number;
    const std::size_t P = padded_rows(L);
    solver_scratch_.resize(wavejet_basis ? wavejet_least_squares_scratch_size(L, B) : least_squares_scratch_size(L, B));
    c.resize(B);
    const bool solved = want_condition // R: the condition number's
                          ? (wavejet_basis ? wavejet_least_squares : least_squares)(work_.data(), L, B,
                                                                                     solver_scratch_.data(), c.data())
                          : least_squares_solution(work_.data(), L, B, solver_scratch_.data(), c.data(), wavejet_basis);
    if(!solved)
      return false;
    for(std::size_t b = 0; b < B; ++b)
      if(!std::isfinite(c[b])) return false;
    if(want_condition)
    {
      Eigen::MatrixXd R = Eigen::MatrixXd::Zero(B, B);
      for(std::size_t j = 0; j < B; ++j)
        for(std::size_t i = 0; i <= j; ++i) R(i, j) = work_[j * P + i];
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(R);
      const Eigen::VectorXd sv = svd.singularValues();
      condition_ = sv(B - 1) > 0 ? sv(0) / sv(B - 1) : std::numeric_limits<double>::infinity();
    }
    return true;
  }

  double condition_ = 0.; // of the last solve, if Fitting_options::compute_condition_number
  Slope_rows slopes_;
  std::vector<double> base_;
  Aligned_vector scaled_, system_, work_, xs_, ys_, coordinates_, solver_scratch_; // read by the vectorized kernels
  std::vector<double> residual_, sorted_, weights_;
  std::vector<double> first_, trial_, best_, trial_solution_;
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_FITTING_CORE_H
