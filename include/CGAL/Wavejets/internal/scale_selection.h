// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_SCALE_SELECTION_H
#define CGAL_WAVEJETS_INTERNAL_SCALE_SELECTION_H

// The per-point choice of a neighborhood size from a ladder of sizes (wavejet_estimate_scales()):
// one k-nearest query at the largest size, a Wavejet fitted to each nested prefix of the neighbors
// (nearest first), and the size whose estimated normal error is the smallest
// (doc/Wavejets/Mathematics.txt, "Choosing the scale per point").

#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/fitting_core.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// Weight of the variance term of the estimated error (see Scale_chooser::choose()): the squared
/// slope error of a least-squares plane through k points of a disk of radius R with height noise
/// sigma is 8 sigma^2 / (k R^2) (two slopes, each of variance 4 sigma^2 / (k R^2)); the higher-order
/// terms of a Wavejet inflate it (measured on the benchmark's surfaces: 4x is the best of 1, 4 and 16
/// times that, benchmark/Wavejets/scale_selection.md).
constexpr double scale_variance_weight = 32.;

/// What the ladder gives for one point.
struct Scale_choice
{
  std::size_t rung = 0;            // index of the chosen size in the ladder
  bool found = false;              // false: no size of the ladder could be fitted
};

/// Fits the nested neighborhoods of one point and picks one (one instance per thread).
class Scale_chooser
{
public:
  /// `offsets[0]` is the query point (a zero offset), then its neighbors nearest first; `L` of them.
  /// `ladder`: increasing numbers of neighbors (query excluded); the rungs beyond `L - 1` neighbors
  /// are not fitted. `descriptor` (null: none): receives, per rung, the magnitude of the
  /// second-order part of the Wavejet in world units (1/length, like a curvature; 0 where not fitted).
  Scale_choice choose(const Eigen::Vector3d* offsets, std::size_t L, const std::vector<unsigned int>& ladder,
                      std::size_t order, const Fitting_options& options, const Eigen::Vector3d* hint,
                      double* descriptor)
  {
    const std::size_t J = ladder.size();
    residual2_.assign(J, std::numeric_limits<double>::infinity());
    radius_.assign(J, 0.);
    for(std::size_t j = 0; j < J; ++j)
    {
      if(descriptor) descriptor[j] = 0.;
      const std::size_t count = std::size_t(ladder[j]) + 1;
      if(count > L) continue;
      if(fitter_.fit(offsets, count, order, options, hint, fit_) != Fit_status::SUCCESS) continue;
      radius_[j] = fit_.radius;
      const std::size_t unknowns = number_of_coefficients(fit_.order);
      if(count > unknowns) residual2_[j] = squared_residual(offsets, count) / double(count - unknowns);
      if(descriptor) descriptor[j] = second_order_magnitude();
    }
    // The noise variance: the smallest residual variance over the ladder (the bias of a too large
    // neighborhood only adds to it).
    double noise2 = std::numeric_limits<double>::infinity();
    for(double r2 : residual2_) noise2 = (std::min)(noise2, r2);
    Scale_choice choice;
    double best = std::numeric_limits<double>::infinity();
    for(std::size_t j = 0; j < J; ++j)
    {
      if(!std::isfinite(residual2_[j]) || !(radius_[j] > 0)) continue;
      const double R2 = radius_[j] * radius_[j];
      // Estimated squared normal error: variance (noise over the neighborhood) + squared bias (the
      // residual the noise does not explain, a height error over R: a slope error).
      const double error = scale_variance_weight * noise2 / (double(ladder[j]) * R2) +
                           (std::max)(residual2_[j] - noise2, 0.) / R2;
      if(error < best) { best = error; choice.rung = j; choice.found = true; }
    }
    if(!choice.found) // every fitted rung was exact (no degrees of freedom): the largest fitted one
      for(std::size_t j = J; j-- > 0;)
        if(radius_[j] > 0) { choice.rung = j; choice.found = true; break; }
    return choice;
  }

private:
  // Sum of the squared height residuals of the last fit at its `count` points, world units.
  double squared_residual(const Eigen::Vector3d* offsets, std::size_t count)
  {
    const Frame& f = fit_.frame;
    const double R = fit_.radius;
    x_.resize(count); y_.resize(count); h_.resize(count);
    for(std::size_t l = 0; l < count; ++l)
    {
      x_[l] = offsets[l].dot(f.u) / R;
      y_[l] = offsets[l].dot(f.v) / R;
      h_[l] = offsets[l].dot(f.n) / R;
    }
    const std::size_t B = number_of_coefficients(fit_.order);
    basis_.resize(B * count);
    evaluate_basis_columns(x_.data(), y_.data(), count, count, fit_.order, basis_.data());
    const double* c = fitter_.coefficients();
    double sum = 0.;
    for(std::size_t l = 0; l < count; ++l)
    {
      double height = 0.;
      for(std::size_t b = 0; b < B; ++b) height += basis_[b * count + l] * c[b];
      sum += (h_[l] - height) * (h_[l] - height);
    }
    return sum * R * R;
  }

  // |f_2| of the last fit: the norm of its three order-2 unknowns, in world units (1/length).
  double second_order_magnitude() const
  {
    if(fit_.order < 2) return 0.;
    const double* c = fitter_.coefficients() + order_offset(2);
    return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / fit_.radius;
  }

  Fitter fitter_;
  Fit_result fit_;
  std::vector<double> residual2_, radius_, x_, y_, h_, basis_;
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_SCALE_SELECTION_H
