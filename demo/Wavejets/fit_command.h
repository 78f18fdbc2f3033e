// The computations of the `wavejets` tool's fitting commands (normals, curvature, enhance-positions,
// enhance-normals) on a Point_set: the whole point set (an in-core run, wavejets.cpp) or one tile of
// it (a streamed run, streaming.cpp). Both runs call these same functions, with the same named
// parameters, so that they write the same values; a tile only adds Wavejets::parameters::tile(),
// owned_map() and outside_map() (the `Tiling` argument).
#ifndef WAVEJETS_DEMO_FIT_COMMAND_H
#define WAVEJETS_DEMO_FIT_COMMAND_H

#include "point_set_io.h"

#include <CGAL/Wavejets/Processing_report.h>
#include <CGAL/Wavejets/Tile.h>
#include <CGAL/Wavejets/internal/cgal_compatibility.h> // find_property_map: CGAL 5.5 and 6
#include <CGAL/property_map.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <array>
#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace wavejets_demo {

typedef CGAL::Parallel_if_available_tag Concurrency_tag;
typedef std::function<bool(double)> Callback;

/// The tool's commands, as bits (the flags table says which flags apply to which commands).
enum Command_bit { NORMALS = 1, CURVATURE = 2, POSITIONS = 4, NORMAL_FILTER = 8, RENDER = 16 };
const unsigned FITS = NORMALS | CURVATURE | POSITIONS | NORMAL_FILTER;

/// What a fitting command computes, as chosen by its command line.
struct Fit_settings
{
  unsigned command = NORMALS;
  unsigned int k = 0;          // neighbors (with radius > 0: at most k in the radius, 0: no limit)
  double radius = 0.;
  std::size_t order = 2;
  std::complex<double> gain = CGAL::Wavejets::default_filter_gain;
  double evaluation_radius = 0.;
  bool has_clamp = false;
  double max_displacement = 0.;
  bool along_input_normals = false;
  bool consistent_normals = false;
  /// Orientation of estimated normals toward this point (no value: a minimum spanning tree, in core only).
  std::optional<std::array<double, 3> > viewpoint;
};

/// A bool property map (the functions' fitted, owned and outside maps) stored in a uchar property
/// (PLY has no bool), or writing nothing when it has none.
struct Uchar_bool_map
{
  typedef Point_set::Index key_type;
  typedef bool value_type;
  typedef bool reference;
  typedef boost::read_write_property_map_tag category;
  std::optional<Point_set::Property_map<unsigned char> > map;
  friend void put(const Uchar_bool_map& m, key_type k, bool v) { if(m.map) (*m.map)[k] = v ? 1 : 0; }
  friend bool get(const Uchar_bool_map& m, key_type k) { return m.map && (*m.map)[k] != 0; }
};

/// A direction written as three double properties (the PLY columns k1_dir_x, k1_dir_y, k1_dir_z).
struct Direction_columns_map
{
  typedef Point_set::Index key_type;
  typedef Vector value_type;
  typedef Vector reference;
  typedef boost::read_write_property_map_tag category;
  Point_set::Property_map<double> x, y, z;
  friend void put(const Direction_columns_map& m, key_type k, const Vector& v) { m.x[k] = v.x(); m.y[k] = v.y(); m.z[k] = v.z(); }
  friend Vector get(const Direction_columns_map& m, key_type k) { return Vector(m.x[k], m.y[k], m.z[k]); }
};

/// The properties a fitting command writes besides the points and normals, in the order of the
/// output's columns: fitted, then for curvature the names of `curvature_column_names()`.
struct Output_columns
{
  Point_set::Property_map<unsigned char> fitted;
  std::vector<Point_set::Property_map<double> > curvature;
};

/// mean_curvature, gaussian_curvature, k1, k2, quality, k1_dir_x/y/z, k2_dir_x/y/z.
const std::vector<std::string>& curvature_column_names();

/// Adds the output columns of `command` to `points`, zero (a property of the same name is reused
/// with its type changed to the output's), and a zero normal map when it has none (normals to be
/// estimated). Called in the same order on the whole point set or on each chunk of it, so that the
/// written PLY has the same header.
Output_columns add_output_columns(Point_set& points, unsigned command);

/// How a function call is told that it runs on one tile of a larger point set.
struct In_core
{
  template <class NP> const NP& operator()(const NP& np) const { return np; }
};
struct In_tile
{
  CGAL::Wavejets::Tile tile;
  Point_set::Property_map<unsigned char> owned, outside;
  template <class NP> auto operator()(const NP& np) const
  {
    namespace WP = CGAL::Wavejets::parameters;   // after CGAL's parameters: prepended
    return WP::outside_map(Uchar_bool_map{outside}, WP::owned_map(Uchar_bool_map{owned}, WP::tile(tile, np)));
  }
};

/// One value per point, by point index, or 0 for every point when it has none (0 stands for the
/// command's --k, --radius or --order).
template <class T>
struct Per_point_values
{
  typedef Point_set::Index key_type;
  typedef T value_type;
  typedef T reference;
  typedef boost::readable_property_map_tag category;
  std::shared_ptr<const std::vector<T> > values;
  friend T get(const Per_point_values& m, key_type i) { return m.values ? (*m.values)[std::size_t(i)] : T(0); }
};

/// Each point's own neighborhood (--k auto, or --k, --radius, --order given a column's name): its
/// number of neighbors, radius and order, passed to every function call (as a Tiling is).
struct Per_point_scales
{
  Per_point_values<unsigned int> k;
  Per_point_values<double> radius;
  Per_point_values<unsigned int> order;
  template <class NP> auto operator()(const NP& np) const
  {
    namespace WP = CGAL::Wavejets::parameters;   // after CGAL's parameters: prepended
    return WP::order_map(order, WP::neighbor_radius_map(radius, WP::neighborhood_size_map(k, np)));
  }
};
/// What --k auto chose: the sizes (`tiling()`) and a sentence for the summary.
struct Automatic_scales
{
  Per_point_scales sizes;
  std::string summary;
  const Per_point_scales& tiling() const { return sizes; }
};

/// The values of the numeric property `name` of `points` (any of the PLY types), by point index;
/// none if it has no such property.
std::optional<std::vector<double> > numeric_column(const Point_set& points, const std::string& name);
/// --k auto: `wavejet_estimate_scales()` at `order` with the default ladder, into the column scale_k
/// (and with `descriptor_columns`, the columns f2_k<N>: |f_2| at each size N of the ladder).
Automatic_scales estimate_scales(Point_set& points, std::size_t order, bool descriptor_columns, const Callback& cb);

namespace fit_detail {
template <class Extra>
auto fit_parameters(const Extra& extra, const Fit_settings& s, Point_set& points, const Callback& cb)
{
  return extra.neighbor_radius(s.radius).callback(cb).point_map(points.point_map()).normal_map(points.normal_map());
}
} // namespace fit_detail

/// Estimates the normals of a point set that has none (order `order`, writing `fitted` when it has
/// a map), oriented toward the viewpoint when the settings give one (else left to the caller).
template <class Tiling>
CGAL::Wavejets::Processing_report estimate_normals_of_bare_points(Point_set& points, const Fit_settings& s,
                                                                  std::size_t order, const Uchar_bool_map& fitted,
                                                                  const Callback& cb, const Tiling& tiling)
{
  namespace WP = CGAL::Wavejets::parameters;
  const CGAL::Wavejets::Processing_report r = CGAL::wavejet_estimate_normals<Concurrency_tag>(points, s.k,
    tiling(fit_detail::fit_parameters(WP::order(order).fitted_map(fitted), s, points, cb)));
  if(s.viewpoint) {
    const std::array<double, 3>& v = *s.viewpoint;
    for(Point_set::Index i : points) {
      const Point& p = points.point(i);
      Vector& n = points.normal(i);
      if(n.x() * (v[0] - p.x()) + n.y() * (v[1] - p.y()) + n.z() * (v[2] - p.z()) < 0) n = -n;
    }
  }
  return r;
}

/// The command itself, on points with oriented normals: writes the normals (and for
/// enhance-positions the positions), the fitted column and, for curvature, its columns.
template <class Tiling>
CGAL::Wavejets::Processing_report run_fit_command(Point_set& points, const Fit_settings& s, const Output_columns& c,
                                                  const Callback& cb, const Tiling& tiling)
{
  namespace WP = CGAL::Wavejets::parameters;
  const Uchar_bool_map fitted{c.fitted};
  if(s.command == NORMALS)
    return CGAL::wavejet_estimate_normals<Concurrency_tag>(points, s.k,
      tiling(fit_detail::fit_parameters(WP::order(s.order).orient_with_input_normals(true).fitted_map(fitted), s, points, cb)));
  if(s.command == CURVATURE) {
    const std::vector<Point_set::Property_map<double> >& m = c.curvature;
    const CGAL::Wavejets::Processing_report r = CGAL::wavejet_estimate_curvatures<Concurrency_tag>(points, s.k,
      tiling(fit_detail::fit_parameters(WP::order(s.order).mean_curvature_map(m[0]).gaussian_curvature_map(m[1])
                                          .maximal_principal_curvature_map(m[2]).minimal_principal_curvature_map(m[3])
                                          .maximal_principal_direction_map(Direction_columns_map{m[5], m[6], m[7]})
                                          .minimal_principal_direction_map(Direction_columns_map{m[8], m[9], m[10]})
                                          .fitted_map(fitted), s, points, cb)));
    for(Point_set::Index i : points) m[4][i] = m[0][i];   // quality = mean curvature (MeshLab's color by quality)
    return r;
  }
  if(s.command == POSITIONS) {
    const double gain = s.gain.real();
    auto enhance = [&](const auto& np) {
      return CGAL::wavejet_enhance_positions<Concurrency_tag>(points, s.k, gain,
               tiling(fit_detail::fit_parameters(np, s, points, cb)));
    };
    return s.has_clamp
      ? enhance(WP::maximum_displacement(s.max_displacement).order(s.order).evaluation_radius(s.evaluation_radius)
                  .move_along_input_normals(s.along_input_normals).restrict_to_consistent_normals(s.consistent_normals)
                  .write_normals(true).fitted_map(fitted))
      : enhance(WP::order(s.order).evaluation_radius(s.evaluation_radius).move_along_input_normals(s.along_input_normals)
                  .restrict_to_consistent_normals(s.consistent_normals).write_normals(true).fitted_map(fitted));
  }
  return CGAL::wavejet_enhance_normals<Concurrency_tag>(points, s.k, s.gain,
    tiling(fit_detail::fit_parameters(WP::order(s.order).evaluation_radius(s.evaluation_radius)
                                        .restrict_to_consistent_normals(s.consistent_normals).fitted_map(fitted),
                                      s, points, cb)));
}

/// enhance-positions on a point set: the normals of the moved points, fitted again (order 2) and
/// oriented like the normals the enhancement wrote.
template <class Tiling>
CGAL::Wavejets::Processing_report estimate_normals_of_result(Point_set& points, const Fit_settings& s, const Callback& cb,
                                                             const Tiling& tiling)
{
  namespace WP = CGAL::Wavejets::parameters;
  return CGAL::wavejet_estimate_normals<Concurrency_tag>(points, s.k,
    tiling(fit_detail::fit_parameters(WP::order(std::size_t(2)).orient_with_input_normals(true), s, points, cb)));
}

/// The report of a run, one phrase: "N points fitted, M not fitted (left unchanged), ...".
std::string report_text(const CGAL::Wavejets::Processing_report& r);

/// Adds the counts of `b` (a tile's report) to `a`.
void add_report(CGAL::Wavejets::Processing_report& a, const CGAL::Wavejets::Processing_report& b);

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_FIT_COMMAND_H
