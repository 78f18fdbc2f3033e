// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_FITTING_OPTIONS_H
#define CGAL_WAVEJETS_FITTING_OPTIONS_H

#include <cstddef>

namespace CGAL {
namespace Wavejets {

/// \ingroup PkgWavejetsRef
/// Outcome of one Wavejet fit.
enum class Fit_status
{
  SUCCESS = 0,           ///< a Wavejet of order >= the minimum order was fitted
  TOO_FEW_POINTS,        ///< fewer points than `neighbors_per_coefficient * (K+1)(K+2)/2` even at the minimum order
  DEGENERATE_NEIGHBORHOOD, ///< coincident, collinear or otherwise rank-deficient points, even at the minimum order
  NON_FINITE_INPUT,      ///< a coordinate (or the seed normal) is NaN or infinite
  /// The neighborhood radius Rf is outside [1e-20, 1e20] (or, in `Wavejet_fitting`, a world-unit
  /// quantity overflowed): world-unit coefficients f_{k,n} scale as Rf^{1-k}, enclosed areas a_n(Rf)
  /// as Rf^3 with terms in Rf^{k+2}, curvatures as 1/Rf, and at such scales they leave the range
  /// of double (or lose their high orders to underflow). Rescale the input (e.g. to meters).
  OUT_OF_RANGE
};

/// \ingroup PkgWavejetsRef
/// Human-readable name of a `Fit_status`.
inline const char* fit_status_name(Fit_status s)
{
  switch(s) {
    case Fit_status::SUCCESS: return "success";
    case Fit_status::TOO_FEW_POINTS: return "too few points";
    case Fit_status::DEGENERATE_NEIGHBORHOOD: return "degenerate neighborhood";
    case Fit_status::NON_FINITE_INPUT: return "non-finite input";
    case Fit_status::OUT_OF_RANGE: return "out of range (neighborhood too small for double)";
  }
  return "unknown";
}

/// \ingroup PkgWavejetsRef
/// Which fit the differential quantities (curvatures, principal directions) are read from.
///
/// The curvature formulas of a graph are exact in any parameterization plane, so both are valid.
/// `INITIAL_FRAME` (default) reads them from the first fit, in the PCA frame (or the seed frame):
/// with a PCA frame this is the same least-squares problem as `CGAL::Monge_via_jet_fitting`, and it
/// was measured more accurate than the corrected frame on noise-free analytic surfaces.
/// `TANGENT_FRAME` reads them from the fit in the final, corrected tangent frame.
enum class Curvature_frame
{
  INITIAL_FRAME, ///< the first fit, in the PCA frame (or the seed frame); the default
  TANGENT_FRAME  ///< the fit in the final, corrected tangent frame
};

/// \ingroup PkgWavejetsRef
/// How a normal passed to `Wavejet_fitting::operator()` is used.
enum class Normal_use
{
  ORIENT,    ///< the frame comes from PCA; the normal only orients it (at most 90 degrees from the frame normal, also after the tangent-plane correction, which never takes a frame pointing away from it)
  SEED_FRAME ///< the first fit is done in the plane orthogonal to the normal (which also orients it)
};

/// \ingroup PkgWavejetsRef
/// Options of `Wavejet_fitting` that `CGAL::Monge_via_jet_fitting` has no equivalent for.
/// The point-set functions set them from named parameters.
struct Fitting_options
{
  /// Adaptive order: the order K is lowered until the number of points L satisfies
  /// `L >= neighbors_per_coefficient * (K+1)(K+2)/2` (the factor beta of the paper).
  /// A value below 1 or NaN is read as 1 (the point-set functions reject it instead).
  double neighbors_per_coefficient = 1.1;
  /// Lowest order accepted by the adaptive order before the fit fails (clamped to the requested order).
  std::size_t minimum_order = 2;
  /// Maximum number of re-fits in the corrected tangent plane (0 switches the correction off).
  std::size_t correction_iterations = 2;
  /// Order of the fits of the tangent-plane search (the first fit and the re-fits of the
  /// correction). 0, or a value >= the fit order: the fit order itself (each re-fit is a full fit).
  /// A lower order, e.g. 2, makes the search cheap: the plane is found with fits of that order, then
  /// one fit of the full order is done in it; its residual tilt f_{1,+-1} is kept (the normal is that
  /// of the full-order surface, see `Wavejet_form::normal_direction()`). With
  /// `Curvature_frame::INITIAL_FRAME`, the full-order fit in the initial frame is also done, for the
  /// curvatures. Of the point-set functions, `wavejet_estimate_normals()` uses 2 by default, the
  /// others 0 (see `function_defaults()`).
  std::size_t tangent_plane_order = 0;
  /// Number of iteratively reweighted least-squares passes (Tukey biweight; 0 = plain least squares).
  std::size_t robust_iterations = 0;
  /// Neighborhood radius Rf used to rescale the coordinates; 0 means the distance from the query
  /// point to its farthest neighbor. (The point-set functions set it from `neighbor_radius`.)
  double neighborhood_radius = 0.;
  /// Fit whose frame the curvatures are read from.
  Curvature_frame curvature_frame = Curvature_frame::INITIAL_FRAME;
  /// Role of a given normal.
  Normal_use normal_use = Normal_use::ORIENT;
  /// Compute `condition_number()` (an SVD of the triangular factor; costs a little). It also makes
  /// the order-2 fits build their systems and solve them by the QR, where they are otherwise solved
  /// from the neighborhood's moments without building them (faster; the two agree to about 1e-15
  /// relative on real neighborhoods). The point-set functions, which have no use for it, switch it off.
  bool compute_condition_number = true;
  /// Hermite fit: weight w of the slope equations given by the neighbors' normals (used only when
  /// normals of the neighbors are given, e.g. through `Wavejet_fitting`'s overload that takes them,
  /// or `Wavejets::parameters::use_neighbor_normals(true)`). Each neighbor normal m (not nearly
  /// parallel to the fitting plane: cos theta = |m.n| / |m| >= 0.2, n the frame normal) adds the two rows
  /// w c dz/dx(x_l, y_l) = -w c (m.u)/(m.n) and w c dz/dy(x_l, y_l) = -w c (m.v)/(m.n), c = cos^2 theta,
  /// in the frame (u, v, n), next to the height rows z(x_l, y_l) = z_l. The fit works in coordinates
  /// divided by Rf, where heights are in units of Rf and slopes are dimensionless (unchanged by the
  /// rescaling), so a slope error of 1 of a normal along n weighs as much as a height error of w Rf.
  /// c: a slope moves by up to d theta / cos^2 theta when its normal turns by d theta, so c makes every
  /// normal count by its angular error (benchmark/Wavejets/accuracy_ponca.md, K 2: mean-curvature error
  /// 12% lower than without c on average over its noisy and clean rows, up to 57% lower on the Goursat
  /// surface, at most 0.7% higher). The sign of m does not matter
  /// (unoriented normals are fine). 0 switches the slope rows off.
  double neighbor_normal_weight = 1.;
  /// Weight the rows of neighbor q by the smooth compact kernel (1 - |q - p|^2 / Rf^2)^2 (points at
  /// distance Rf get weight 0; false: every point has weight 1).
  bool compact_weights = false;
};

} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_FITTING_OPTIONS_H
