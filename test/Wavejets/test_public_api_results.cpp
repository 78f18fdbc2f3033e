// Includes every public header and calls every public function (Wavejet_fitting and the four
// point-set functions, with the named parameters that change the computation), compiled with the
// project's warnings as errors. Writes every result, one labelled record a line with %.17g
// values, to $WAVEJETS_OUTPUT_DIR/public_api_results.txt (default: the working directory).
// When $WAVEJETS_REFERENCE_RESULTS names such a file from another build (another compiler, another
// CGAL release), every record must agree with it to 1e-12 relative to the record's largest value:
// scripts/test.sh compares the clang + CGAL 6.1 leg with the g++ + CGAL 5.5 leg this way.
// It also checks the contracts of the public API that no record shows (contracts()): the error
// model (which bad argument throws what), Processing_report::moves_points, and that the functions'
// defaults are those of function_defaults().
// Run from test/Wavejets (reads data/kitten.xyz).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>
#include <CGAL/version.h>

#include <CGAL/Wavejet_fitting.h>
#include <CGAL/Wavejets/Fitting_options.h>
#include <CGAL/Wavejets/Function_defaults.h>
#include <CGAL/Wavejets/Processing_report.h>
#include <CGAL/Wavejets/parameters.h>
#include <CGAL/Wavejets/version.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_scales.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wavejets_test_support.h"
#include "wavejets_test_types.h"

using namespace wavejets_test::types;
namespace WJP = CGAL::Wavejets::parameters;

/// Labelled records of doubles, written as text.
class Records
{
public:
  void add(const std::string& label, const std::vector<double>& values) { m_records.emplace_back(label, values); }
  void add_points(const std::string& label, const std::vector<PV>& points, bool normals)
  {
    for(std::size_t i = 0; i < points.size(); ++i)
    {
      const Point& p = points[i].first;
      const Vector& n = points[i].second;
      std::vector<double> v{p.x(), p.y(), p.z()};
      if(normals) v.insert(v.end(), {n.x(), n.y(), n.z()});
      add(label + "[" + std::to_string(i) + "]", v);
    }
  }
  void write(std::ostream& os) const
  {
    char buffer[32];
    for(const auto& r : m_records)
    {
      os << r.first;
      for(double x : r.second)
      {
        std::snprintf(buffer, sizeof buffer, " %.17g", x);
        os << buffer;
      }
      os << "\n";
    }
  }
  static std::map<std::string, std::vector<double> > read(std::istream& is)
  {
    std::map<std::string, std::vector<double> > records;
    std::string line;
    while(std::getline(is, line))
    {
      std::istringstream ls(line);
      std::string label;
      ls >> label;
      std::vector<double> values;
      std::string word;
      while(ls >> word) values.push_back(std::strtod(word.c_str(), nullptr));
      records[label] = values;
    }
    return records;
  }
  const std::vector<std::pair<std::string, std::vector<double> > >& records() const { return m_records; }

private:
  std::vector<std::pair<std::string, std::vector<double> > > m_records;
};

static void fit_one_point(const std::vector<PV>& input, Records& out)
{
  typedef CGAL::Wavejet_fitting<Kernel> Fitting;
  // The 60 nearest points to the point 100 (brute force; ties by index), the query first.
  std::vector<std::pair<double, std::size_t> > by_distance;
  for(std::size_t i = 0; i < input.size(); ++i)
    by_distance.emplace_back(CGAL::squared_distance(input[i].first, input[100].first), i);
  std::sort(by_distance.begin(), by_distance.end());
  std::vector<Point> neighborhood;
  std::vector<Vector> normals;
  for(std::size_t j = 0; j < 61; ++j)
  {
    neighborhood.push_back(input[by_distance[j].second].first);
    normals.push_back(input[by_distance[j].second].second);
  }
  {
    // The Hermite fit (heights and the neighbors' normals).
    Fitting fitting;
    const Fitting::Wavejet_form form = fitting(neighborhood.begin(), neighborhood.end(), normals.begin(), 4);
    const Vector n = form.normal_direction();
    out.add("fitting_hermite_K4", {double(int(form.status())), double(form.order()), n.x(), n.y(), n.z(),
                                   form.mean_curvature(), form.gaussian_curvature()});
    out.add("fitting_hermite_K4_coefficients", form.coefficients());
  }

  for(std::size_t order : {2, 4, 6})
  {
    Fitting fitting;
    const Fitting::Wavejet_form form = fitting(neighborhood.begin(), neighborhood.end(), order);
    const std::string label = "fitting_K" + std::to_string(order);
    const Vector n = form.normal_direction(), d1 = form.maximal_principal_direction();
    out.add(label + "_status", {double(int(form.status())), double(form.order()), form.radius(),
                                double(form.number_of_points()), double(form.number_of_corrections())});
    out.add(label + "_normal", {n.x(), n.y(), n.z()});
    out.add(label + "_curvatures", {form.mean_curvature(), form.gaussian_curvature(), form.principal_curvatures(0),
                                    form.principal_curvatures(1)});
    out.add(label + "_direction", {d1.x(), d1.y(), d1.z()});
    out.add(label + "_coefficients", form.coefficients());
    const std::complex<double> a0 = form.enclosed_area_coefficient(0), a2 = form.enclosed_area_coefficient(2, 0.5 * form.radius());
    out.add(label + "_enclosed_area", {a0.real(), a0.imag(), a2.real(), a2.imag()});
    const std::complex<double> f31 = form.coefficient(3 < order ? 3 : 1, 1);
    out.add(label + "_coefficient", {f31.real(), f31.imag(), fitting.condition_number()});
  }
}

static void report(const std::string& label, const CGAL::Wavejets::Processing_report& r, Records& out)
{
  out.add(label + "_report", {double(r.number_of_points), double(r.number_of_fitted_points),
                              double(r.number_of_unfitted_points), double(r.number_of_reduced_order_points),
                              double(r.number_of_clamped_points), double(r.interrupted)});
  std::ostringstream text;
  text << r; // operator<< is public API too
  if(text.str().empty()) std::exit(EXIT_FAILURE);
}

static void point_set_functions(const std::vector<PV>& input, Records& out)
{
  const auto pm = CGAL::parameters::point_map(Point_map()).normal_map(Normal_map());
  {
    std::vector<PV> points = input;
    report("estimate_normals_K4", CGAL::wavejet_estimate_normals<Seq>(points, 24, WJP::order(4, pm)), out);
    out.add_points("estimate_normals_K4", points, true);
  }
  {
    std::vector<PV> points = input;
    report("estimate_normals_robust", CGAL::wavejet_estimate_normals<Seq>(points, 30,
             WJP::robust_iterations(3).orient_with_input_normals(true).neighbor_radius(0.05).point_map(Point_map())
               .normal_map(Normal_map())), out);
    out.add_points("estimate_normals_robust", points, true);
  }
  {
    std::vector<PV> points = input;
    std::vector<double> h(points.size()), kg(points.size()), k1(points.size()), k2(points.size());
    std::vector<Vector> d1(points.size()), d2(points.size());
    std::vector<std::size_t> index(points.size());
    for(std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    std::vector<Point> positions;
    for(const PV& p : input) positions.push_back(p.first);
    report("estimate_curvatures", CGAL::wavejet_estimate_curvatures<Seq>(index, 30,
             WJP::mean_curvature_map(CGAL::make_property_map(h)).gaussian_curvature_map(CGAL::make_property_map(kg))
               .maximal_principal_curvature_map(CGAL::make_property_map(k1))
               .minimal_principal_curvature_map(CGAL::make_property_map(k2))
               .maximal_principal_direction_map(CGAL::make_property_map(d1))
               .minimal_principal_direction_map(CGAL::make_property_map(d2))
               .curvature_frame(CGAL::Wavejets::Curvature_frame::TANGENT_FRAME).order(3)
               .point_map(CGAL::make_property_map(positions))), out);
    for(std::size_t i = 0; i < index.size(); ++i)
      out.add("estimate_curvatures[" + std::to_string(i) + "]",
              {h[i], kg[i], k1[i], k2[i], d1[i].x(), d1[i].y(), d1[i].z(), d2[i].x(), d2[i].y(), d2[i].z()});
  }
  {
    std::vector<PV> points = input;
    report("enhance_positions", CGAL::wavejet_enhance_positions<Seq>(points, 40, 2.,
             WJP::order(4).write_normals(true).evaluation_radius(0.03).point_map(Point_map()).normal_map(Normal_map())), out);
    out.add_points("enhance_positions", points, true);
  }
  {
    // The Hermite curvatures, with the normals estimated first (no normal map given).
    std::vector<Point> positions;
    for(const PV& p : input) positions.push_back(p.first);
    std::vector<double> h(positions.size()), k1(positions.size()), k2(positions.size());
    std::vector<std::size_t> index(positions.size());
    for(std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    report("estimate_curvatures_hermite", CGAL::wavejet_estimate_curvatures<Seq>(index, 30,
             WJP::mean_curvature_map(CGAL::make_property_map(h)).maximal_principal_curvature_map(CGAL::make_property_map(k1))
               .minimal_principal_curvature_map(CGAL::make_property_map(k2)).use_neighbor_normals(true)
               .point_map(CGAL::make_property_map(positions))), out);
    for(std::size_t i = 0; i < index.size(); ++i)
      out.add("estimate_curvatures_hermite[" + std::to_string(i) + "]", {h[i], k1[i], k2[i]});
  }
  {
    // Positions moved along the input normals (the paper's Figure 12 pipeline).
    std::vector<PV> points = input;
    report("enhance_positions_along_input_normals", CGAL::wavejet_enhance_positions<Seq>(points, 40, 2.,
             WJP::move_along_input_normals(true, pm)), out);
    out.add_points("enhance_positions_along_input_normals", points, false);
  }
  {
    std::vector<PV> points = input;
    report("enhance_normals", CGAL::wavejet_enhance_normals<Seq>(points, 40, std::complex<double>(1., 2.),
             WJP::order(5, pm)), out);
    out.add_points("enhance_normals", points, true);
  }
  {
    // The scale per point: the chosen sizes and the descriptor, then normals with those sizes and
    // an order per point.
    std::vector<std::size_t> index(input.size());
    std::vector<Point> positions;
    std::vector<Vector> normals;
    for(std::size_t i = 0; i < index.size(); ++i)
    {
      index[i] = i;
      positions.push_back(input[i].first);
      normals.push_back(input[i].second);
    }
    std::vector<unsigned int> sizes(index.size(), 0), orders(index.size(), 0);
    std::vector<std::vector<double> > descriptor(index.size());
    report("estimate_scales", CGAL::wavejet_estimate_scales<Seq>(index,
             WJP::neighborhood_size_map(CGAL::make_property_map(sizes)).neighborhood_sizes(std::vector<unsigned int>{12, 20, 32, 50})
               .scale_descriptor_map(CGAL::make_property_map(descriptor)).point_map(CGAL::make_property_map(positions))), out);
    for(std::size_t i = 0; i < index.size(); ++i)
    {
      std::vector<double> record(1, double(sizes[i]));
      record.insert(record.end(), descriptor[i].begin(), descriptor[i].end());
      out.add("estimate_scales[" + std::to_string(i) + "]", record);
      orders[i] = 2 + unsigned(i % 2);
    }
    report("estimate_normals_per_point_scales", CGAL::wavejet_estimate_normals<Seq>(index, 30,
             WJP::neighborhood_size_map(CGAL::make_property_map(sizes)).order_map(CGAL::make_property_map(orders))
               .orient_with_input_normals(true).point_map(CGAL::make_property_map(positions))
               .normal_map(CGAL::make_property_map(normals))), out);
    for(std::size_t i = 0; i < index.size(); ++i)
      out.add("estimate_normals_per_point_scales[" + std::to_string(i) + "]", {normals[i].x(), normals[i].y(), normals[i].z()});
  }
}

using wavejets_test::check_printed;

/// Whether `f()` throws an exception of type E.
template <class E, class F>
static bool throws(const F& f)
{
  try { f(); }
  catch(const E&) { return true; }
  catch(...) { return false; }
  return false;
}

/// The contracts of the public API that the records do not show.
static void contracts(const std::vector<PV>& input)
{
  typedef CGAL::Wavejet_fitting<Kernel> Fitting;
  typedef CGAL::Wavejets::Point_set_function F;
  std::vector<Point> neighborhood;
  for(std::size_t j = 0; j < 40; ++j) neighborhood.push_back(input[j].first);
  Fitting fitting;
  check_printed(throws<std::invalid_argument>([&] { fitting(neighborhood.begin(), neighborhood.end(), 0); }),
        "Wavejet_fitting: order 0 throws std::invalid_argument (in every build type)");
  Fitting::Wavejet_form form = fitting(neighborhood.begin(), neighborhood.end(), 4);
  check_printed(form.is_valid(), "Wavejet_fitting: order 4 on 40 points is fitted");
  check_printed(throws<std::out_of_range>([&] { form.principal_curvatures(2); }), "principal_curvatures(2) throws std::out_of_range");
  check_printed(throws<std::out_of_range>([&] { fitting.pca_basis(3); }), "pca_basis(3) throws std::out_of_range");
  // A coefficient vector shortened by the user (writable coefficients()): reads stay within it.
  const std::complex<double> f20 = form.coefficient(2, 0);
  form.coefficients().resize(7); // orders 0 to 2 complete (6 values), one value of order 3
  check_printed(form.coefficient(2, 0) == f20 && form.coefficient(3, 1) == std::complex<double>(0., 0.) &&
          form.coefficient(4, 0) == std::complex<double>(0., 0.),
        "coefficient(k, n) of a shortened coefficient vector: stored orders read, the others 0");
  check_printed(std::isfinite(std::abs(form.enclosed_area_coefficient(0))) && std::isfinite(std::abs(form.enclosed_area_coefficient(3))),
        "enclosed_area_coefficient of a shortened coefficient vector: finite, within the stored orders");
  form.comply_wrt_given_normal(-form.normal_direction());
  check_printed(form.coefficient(2, 0) == -f20, "comply_wrt_given_normal flips the stored coefficients only");

  // Processing_report::moves_points, and the clamped count printed only then.
  const auto pm = CGAL::parameters::point_map(Point_map()).normal_map(Normal_map());
  std::vector<PV> a = input, b = input;
  const CGAL::Wavejets::Processing_report moved = CGAL::wavejet_enhance_positions<Seq>(a, 30, 2., pm);
  const CGAL::Wavejets::Processing_report normals = CGAL::wavejet_estimate_normals<Seq>(b, 30, pm);
  std::ostringstream moved_text, normals_text;
  moved_text << moved;
  normals_text << normals;
  check_printed(moved.moves_points && !normals.moves_points, "moves_points: true for enhance_positions only");
  check_printed(moved_text.str().find("clamped") != std::string::npos && normals_text.str().find("clamped") == std::string::npos,
        "the report prints the clamped count for enhance_positions only: '" + normals_text.str() + "'");

  // The functions' defaults are function_defaults()'s: no order given == the table's order (bitwise).
  std::vector<PV> x = input, y = input;
  CGAL::wavejet_estimate_normals<Seq>(x, 30, pm);
  CGAL::wavejet_estimate_normals<Seq>(y, 30, WJP::order(CGAL::Wavejets::function_defaults(F::ESTIMATE_NORMALS).order,
    WJP::tangent_plane_order(CGAL::Wavejets::function_defaults(F::ESTIMATE_NORMALS).fitting.tangent_plane_order, pm)));
  check_printed(x == y, "estimate_normals: defaults == function_defaults(ESTIMATE_NORMALS), bitwise");
  x = input, y = input;
  CGAL::wavejet_enhance_positions<Seq>(x, 30, 2., pm);
  const CGAL::Wavejets::Function_defaults d = CGAL::Wavejets::function_defaults(F::ENHANCE_POSITIONS);
  check_printed(d.maximum_displacement_in_radii > 0 && d.order == 4, "function_defaults(ENHANCE_POSITIONS): order 4, a clamp");
  CGAL::wavejet_enhance_positions<Seq>(y, 30, 2., WJP::order(d.order, WJP::tangent_plane_order(d.fitting.tangent_plane_order,
    WJP::neighbors_per_coefficient(d.fitting.neighbors_per_coefficient, pm))));
  check_printed(x == y, "enhance_positions: defaults == function_defaults(ENHANCE_POSITIONS), bitwise");
  x = input, y = input;
  CGAL::wavejet_enhance_normals<Seq>(x, 30, std::complex<double>(2., 0.), pm);
  CGAL::wavejet_enhance_normals<Seq>(y, 30, std::complex<double>(2., 0.),
    WJP::order(CGAL::Wavejets::function_defaults(F::ENHANCE_NORMALS).order, pm));
  check_printed(x == y, "enhance_normals: defaults == function_defaults(ENHANCE_NORMALS), bitwise");
}

/// Compares with a reference file: every record present in both, to `tolerance` relative to the
/// record's largest absolute value; every reference record must be present here.
static bool compare(const Records& results, const char* reference_file, double tolerance)
{
  std::ifstream in(reference_file);
  if(!in)
  {
    std::cerr << "cannot read the reference results " << reference_file << std::endl;
    return false;
  }
  const std::map<std::string, std::vector<double> > reference = Records::read(in);
  std::size_t compared = 0, differing = 0;
  double worst = 0.;
  std::string worst_label;
  for(const auto& r : results.records())
  {
    const auto it = reference.find(r.first);
    if(it == reference.end() || it->second.size() != r.second.size())
    {
      std::cerr << "record " << r.first << " is missing or has another size in the reference" << std::endl;
      ++differing;
      continue;
    }
    double scale = 0., difference = 0.;
    for(std::size_t j = 0; j < r.second.size(); ++j)
    {
      scale = (std::max)({scale, std::abs(r.second[j]), std::abs(it->second[j])});
      difference = (std::max)(difference, std::abs(r.second[j] - it->second[j]));
    }
    const double relative = scale > 0 ? difference / scale : 0.;
    if(!(relative <= tolerance)) ++differing;
    if(!(relative <= worst)) { worst = relative; worst_label = r.first; }
    ++compared;
  }
  const bool ok = differing == 0 && compared == reference.size();
  std::cout << (ok ? "[ OK ] " : "[FAIL] ") << "agreement with " << reference_file << ": " << compared << " records of "
            << reference.size() << ", " << differing << " differ by more than " << tolerance
            << " relative; largest difference " << worst << " (" << worst_label << ")" << std::endl;
  return ok;
}

int main(int argc, char** argv)
{
  const char* file = argc > 1 ? argv[1] : "data/kitten.xyz";
  std::vector<PV> input;
  if(!CGAL::IO::read_points(file, std::back_inserter(input), CGAL::parameters::point_map(Point_map()).normal_map(Normal_map())) ||
     input.size() < 200)
  {
    std::cerr << "cannot read " << file << std::endl;
    return EXIT_FAILURE;
  }
  contracts(input);
  Records results;
  fit_one_point(input, results);
  point_set_functions(input, results);

  const char* directory = std::getenv("WAVEJETS_OUTPUT_DIR");
  const std::string output = std::string(directory && *directory ? directory : ".") + "/public_api_results.txt";
  std::ofstream os(output);
  results.write(os);
  os.close();
  std::cout << "CGAL " << CGAL_VERSION_STR << ", CGAL Wavejets " << CGAL_WAVEJETS_VERSION_STR << ": "
            << results.records().size() << " records written to " << output << std::endl;
  if(!os) return EXIT_FAILURE;

  if(wavejets_test::all_counts().failures > 0) return EXIT_FAILURE;
  const char* reference = std::getenv("WAVEJETS_REFERENCE_RESULTS");
  if(reference && *reference)
    return compare(results, reference, 1e-12) ? EXIT_SUCCESS : EXIT_FAILURE;
  std::cout << "no WAVEJETS_REFERENCE_RESULTS: results written, nothing compared" << std::endl;
  return EXIT_SUCCESS;
}
