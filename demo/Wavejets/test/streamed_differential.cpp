// Randomized differential test of the streamed runs: for each case (a seed), a random point set and
// a random command line; the in-memory run, the streamed run (--tile-size) and, for every fourth
// case, the staged steps (--job DIR --stage ...) must write the same bytes, or fail alike. Also:
// the streamed summary's count of fitted points is that of the written `fitted` column, and every
// point written with `fitted` 0 keeps its input position (and normal, where the command writes the
// input's normals for it).
//
//   streamed_differential [--cases N] [--seed S] [--dir DIR] [--progress]
//
// runs the cases S, S+1, ..., S+N-1 (defaults: 1000 cases from seed 1, in a folder of the system's
// temporary directory). The soak mode is the same with more cases (e.g. --cases 100000). A failure
// prints its seed, keeps its files in DIR/case-SEED and prints the tool's command lines that
// reproduce it; `--cases 1 --seed SEED` runs that case alone. Exit status: 0 when every case
// passed, 1 otherwise.
//
// The cases: 30 to 3,000 points (log-uniform) on a bumpy patch, a sphere, in clusters or with a
// thin dense band; exact copies of some points (up to more than k copies); sometimes far from the
// origin (offsets up to 1e6); with unit normals or without (then --orient-toward); as binary PLY,
// ASCII PLY or XYZ; any of the four commands, k from 2 to 200 or a radius (with or without a cap
// on the neighbors), orders 1 to 5, tiles from 5 points to more than the whole set, chunks of 1
// point to more than the whole set (WAVEJETS_CHUNK_POINTS), 1 or 2 threads, binary or ASCII output.
#include "tool.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace {

// A portable random source (the standard distributions differ between libraries): splitmix64.
class Random
{
public:
  explicit Random(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull) {}
  std::uint64_t bits()
  {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(bits() >> 11) * (1.0 / 9007199254740992.0); }   // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  std::size_t integer(std::size_t lo, std::size_t hi) { return lo + std::size_t(bits() % (hi - lo + 1)); }   // [lo, hi]
  std::size_t log_uniform(std::size_t lo, std::size_t hi)
  {
    return std::min(hi, std::size_t(std::exp(uniform(std::log(double(lo)), std::log(double(hi) + 1.)))));
  }
  double gaussian()
  {
    const double u = 1. - uniform(), v = uniform();
    return std::sqrt(-2. * std::log(u)) * std::cos(6.283185307179586 * v);
  }
  bool chance(double p) { return uniform() < p; }

private:
  std::uint64_t state_;
};

struct Point { double p[3], n[3]; };

// A point of the bumpy patch z = a sin(f x) cos(f y) over [-1, 1]^2, with its unit normal.
Point patch_point(double x, double y, double a, double f)
{
  const double z = a * std::sin(f * x) * std::cos(f * y);
  double n[3] = {-a * f * std::cos(f * x) * std::cos(f * y), a * f * std::sin(f * x) * std::sin(f * y), 1.};
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  return Point{{x, y, z}, {n[0] / l, n[1] / l, n[2] / l}};
}

struct Case
{
  std::vector<Point> points;
  bool normals = true;
  std::string format;                 // ply, ascii-ply, xyz
  std::vector<std::string> command;   // the tool's command and flags, without IN, OUT and streaming
  std::size_t tile_size = 0;
  std::size_t chunk_points = 0;       // WAVEJETS_CHUNK_POINTS of the streamed runs
  bool staged = false;
  std::string description;
};

Case make_case(std::uint64_t seed)
{
  Random r(seed);
  Case c;
  const std::size_t n = r.log_uniform(30, 3000);
  const int shape = int(r.integer(0, 3));
  const double a = r.uniform(0., 0.3), f = r.uniform(1., 8.);
  std::ostringstream d;
  // Cluster centres, for shape 2.
  std::vector<std::pair<double, double> > centres(r.integer(1, 5));
  for(auto& ce : centres) ce = {r.uniform(-0.8, 0.8), r.uniform(-0.8, 0.8)};
  for(std::size_t i = 0; i < n; ++i) {
    if(shape == 1) {   // a sphere of radius 1
      double v[3] = {r.gaussian(), r.gaussian(), r.gaussian()};
      const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      c.points.push_back(Point{{v[0] / l, v[1] / l, v[2] / l}, {v[0] / l, v[1] / l, v[2] / l}});
      continue;
    }
    double x = r.uniform(-1., 1.), y = r.uniform(-1., 1.);
    if(shape == 2) {   // clusters of spread 0.01 to 0.2
      const auto& ce = centres[r.integer(0, centres.size() - 1)];
      const double s = 0.01 + 0.19 * double(&ce - &centres[0]) / double(centres.size());
      x = ce.first + s * r.gaussian();
      y = ce.second + s * r.gaussian();
    } else if(shape == 3 && r.chance(0.3)) {   // a thin dense band
      x = r.uniform(0.2, 0.22);
    }
    c.points.push_back(patch_point(x, y, a, f));
  }
  d << n << " points on a " << (shape == 0 ? "bumpy patch" : shape == 1 ? "sphere" : shape == 2 ? "patch, in clusters" : "patch with a dense band");
  // Exact copies of some points, some of them more than k times.
  if(r.chance(0.4)) {
    const std::size_t copied = r.integer(1, std::max<std::size_t>(1, n / 20));
    std::size_t added = 0;
    for(std::size_t j = 0; j < copied; ++j) {
      const Point q = c.points[r.integer(0, n - 1)];
      const std::size_t copies = r.chance(0.2) ? r.integer(5, 60) : r.integer(1, 3);
      for(std::size_t m = 0; m < copies; ++m) c.points.insert(c.points.begin() + std::ptrdiff_t(r.integer(0, c.points.size())), q);
      added += copies;
    }
    d << ", " << added << " exact copies";
  }
  // Far from the origin, and scaled.
  const double scale = r.chance(0.3) ? std::pow(10., r.uniform(-3., 3.)) : 1.;
  double offset[3] = {0, 0, 0};
  if(r.chance(0.3)) for(double& o : offset) o = r.uniform(-1e6, 1e6);
  for(Point& q : c.points)
    for(int k = 0; k < 3; ++k) q.p[k] = q.p[k] * scale + offset[k];
  if(scale != 1. || offset[0] != 0.) d << ", scaled by " << scale << " around (" << offset[0] << ", " << offset[1] << ", " << offset[2] << ")";
  // Normals: unit, some flipped; or none.
  c.normals = r.chance(0.7);
  if(c.normals)
    for(Point& q : c.points)
      if(r.chance(0.1)) for(double& v : q.n) v = -v;
  const int format = int(r.integer(0, 2));
  c.format = format == 0 ? "ply" : format == 1 ? "ascii-ply" : "xyz";
  d << ", " << (c.normals ? "with" : "without") << " normals, " << c.format;

  static const char* const commands[4] = {"normals", "curvature", "enhance-positions", "enhance-normals"};
  const std::size_t total = c.points.size();
  c.command.push_back(commands[r.integer(0, 3)]);
  const unsigned order = unsigned(r.integer(1, 5));
  c.command.insert(c.command.end(), {"--order", std::to_string(order)});
  const std::size_t k = r.log_uniform(2, std::min<std::size_t>(200, total - 1));
  if(r.chance(0.2)) {   // a radius: about k points' worth on a unit surface
    const double radius = scale * std::sqrt(4. * double(k) / (3.14159 * double(total))) * (shape == 1 ? 2. : 1.);
    std::ostringstream rs;
    rs << std::setprecision(17) << radius;
    c.command.insert(c.command.end(), {"--radius", rs.str(), "--k", r.chance(0.5) ? "0" : std::to_string(k)});
  } else {
    c.command.insert(c.command.end(), {"--k", std::to_string(k)});
  }
  if(c.command[0] == "enhance-positions" || c.command[0] == "enhance-normals") {
    c.command.insert(c.command.end(), {"--gain", r.chance(0.5) ? "2" : "-1"});
    if(r.chance(0.3)) c.command.push_back(r.chance(0.5) ? "--consistent-normals" : "--all-neighbors");
  }
  if(!c.normals) c.command.insert(c.command.end(), {"--orient-toward", "0,0,1e7"});
  c.command.insert(c.command.end(), {"--threads", r.chance(0.5) ? "1" : "2"});
  if(r.chance(0.2)) c.command.push_back("--ascii");
  c.tile_size = r.log_uniform(5, 2 * total);
  c.chunk_points = r.log_uniform(1, 2 * total);
  c.staged = seed % 4 == 0;
  c.description = d.str();
  return c;
}

std::string join(const std::vector<std::string>& v)
{
  std::string s;
  for(const std::string& a : v) s += (s.empty() ? "" : " ") + a;
  return s;
}

void write_input(const Case& c, const std::string& path)
{
  std::ofstream os(path, std::ios::binary);
  os << std::setprecision(17);
  if(c.format == "xyz") {
    for(const Point& q : c.points) {
      os << q.p[0] << ' ' << q.p[1] << ' ' << q.p[2];
      if(c.normals) os << ' ' << q.n[0] << ' ' << q.n[1] << ' ' << q.n[2];
      os << '\n';
    }
    return;
  }
  const bool ascii = c.format == "ascii-ply";
  os << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian") << " 1.0\nelement vertex " << c.points.size()
     << "\nproperty double x\nproperty double y\nproperty double z\n";
  if(c.normals) os << "property double nx\nproperty double ny\nproperty double nz\n";
  os << "end_header\n";
  for(const Point& q : c.points) {
    const int fields = c.normals ? 6 : 3;
    for(int f = 0; f < fields; ++f) {
      const double v = f < 3 ? q.p[f] : q.n[f - 3];
      if(ascii) os << v << (f + 1 < fields ? ' ' : '\n');
      else os.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
  }
}

std::string read_file(const std::string& path)
{
  std::ifstream is(path, std::ios::binary);
  std::ostringstream s;
  s << is.rdbuf();
  return s.str();
}

// The tool run in this process: its exit status, its standard output in `out`.
int run_tool(const std::vector<std::string>& args, std::string* out = nullptr)
{
  std::ostringstream captured;
  std::streambuf* cout = std::cout.rdbuf(captured.rdbuf());
  std::ostringstream errors;
  std::streambuf* cerr = std::cerr.rdbuf(errors.rdbuf());
  int status = 0;
  try {
    status = wavejets_demo::run_wavejets_tool(args);
  } catch(...) {
    std::cout.rdbuf(cout);
    std::cerr.rdbuf(cerr);
    throw;
  }
  std::cout.rdbuf(cout);
  std::cerr.rdbuf(cerr);
  if(out) *out = captured.str() + errors.str();
  return status;
}

// The vertices of a PLY the tool wrote: each property's values by name.
std::map<std::string, std::vector<double> > read_vertices(const std::string& path)
{
  const std::string bytes = read_file(path);
  std::istringstream is(bytes);
  std::string line, format;
  std::size_t count = 0;
  std::vector<std::pair<std::string, std::string> > properties;   // type, name
  while(std::getline(is, line) && line != "end_header") {
    std::istringstream l(line);
    std::string word;
    l >> word;
    if(word == "format") l >> format;
    else if(word == "element") { std::string name; l >> name >> count; }
    else if(word == "property") { std::string type, name; l >> type >> name; properties.emplace_back(type, name); }
  }
  std::map<std::string, std::vector<double> > v;
  std::size_t at = std::size_t(is.tellg());
  for(std::size_t i = 0; i < count; ++i)
    for(const auto& p : properties) {
      double x = 0.;
      if(format == "ascii") is >> x;
      else if(p.first == "double") { std::memcpy(&x, &bytes[at], 8); at += 8; }
      else if(p.first == "float") { float f; std::memcpy(&f, &bytes[at], 4); x = f; at += 4; }
      else if(p.first == "uchar") { x = double((unsigned char)(bytes[at])); at += 1; }
      else throw std::runtime_error(path + ": unexpected property type " + p.first);
      v[p.second].push_back(x);
    }
  return v;
}

struct Runner
{
  std::string dir;
  std::vector<std::string> failures;   // of the current case
  std::vector<std::string> commands;   // of the current case, to reproduce it
  std::string environment;             // of the streamed runs

  int run(const std::vector<std::string>& args, std::string* out = nullptr)
  {
    const bool streamed = std::find(args.begin(), args.end(), "--tile-size") != args.end();
    commands.push_back((streamed ? environment + " " : std::string()) + "wavejets " + join(args));
    return run_tool(args, out);
  }
  void fail(const std::string& what) { failures.push_back(what); }

  // The staged steps of a streamed run, as wavejets.distributed runs them (the tiles in reverse
  // order, one of them twice); returns the exit status of the first step that failed, else 0.
  int staged(const std::vector<std::string>& base, const std::string& job)
  {
    mkdir(job.c_str(), 0777);
    std::vector<std::string> a = base;
    a.insert(a.end(), {"-q", "--job", job, "--stage"});
    auto step = [&](const std::string& stage) {
      std::vector<std::string> s = a;
      s.push_back(stage);
      return run(s);
    };
    if(int status = step("prepare")) return status;
    std::size_t passes = 0;
    {
      std::istringstream is(read_file(job + "/run"));
      std::string key;
      while(is >> key) if(key == "passes") is >> passes; else is >> key;
    }
    for(std::size_t p = 0; p < passes; ++p) {
      if(p > 0) if(int status = step("bin:" + std::to_string(p))) return status;
      std::size_t tiles = 0;
      std::istringstream(read_file(job + "/pass-" + std::to_string(p) + ".tiles")) >> tiles;
      for(std::size_t t = tiles; t-- > 0;)
        if(int status = step("tile:" + std::to_string(p) + ":" + std::to_string(t))) return status;
      if(tiles > 0) if(int status = step("tile:" + std::to_string(p) + ":0")) return status;
    }
    bool parts = false;
    {
      std::istringstream is(read_file(job + "/run"));
      std::string key;
      while(is >> key) if(key == "write_in_parts") is >> parts; else is >> key;
    }
    if(!parts) return step("write");
    for(int c = 2; c >= 0; --c) if(int status = step("write:" + std::to_string(c) + ":3")) return status;
    return step("finish:3");
  }
};

// A folder, created if needed; throws if it cannot be.
void make_folder(const std::string& dir)
{
  struct stat st;
  if(mkdir(dir.c_str(), 0777) != 0 && !(stat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode)))
    throw std::runtime_error("cannot create the folder " + dir + " (" + std::strerror(errno) + ")");
}

enum class Outcome { COMPARED, REJECTED_ALIKE, FAILED };

Outcome run_case(std::uint64_t seed, const std::string& root)
{
  const Case c = make_case(seed);
  Runner runner;
  runner.dir = root + "/case-" + std::to_string(seed);
  make_folder(runner.dir);
  const std::string in = runner.dir + "/in." + (c.format == "xyz" ? "xyz" : "ply");
  write_input(c, in);
  if(read_file(in).empty()) throw std::runtime_error("cannot write " + in);
  const std::string core = runner.dir + "/core.ply", streamed = runner.dir + "/streamed.ply", staged = runner.dir + "/staged.ply";
  auto with = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> a = {c.command[0], in, out};
    a.insert(a.end(), c.command.begin() + 1, c.command.end());
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const int core_status = runner.run(with(core, {"-q"}));
  runner.environment = "WAVEJETS_CHUNK_POINTS=" + std::to_string(c.chunk_points);
  setenv("WAVEJETS_CHUNK_POINTS", std::to_string(c.chunk_points).c_str(), 1);
  std::string summary;
  const int streamed_status = runner.run(with(streamed, {"--tile-size", std::to_string(c.tile_size)}), &summary);
  if(core_status != streamed_status)
    runner.fail("in memory exit " + std::to_string(core_status) + ", streamed exit " + std::to_string(streamed_status) + ": " + summary);
  else if(core_status == 0) {
    const std::string expected = read_file(core);
    if(read_file(streamed) != expected) runner.fail("the streamed output differs from the in-memory one");
    const auto v = read_vertices(streamed);
    const std::vector<double>& fitted = v.at("fitted");
    const std::size_t count = std::size_t(std::count(fitted.begin(), fitted.end(), 1.));
    if(summary.find(std::to_string(fitted.size()) + " points in input order, " + std::to_string(count) + " of them fitted") == std::string::npos)
      runner.fail("the summary does not give the written file's " + std::to_string(count) + " fitted points: " + summary);
    // Unfitted points keep their input position (and, but for enhance-positions, whose normals are
    // estimated again, their input normal).
    const bool keeps_normal = c.normals && c.command[0] != "enhance-positions";
    for(std::size_t i = 0; i < fitted.size(); ++i) {
      if(fitted[i] != 0.) continue;
      const Point& q = c.points[i];
      const bool ascii_output = std::find(c.command.begin(), c.command.end(), "--ascii") != c.command.end();
      auto same = [&](double written, double input) { return ascii_output ? std::abs(written - input) <= 1e-15 * std::abs(input) : written == input; };
      bool kept = same(v.at("x")[i], q.p[0]) && same(v.at("y")[i], q.p[1]) && same(v.at("z")[i], q.p[2]);
      if(keeps_normal) kept = kept && same(v.at("nx")[i], q.n[0]) && same(v.at("ny")[i], q.n[1]) && same(v.at("nz")[i], q.n[2]);
      if(!kept) { runner.fail("unfitted point " + std::to_string(i) + " does not keep its input"); break; }
    }
    if(c.staged) {
      const int status = runner.staged(with(staged, {"--tile-size", std::to_string(c.tile_size)}), runner.dir + "/job");
      if(status != 0) runner.fail("a staged step failed (exit " + std::to_string(status) + ")");
      else if(read_file(staged) != expected) runner.fail("the staged output differs from the in-memory one");
    }
  }
  unsetenv("WAVEJETS_CHUNK_POINTS");
  if(runner.failures.empty()) {
    std::system(("rm -rf '" + runner.dir + "'").c_str());
    return core_status == 0 ? Outcome::COMPARED : Outcome::REJECTED_ALIKE;
  }
  std::cout << "FAILED case " << seed << " (" << c.description << "): " << join(runner.failures) << "\n"
            << "  its files are kept in " << runner.dir << "; the commands that reproduce it:\n";
  for(const std::string& command : runner.commands) std::cout << "    " << command << "\n";
  std::cout << "  run it alone: streamed_differential --cases 1 --seed " << seed << std::endl;
  return Outcome::FAILED;
}

} // namespace

int main(int argc, char** argv)
{
  std::uint64_t cases = 1000, seed = 1;
  std::string dir;
  bool progress = false;
  for(int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if(a == "--cases" && i + 1 < argc) cases = std::strtoull(argv[++i], nullptr, 10);
    else if(a == "--seed" && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
    else if(a == "--dir" && i + 1 < argc) dir = argv[++i];
    else if(a == "--progress") progress = true;
    else {
      std::cerr << "usage: streamed_differential [--cases N] [--seed S] [--dir DIR] [--progress]" << std::endl;
      return 2;
    }
  }
  if(dir.empty()) {
    const char* tmp = std::getenv("TMPDIR");
    dir = std::string(tmp ? tmp : "/tmp") + "/wavejets-streamed-differential";
  }
  std::uint64_t failed = 0, rejected = 0;
  try {
    make_folder(dir);
    for(std::uint64_t i = 0; i < cases; ++i) {
      const Outcome o = run_case(seed + i, dir);
      failed += o == Outcome::FAILED;
      rejected += o == Outcome::REJECTED_ALIKE;
      if(progress && (i + 1) % 1000 == 0) std::cerr << (i + 1) << " cases, " << failed << " failed" << std::endl;
    }
  } catch(const std::exception& e) {
    std::cout << "streamed_differential: " << e.what() << std::endl;
    return 1;
  }
  std::cout << "streamed_differential: cases " << seed << " to " << seed + cases - 1 << " (in memory, streamed, "
            << "and staged steps for every fourth): " << (cases - failed - rejected) << " outputs compared, " << rejected
            << " inputs rejected alike by both runs" << std::endl;
  // A setup where every run fails would pass unnoticed: most cases must be real comparisons.
  if(10 * rejected > cases) {
    std::cout << "more than a tenth of the cases were rejected by both runs: the test compares too little" << std::endl;
    ++failed;
  }
  std::cout << (cases - failed) << " passed, " << failed << " failed" << std::endl;
  return failed == 0 ? 0 : 1;
}
