// See fit_command.h.
#include "fit_command.h"

#include <CGAL/wavejet_estimate_scales.h>

#include <map>

namespace wavejets_demo {

namespace {

// Removes a property of our output names that the input may carry with another type.
void drop_property(Point_set& points, const std::string& name)
{
  bool found;
  Point_set::Property_map<float> f;
  std::tie(f, found) = CGAL::Wavejets::internal::find_property_map<float>(points, name);
  if(found) points.remove_property_map(f);
  Point_set::Property_map<int> i;
  std::tie(i, found) = CGAL::Wavejets::internal::find_property_map<int>(points, name);
  if(found) points.remove_property_map(i);
}

// A zero property named `name` of type T (one of the input's, of another type, is replaced).
template <class T>
Point_set::Property_map<T> zero_column(Point_set& points, const std::string& name)
{
  drop_property(points, name);
  Point_set::Property_map<T> m = points.template add_property_map<T>(name, T(0)).first;
  for(Point_set::Index i : points) m[i] = T(0);
  return m;
}

} // namespace

const std::vector<std::string>& curvature_column_names()
{
  static const std::vector<std::string> names = {"mean_curvature", "gaussian_curvature", "k1", "k2", "quality",
                                                 "k1_dir_x", "k1_dir_y", "k1_dir_z", "k2_dir_x", "k2_dir_y", "k2_dir_z"};
  return names;
}

Output_columns add_output_columns(Point_set& points, unsigned command)
{
  Output_columns c;
  c.fitted = zero_column<unsigned char>(points, "fitted");
  if(!points.has_normal_map()) points.add_normal_map(Vector(0, 0, 0));
  if(command == CURVATURE)
    for(const std::string& name : curvature_column_names()) c.curvature.push_back(zero_column<double>(points, name));
  return c;
}

namespace {
/// The descriptor of wavejet_estimate_scales() into one double column per size of the ladder.
struct Descriptor_columns_map
{
  typedef Point_set::Index key_type;
  typedef std::vector<double> value_type;
  typedef std::vector<double> reference;
  typedef boost::writable_property_map_tag category;
  std::vector<Point_set::Property_map<double> > columns;
  friend void put(const Descriptor_columns_map& m, key_type k, const std::vector<double>& v)
  {
    for(std::size_t j = 0; j < m.columns.size(); ++j) m.columns[j][k] = v[j];
  }
};
} // namespace

Automatic_scales estimate_scales(Point_set& points, std::size_t order, bool descriptor_columns, const Callback& cb)
{
  namespace WP = CGAL::Wavejets::parameters;
  const std::vector<unsigned int> ladder = CGAL::Wavejets::default_neighborhood_sizes(order);
  Automatic_scales a;
  const Point_set::Property_map<int> scale_k = zero_column<int>(points, "scale_k");
  Descriptor_columns_map descriptor; // no column: nothing written
  if(descriptor_columns)
    for(unsigned int k : ladder) descriptor.columns.push_back(zero_column<double>(points, "f2_k" + std::to_string(k)));
  const CGAL::Wavejets::Processing_report r = CGAL::wavejet_estimate_scales<Concurrency_tag>(points,
    WP::order(order).neighborhood_size_map(scale_k).neighborhood_sizes(ladder).scale_descriptor_map(descriptor)
      .callback(cb).point_map(points.point_map()));
  // The share of the fitted points at each size (an unfitted point keeps scale_k 0, and each function
  // then fits it at the largest size).
  std::map<int, std::size_t> count;
  auto k = std::make_shared<std::vector<unsigned int> >(points.size(), 0u);
  for(Point_set::Index i : points)
  {
    ++count[scale_k[i]];
    (*k)[std::size_t(i)] = unsigned(scale_k[i]);
  }
  a.sizes.k.values = k;
  a.summary = "Scales chosen per point (order " + std::to_string(order) + "; " + std::to_string(r.number_of_unfitted_points) +
              " without one, fitted at " + std::to_string(ladder.back()) + " neighbors):";
  for(unsigned int k : ladder)
  {
    const double share = r.number_of_points ? 100. * double(count[int(k)]) / double(r.number_of_points) : 0.;
    a.summary += " " + std::to_string(k) + ": " + std::to_string(int(std::lround(share))) + "%";
    if(k != ladder.back()) a.summary += ",";
  }
  a.summary += ".";
  return a;
}

namespace {
template <class T>
bool copy_column(const Point_set& points, const std::string& name, std::vector<double>& out)
{
  bool found;
  Point_set::Property_map<T> m;
  std::tie(m, found) = CGAL::Wavejets::internal::find_property_map<T>(points, name);
  if(!found) return false;
  out.assign(points.size(), 0.);
  for(Point_set::Index i : points) out[std::size_t(i)] = double(m[i]);
  return true;
}
} // namespace

std::optional<std::vector<double> > numeric_column(const Point_set& points, const std::string& name)
{
  std::vector<double> v;
  if(copy_column<double>(points, name, v) || copy_column<float>(points, name, v) || copy_column<int>(points, name, v) ||
     copy_column<unsigned int>(points, name, v) || copy_column<short>(points, name, v) ||
     copy_column<unsigned short>(points, name, v) || copy_column<signed char>(points, name, v) ||
     copy_column<unsigned char>(points, name, v))
    return v;
  return std::nullopt;
}

std::string report_text(const CGAL::Wavejets::Processing_report& r)
{
  std::string s = std::to_string(r.number_of_fitted_points) + " points fitted, " +
                  std::to_string(r.number_of_unfitted_points) + " not fitted (left unchanged), " +
                  std::to_string(r.number_of_reduced_order_points) + " at reduced order";
  if(r.moves_points) s += ", " + std::to_string(r.number_of_clamped_points) + " displacements clamped";
  return s;
}

void add_report(CGAL::Wavejets::Processing_report& a, const CGAL::Wavejets::Processing_report& b)
{
  a.number_of_fitted_points += b.number_of_fitted_points;
  a.number_of_unfitted_points += b.number_of_unfitted_points;
  a.number_of_non_finite_points += b.number_of_non_finite_points;
  a.number_of_reduced_order_points += b.number_of_reduced_order_points;
  a.number_of_clamped_points += b.number_of_clamped_points;
  a.number_of_outside_points += b.number_of_outside_points;
  a.moves_points = a.moves_points || b.moves_points;
  a.interrupted = a.interrupted || b.interrupted;
}

} // namespace wavejets_demo
