// Built against an installed CGAL Wavejets by the test wavejets_install_and_consume: estimates the
// normals of a small sphere sample with wavejet_estimate_normals (Parallel_if_available_tag) and
// checks them against the exact normals; prints the package version.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Wavejets/version.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <utility>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef std::pair<K::Point_3, K::Vector_3> Point_with_normal;

int main()
{
  // A Fibonacci sphere of radius 1.
  std::vector<Point_with_normal> points;
  const int n = 2000;
  const double golden = 3.14159265358979323846 * (3. - std::sqrt(5.));
  for(int i = 0; i < n; ++i)
  {
    const double z = 1. - 2. * (i + 0.5) / n, r = std::sqrt(1. - z * z), t = golden * i;
    points.emplace_back(K::Point_3(r * std::cos(t), r * std::sin(t), z), K::Vector_3(0, 0, 0));
  }
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_estimate_normals<CGAL::Parallel_if_available_tag>(
    points, 18, CGAL::parameters::point_map(CGAL::First_of_pair_property_map<Point_with_normal>())
                  .normal_map(CGAL::Second_of_pair_property_map<Point_with_normal>()));
  double worst = 0.;
  for(const Point_with_normal& p : points)
  {
    const K::Vector_3 exact = p.first - CGAL::ORIGIN;
    worst = (std::max)(worst, 1. - std::abs(p.second * exact) / std::sqrt(p.second.squared_length()));
  }
  std::cout << "CGAL Wavejets " << CGAL_WAVEJETS_VERSION_STR << ": " << report.number_of_fitted_points << " of "
            << points.size() << " normals fitted, worst 1 - |cos| = " << worst << std::endl;
  return report.number_of_fitted_points == points.size() && worst < 1e-6 ? EXIT_SUCCESS : EXIT_FAILURE;
}
