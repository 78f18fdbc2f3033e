// Fits one Wavejet with CGAL::Wavejet_fitting, the counterpart of Monge_via_jet_fitting:
// the first point of the range is where the Wavejet is computed, the others are its neighbors.
// Usage: wavejet_fitting_example [points.xyz] [order]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Wavejet_fitting.h>

#include <cstdlib>
#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Search_traits_3<Kernel> Traits;
typedef CGAL::Orthogonal_k_neighbor_search<Traits> Knn;

int main(int argc, char** argv)
{
  const std::string fname = argc > 1 ? argv[1] : "data/kitten.xyz";
  const std::size_t order = argc > 2 ? std::size_t(std::atoi(argv[2])) : 4;
  std::vector<Point> points;
  if(!CGAL::IO::read_points(fname, std::back_inserter(points)) || points.empty())
  {
    std::cerr << "Error: cannot read points from " << fname << std::endl;
    return EXIT_FAILURE;
  }

  // The 40 nearest neighbors of the first point, query point first.
  Knn::Tree tree(points.begin(), points.end());
  Knn search(tree, points[0], 41);
  std::vector<Point> neighborhood(1, points[0]);
  for(const auto& hit : search)
    if(hit.first != points[0]) neighborhood.push_back(hit.first);

  CGAL::Wavejet_fitting<Kernel> fitting; // default options: PCA frame, 2 tangent-plane re-fits
  CGAL::Wavejet_fitting<Kernel>::Wavejet_form form = fitting(neighborhood.begin(), neighborhood.end(), order);
  if(!form.is_valid())
  {
    std::cerr << "Error: no Wavejet at this point: " << CGAL::Wavejets::fit_status_name(form.status()) << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << form;
  std::cout << "a_0(Rf) = " << form.enclosed_area_coefficient(0) << ", condition number "
            << fitting.condition_number() << std::endl;
  return EXIT_SUCCESS;
}
