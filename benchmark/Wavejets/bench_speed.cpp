// Speed benchmark of the Wavejets point-set functions against CGAL's jet fitting.
//
// Samples N points uniformly on examples/Wavejets/data/bunny00.off (fixed seed) and times, in one
// process, with CGAL::Real_timer:
//   * the k-NN search alone (the package's internal Neighbor_query: tree build + N queries), the
//     floor of any neighborhood method, and CGAL's Orthogonal_k_neighbor_search for the same lists;
//   * CGAL::jet_estimate_normals (degree 2/k 18, 4/k 32, 6/k 96) against
//     CGAL::wavejet_estimate_normals at the same order and k;
//   * CGAL::wavejet_estimate_curvatures and CGAL::wavejet_enhance_positions (K = 6);
//   * the fitting core alone (Fitter::fit on pre-gathered neighborhoods, one thread) and, where Ponca
//     is found (ponca_types.h), Ponca's APSS fit on the same neighborhoods;
//   * the package's hand-written Householder QR against Eigen's HouseholderQR on the same Wavejet
//     systems (why the hand-written solver exists);
// with Sequential_tag and Parallel_tag. A scaling mode re-runs this executable once per
// configuration (N, K, threads) so that each peak memory figure belongs to one run.
// It writes its tables as CSV (csv/results.*.csv); make_reports.py writes results.md and results.png from them.
// See README.md in this directory.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/point_generators_3.h>
#include <CGAL/Random.h>
#include <CGAL/Real_timer.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/Wavejets/internal/basis.h>
#include <CGAL/Wavejets/internal/least_squares.h>

#include <Eigen/Dense>

#include "bench_common.h"
#include "cgal_k_neighbor_search.h"
#include "ponca_types.h"

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/info.h>
#endif

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef std::pair<Point, Vector> Point_with_normal;
typedef std::vector<Point_with_normal> Points;
typedef CGAL::First_of_pair_property_map<Point_with_normal> Point_map;
typedef CGAL::Second_of_pair_property_map<Point_with_normal> Normal_map;
typedef CGAL::Surface_mesh<Point> Mesh;

namespace WI = CGAL::Wavejets::internal;
namespace WP = CGAL::Wavejets::parameters;

// ---------------------------------------------------------------------------------------------
// Utilities

static double peak_rss_mb()
{
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.; // Linux: kilobytes
}

static std::string shell_line(const std::string& cmd)
{
  std::string r;
  if(FILE* p = popen(cmd.c_str(), "r"))
  {
    char buf[512];
    while(fgets(buf, sizeof buf, p)) r += buf;
    pclose(p);
  }
  while(!r.empty() && (r.back() == '\n' || r.back() == ' ')) r.pop_back();
  return r;
}

static int max_threads()
{
#ifdef CGAL_LINKED_WITH_TBB
  return tbb::info::default_concurrency();
#else
  return 1;
#endif
}

// Limits TBB to `t` threads while alive (t <= 0: no limit).
struct Thread_limit
{
#ifdef CGAL_LINKED_WITH_TBB
  std::unique_ptr<tbb::global_control> gc;
  explicit Thread_limit(int t)
  {
    if(t > 0) gc.reset(new tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(t)));
  }
#else
  explicit Thread_limit(int) {}
#endif
};

static Points sample_bunny(const std::string& file, std::size_t n, int seed)
{
  Mesh mesh;
  std::ifstream in(file);
  if(!in || !(in >> mesh) || mesh.number_of_faces() == 0)
  {
    std::cerr << "cannot read the mesh " << file << "\n";
    std::exit(1);
  }
  // The generator draws the triangle with `random` but the point inside it with
  // CGAL::get_default_random() (CGAL 5.5.1): seed both, or the sample changes from run to run.
  CGAL::Random random(seed);
  CGAL::get_default_random() = CGAL::Random(seed + 1);
  CGAL::Random_points_in_triangle_mesh_3<Mesh> generator(mesh, random);
  Points points;
  points.reserve(n);
  for(std::size_t i = 0; i < n; ++i, ++generator)
    points.emplace_back(*generator, Vector(0, 0, 0));
  return points;
}

// Every step-th point (a subset with the same spatial extent, at lower density).
static Points strided_subset(const Points& points, std::size_t m)
{
  if(m == 0 || m >= points.size()) return points;
  Points r;
  r.reserve(m);
  const double step = double(points.size()) / double(m);
  for(std::size_t i = 0; i < m; ++i) r.push_back(points[std::size_t(double(i) * step)]);
  return r;
}

static auto np_maps() { return CGAL::parameters::point_map(Point_map()).normal_map(Normal_map()); }

// ---------------------------------------------------------------------------------------------
// Timed steps

struct Row
{
  std::string step, mode;
  int threads;
  std::size_t n;
  double seconds;
  double rss_mb;
  std::string against; // the row of the reference (CGAL) this one is compared with
  double us() const { return 1e6 * seconds / double(n); }
};

template <class Tag>
static double time_knn(const Points& points, unsigned int k)
{
  CGAL::Real_timer t;
  t.start();
  std::vector<WI::Neighbor_query::Point> pts;
  pts.reserve(points.size());
  for(const auto& p : points) pts.emplace_back(p.first.x(), p.first.y(), p.first.z());
  std::vector<unsigned char> finite(points.size(), 1);
  const WI::Neighbor_query query(pts, finite, Tag());
  const std::vector<std::size_t> order = query.processing_order(); // the drivers' visiting order
  std::vector<std::size_t> chunks;
  for(std::size_t b = 0; b < points.size(); b += 256) chunks.push_back(b);
  std::vector<std::size_t> checksum(chunks.size(), 0);
  CGAL::for_each<Tag>(chunks, [&](std::size_t begin) -> bool {
    std::vector<std::size_t> nb;
    WI::Neighbor_query::Scratch scratch;
    const std::size_t end = (std::min)(begin + 256, points.size());
    for(std::size_t position = begin; position < end; ++position)
    {
      query.neighbors(order[position], k, 0., nb, scratch);
      checksum[begin / 256] += nb.size();
    }
    return true;
  });
  t.stop();
  std::size_t total = 0;
  for(std::size_t c : checksum) total += c;
  if(total != points.size() * std::size_t(k)) std::cerr << "kNN checksum mismatch\n";
  return t.time();
}

/// The k-NN lists of every point by CGAL's Orthogonal_k_neighbor_search (cgal_k_neighbor_search.h), sequentially
/// in its kd-tree's leaf order, build included; `mismatches`: the points whose list differs from Neighbor_query's.
static double time_cgal_knn(const Points& points, unsigned int k, std::size_t& mismatches)
{
  std::vector<WI::Neighbor_query::Point> pts;
  for(const auto& p : points) pts.emplace_back(p.first.x(), p.first.y(), p.first.z());
  const std::vector<unsigned char> finite(points.size(), 1);
  const WI::Neighbor_query query(pts, finite);
  std::vector<std::size_t> reference(points.size() * k), nb;
  WI::Neighbor_query::Scratch scratch;
  for(std::size_t i = 0; i < points.size(); ++i)
  {
    query.neighbors(i, k, 0., nb, scratch);
    std::copy(nb.begin(), nb.end(), reference.begin() + i * k);
  }
  mismatches = 0;
  CGAL::Real_timer t;
  t.start();
  const wavejets_bench::Cgal_k_neighbor_search cgal_search(pts);
  for(std::size_t i : cgal_search.leaf_order())
  {
    cgal_search.neighbors(i, k, nb, scratch.candidates);
    mismatches += nb.size() != k || !std::equal(nb.begin(), nb.end(), reference.begin() + i * k);
  }
  t.stop();
  return t.time();
}

template <class Tag>
static double time_cgal_jet(Points& points, unsigned int degree, unsigned int k)
{
  CGAL::Real_timer t;
  t.start();
  CGAL::jet_estimate_normals<Tag>(points, k, np_maps().degree_fitting(degree));
  t.stop();
  return t.time();
}

template <class Tag>
static double time_wavejet_normals(Points& points, std::size_t order, unsigned int k)
{
  CGAL::Real_timer t;
  t.start();
  CGAL::wavejet_estimate_normals<Tag>(points, k, WP::order(order, np_maps()));
  t.stop();
  return t.time();
}

// Writable map keyed by the elements of a vector (their address gives the index).
struct Element_index_map
{
  typedef Point_with_normal key_type;
  typedef double value_type;
  typedef double reference;
  typedef boost::writable_property_map_tag category;
  const Point_with_normal* base;
  double* values;
  friend void put(const Element_index_map& m, const Point_with_normal& key, double v) { m.values[&key - m.base] = v; }
};

template <class Tag>
static double time_wavejet_curvatures(const Points& points, std::size_t order, unsigned int k)
{
  std::vector<double> H(points.size(), 0.);
  Points copy = points;
  CGAL::Real_timer t;
  t.start();
  CGAL::wavejet_estimate_curvatures<Tag>(
    copy, k, WP::order(order, np_maps()).mean_curvature_map(Element_index_map{copy.data(), H.data()}));
  t.stop();
  return t.time();
}

template <class Tag>
static double time_wavejet_enhance(Points& points, std::size_t order, unsigned int k)
{
  CGAL::Real_timer t;
  t.start();
  CGAL::wavejet_enhance_positions<Tag>(points, k, 2., WP::order(order, np_maps()));
  t.stop();
  return t.time();
}

/// The k-NN neighborhoods of m points spread over the sample (every (N / m)-th), as the fitting-core
/// rows time them: the centers and, per center, its k neighbors.
struct Sampled_neighborhoods
{
  std::vector<WI::Neighbor_query::Point> points;
  std::vector<std::size_t> centers, members; // members: k per center
};

static Sampled_neighborhoods sample_neighborhoods(const Points& points, std::size_t m, unsigned int k)
{
  Sampled_neighborhoods s;
  m = (std::min)(m, points.size());
  for(const auto& p : points) s.points.emplace_back(p.first.x(), p.first.y(), p.first.z());
  std::vector<unsigned char> finite(points.size(), 1);
  const WI::Neighbor_query query(s.points, finite);
  std::vector<std::size_t> nb;
  WI::Neighbor_query::Scratch scratch;
  const std::size_t step = points.size() / m;
  for(std::size_t q = 0; q < m; ++q)
  {
    s.centers.push_back(q * step);
    query.neighbors(q * step, k, 0., nb, scratch);
    s.members.insert(s.members.end(), nb.begin(), nb.end());
  }
  return s;
}

/// The smallest of three runs of `run` (a callable returning seconds): for the short timings (a few
/// hundred milliseconds or less), which the noise of a shared machine would otherwise dominate.
template <class Run>
static double fastest_of_three(Run run)
{
  double best = run();
  for(int r = 1; r < 3; ++r) best = (std::min)(best, run());
  return best;
}

/// The fit settings of the point-set function `f` (of those timed here: wavejet_estimate_normals or
/// wavejet_enhance_positions) with its defaults and order `order`, as the function reads them (the
/// settings readers in its header).
static CGAL::Wavejets::Fitting_options function_fitting(const Points& points, std::size_t order, unsigned int k,
                                                       CGAL::Wavejets::Point_set_function f)
{
  Points copy(points.begin(), points.begin() + (std::min<std::size_t>)(points.size(), 1));
  const auto np = WP::order(order, np_maps());
  if(f == CGAL::Wavejets::Point_set_function::ENHANCE_POSITIONS)
    return WI::enhance_positions_settings(copy, k, np).driver.fitting;
  if(f != CGAL::Wavejets::Point_set_function::ESTIMATE_NORMALS)
    throw std::logic_error("function_fitting: only the functions timed here");
  return WI::estimate_normals_settings(copy, k, np).fitting;
}

/// The fitting core alone: Fitter::fit on m neighborhoods of the k-NN (the center and its k
/// neighbors), gathered first (not timed), with the settings `fitting`, one thread; returns the time
/// scaled to all the points.
static double time_fitter(const Points& points, std::size_t m, std::size_t order, unsigned int k,
                          const CGAL::Wavejets::Fitting_options& fitting);

/// The same with the defaults of Fitting_options (as the functions read them) and `corrections`
/// tangent-plane re-fits.
static double time_fitter(const Points& points, std::size_t m, std::size_t order, unsigned int k,
                          std::size_t corrections = 2)
{
  CGAL::Wavejets::Fitting_options fitting =
    WI::read_fitting_options(CGAL::parameters::default_values(), CGAL::Wavejets::Fitting_options(), "bench");
  fitting.correction_iterations = corrections;
  return time_fitter(points, m, order, k, fitting);
}

static double time_fitter(const Points& points, std::size_t m, std::size_t order, unsigned int k,
                          const CGAL::Wavejets::Fitting_options& fitting)
{
  const Sampled_neighborhoods hoods = sample_neighborhoods(points, m, k);
  m = hoods.centers.size();
  const std::vector<WI::Neighbor_query::Point>& pts = hoods.points;
  std::vector<Eigen::Vector3d> offsets;
  offsets.reserve(m * (k + 1));
  for(std::size_t q = 0; q < m; ++q)
  {
    const std::size_t i = hoods.centers[q];
    const Eigen::Vector3d p(pts[i].x(), pts[i].y(), pts[i].z());
    offsets.push_back(Eigen::Vector3d::Zero());
    for(std::size_t j = q * k; j < (q + 1) * k; ++j)
    {
      const WI::Neighbor_query::Point& n = pts[hoods.members[j]];
      offsets.push_back(Eigen::Vector3d(n.x(), n.y(), n.z()) - p);
    }
  }
  WI::Fitter fitter;
  WI::Fit_result fit;
  double sum = 0.;
  CGAL::Real_timer t;
  t.start();
  for(std::size_t q = 0; q < m; ++q)
  {
    fitter.fit(offsets.data() + q * (k + 1), k + 1, order, fitting, nullptr, fit);
    sum += fit.frame.n.z();
  }
  t.stop();
  if(!std::isfinite(sum)) std::cerr << "fitter produced NaN\n";
  return t.time() * double(points.size()) / double(m); // reported over N points below
}

#ifdef WAVEJETS_HAVE_PONCA
/// Ponca's APSS fit (OrientedSphereFit + GLSParam, constant weights, as bench_ponca_accuracy's APSS
/// column) on the neighborhoods time_fitter() fits (the center and its k neighbors), one thread:
/// per neighborhood the radius (the farthest neighbor, as Rf), the fit, kappa and the normal. The
/// positions and normals are gathered before the timer starts. The normals are the Wavejet normals
/// of the sample (k 18), each neighbor's flipped to agree with its center's (APSS needs consistently
/// oriented normals; not timed).
static double time_apss(const Points& points, std::size_t m, unsigned int k)
{
  const Sampled_neighborhoods hoods = sample_neighborhoods(points, m, k);
  m = hoods.centers.size();
  Points oriented = points;
  CGAL::wavejet_estimate_normals<CGAL::Sequential_tag>(oriented, 18, np_maps());
  auto position = [&](std::size_t i) {
    return Ponca_point::VectorType(hoods.points[i].x(), hoods.points[i].y(), hoods.points[i].z());
  };
  auto normal = [&](std::size_t i) {
    const Vector& n = oriented[i].second;
    return Ponca_point::VectorType(n.x(), n.y(), n.z());
  };
  std::vector<Ponca_point> gathered;
  gathered.reserve(m * (k + 1));
  for(std::size_t q = 0; q < m; ++q)
  {
    const std::size_t c = hoods.centers[q];
    gathered.emplace_back(position(c), normal(c));
    for(std::size_t j = q * k; j < (q + 1) * k; ++j)
    {
      const std::size_t i = hoods.members[j];
      const double agree = normal(i).dot(normal(c));
      gathered.emplace_back(position(i), agree < 0. ? Ponca_point::VectorType(-normal(i)) : normal(i));
    }
  }
  double sum = 0.;
  std::size_t stable = 0;
  CGAL::Real_timer t;
  t.start();
  for(std::size_t q = 0; q < m; ++q)
  {
    const Ponca_point* hood = gathered.data() + q * (k + 1);
    const Ponca_point::VectorType& c = hood[0].pos();
    double Rf = 0.;
    for(std::size_t j = 1; j <= k; ++j) Rf = (std::max)(Rf, (hood[j].pos() - c).norm());
    APSS_constant fit;
    fit.setNeighborFilter(Constant_weight(c, Rf * (1. + 1e-9) + 1e-300)); // every neighbor inside the kernel
    if(fit.compute(hood, hood + k + 1) == Ponca::STABLE)
    {
      ++stable;
      sum += fit.kappa() + fit.primitiveGradient(c).normalized().z();
    }
  }
  t.stop();
  if(!std::isfinite(sum) || stable < m / 2) std::cerr << "APSS: " << stable << " of " << m << " fits stable\n";
  return t.time() * double(points.size()) / double(m); // reported over N points below
}
#endif

// ---------------------------------------------------------------------------------------------
// Options

struct Options
{
  std::size_t n = 100000;
  std::size_t cgal_subset = 20000; // CGAL degree 6 / k 96 runs on this many points (0: all)
  std::string mode = "speed";      // speed | scaling | all | single
  std::string mesh = wavejets_bench::source_dir() + "/data/bunny00.off";
  std::string csv_dir = wavejets_bench::source_dir() + "/csv"; // where results.*.csv go (make_reports.py reads them there)
  std::size_t scaling_max_n = 2000000;
  bool no_write = false;
  int seed = 42;
  // --single: one configuration, prints "SINGLE seconds peak_rss_mb"
  std::string fn = "enhance";
  std::size_t order = 6;
  unsigned int k = 96;
  int threads = 0;
};

static void usage()
{
  std::cout <<
    "bench_speed [N] [--n N] [--mode speed|scaling|all|solver] [--cgal-subset M] [--scaling-max-n N]\n"
    "            [--mesh file.off] [--csv-dir DIR] [--no-write] [--seed S]\n"
    "  speed   : the comparison table at N points (default 100000); CGAL degree 6/k 96 runs on a\n"
    "            strided subset of M points (default 20000, 0 = all), compared in us/point\n"
    "  scaling : N from 100k to --scaling-max-n (default 2M), K from 2 to 10, 1 vs all threads,\n"
    "            one sub-process per configuration (its own peak memory)\n"
    "  all     : both\n";
}

static Options parse(int argc, char** argv)
{
  Options o;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if(i + 1 >= argc) { usage(); std::exit(1); }
      return argv[++i];
    };
    if(a == "--help" || a == "-h") { usage(); std::exit(0); }
    else if(a == "--n") o.n = std::stoul(next());
    else if(a == "--mode") o.mode = next();
    else if(a == "--cgal-subset") o.cgal_subset = std::stoul(next());
    else if(a == "--scaling-max-n") o.scaling_max_n = std::stoul(next());
    else if(a == "--mesh") o.mesh = next();
    else if(a == "--csv-dir") o.csv_dir = next();
    else if(a == "--no-write") o.no_write = true;
    else if(a == "--seed") o.seed = std::stoi(next());
    else if(a == "--single") o.mode = "single";
    else if(a == "--fn") o.fn = next();
    else if(a == "--order") o.order = std::stoul(next());
    else if(a == "--k") o.k = unsigned(std::stoul(next()));
    else if(a == "--threads") o.threads = std::stoi(next());
    else if(!a.empty() && a[0] != '-') o.n = std::stoul(a);
    else { usage(); std::exit(1); }
  }
  return o;
}

// ---------------------------------------------------------------------------------------------
// Speed table

static std::string fmt(double v, int prec)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

/// The speed targets of the benchmark's issue, filled in by the runs (negative: not measured).
struct Targets
{
  double ratio_k6 = -1., ratio_k2 = -1.;       // CGAL us/point over Wavejets us/point, Sequential_tag
  double fit_k2 = -1., fit_k2_single = -1.;    // us per fit, K 2, k 100
  double fit_k6 = -1.;                         // us per fit, K 6, k 96
  double fit_k2_over_apss_50 = -1., fit_k2_over_apss_100 = -1.; // Fitter::fit K 2 over Ponca's APSS, same neighborhoods
  double knn_k18_over_cgal = -1., knn_k96_over_cgal = -1.; // Neighbor_query time / CGAL's Orthogonal_k_neighbor_search
  double enhance_600k = -1.;                   // s, wavejet_enhance_positions K 6 k 96, N = 600000, all threads
  double enhance_5m = -1., enhance_5m_rss_mb = -1.; // the same at N = 5000000: s, peak MB
  double thread_speedup_min = -1.;             // smallest 2-thread speed-up of the fitting functions
  int threads = 0;
};

static wavejets_bench::Csv_table targets_table(const Targets& t)
{
  wavejets_bench::Csv_table s({"target", "wanted", "measured", ""});
  auto row = [&](const std::string& what, const std::string& target, double value, int prec, const std::string& unit,
                 bool met) {
    s.add_row({what, target, value < 0 ? std::string("not run") : fmt(value, prec) + unit,
               value < 0 ? "-" : (met ? "met" : "not met")});
  };
  row("wavejet_estimate_normals K 6, k 96 vs jet_estimate_normals degree 6 (seq)", ">= 30x", t.ratio_k6, 1, "x",
      t.ratio_k6 >= 30.);
  row("wavejet_estimate_normals K 2, k 18 vs jet_estimate_normals degree 2 (seq)", ">= 5x", t.ratio_k2, 1, "x",
      t.ratio_k2 >= 5.);
  row("Fitter::fit, K 2, k 100, default (2 re-fits), per point per thread", "<= 1 us", t.fit_k2, 2, " us", t.fit_k2 <= 1.);
  row("Fitter::fit, K 6, k 96, default, per point per thread", "<= 6 us", t.fit_k6, 2, " us", t.fit_k6 <= 6.);
  row("Fitter::fit K 2 (default) over Ponca's APSS fit, same neighborhoods, k 50", "<= 3x", t.fit_k2_over_apss_50, 2, "x",
      t.fit_k2_over_apss_50 <= 3.);
  row("the same, k 100", "<= 3x", t.fit_k2_over_apss_100, 2, "x", t.fit_k2_over_apss_100 <= 3.);
  row("k-NN k 18 (Neighbor_query, seq, tree build included) over CGAL's Orthogonal_k_neighbor_search", "<= 1x",
      t.knn_k18_over_cgal, 2, "x", t.knn_k18_over_cgal <= 1.);
  row("k-NN k 96, likewise", "<= 1x", t.knn_k96_over_cgal, 2, "x", t.knn_k96_over_cgal <= 1.);
  row("wavejet_enhance_positions K 6, k 96, N = 600000, end to end (" + std::to_string(t.threads) + " threads)",
      "<= 6 s", t.enhance_600k, 1, " s", t.enhance_600k <= 6.);
  row("the same, N = 5000000 (--scaling-max-n 5000000)", "<= 50 s", t.enhance_5m, 1, " s", t.enhance_5m <= 50.);
  row("the same, N = 5000000, peak memory", "<= 1024 MB", t.enhance_5m_rss_mb, 0, " MB", t.enhance_5m_rss_mb <= 1024.);
  row("2 threads vs 1, smallest speed-up of wavejet_estimate_normals / wavejet_enhance_positions (N = 600000)",
      ">= 1.8x", t.thread_speedup_min, 2, "x", t.thread_speedup_min >= 1.8);
  return s;
}

/// The Wavejet least-squares systems of m neighborhoods (k neighbors, order K), as the fitter builds
/// them: offsets divided by the farthest one, in the PCA frame, basis columns r^k cos/sin(n theta).
struct Qr_systems
{
  std::size_t rows = 0, cols = 0, P = 0, m = 0;
  std::vector<double> A; // m systems, each P x (cols + 1), column-major, b last
};

static Qr_systems wavejet_systems(const Points& points, std::size_t m, std::size_t order, unsigned int k)
{
  std::vector<WI::Neighbor_query::Point> pts;
  for(const Point_with_normal& p : points) pts.emplace_back(p.first.x(), p.first.y(), p.first.z());
  const std::vector<unsigned char> finite(pts.size(), 1);
  const WI::Neighbor_query query(pts, finite, CGAL::Sequential_tag());
  Qr_systems S;
  S.rows = k + 1;
  S.cols = WI::number_of_coefficients(order);
  S.P = WI::padded_rows(S.rows);
  S.m = m;
  S.A.assign(m * S.P * (S.cols + 1), 0.);
  std::vector<std::size_t> nb;
  WI::Neighbor_query::Scratch scratch;
  std::vector<double> x(S.P, 0.), y(S.P, 0.); // evaluate_basis_columns() reads the zero padding rows too
  for(std::size_t q = 0; q < m; ++q)
  {
    const std::size_t i = q * (points.size() / m);
    query.neighbors(i, k, 0., nb, scratch);
    std::vector<Eigen::Vector3d> d(1, Eigen::Vector3d::Zero());
    for(std::size_t j : nb) d.push_back(Eigen::Vector3d(pts[j].x() - pts[i].x(), pts[j].y() - pts[i].y(), pts[j].z() - pts[i].z()));
    double r = 0.;
    for(const Eigen::Vector3d& e : d) r = (std::max)(r, e.norm());
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for(Eigen::Vector3d& e : d) { e /= r; C += e * e.transpose(); }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(C); // ascending: column 0 is the normal
    double* A = S.A.data() + q * S.P * (S.cols + 1);
    for(std::size_t l = 0; l < S.rows; ++l)
    {
      x[l] = d[l].dot(pca.eigenvectors().col(2));
      y[l] = d[l].dot(pca.eigenvectors().col(1));
      A[S.cols * S.P + l] = d[l].dot(pca.eigenvectors().col(0));
    }
    WI::evaluate_basis_columns(x.data(), y.data(), S.rows, S.P, order, A);
  }
  return S;
}

/// One line of the QR table: the hand-written kernel (run-time dispatch, and the baseline code) and
/// Eigen's HouseholderQR (one object reused, no allocation per solve) on the same systems.
static std::vector<std::string> qr_comparison_row(const Points& points, std::size_t order, unsigned int k)
{
  const std::size_t m = (std::min<std::size_t>)(points.size(), 20000);
  const Qr_systems S = wavejet_systems(points, m, order, k);
  const std::size_t size = S.P * (S.cols + 1);
  std::vector<double, WI::Aligned_allocator<double> > work(size), v(WI::wavejet_least_squares_scratch_size(S.rows, S.cols));
  std::vector<double> c(S.cols), mine(m * S.cols), eigen(m * S.cols), qr(m * S.cols);
  auto time_kernel = [&](bool (*kernel)(double*, std::size_t, std::size_t, double*, double*)) {
    CGAL::Real_timer t;
    t.start();
    for(std::size_t q = 0; q < m; ++q)
    {
      std::copy(S.A.begin() + q * size, S.A.begin() + (q + 1) * size, work.begin());
      kernel(work.data(), S.rows, S.cols, v.data(), mine.data() + q * S.cols);
    }
    t.stop();
    return t.time() * 1e6 / double(m);
  };
  const double us_baseline = time_kernel(&WI::householder_kernel);
  // The solver the fits run, and how many systems its guards left to the QR: at order 2 the moments
  // (order2_least_squares(), from the columns x, y and b: the fitter builds no other), else
  // wavejet_least_squares() (the semi-normal equations from semi_normal_minimum_columns unknowns,
  // their Gram matrix from polar moments); least_squares() is the same with the Gram matrix dot by dot.
  std::size_t fallbacks = 0;
  const bool moments = order == 2;
  std::vector<double, WI::Aligned_allocator<double> > points_xyh(3 * S.P);
  auto order2_from_columns = [&](const double* A, std::size_t rows, double* solution) {
    const std::size_t columns[3] = {1, 2, S.cols}; // x, y and b
    for(std::size_t i = 0; i < 3; ++i)
      std::copy(A + columns[i] * S.P, A + (columns[i] + 1) * S.P, points_xyh.begin() + i * S.P);
    return WI::order2_least_squares(points_xyh.data(), rows, solution);
  };
  double us_semi_normal = 0., us_gram_by_dots = 0.;
  if(moments)
  {
    CGAL::Real_timer t;
    t.start();
    for(std::size_t q = 0; q < m; ++q)
      if(!order2_from_columns(S.A.data() + q * size, S.rows, mine.data() + q * S.cols))
      { // as the fitter does: build the system and solve it with least_squares()
        ++fallbacks;
        std::copy(S.A.begin() + q * size, S.A.begin() + (q + 1) * size, work.begin());
        WI::least_squares(work.data(), S.rows, S.cols, v.data(), mine.data() + q * S.cols);
      }
    t.stop();
    us_semi_normal = t.time() * 1e6 / double(m);
  }
  else
  {
    us_gram_by_dots = time_kernel(&WI::least_squares);
    us_semi_normal = time_kernel(&WI::wavejet_least_squares);
    const bool polar = WI::uses_polar_moments(S.rows, S.cols);
    for(std::size_t q = 0; q < m; ++q)
    {
      std::copy(S.A.begin() + q * size, S.A.begin() + (q + 1) * size, work.begin());
      fallbacks += !(polar ? WI::wavejet_semi_normal_kernel<> : WI::semi_normal_kernel<>)(work.data(), S.rows, S.cols,
                                                                                      v.data(), c.data());
    }
  }
  // Largest difference between the solutions `a` and `reference` of one system, relative to the
  // reference's largest coefficient, over the m systems.
  auto worst_relative_difference = [&](const std::vector<double>& a, const std::vector<double>& reference) {
    double worst = 0.;
    for(std::size_t q = 0; q < m; ++q)
    {
      double dn = 0., n = 0.;
      for(std::size_t j = 0; j < S.cols; ++j)
      {
        dn = (std::max)(dn, std::abs(a[q * S.cols + j] - reference[q * S.cols + j]));
        n = (std::max)(n, std::abs(reference[q * S.cols + j]));
      }
      worst = (std::max)(worst, n > 0 ? dn / n : dn);
    }
    return worst;
  };
  std::vector<double> semi_normal = mine;
  const double us_dispatch = time_kernel(&WI::householder_least_squares);
  qr = mine;
  const double worst_semi_normal = worst_relative_difference(semi_normal, qr);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_eigen(S.rows, S.cols);
  CGAL::Real_timer t;
  t.start();
  for(std::size_t q = 0; q < m; ++q)
  {
    const double* A = S.A.data() + q * size;
    qr_eigen.compute(Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<> >(A, S.rows, S.cols, Eigen::OuterStride<>(S.P)));
    Eigen::Map<Eigen::VectorXd>(eigen.data() + q * S.cols, S.cols) =
      qr_eigen.solve(Eigen::Map<const Eigen::VectorXd>(A + S.cols * S.P, S.rows));
  }
  t.stop();
  const double us_eigen = t.time() * 1e6 / double(m);
  const double worst = worst_relative_difference(mine, eigen);
  auto scientific = [](double v) {
    std::ostringstream s;
    s << std::scientific << std::setprecision(1) << v;
    return s.str();
  };
  return {std::to_string(order), std::to_string(k), std::to_string(S.rows) + " x " + std::to_string(S.cols),
          std::to_string(m), fmt(us_dispatch, 2), fmt(us_baseline, 2), fmt(us_eigen, 2),
          fmt(us_eigen / us_dispatch, 1) + "x", fmt(us_eigen / us_baseline, 1) + "x", scientific(worst),
          fmt(us_semi_normal, 2), fmt(us_dispatch / us_semi_normal, 1) + "x",
          moments ? std::string("-") : fmt(us_gram_by_dots, 2), std::to_string(fallbacks),
          scientific(worst_semi_normal)};
}

/// The compilation of the least-squares kernels that WI::dispatch_solver() runs on this processor.
static std::string solver_variant()
{
  if(WI::processor_runs_avx512())
    return "AVX-512 (the order-2 fits eight neighbors per step)";
  if(WI::processor_runs_fma())
    return "AVX2 + FMA";
  return WI::processor_runs_avx() ? "AVX" : "baseline";
}

/// The hand-written QR against Eigen's, and the solver the fits run, at four (K, k) (results.md, section Least
/// squares).
static wavejets_bench::Csv_table qr_comparison_table(const Points& points)
{
  wavejets_bench::Csv_table table(
    {"K", "k", "system", "systems", "hand-written QR, dispatch (us)", "baseline kernel (us)",
     "Eigen HouseholderQR (us)",
     "gain (dispatch)", "gain (baseline)", "max relative difference",
     "the fits' solver, dispatch (us): K 2 from the moments, the QR at K 3 and 4, the semi-normal equations from K 5 "
     "(their Gram matrix from polar moments)",
     "its gain over the QR", "the same with the Gram matrix dot by dot (us)",
     "systems its guards refuse (solved by the QR)", "its max relative difference to the QR"});
  for(const std::pair<std::size_t, unsigned int>& c : {std::make_pair(std::size_t(2), 18u), std::make_pair(std::size_t(2), 100u),
                                                       std::make_pair(std::size_t(4), 32u), std::make_pair(std::size_t(6), 96u)})
    table.add_row(qr_comparison_row(points, c.first, c.second));
  return table;
}

/// One fit at the full order in a given frame, as the fitting core runs it, on the systems of
/// wavejet_systems() (m neighborhoods of the k-NN, PCA frame), one thread, in us per fit: the basis
/// columns built from the points' (x, y) (none at order 2, which is solved from the moments of the
/// points, order2_least_squares()), and the solve in place (wavejet_least_squares(); the copy that restores
/// each system before its solve is timed alone and subtracted).
struct Final_fit_times
{
  double basis_us = 0., solve_us = 0.;
};

static Final_fit_times time_final_fit(const Points& points, std::size_t order, unsigned int k)
{
  const std::size_t m = (std::min<std::size_t>)(points.size(), 20000);
  const Qr_systems S = wavejet_systems(points, m, order, k);
  const std::size_t size = S.P * (S.cols + 1);
  std::vector<double, WI::Aligned_allocator<double> > work(size), scratch(WI::wavejet_least_squares_scratch_size(S.rows, S.cols));
  std::vector<double, WI::Aligned_allocator<double> > x(S.P), y(S.P), xyh(3 * S.P);
  std::vector<double> c(S.cols);
  double sum = 0.;
  auto system = [&](std::size_t q) { return S.A.data() + q * size; };
  // us per system of `step` after `prepare` (both run for each system q), less `prepare` alone.
  auto us_per_system = [&](auto prepare, auto step) {
    CGAL::Real_timer alone, both;
    alone.start();
    for(std::size_t q = 0; q < m; ++q) prepare(q);
    alone.stop();
    both.start();
    for(std::size_t q = 0; q < m; ++q) { prepare(q); step(); }
    both.stop();
    return (both.time() - alone.time()) * 1e6 / double(m);
  };
  Final_fit_times times;
  if(order == 2)
    times.solve_us = us_per_system(
      [&](std::size_t q) { // the columns x, y and h
        std::copy(system(q) + S.P, system(q) + 3 * S.P, xyh.data());
        std::copy(system(q) + S.cols * S.P, system(q) + (S.cols + 1) * S.P, xyh.data() + 2 * S.P);
      },
      [&] { if(WI::order2_least_squares(xyh.data(), S.rows, c.data())) sum += c[3]; });
  else
  {
    times.basis_us = us_per_system(
      [&](std::size_t q) { // column 1 is x, column 2 is y
        std::copy(system(q) + S.P, system(q) + 2 * S.P, x.data());
        std::copy(system(q) + 2 * S.P, system(q) + 3 * S.P, y.data());
      },
      [&] {
        WI::evaluate_basis_columns(x.data(), y.data(), S.rows, S.P, order, work.data());
        sum += work[S.P + 1];
      });
    times.solve_us = us_per_system([&](std::size_t q) { std::copy(system(q), system(q) + size, work.begin()); },
                                   [&] { if(WI::wavejet_least_squares(work.data(), S.rows, S.cols, scratch.data(), c.data())) sum += c[3]; });
  }
  if(!std::isfinite(sum)) std::cerr << "final fit produced NaN\n";
  return times;
}

/// Where the time of three point-set functions goes (Sequential_tag, one thread, us per point): the
/// whole call; the k-NN (Neighbor_query, tree included); the fitting core (Fitter::fit on
/// pre-gathered neighborhoods, the function's own fit settings), split into one fit at the full order
/// (basis, solve: time_final_fit()) and the rest of the core (PCA frame, the other solves of the
/// tangent-plane search, frames); and what remains of the call (gathering the neighborhoods, the
/// filter, writing the results).
static wavejets_bench::Csv_table time_breakdown_table(const Points& input)
{
  wavejets_bench::Csv_table s({"function", "total", "k-NN", "fitting core", "of which: one full-order fit, basis",
                               "its solve", "the rest of the core (PCA, the other solves of the tangent-plane search)",
                               "the rest of the call (gathering, filter, writing)"});
  struct Case
  {
    const char* name;
    CGAL::Wavejets::Point_set_function f;
    std::size_t order;
    unsigned int k;
  };
  const Case cases[] = {{"wavejet_estimate_normals, K 2, k 18", CGAL::Wavejets::Point_set_function::ESTIMATE_NORMALS, 2, 18},
                        {"wavejet_estimate_normals, K 6, k 96", CGAL::Wavejets::Point_set_function::ESTIMATE_NORMALS, 6, 96},
                        {"wavejet_enhance_positions, K 6, k 96", CGAL::Wavejets::Point_set_function::ENHANCE_POSITIONS, 6, 96}};
  const double N = double(input.size());
  const std::size_t m = (std::min<std::size_t>)(input.size(), 20000);
  // The parts are timed in turn, five rounds, and each keeps its fastest round: all of them see the
  // machine in the same state (the last two columns are differences, which slow drifts of a shared
  // machine would otherwise dominate).
  const int rounds = 5;
  for(const Case& c : cases)
  {
    const CGAL::Wavejets::Fitting_options fitting = function_fitting(input, c.order, c.k, c.f);
    double total = 1e300, knn = 1e300, fit = 1e300;
    Final_fit_times final_fit{1e300, 1e300};
    for(int round = 0; round < rounds; ++round)
    {
      Points copy = input;
      total = (std::min)(total, 1e6 / N *
        (c.f == CGAL::Wavejets::Point_set_function::ENHANCE_POSITIONS ? time_wavejet_enhance<CGAL::Sequential_tag>(copy, c.order, c.k)
                                                                     : time_wavejet_normals<CGAL::Sequential_tag>(copy, c.order, c.k)));
      knn = (std::min)(knn, 1e6 / N * time_knn<CGAL::Sequential_tag>(input, c.k));
      fit = (std::min)(fit, 1e6 / N * time_fitter(input, m, c.order, c.k, fitting));
      const Final_fit_times again = time_final_fit(input, c.order, c.k);
      final_fit.basis_us = (std::min)(final_fit.basis_us, again.basis_us);
      final_fit.solve_us = (std::min)(final_fit.solve_us, again.solve_us);
    }
    s.add_row({c.name, fmt(total, 2), fmt(knn, 2), fmt(fit, 2),
               c.order == 2 ? std::string("-") : fmt(final_fit.basis_us, 2), fmt(final_fit.solve_us, 2),
               fmt(fit - final_fit.basis_us - final_fit.solve_us, 2), fmt(total - knn - fit, 2)});
  }
  // results.md explains the columns: each the fastest of `rounds`, on `m` neighborhoods.
  return s;
}

static void run_speed(const Options& o, std::vector<Row>& rows, std::vector<std::string>& notes, Targets& targets)
{
  const int T = max_threads();
  CGAL::Real_timer ts;
  ts.start();
  const Points input = sample_bunny(o.mesh, o.n, o.seed);
  ts.stop();
  std::cout << "sampled " << input.size() << " points in " << ts.time() << " s\n";

  auto add = [&](const std::string& step, const std::string& mode, int threads, std::size_t n, double s,
                 const std::string& against = std::string()) {
    rows.push_back(Row{step, mode, threads, n, s, peak_rss_mb(), against});
    const Row& r = rows.back();
    std::cout << std::left << std::setw(44) << step << std::setw(5) << mode << " threads " << threads << "  N " << n
              << "  " << fmt(s, 3) << " s  " << fmt(r.us(), 2) << " us/pt  peak " << fmt(r.rss_mb, 0) << " MB"
              << std::endl;
  };

  // kNN floor
  for(unsigned int k : {18u, 32u, 96u})
  {
    const std::string name = "kNN only (Neighbor_query), k " + std::to_string(k);
    add(name, "seq", 1, input.size(), time_knn<CGAL::Sequential_tag>(input, k));
#ifdef CGAL_LINKED_WITH_TBB
    add(name, "par", T, input.size(), time_knn<CGAL::Parallel_tag>(input, k));
#endif
  }
  // The same lists by CGAL's own k-NN search, sequential, build included.
  for(unsigned int k : {18u, 96u})
  {
    const double ours = time_knn<CGAL::Sequential_tag>(input, k);
    std::size_t mismatches = 0;
    const double cgal = time_cgal_knn(input, k, mismatches);
    const std::string name =
      "kNN alternative, CGAL Orthogonal_k_neighbor_search (the package's before), k " + std::to_string(k);
    add(name, "seq", 1, input.size(), cgal);
    notes.push_back(name + ": " + std::to_string(mismatches) + " of " + std::to_string(input.size()) +
                    " neighbor lists differ from Neighbor_query's");
    (k == 96 ? targets.knn_k96_over_cgal : targets.knn_k18_over_cgal) = ours / cgal;
  }

  // Fitting core alone
  {
    const std::size_t m = (std::min<std::size_t>)(input.size(), 20000);
    add("Fitter::fit only, K 2, k 100 (1 thread)", "seq", 1, input.size(), fastest_of_three([&] { return time_fitter(input, m, 2, 100); }));
    targets.fit_k2 = rows.back().us();
    add("Fitter::fit only, K 2, k 100, no re-fit (1 thread)", "seq", 1, input.size(),
        fastest_of_three([&] { return time_fitter(input, m, 2, 100, 0); }));
    targets.fit_k2_single = rows.back().us();
    add("Fitter::fit only, K 6, k 96 (1 thread)", "seq", 1, input.size(), fastest_of_three([&] { return time_fitter(input, m, 6, 96); }));
    targets.fit_k6 = rows.back().us();
    add("Fitter::fit only, K 2, k 50 (1 thread)", "seq", 1, input.size(), fastest_of_three([&] { return time_fitter(input, m, 2, 50); }));
#ifdef WAVEJETS_HAVE_PONCA
    const double fit_k2_k50 = rows.back().us();
    add("Ponca APSS fit only, k 50 (1 thread)", "seq", 1, input.size(), fastest_of_three([&] { return time_apss(input, m, 50); }));
    targets.fit_k2_over_apss_50 = fit_k2_k50 / rows.back().us();
    add("Ponca APSS fit only, k 100 (1 thread)", "seq", 1, input.size(), fastest_of_three([&] { return time_apss(input, m, 100); }));
    targets.fit_k2_over_apss_100 = targets.fit_k2 / rows.back().us();
    notes.push_back("`Ponca APSS fit only`: Ponca's OrientedSphereFit + GLSParam, constant weights (bench_ponca_accuracy's "
                    "APSS), on the neighborhoods of the `Fitter::fit only` rows of the same k (positions and oriented "
                    "Wavejet normals gathered before timing; the radius loop, the fit, kappa and the normal timed; the smallest of three runs).");
#else
    notes.push_back("Ponca was not found when bench_speed was configured: no APSS rows (set WAVEJETS_PONCA_DIR or "
                    "WAVEJETS_PONCA_TARBALL).");
#endif
    notes.push_back("`Fitter::fit only`: the fitting core on " + std::to_string(m) +
                    " pre-gathered neighborhoods (k-NN not timed), one thread, the smallest of three runs, scaled to us/point; default "
                    "options (PCA frame, least squares, 2 tangent-plane re-fits: 3 solves), or `no re-fit` "
                    "(correction_iterations 0: PCA and one solve).");
  }

  // Normals: CGAL jets against Wavejets
  const unsigned int orders[3] = {2, 4, 6}, ks[3] = {18, 32, 96};
  bool bitwise = true;
  double max_angle_deg = 0., sum_angle_deg = 0.;
  std::size_t n_angle = 0;
  for(int c = 0; c < 3; ++c)
  {
    const unsigned int d = orders[c], k = ks[c];
    const bool subset = (d == 6 && o.cgal_subset > 0 && o.cgal_subset < input.size());
    Points cgal_points = subset ? strided_subset(input, o.cgal_subset) : input;
    const std::string cname = "CGAL jet_estimate_normals, degree " + std::to_string(d) + ", k " + std::to_string(k);
    const std::string wname = "wavejet_estimate_normals, K " + std::to_string(d) + ", k " + std::to_string(k);
    add(cname, "seq", 1, cgal_points.size(), time_cgal_jet<CGAL::Sequential_tag>(cgal_points, d, k));
    const double cgal_seq_us = rows.back().us();
#ifdef CGAL_LINKED_WITH_TBB
    add(cname, "par", T, cgal_points.size(), time_cgal_jet<CGAL::Parallel_tag>(cgal_points, d, k));
#endif
    if(subset)
      notes.push_back("CGAL degree 6 / k 96 ran on a strided subset of " + std::to_string(cgal_points.size()) +
                      " of the N points (same surface, lower density; cost per point does not depend on density): "
                      "its ratio compares us/point.");
    Points seq = input;
    add(wname, "seq", 1, input.size(), time_wavejet_normals<CGAL::Sequential_tag>(seq, d, k), cname);
    if(d == 2) targets.ratio_k2 = cgal_seq_us / rows.back().us();
    if(d == 6) targets.ratio_k6 = cgal_seq_us / rows.back().us();
#ifdef CGAL_LINKED_WITH_TBB
    Points par = input;
    add(wname, "par", T, input.size(), time_wavejet_normals<CGAL::Parallel_tag>(par, d, k), cname);
    for(std::size_t i = 0; i < input.size(); ++i)
      if(!(seq[i].second == par[i].second)) { bitwise = false; break; }
#endif
    if(!subset) // agreement with CGAL (unoriented), same neighborhoods
      for(std::size_t i = 0; i < input.size(); ++i)
      {
        const Vector& a = seq[i].second; const Vector& b = cgal_points[i].second;
        const double cs = std::abs(a * b) / std::sqrt(a.squared_length() * b.squared_length());
        const double ang = std::acos((std::min)(1., cs)) * 180. / CGAL_PI;
        if(std::isfinite(ang)) { max_angle_deg = (std::max)(max_angle_deg, ang); sum_angle_deg += ang; ++n_angle; }
      }
  }
#ifdef CGAL_LINKED_WITH_TBB
  notes.push_back(std::string("Wavejet normals, Sequential_tag vs Parallel_tag: ") +
                  (bitwise ? "bitwise identical" : "DIFFERENT"));
#endif
  if(n_angle)
    notes.push_back("Angle between Wavejet and CGAL jet normals (degrees 2 and 4, same k, unoriented): mean " +
                    fmt(sum_angle_deg / double(n_angle), 3) + " deg, max " + fmt(max_angle_deg, 2) +
                    " deg (the Wavejet normal is that of the order-K Wavejet fitted in the tangent plane found by order-2 fits, "
                    "CGAL's that of the jet fitted in the PCA frame).");

  // Curvatures and position enhancement
  for(int c : {0, 2})
  {
    const std::string name = "wavejet_estimate_curvatures, K " + std::to_string(orders[c]) + ", k " + std::to_string(ks[c]);
    add(name, "seq", 1, input.size(), time_wavejet_curvatures<CGAL::Sequential_tag>(input, orders[c], ks[c]));
#ifdef CGAL_LINKED_WITH_TBB
    add(name, "par", T, input.size(), time_wavejet_curvatures<CGAL::Parallel_tag>(input, orders[c], ks[c]));
#endif
  }
  {
    const std::string name = "wavejet_enhance_positions, K 6, k 96";
    Points a = input;
    add(name, "seq", 1, input.size(), time_wavejet_enhance<CGAL::Sequential_tag>(a, 6, 96));
#ifdef CGAL_LINKED_WITH_TBB
    Points b = input;
    add(name, "par", T, input.size(), time_wavejet_enhance<CGAL::Parallel_tag>(b, 6, 96));
    bool same = true;
    for(std::size_t i = 0; i < input.size(); ++i)
      if(!(a[i].first == b[i].first)) { same = false; break; }
    notes.push_back(std::string("wavejet_enhance_positions, Sequential_tag vs Parallel_tag: ") +
                    (same ? "bitwise identical" : "DIFFERENT"));
#endif
  }
}

static wavejets_bench::Csv_table speed_table(const std::vector<Row>& rows)
{
  wavejets_bench::Csv_table s(
    {"step", "tag", "threads", "N", "time (s)", "us / point", "x faster than CGAL", "par speed-up", "peak RSS (MB)"});
  for(const Row& r : rows)
  {
    std::string ratio = "", speedup = "";
    if(!r.against.empty())
      for(const Row& c : rows)
        if(c.step == r.against && c.mode == r.mode) ratio = fmt(c.us() / r.us(), 1) + "x";
    if(r.mode == "par")
      for(const Row& c : rows)
        if(c.step == r.step && c.mode == "seq") speedup = fmt(c.seconds / r.seconds, 2) + "x";
    s.add_row({r.step, r.mode, std::to_string(r.threads), std::to_string(r.n), fmt(r.seconds, 3), fmt(r.us(), 2), ratio,
               speedup, fmt(r.rss_mb, 0)});
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Scaling: one sub-process per configuration

static int run_single(const Options& o)
{
  Thread_limit limit(o.threads);
  Points points = sample_bunny(o.mesh, o.n, o.seed);
  double s = 0.;
  if(o.fn == "enhance")
    s = o.threads == 1 ? time_wavejet_enhance<CGAL::Sequential_tag>(points, o.order, o.k)
                       : time_wavejet_enhance<CGAL::Parallel_tag>(points, o.order, o.k);
  else if(o.fn == "normals")
    s = o.threads == 1 ? time_wavejet_normals<CGAL::Sequential_tag>(points, o.order, o.k)
                       : time_wavejet_normals<CGAL::Parallel_tag>(points, o.order, o.k);
  else if(o.fn == "knn")
    s = o.threads == 1 ? time_knn<CGAL::Sequential_tag>(points, o.k) : time_knn<CGAL::Parallel_tag>(points, o.k);
  std::cout << "SINGLE " << s << " " << peak_rss_mb() << std::endl;
  return 0;
}

struct Scaling_row
{
  std::string fn;
  std::size_t n, order;
  unsigned int k;
  int threads;
  double seconds, rss_mb;
};

static bool run_child(const Options& o, const std::string& fn, std::size_t n, std::size_t order, unsigned int k,
                      int threads, Scaling_row& row)
{
  std::ostringstream cmd;
  cmd << "/proc/" << getpid() << "/exe --single --mesh '" << o.mesh << "' --seed " << o.seed << " --fn " << fn
      << " --n " << n << " --order " << order << " --k " << k << " --threads " << threads;
  const std::string out = shell_line(cmd.str());
  const std::size_t p = out.rfind("SINGLE ");
  if(p == std::string::npos) { std::cerr << "child failed: " << cmd.str() << "\n" << out << "\n"; return false; }
  std::istringstream in(out.substr(p + 7));
  row = Scaling_row{fn, n, order, k, threads, 0., 0.};
  in >> row.seconds >> row.rss_mb;
  std::cout << std::left << std::setw(8) << fn << " N " << std::setw(8) << n << " K " << order << " k " << k
            << " threads " << threads << "  " << fmt(row.seconds, 3) << " s  " << fmt(1e6 * row.seconds / n, 2)
            << " us/pt  peak " << fmt(row.rss_mb, 0) << " MB" << std::endl;
  return true;
}

/// The three scaling tables (results.md, section Scaling).
struct Scaling_tables
{
  wavejets_bench::Csv_table n{{"function", "K", "k", "N", "time (s)", "us / point", "peak RSS (MB)", "bytes / point"}};
  wavejets_bench::Csv_table order{{"K", "unknowns", "time (s)", "us / point", "peak RSS (MB)"}};
  wavejets_bench::Csv_table threads{{"function", "K", "k", "threads", "time (s)", "speed-up"}};
};

static Scaling_tables run_scaling(const Options& o, std::vector<std::string>& notes, Targets& targets)
{
  const int T = max_threads();
  Scaling_row r;
  Scaling_tables s;

  // N: time and memory against N (K = 6, k = 96 enhancement and K = 2, k = 18 normals, all threads)
  std::vector<std::size_t> ns;
  for(std::size_t n : {100000ul, 200000ul, 600000ul, 1000000ul, 2000000ul, 5000000ul})
    if(n <= o.scaling_max_n) ns.push_back(n);
  for(const char* fn : {"normals", "enhance"})
    for(std::size_t n : ns)
    {
      const bool enh = std::string(fn) == "enhance";
      if(!run_child(o, fn, n, enh ? 6 : 2, enh ? 96 : 18, T, r)) continue;
      if(enh && n == 600000) targets.enhance_600k = r.seconds;
      if(enh && n == 5000000)
      {
        targets.enhance_5m = r.seconds;
        targets.enhance_5m_rss_mb = r.rss_mb;
      }
      s.n.add_row({enh ? "wavejet_enhance_positions" : "wavejet_estimate_normals", std::to_string(r.order),
                   std::to_string(r.k), std::to_string(n), fmt(r.seconds, 2), fmt(1e6 * r.seconds / n, 2),
                   fmt(r.rss_mb, 0), fmt(r.rss_mb * 1048576. / n, 0)});
    }
  if(o.scaling_max_n < 5000000)
    notes.push_back("Not run: N above " + std::to_string(o.scaling_max_n) + " (pass --scaling-max-n 5000000).");

  // K: order from 2 to 10 at fixed k = 96 (enough points for K = 10: 66 unknowns x 1.1)
  const std::size_t nk = (std::min<std::size_t>)(o.n, 100000);
  for(std::size_t K = 2; K <= 10; ++K)
    if(run_child(o, "enhance", nk, K, 96, T, r))
      s.order.add_row({std::to_string(K), std::to_string(WI::number_of_coefficients(K)), fmt(r.seconds, 2),
                       fmt(1e6 * r.seconds / nk, 2), fmt(r.rss_mb, 0)});

  // Threads
  const std::size_t nt = (std::min<std::size_t>)(600000, o.scaling_max_n);
  for(const char* fn : {"knn", "normals", "enhance"})
  {
    const std::string f = fn;
    const std::size_t K = f == "normals" ? 2 : 6;
    const unsigned int k = f == "normals" ? 18 : 96;
    double t1 = 0.;
    for(int t = 1; t <= T; t = (t == T ? T + 1 : (std::min)(2 * t, T)))
      if(run_child(o, fn, nt, K, k, t, r))
      {
        if(t == 1) t1 = r.seconds;
        if(t == 2 && f != "knn" && (targets.thread_speedup_min < 0 || t1 / r.seconds < targets.thread_speedup_min))
          targets.thread_speedup_min = t1 / r.seconds;
        s.threads.add_row({f == "knn"       ? "kNN only"
                           : f == "normals" ? "wavejet_estimate_normals"
                                            : "wavejet_enhance_positions",
                           f == "knn" ? std::string("-") : std::to_string(K), std::to_string(k), std::to_string(t),
                           fmt(r.seconds, 2), fmt(t1 / r.seconds, 2) + "x"});
      }
  }
  if(T < 4) notes.push_back("Threads: only 1 to " + std::to_string(T) + " on this machine.");
  return s;
}

// ---------------------------------------------------------------------------------------------

int main(int argc, char** argv)
{
  const Options o = parse(argc, argv);
  if(o.mode == "single") return run_single(o);
  if(o.mode == "solver") // the least-squares table alone, printed (nothing written)
  {
    std::cout << qr_comparison_table(sample_bunny(o.mesh, o.n, o.seed)).str();
    return EXIT_SUCCESS;
  }

  // Each table goes to <csv-dir>/results.<name>.csv; make_reports.py writes results.md and results.png from them.
  std::vector<std::pair<std::string, wavejets_bench::Csv_table> > tables;
  std::vector<Row> rows;
  std::vector<std::string> notes;
  Targets targets;
  targets.threads = max_threads();
  CGAL::Real_timer total;
  total.start();
  if(o.mode == "speed" || o.mode == "all")
  {
    run_speed(o, rows, notes, targets);
    tables.emplace_back("speed", speed_table(rows));
    const Points sample = sample_bunny(o.mesh, o.n, o.seed);
    tables.emplace_back("least_squares", qr_comparison_table(sample));
    tables.emplace_back("time_split", time_breakdown_table(sample));
  }
  if(o.mode == "scaling" || o.mode == "all")
  {
    Scaling_tables scaling = run_scaling(o, notes, targets);
    tables.emplace_back("scaling_n", std::move(scaling.n));
    tables.emplace_back("scaling_order", std::move(scaling.order));
    tables.emplace_back("scaling_threads", std::move(scaling.threads));
  }
  total.stop();
  tables.emplace_back("targets", targets_table(targets));

  wavejets_bench::Csv_table note_table({"note"});
  for(const std::string& n : notes) note_table.add_row({n});
  tables.emplace_back("notes", std::move(note_table));
  wavejets_bench::Csv_table context = wavejets_bench::context_table();
  context.add_row({"machine", shell_line("lscpu | sed -n 's/^Model name: *//p' | head -1") + ", " +
                                std::to_string(std::thread::hardware_concurrency()) + " hardware threads (" +
                                shell_line("lscpu | sed -n 's/^Core(s) per socket: *//p' | head -1") +
                                " cores per socket), " +
                                shell_line("awk '/MemTotal/ {printf \"%.1f GB\", $2/1048576}' /proc/meminfo") +
                                " RAM; TBB threads: " + std::to_string(max_threads()) +
                                "; the solver's variant the dispatch runs: " + solver_variant()});
  context.add_row({"total time (s)", fmt(total.time(), 1)});
  tables.emplace_back("context", std::move(context));

  for(const auto& t : tables)
  {
    std::cout << "\nresults." << t.first << "\n" << t.second.str();
    if(!o.no_write) t.second.write(o.csv_dir, "results." + t.first);
  }
  return 0;
}
