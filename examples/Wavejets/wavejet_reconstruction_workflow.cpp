// Surface reconstruction from a scan, the way CGAL's reconstruction tutorial does it, with
// Wavejet normals: read the scan, remove outliers, simplify, estimate normals with
// wavejet_estimate_normals (instead of jet_estimate_normals), orient them with
// mst_orient_normals, optionally amplify the surface details with wavejet_enhance_positions,
// then mesh with Poisson surface reconstruction and write the mesh and the processed points.
//
// Usage: wavejet_reconstruction_workflow [input] [output.ply] [options]
//   input        any point set CGAL::IO reads (.xyz, .pwn, .ply, .off vertices); default data/kitten.xyz
//   output.ply   the reconstructed mesh; the processed points (with their oriented normals) go to
//                output_points.ply next to it. Default: $WAVEJETS_OUTPUT_DIR/kitten_poisson.ply
//   --k N        neighbors of the normal estimation and orientation (default 24, as in the tutorial)
//   --order K    Wavejet order of the normals (default 2)
//   --robust     robust_iterations(3): Tukey-weighted fits, for scans with outliers left
//   --grid F     grid simplification cell = F x average spacing (default 2, as in the tutorial; 0: off)
//   --enhance G  before meshing, move the points with wavejet_enhance_positions, gain G (2 doubles
//                the details, 1 only denoises); off by default
// Larger setting, e.g.: wavejet_reconstruction_workflow data/kitten.xyz out.ply --grid 0 --k 48 --enhance 2
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Point_set_3/IO.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/compute_average_spacing.h>
#include <CGAL/grid_simplify_point_set.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/poisson_surface_reconstruction.h>
#include <CGAL/remove_outliers.h>

#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Point_set_3<Point, Vector> Point_set;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef CGAL::Parallel_if_available_tag Concurrency_tag;

namespace WP = CGAL::Wavejets::parameters;

int main(int argc, char** argv)
{
  // Command line (see the header comment).
  std::string input = "data/kitten.xyz";
  const char* dir = std::getenv("WAVEJETS_OUTPUT_DIR");
  std::string output = std::string(dir ? dir : ".") + "/kitten_poisson.ply";
  unsigned int k = 24;
  std::size_t order = 2, robust_iterations = 0;
  double grid_factor = 2., gain = 0.;
  bool enhance = false;
  int positional = 0;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if(a == "--k" && has_value) k = unsigned(std::atoi(argv[++i]));
    else if(a == "--order" && has_value) order = std::size_t(std::atoi(argv[++i]));
    else if(a == "--grid" && has_value) grid_factor = std::atof(argv[++i]);
    else if(a == "--enhance" && has_value) { enhance = true; gain = std::atof(argv[++i]); }
    else if(a == "--robust") robust_iterations = 3;
    else if(a.size() > 1 && a[0] == '-')
    {
      std::cerr << "Error: unknown or incomplete option " << a << " (see the source's header comment)" << std::endl;
      return EXIT_FAILURE;
    }
    else if(positional == 0) { input = a; ++positional; }
    else if(positional == 1) { output = a; ++positional; }
    else { std::cerr << "Error: too many arguments" << std::endl; return EXIT_FAILURE; }
  }
  if(k < 2 || order < 1 || !(grid_factor >= 0.))
  {
    std::cerr << "Error: need --k >= 2, --order >= 1 and --grid >= 0" << std::endl;
    return EXIT_FAILURE;
  }

  // 1. Read the scan into a Point_set_3 (points, and normals if the file has them: they are
  //    replaced by the estimated ones below).
  Point_set points;
  if(!CGAL::IO::read_point_set(input, points) || points.empty())
  {
    std::cerr << "Error: cannot read " << input << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Read " << points.size() << " points from " << input << std::endl;
  if(!points.has_normal_map()) points.add_normal_map();

  // 2. Remove outliers: points whose average distance to their 24 nearest neighbors exceeds
  //    twice the average of that distance over all points (CGAL's outlier-removal example; the
  //    tutorial's threshold_percent(5) alone would remove 5% of the points of a clean scan too).
  const double spacing_24 = CGAL::compute_average_spacing<Concurrency_tag>(points, 24);
  Point_set::iterator first_outlier = CGAL::remove_outliers<Concurrency_tag>(
    points, 24, points.parameters().threshold_percent(100.).threshold_distance(2. * spacing_24));
  points.remove(first_outlier, points.end());
  std::cout << points.number_of_removed_points() << " outliers removed" << std::endl;
  points.collect_garbage();

  // 3. Simplify: keep one point per cell of a grid of grid_factor x the average spacing, which
  //    also evens out the density of scan lines.
  double spacing = CGAL::compute_average_spacing<Concurrency_tag>(points, 6);
  if(grid_factor > 0.)
  {
    Point_set::iterator first_removed = CGAL::grid_simplify_point_set(points, grid_factor * spacing);
    points.remove(first_removed, points.end());
    std::cout << points.number_of_removed_points() << " points removed by the grid simplification" << std::endl;
    points.collect_garbage();
  }
  if(points.size() < 3)
  {
    std::cerr << "Error: only " << points.size() << " points left" << std::endl;
    return EXIT_FAILURE;
  }

  // 4. Normals: the Wavejet normal of every point (drop-in for jet_estimate_normals, same k).
  //    They are unoriented, like jet_estimate_normals'. The package's parameters come first in
  //    the chain; the Point_set_3's point and normal maps are used by default.
  const CGAL::Wavejets::Processing_report normal_report = CGAL::wavejet_estimate_normals<Concurrency_tag>(
    points, k, WP::order(order).robust_iterations(robust_iterations));
  std::cout << "Normals: " << normal_report << std::endl;

  // 5. Orient the normals consistently (minimum spanning tree); the points that cannot be
  //    oriented are removed, as in the tutorial.
  Point_set::iterator first_unoriented = CGAL::mst_orient_normals(points, k, points.parameters());
  points.remove(first_unoriented, points.end());
  std::cout << points.number_of_removed_points() << " points could not be oriented and were removed" << std::endl;
  points.collect_garbage();

  // 6. Optional: amplify (gain > 1), keep (1: denoise) or flatten (< 1) the surface details.
  //    Order 4 (the filter's default) on 2k neighbors; write_normals(true) replaces the normals by
  //    those of the moved surface, oriented like the mst_orient_normals ones.
  if(enhance)
  {
    const CGAL::Wavejets::Processing_report enhance_report = CGAL::wavejet_enhance_positions<Concurrency_tag>(
      points, 2 * k, gain, WP::order(4).write_normals(true));
    std::cout << "Enhancement (gain " << gain << "): " << enhance_report << std::endl;
  }

  // 7. Poisson surface reconstruction (needs oriented normals), with the average spacing of the
  //    processed points as size parameter, as in the tutorial.
  spacing = CGAL::compute_average_spacing<Concurrency_tag>(points, 6);
  Mesh mesh;
  if(!CGAL::poisson_surface_reconstruction_delaunay(points.begin(), points.end(), points.point_map(),
                                                    points.normal_map(), mesh, spacing)
     || mesh.number_of_faces() == 0)
  {
    std::cerr << "Error: Poisson reconstruction failed" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Poisson mesh: " << mesh.number_of_vertices() << " vertices, " << mesh.number_of_faces()
            << " triangles, " << (CGAL::is_closed(mesh) ? "closed" : "NOT closed") << std::endl;

  // 8. Write the mesh and the processed points (binary PLY; MeshLab and CloudCompare open both).
  const std::string points_output = output.substr(0, output.rfind('.')) + "_points.ply";
  if(!CGAL::IO::write_polygon_mesh(output, mesh, CGAL::parameters::use_binary_mode(true))
     || !CGAL::IO::write_point_set(points_output, points, CGAL::parameters::use_binary_mode(true)))
  {
    std::cerr << "Error: cannot write " << output << " or " << points_output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << " and " << points_output << std::endl;
  return CGAL::is_closed(mesh) && normal_report.number_of_unfitted_points == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
