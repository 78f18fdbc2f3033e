// Amplifies the surface details of a scan by moving its points (Wavejets position filter),
// and writes a PLY. Usage: wavejet_enhance_positions_example [input.xyz] [output.ply] [gain]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/IO/write_points.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_enhance_positions.h>

#include <cstdlib>
#include <iostream>
#include <utility>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef std::pair<Point, Vector> Point_with_normal;
typedef CGAL::Parallel_if_available_tag Concurrency_tag;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : "data/kitten.xyz";
  const char* dir = std::getenv("WAVEJETS_OUTPUT_DIR");
  const std::string output = argc > 2 ? argv[2] : std::string(dir ? dir : ".") + "/kitten_enhanced_positions.ply";
  const double gain = argc > 3 ? std::atof(argv[3]) : 2.;

  const auto point_map = CGAL::First_of_pair_property_map<Point_with_normal>();
  const auto normal_map = CGAL::Second_of_pair_property_map<Point_with_normal>();
  std::vector<Point_with_normal> points;
  if(!CGAL::IO::read_points(input, std::back_inserter(points),
                            CGAL::parameters::point_map(point_map).normal_map(normal_map)))
  {
    std::cerr << "Error: cannot read " << input << std::endl;
    return EXIT_FAILURE;
  }

  // gain > 1 amplifies details, 0 <= gain < 1 flattens them, gain < 0 inverts them.
  // Each point moves at most Rf/2 (the default clamp); the Wavejet normals are written too.
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_enhance_positions<Concurrency_tag>(
    points, 40, gain,
    CGAL::Wavejets::parameters::order(4).write_normals(true).point_map(point_map).normal_map(normal_map));
  std::cout << report << std::endl;

  if(!CGAL::IO::write_PLY(output, points, CGAL::parameters::point_map(point_map).normal_map(normal_map)))
  {
    std::cerr << "Error: cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << std::endl;
  return EXIT_SUCCESS;
}
