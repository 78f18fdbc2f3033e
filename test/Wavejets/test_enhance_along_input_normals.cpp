// Tests of wavejet_enhance_positions' named parameter move_along_input_normals (the paper's
// Figure 12 pipeline: normals filtered first, positions moved along them).
//
// Surface: the plane z = A sin(2 pi x / lambda) (lambda = 4 Rf), jittered grid, with and without
// white noise along z. Every check is an explicit `if` that counts failures; each group prints
// its measured numbers.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wavejets_test_support.h"
#include "wavejets_test_types.h"

using namespace wavejets_test;
using namespace wavejets_test::types;
namespace WJP = CGAL::Wavejets::parameters;

static const double PI = 3.14159265358979323846;

static std::string fmt(double x) { return significant_digits(x, 3); }

// n x n jittered grid of spacing h on z = A sin(2 pi x / lambda) + noise, with exact unit normals
// of the sinusoid (upward).
static PV_range sinusoid(std::size_t n, double h, double A, double lambda, double noise, std::uint64_t seed)
{
  Gauss g(seed);
  PV_range pts;
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = 0; j < n; ++j)
    {
      const double x = (double(i) + 0.3 * (g.uniform() - 0.5)) * h, y = (double(j) + 0.3 * (g.uniform() - 0.5)) * h;
      const double w = 2. * PI / lambda;
      const double z = A * std::sin(w * x) + noise * g();
      const double dz = A * w * std::cos(w * x);
      pts.emplace_back(Point(x, y, z), Vector(-dz, 0., 1.) / std::sqrt(1. + dz * dz));
    }
  return pts;
}

// Runs the position filter; `along`: move_along_input_normals.
template <class Tag>
static PV_range enhance(PV_range pts, double gain, bool along, unsigned int k = 40)
{
  CGAL::wavejet_enhance_positions<Tag>(pts, k, gain,
    WJP::order(4).move_along_input_normals(along).point_map(Point_map()).normal_map(Normal_map()));
  return pts;
}

static Vector motion(const PV_range& a, const PV_range& b, std::size_t i) { return b[i].first - a[i].first; }
static double length(const Vector& v) { return std::sqrt(v.squared_length()); }

// The sinusoid of every case: n x n points of spacing h, k neighbors; Rf of 40 neighbors on this
// grid: about sqrt(40 / pi) h = 3.6 h.
static const std::size_t n = 60;
static const double h = 0.01;
static const unsigned int k = 40;
static const double Rf = std::sqrt(double(k) / PI) * h, lambda = 4. * Rf, A = 0.1 * Rf;

// 1. Input normals equal to the Wavejet normals: same result as the default mode. The Wavejet
//    normals come from write_normals (the fitted surface's normal, which differs from the frame
//    normal the default mode moves along by the residual tilt f_{1,1}, ~1e-6 rad after the
//    tangent-plane search): the deviation is |d| times that angle.
static void test_input_normals_equal_wavejet_normals()
{
  const PV_range in = sinusoid(n, h, A, lambda, 0., 1);
  PV_range wj = in;
  CGAL::wavejet_enhance_positions<Seq>(wj, k, 1., WJP::order(4).write_normals(true)
                                                   .point_map(Point_map()).normal_map(Normal_map()));
  PV_range with_wj = in;
  for(std::size_t i = 0; i < in.size(); ++i) with_wj[i].second = wj[i].second;
  const PV_range def = enhance<Seq>(with_wj, 2., false), along = enhance<Seq>(with_wj, 2., true);
  double worst = 0., dmax = 0.;
  for(std::size_t i = 0; i < in.size(); ++i)
  {
    worst = (std::max)(worst, length(along[i].first - def[i].first));
    dmax = (std::max)(dmax, length(motion(in, def, i)));
  }
  report("1. input normals = Wavejet normals: same as the default mode (gain 2, K 4, k 40)",
         dmax > 0.5 * A && worst <= 1e-4 * dmax,
         "max |p_along - p_default| = " + fmt(worst) + " = " + fmt(worst / dmax) +
         " x max motion " + fmt(dmax) + " (<= 1e-4)");
}

// 2. Arbitrary input normals (the exact normals tilted by 25 degrees about a random axis, random
//    lengths in [0.5, 3], every third one flipped): each point moves exactly along its input
//    normal, by the default mode's distance, to the same side; flipping normals changes nothing.
static void test_motion_along_arbitrary_normals()
{
  PV_range in = sinusoid(n, h, A, lambda, 0., 2);
  Gauss g(7);
  for(std::size_t i = 0; i < in.size(); ++i)
  {
    const Vector nz = in[i].second;
    Vector axis(g(), g(), g());
    axis = axis - (axis * nz) * nz;
    axis = axis / length(axis);
    const double t = 25. * PI / 180.;
    const Vector tilted = std::cos(t) * nz + std::sin(t) * CGAL::cross_product(axis, nz);
    const double scale = (0.5 + 2.5 * g.uniform()) * (i % 3 == 0 ? -1. : 1.);
    in[i].second = scale * tilted;
  }
  PV_range flipped = in;
  for(PV& p : flipped) p.second = -p.second;
  const PV_range def = enhance<Seq>(in, 2., false), along = enhance<Seq>(in, 2., true),
                 along_flipped = enhance<Seq>(flipped, 2., true);
  // Motion is measured as p' - p: its direction is known to a few ulp of the coordinates (<= 0.6).
  const double ulp = 0.6 * std::numeric_limits<double>::epsilon();
  double off_line = 0., length_worst = 0., flip_worst = 0., dmax = 0.;
  std::size_t opposite = 0;
  for(std::size_t i = 0; i < in.size(); ++i)
  {
    const Vector md = motion(in, def, i), ma = motion(in, along, i), m = in[i].second;
    const double la = length(ma), ld = length(md);
    dmax = (std::max)(dmax, ld);
    off_line = (std::max)(off_line, length(CGAL::cross_product(ma, m)) / length(m));
    length_worst = (std::max)(length_worst, std::abs(la - ld));
    if(ma * md < 0) ++opposite;
    flip_worst = (std::max)(flip_worst, length(along_flipped[i].first - along[i].first));
  }
  report("2. normals tilted 25 deg, random lengths and signs: motion along them, default distance",
         dmax > 0.5 * A && off_line <= 8. * ulp && length_worst <= 8. * ulp && opposite == 0 &&
           flip_worst <= 1e-12 * dmax,
         "max distance of p' from the line p + t m = " + fmt(off_line) + " (8 ulp: " + fmt(8. * ulp) +
         "), max ||motion| - |default motion|| = " +
         fmt(length_worst) + ", opposite sides " + std::to_string(opposite) +
         ", max change when all m flipped = " + fmt(flip_worst) + " (max motion " + fmt(dmax) + ")");
}

// 3. A zero or NaN input normal: that point moves along its Wavejet normal, as in the default mode.
static void test_zero_or_nan_normal()
{
  PV_range in = sinusoid(n, h, A, lambda, 0., 3);
  const std::size_t z = in.size() / 2 + n / 2, nan = z + 1;
  in[z].second = Vector(0., 0., 0.);
  in[nan].second = Vector(std::numeric_limits<double>::quiet_NaN(), 0., 1.);
  const PV_range def = enhance<Seq>(in, 2., false), along = enhance<Seq>(in, 2., true);
  const double dz = length(along[z].first - def[z].first), dn = length(along[nan].first - def[nan].first);
  bool finite = true;
  for(const PV& p : along) finite = finite && std::isfinite(p.first.x()) && std::isfinite(p.first.y()) && std::isfinite(p.first.z());
  report("3. zero / NaN input normal: moves along the Wavejet normal",
         dz == 0. && dn == 0. && finite && length(motion(in, def, z)) > 0.,
         "|p_along - p_default| = " + fmt(dz) + " (zero normal), " + fmt(dn) + " (NaN normal)");
}

// 4. No normal map: std::invalid_argument naming the parameter, nothing written.
static void test_no_normal_map_rejected()
{
  CGAL::Point_set_3<Point> ps;
  for(const PV& p : sinusoid(20, h, A, lambda, 0., 4)) ps.insert(p.first);
  const Point before = ps.point(*ps.begin());
  std::string what;
  try { CGAL::wavejet_enhance_positions<Seq>(ps, 20, 2., WJP::move_along_input_normals(true)); }
  catch(const std::invalid_argument& e) { what = e.what(); }
  std::vector<Point> plain;
  for(const PV& p : sinusoid(20, h, A, lambda, 0., 4)) plain.push_back(p.first);
  std::string what_plain;
  try { CGAL::wavejet_enhance_positions<Seq>(plain, 20, 2., WJP::move_along_input_normals(true)); }
  catch(const std::invalid_argument& e) { what_plain = e.what(); }
  bool plain_ok = true; // without the parameter the same call works
  try { CGAL::wavejet_enhance_positions<Seq>(plain, 20, 2., WJP::move_along_input_normals(false)); }
  catch(const std::exception&) { plain_ok = false; }
  report("4. no normal map: std::invalid_argument",
         what.find("move_along_input_normals") != std::string::npos &&
           what_plain.find("move_along_input_normals") != std::string::npos && plain_ok &&
           ps.point(*ps.begin()) == before,
         "Point_set_3: \"" + what + "\"; std::vector<Point_3>: \"" + what_plain + "\"");
}

// 5. Sequential_tag and Parallel_tag: bitwise identical (noisy input, normals from the normal filter).
static void test_sequential_equals_parallel()
{
  PV_range in = sinusoid(n, h, A, lambda, 0.1 * A, 5);
  CGAL::wavejet_enhance_normals<Seq>(in, k, 0., WJP::order(4).point_map(Point_map()).normal_map(Normal_map()));
  const PV_range s = enhance<Seq>(in, 2., true), p = enhance<Par>(in, 2., true);
  report("5. Sequential_tag == Parallel_tag, bitwise", same_bits(s, p), std::to_string(in.size()) + " points");
}

// 6. Figure 12 pipeline on a noisy sinusoid (noise sigma = A / 2): the normals filtered at gain 0
//    give a more stable motion direction than the Wavejet normals of the default mode. The
//    sinusoid runs along x, so every smoothing of its normals has no y component: the RMS y
//    component of the unit motion direction measures the noise of the direction alone (the
//    x component also holds the detail's tilt, which the gain-0 filter blurs on purpose). Interior
//    points only (at the border both directions tilt away from the missing side).
static void test_figure12_pipeline_steadier_direction()
{
  const PV_range in = sinusoid(n, h, A, lambda, 0.5 * A, 6);
  PV_range filtered = in;
  CGAL::wavejet_enhance_normals<Seq>(filtered, k, 0., WJP::order(4).point_map(Point_map()).normal_map(Normal_map()));
  const PV_range def = enhance<Seq>(in, 2., false), along = enhance<Seq>(filtered, 2., true);
  double y_def = 0., y_along = 0.;
  std::size_t count = 0;
  const double lo = 1.5 * Rf, hi = double(n - 1) * h - 1.5 * Rf; // interior: full neighborhoods
  for(std::size_t i = 0; i < in.size(); ++i)
  {
    const Point& q = in[i].first;
    if(q.x() < lo || q.x() > hi || q.y() < lo || q.y() > hi) continue;
    const Vector md = motion(in, def, i), ma = motion(in, along, i);
    if(length(md) < 1e-3 * A || length(ma) < 1e-3 * A) continue; // direction not resolved
    y_def += CGAL::square(md.y() / length(md));
    y_along += CGAL::square(ma.y() / length(ma));
    ++count;
  }
  y_def = std::sqrt(y_def / double(count));
  y_along = std::sqrt(y_along / double(count));
  report("6. Figure 12 pipeline (noise A/2): steadier motion direction",
         count > in.size() / 4 && y_along < 0.75 * y_def,
         "RMS off-pattern (y) component of the motion direction: " + fmt(y_along) +
         " (filtered normals) vs " + fmt(y_def) + " (Wavejet normals, default mode), " +
         std::to_string(count) + " points");
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"along_input_normals.input_normals_equal_wavejet_normals", test_input_normals_equal_wavejet_normals},
    Case{"along_input_normals.motion_along_arbitrary_normals", test_motion_along_arbitrary_normals},
    Case{"along_input_normals.zero_or_nan_normal", test_zero_or_nan_normal},
    Case{"along_input_normals.no_normal_map_rejected", test_no_normal_map_rejected},
    Case{"along_input_normals.sequential_equals_parallel", test_sequential_equals_parallel},
    Case{"along_input_normals.figure12_pipeline_steadier_direction", test_figure12_pipeline_steadier_direction},
  });
}
