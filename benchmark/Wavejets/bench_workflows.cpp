// What swapping the normal estimator buys in CGAL's reconstruction workflow (read, remove
// outliers, estimate normals, orient them with mst_orient_normals, Poisson reconstruction):
// on closed triangle meshes with known geometry, sampled densely, with Gaussian position noise
// and outliers, each normal estimator feeds the same workflow, and the reconstructed surface is
// compared with the true one (point-to-mesh distances through AABB trees, both ways).
//
// Usage: bench_workflows [--points N] [--k K] [--samples M] [--mesh file.off]... [--csv-dir DIR]
//                        [--no-write]
//   --points N   points sampled per mesh (default 30000)
//   --k K        neighbors of every normal estimator and of mst_orient_normals (default 24, CGAL's tutorial)
//   --samples M  points sampled on each surface for the distances (default 30000)
//   --mesh F     a closed triangle mesh (repeatable; default data/bunny00.off and data/fandisk.off)
//   --csv-dir D  where the tables go as CSV (default csv/ next to this source: workflows.<mesh>.csv,
//                workflows.meshes.csv, workflows.context.csv); make_reports.py writes workflows.md and
//                workflows.png from them
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/version.h>
#if CGAL_VERSION_MAJOR >= 6
#include <CGAL/AABB_traits_3.h>
#else
#include <CGAL/AABB_traits.h>
#endif
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Random.h>
#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/point_generators_3.h>

#include <CGAL/compute_average_spacing.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/poisson_surface_reconstruction.h>
#include <CGAL/remove_outliers.h>

#include <CGAL/wavejet_estimate_normals.h>

#include "bench_common.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <random>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>


typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Point_set_3<Point, Vector> Point_set;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
#if CGAL_VERSION_MAJOR >= 6
typedef CGAL::AABB_traits_3<Kernel, Primitive> Traits;
#else
typedef CGAL::AABB_traits<Kernel, Primitive> Traits;
#endif
typedef CGAL::AABB_tree<Traits> Tree;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace WP = CGAL::Wavejets::parameters;

struct Condition
{
  std::string name;
  double sigma;            // Gaussian noise per coordinate, fraction of the bounding-box diagonal
  double outlier_fraction; // points moved by a uniform vector of a ball of radius 2.5% of the diagonal
};

struct Estimator
{
  std::string name;
  std::function<void(Point_set&, unsigned int)> run; // writes the unoriented normals
};

struct Result
{
  std::string mesh, condition, estimator;
  std::size_t input = 0, after_outlier_removal = 0, oriented = 0;
  double normal_seconds = 0., mean_angle = 0., flipped_percent = 0.;
  bool reconstructed = false;
  std::size_t vertices = 0;
  double to_true_mean = 0., to_true_p95 = 0., from_true_mean = 0., from_true_p95 = 0., hausdorff = 0.;
};

static std::string fmt(double v, int digits = 3)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// Mean, 95th percentile and maximum of distances.
static void summarize(std::vector<double> d, double& mean, double& p95, double& max)
{
  std::sort(d.begin(), d.end());
  double sum = 0.;
  for(double x : d) sum += x;
  mean = sum / double(d.size());
  p95 = d[std::size_t(0.95 * double(d.size() - 1))];
  max = d.back();
}

static std::vector<double> distances(const std::vector<Point>& from, const Tree& to)
{
  std::vector<double> d;
  d.reserve(from.size());
  for(const Point& p : from) d.push_back(std::sqrt(to.squared_distance(p)));
  return d;
}

static std::vector<Point> sample(const Mesh& mesh, std::size_t n, unsigned int seed)
{
  // The generator draws the triangle with `random` but the point inside it with
  // CGAL::get_default_random() (CGAL 5.5.1): seed both, or the sample changes from run to run.
  CGAL::Random random(seed);
  CGAL::get_default_random() = CGAL::Random(seed + 1);
  std::vector<Point> points;
  points.reserve(n);
  CGAL::Random_points_in_triangle_mesh_3<Mesh> generator(mesh, random);
  std::copy_n(generator, n, std::back_inserter(points));
  return points;
}

// Order 2 (the default); robust_iterations(0) and use_neighbor_normals(false) are the defaults.
// With use_neighbor_normals(true) the function estimates the neighbors' normals itself first (the
// point set's normals are not read: no parameter asks for the input normals).
static void wavejet_normals(Point_set& points, unsigned int k, std::size_t robust_iterations, bool hermite)
{
  CGAL::wavejet_estimate_normals<CGAL::Sequential_tag>(
    points, k, WP::order(2).robust_iterations(robust_iterations).use_neighbor_normals(hermite));
}

struct Options
{
  std::string here = wavejets_bench::source_dir() + "/"; // ends in '/'
  std::size_t n = 30000, samples = 30000;
  unsigned int k = 24;
  std::vector<std::string> meshes;
  std::string csv_dir = here + "csv";
  bool write = true;
};

/// Reads the options; returns false when the program should stop at once with `exit_code`.
static bool parse_command_line(int argc, char** argv, Options& o, int& exit_code)
{
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if(a == "--points" && has_value) o.n = std::stoul(argv[++i]);
    else if(a == "--k" && has_value) o.k = unsigned(std::stoul(argv[++i]));
    else if(a == "--samples" && has_value) o.samples = std::stoul(argv[++i]);
    else if(a == "--mesh" && has_value) o.meshes.push_back(argv[++i]);
    else if(a == "--csv-dir" && has_value) o.csv_dir = argv[++i];
    else if(a == "--no-write") o.write = false;
    else
    {
      std::cerr << "usage: bench_workflows [--points N] [--k K] [--samples M] [--mesh file.off]... [--csv-dir DIR] "
                   "[--no-write]\n";
      exit_code = a == "--help" ? 0 : 1;
      return false;
    }
  }
  if(o.n < 1000 || o.k < 6 || o.samples < 1000)
  {
    std::cerr << "need --points >= 1000, --k >= 6, --samples >= 1000\n";
    exit_code = 1;
    return false;
  }
  if(o.meshes.empty())
    o.meshes = {o.here + "data/bunny00.off",
                o.here + "data/fandisk.off"};
  return true;
}

static std::vector<Condition> scan_conditions()
{
  return {
    {"noise 0", 0., 0.}, {"noise 0.25%", 0.0025, 0.}, {"noise 0.5%", 0.005, 0.},
    {"noise 0.25% + 5% outliers", 0.0025, 0.05}};
}

// Every estimator writes unoriented normals with the same k, Sequential_tag (timed alone).
static std::vector<Estimator> normal_estimators()
{
  return {
    {"pca_estimate_normals", [](Point_set& ps, unsigned int kk) {
       CGAL::pca_estimate_normals<CGAL::Sequential_tag>(ps, kk, ps.parameters()); }},
    {"jet_estimate_normals (degree 2)", [](Point_set& ps, unsigned int kk) {
       CGAL::jet_estimate_normals<CGAL::Sequential_tag>(ps, kk, ps.parameters().degree_fitting(2)); }},
    {"wavejet_estimate_normals (order 2)", [](Point_set& ps, unsigned int kk) { wavejet_normals(ps, kk, 0, false); }},
    {"wavejet_estimate_normals, robust_iterations(3)", [](Point_set& ps, unsigned int kk) { wavejet_normals(ps, kk, 3, false); }},
    {"wavejet_estimate_normals, use_neighbor_normals(true)", [](Point_set& ps, unsigned int kk) {
       wavejet_normals(ps, kk, 0, true); }}};
}

/// A true mesh and what the measures need from it (all references to objects of run_mesh).
struct Ground_truth
{
  const std::string& name;
  const Mesh& mesh;
  const Tree& tree;
  const std::vector<Point>& samples; // points on the mesh, for the distances from it
  double diagonal, outward;
};

/// The scan of condition number `index`: the clean samples + Gaussian noise; a fraction of them moved off the
/// surface by a uniform vector of a ball of radius 2.5% of the diagonal (the same points for every estimator).
/// Returns the map that marks the outliers.
static Point_set::Property_map<unsigned char> make_scan(Point_set& scan, const std::vector<Point>& clean,
                                                        const Condition& c, unsigned int index, double diagonal)
{
  std::mt19937 engine(1000u + index);
  std::normal_distribution<double> gauss(0., c.sigma * diagonal);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  scan.add_normal_map();
  Point_set::Property_map<unsigned char> is_outlier = scan.add_property_map<unsigned char>("outlier", 0).first;
  const std::size_t stride = c.outlier_fraction > 0. ? std::size_t(1. / c.outlier_fraction + 0.5) : 0;
  for(std::size_t i = 0; i < clean.size(); ++i)
  {
    Vector d(0, 0, 0);
    if(c.sigma > 0.) d = Vector(gauss(engine), gauss(engine), gauss(engine));
    const Point_set::iterator it = scan.insert(clean[i] + d);
    if(stride > 0 && i % stride == 0)
    {
      Vector b;
      do b = Vector(uniform(engine), uniform(engine), uniform(engine)); while(b.squared_length() > 1.);
      scan.point(*it) = scan.point(*it) + 0.025 * diagonal * b;
      is_outlier[*it] = 1;
    }
  }
  return is_outlier;
}

/// The workflow's outlier removal (wavejet_reconstruction_workflow.cpp): average distance to
/// 24 neighbors above twice its average over all points.
static void remove_scan_outliers(Point_set& scan)
{
  const double input_spacing = CGAL::compute_average_spacing<CGAL::Sequential_tag>(scan, 24);
  scan.remove(CGAL::remove_outliers<CGAL::Sequential_tag>(
                scan, 24, scan.parameters().threshold_percent(100.).threshold_distance(2. * input_spacing)),
              scan.end());
  scan.collect_garbage();
}

/// Normal error against the true (outward) normal of the closest triangle, outliers excluded.
static void measure_normals(const Point_set& points, const Point_set::Property_map<unsigned char>& is_outlier,
                            const Ground_truth& t, Result& r)
{
  double angle_sum = 0.;
  std::size_t counted = 0, flipped = 0;
  for(Point_set::Index i : points)
  {
    if(is_outlier[i]) continue;
    const Vector tn = t.outward * PMP::compute_face_normal(t.tree.closest_point_and_primitive(points.point(i)).second, t.mesh);
    const Vector m = points.normal(i);
    const double cosine = CGAL::to_double(tn * m) / std::sqrt(CGAL::to_double(m.squared_length()));
    const double angle = std::acos(std::clamp(std::abs(cosine), 0., 1.)) * 180. / CGAL_PI;
    angle_sum += angle;
    flipped += cosine < 0;
    ++counted;
  }
  r.mean_angle = angle_sum / double(counted);
  r.flipped_percent = 100. * double(flipped) / double(counted);
}

/// Poisson reconstruction, as in the workflow (size parameter: average spacing), and its distances to the truth.
static void reconstruct_and_measure(const Point_set& points, const Ground_truth& t, std::size_t samples, Result& r)
{
  Mesh reconstruction;
  const double spacing = CGAL::compute_average_spacing<CGAL::Sequential_tag>(points, 6);
  // CGAL's surface mesher may stop on an assertion for some normals (seen on fandisk at noise 0.25%
  // with badly oriented normals): that is a failed reconstruction of this estimator, not of the run.
  try {
    r.reconstructed = CGAL::poisson_surface_reconstruction_delaunay(
                        points.begin(), points.end(), points.point_map(), points.normal_map(), reconstruction, spacing)
                      && reconstruction.number_of_faces() > 0;
  } catch(const CGAL::Failure_exception& e) {
    std::cout << "  (Poisson reconstruction failed: " << e.message() << ")" << std::endl;
    r.reconstructed = false;
  }
  if(r.reconstructed)
  {
    r.vertices = reconstruction.number_of_vertices();
    Tree tree(faces(reconstruction).first, faces(reconstruction).second, reconstruction);
    tree.accelerate_distance_queries();
    double max_to = 0., max_from = 0.;
    summarize(distances(sample(reconstruction, samples, 11), t.tree), r.to_true_mean, r.to_true_p95, max_to);
    summarize(distances(t.samples, tree), r.from_true_mean, r.from_true_p95, max_from);
    for(double* v : {&r.to_true_mean, &r.to_true_p95, &r.from_true_mean, &r.from_true_p95}) *v *= 100. / t.diagonal;
    r.hausdorff = std::max(max_to, max_from) * 100. / t.diagonal;
  }
}

/// One estimator in the workflow on `scan` (after outlier removal; `input` points before).
static Result run_workflow(const Estimator& e, const Point_set& scan, const Point_set::Property_map<unsigned char>& is_outlier,
                           std::size_t input, const Condition& c, const Ground_truth& t, const Options& o,
                           const CGAL::Real_timer& total)
{
  Result r;
  r.mesh = t.name; r.condition = c.name; r.estimator = e.name;
  r.input = input; r.after_outlier_removal = scan.size();
  Point_set points = scan;
  CGAL::Real_timer timer;
  timer.start();
  e.run(points, o.k);
  timer.stop();
  r.normal_seconds = timer.time();
  // No collect_garbage(): `points` keeps the indices of `scan`, so scan's maps read it.
  points.remove(CGAL::mst_orient_normals(points, o.k, points.parameters()), points.end());
  r.oriented = points.size();
  measure_normals(points, is_outlier, t, r);
  reconstruct_and_measure(points, t, o.samples, r);
  std::cout << "  " << e.name << ": normals " << fmt(r.normal_seconds) << " s, mean angle " << fmt(r.mean_angle, 2)
            << " deg, flipped " << fmt(r.flipped_percent, 2) << "%, reconstruction -> truth mean "
            << fmt(r.to_true_mean) << "% p95 " << fmt(r.to_true_p95) << "%, truth -> reconstruction p95 "
            << fmt(r.from_true_p95) << "% (" << fmt(total.time(), 0) << " s so far)" << std::endl;
  return r;
}

/// The workflow with every estimator on every scan of one mesh; appends its row to `meshes`.
static bool run_mesh(const std::string& file, const Options& o, std::vector<Result>& results,
                     wavejets_bench::Csv_table& meshes, const CGAL::Real_timer& total)
{
  Mesh truth;
  if(!CGAL::IO::read_polygon_mesh(file, truth) || truth.is_empty() || !CGAL::is_triangle_mesh(truth)
     || !CGAL::is_closed(truth))
  {
    std::cerr << "cannot read " << file << " as a closed triangle mesh\n";
    return false;
  }
  const std::string mesh_name = file.substr(file.find_last_of('/') + 1);
  const CGAL::Bbox_3 box = PMP::bbox(truth);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin())
                                    + CGAL::square(box.zmax() - box.zmin()));
  const double outward = PMP::volume(truth) > 0 ? 1. : -1.; // faces oriented outward or inward
  Tree truth_tree(faces(truth).first, faces(truth).second, truth);
  truth_tree.accelerate_distance_queries();
  const std::vector<Point> truth_samples = sample(truth, o.samples, 7);
  const std::vector<Point> clean = sample(truth, o.n, 42);
  const double spacing = CGAL::compute_average_spacing<CGAL::Sequential_tag>(clean, 6);
  meshes.add_row({mesh_name, std::to_string(truth.number_of_vertices()), std::to_string(truth.number_of_faces()),
                  fmt(diagonal, 4), fmt(spacing / diagonal * 100., 3)});
  const Ground_truth t{mesh_name, truth, truth_tree, truth_samples, diagonal, outward};
  const std::vector<Condition> conditions = scan_conditions();
  for(const Condition& c : conditions)
  {
    Point_set scan;
    const Point_set::Property_map<unsigned char> is_outlier =
      make_scan(scan, clean, c, unsigned(&c - conditions.data()), diagonal);
    const std::size_t input = scan.size();
    remove_scan_outliers(scan);
    std::size_t outliers_left = 0;
    for(Point_set::Index i : scan) outliers_left += is_outlier[i];
    std::cout << mesh_name << ", " << c.name << ": " << input << " points, " << scan.size()
              << " after remove_outliers (" << outliers_left << " outliers left)" << std::endl;
    for(const Estimator& e : normal_estimators()) results.push_back(run_workflow(e, scan, is_outlier, input, c, t, o, total));
  }
  return true;
}

/// The name of a mesh's table: the file name without its extension and trailing digits (bunny00.off: bunny).
static std::string table_name(const std::string& mesh_name)
{
  std::string stem = mesh_name.substr(0, mesh_name.find('.'));
  while(!stem.empty() && std::isdigit(static_cast<unsigned char>(stem.back()))) stem.pop_back();
  return "workflows." + stem;
}

/// The table of one mesh: every scan and estimator.
static wavejets_bench::Csv_table mesh_table(const std::string& mesh_name, const std::vector<Result>& results)
{
  wavejets_bench::Csv_table table({"scan", "normals", "normal step (s)", "mean angle (deg)", "inward (%)",
                                   "rec. to true: mean", "p95", "true to rec.: mean", "p95", "Hausdorff"});
  for(const Result& r : results)
  {
    if(r.mesh != mesh_name) continue;
    std::vector<std::string> row{r.condition + " (" + std::to_string(r.after_outlier_removal) + " pts)", r.estimator,
                                 fmt(r.normal_seconds, 3), fmt(r.mean_angle, 2), fmt(r.flipped_percent, 2)};
    if(r.reconstructed)
      for(const std::string& c : {fmt(r.to_true_mean), fmt(r.to_true_p95), fmt(r.from_true_mean), fmt(r.from_true_p95),
                                  fmt(r.hausdorff, 2)})
        row.push_back(c);
    else
      for(const char* c : {"failed", "", "", "", ""}) row.push_back(c);
    table.add_row(row);
  }
  return table;
}

int main(int argc, char** argv)
{
  Options o;
  int exit_code = 0;
  if(!parse_command_line(argc, argv, o, exit_code)) return exit_code;
  CGAL::Real_timer total;
  total.start();
  std::vector<Result> results;
  wavejets_bench::Csv_table meshes({"mesh", "vertices", "triangles", "bounding-box diagonal",
                                    "average spacing of the clean samples, 6 neighbors (% of the diagonal)"});
  for(const std::string& file : o.meshes)
    if(!run_mesh(file, o, results, meshes, total)) return 1;
  total.stop();

  // workflows.md's tables, as CSV: one per mesh, the meshes, the run's context (make_reports.py writes the report).
  std::vector<std::pair<std::string, wavejets_bench::Csv_table> > tables;
  for(const std::string& file : o.meshes)
  {
    const std::string mesh_name = file.substr(file.find_last_of('/') + 1);
    tables.emplace_back(table_name(mesh_name), mesh_table(mesh_name, results));
  }
  tables.emplace_back("workflows.meshes", meshes);
  wavejets_bench::Csv_table context = wavejets_bench::context_table();
  context.add_row({"machine", std::to_string(std::thread::hardware_concurrency()) + " hardware threads; " +
#if defined(__clang__)
                                "clang++ " + std::to_string(__clang_major__) +
#elif defined(__GNUC__)
                                "g++ " + std::to_string(__GNUC__) +
#endif
                                " and CGAL " + CGAL_VERSION_STR + ", Release"});
  context.add_row({"run time (s)", fmt(total.time(), 0)});
  tables.emplace_back("workflows.context", context);
  for(const auto& t : tables)
  {
    std::cout << "\n" << t.first << "\n" << t.second.str();
    if(o.write) t.second.write(o.csv_dir, t.first);
  }
  return 0;
}
