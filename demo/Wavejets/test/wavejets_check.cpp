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
//   wavejets_check faces IN OUT
//     IN and OUT (OFF, PLY or OBJ, read as polygon soups) have as many vertices and the same faces
//     (same vertex indices, same order); OUT has at least one face.
//   wavejets_check no_faces OUT     OUT (a PLY) has no face element.
//   wavejets_check along IN OUT FRACTION
//     at least FRACTION of the points that moved from IN to OUT moved along their normal in IN
//     (sine of the angle below 1e-6).
//   wavejets_check renderer         self-checks of the renderer on tiny scenes (triangles, splats).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Wavejets/internal/cgal_compatibility.h> // find_property_map: CGAL 5.5 and 6
#include <CGAL/Point_set_3/IO.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/IO/polygon_soup_io.h>

#include "render.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
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

// The renderer on tiny scenes, viewed along +z (default camera), 64 x 64 pixels.
static int renderer_checks()
{
  using wavejets_demo::Cloud;
  using wavejets_demo::Vec3;
  wavejets_demo::View_options view;
  view.width = view.height = 64;
  auto pixel = [](const wavejets_demo::Image& im, int x, int y) {
    const std::size_t i = (std::size_t(y) * im.width + x) * 3;
    return std::array<int, 3>{{im.rgb[i], im.rgb[i + 1], im.rgb[i + 2]}};
  };
  auto is_background = [](const std::array<int, 3>& c) {
    return c[0] == wavejets_demo::background[0] && c[1] == wavejets_demo::background[1] && c[2] == wavejets_demo::background[2];
  };
  // 1. A unit square of two triangles facing the camera covers the middle of the frame, without a
  //    crack along its diagonal.
  Cloud square;
  square.points = {{{0, 0, 0}}, {{1, 0, 0}}, {{1, 1, 0}}, {{0, 1, 0}}};
  square.normals.assign(4, Vec3{{0, 0, 1}});
  square.faces = {{0, 1, 2}, {0, 2, 3}};
  square.spacing = 1.;
  wavejets_demo::Image im = wavejets_demo::render({&square}, view);
  for(int y = 8; y < 56; ++y)
    for(int x = 8; x < 56; ++x)
      if(is_background(pixel(im, x, y))) return fail("triangles: background at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
  // 2. Z-buffer: a red square in front of it (nearer the camera, at z = 1) hides it; behind (z = -1), it is hidden.
  for(int back = 0; back < 2; ++back) {
    Cloud both = square;
    both.scalar.assign(8, 0.);   // white-ish
    for(int j = 0; j < 4; ++j) {
      Vec3 p = square.points[j];
      p[2] = back ? -1. : 1.;
      both.points.push_back(p);
      both.normals.push_back(Vec3{{0, 0, 1}});
      both.scalar[4 + j] = 1.;   // red
    }
    both.faces.push_back({4, 5, 6});
    both.faces.push_back({4, 6, 7});
    im = wavejets_demo::render({&both}, view);
    const std::array<int, 3> c = pixel(im, 32, 32);
    const bool reddish = c[0] > c[1] + 60;
    if(reddish == bool(back)) return fail(std::string("z-buffer: the ") + (back ? "hidden red square shows" : "front red square is hidden"));
  }
  // 3. Smooth shading: normals that turn across one triangle give varying shades inside it.
  Cloud bent = square;
  bent.normals = {{{-0.7, 0, 0.7}}, {{0.7, 0, 0.7}}, {{0.7, 0, 0.7}}, {{-0.7, 0, 0.7}}};
  im = wavejets_demo::render({&bent}, view);
  if(pixel(im, 12, 32) == pixel(im, 52, 32)) return fail("smooth shading: the same shade across the square");
  // 4. Splats: a point seen edge-on draws a thin ellipse, not a full disc sticking out of the silhouette.
  Cloud facing, edge_on;
  for(int i = 0; i < 3; ++i) {   // three points set the frame; the middle one is measured
    facing.points.push_back(Vec3{{double(i), 0., 0.}});
    facing.normals.push_back(Vec3{{0., 0., 1.}});
  }
  edge_on = facing;
  for(Vec3& n : edge_on.normals) n = Vec3{{0., 1., 0.}};
  facing.spacing = edge_on.spacing = 0.4;
  auto drawn = [&](const Cloud& c) {
    const wavejets_demo::Image image = wavejets_demo::render({&c}, view);
    std::size_t count = 0;
    for(int y = 0; y < image.height; ++y)
      for(int x = 24; x < 40; ++x) count += !is_background(pixel(image, x, y));
    return count;
  };
  const std::size_t round = drawn(facing), thin = drawn(edge_on);
  if(!(round > 0 && thin * 2 < round))
    return fail("splats: edge-on splat covers " + std::to_string(thin) + " pixels, facing " + std::to_string(round));
  std::cout << "OK: renderer (triangles cover, z-buffer, smooth shading, splat " << thin << " / " << round << " pixels)" << std::endl;
  return EXIT_SUCCESS;
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
  if(mode == "faces" && argc == 4) {
    std::vector<Kernel::Point_3> pa, pb;
    std::vector<std::vector<std::size_t> > fa, fb;
    if(!CGAL::IO::read_polygon_soup(argv[2], pa, fa)) return fail(std::string("cannot read ") + argv[2] + " as a polygon soup");
    if(!CGAL::IO::read_polygon_soup(argv[3], pb, fb)) return fail(std::string("cannot read ") + argv[3] + " as a polygon soup");
    if(pa.size() != pb.size()) return fail("vertex count " + std::to_string(pb.size()) + " != " + std::to_string(pa.size()));
    if(fb.empty()) return fail("no faces in the output");
    if(fa != fb) return fail("the faces differ (" + std::to_string(fa.size()) + " faces in, " + std::to_string(fb.size()) + " out)");
    std::cout << "OK: " << pb.size() << " vertices, the same " << fb.size() << " faces" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "no_faces" && argc == 3) {
    std::ifstream is(argv[2], std::ios::binary);
    std::string line;
    while(std::getline(is, line) && line.compare(0, 10, "end_header") != 0)
      if(line.compare(0, 12, "element face") == 0) return fail(std::string(argv[2]) + " has a face element");
    if(!is) return fail(std::string("no PLY header in ") + argv[2]);
    std::cout << "OK: no faces" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "along" && argc == 5) {
    Point_set in, out;
    if(!read(argv[2], in) || !read(argv[3], out) || in.size() != out.size()) return fail("cannot read the files or sizes differ");
    if(!in.has_normal_map()) return fail("IN has no normals");
    std::size_t moved = 0, along = 0;
    for(std::size_t i = 0; i < in.size(); ++i) {
      const Point_set::Index a = *(in.begin() + i), b = *(out.begin() + i);
      const Kernel::Vector_3 m = out.point(b) - in.point(a), n = in.normal(a);
      if(m == CGAL::NULL_VECTOR) continue;
      ++moved;
      const double sine = std::sqrt(CGAL::cross_product(m, n).squared_length() / (m.squared_length() * n.squared_length()));
      along += (sine < 1e-6);
    }
    const double fraction = moved ? double(along) / double(moved) : 0.;
    std::cout << along << " of the " << moved << " moved points moved along their input normal" << std::endl;
    if(moved == 0 || fraction < std::atof(argv[4])) return fail("fraction " + std::to_string(fraction));
    std::cout << "OK" << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "binary_ply" && argc == 6) {
    // IN's points (and normals) written to OUT as a binary PLY of TYPE (float, double or int: coordinates times
    // 1000) and ENDIANNESS (little, big), with a uchar column between the coordinates and the normals.
    Point_set in;
    if(!read(argv[2], in)) return fail(std::string("cannot read ") + argv[2]);
    const std::string type = argv[4], endianness = argv[5];
    if(type != "float" && type != "double" && type != "int") return fail("TYPE: float, double or int");
    if(endianness != "little" && endianness != "big") return fail("ENDIANNESS: little or big");
    std::ostringstream os;
    os << "ply\nformat binary_" << endianness << "_endian 1.0\nelement vertex " << in.size() << "\n";
    for(const char* name : {"x", "y", "z"}) os << "property " << type << " " << name << "\n";
    os << "property uchar red\n";
    if(in.has_normal_map())
      for(const char* name : {"nx", "ny", "nz"}) os << "property " << type << " " << name << "\n";
    os << "end_header\n";
    const std::uint16_t one = 1;
    const bool swap = (*reinterpret_cast<const unsigned char*>(&one) == 1) != (endianness == "little");
    auto put = [&](const void* value, std::size_t bytes) {
      char b[8];
      std::memcpy(b, value, bytes);
      if(swap) std::reverse(b, b + bytes);
      os.write(b, std::streamsize(bytes));
    };
    auto put_value = [&](double v) {
      if(type == "float") { const float f = float(v); put(&f, 4); }
      else if(type == "double") put(&v, 8);
      else { const std::int32_t i = std::int32_t(std::lround(v * 1000.)); put(&i, 4); }
    };
    for(Point_set::Index i : in) {
      const Kernel::Point_3& p = in.point(i);
      put_value(p.x()); put_value(p.y()); put_value(p.z());
      const unsigned char red = static_cast<unsigned char>(std::size_t(i) % 251);
      put(&red, 1);
      if(in.has_normal_map()) { const Kernel::Vector_3& n = in.normal(i); put_value(n.x()); put_value(n.y()); put_value(n.z()); }
    }
    std::ofstream out(argv[3], std::ios::binary);
    out << os.str();
    if(!out) return fail(std::string("cannot write ") + argv[3]);
    std::cout << "OK: wrote " << argv[3] << std::endl;
    return EXIT_SUCCESS;
  }
  if(mode == "renderer" && argc == 2) return renderer_checks();
  std::cerr << "usage: wavejets_check points IN OUT TOLERANCE [PROPERTY...] | same A B | agree A B F | motion IN OUT K LOW HIGH FRACTION | png FILE W H | faces IN OUT | no_faces OUT | binary_ply IN OUT float|double|int little|big | renderer" << std::endl;
  return 2;
}
