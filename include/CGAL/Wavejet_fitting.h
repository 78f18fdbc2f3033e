// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJET_FITTING_H
#define CGAL_WAVEJET_FITTING_H

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/number_utils.h>
#include <CGAL/assertions.h>

#include <CGAL/Wavejets/Fitting_options.h>
#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/differential_quantities.h>
#include <CGAL/Wavejets/internal/fitting_core.h>

#include <CGAL/disable_warnings.h>

#include <complex>
#include <cstddef>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {

/*!
\ingroup PkgWavejetsRef

Fits a Wavejet, the local height field z(r, theta) = sum_{k <= K} sum_{|n| <= k, n = k mod 2}
f_{k,n} r^k e^{i n theta} over the tangent plane, to a point and its neighbors
(Béarzi, Digne, Chaine, Eurographics 2018). The interface mirrors `Monge_via_jet_fitting`:
the first point of the range is the point where the Wavejet is computed, the others are its
neighbors, and the result is a `Wavejet_form`.

The fit (see \ref Wavejets_fitting in the user manual) uses a PCA frame (or a seed normal), coordinates rescaled by the
neighborhood radius Rf, least squares (guarded corrected semi-normal equations, else Householder QR) in the real basis r^k cos(n theta),
r^k sin(n theta), adaptive order (the order is lowered until there are at least
`neighbors_per_coefficient * (K+1)(K+2)/2` points and the system has full rank), optional
Tukey IRLS, and re-fits in the corrected tangent plane (keeping the frame of smallest
|f_{1,1}|). A K-Wavejet spans the same polynomials as a degree-K jet, so with
`correction_iterations == 0` the curvatures equal those of `Monge_via_jet_fitting` on the same points.

\tparam DataKernel kernel of the input points and of the `Wavejet_form` (e.g. `Epick`).
\tparam LocalKernel kernel with `double` number type used for `pca_basis()`; default `Simple_cartesian<double>`.

The optional settings that `Monge_via_jet_fitting` has no equivalent for are grouped in a
`Wavejets::Fitting_options`, given to the constructor or changed through `options()`.

One instance must not be used by two threads at the same time; it keeps scratch memory between
calls, so reusing one instance for many points avoids allocations.
*/
template <class DataKernel, class LocalKernel = Simple_cartesian<double> >
class Wavejet_fitting
{
public:
  /// \name Types
  /// @{

  /// The kernel of the input points and of `Wavejet_form`.
  typedef DataKernel Data_kernel;
  /// The kernel of `pca_basis()` and `condition_number()`.
  typedef LocalKernel Local_kernel;
  /// Number type of `Local_kernel`.
  typedef typename Local_kernel::FT FT;
  /// Point type of `Local_kernel`.
  typedef typename Local_kernel::Point_3 Point_3;
  /// Vector type of `Local_kernel`.
  typedef typename Local_kernel::Vector_3 Vector_3;
  /// Number type of `Data_kernel`.
  typedef typename Data_kernel::FT DFT;
  /// @}

  static_assert(std::is_convertible<double, FT>::value, "Local_kernel::FT must be constructible from double");

  /*!
  The result of a fit: the Wavejet's frame, coefficients (world units) and differential quantities.
  Number types come from `DataKernel`. Default-constructed or failed forms have `is_valid() == false`;
  then `origin()` is the query point, `order()` is 0, and every other quantity is zero.
  A valid form has only finite quantities: a fit whose world-unit coefficients or curvatures would
  overflow (radius Rf outside [1e-20, 1e20], or a quantity among the coefficients, the curvatures and
  the a_n(Rf) that overflows at a high order) fails with `Fit_status::OUT_OF_RANGE`.

  Number type of the coefficients: the fit is computed in `double` whatever the kernel, and
  `coefficient()` and `enclosed_area_coefficient()` return `Complex`, which is
  `std::complex<double>`. For the kernels whose `FT` is `double` (`Exact_predicates_inexact_constructions_kernel`,
  `Simple_cartesian<double>`) this is `std::complex<FT>`. For a kernel with another `FT`
  (e.g. `Exact_predicates_exact_constructions_kernel`, `Simple_cartesian<float>`) it stays
  `std::complex<double>`: the values are `double` anyway, and `std::complex<T>` is specified only
  for floating-point `T`.

  Evaluation radius: `enclosed_area_coefficient(n, s)` evaluates a_n(s) at the `s` it is given,
  also beyond Rf (where the polynomial is extrapolated, outside the points it was fitted to); it is
  not clamped. The point-set functions (`wavejet_enhance_positions()`, `wavejet_enhance_normals()`)
  clamp their `evaluation_radius` to Rf per point. To reproduce them, pass `(std::min)(s, radius())`.
  */
  class Wavejet_form
  {
  public:
    /// \name Types
    /// @{

    /// Number type of `Data_kernel`.
    typedef typename Data_kernel::FT FT;
    /// Point type of `Data_kernel`.
    typedef typename Data_kernel::Point_3 Point_3;
    /// Vector type of `Data_kernel`.
    typedef typename Data_kernel::Vector_3 Vector_3;
    /// Type of the complex coefficients f_{k,n} and a_n(s): `std::complex<double>`, i.e.
    /// `std::complex<FT>` for the kernels with `FT == double` (Epick, `Simple_cartesian<double>`);
    /// see the class description for other kernels.
    typedef std::complex<double> Complex;
    /// @}

    /// Creates an invalid form (`is_valid() == false`): origin at the origin, null vectors, no coefficients.
    Wavejet_form()
      : m_origin(ORIGIN), m_d1(NULL_VECTOR), m_d2(NULL_VECTOR), m_normal(NULL_VECTOR),
        m_u(NULL_VECTOR), m_v(NULL_VECTOR), m_frame_normal(NULL_VECTOR)
    {}

    /// \name Status
    /// @{

    /// Outcome of the fit: `Wavejets::Fit_status::SUCCESS`, or why no Wavejet could be fitted.
    Wavejets::Fit_status status() const { return m_status; }
    /// `status() == Wavejets::Fit_status::SUCCESS`; all other quantities are meaningful only then.
    bool is_valid() const { return m_status == Wavejets::Fit_status::SUCCESS; }
    /// Order K actually fitted (after adaptive reduction); 0 if the fit failed.
    std::size_t order() const { return m_order; }
    /// Neighborhood radius Rf used for the rescaling (world units).
    FT radius() const { return FT(m_radius); }
    /// Number of points of the fit (query point included).
    std::size_t number_of_points() const { return m_number_of_points; }
    /// Number of accepted tangent-plane re-fits.
    std::size_t number_of_corrections() const { return m_corrections; }
    /// |f_{1,1}| left in the final frame (0 in the exact tangent plane).
    FT tangent_plane_residual() const { return FT(m_final_tilt); }
    /// @}

    /// \name Geometry (data kernel types)
    /// @{

    /// Point of the Wavejet surface above the query point p: p + f_{0,0} n (n the frame normal).
    Point_3 origin() const { return m_origin; }
    /// Writable access to `origin()`.
    Point_3& origin() { return m_origin; }
    /// Unit normal of the Wavejet surface at `origin()` (the frame normal tilted by the residual f_{1,+-1}).
    Vector_3 normal_direction() const { return m_normal; }
    /// Writable access to `normal_direction()`.
    Vector_3& normal_direction() { return m_normal; }
    /// First axis u of the final tangent frame: theta = 0 along u.
    Vector_3 first_tangent_direction() const { return m_u; }
    /// Writable access to `first_tangent_direction()`.
    Vector_3& first_tangent_direction() { return m_u; }
    /// Second axis v = n x u of the final tangent frame.
    Vector_3 second_tangent_direction() const { return m_v; }
    /// Writable access to `second_tangent_direction()`.
    Vector_3& second_tangent_direction() { return m_v; }
    /// Third axis n of the final tangent frame, along which heights (and coefficients) are measured.
    Vector_3 frame_normal_direction() const { return m_frame_normal; }
    /// Writable access to `frame_normal_direction()`.
    Vector_3& frame_normal_direction() { return m_frame_normal; }
    /// Direction of the maximal principal curvature (unit, tangent; (d1, d2, normal) is direct).
    Vector_3 maximal_principal_direction() const { return m_d1; }
    /// Writable access to `maximal_principal_direction()`.
    Vector_3& maximal_principal_direction() { return m_d1; }
    /// Direction of the minimal principal curvature.
    Vector_3 minimal_principal_direction() const { return m_d2; }
    /// Writable access to `minimal_principal_direction()`.
    Vector_3& minimal_principal_direction() { return m_d2; }
    /// @}

    /// \name Coefficients (world units, final frame)
    /// @{

    /// f_{k,n}: z = sum f_{k,n} r^k e^{i n theta}, r and z in the input length unit, theta from
    /// `first_tangent_direction()`. Zero for any (k, n) that is not a coefficient of this Wavejet
    /// (|n| > k, parity mismatch, or k > order()).
    Complex coefficient(int k, int n) const
    {
      if(!is_valid() || !Wavejets::internal::is_wavejet_index(k, n) || std::size_t(k) >= stored_orders())
        return Complex(0., 0.);
      return Wavejets::internal::complex_coefficient(m_coefficients.data(), k, n);
    }
    /// The (K+1)(K+2)/2 real unknowns, world units: for k = 0..K, order k starts at k(k+1)/2 and holds
    /// f_{k,0} (k even) then alpha_{k,n}, beta_{k,n} for n = 1 or 2, ..., k, with
    /// f_{k,n} = (alpha_{k,n} - i beta_{k,n}) / 2 and f_{k,-n} = conj(f_{k,n}).
    const std::vector<double>& coefficients() const { return m_coefficients; }
    /// Writable access to `coefficients()`.
    std::vector<double>& coefficients() { return m_coefficients; }
    /// Enclosed-area coefficient a_n(s) = sum_{k >= |n|, k = n mod 2} f_{k,n} s^{k+2}/(k+2) (length^3),
    /// all terms included (the filters drop the k = 0 and k = 1 terms themselves). `s` is in world
    /// units and is not clamped to `radius()` (the point-set functions clamp it; see the class description).
    Complex enclosed_area_coefficient(int n, double s) const
    {
      if(!is_valid() || std::size_t(std::abs(n)) >= stored_orders())
        return Complex(0., 0.);
      return Wavejets::internal::enclosed_area(m_coefficients.data(), stored_orders() - 1, n, s);
    }
    /// a_n(Rf).
    Complex enclosed_area_coefficient(int n) const { return enclosed_area_coefficient(n, m_radius); }
    /// @}

    /// \name Curvature (signs relative to `normal_direction()`: bending toward it is positive)
    /// @{

    /// Mean curvature H = (k1 + k2) / 2 (a sphere of radius R with outward normals has H = -1/R).
    FT mean_curvature() const { return FT(m_mean); }
    /// Gaussian curvature K_G = k1 k2 (does not depend on the orientation).
    FT gaussian_curvature() const { return FT(m_gaussian); }
    /// `i == 0`: maximal, `i == 1`: minimal principal curvature.
    /// \throws std::out_of_range if `i > 1`.
    FT principal_curvatures(std::size_t i) const
    {
      if(i > 1) throw std::out_of_range("Wavejet_form::principal_curvatures: index " + std::to_string(i) + " > 1");
      return FT(i == 0 ? m_k1 : m_k2);
    }
    /// @}

    /// Flips the orientation if `given_normal` points to the other side of `normal_direction()`:
    /// the normal and frame normal change sign, v changes sign (the frame stays direct, theta -> -theta),
    /// f_{k,n} becomes -conj(f_{k,n}), H and the principal curvatures change sign and k1, k2 (with
    /// their directions) swap. `origin()` does not change.
    void comply_wrt_given_normal(const Vector_3& given_normal)
    {
      if(!is_valid() || given_normal * m_normal >= FT(0))
        return;
      m_normal = -m_normal;
      m_frame_normal = -m_frame_normal;
      m_v = -m_v;
      for(std::size_t k = 0; k < stored_orders(); ++k)
      {
        const std::size_t o = Wavejets::internal::order_offset(k);
        if(k % 2 == 0) m_coefficients[o] = -m_coefficients[o];
        for(std::size_t n = (k % 2 == 0 ? 2 : 1); n <= k; n += 2)
          m_coefficients[o + n - 1] = -m_coefficients[o + n - 1]; // alpha -> -alpha, beta unchanged
      }
      m_mean = -m_mean;
      const double k1 = m_k1;
      m_k1 = -m_k2;
      m_k2 = -k1;
      std::swap(m_d1, m_d2);
    }

    /// Writes, as text: the status (`fit_status_name()`); a line with the order, the number of points,
    /// Rf, the number of corrections and the residual |f_{1,1}|; one line each for the origin, the
    /// normal and the frame axes u, v, n; a line with H and K_G; one line each with k1 and d1, k2 and
    /// d2; then one line per order k <= `order()` with every f(k,n), n = -k, -k+2, ..., k. Numbers use
    /// the stream's precision.
    std::ostream& dump_verbose(std::ostream& os) const
    {
      os << "Wavejet form: " << Wavejets::fit_status_name(m_status) << "\n";
      os << "  order: " << m_order << "  points: " << m_number_of_points << "  radius Rf: " << m_radius
         << "  corrections: " << m_corrections << "  |f11| residual: " << m_final_tilt << "\n";
      os << "  origin: " << m_origin << "\n  normal: " << m_normal << "\n";
      os << "  frame u: " << m_u << "\n  frame v: " << m_v << "\n  frame n: " << m_frame_normal << "\n";
      os << "  mean curvature: " << m_mean << "  gaussian curvature: " << m_gaussian << "\n";
      os << "  k1: " << m_k1 << "  d1: " << m_d1 << "\n  k2: " << m_k2 << "  d2: " << m_d2 << "\n";
      for(std::size_t k = 0; k <= m_order; ++k)
      {
        os << "  order " << k << ":";
        for(int n = -int(k); n <= int(k); n += 2)
          os << " f(" << k << "," << n << ")=" << coefficient(int(k), n);
        os << "\n";
      }
      return os;
    }

    /// Writes `f` with `dump_verbose()`.
    friend std::ostream& operator<<(std::ostream& os, const Wavejet_form& f) { return f.dump_verbose(os); }

  private:
    friend class Wavejet_fitting;
    // Number of orders k = 0, 1, ... whose coefficients are all stored: `order() + 1`, unless the
    // vector was resized through the writable `coefficients()`; every read stays within them.
    std::size_t stored_orders() const
    {
      std::size_t orders = 0;
      while(orders <= m_order && Wavejets::internal::number_of_coefficients(orders) <= m_coefficients.size()) ++orders;
      return orders;
    }
    Wavejets::Fit_status m_status = Wavejets::Fit_status::TOO_FEW_POINTS;
    std::size_t m_order = 0, m_number_of_points = 0, m_corrections = 0;
    double m_radius = 0., m_final_tilt = 0.;
    Point_3 m_origin;
    Vector_3 m_d1, m_d2, m_normal, m_u, m_v, m_frame_normal;
    std::vector<double> m_coefficients;
    double m_mean = 0., m_gaussian = 0., m_k1 = 0., m_k2 = 0.;
  };

  /// Creates a fitting object with the given options.
  explicit Wavejet_fitting(const Wavejets::Fitting_options& options = Wavejets::Fitting_options())
    : m_options(options)
  {}

  /// The options used by the next fits.
  const Wavejets::Fitting_options& options() const { return m_options; }
  /// Writable access to the options used by the next fits.
  Wavejets::Fitting_options& options() { return m_options; }

  /*!
  Fits a Wavejet of order `order` (lowered if the points cannot support it) at `*begin`.
  \tparam InputIterator random-access or forward iterator with value type `Data_kernel::Point_3`.
  \param begin first point of the range: the point where the Wavejet is computed.
  \param end past-the-end iterator of the range; the points after `*begin` are its neighbors.
  \param order requested order K; it is lowered (not below `options().minimum_order`) until the
         range has `options().neighbors_per_coefficient * (K+1)(K+2)/2` points and the system has full rank.
  \return the fitted form; a range too small or degenerate gives a form with `is_valid() == false`
          and the reason in `Wavejet_form::status()`.
  \throws std::invalid_argument if `order == 0` (in every build, like the point-set functions'
          bad arguments; a fit that fails because of its points is not an error but a status).
  */
  template <class InputIterator>
  Wavejet_form operator()(InputIterator begin, InputIterator end, std::size_t order)
  {
    return fit(begin, end, order, nullptr);
  }

  /*!
  Same as the other `operator()`, with a normal at `*begin` that orients the frame (the frame normal
  makes an angle of at most 90 degrees with it), or also seeds
  the first fit's frame when `options().normal_use == Wavejets::Normal_use::SEED_FRAME`.
  \param begin first point of the range: the point where the Wavejet is computed.
  \param end past-the-end iterator of the range.
  \param order requested order K (see above).
  \param normal a normal at `*begin`; it need not be unit, only its direction is used.
  */
  template <class InputIterator>
  Wavejet_form operator()(InputIterator begin, InputIterator end, std::size_t order,
                          const typename Data_kernel::Vector_3& normal)
  {
    const Eigen::Vector3d hint(to_double(normal.x()), to_double(normal.y()), to_double(normal.z()));
    return fit(begin, end, order, &hint);
  }

  /*!
  Hermite fit: fits the Wavejet to the points' heights and to the slopes their normals give
  (see `Wavejets::Fitting_options::neighbor_normal_weight`, which weighs the two kinds of equations;
  with a weight of 0 this is the plain fit). Every fit of the procedure (the first fit, the
  tangent-plane re-fits, the robust passes) is the Hermite fit. The normals need not be unit nor
  oriented; a normal that is not finite, zero, or makes more than about 78 degrees (cosine 0.2) with
  the frame normal gives no slope equation. The first normal, the one at `*begin`, also orients the
  frame as the `normal` of the other overload does (or seeds it, with `Wavejets::Normal_use::SEED_FRAME`),
  unless it is zero or not finite. The adaptive order still counts points, not equations.
  \tparam InputIterator iterator with value type `Data_kernel::Point_3`.
  \tparam NormalIterator iterator with value type `Data_kernel::Vector_3`, over as many normals as there are points.
  \param begin first point of the range: the point where the Wavejet is computed.
  \param end past-the-end iterator of the range.
  \param normals_begin normal of `*begin`, then of each following point, in the same order.
  \param order requested order K (see above).
  */
  template <class InputIterator, class NormalIterator>
  Wavejet_form operator()(InputIterator begin, InputIterator end, NormalIterator normals_begin, std::size_t order)
  {
    m_normals.clear();
    for(InputIterator it = begin; it != end; ++it, ++normals_begin)
    {
      const typename Data_kernel::Vector_3& m = *normals_begin;
      m_normals.emplace_back(to_double(m.x()), to_double(m.y()), to_double(m.z()));
    }
    if(m_normals.empty() || !m_normals.front().allFinite() || !(m_normals.front().squaredNorm() > 0.))
      return fit(begin, end, order, nullptr, m_normals.data());
    const Eigen::Vector3d hint = m_normals.front();
    return fit(begin, end, order, &hint, m_normals.data());
  }

  /// Condition number (ratio of the largest to the smallest singular value) of the kept fit's
  /// least-squares matrix: one row per point, coordinates (q - p)/Rf in the form's final frame,
  /// columns r^k, r^k cos(n theta), r^k sin(n theta) (rows scaled by the square roots of the weights
  /// of the last IRLS pass, if any; a Hermite fit adds its slope rows, weighted). Meaningful after a successful fit; 0 before any fit, or when
  /// `options().compute_condition_number` is false. It is not comparable with
  /// `Monge_via_jet_fitting::condition_number()`, which is that of CGAL's own preconditioned monomial system.
  FT condition_number() const { return FT(m_result.condition_number); }

  /// PCA of the last neighborhood (the query point included): eigenvalue of the covariance matrix
  /// of the points about their barycenter, divided by the number of points (world units squared,
  /// the convention of `Monge_via_jet_fitting::pca_basis()`), and unit eigenvector; `i == 0` largest,
  /// `i == 2` smallest (the PCA normal); the three eigenvectors form a direct orthonormal basis.
  /// Fitted without a normal and with no accepted re-fit, the form's frame (u, v, n) is this basis.
  /// \throws std::out_of_range if `i > 2`.
  std::pair<FT, Vector_3> pca_basis(std::size_t i) const
  {
    if(i > 2) throw std::out_of_range("Wavejet_fitting::pca_basis: index " + std::to_string(i) + " > 2");
    const Eigen::Vector3d e = m_result.pca_vectors.col(int(i));
    return std::make_pair(FT(m_result.pca_values(int(i))), Vector_3(e.x(), e.y(), e.z()));
  }

private:
  template <class InputIterator>
  Wavejet_form fit(InputIterator begin, InputIterator end, std::size_t order, const Eigen::Vector3d* hint,
                   const Eigen::Vector3d* neighbor_normals = nullptr)
  {
    if(order < 1) throw std::invalid_argument("Wavejet_fitting: the order must be >= 1");
    Wavejet_form form;
    m_offsets.clear();
    if(begin == end)
    {
      form.m_status = Wavejets::Fit_status::TOO_FEW_POINTS;
      return form;
    }
    const typename Data_kernel::Point_3& p = *begin;
    form.m_origin = p;
    for(InputIterator it = begin; it != end; ++it)
    {
      const typename Data_kernel::Point_3& q = *it;
      m_offsets.emplace_back(to_double(q.x() - p.x()), to_double(q.y() - p.y()), to_double(q.z() - p.z()));
    }
    if(!(is_finite(to_double(p.x())) && is_finite(to_double(p.y())) && is_finite(to_double(p.z()))))
    {
      form.m_status = Wavejets::Fit_status::NON_FINITE_INPUT;
      return form;
    }
    m_fitter.fit(m_offsets.data(), m_offsets.size(), order, m_options, hint, m_result, neighbor_normals);
    form.m_status = m_result.status;
    form.m_number_of_points = m_result.number_of_points;
    if(!m_result.success())
      return form;

    const Wavejets::internal::Fit_result& r = m_result;
    typedef typename Data_kernel::Vector_3 DVector;
    auto to_vector = [](const Eigen::Vector3d& e) { return DVector(e.x(), e.y(), e.z()); };
    const std::size_t B = Wavejets::internal::number_of_coefficients(r.order);
    const double* c = m_fitter.coefficients();
    form.m_order = r.order;
    form.m_radius = r.radius;
    form.m_corrections = r.corrections;
    form.m_final_tilt = r.final_tilt;
    form.m_coefficients.resize(B);
    double scale = r.radius; // Rf^{1-k}
    for(std::size_t k = 0; k <= r.order; ++k, scale /= r.radius)
      for(std::size_t j = 0; j <= k; ++j)
        form.m_coefficients[Wavejets::internal::order_offset(k) + j] = c[Wavejets::internal::order_offset(k) + j] * scale;

    const double f00 = form.m_coefficients[0];
    form.m_origin = p + to_vector(r.frame.n * f00);
    form.m_u = to_vector(r.frame.u);
    form.m_v = to_vector(r.frame.v);
    form.m_frame_normal = to_vector(r.frame.n);
    const double fx = r.order >= 1 ? form.m_coefficients[1] : 0., fy = r.order >= 1 ? form.m_coefficients[2] : 0.;
    form.m_normal = to_vector(Wavejets::internal::graph_normal(r.frame, fx, fy));

    Wavejets::internal::Curvature_info ci = Wavejets::internal::graph_curvature(
      r.curvature_derivatives, r.curvature_frame.u, r.curvature_frame.v, r.curvature_frame.n);
    form.m_mean = ci.mean;
    form.m_gaussian = ci.gaussian;
    form.m_k1 = ci.k1;
    form.m_k2 = ci.k2;
    form.m_d1 = to_vector(ci.d1);
    form.m_d2 = to_vector(ci.d2);
    // World-unit coefficients scale as Rf^{1-k}: at tiny scales and high orders they overflow
    // (e.g. Rf = 1e-40, K = 9). Never return a "valid" form with infinite quantities.
    bool finite = std::isfinite(ci.mean) && std::isfinite(ci.gaussian) && std::isfinite(ci.k1) && std::isfinite(ci.k2);
    for(double x : form.m_coefficients) finite = finite && std::isfinite(x);
    for(int n = 0; finite && n <= int(r.order); ++n)
      finite = std::isfinite(std::abs(form.enclosed_area_coefficient(n)));
    if(!finite)
    {
      Wavejet_form failed;
      failed.m_origin = p;
      failed.m_status = Wavejets::Fit_status::OUT_OF_RANGE;
      failed.m_number_of_points = form.m_number_of_points;
      return failed;
    }
    return form;
  }

  Wavejets::Fitting_options m_options;
  Wavejets::internal::Fitter m_fitter;
  Wavejets::internal::Fit_result m_result;
  std::vector<Eigen::Vector3d> m_offsets, m_normals;
};

} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_WAVEJET_FITTING_H
