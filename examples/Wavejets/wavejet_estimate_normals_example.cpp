// Estimates normals with Wavejets, as jet_estimate_normals does with jets, and writes a PLY.
// Usage: wavejet_estimate_normals_example [input.xyz] [output.ply]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/IO/write_points.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_estimate_normals.h>

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
  const std::string output = argc > 2 ? argv[2] : std::string(dir ? dir : ".") + "/kitten_wavejet_normals.ply";

  std::vector<Point_with_normal> points;
  if(!CGAL::IO::read_points(input, std::back_inserter(points),
                            CGAL::parameters::point_map(CGAL::First_of_pair_property_map<Point_with_normal>())))
  {
    std::cerr << "Error: cannot read " << input << std::endl;
    return EXIT_FAILURE;
  }

  // Order-2 Wavejets on 18 neighbors (the counterpart of jet_estimate_normals with degree 2).
  // The normals are unoriented, like jet_estimate_normals'.
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_estimate_normals<Concurrency_tag>(
    points, 18,
    CGAL::Wavejets::parameters::order(2)
      .point_map(CGAL::First_of_pair_property_map<Point_with_normal>())
      .normal_map(CGAL::Second_of_pair_property_map<Point_with_normal>()));
  std::cout << report << std::endl;

  if(!CGAL::IO::write_PLY(output, points,
                          CGAL::parameters::point_map(CGAL::First_of_pair_property_map<Point_with_normal>())
                            .normal_map(CGAL::Second_of_pair_property_map<Point_with_normal>())))
  {
    std::cerr << "Error: cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << std::endl;
  return report.number_of_unfitted_points == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
