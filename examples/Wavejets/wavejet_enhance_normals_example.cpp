// Exaggerates (or blurs, inverts, twists) the normal variation of a scan with the Wavejets
// normal filter; positions are unchanged. Writes a PLY to view with shading.
// Usage: wavejet_enhance_normals_example [input.xyz] [output.ply] [gain_real] [gain_imag]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/IO/write_points.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_enhance_normals.h>

#include <complex>
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
  const std::string output = argc > 2 ? argv[2] : std::string(dir ? dir : ".") + "/kitten_enhanced_normals.ply";
  const std::complex<double> gain(argc > 3 ? std::atof(argv[3]) : 3., argc > 4 ? std::atof(argv[4]) : 0.);

  const auto point_map = CGAL::First_of_pair_property_map<Point_with_normal>();
  const auto normal_map = CGAL::Second_of_pair_property_map<Point_with_normal>();
  std::vector<Point_with_normal> points; // the input normals orient the output normals
  if(!CGAL::IO::read_points(input, std::back_inserter(points),
                            CGAL::parameters::point_map(point_map).normal_map(normal_map)))
  {
    std::cerr << "Error: cannot read " << input << std::endl;
    return EXIT_FAILURE;
  }

  // gain 1: the Wavejet's own (denoised) normals; > 1 exaggerates; 0 blurs; < 0 inverts; i: twists.
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_enhance_normals<Concurrency_tag>(
    points, 40, gain, CGAL::Wavejets::parameters::order(5).point_map(point_map).normal_map(normal_map));
  std::cout << report << std::endl;

  if(!CGAL::IO::write_PLY(output, points, CGAL::parameters::point_map(point_map).normal_map(normal_map)))
  {
    std::cerr << "Error: cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << std::endl;
  return EXIT_SUCCESS;
}
