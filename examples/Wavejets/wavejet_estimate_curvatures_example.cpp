// Estimates per-point curvature of a scan with Wavejets, prints statistics and writes a PLY
// with scalar properties (mean_curvature, gaussian_curvature, k1, k2) that MeshLab and
// CloudCompare open. Usage: wavejet_estimate_curvatures_example [input.xyz] [output.ply] [k] [order]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Point_set_3/IO.h>
#include <CGAL/wavejet_estimate_curvatures.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Point_set_3<Point> Point_set;
typedef CGAL::Parallel_if_available_tag Concurrency_tag;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : "data/kitten.xyz";
  const char* dir = std::getenv("WAVEJETS_OUTPUT_DIR");
  const std::string output = argc > 2 ? argv[2] : std::string(dir ? dir : ".") + "/kitten_curvatures.ply";
  const unsigned int k = argc > 3 ? unsigned(std::atoi(argv[3])) : 40;
  const std::size_t order = argc > 4 ? std::size_t(std::atoi(argv[4])) : 3;

  Point_set points; // the kitten scan has oriented normals: they fix the sign of the curvature
  if(!CGAL::IO::read_point_set(input, points) || points.empty())
  {
    std::cerr << "Error: cannot read " << input << std::endl;
    return EXIT_FAILURE;
  }
  Point_set::Property_map<double> mean = points.add_property_map<double>("mean_curvature", 0.).first;
  Point_set::Property_map<double> gauss = points.add_property_map<double>("gaussian_curvature", 0.).first;
  Point_set::Property_map<double> k1 = points.add_property_map<double>("k1", 0.).first;
  Point_set::Property_map<double> k2 = points.add_property_map<double>("k2", 0.).first;

  namespace WP = CGAL::Wavejets::parameters;
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_estimate_curvatures<Concurrency_tag>(
    points, k,
    WP::order(order).mean_curvature_map(mean).gaussian_curvature_map(gauss)
      .maximal_principal_curvature_map(k1).minimal_principal_curvature_map(k2)
      .point_map(points.point_map()).normal_map(points.normal_map()));
  std::cout << report << std::endl;

  // Statistics: median and 5%/95% percentiles (curvature is 1/length: the kitten is about 1 unit tall;
  // with outward normals, convex parts have H < 0).
  auto print = [&](const char* name, Point_set::Property_map<double> m) {
    std::vector<double> v;
    for(Point_set::Index i : points) v.push_back(m[i]);
    std::sort(v.begin(), v.end());
    auto at = [&](double q) { return v[std::size_t(q * double(v.size() - 1))]; };
    std::cout << name << ": 5% " << at(0.05) << "  median " << at(0.5) << "  95% " << at(0.95) << std::endl;
  };
  print("mean curvature H    ", mean);
  print("gaussian curvature K", gauss);
  print("k1                  ", k1);
  print("k2                  ", k2);

  if(!CGAL::IO::write_point_set(output, points))
  {
    std::cerr << "Error: cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << std::endl;
  return EXIT_SUCCESS;
}
