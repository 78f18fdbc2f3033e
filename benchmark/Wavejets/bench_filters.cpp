// Transfer functions of the two Wavejet filters, against the unsharp-masking baselines of the
// paper's Figure 6 (Béarzi et al. 2018), in one run.
//
// Surface: the plane z = A sin(2 pi x / lambda) + white noise (Gaussian, along z, sigma = A / 10),
// sampled on a jittered grid (spacing h = Rf / 6, jitter +-0.15 h: about 113 points per
// neighborhood, the density at which the figures issue 13 quotes are reproduced), A = Rf / 20,
// lambda / Rf from 1 to 20. Every filter runs on the same noisy sample with radius neighborhoods of
// radius Rf (k = 0, neighbor_radius Rf); the measures are taken on the interior points (at least
// 1.5 Rf from the border of the sample, so that their neighborhoods are full discs).
//
// Measures (least squares on the known pattern, interior points):
//   positions  fit z = a sin(w x) + b cos(w x) + c to the points (x, z), w = 2 pi / lambda, before and
//              after the filter (after: at the moved points' own x). Detail gain = a_out / a_in (signed:
//              an inverted detail has a negative gain), noise gain = RMS residual out / RMS residual in.
//   normals    the tilt pattern: the slope s_x = -n_x / n_z of the normals, fitted as a cos(w x) +
//              b sin(w x) + c (the exact slope is A w cos(w x)); residual = (s_x - fit, s_y), since
//              the pattern has no y slope. The normal filter has no noisy input normals to compare
//              with (the input normals only orient it), so its gains are relative to its identity,
//              gain 1 (the Wavejet's own, denoised normal): detail gain = a(gain) / a(1), noise gain
//              = RMS residual(gain) / RMS residual(1). The column "kept" = a(1) / (A w) says how much
//              of the exact tilt the Wavejet normal itself keeps.
//
// wavejet_enhance_positions is linear in the gain once the fits are done (p' = p + (f00 - 2 pi
// (gain - 1) a0 / Rf^2) n): the transfer tables run it at gains 1 and 2 with the clamp off and get
// the other gains as p1 + (gain - 1)(p2 - p1) (checked against a direct run). The headline check
// runs it directly, with the default clamp (Rf / 2).
//
// Baselines (positions, same neighborhoods, same degree K as the Wavejet order):
//   H-USM   unsharp masking by the mean curvature: p' = p - c H n, with H = (k1 + k2) / 2 and n from
//           CGAL::Monge_via_jet_fitting (degree K, Monge degree 2) on the point's radius-Rf
//           neighborhood (query point first), n oriented up (comply_wrt_given_normal).
//   J-USM   unsharp masking by CGAL::jet_smooth_point_set (degree K, the k nearest neighbors with k the
//           mean number of points in a disc of radius Rf; CGAL 5.5's radius query does not put the
//           query point first, and the jet's origin is then the projection of another point):
//           p' = p + (g - 1)(p - smooth(p)).
// Both are linear in their factor (c, g); "at equal detail gain" solves the factor that gives the
// Wavejet filter's detail gain (same lambda, K, gain), then measures that output's noise gain.
// J-USM is also reported at g = the Wavejet gain (the comparison issue 13 quotes).
//
// Usage: bench_filters [--quick] [--csv-dir DIR]
// Writes its tables as DIR/filters.*.csv (default: csv/ next to this source); make_reports.py writes filters.md
// and filters.png from them (see README.md in this folder).
// --quick: lambda / Rf in {2, 4, 10} and K in {2, 4} only (a smoke run; writes nothing unless --csv-dir).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Real_timer.h>
#include <CGAL/jet_smooth_point_set.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/Wavejets/internal/neighbor_query.h>

#include "bench_common.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef std::pair<Point, Vector> PV;
typedef std::vector<PV> PV_range;
typedef CGAL::First_of_pair_property_map<PV> Point_map;
typedef CGAL::Second_of_pair_property_map<PV> Normal_map;
typedef CGAL::Parallel_if_available_tag Tag;
namespace WP = CGAL::Wavejets::parameters;

static const double PI = 3.14159265358979323846;
static const double Rf = 1.;             // neighborhood radius (the unit of the benchmark)
static const double A = 0.05 * Rf;       // detail amplitude
static const double noise_ratio = 0.1;   // noise sigma / A
static const double gains[] = {-1., 0., 2., 3.};

static std::string fmt(double v, int prec = 3)
{
  if(!std::isfinite(v)) return "n/a";
  std::ostringstream s;
  if(v != 0. && (std::abs(v) < 1e-3 || std::abs(v) >= 1e4)) s << std::scientific << std::setprecision(prec - 1) << v;
  else s << std::fixed << std::setprecision(prec - 1 - (std::abs(v) >= 10. ? 1 : 0)) << v;
  return s.str();
}

// Portable deterministic standard normal (mt19937_64 is specified by the standard; the
// distributions are not, so Box-Muller is written out).
struct Gauss
{
  std::mt19937_64 gen;
  explicit Gauss(std::uint64_t seed) : gen(seed) {}
  double uniform() { return (double(gen() >> 11) + 0.5) * (1. / 9007199254740992.); }
  double operator()() { return std::sqrt(-2. * std::log(uniform())) * std::cos(2. * PI * uniform()); }
};

// ---------------------------------------------------------------------------------------------
// The sample
// ---------------------------------------------------------------------------------------------
struct Sample
{
  double lambda, h;
  PV_range points;                 // noisy positions, exact upward normals of the pattern
  std::vector<std::size_t> inner;  // interior points (full neighborhoods)
  double w() const { return 2. * PI / lambda; }
};

// Grid of spacing h on [0, Lx] x [0, Ly]: Lx covers a wavelength (at least 10 Rf) plus the
// margins, Ly a band of 4 Rf plus the margins.
static Sample make_sample(double lambda, double h, double noise_sigma, std::uint64_t seed)
{
  Sample s;
  s.lambda = lambda;
  s.h = h;
  const double margin = 1.5 * Rf;
  const double Lx = (std::max)(lambda, 10. * Rf) + 2. * margin, Ly = 4. * Rf + 2. * margin;
  const std::size_t nx = std::size_t(Lx / h) + 1, ny = std::size_t(Ly / h) + 1;
  Gauss g(seed);
  const double w = s.w();
  for(std::size_t i = 0; i < nx; ++i)
    for(std::size_t j = 0; j < ny; ++j)
    {
      const double x = (double(i) + 0.3 * (g.uniform() - 0.5)) * h;
      const double y = (double(j) + 0.3 * (g.uniform() - 0.5)) * h;
      const double z = A * std::sin(w * x) + noise_sigma * g();
      const double dz = A * w * std::cos(w * x);
      if(x >= margin && x <= Lx - margin && y >= margin && y <= Ly - margin) s.inner.push_back(s.points.size());
      s.points.emplace_back(Point(x, y, z), Vector(-dz, 0., 1.) / std::sqrt(1. + dz * dz));
    }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Pattern fits
// ---------------------------------------------------------------------------------------------
struct Pattern
{
  double amplitude = 0.; // in-phase coefficient
  double rms = 0.;       // RMS residual
};

// Least squares of values[i] ~ a f(w t_i) + b g(w t_i) + c over the interior points; extra[i] (if
// given) adds to the residual (a component the pattern does not have).
static Pattern fit_pattern(const Sample& s, const std::vector<double>& t, const std::vector<double>& values,
                           bool cosine_pattern, const std::vector<double>* extra = nullptr)
{
  const std::size_t m = s.inner.size();
  Eigen::MatrixXd M(m, 3);
  Eigen::VectorXd z(m);
  for(std::size_t r = 0; r < m; ++r)
  {
    const std::size_t i = s.inner[r];
    const double sn = std::sin(s.w() * t[i]), cs = std::cos(s.w() * t[i]);
    M(r, 0) = cosine_pattern ? cs : sn;
    M(r, 1) = cosine_pattern ? sn : cs;
    M(r, 2) = 1.;
    z(r) = values[i];
  }
  const Eigen::Vector3d c = M.colPivHouseholderQr().solve(z);
  const Eigen::VectorXd res = z - M * c;
  double ss = res.squaredNorm();
  if(extra)
    for(std::size_t r = 0; r < m; ++r) ss += (*extra)[s.inner[r]] * (*extra)[s.inner[r]];
  Pattern p;
  p.amplitude = c(0);
  p.rms = std::sqrt(ss / double(m));
  return p;
}

static Pattern height_pattern(const Sample& s, const std::vector<Point>& pts)
{
  std::vector<double> x(pts.size()), z(pts.size());
  for(std::size_t i = 0; i < pts.size(); ++i) { x[i] = pts[i].x(); z[i] = pts[i].z(); }
  return fit_pattern(s, x, z, false);
}

static Pattern tilt_pattern(const Sample& s, const PV_range& pts)
{
  std::vector<double> x(pts.size()), sx(pts.size()), sy(pts.size());
  for(std::size_t i = 0; i < pts.size(); ++i)
  {
    const Vector& n = pts[i].second;
    x[i] = s.points[i].first.x();
    sx[i] = -n.x() / n.z();
    sy[i] = -n.y() / n.z();
  }
  return fit_pattern(s, x, sx, true, &sy);
}

static std::vector<Point> positions(const PV_range& r)
{
  std::vector<Point> p;
  p.reserve(r.size());
  for(const PV& q : r) p.push_back(q.first);
  return p;
}

// p + c * (q - p), per point (q - p: a per-point motion, scaled).
static std::vector<Point> scaled_motion(const std::vector<Point>& p, const std::vector<Vector>& motion, double c)
{
  std::vector<Point> out(p.size());
  for(std::size_t i = 0; i < p.size(); ++i) out[i] = p[i] + c * motion[i];
  return out;
}

// ---------------------------------------------------------------------------------------------
// Filters
// ---------------------------------------------------------------------------------------------
static std::vector<Point> wavejet_positions(const Sample& s, std::size_t K, double gain, bool clamp,
                                            double evaluation_radius = 0.)
{
  PV_range pts = s.points;
  if(clamp)
    CGAL::wavejet_enhance_positions<Tag>(pts, 0, gain, WP::order(K).evaluation_radius(evaluation_radius).neighbor_radius(Rf)
                                                         .point_map(Point_map()).normal_map(Normal_map()));
  else
    CGAL::wavejet_enhance_positions<Tag>(pts, 0, gain, WP::order(K).maximum_displacement(std::numeric_limits<double>::infinity())
                                                         .neighbor_radius(Rf).point_map(Point_map()).normal_map(Normal_map()));
  return positions(pts);
}

static PV_range wavejet_normals(const Sample& s, std::size_t K, double gain)
{
  PV_range pts = s.points;
  CGAL::wavejet_enhance_normals<Tag>(pts, 0, gain, WP::order(K).neighbor_radius(Rf)
                                                     .point_map(Point_map()).normal_map(Normal_map()));
  return pts;
}

// H-USM: per point, the motion -H n of CGAL's jet (degree K) on its radius-Rf neighborhood.
static std::vector<Vector> mean_curvature_motion(const Sample& s, std::size_t K)
{
  typedef CGAL::Wavejets::internal::Neighbor_query Query;
  std::vector<Query::Point> pts;
  for(const PV& p : s.points) pts.emplace_back(p.first.x(), p.first.y(), p.first.z());
  const std::vector<unsigned char> in_tree(pts.size(), 1);
  const Query query(pts, in_tree);
  std::vector<Vector> motion(pts.size(), CGAL::NULL_VECTOR);
  CGAL::Monge_via_jet_fitting<Kernel> monge;
  std::vector<std::size_t> nb;
  Query::Scratch scratch;
  std::vector<Point> hood;
  for(std::size_t i = 0; i < pts.size(); ++i)
  {
    query.neighbors(i, 0, Rf, nb, scratch);
    hood.assign(1, s.points[i].first);
    for(std::size_t j : nb) hood.push_back(s.points[j].first);
    if(hood.size() < (K + 1) * (K + 2) / 2) continue; // CGAL's precondition: border points only
    auto m = monge(hood.begin(), hood.end(), K, 2);
    m.comply_wrt_given_normal(Vector(0., 0., 1.));
    const double H = 0.5 * (m.principal_curvatures(0) + m.principal_curvatures(1));
    motion[i] = -H * m.normal_direction();
  }
  return motion;
}

// J-USM: per point, p - smooth(p) (CGAL::jet_smooth_point_set, degree K, k nearest: as many points as
// a disc of radius Rf holds on average).
static std::vector<Vector> jet_detail(const Sample& s, std::size_t K)
{
  std::vector<Point> smooth = positions(s.points);
  const unsigned int k = (unsigned int)(std::lround(PI * Rf * Rf / (s.h * s.h)));
  CGAL::jet_smooth_point_set<Tag>(smooth, k, CGAL::parameters::degree_fitting(K));
  std::vector<Vector> d(smooth.size());
  for(std::size_t i = 0; i < smooth.size(); ++i) d[i] = s.points[i].first - smooth[i];
  return d;
}

// A baseline p + c * motion at the factor c that gives detail gain `target` (linear in c, solved on
// the heights at the input x, then measured exactly on the moved points).
struct Matched
{
  double factor = std::numeric_limits<double>::quiet_NaN();
  double detail = std::numeric_limits<double>::quiet_NaN();
  double noise = std::numeric_limits<double>::quiet_NaN();
};
static Matched match_detail(const Sample& s, const std::vector<Vector>& motion, double target, const Pattern& in)
{
  std::vector<double> x(motion.size()), dz(motion.size());
  for(std::size_t i = 0; i < motion.size(); ++i) { x[i] = s.points[i].first.x(); dz[i] = motion[i].z(); }
  const double a = fit_pattern(s, x, dz, false).amplitude;
  Matched r;
  const double c = (target - 1.) * in.amplitude / a;
  if(!std::isfinite(c) || std::abs(c) * std::abs(a) < 1e-9 * in.amplitude || std::abs(a) < 1e-3 * in.amplitude)
    return r; // the baseline barely sees the pattern: no factor reaches the target
  const Pattern out = height_pattern(s, scaled_motion(positions(s.points), motion, c));
  r.factor = c;
  r.detail = out.amplitude / in.amplitude;
  r.noise = out.rms / in.rms;
  return r;
}

struct Gain_pair { double detail, noise; };

// ---------------------------------------------------------------------------------------------
// The paper's Figure 12 pipeline (move_along_input_normals) and the other ways to move along a
// given direction m (unit, on the side of the Wavejet normal n) by the filter's height d:
//   (c) p + d m               what move_along_input_normals does (the motion's length is |d|)
//   (a) p + d / (n.m) m       lands on the plane at height d over p's tangent plane
//   (b) p + d (n.m) m         the projection of the default motion d n onto the line of m
// (a) and (b) are computed from the run of (c) (d = motion . m) and the Wavejet normals n.
// ---------------------------------------------------------------------------------------------
struct Pipeline_row
{
  std::string name;
  Gain_pair g;
  double drift; // RMS of the motions' y component (off the pattern) / input noise sigma
};

static std::vector<Pipeline_row> figure12_pipeline(double lambda, double noise_sigma, std::size_t K, double gain)
{
  const Sample s = make_sample(lambda, Rf / 6., noise_sigma, 4242);
  const std::vector<Point> p0 = positions(s.points);
  const Pattern in = height_pattern(s, p0);
  // Default mode, with the Wavejet normals (at the input points) written.
  PV_range def = s.points;
  CGAL::wavejet_enhance_positions<Tag>(def, 0, gain, WP::order(K).write_normals(true).neighbor_radius(Rf)
                                                       .point_map(Point_map()).normal_map(Normal_map()));
  // Pipeline: normals filtered at gain 0, then positions moved along them.
  PV_range filtered = wavejet_normals(s, K, 0.), along = filtered;
  CGAL::wavejet_enhance_positions<Tag>(along, 0, gain, WP::order(K).move_along_input_normals(true).neighbor_radius(Rf)
                                                         .point_map(Point_map()).normal_map(Normal_map()));
  std::vector<Vector> a_motion(p0.size()), b_motion(p0.size());
  for(std::size_t i = 0; i < p0.size(); ++i)
  {
    const Vector n = def[i].second, m = filtered[i].second / std::sqrt(filtered[i].second.squared_length());
    const double d = (along[i].first - p0[i]) * m, c = n * m;
    a_motion[i] = (d / c) * m;
    b_motion[i] = (d * c) * m;
  }
  const auto row = [&](const std::string& name, const std::vector<Point>& out) {
    const Pattern o = height_pattern(s, out);
    double drift = 0.;
    for(std::size_t i : s.inner) drift += CGAL::square(out[i].y() - p0[i].y());
    return Pipeline_row{name, {o.amplitude / in.amplitude, o.rms / in.rms},
                        std::sqrt(drift / double(s.inner.size())) / noise_sigma};
  };
  return {row("default: along the Wavejet normal", positions(def)),
          row("(c) Figure 12: along the gain-0 normals, p + d m (move_along_input_normals)", positions(along)),
          row("(a) along the gain-0 normals, p + d / (n.m) m", scaled_motion(p0, a_motion, 1.)),
          row("(b) along the gain-0 normals, p + d (n.m) m", scaled_motion(p0, b_motion, 1.))};
}

// ---------------------------------------------------------------------------------------------
// Command line
// ---------------------------------------------------------------------------------------------

struct Options
{
  std::string out_dir = wavejets_bench::source_dir() + "/csv";
  bool quick = false, out_given = false;
  bool write() const { return !quick || out_given; } // --quick writes nothing unless --csv-dir
};

/// Reads the options; false on a usage error.
static bool parse_command_line(int argc, char** argv, Options& o)
{
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--quick") o.quick = true;
    else if(a == "--csv-dir" && i + 1 < argc) { o.out_dir = argv[++i]; o.out_given = true; }
    else
    {
      std::cerr << "usage: bench_filters [--quick] [--csv-dir DIR]\n";
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Measures
// ---------------------------------------------------------------------------------------------

/// The transfer tables: results[K][lambda index][gain index].
struct Transfer
{
  std::vector<double> lambdas;
  std::vector<std::size_t> orders;
  std::map<std::size_t, std::vector<std::vector<Gain_pair> > > pos, nrm;
  std::map<std::size_t, std::vector<double> > kept;
  std::map<std::size_t, std::vector<std::vector<Matched> > > husm, jusm;
  std::map<std::size_t, std::vector<std::vector<Gain_pair> > > jusm_same; // J-USM at g = gain
  double linearity = 0.;                                                  // max |direct - p1 + 2 (p2 - p1)|
};

/// The Wavejet filters and the baselines at order K on the sample of wavelength lambdas[l].
static void measure_wavelength(Transfer& t, std::size_t K, std::size_t l, const CGAL::Real_timer& total)
{
  const double h = Rf / 6.;
  const double sigma = noise_ratio * A;
  const Sample s = make_sample(t.lambdas[l] * Rf, h, sigma, 1000 + l);
  const std::vector<Point> p0 = positions(s.points);
  const Pattern in = height_pattern(s, p0);
  // Wavejet positions: gains 1 and 2, the others by linearity.
  const std::vector<Point> p1 = wavejet_positions(s, K, 1., false), p2 = wavejet_positions(s, K, 2., false);
  std::vector<Vector> step(p0.size());
  for(std::size_t i = 0; i < p0.size(); ++i) step[i] = p2[i] - p1[i];
  if(l == 0)
  {
    const std::vector<Point> p3 = wavejet_positions(s, K, 3., false), lin = scaled_motion(p1, step, 2.);
    for(std::size_t i = 0; i < p0.size(); ++i)
      t.linearity = (std::max)(t.linearity, std::sqrt(CGAL::squared_distance(p3[i], lin[i])));
  }
  // Baselines' motions.
  const std::vector<Vector> hm = mean_curvature_motion(s, K), jd = jet_detail(s, K);
  const Pattern n1 = tilt_pattern(s, wavejet_normals(s, K, 1.));
  t.kept[K][l] = n1.amplitude / (A * s.w());
  for(double g : gains)
  {
    const Pattern out = height_pattern(s, scaled_motion(p1, step, g - 1.));
    const Gain_pair wj{out.amplitude / in.amplitude, out.rms / in.rms};
    t.pos[K][l].push_back(wj);
    const Pattern nt = tilt_pattern(s, wavejet_normals(s, K, g));
    t.nrm[K][l].push_back({nt.amplitude / n1.amplitude, nt.rms / n1.rms});
    t.husm[K][l].push_back(match_detail(s, hm, wj.detail, in));
    t.jusm[K][l].push_back(match_detail(s, jd, wj.detail, in));
    const Pattern js = height_pattern(s, scaled_motion(p0, jd, g - 1.));
    t.jusm_same[K][l].push_back({js.amplitude / in.amplitude, js.rms / in.rms});
  }
  std::cerr << "K " << K << " lambda/Rf " << t.lambdas[l] << ": " << p0.size() << " points, gain 2: detail x"
            << fmt(t.pos[K][l][2].detail) << " noise x" << fmt(t.pos[K][l][2].noise) << " (" << fmt(total.time(), 3)
            << " s)\n";
}

static Transfer measure_transfer(bool quick, const CGAL::Real_timer& total)
{
  Transfer t;
  t.lambdas = quick ? std::vector<double>{2., 4., 10.}
                    : std::vector<double>{1., 1.5, 2., 3., 4., 5., 6., 8., 10., 12., 15., 20.};
  t.orders = quick ? std::vector<std::size_t>{2, 4} : std::vector<std::size_t>{2, 4, 6, 8};
  for(std::size_t K : t.orders)
  {
    t.pos[K].resize(t.lambdas.size());
    t.nrm[K].resize(t.lambdas.size());
    t.kept[K].resize(t.lambdas.size());
    t.husm[K].resize(t.lambdas.size());
    t.jusm[K].resize(t.lambdas.size());
    t.jusm_same[K].resize(t.lambdas.size());
    for(std::size_t l = 0; l < t.lambdas.size(); ++l)
      measure_wavelength(t, K, l, total);
  }
  return t;
}

// The headline check: lambda = 4 Rf, K = 4, gain 2, direct run with the default clamp.
// The first row (about 113 points per neighborhood, evaluation radius Rf: the benchmark's sampling and
// the defaults) is the check; the others show how it moves with the density and the evaluation radius.
// noise_alone: RMS over the interior of the height difference between the outputs of the noisy
// and the noise-free sample (same jittered grid) / sigma: the propagated noise without the filter's
// own deviation from a sinusoid, which the residual also counts.
struct Check { double neighbors, s; Gain_pair wj, jet; double noise_alone; bool pass; };

static std::vector<Check> headline_checks()
{
  const double sigma = noise_ratio * A;
  std::vector<Check> checks;
  for(double hh : {Rf / 6., Rf / 3.5, Rf / 5., Rf / 7.})
    for(double ev : {1., 0.8, 0.6})
    {
      const Sample s = make_sample(4. * Rf, hh, sigma, 77);
      const Pattern in = height_pattern(s, positions(s.points));
      const std::vector<Point> wj = wavejet_positions(s, 4, 2., true, ev * Rf);
      const std::vector<Point> wj_clean = wavejet_positions(make_sample(4. * Rf, hh, 0., 77), 4, 2., true, ev * Rf);
      double alone = 0.;
      for(std::size_t i : s.inner) alone += CGAL::square(wj[i].z() - wj_clean[i].z());
      const Pattern out = height_pattern(s, wj);
      const Pattern js = height_pattern(s, scaled_motion(positions(s.points), jet_detail(s, 4), 1.));
      Check c;
      c.neighbors = PI * Rf * Rf / (hh * hh);
      c.s = ev;
      c.wj = {out.amplitude / in.amplitude, out.rms / in.rms};
      c.jet = {js.amplitude / in.amplitude, js.rms / in.rms};
      c.noise_alone = std::sqrt(alone / double(s.inner.size())) / sigma;
      c.pass = c.wj.detail > 1.5 && c.wj.noise <= 1.25;
      checks.push_back(c);
    }
  return checks;
}

static void print_checks(const std::vector<Check>& checks, const Transfer& t)
{
  for(const Check& c : checks)
    std::cout << (c.pass ? "[PASS] " : "[FAIL] ") << "plane, lambda 4 Rf, noise A/10, K 4, gain 2, ~" << fmt(c.neighbors, 2)
              << " neighbors, evaluation radius " << fmt(c.s, 2) << " Rf: Wavejet detail x" << fmt(c.wj.detail) << ", noise x"
              << fmt(c.wj.noise) << " (noise alone x" << fmt(c.noise_alone) << ") (target: detail > 1.5, noise <= 1.25); jet_smooth unsharp masking at gain 2: detail x"
              << fmt(c.jet.detail) << ", noise x" << fmt(c.jet.noise) << (&c == &checks[0] ? "  <- the check" : "") << "\n";
  std::cout << "linearity in the gain (gain 3 direct vs by linearity, lambda " << t.lambdas[0] << " Rf): max "
            << fmt(t.linearity) << " Rf\n";
}

struct Pipeline_case { double noise; std::vector<Pipeline_row> rows; };

/// The Figure 12 pipeline on noisy input.
static std::vector<Pipeline_case> figure12_cases()
{
  std::vector<Pipeline_case> pipeline;
  for(double nr : {0.5, 1.})
  {
    pipeline.push_back({nr, figure12_pipeline(4. * Rf, nr * A, 4, 2.)});
    for(const Pipeline_row& r : pipeline.back().rows)
      std::cout << "Figure 12, noise " << nr << " A, " << r.name << ": detail x" << fmt(r.g.detail) << ", noise x"
                << fmt(r.g.noise) << ", drift " << fmt(r.drift) << " sigma\n";
  }
  return pipeline;
}

/// Where the lead is lost: at equal detail gain, the Wavejet filter's noise gain against each baseline's; one line per
/// (K, gain) where a baseline has less noise.
static std::vector<std::string> where_the_lead_is_lost(const Transfer& t)
{
  std::vector<std::string> lost;
  for(std::size_t K : t.orders)
    for(std::size_t gi = 0; gi < 4; ++gi)
    {
      std::vector<std::string> where;
      for(std::size_t l = 0; l < t.lambdas.size(); ++l)
      {
        const double wj = t.pos.at(K)[l][gi].noise;
        const double hb = t.husm.at(K)[l][gi].noise, jb = t.jusm.at(K)[l][gi].noise;
        std::string who;
        if(std::isfinite(hb) && hb < wj) who += "H-USM";
        if(std::isfinite(jb) && jb < wj) who += who.empty() ? "J-USM" : ", J-USM";
        if(!who.empty()) where.push_back(fmt(t.lambdas[l], 2) + " (" + who + ")");
      }
      if(!where.empty())
      {
        std::ostringstream line;
        line << "K " << K << ", gain " << gains[gi] << ": lambda / Rf = ";
        for(std::size_t i = 0; i < where.size(); ++i) line << (i ? ", " : "") << where[i];
        lost.push_back(line.str());
      }
    }
  if(lost.empty()) lost.push_back("nowhere in the tables");
  return lost;
}

// ---------------------------------------------------------------------------------------------
// Tables, as CSV: make_reports.py writes filters.md and filters.png from them
// ---------------------------------------------------------------------------------------------

typedef std::map<std::size_t, std::vector<std::vector<Gain_pair> > > Gains_by_order;

static std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

/// The name of the i-th table of a kind: `base`, then base_2, base_3...
static std::string nth(const std::string& base, std::size_t i)
{
  return i == 0 ? base : base + "_" + std::to_string(i + 1);
}

/// A grid (filters.*_grid.csv, the plot's data): per lambda / Rf, per K and gain, detail gain and noise gain.
static wavejets_bench::Csv_table gain_grid(const Transfer& t, const Gains_by_order& R)
{
  std::vector<std::string> header{"lambda/Rf"};
  for(std::size_t K : t.orders)
    for(double g : gains)
      for(const char* m : {" detail", " noise"}) header.push_back("K" + std::to_string(K) + " gain " + number(g) + m);
  wavejets_bench::Csv_table table(header);
  for(std::size_t l = 0; l < t.lambdas.size(); ++l)
  {
    std::vector<std::string> row{number(t.lambdas[l])};
    for(std::size_t K : t.orders)
      for(std::size_t gi = 0; gi < 4; ++gi)
      {
        row.push_back(number(R.at(K)[l][gi].detail));
        row.push_back(number(R.at(K)[l][gi].noise));
      }
    table.add_row(row);
  }
  return table;
}

/// filters.baselines_grid.csv: per lambda / Rf and K, gain 2: the noise gain of WJ, H-USM and J-USM at WJ's detail
/// gain, then J-USM at g = 2: detail gain, noise gain.
static wavejets_bench::Csv_table baseline_grid(const Transfer& t)
{
  std::vector<std::string> header{"lambda/Rf"};
  for(std::size_t K : t.orders)
    for(const char* c : {"WJ noise", "H-USM noise at WJ detail", "J-USM noise at WJ detail", "J-USM g2 detail",
                         "J-USM g2 noise"})
      header.push_back("K" + std::to_string(K) + " " + c);
  wavejets_bench::Csv_table table(header);
  for(std::size_t l = 0; l < t.lambdas.size(); ++l)
  {
    std::vector<std::string> row{number(t.lambdas[l])};
    for(std::size_t K : t.orders)
      for(double v : {t.pos.at(K)[l][2].noise, t.husm.at(K)[l][2].noise, t.jusm.at(K)[l][2].noise,
                      t.jusm_same.at(K)[l][2].detail, t.jusm_same.at(K)[l][2].noise})
        row.push_back(number(v));
    table.add_row(row);
  }
  return table;
}

static wavejets_bench::Csv_table check_table(const std::vector<Check>& checks)
{
  wavejets_bench::Csv_table table({"points per neighborhood", "evaluation radius / Rf", "Wavejet detail gain",
                                   "Wavejet noise gain", "noise alone", "target", "J-USM g = 2 detail",
                                   "J-USM g = 2 noise"});
  for(const Check& c : checks)
    table.add_row({"~" + fmt(c.neighbors, 2), fmt(c.s, 2), fmt(c.wj.detail), fmt(c.wj.noise), fmt(c.noise_alone),
                   std::string("detail > 1.5, noise <= 1.25: ") + (c.pass ? "pass" : "FAIL"), fmt(c.jet.detail),
                   fmt(c.jet.noise)});
  return table;
}

/// Per K, one table: per lambda / Rf (and, `with_kept`, the share of the tilt the gain-1 normal keeps), per gain:
/// detail gain and noise gain.
static void add_gain_tables(std::vector<std::pair<std::string, wavejets_bench::Csv_table> >& tables,
                            const std::string& name, const Transfer& t, const Gains_by_order& R, bool with_kept)
{
  for(std::size_t i = 0; i < t.orders.size(); ++i)
  {
    const std::size_t K = t.orders[i];
    std::vector<std::string> header{"lambda / Rf"};
    if(with_kept) header.push_back("kept");
    for(double g : gains)
      for(const char* m : {" detail", " noise"}) header.push_back("gain " + number(g) + m);
    wavejets_bench::Csv_table table(header);
    for(std::size_t l = 0; l < t.lambdas.size(); ++l)
    {
      std::vector<std::string> row{number(t.lambdas[l])};
      if(with_kept) row.push_back(fmt(t.kept.at(K)[l]));
      for(std::size_t gi = 0; gi < 4; ++gi)
      {
        row.push_back(fmt(R.at(K)[l][gi].detail));
        row.push_back(fmt(R.at(K)[l][gi].noise));
      }
      table.add_row(row);
    }
    tables.emplace_back(nth(name, i), table);
  }
}

/// Noise gains against unsharp masking at equal detail gain (positions): one table per K and gain 2, 3.
static void add_baseline_tables(std::vector<std::pair<std::string, wavejets_bench::Csv_table> >& tables,
                                const Transfer& t)
{
  std::size_t i = 0;
  for(std::size_t K : t.orders)
    for(std::size_t gi : {std::size_t(2), std::size_t(3)})
    {
      wavejets_bench::Csv_table table({"lambda / Rf", "WJ detail", "WJ noise", "H-USM noise", "H-USM c / Rf^2",
                                       "J-USM noise", "J-USM g", "J-USM at g = " + number(gains[gi]) + ": detail",
                                       "noise"});
      for(std::size_t l = 0; l < t.lambdas.size(); ++l)
      {
        const Matched& hb = t.husm.at(K)[l][gi];
        const Matched& jb = t.jusm.at(K)[l][gi];
        table.add_row({number(t.lambdas[l]), fmt(t.pos.at(K)[l][gi].detail), fmt(t.pos.at(K)[l][gi].noise),
                       fmt(hb.noise), fmt(hb.factor / (Rf * Rf)), fmt(jb.noise), fmt(1. + jb.factor),
                       fmt(t.jusm_same.at(K)[l][gi].detail), fmt(t.jusm_same.at(K)[l][gi].noise)});
      }
      tables.emplace_back(nth("filters.usm", i++), table);
    }
}

static wavejets_bench::Csv_table figure12_table(const std::vector<Pipeline_case>& pipeline)
{
  wavejets_bench::Csv_table table({"noise sigma", "method", "detail gain", "noise gain", "drift / sigma"});
  for(const Pipeline_case& c : pipeline)
    for(const Pipeline_row& r : c.rows)
      table.add_row({fmt(c.noise, 2) + " A", r.name, fmt(r.g.detail), fmt(r.g.noise), fmt(r.drift)});
  return table;
}

// ---------------------------------------------------------------------------------------------
// Main
// ---------------------------------------------------------------------------------------------

int main(int argc, char** argv)
{
  Options o;
  if(!parse_command_line(argc, argv, o)) return 2;
  CGAL::Real_timer total;
  total.start();
  const Transfer t = measure_transfer(o.quick, total);
  const std::vector<Check> checks = headline_checks();
  const bool all_pass = checks[0].pass;
  print_checks(checks, t);
  const std::vector<Pipeline_case> pipeline = figure12_cases();
  const std::vector<std::string> lost = where_the_lead_is_lost(t);
  std::cout << "Baselines with less noise than the Wavejet filter at equal detail gain:\n";
  for(const std::string& line : lost) std::cout << "- " << line << "\n";
  total.stop();
  if(!o.write()) return all_pass ? 0 : 1;

  std::vector<std::pair<std::string, wavejets_bench::Csv_table> > tables;
  tables.emplace_back("filters.check", check_table(checks));
  add_gain_tables(tables, "filters.positions", t, t.pos, false);
  add_gain_tables(tables, "filters.normals", t, t.nrm, true);
  add_baseline_tables(tables, t);
  wavejets_bench::Csv_table lost_table({"configuration"});
  for(const std::string& line : lost) lost_table.add_row({line});
  tables.emplace_back("filters.lead_lost", lost_table);
  tables.emplace_back("filters.figure12", figure12_table(pipeline));
  tables.emplace_back("filters.positions_grid", gain_grid(t, t.pos));
  tables.emplace_back("filters.normals_grid", gain_grid(t, t.nrm));
  tables.emplace_back("filters.baselines_grid", baseline_grid(t));
  wavejets_bench::Csv_table context = wavejets_bench::context_table();
  context.add_row({"machine", wavejets_bench::machine_description()});
  context.add_row({"run time (s)", fmt(total.time(), 3)});
  context.add_row({"linearity (Rf)", fmt(t.linearity)});
  tables.emplace_back("filters.context", context);
  for(const auto& table : tables) table.second.write(o.out_dir, table.first);
  return all_pass ? 0 : 1;
}
