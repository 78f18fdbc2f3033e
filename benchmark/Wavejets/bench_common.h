// Small helpers shared by the benchmarks of benchmark/Wavejets/ (not part of the package).

#ifndef WAVEJETS_BENCH_COMMON_H
#define WAVEJETS_BENCH_COMMON_H

#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/info.h>
#endif

namespace wavejets_bench {

/// This folder (benchmark/Wavejets of the source tree), where the benchmarks read their data and write
/// their csv/ tables: an absolute path set by CMake in source_dir.cpp (the only file that sees it, so
/// that the benchmarks' compilations stay the same in every clone for ccache; `__FILE__` is no help:
/// ccache's base directory makes it relative to the build folder).
std::string source_dir();

/// One table of a benchmark's results, written as CSV (first row: the column names). The benchmarks write
/// their tables as csv/<report>.<table>.csv; make_reports.py writes the Markdown reports and plots from them.
class Csv_table
{
public:
  explicit Csv_table(std::vector<std::string> header) { m_rows.push_back(std::move(header)); }

  void add_row(std::vector<std::string> cells) { m_rows.push_back(std::move(cells)); }

  /// The table as CSV text: cells holding a comma, a quote or a line break are quoted.
  std::string str() const
  {
    std::ostringstream s;
    for(const std::vector<std::string>& row : m_rows)
    {
      for(std::size_t i = 0; i < row.size(); ++i)
      {
        const std::string& c = row[i];
        if(i) s << ',';
        if(c.find_first_of(",\"\n") == std::string::npos) { s << c; continue; }
        s << '"';
        for(char ch : c) s << (ch == '"' ? "\"\"" : std::string(1, ch));
        s << '"';
      }
      s << '\n';
    }
    return s.str();
  }

  /// Writes the table to `directory`/`name`.csv and says so on standard output.
  void write(const std::string& directory, const std::string& name) const
  {
    const std::string path = directory + "/" + name + ".csv";
    std::ofstream f(path);
    f << str();
    if(!f) { std::cerr << "cannot write " << path << "\n"; std::exit(EXIT_FAILURE); }
    std::cout << "wrote " << path << "\n";
  }

private:
  std::vector<std::vector<std::string> > m_rows;
};

/// A run's context for its report (the machine, the run time): a two-column table key,value.
inline Csv_table context_table() { return Csv_table({"key", "value"}); }

/// The machine, for the reports: CPU model, hardware threads and TBB's thread count. With
/// `names_parallel_tag`, also says that the benchmark runs with Parallel_if_available_tag (sequential
/// without TBB).
inline std::string machine_description(bool names_parallel_tag = true)
{
  std::string cpu = "unknown CPU";
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while(std::getline(f, line))
    if(line.rfind("model name", 0) == 0) { cpu = line.substr(line.find(':') + 2); break; }
  std::ostringstream s;
  s << cpu << ", " << std::thread::hardware_concurrency() << " hardware threads";
#ifdef CGAL_LINKED_WITH_TBB
  s << ", TBB with " << tbb::info::default_concurrency() << " threads"
    << (names_parallel_tag ? " (Parallel_if_available_tag)" : "");
#else
  if(names_parallel_tag) s << ", no TBB (sequential)";
#endif
  return s.str();
}

/// The degree of CGAL's jet on a neighborhood of `points` points at requested degree K: K, or where the
/// neighborhood has fewer than 1.1 (K+1)(K+2)/2 points, the largest degree it allows (the Wavejets' adaptive
/// rule, factor 1.1). Below 2: no jet fits.
inline std::size_t adaptive_jet_degree(std::size_t points, std::size_t K)
{
  std::size_t deg = K;
  while(deg >= 2 && double(points) < 1.1 * double((deg + 1) * (deg + 2) / 2)) --deg;
  return deg;
}

/// CGAL's jet estimate on the neighborhood `pts` (query point first): `monge` (a CGAL::Monge_via_jet_fitting) of
/// degree adaptive_jet_degree(pts.size(), K), Monge degree 2, oriented by `orientation`. Sets the fields ok, H, K,
/// k1, k2 and n of `r`; leaves `r` as it is where no jet fits.
template <class Monge, class Point, class Vector, class Estimate>
void jet_estimate(Monge& monge, const std::vector<Point>& pts, std::size_t K, const Vector& orientation, Estimate& r)
{
  const std::size_t deg = adaptive_jet_degree(pts.size(), K);
  if(deg < 2) return;
  typename Monge::Monge_form m = monge(pts.begin(), pts.end(), deg, 2);
  m.comply_wrt_given_normal(orientation);
  r.k1 = m.principal_curvatures(0);
  r.k2 = m.principal_curvatures(1);
  r.H = 0.5 * (r.k1 + r.k2);
  r.K = r.k1 * r.k2;
  const Vector n = m.normal_direction();
  r.n = decltype(r.n)(n.x(), n.y(), n.z());
  r.ok = true;
}

} // namespace wavejets_bench

#endif // WAVEJETS_BENCH_COMMON_H
