// Checker of the `wavejets` CLI tests.
//   wavejets_check points IN OUT TOLERANCE [PROPERTY...]
//     OUT has as many points as IN, point i of OUT is within TOLERANCE of point i of IN (order
//     kept), OUT has normals and every PROPERTY (a double or uchar PLY property).
//   wavejets_check same OUT_A OUT_B     the two PLY files hold identical points and normals
//   wavejets_check agree A B FRACTION   at least FRACTION of the normals of A and B point to the same side
//   wavejets_check motion IN OUT K LOW HIGH FRACTION
//     with Rf_i the distance from point i of IN to its K-th nearest other point of IN (the
//     neighborhood radius of a fit on K nearest neighbors) and m_i the distance from point i of IN
//     to point i of OUT: at least one m_i > LOW x Rf_i, and at most FRACTION of the points have
//     m_i > HIGH x Rf_i (FRACTION 0: all within).
//   wavejets_check png FILE WIDTH HEIGHT
//     FILE is a WIDTH x HEIGHT PNG with at least 1% of its pixels not background.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Wavejets/internal/cgal_compatibility.h> // find_property_map: CGAL 5.5 and 6
#include <CGAL/Point_set_3/IO.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>

#include "render.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef CGAL::Point_set_3<Kernel::Point_3, Kernel::Vector_3> Point_set;

static int fail(const std::string& message)
{
  std::cerr << "FAIL: " << message << std::endl;
  return EXIT_FAILURE;
}

static bool read(const std::string& path, Point_set& points)
{
  return CGAL::IO::read_point_set(path, points) && !points.empty();
}

int main(int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if(mode == "points" && argc >= 5) {
    Point_set in, out;
    if(!read(argv[2], in)) return fail(std::string("cannot read ") + argv[2]);
    if(!read(argv[3], out)) return fail(std::string("cannot read ") + argv[3]);
    const double tolerance = std::atof(argv[4]);
    if(in.size() != out.size())
      return fail("point count " + std::to_string(out.size()) + " != input " + std::to_string(in.size()));
    if(!out.has_normal_map()) return fail("no normals in the output");
    const auto fitted = CGAL::Wavejets::internal::find_property_map<unsigned char>(out, "fitted");
    double worst = 0.;
    std::size_t nonunit = 0;
    for(std::size_t i = 0; i < in.size(); ++i) {
      const Point_set::Index a = *(in.begin() + i), b = *(out.begin() + i);
      worst = (std::max)(worst, std::sqrt(CGAL::squared_distance(in.point(a), out.point(b))));
      const bool new_normal = !fitted.second || fitted.first[b];   // unfitted points keep the input's
      if(new_normal && std::abs(out.normal(b).squared_length() - 1.) > 1e-6) ++nonunit;
    }
    if(!(worst <= tolerance))
      return fail("point moved by " + std::to_string(worst) + " > " + std::to_string(tolerance) + " (order lost?)");
    if(nonunit > 0) return fail(std::to_string(nonunit) + " new normals are not unit vectors");
    for(int p = 5; p < argc; ++p) {
      const bool as_double = CGAL::Wavejets::internal::find_property_map<double>(out, argv[p]).second;
      const bool as_uchar = CGAL::Wavejets::internal::find_property_map<unsigned char>(out, argv[p]).second;
      if(!as_double && !as_uchar) return fail(std::string("property ") + argv[p] + " missing");
    }
    std::cout << "OK: " << out.size() << " points in order (max motion " << worst << ")" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "same" && argc == 4) {
    Point_set a, b;
    if(!read(argv[2], a) || !read(argv[3], b)) return fail("cannot read the files");
    if(a.size() != b.size()) return fail("sizes differ");
    for(std::size_t i = 0; i < a.size(); ++i) {
      const Point_set::Index x = *(a.begin() + i), y = *(b.begin() + i);
      if(a.point(x) != b.point(y) || a.normal(x) != b.normal(y)) return fail("point " + std::to_string(i) + " differs");
    }
    std::cout << "OK: identical" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "agree" && argc == 5) {
    Point_set a, b;
    if(!read(argv[2], a) || !read(argv[3], b) || a.size() != b.size()) return fail("cannot read the files or sizes differ");
    if(!a.has_normal_map() || !b.has_normal_map()) return fail("no normals");
    std::size_t same = 0;
    for(std::size_t i = 0; i < a.size(); ++i)
      if(a.normal(*(a.begin() + i)) * b.normal(*(b.begin() + i)) > 0) ++same;
    const double fraction = double(same) / double(a.size());
    if(fraction < std::atof(argv[4])) return fail("only " + std::to_string(fraction) + " of the normals agree");
    std::cout << "OK: " << fraction << " of the normals agree" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "motion" && argc == 8) {
    Point_set in, out;
    if(!read(argv[2], in) || !read(argv[3], out) || in.size() != out.size())
      return fail("cannot read the files or sizes differ");
    const unsigned int k = unsigned(std::atoi(argv[4]));
    const double low = std::atof(argv[5]), high = std::atof(argv[6]), fraction = std::atof(argv[7]);
    typedef CGAL::Search_traits_3<Kernel> Traits;
    typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
    std::vector<Kernel::Point_3> points;
    for(Point_set::Index i : in) points.push_back(in.point(i));
    const Search::Tree tree(points.begin(), points.end());
    double worst = 0., largest = 0., largest_rf = 0.;
    std::size_t beyond_low = 0, beyond_high = 0;
    for(std::size_t i = 0; i < points.size(); ++i) {
      double rf = 0.;   // K + 1 nearest: the point itself, then its K nearest others
      for(const auto& neighbor : Search(tree, points[i], k + 1)) rf = (std::max)(rf, std::sqrt(neighbor.second));
      const double moved = std::sqrt(CGAL::squared_distance(points[i], out.point(*(out.begin() + i))));
      if(!(rf > 0)) return fail("point " + std::to_string(i) + " has no neighborhood radius");
      largest_rf = (std::max)(largest_rf, rf);
      worst = (std::max)(worst, moved / rf);
      largest = (std::max)(largest, moved);
      if(moved > low * rf) ++beyond_low;
      if(!(moved <= high * rf)) ++beyond_high;
    }
    std::cout << "max Rf " << largest_rf << ", max motion " << largest << ", max motion / Rf " << worst << ", " << beyond_low
              << " points moved by more than " << low << " Rf, " << beyond_high << " by more than " << high << " Rf"
              << std::endl;
    if(!(double(beyond_high) <= fraction * double(points.size())))
      return fail(std::to_string(beyond_high) + " points moved by more than " + std::to_string(high) + " Rf (allowed: " +
                  std::to_string(fraction * double(points.size())) + ")");
    if(beyond_low == 0) return fail("no point moved by more than " + std::to_string(low) + " Rf");
    std::cout << "OK" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "png" && argc == 5) {
    wavejets_demo::Image image;
    try {
      image = wavejets_demo::read_png(argv[2]);
    } catch(const std::exception& e) { return fail(e.what()); }
    if(image.width != std::atoi(argv[3]) || image.height != std::atoi(argv[4]))
      return fail("size " + std::to_string(image.width) + "x" + std::to_string(image.height));
    std::size_t drawn = 0;
    for(std::size_t i = 0; i < image.rgb.size(); i += 3)
      if(image.rgb[i] != wavejets_demo::background[0] || image.rgb[i + 1] != wavejets_demo::background[1] ||
         image.rgb[i + 2] != wavejets_demo::background[2]) ++drawn;
    const std::size_t pixels = std::size_t(image.width) * image.height;
    if(drawn * 100 < pixels) return fail("only " + std::to_string(drawn) + " pixels drawn");
    std::cout << "OK: " << image.width << "x" << image.height << ", " << drawn << " pixels drawn" << std::endl;
    return EXIT_SUCCESS;
  }
  std::cerr << "usage: wavejets_check points IN OUT TOLERANCE [PROPERTY...] | same A B | agree A B F | motion IN OUT K LOW HIGH FRACTION | png FILE W H" << std::endl;
  return 2;
}
