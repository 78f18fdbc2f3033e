// Fuzz harness shared by test_fuzz.cpp (seeded random fuzzing, run by CTest) and
// fuzz/wavejets_libfuzzer.cpp (libFuzzer target, built with clang only). It turns a stream of
// random numbers into random neighborhoods (sizes 0-200; smooth, noisy, identical, duplicated,
// collinear, coplanar, two-sheet, unstructured or clustered points; tiny to huge scales, far
// translations, NaN/inf injection), random orders 0-12 and random options, fits them with
// CGAL::Wavejet_fitting, and runs the four point-set functions on random small point sets with
// random parameters. Each call checks: no crash, only the documented exception types (and exactly
// when the input is documented as invalid), finite outputs or the failure state, point count and
// order preserved, report consistent.

#ifndef WAVEJETS_TEST_FUZZ_HARNESS_H
#define WAVEJETS_TEST_FUZZ_HARNESS_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Wavejet_fitting.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <Eigen/Geometry>

#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace wavejets_fuzz {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
typedef std::pair<Point, Vector> PN;
typedef CGAL::Wavejet_fitting<K> Fitting;
typedef Fitting::Wavejet_form Form;
namespace WP = CGAL::Wavejets::parameters;

/// Random numbers from a 64-bit generator: `Next` is `uint64_t()`.
template <class Next>
struct Source
{
  Next next;
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); } // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  std::size_t below(std::size_t n) { return n ? std::size_t(next() % n) : 0; }
  bool chance(double p) { return uniform() < p; }
  double normal() { const double u = uniform(1e-300, 1.), v = uniform(); return std::sqrt(-2 * std::log(u)) * std::cos(6.283185307179586 * v); }
};

/// splitmix64: the seeded generator of test_fuzz.
struct Splitmix
{
  std::uint64_t state;
  std::uint64_t operator()()
  {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
};

/// The libFuzzer input as a generator (zeros once exhausted).
struct Bytes
{
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  std::uint64_t operator()()
  {
    std::uint64_t v = 0;
    for(int i = 0; i < 8; ++i) v = (v << 8) | (pos < size ? data[pos++] : 0);
    return v;
  }
};

inline bool fin(double x) { return std::isfinite(x); }
inline bool fin(const Point& p) { return fin(p.x()) && fin(p.y()) && fin(p.z()); }
inline bool fin(const Vector& v) { return fin(v.x()) && fin(v.y()) && fin(v.z()); }
inline bool unit(const Vector& v) { return fin(v) && std::abs(std::sqrt(v.squared_length()) - 1.) < 1e-6; }
inline bool same_bits(const Point& a, const Point& b)
{
  const double x[3] = {a.x(), a.y(), a.z()}, y[3] = {b.x(), b.y(), b.z()};
  return std::memcmp(x, y, sizeof x) == 0;
}
inline bool same_bits(const Vector& a, const Vector& b)
{
  const double x[3] = {a.x(), a.y(), a.z()}, y[3] = {b.x(), b.y(), b.z()};
  return std::memcmp(x, y, sizeof x) == 0;
}

/// Counters of a fuzz run. A "real fit" is a call of the fitting core (internal::Fitter::fit) with
/// order >= 1 on accepted parameters and finite input, i.e. one that gets past the input checks to
/// the adaptive order, the PCA and the least squares (see fuzz_fit and fuzz_function).
struct Stats
{
  std::size_t fits = 0, valid_fits = 0, failed_fits = 0, order_zero_rejections = 0, function_calls = 0,
              invalid_argument = 0, fitted_points = 0;
  std::size_t real_fits = 0;          // Wavejet_fitting calls that are real fits
  std::size_t function_real_fits = 0; // points of accepted function calls that are real fits
  std::size_t non_finite_fits = 0;    // Wavejet_fitting calls rejected with NON_FINITE_INPUT
  std::string first_failure;
  std::size_t failures = 0;
  void fail(const std::string& what)
  {
    if(failures++ == 0) first_failure = what;
  }
};

/// A random neighborhood (query point first) and its normals, with random degeneracies.
template <class Src>
void random_points(Src& s, std::size_t L, std::vector<Point>& pts, std::vector<Vector>& normals, int& structure)
{
  pts.clear();
  normals.clear();
  structure = int(s.below(10));
  const double a = s.uniform(-2, 2), b = s.uniform(-2, 2), c = s.uniform(-2, 2), d3 = s.uniform(-1, 1);
  const double noise = structure == 1 ? s.uniform(0, 0.05) : 0.;
  Eigen::Quaterniond q(s.normal(), s.normal(), s.normal(), s.normal());
  if(q.norm() == 0) q = Eigen::Quaterniond::Identity();
  q.normalize();
  const Eigen::Matrix3d R = q.toRotationMatrix();
  double scale = std::pow(10., s.uniform(-1, 1));
  if(s.chance(0.1)) scale = std::pow(10., s.uniform(-150, 150)); // tiny or huge
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  if(s.chance(0.15)) t = Eigen::Vector3d(s.normal(), s.normal(), s.normal()) * std::pow(10., s.uniform(0, 9));
  for(std::size_t i = 0; i < L; ++i)
  {
    double x = i == 0 ? 0. : s.uniform(-1, 1), y = i == 0 ? 0. : s.uniform(-1, 1), z = 0., nx = 0, ny = 0;
    switch(structure)
    {
      case 0: case 1: case 5:
        z = a * x * x + b * x * y + c * y * y + d3 * x * x * x + noise * s.normal();
        nx = -(2 * a * x + b * y + 3 * d3 * x * x); ny = -(b * x + 2 * c * y);
        break;
      case 2: x = y = 0.; break;                                    // all identical
      case 3: y = 0.5 * x; z = (s.chance(0.2) ? 1e-14 * s.normal() : 0.); break; // collinear
      case 4: break;                                                // coplanar
      case 6: z = (i % 2) * 0.05; break;                           // two sheets
      case 7: z = s.uniform(-1, 1); break;                          // no structure
      case 8: { const double r2 = x * x + y * y; z = r2 < 1 ? 1. - std::sqrt(1. - r2) : 0.; nx = -x; ny = -y; break; }
      case 9: if(s.chance(0.5)) x = y = 0.; z = a * x * x; break;   // clustered on the query
    }
    const Eigen::Vector3d p = R * Eigen::Vector3d(x, y, z) * scale + t;
    Eigen::Vector3d n = R * Eigen::Vector3d(nx, ny, 1.).normalized();
    if(structure == 6 && i % 2) n = -n;
    if(s.chance(0.1)) n = -n; // unoriented
    pts.push_back(Point(p.x(), p.y(), p.z()));
    normals.push_back(Vector(n.x(), n.y(), n.z()));
  }
  if(structure == 5 && L > 1) // exact duplicates
    for(std::size_t i = 0, m = s.below(L); i < m; ++i)
    {
      const std::size_t from = s.below(L), to = s.below(L);
      pts[to] = pts[from];
    }
  const double bad[4] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity(), 1e308};
  if(L > 0 && s.chance(0.05)) // non-finite (or extreme) coordinates
    for(std::size_t i = 0, m = 1 + s.below(3); i < m; ++i)
    {
      const std::size_t j = s.below(L);
      const Point& p = pts[j];
      double c3[3] = {p.x(), p.y(), p.z()};
      c3[s.below(3)] = bad[s.below(4)];
      pts[j] = Point(c3[0], c3[1], c3[2]);
    }
  if(L > 0 && s.chance(0.05)) normals[s.below(L)] = Vector(0, 0, 0);
  if(L > 0 && s.chance(0.05)) normals[s.below(L)] = Vector(std::numeric_limits<double>::quiet_NaN(), 0, 1);
}

/// Checks a form: valid -> every quantity finite; otherwise the documented failure state.
inline void check_form(const Form& f, const Point& query, Stats& st)
{
  if(f.is_valid())
  {
    ++st.valid_fits;
    bool ok = fin(f.origin()) && unit(f.normal_direction()) && unit(f.first_tangent_direction()) &&
              unit(f.second_tangent_direction()) && unit(f.frame_normal_direction()) &&
              unit(f.maximal_principal_direction()) && unit(f.minimal_principal_direction()) &&
              fin(f.mean_curvature()) && fin(f.gaussian_curvature()) && fin(f.principal_curvatures(0)) &&
              fin(f.principal_curvatures(1)) && fin(f.radius()) && f.radius() > 0 && f.order() >= 1 &&
              fin(f.tangent_plane_residual()) && fin(f.enclosed_area_coefficient(0).real()) &&
              f.coefficients().size() == (f.order() + 1) * (f.order() + 2) / 2;
    for(double c : f.coefficients()) ok = ok && fin(c);
    if(!ok)
    {
      std::ostringstream os;
      os.precision(17);
      os << "valid form with a non-finite or inconsistent quantity:\n" << f;
      st.fail(os.str());
    }
  }
  else
  {
    ++st.failed_fits;
    if(f.status() == CGAL::Wavejets::Fit_status::SUCCESS || f.order() != 0 || !f.coefficients().empty() ||
       f.mean_curvature() != 0 || !same_bits(f.origin(), query))
      st.fail("failed form not in the documented failure state");
  }
}

/// One Wavejet_fitting call on a random neighborhood with random order and options. Counts it in
/// `st.real_fits` when it is a real fit: order >= 1 (order 0 throws before any work), at least one
/// point, and a status other than NON_FINITE_INPUT (the only status of the early returns for a
/// non-finite query point, offset q - p or normal, in Wavejet_fitting and in the fitting core).
template <class Src>
void fuzz_fit(Src& s, Fitting& fitting, Stats& st, std::vector<Point>& pts, std::vector<Vector>& normals)
{
  std::size_t L;
  const double u = s.uniform();
  L = u < 0.3 ? s.below(13) : u < 0.85 ? 13 + s.below(48) : 61 + s.below(140); // 0..200
  int structure;
  random_points(s, L, pts, normals, structure);
  const std::size_t order = s.below(13); // 0..12
  CGAL::Wavejets::Fitting_options& o = fitting.options();
  o = CGAL::Wavejets::Fitting_options();
  if(s.chance(0.3)) o.neighbors_per_coefficient = s.chance(0.1) ? std::numeric_limits<double>::quiet_NaN() : s.uniform(0.5, 3.);
  if(s.chance(0.3)) o.minimum_order = s.below(5);
  if(s.chance(0.3)) o.correction_iterations = s.below(4);
  if(s.chance(0.3)) o.robust_iterations = s.below(4);
  if(s.chance(0.15))
  {
    const double r = L > 1 ? std::sqrt(CGAL::squared_distance(pts[0], pts[L - 1])) : 1.;
    o.neighborhood_radius = s.chance(0.2) ? std::pow(10., s.uniform(-300, 300)) : r * s.uniform(0.5, 2.);
  }
  if(s.chance(0.3)) o.curvature_frame = CGAL::Wavejets::Curvature_frame::TANGENT_FRAME;
  if(s.chance(0.3)) o.normal_use = CGAL::Wavejets::Normal_use::SEED_FRAME;
  o.compute_condition_number = s.chance(0.3);
  const bool with_normal = L > 0 && s.chance(0.5);
  ++st.fits;
  const std::size_t failures_before = st.failures;
  struct Describe // on a new failure, appends the input to the message
  {
    Stats& st; std::size_t before; const std::vector<Point>& pts; std::size_t order; int structure; bool normal;
    const CGAL::Wavejets::Fitting_options& o;
    ~Describe()
    {
      if(st.failures != before + 1) return;
      std::ostringstream os;
      os.precision(17);
      os << "\n  input: structure " << structure << ", order " << order << ", normal " << normal << ", beta "
         << o.neighbors_per_coefficient << ", min order " << o.minimum_order << ", corrections " << o.correction_iterations
         << ", robust " << o.robust_iterations << ", radius " << o.neighborhood_radius << ", L " << pts.size() << "\n";
      for(std::size_t i = 0; i < pts.size() && i < 8; ++i) os << "    " << pts[i] << "\n";
      st.first_failure += os.str();
    }
  } describe{st, failures_before, pts, order, structure, with_normal, o};
  try
  {
    Form f = with_normal ? fitting(pts.begin(), pts.end(), order, normals[0]) : fitting(pts.begin(), pts.end(), order);
    if(order == 0) st.fail("order 0 accepted by Wavejet_fitting (std::invalid_argument expected)");
    if(f.status() == CGAL::Wavejets::Fit_status::NON_FINITE_INPUT) ++st.non_finite_fits;
    else if(L > 0 && order >= 1) ++st.real_fits;
    check_form(f, L ? pts[0] : Point(CGAL::ORIGIN), st);
    if(L && f.is_valid() != (f.status() == CGAL::Wavejets::Fit_status::SUCCESS)) st.fail("is_valid inconsistent");
    if(f.is_valid() && !(fin(fitting.condition_number()) || !o.compute_condition_number))
    {
      // an infinite condition number is allowed (exactly singular R), NaN is not
      if(std::isnan(fitting.condition_number())) st.fail("NaN condition number");
    }
  }
  catch(const std::invalid_argument&)
  {
    ++st.order_zero_rejections;
    if(order != 0) st.fail("std::invalid_argument with order >= 1");
  }
  catch(const std::exception& e)
  {
    st.fail(std::string("Wavejet_fitting threw an undocumented exception: ") + e.what());
  }
}

/// Writable map keyed by the elements of a vector (writes to the parallel vector `out`).
template <class V>
struct Slot_map
{
  typedef PN key_type;
  typedef V value_type;
  typedef V reference;
  typedef boost::writable_property_map_tag category;
  const PN* base;
  std::vector<V>* out;
  friend void put(const Slot_map& m, const PN& key, const V& v) { (*m.out)[std::size_t(&key - m.base)] = v; }
};

/// One call of a random point-set function on a random small point set with random parameters.
/// Returns the number of real fits it made: 0 when the parameters are rejected, otherwise the
/// number of points with finite coordinates (the driver calls the fitting core once for each of
/// them, with order >= 1; non-finite neighbors are never returned by the neighbor query, and a
/// non-finite input normal only leaves the fit unoriented). This is a lower bound: the functions
/// that re-estimate normals (write_normals) fit the moved points a second time, not counted.
/// Also added to `st.function_real_fits`.
template <class Src>
std::size_t fuzz_function(Src& s, Stats& st, std::vector<Point>& pts, std::vector<Vector>& normals)
{
  const std::size_t N = s.below(61);
  int structure;
  random_points(s, N, pts, normals, structure);
  std::vector<PN> in(N);
  for(std::size_t i = 0; i < N; ++i) in[i] = PN(pts[i], normals[i]);
  std::vector<PN> v = in;
  const int fn = int(s.below(4));
  // Parameters, some invalid on purpose; `invalid` predicts the documented std::invalid_argument.
  unsigned int k = unsigned(s.below(40));
  if(s.chance(0.03)) k = 4000000000u;
  double radius = 0.;
  if(s.chance(0.2))
  {
    const double r = N > 1 ? std::sqrt(CGAL::squared_distance(pts[0], pts[N - 1])) : 1.;
    const double pick = s.uniform();
    radius = pick < 0.05 ? -1. : pick < 0.1 ? std::numeric_limits<double>::quiet_NaN() : pick < 0.2 ? 1e-300
                                                                                          : r * s.uniform(0.1, 1.);
    if(!fin(radius)) radius = pick < 0.07 ? std::numeric_limits<double>::infinity() : radius;
  }
  const std::size_t order = s.below(9);
  const double beta = s.chance(0.1) ? s.uniform(0.5, 1.5) : 1.1;
  const std::size_t robust = s.chance(0.2) ? s.below(3) : 0, corrections = s.below(3), min_order = s.below(4);
  const bool restrict_normals = s.chance(0.2), seed = s.chance(0.2), orient = s.chance(0.3);
  double gain = s.uniform(-3, 5);
  if(s.chance(0.05)) gain = s.chance(0.5) ? std::numeric_limits<double>::quiet_NaN() : std::pow(10., s.uniform(0, 110));
  std::complex<double> cgain(gain, s.chance(0.5) ? s.uniform(-2, 2) : 0.);
  double clamp = 0.; // default
  if(s.chance(0.2)) clamp = s.chance(0.3) ? std::numeric_limits<double>::infinity() : s.chance(0.1) ? -1. : s.uniform(1e-6, 1.);
  double eval_radius = s.chance(0.2) ? (s.chance(0.1) ? -1. : s.uniform(0, 2.)) : 0.;

  bool invalid = order == 0 || !(beta >= 1.) || (k < 2 && !(radius > 0)) || !(fin(radius) && !(radius < 0));
  if(fn >= 2) invalid = invalid || !fin(gain) || std::abs(cgain) > 1e100 || (fn == 2 && std::abs(gain) > 1e100) || eval_radius < 0;
  if(fn == 2) invalid = invalid || (clamp != 0. && !(clamp > 0));

  typedef CGAL::First_of_pair_property_map<PN> Pmap;
  typedef CGAL::Second_of_pair_property_map<PN> Nmap;
  std::vector<double> H(N, 12345.), KG(N, 12345.);
  std::vector<bool> fitted_b(N, false);
  std::vector<int> fitted(N, 0);
  auto base = WP::order(order).neighbors_per_coefficient(beta).robust_iterations(robust).correction_iterations(corrections)
                .minimum_order(min_order).restrict_to_consistent_normals(restrict_normals).seed_with_input_normals(seed)
                .evaluation_radius(eval_radius).fitted_map(Slot_map<int>{v.data(), &fitted});
  const bool parallel = s.chance(0.02);
  CGAL::Wavejets::Processing_report rep;
  ++st.function_calls;
  try
  {
    auto np = base.neighbor_radius(radius).point_map(Pmap()).normal_map(Nmap());
    switch(fn)
    {
      case 0:
        rep = parallel ? CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(v, k, WP::orient_with_input_normals(orient, np))
                       : CGAL::wavejet_estimate_normals<CGAL::Sequential_tag>(v, k, WP::orient_with_input_normals(orient, np));
        break;
      case 1:
        rep = CGAL::wavejet_estimate_curvatures<CGAL::Sequential_tag>(
          v, k, WP::mean_curvature_map(Slot_map<double>{v.data(), &H}, WP::gaussian_curvature_map(Slot_map<double>{v.data(), &KG}, np)));
        break;
      case 2:
        if(clamp != 0.)
          rep = CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(v, k, gain, WP::maximum_displacement(clamp, WP::write_normals(s.chance(0.5), np)));
        else
          rep = parallel ? CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(v, k, gain, WP::write_normals(true, np))
                         : CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(v, k, gain, np);
        break;
      default:
        rep = CGAL::wavejet_enhance_normals<CGAL::Sequential_tag>(v, k, cgain, np);
    }
    if(invalid) st.fail("function " + std::to_string(fn) + " accepted invalid parameters");
  }
  catch(const std::invalid_argument& e)
  {
    ++st.invalid_argument;
    if(!invalid) st.fail("function " + std::to_string(fn) + " threw on valid parameters: " + e.what());
    if(v.size() != N) st.fail("input resized by a throwing call");
    for(std::size_t i = 0; i < N && i < v.size(); ++i)
      if(!same_bits(v[i].first, in[i].first) || !same_bits(v[i].second, in[i].second))
      { st.fail("input modified by a throwing call"); break; }
    return 0;
  }
  catch(const std::exception& e)
  {
    st.fail("function " + std::to_string(fn) + " threw an undocumented exception: " + e.what());
    return 0;
  }
  // Invariants: count, order, untouched unfitted points, finite outputs, consistent report.
  if(v.size() != N) { st.fail("point count changed"); return 0; }
  std::size_t nfit = 0, nonfinite = 0;
  for(std::size_t i = 0; i < N; ++i)
  {
    nonfinite += !fin(in[i].first);
    if(!fitted[i])
    {
      if(!same_bits(v[i].first, in[i].first) || !same_bits(v[i].second, in[i].second) || H[i] != 12345.)
        st.fail("unfitted point modified");
      continue;
    }
    ++nfit;
    if(!fin(in[i].first)) st.fail("non-finite point fitted");
    if(!fin(v[i].first)) st.fail("non-finite output position");
    if(fn != 2 && !same_bits(v[i].first, in[i].first)) st.fail("position changed by a function that must not move points");
    if((fn == 0 || fn == 3) && !unit(v[i].second)) st.fail("non-unit or non-finite output normal");
    if(fn == 1 && !(fin(H[i]) && fin(KG[i]))) st.fail("non-finite curvature");
  }
  st.fitted_points += nfit;
  if(rep.number_of_points != N || rep.number_of_fitted_points != nfit || rep.number_of_fitted_points + rep.number_of_unfitted_points != N ||
     rep.number_of_non_finite_points != nonfinite || rep.interrupted)
    st.fail("inconsistent Processing_report");
  st.function_real_fits += N - nonfinite;
  return N - nonfinite;
}

} // namespace wavejets_fuzz

#endif // WAVEJETS_TEST_FUZZ_HARNESS_H
