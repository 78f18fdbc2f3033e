// Feature points of a scan from its Wavejet curvatures: estimate (or read) oriented normals,
// estimate the principal curvatures k1 >= k2 of every point with wavejet_estimate_curvatures,
// select the points on strongly bent convex ridges and concave valleys by thresholds on k1 and
// k2, color the scan by mean curvature and write two PLY files that MeshLab and CloudCompare
// open: every point with its scalar properties (mean_curvature, gaussian_curvature, k1, k2,
// feature) and colors (red, green, blue), and the feature points alone.
//
// Usage: wavejet_curvature_workflow [input] [output.ply] [options]
//   input            any point set CGAL::IO reads; default data/kitten.xyz (a scan with outward normals)
//   output.ply       default $WAVEJETS_OUTPUT_DIR/kitten_curvature_features.ply; the feature points
//                    go to output_only.ply next to it
//   --radius-factor F  neighborhood radius = F x the average spacing to 6 neighbors (default 5)
//   --order K        Wavejet order (default 3: noisy scans want 2 or 3, clean dense data 4 to 8)
//   --threshold T    curvature threshold, 1/length (default 1/Rf, a bend of the neighborhood's radius)
// Larger setting, e.g.: wavejet_curvature_workflow data/kitten.xyz out.ply --radius-factor 8 --order 4
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Point_set_3/IO.h>

#include <CGAL/compute_average_spacing.h>
#include <CGAL/mst_orient_normals.h>

#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Point_set_3<Point, Vector> Point_set;
typedef CGAL::Parallel_if_available_tag Concurrency_tag;

namespace WP = CGAL::Wavejets::parameters;

int main(int argc, char** argv)
{
  // Command line (see the header comment).
  std::string input = "data/kitten.xyz";
  const char* dir = std::getenv("WAVEJETS_OUTPUT_DIR");
  std::string output = std::string(dir ? dir : ".") + "/kitten_curvature_features.ply";
  double radius_factor = 5., threshold = 0.;
  std::size_t order = 3;
  int positional = 0;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if(a == "--radius-factor" && has_value) radius_factor = std::atof(argv[++i]);
    else if(a == "--order" && has_value) order = std::size_t(std::atoi(argv[++i]));
    else if(a == "--threshold" && has_value) threshold = std::atof(argv[++i]);
    else if(a.size() > 1 && a[0] == '-')
    {
      std::cerr << "Error: unknown or incomplete option " << a << " (see the source's header comment)" << std::endl;
      return EXIT_FAILURE;
    }
    else if(positional == 0) { input = a; ++positional; }
    else if(positional == 1) { output = a; ++positional; }
    else { std::cerr << "Error: too many arguments" << std::endl; return EXIT_FAILURE; }
  }
  if(!(radius_factor > 0.) || order < 1 || !(threshold >= 0.))
  {
    std::cerr << "Error: need --radius-factor > 0, --order >= 1 and --threshold >= 0" << std::endl;
    return EXIT_FAILURE;
  }

  // 1. Read the scan.
  Point_set points;
  if(!CGAL::IO::read_point_set(input, points) || points.size() < 3)
  {
    std::cerr << "Error: cannot read " << input << " (or fewer than 3 points)" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Read " << points.size() << " points from " << input << std::endl;

  // 2. Oriented normals fix the signs of the curvatures (a surface bending toward the normal has
  //    a positive curvature, so with outward normals a convex ridge has k2 < 0). Without normals
  //    in the file: Wavejet normals, then a consistent orientation (mst_orient_normals).
  if(!points.has_normal_map())
  {
    points.add_normal_map();
    CGAL::wavejet_estimate_normals<Concurrency_tag>(points, 18, WP::order(2));
    points.remove(CGAL::mst_orient_normals(points, 18, points.parameters()), points.end());
    std::cout << points.number_of_removed_points() << " points could not be oriented and were removed" << std::endl;
    points.collect_garbage();
  }

  // 3. Neighborhoods: a fixed radius, a multiple of the average spacing, so that the curvature is
  //    measured at the same scale everywhere whatever the local density (k = 0: no cap).
  const double spacing = CGAL::compute_average_spacing<Concurrency_tag>(points, 6);
  const double radius = radius_factor * spacing;

  // 4. Curvatures of every point into Point_set_3 properties, named as the PLY properties.
  Point_set::Property_map<double> mean = points.add_property_map<double>("mean_curvature", 0.).first;
  Point_set::Property_map<double> gauss = points.add_property_map<double>("gaussian_curvature", 0.).first;
  Point_set::Property_map<double> k1 = points.add_property_map<double>("k1", 0.).first;
  Point_set::Property_map<double> k2 = points.add_property_map<double>("k2", 0.).first;
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_estimate_curvatures<Concurrency_tag>(
    points, 0,
    WP::order(order).mean_curvature_map(mean).gaussian_curvature_map(gauss)
      .maximal_principal_curvature_map(k1).minimal_principal_curvature_map(k2)
      .neighbor_radius(radius));
  std::cout << "Curvatures (Rf = " << radius << "): " << report << std::endl;

  // 5. Feature points: a convex ridge bends away from the outward normal in one direction more
  //    than in any other (k2 < -T and |k2| > |k1|); a concave valley bends toward it (k1 > T and
  //    k1 > |k2|). Property "feature": -1 ridge, +1 valley, 0 neither.
  const double T = threshold > 0. ? threshold : 1. / radius;
  Point_set::Property_map<double> feature = points.add_property_map<double>("feature", 0.).first;
  std::size_t ridges = 0, valleys = 0;
  for(Point_set::Index i : points)
  {
    if(k2[i] < -T && -k2[i] > std::abs(k1[i])) { feature[i] = -1.; ++ridges; }
    else if(k1[i] > T && k1[i] > std::abs(k2[i])) { feature[i] = 1.; ++valleys; }
  }
  std::cout << "Threshold T = " << T << ": " << ridges << " ridge points (blue), " << valleys
            << " valley points (red), of " << points.size() << std::endl;

  // 6. Colors: the mean curvature H on a diverging map, blue (H <= -T, convex) to white (0) to
  //    red (H >= T, concave); "red", "green", "blue" uchar properties are the PLY vertex colors.
  Point_set::Property_map<unsigned char> red = points.add_property_map<unsigned char>("red", 0).first;
  Point_set::Property_map<unsigned char> green = points.add_property_map<unsigned char>("green", 0).first;
  Point_set::Property_map<unsigned char> blue = points.add_property_map<unsigned char>("blue", 0).first;
  for(Point_set::Index i : points)
  {
    const double t = std::clamp(mean[i] / T, -1., 1.);
    const unsigned char fade = (unsigned char)(255. * (1. - std::abs(t)) + 0.5);
    red[i] = t < 0 ? fade : 255;
    green[i] = fade;
    blue[i] = t > 0 ? fade : 255;
  }

  // 7. Write all the points, then the feature points alone (a copy without the others).
  const std::string features_output = output.substr(0, output.rfind('.')) + "_only.ply";
  Point_set features = points; // a copy has the same indices, so the maps of `points` read it
  features.remove(std::partition(features.begin(), features.end(),
                                 [&](Point_set::Index i) { return feature[i] != 0.; }),
                  features.end());
  features.collect_garbage();
  if(!CGAL::IO::write_point_set(output, points, CGAL::parameters::use_binary_mode(true))
     || !CGAL::IO::write_point_set(features_output, features, CGAL::parameters::use_binary_mode(true)))
  {
    std::cerr << "Error: cannot write " << output << " or " << features_output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << " and " << features_output << " (" << features.size() << " points)" << std::endl;
  return report.number_of_unfitted_points == 0 && ridges + valleys > 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
