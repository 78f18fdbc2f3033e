// wavejets: command-line tool of the CGAL Wavejets package (run_wavejets_tool(): main.cpp, and the
// Python module for wavejets.distributed).
//   wavejets normals|curvature|enhance-positions|enhance-normals IN OUT.ply [flags]
//   wavejets render IN OUT.png [flags]      wavejets render --compare A B OUT.png [flags]
// Run `wavejets --help` or `wavejets <command> --help` for the flags.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>
#include <CGAL/Wavejets/internal/cgal_compatibility.h> // find_property_map: CGAL 5.5 and 6
#include <CGAL/Wavejets/Function_defaults.h>
#include <CGAL/Wavejets/version.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>
#include <CGAL/wavejet_estimate_scales.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/info.h>
#endif

#include "fit_command.h"
#include "platform.h"
#include "point_set_io.h"
#include "streaming.h"
#include "tool.h"
#include "render.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>


using wavejets_demo::Kernel;
using wavejets_demo::Point;
using wavejets_demo::Vector;
using wavejets_demo::Point_set;
using wavejets_demo::File_error;
using wavejets_demo::Input;
using wavejets_demo::Output_format;
using wavejets_demo::lower_extension;
using wavejets_demo::output_format;
using wavejets_demo::read_input;
using wavejets_demo::write_output;
using wavejets_demo::report_text;
using wavejets_demo::Concurrency_tag;
namespace WP = CGAL::Wavejets::parameters;
using Clock = std::chrono::steady_clock;

namespace {

const char* const version = "wavejets " CGAL_WAVEJETS_VERSION_STR " (CGAL Wavejets package)";

// ------------------------------------------------------------------------------------------------
// Errors: a user error (bad flag: exit 2) or a file/processing error (File_error, point_set_io.h:
// exit 1), one line each.
struct Usage_error : std::runtime_error { using std::runtime_error::runtime_error; };

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string format(double v, int precision = 4)
{
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

// ------------------------------------------------------------------------------------------------
// Commands and flags. The help text is generated from this table.
using wavejets_demo::NORMALS;
using wavejets_demo::CURVATURE;
using wavejets_demo::POSITIONS;
using wavejets_demo::NORMAL_FILTER;
using wavejets_demo::RENDER;
using wavejets_demo::FITS;

struct Command_info { const char* name; unsigned bit; const char* synopsis; const char* summary; };
const Command_info commands[] = {
  {"normals", NORMALS, "IN OUT.ply", "estimate oriented normals (Wavejet normals; orientation from the input normals, else by a minimum spanning tree)"},
  {"curvature", CURVATURE, "IN OUT.ply", "estimate mean/Gaussian/principal curvatures and principal directions as PLY scalar properties"},
  {"enhance-positions", POSITIONS, "IN OUT.ply", "move points along their normal: gain > 1 amplifies details, [0,1) flattens, < 0 inverts"},
  {"enhance-normals", NORMAL_FILTER, "IN OUT.ply", "tilt normals: gain > 1 exaggerates shading detail, 0 blurs, < 0 inverts, imaginary part twists"},
  {"render", RENDER, "IN OUT.png | --compare A B OUT.png", "draw a mesh as shaded triangles, a point set as shaded splats (or two side by side) into a PNG"},
};

struct Flag_info { const char* name; const char* arg; unsigned commands; const char* help; };
const Flag_info flags[] = {
  {"--k", "N", FITS, "neighbors per fit (k nearest: Rf per point follows the sampling; default 40, 1.5 x the coefficients above order 6); with --radius: at most N nearest within the radius (0: no limit); auto: each point's own, chosen among 7 sizes (10 to 160 at order 2; in memory only), written as the column scale_k (curvature: also f2_k<N>, |f_2| at each size); a column's name (e.g. scale_k): each point's own k from that property of the input (0: the default; in memory only)"},
  {"--radius", "R", FITS, "neighborhood radius in model units (points with too few neighbors inside are reported, not fitted); a column's name: each point's own radius from that property of the input (0: its k nearest neighbors, --k N then needed; in memory only)"},
  {"--radius-factor", "F", FITS, "instead of --k and --radius: one radius of F x the average spacing to the 6 nearest neighbors (e.g. 4)"},
  {"--order", "K", FITS, "Wavejet order (default 2 for normals and curvature, 4 for the enhance commands); a column's name: each point's own order from that property of the input (0: the default; in memory only)"},
  {"--gain", "G|RE,IM", POSITIONS | NORMAL_FILTER, "filter gain (default 2); enhance-normals takes a complex gain, e.g. 0,2 for 2i (twist)"},
  {"--evaluation-radius", "S", POSITIONS | NORMAL_FILTER, "radius s of the enclosed-area coefficients a_n(s), model units (default: the fit radius Rf)"},
  {"--max-displacement", "D|none", POSITIONS, "clamp each point's motion to D model units (default Rf/2 per point; none: no clamp)"},
  {"--along-input-normals", "", POSITIONS, "move each point along its input normal instead of its Wavejet normal (for noisy inputs: first enhance-normals --gain 0, then this on its output)"},
  {"--consistent-normals", "", POSITIONS | NORMAL_FILTER, "leave out the neighbors whose normal points more than 90 degrees away from the point's (the other side of a thin part, e.g. ears); the default for a mesh"},
  {"--all-neighbors", "", POSITIONS | NORMAL_FILTER, "keep every neighbor, whatever its normal (the default for a point set)"},
  {"--orient-toward", "X,Y,Z", FITS, "a point set without normals: orient the estimated normals toward this viewpoint (a scan's scanner position; on a closed object seen from one point the far side points inward), instead of by a minimum spanning tree; needed to stream such a point set"},
  {"--max-memory", "SIZE", FITS, "stream a point set larger than memory (PLY or XYZ): process it in spatial tiles sized for about SIZE of memory (e.g. 2G, 500M); the output is the same, byte for byte"},
  {"--tile-size", "N", FITS, "stream in tiles of at most N points (instead of --max-memory)"},
  {"--verify", "", FITS, "with --max-memory or --tile-size: also run the command in memory (it needs the memory of an in-memory run) and write OUT only if both give the same bytes"},
  {"--job", "DIR", FITS, "run one step of a streamed run (--stage), sharing the folder DIR with the other steps: how python3 -m wavejets.distributed spreads a run over processes or machines"},
  {"--stage", "STEP", FITS, "with --job: prepare (read IN, bin the first pass), tile:P:T (tile T of pass P), bin:P (bin pass P from pass P-1's tiles), write (OUT from the last pass's tiles), or write:C:N (part C of N of OUT's vertices; binary output of a binary PLY) then finish:N (OUT from the N parts)"},
  {"--threads", "N", FITS | RENDER, "worker threads (default: all cores; 1: sequential, same results)"},
  {"--ascii", "", FITS, "write ASCII PLY (default: binary little-endian PLY, doubles)"},
  {"--width", "W", RENDER, "image width in pixels, all panels together (default 800 per panel)"},
  {"--height", "H", RENDER, "image height in pixels (default 800)"},
  {"--view", "X,Y,Z", RENDER, "direction from the object toward the camera, orthographic (default 0,0,1)"},
  {"--up", "X,Y,Z", RENDER, "world direction shown upward (default 0,1,0)"},
  {"--splat", "F", RENDER, "splat radius of a point set in average point spacings (default 1.2)"},
  {"--color-by", "NAME", RENDER, "color by a scalar PLY property, blue < 0 < red (e.g. mean_curvature)"},
  {"--compare", "", RENDER, "render A and B (up to 8 inputs: A B C ... OUT.png) side by side with the same camera"},
  {"--quiet", "", FITS | RENDER, "no progress bar and no summary (errors are still printed)"},
  {"--help", "", FITS | RENDER, "show this help (-h)"},
};

const Command_info* find_command(const std::string& name)
{
  for(const Command_info& c : commands)
    if(name == c.name) return &c;
  return nullptr;
}

void print_flags(std::ostream& os, unsigned bit)
{
  for(const Flag_info& f : flags)
    if(f.commands & bit) {
      std::string lhs = std::string("  ") + f.name + (f.arg[0] ? std::string(" ") + f.arg : std::string());
      os << std::left << std::setw(28) << lhs << " " << f.help << "\n";
    }
}

void print_global_help(std::ostream& os)
{
  os << "Usage: wavejets <command> IN OUT [flags]    (wavejets <command> --help for its flags)\n\n"
        "Wavejet surface fitting and detail enhancement of point sets and meshes (CGAL Wavejets package).\n"
        "IN: a point set (.xyz .pwn, or .ply .off without faces) or a mesh (.off .obj, or .ply with faces;\n"
        "faces are copied as they are). Normals are used when present; else a mesh takes those of its\n"
        "faces and a point set's are estimated (Wavejet normals, oriented by a minimum spanning tree).\n"
        "OUT.ply keeps every input point, in input order, with its normal and the input's other\n"
        "properties, and a mesh's faces; a mesh can also be written as OUT.off or OUT.obj.\n\n"
        "Commands:\n";
  for(const Command_info& c : commands)
    os << "  " << std::left << std::setw(18) << c.name << " " << c.summary << "\n";
  os << "\nFlags of the fitting commands:\n";
  print_flags(os, NORMALS | CURVATURE);
  os << "  (enhance-positions, enhance-normals also take --gain and --evaluation-radius;\n"
        "   enhance-positions also --max-displacement; render has its own flags)\n"
        "  --version                  print the version\n\n"
        "Exit status: 0 success, 1 unreadable or invalid input / unwritable output (nothing written),\n"
        "2 bad command line. Points with NaN or infinite coordinates are rejected (exit 1).\n";
}

void print_command_help(std::ostream& os, const Command_info& c)
{
  std::string summary = c.summary;
  summary[0] = char(std::toupper(static_cast<unsigned char>(summary[0])));
  os << "Usage: wavejets " << c.name << " " << c.synopsis << " [flags]\n\n" << summary << ".\n";
  switch(c.bit) {
    case NORMALS:
      os << "Writes the Wavejet normal of every point (nx ny nz) and fitted (uchar, 1 where a Wavejet was fitted).\n";
      break;
    case CURVATURE:
      os << "Writes, per point (double): mean_curvature, gaussian_curvature, k1, k2 (k1 >= k2), k1_dir_x/y/z,\n"
            "k2_dir_x/y/z (unit principal directions), quality (= mean_curvature, for MeshLab's color by\n"
            "quality), and fitted (uchar). Signs follow the normals: H < 0 where the surface bends away from\n"
            "the normal (convex parts with outward normals). Unfitted points get 0 and fitted = 0.\n";
      break;
    case POSITIONS:
      os << "Writes the moved points, their normals re-estimated on the moved points (oriented like the\n"
            "input), and fitted (uchar). Unfitted points do not move.\n";
      break;
    case NORMAL_FILTER:
      os << "Writes the filtered normals (positions unchanged) and fitted (uchar). Unfitted points keep\n"
            "their normal.\n";
      break;
    case RENDER:
      os << "Orthographic view, one fixed light, z-buffered. A mesh is drawn as triangles with smooth shading\n"
            "(its normals, else those of its faces); a point set as splats on the points' tangent planes, shaded\n"
            "by the normals (estimated when the input has none). The picture is framed on the bounding box of\n"
            "all inputs (one camera for both panels of --compare).\n";
      break;
  }
  os << "\nFlags:\n";
  print_flags(os, c.bit);
  if(c.bit & FITS)
    os << "\nNeighborhoods: by default the 40 nearest neighbors (1.5 x the coefficients above order 6): Rf\n"
          "follows the density, so non-uniform samplings are fitted everywhere; --k N: N nearest; --radius\n"
          "(with or without --k): a fixed radius; --radius-factor F: a radius of F x the average spacing;\n"
          "--k auto: each point's own k; --k, --radius, --order NAME: each point's own, from the input's\n"
          "property NAME (e.g. the scale_k that --k auto wrote).\n";
}

// ------------------------------------------------------------------------------------------------
// Parsed command line.
struct Options
{
  const Command_info* command = nullptr;
  std::vector<std::string> files;
  bool has_k = false;
  bool auto_k = false;                     // --k auto: wavejet_estimate_scales() per point
  unsigned int k = 0;
  std::string k_column, radius_column, order_column;   // --k, --radius, --order given a property's name
  double radius = 0., radius_factor = 0.;  // radius_factor 0: not given
  std::size_t order = 0;                 // 0: the command's default
  bool has_gain = false;
  std::complex<double> gain = CGAL::Wavejets::default_filter_gain;
  double evaluation_radius = 0.;
  bool has_clamp = false;
  double max_displacement = 0.;          // infinity: no clamp
  int threads = 0;
  bool ascii = false, quiet = false, compare = false, along_input_normals = false;
  bool verify = false;                     // a streamed run compared with the in-memory one
  std::optional<bool> consistent_normals;             // not given: on for a mesh (normals from its faces), off for a point set
  std::optional<std::array<double, 3> > viewpoint;   // --orient-toward
  double max_memory = 0.;                  // bytes, 0: not given
  std::size_t tile_size = 0;               // 0: not given (no streaming unless --max-memory)
  std::string job, stage;                  // one step of a staged streamed run (--job, --stage)
  int width = 0, height = 800;
  wavejets_demo::Vec3 view = {{0., 0., 1.}}, up = {{0., 1., 0.}};
  double splat = 1.2;
  std::string color_by;
};

double parse_number(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if(text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
    throw Usage_error(flag + " expects a finite number, got '" + text + "'");
  return v;
}

long parse_integer(const std::string& flag, const std::string& text, long lo, long hi)
{
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if(text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < lo || v > hi)
    throw Usage_error(flag + " expects an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + text + "'");
  return v;
}

/// A property's name (--k, --radius, --order COLUMN): it starts with a letter or an underscore.
bool is_column_name(const std::string& text)
{
  return !text.empty() && (std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_');
}

std::vector<double> parse_list(const std::string& flag, const std::string& text)
{
  std::vector<double> values;
  std::size_t start = 0;
  while(true) {
    const std::size_t comma = text.find(',', start);
    values.push_back(parse_number(flag, text.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if(comma == std::string::npos) break;
    start = comma + 1;
  }
  return values;
}

// A memory size: bytes, or a number followed by K, M, G or T (powers of 1024; a trailing B is allowed).
double parse_size(const std::string& flag, const std::string& text)
{
  std::string number = text, unit;
  while(!number.empty() && std::isalpha(static_cast<unsigned char>(number.back()))) {
    unit.insert(unit.begin(), char(std::toupper(static_cast<unsigned char>(number.back()))));
    number.pop_back();
  }
  if(unit.size() == 2 && unit[1] == 'B') unit.pop_back();
  const double scale = unit.empty() || unit == "B" ? 1. : unit == "K" ? 1024. : unit == "M" ? 1024. * 1024.
                     : unit == "G" ? 1024. * 1024. * 1024. : unit == "T" ? 1024. * 1024. * 1024. * 1024. : 0.;
  if(scale == 0.) throw Usage_error(flag + " expects a size such as 2G, 500M or 4000000000, got '" + text + "'");
  const double v = parse_number(flag, number) * scale;
  if(!(v > 0)) throw Usage_error(flag + " must be > 0");
  return v;
}

wavejets_demo::Vec3 parse_vector(const std::string& flag, const std::string& text)
{
  const std::vector<double> v = parse_list(flag, text);
  if(v.size() != 3) throw Usage_error(flag + " expects X,Y,Z, got '" + text + "'");
  if(v[0] == 0 && v[1] == 0 && v[2] == 0) throw Usage_error(flag + " must not be the zero vector");
  return {{v[0], v[1], v[2]}};
}

Options parse_command_line(const std::vector<std::string>& args)
{
  Options o;
  if(args.empty()) throw Usage_error("no command given (wavejets --help lists them)");
  if(args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    const Command_info* c = args.size() > 1 ? find_command(args[1]) : nullptr;
    if(c) print_command_help(std::cout, *c); else print_global_help(std::cout);
    std::exit(EXIT_SUCCESS);
  }
  if(args[0] == "--version") { std::cout << version << "\n"; std::exit(EXIT_SUCCESS); }
  o.command = find_command(args[0]);
  if(!o.command) throw Usage_error("unknown command '" + args[0] + "' (wavejets --help lists them)");
  const unsigned bit = o.command->bit;

  for(std::size_t i = 1; i < args.size(); ++i) {
    std::string a = args[i], value;
    if(a == "-h") a = "--help";
    if(a == "-k") a = "--k";
    if(a == "-r") a = "--radius";
    if(a == "-q") a = "--quiet";
    if(a.size() < 2 || a[0] != '-' || (a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.'))) {
      o.files.push_back(a);
      continue;
    }
    const std::size_t eq = a.find('=');
    bool inline_value = false;
    if(eq != std::string::npos) { value = a.substr(eq + 1); a = a.substr(0, eq); inline_value = true; }
    const Flag_info* f = nullptr;
    for(const Flag_info& g : flags)
      if(a == g.name) f = &g;
    if(!f) throw Usage_error("unknown flag " + a + " (wavejets " + o.command->name + " --help lists the flags)");
    if(!(f->commands & bit)) throw Usage_error(std::string(f->name) + " does not apply to " + o.command->name);
    if(f->arg[0] && !inline_value) {
      if(i + 1 >= args.size()) throw Usage_error(a + " needs a value (" + f->arg + ")");
      value = args[++i];
    }
    if(!f->arg[0] && inline_value) throw Usage_error(a + " takes no value");

    if(a == "--help") { print_command_help(std::cout, *o.command); std::exit(EXIT_SUCCESS); }
    else if(a == "--k" && value == "auto") { o.auto_k = true; o.has_k = false; o.k_column.clear(); }
    else if(a == "--k" && is_column_name(value)) { o.k_column = value; o.auto_k = false; o.has_k = false; }
    else if(a == "--k") { o.k = unsigned(parse_integer(a, value, 0, 100000)); o.has_k = true; o.auto_k = false; o.k_column.clear(); }
    else if(a == "--radius" && is_column_name(value)) { o.radius_column = value; o.radius = 0.; }
    else if(a == "--radius") {
      o.radius_column.clear();
      o.radius = parse_number(a, value);
      if(o.radius <= 0) throw Usage_error("--radius must be > 0");
    }
    else if(a == "--radius-factor") {
      o.radius_factor = parse_number(a, value);
      if(o.radius_factor <= 0) throw Usage_error("--radius-factor must be > 0");
    }
    else if(a == "--order" && is_column_name(value)) { o.order_column = value; o.order = 0; }
    else if(a == "--order") { o.order = std::size_t(parse_integer(a, value, 1, 20)); o.order_column.clear(); }
    else if(a == "--gain") {
      const std::vector<double> g = parse_list(a, value);
      if(g.size() > 2) throw Usage_error("--gain expects G or RE,IM, got '" + value + "'");
      o.gain = std::complex<double>(g[0], g.size() > 1 ? g[1] : 0.);
      if(bit == POSITIONS && o.gain.imag() != 0) throw Usage_error("enhance-positions takes a real gain");
      o.has_gain = true;
    }
    else if(a == "--evaluation-radius") {
      o.evaluation_radius = parse_number(a, value);
      if(o.evaluation_radius <= 0) throw Usage_error("--evaluation-radius must be > 0");
    }
    else if(a == "--max-displacement") {
      o.has_clamp = true;
      if(value == "none") o.max_displacement = std::numeric_limits<double>::infinity();
      else {
        o.max_displacement = parse_number(a, value);
        if(o.max_displacement <= 0) throw Usage_error("--max-displacement must be > 0 (or none)");
      }
    }
    else if(a == "--orient-toward") {
      const std::vector<double> v = parse_list(a, value);
      if(v.size() != 3) throw Usage_error(a + " expects X,Y,Z, got '" + value + "'");
      o.viewpoint = std::array<double, 3>{{v[0], v[1], v[2]}};
    }
    else if(a == "--max-memory") o.max_memory = parse_size(a, value);
    else if(a == "--tile-size") o.tile_size = std::size_t(parse_integer(a, value, 1, 2000000000L));
    else if(a == "--threads") o.threads = int(parse_integer(a, value, 1, 4096));
    else if(a == "--job") o.job = value;
    else if(a == "--stage") o.stage = value;
    else if(a == "--ascii") o.ascii = true;
    else if(a == "--verify") o.verify = true;
    else if(a == "--along-input-normals") o.along_input_normals = true;
    else if(a == "--consistent-normals") o.consistent_normals = true;
    else if(a == "--all-neighbors") o.consistent_normals = false;
    else if(a == "--quiet") o.quiet = true;
    else if(a == "--width") o.width = int(parse_integer(a, value, 8, 16384));
    else if(a == "--height") o.height = int(parse_integer(a, value, 8, 16384));
    else if(a == "--view") o.view = parse_vector(a, value);
    else if(a == "--up") o.up = parse_vector(a, value);
    else if(a == "--splat") {
      o.splat = parse_number(a, value);
      if(o.splat <= 0) throw Usage_error("--splat must be > 0");
    }
    else if(a == "--color-by") o.color_by = value;
    else if(a == "--compare") o.compare = true;
  }
  // render --compare takes 2 to 8 inputs (side by side, one camera), then OUT.png.
  if(o.compare ? (o.files.size() < 3 || o.files.size() > 9) : o.files.size() != 2)
    throw Usage_error(std::string(o.command->name) + " expects " + o.command->synopsis + " (got " +
                      std::to_string(o.files.size()) + " file names)");
  const std::string out_ext = lower_extension(o.files.back());
  if(bit == RENDER && out_ext != "png") throw Usage_error("the output of render must be a .png file: " + o.files.back());
  if(bit != RENDER && out_ext != "ply" && out_ext != "off" && out_ext != "obj")
    throw Usage_error("the output must be a .ply file (or .off / .obj for a mesh input): " + o.files.back());
  if((o.radius > 0 || !o.radius_column.empty()) && o.radius_factor > 0)
    throw Usage_error("give --radius or --radius-factor, not both");
  if(o.auto_k && (!o.radius_column.empty() || !o.order_column.empty()))
    throw Usage_error("--k auto chooses numbers of neighbors for one order: not with a --radius or --order column");
  if(o.max_memory > 0 && o.tile_size > 0) throw Usage_error("give --max-memory or --tile-size, not both");
  if(o.job.empty() != o.stage.empty()) throw Usage_error("--job and --stage go together");
  if(o.width == 0) o.width = 800 * int(o.files.size() - 1);   // 800 per panel
  return o;
}

// ------------------------------------------------------------------------------------------------
// Progress bar on stderr (only when it is a terminal): the package calls it from a worker thread
// under Parallel_tag, so it only touches its own state, under a mutex.
class Progress
{
public:
  explicit Progress(bool enabled) : enabled_(enabled && wavejets_demo::stderr_is_terminal()) {}
  std::function<bool(double)> stage(const std::string& label)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    label_ = label;
    start_ = Clock::now();
    last_ = -1;
    return [this](double x) { draw(x); return true; };
  }
  void done()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if(drawn_) std::fprintf(stderr, "\r%*s\r", 72, "");
    drawn_ = false;
  }
private:
  void draw(double x)
  {
    if(!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    const double t = seconds_since(start_);
    const int percent = int(100. * std::max(0., std::min(1., x)));
    if(t < 0.3 || percent == last_) return;   // short runs stay silent
    last_ = percent;
    const int width = 30, full = percent * width / 100;
    std::string bar(std::size_t(full), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%-22s [%s] %3d%%  %5.1f s", label_.c_str(), bar.c_str(), percent, t);
    std::fflush(stderr);
    drawn_ = true;
  }
  bool enabled_, drawn_ = false;
  std::mutex mutex_;
  std::string label_;
  Clock::time_point start_;
  int last_ = -1;
};

double average_spacing(const Point_set& points)
{
  if(points.size() < 3) return 0.; // CGAL::compute_average_spacing requires k >= 2 neighbors
  const unsigned int k = unsigned(std::min<std::size_t>(6, points.size() - 1));
  return CGAL::compute_average_spacing<Concurrency_tag>(points, k, CGAL::parameters::point_map(points.point_map()));
}

// ------------------------------------------------------------------------------------------------
// Fitting commands.
struct Neighborhood
{
  unsigned int k = 0;
  double radius = 0.;
  bool automatic = false;  // --k auto: k per point (k is then the largest size)
  std::optional<wavejets_demo::Per_point_scales> columns;   // --k, --radius or --order given a column's name
  std::string description;
};

bool has_scale_columns(const Options& o)
{
  return !o.k_column.empty() || !o.radius_column.empty() || !o.order_column.empty();
}

/// The values of the property `name` of `points` (--k, --radius or --order COLUMN, `flag`) as T, checked:
/// finite, in [0, highest], whole numbers if `whole`. Their largest value goes to `largest`, and a phrase
/// to `description` ("k from 'scale_k' (10 to 160)").
template <class T>
std::shared_ptr<const std::vector<T> > read_scale_column(const Point_set& points, const std::string& name, const std::string& flag,
                                                         double highest, bool whole, const std::string& path, double& largest,
                                                         std::vector<std::string>& description)
{
  const std::optional<std::vector<double> > column = wavejets_demo::numeric_column(points, name);
  if(!column) throw File_error(path + ": has no numeric property '" + name + "' (--" + flag + " " + name + ")");
  auto values = std::make_shared<std::vector<T> >();
  double lowest = std::numeric_limits<double>::infinity();
  largest = 0.;
  for(std::size_t i = 0; i < column->size(); ++i) {
    const double v = (*column)[i];
    if(!(std::isfinite(v) && v >= 0 && v <= highest && (!whole || v == std::floor(v))))
      throw File_error(path + ": property '" + name + "' (--" + flag + "): point " + std::to_string(i) + " has " + format(v) +
                       ", expected " + (whole ? "an integer in [0, " + std::to_string(long(highest)) + "]" : "a finite number >= 0"));
    values->push_back(T(v));
    lowest = std::min(lowest, v);
    largest = std::max(largest, v);
  }
  if(!column->empty())
    description.push_back(flag + " from '" + name + "' (" + format(lowest) + " to " + format(largest) + ")");
  return values;
}

/// --k, --radius, --order COLUMN: each point's values, and the order whose default k suits every point.
wavejets_demo::Per_point_scales read_scale_columns(const Options& o, const Point_set& points, const std::string& path,
                                                   std::size_t& highest_order, std::string& description)
{
  wavejets_demo::Per_point_scales scales;
  std::vector<std::string> parts;
  double largest = 0.;
  if(!o.k_column.empty())
    scales.k.values = read_scale_column<unsigned int>(points, o.k_column, "k", 100000, true, path, largest, parts);
  if(!o.radius_column.empty())
    scales.radius.values = read_scale_column<double>(points, o.radius_column, "radius",
                                                     std::numeric_limits<double>::max(), false, path, largest, parts);
  if(!o.order_column.empty()) {
    scales.order.values = read_scale_column<unsigned int>(points, o.order_column, "order", 20, true, path, largest, parts);
    highest_order = std::max(highest_order, std::size_t(largest));
  }
  description = "per point (0: the above)";
  for(std::size_t i = 0; i < parts.size(); ++i) description += (i ? ", " : ": ") + parts[i];
  return scales;
}

Neighborhood choose_neighborhood(const Options& o, std::size_t order, const Point_set& points, const std::string& path)
{
  Neighborhood n;
  if(o.auto_k) {
    if(o.radius > 0 || o.radius_factor > 0) throw Usage_error("--k auto chooses numbers of neighbors: not with --radius or --radius-factor");
    const std::vector<unsigned int> ladder = CGAL::Wavejets::default_neighborhood_sizes(order);
    n.k = ladder.back();
    n.automatic = true;
    std::string sizes;
    for(unsigned int k : ladder) sizes += (sizes.empty() ? "" : ", ") + std::to_string(k);
    n.description = "nearest neighbors, per point among " + sizes + " (--k auto)";
    return n;
  }
  std::size_t highest_order = order;   // the default k suits every point's order
  std::string per_point;
  if(has_scale_columns(o)) n.columns = read_scale_columns(o, points, path, highest_order, per_point);
  if(!o.radius_column.empty()) {
    n.k = o.has_k ? o.k : 0;
    const std::vector<double>& radius = *n.columns->radius.values;
    const auto zero = std::find(radius.begin(), radius.end(), 0.);
    if(zero != radius.end() && n.k < 2)
      throw File_error(path + ": property '" + o.radius_column + "' (--radius): point " + std::to_string(zero - radius.begin()) +
                       " has 0 (its k nearest neighbors): give --k N (N >= 2) for such points");
    n.description = "the neighbors in each point's radius" +
                    std::string(n.k ? ", at most " + std::to_string(n.k) + ", else its " + std::to_string(n.k) + " nearest" : "");
  } else if(o.radius > 0) {
    n.radius = o.radius;
    n.k = o.has_k ? o.k : 0;
    n.description = "radius " + format(n.radius) + (n.k ? ", at most " + std::to_string(n.k) + " neighbors" : "");
  } else if(o.radius_factor > 0) {
    if(points.size() < 3)
      throw File_error(path + ": " + std::to_string(points.size()) + " points: too few to choose a neighborhood radius "
                       "from the average spacing (give --k or --radius)");
    const double spacing = average_spacing(points);
    if(!(spacing > 0)) throw File_error(path + ": every point coincides with its nearest neighbors: no neighborhood radius can be "
                                       "chosen from the average spacing (give --k or --radius)");
    n.radius = o.radius_factor * spacing;
    n.k = o.has_k ? o.k : 0;
    n.description = "radius " + format(n.radius) + " (" + format(o.radius_factor) + " x average spacing " + format(spacing) + ")" +
                    (n.k ? ", at most " + std::to_string(n.k) + " neighbors" : "");
  } else {
    if(o.has_k && o.k < 2) throw Usage_error("--k must be >= 2 without --radius");
    n.k = o.has_k ? o.k : unsigned(CGAL::Wavejets::default_number_of_neighbors(highest_order));
    n.description = std::to_string(n.k) + " nearest neighbors" + (o.has_k ? "" : " (default)");
  }
  if(n.columns) n.description += "; " + per_point;
  return n;
}

struct Run_log
{
  std::vector<std::string> lines;   // joined into the summary paragraph
  double fit_seconds = 0.;
};

std::string format_point(const std::array<double, 3>& p)
{
  return "(" + format(p[0]) + ", " + format(p[1]) + ", " + format(p[2]) + ")";
}

// The summary of the estimation of the normals of a point set that has none.
std::string bare_normals_text(std::size_t order, const CGAL::Wavejets::Processing_report& r, const std::string& orientation)
{
  return "The input has no normals: estimated them (order " + std::to_string(order) + "; " +
         std::to_string(r.number_of_unfitted_points) + " not fitted) and " + orientation + ".";
}

// The summary of the normals of enhance-positions' result.
std::string result_normals_text(const CGAL::Wavejets::Processing_report& r)
{
  return "normals re-estimated on the moved points (" + std::to_string(r.number_of_unfitted_points) + " not fitted)";
}

const char* command_stage_label(unsigned bit)
{
  return bit == NORMALS ? "normals" : bit == CURVATURE ? "curvature" : bit == POSITIONS ? "enhancing positions" : "enhancing normals";
}

// Estimates the normals of a point set that has none (its normal map is zero): oriented toward
// --orient-toward's viewpoint, else by a minimum spanning tree (mst_orient_normals reorders its
// range, so it runs on a copy that remembers the indices). Writes `fitted` when it has a map.
template <class Scales>
void estimate_oriented_normals(Point_set& points, const wavejets_demo::Fit_settings& s, std::size_t order,
                               const wavejets_demo::Uchar_bool_map& fitted, Progress& progress, Run_log& log,
                               const Scales& scales)
{
  const Clock::time_point t0 = Clock::now();
  const CGAL::Wavejets::Processing_report r = wavejets_demo::estimate_normals_of_bare_points(points, s, order, fitted,
    progress.stage("estimating normals"), scales);
  progress.done();
  std::string orientation;
  if(s.viewpoint)
    orientation = "oriented them toward the viewpoint " + format_point(*s.viewpoint);
  else {
    typedef std::tuple<Point, Vector, std::size_t> Item;
    std::vector<Item> items;
    items.reserve(points.size());
    std::size_t i = 0;
    for(Point_set::Index idx : points) items.emplace_back(points.point(idx), points.normal(idx), i++);
    const auto first_unoriented = CGAL::mst_orient_normals(items, 18,
      CGAL::parameters::point_map(CGAL::Nth_of_tuple_property_map<0, Item>())
        .normal_map(CGAL::Nth_of_tuple_property_map<1, Item>()));
    const std::size_t unoriented = std::size_t(items.end() - first_unoriented);
    std::vector<Point_set::Index> keys(points.begin(), points.end());
    for(const Item& it : items) points.normal(keys[std::get<2>(it)]) = std::get<1>(it);
    orientation = "oriented them by a minimum spanning tree (18 neighbors; " + std::to_string(unoriented) +
                  " could not be oriented)";
  }
  log.fit_seconds += seconds_since(t0);
  log.lines.push_back(bare_normals_text(order, r, orientation));
}

std::string percentiles(const Point_set& points, Point_set::Property_map<double> m,
                        Point_set::Property_map<unsigned char> fitted)
{
  std::vector<double> v;
  for(Point_set::Index i : points) if(fitted[i]) v.push_back(m[i]);
  if(v.empty()) return "n/a";
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return format(v[std::size_t(q * double(v.size() - 1))], 3); };
  return at(0.05) + " / " + at(0.5) + " / " + at(0.95);
}

// Sets the normals of a mesh's vertices to the area-weighted normals of their faces (adds the normal
// map if needed). A vertex without a face of non-zero area keeps its normal (or gets none: zero);
// counted in `*without_face`. Returns whether some vertex got a normal.
bool set_face_normals(Point_set& points, const wavejets_demo::Faces& faces, std::size_t* without_face)
{
  std::vector<wavejets_demo::Vec3> xyz;
  xyz.reserve(points.size());
  for(Point_set::Index i : points) {
    const Point& p = points.point(i);
    xyz.push_back({{p.x(), p.y(), p.z()}});
  }
  const std::vector<wavejets_demo::Vec3> normals = wavejets_demo::vertex_normals(xyz, faces);
  if(!points.has_normal_map()) points.add_normal_map(Vector(0, 0, 0));
  std::size_t j = 0, missing = 0;
  for(Point_set::Index i : points) {
    const wavejets_demo::Vec3& n = normals[j++];
    if(n[0] == 0 && n[1] == 0 && n[2] == 0) ++missing;
    else points.normal(i) = Vector(n[0], n[1], n[2]);
  }
  if(without_face) *without_face = missing;
  if(missing == points.size() && !without_face) { points.remove_normal_map(); return false; }
  return missing < points.size();
}

// The library function behind a fitting command (its defaults are the command's).
CGAL::Wavejets::Point_set_function library_function(unsigned command_bit)
{
  typedef CGAL::Wavejets::Point_set_function F;
  return command_bit == NORMALS ? F::ESTIMATE_NORMALS : command_bit == CURVATURE ? F::ESTIMATE_CURVATURES
       : command_bit == POSITIONS ? F::ENHANCE_POSITIONS : F::ENHANCE_NORMALS;
}

std::string output_comment(const Options& o) { return std::string("wavejets ") + o.command->name + " of " + o.files[0]; }

std::string threads_text()
{
#ifdef CGAL_LINKED_WITH_TBB
  return "threads: " + std::to_string(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)) + ".";
#else
  return "threads: 1 (built without TBB).";
#endif
}

// What the command line asks of the fitting functions.
wavejets_demo::Fit_settings fit_settings(const Options& o, std::size_t order, const Neighborhood& n, bool consistent_normals)
{
  wavejets_demo::Fit_settings s;
  s.command = o.command->bit;
  s.k = n.k;
  s.radius = n.radius;
  s.order = order;
  s.gain = o.gain;
  s.evaluation_radius = o.evaluation_radius;
  s.has_clamp = o.has_clamp;
  s.max_displacement = o.max_displacement;
  s.along_input_normals = o.along_input_normals;
  s.consistent_normals = consistent_normals;
  s.viewpoint = o.viewpoint;
  return s;
}

// The summary of the command's own run (r), after its settings.
std::string command_text(const wavejets_demo::Fit_settings& s, const CGAL::Wavejets::Processing_report& r)
{
  const std::string order = std::to_string(s.order);
  const std::string evaluation = s.evaluation_radius > 0 ? format(s.evaluation_radius) : std::string("Rf");
  const std::string consistent = s.consistent_normals ? ", neighbors with consistent normals" : "";
  switch(s.command) {
    case NORMALS:
      return "Normals (order " + order + ", oriented like the input normals): " + report_text(r);
    case CURVATURE:
      return "Curvature (order " + order + "): " + report_text(r);
    case POSITIONS:
      return "Position enhancement (order " + order + ", gain " + format(s.gain.real()) + ", evaluation radius " + evaluation +
             ", clamp " + (!s.has_clamp ? std::string("Rf/2") : std::isinf(s.max_displacement) ? std::string("none") : format(s.max_displacement)) +
             (s.along_input_normals ? std::string(", along the input normals") : std::string()) + consistent + "): " + report_text(r);
    default: {
      const std::complex<double> g = s.gain;
      const std::string gain = g.imag() == 0 ? format(g.real()) : format(g.real()) + (g.imag() < 0 ? "" : "+") + format(g.imag()) + "i";
      return "Normal enhancement (order " + order + ", gain " + gain + ", evaluation radius " + evaluation + consistent + "): " +
             report_text(r);
    }
  }
}

// The summary of a streamed run (without timings: a staged run's, whose steps ran elsewhere).
std::string streamed_summary(const Options& o, const wavejets_demo::Fit_settings& s, const wavejets_demo::Streaming_settings& settings,
                             const Neighborhood& n, std::size_t order, const wavejets_demo::Streamed_run& run, double seconds)
{
  const unsigned bit = o.command->bit;
  std::ostringstream t;
  t << std::fixed << std::setprecision(2) << o.command->name << ": streamed a point set of " << run.points << " points from "
    << o.files[0] << " (" << run.format << ", " << (run.had_normals ? "with" : "without") << " normals) in tiles of at most "
    << settings.tile_size << " points (" << run.tiles << " tiles; " << run.rerun_points
    << " points fitted again with a larger halo); neighborhoods: " << n.description << "; ";
  if(o.job.empty()) t << threads_text() << " ";
  if(run.bare_normals) t << bare_normals_text(bit == NORMALS ? order : 2, *run.bare_normals, "oriented them toward the viewpoint " + format_point(*s.viewpoint)) << " ";
  if(run.command) {
    t << command_text(s, *run.command);
    if(run.result_normals) t << "; " << result_normals_text(*run.result_normals);
    t << ". ";
  }
  if(o.job.empty())
    t << "Reading and checking took " << run.scan_seconds << " s, binning " << run.binning_seconds << " s, fitting "
      << run.fit_seconds << " s, writing " << run.write_seconds << " s. ";
  t << "Wrote " << o.files[1] << " (" << (o.ascii ? "ASCII" : "binary little-endian") << " PLY, " << run.points
    << " points in input order, " << run.written_fitted << " of them fitted, properties: x y z";
  for(const std::string& p : run.columns) t << " " << p;
  t << (o.verify ? "; verified: the same bytes as the in-memory run)" : ")");
  if(o.job.empty()) t << "; total " << seconds << " s";
  t << ".";
  return t.str();
}

// One step of a staged streamed run (--job DIR --stage STEP).
int run_stage(const Options& o, const wavejets_demo::Fit_settings& s, const wavejets_demo::Streaming_settings& settings,
              const Neighborhood& n, std::size_t order, Progress& progress)
{
  const std::string& in_path = o.files[0];
  const std::string& out_path = o.files[1];
  const std::string& stage = o.stage;
  auto number = [&](const std::string& text) {
    if(text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
      throw Usage_error("--stage " + stage + ": expected prepare, tile:P:T, bin:P, write, write:C:N or finish:N");
    return std::size_t(std::stoull(text));
  };
  if(stage == "prepare") {
    const std::size_t passes = wavejets_demo::staged_prepare(in_path, o.job, s, settings);
    if(!o.quiet) std::cout << "prepared " << o.job << ": " << passes << " passes, " << wavejets_demo::staged_tiles(o.job, 0)
                           << " tiles in the first" << std::endl;
  } else if(stage.compare(0, 5, "tile:") == 0) {
    const std::size_t colon = stage.find(':', 5);
    if(colon == std::string::npos) throw Usage_error("--stage " + stage + ": expected tile:P:T");
    wavejets_demo::staged_tile(o.job, number(stage.substr(5, colon - 5)), number(stage.substr(colon + 1)), s, settings);
  } else if(stage.compare(0, 4, "bin:") == 0) {
    wavejets_demo::staged_bin(o.job, number(stage.substr(4)), s, settings);
  } else if(stage.compare(0, 6, "write:") == 0) {
    const std::size_t colon = stage.find(':', 6);
    if(colon == std::string::npos) throw Usage_error("--stage " + stage + ": expected write:C:N");
    wavejets_demo::staged_write_part(in_path, o.job, number(stage.substr(6, colon - 6)), number(stage.substr(colon + 1)), s, settings);
  } else if(stage == "write" || stage.compare(0, 7, "finish:") == 0) {
    const wavejets_demo::Streamed_run run =
      stage == "write" ? wavejets_demo::staged_write(in_path, out_path, o.job, s, settings, progress.stage("writing"))
                       : wavejets_demo::staged_finish(in_path, out_path, o.job, number(stage.substr(7)), s, settings);
    progress.done();
    if(!o.quiet) std::cout << streamed_summary(o, s, settings, n, order, run, 0.) << std::endl;
  } else number("");
  return EXIT_SUCCESS;
}

void compare_with_in_memory_run(const Options& o, const std::string& streamed, Progress& progress);
int run_fit_command_on_input(const Options& o, Progress& progress);

// A streamed run (--max-memory, --tile-size): a point set read in passes and fitted tile by tile;
// the same output file as in memory.
int run_streamed_command(const Options& o, Progress& progress)
{
  const Clock::time_point t0 = Clock::now();
  const std::string& in_path = o.files[0];
  const std::string& out_path = o.files[1];
  if(output_format(out_path) != Output_format::PLY) throw Usage_error("a streamed run writes a .ply file, not " + out_path);
  if(o.radius_factor > 0)
    throw Usage_error("--radius-factor needs the average spacing of the whole point set: give --k or --radius with " +
                      std::string(o.max_memory > 0 ? "--max-memory" : "--tile-size"));
  const unsigned bit = o.command->bit;
  const std::size_t order = o.order ? o.order : CGAL::Wavejets::function_defaults(library_function(bit)).order;
  if(o.auto_k) throw Usage_error("--k auto runs in memory: not with --max-memory, --tile-size or --job");
  if(has_scale_columns(o))
    throw Usage_error("--k, --radius or --order given a column's name run in memory: not with --max-memory, --tile-size or --job");
  const Neighborhood n = choose_neighborhood(o, order, Point_set(), in_path);
  const wavejets_demo::Fit_settings s = fit_settings(o, order, n, o.consistent_normals.value_or(false));
  wavejets_demo::Streaming_settings settings;
  settings.tile_size = o.tile_size > 0 ? o.tile_size : wavejets_demo::tile_size_for_memory(o.max_memory > 0 ? o.max_memory : 2e9);
  settings.ascii = o.ascii;
  settings.comment = output_comment(o);
  if(!o.job.empty()) {
    if(o.verify) throw Usage_error("--verify compares a whole streamed run: not with --job");
    return run_stage(o, s, settings, n, order, progress);
  }
  if(!o.verify) {
    const wavejets_demo::Streamed_run run = wavejets_demo::run_streamed(in_path, out_path, s, settings, progress.stage("streaming"));
    progress.done();
    if(!o.quiet) std::cout << streamed_summary(o, s, settings, n, order, run, seconds_since(t0)) << std::endl;
    return EXIT_SUCCESS;
  }
  // --verify: the streamed output under a temporary name, moved to OUT once the in-memory run wrote the same bytes.
  wavejets_demo::Output_file verified(out_path);
  const wavejets_demo::Streamed_run run =
    wavejets_demo::run_streamed(in_path, verified.temporary_path(), s, settings, progress.stage("streaming"));
  progress.done();
  compare_with_in_memory_run(o, verified.temporary_path(), progress);
  verified.commit();
  if(!o.quiet) std::cout << streamed_summary(o, s, settings, n, order, run, seconds_since(t0)) << std::endl;
  return EXIT_SUCCESS;
}

// --verify: runs the command of `o` in memory into a scratch file next to OUT and compares it with
// `streamed`, the streamed run's output; a difference is an error naming its first byte.
void compare_with_in_memory_run(const Options& o, const std::string& streamed, Progress& progress)
{
  Options in_memory = o;
  in_memory.max_memory = 0;
  in_memory.tile_size = 0;
  in_memory.verify = false;
  in_memory.quiet = true;
  // A free name next to OUT, ending in .ply as the in-memory writer needs; removed when this returns.
  const wavejets_demo::Output_file free_name(o.files[1]);
  in_memory.files[1] = free_name.temporary_path() + ".ply";
  struct Remove { const std::string& path; ~Remove() { std::remove(path.c_str()); } } remove_reference{in_memory.files[1]};
  run_fit_command_on_input(in_memory, progress);
  std::ifstream a(streamed, std::ios::binary), b(in_memory.files[1], std::ios::binary);
  std::vector<char> x(1 << 20), y(1 << 20);
  for(std::uint64_t at = 0;;) {
    a.read(x.data(), std::streamsize(x.size()));
    b.read(y.data(), std::streamsize(y.size()));
    const std::size_t n = std::size_t(a.gcount()), m = std::size_t(b.gcount());
    const std::size_t same = std::size_t(std::mismatch(x.begin(), x.begin() + std::ptrdiff_t(std::min(n, m)), y.begin()).first - x.begin());
    if(same < std::min(n, m) || n != m)
      throw File_error(o.files[1] + ": not written: the streamed output differs from the in-memory run from byte " +
                       std::to_string(at + same) + " on (a defect of the streamed run; please report it with the command)");
    if(n == 0) return;
    at += n;
  }
}

int run_fit_command_on_input(const Options& o, Progress& progress)
{
  if(o.max_memory > 0 || o.tile_size > 0 || !o.job.empty()) return run_streamed_command(o, progress);
  const Clock::time_point t0 = Clock::now();
  const std::string& in_path = o.files[0];
  const std::string& out_path = o.files[1];
  Input in = read_input(in_path);
  Point_set& points = in.points;
  if(!in.is_mesh() && output_format(out_path) != Output_format::PLY)
    throw Usage_error(in_path + " is a point set (no faces): write it as .ply, not " + out_path);
  const unsigned bit = o.command->bit;
  const std::size_t order = o.order ? o.order : CGAL::Wavejets::function_defaults(library_function(bit)).order;
  const Neighborhood n = choose_neighborhood(o, order, points, in_path);
  Run_log log;
  // A mesh without normals: its faces give oriented vertex normals (no estimation, no MST).
  if(in.is_mesh() && !in.had_normals && set_face_normals(points, in.faces, nullptr))
    log.lines.push_back("The input has no normals: used the area-weighted normals of its faces.");
  const bool bare = !points.has_normal_map();
  // A mesh's normals come from its oriented faces (or its file): neighbors on the other side of a
  // thin part (ears, fins, sheets) are left out by default; a point set's normals may be unoriented.
  const wavejets_demo::Fit_settings s = fit_settings(o, order, n, o.consistent_normals.value_or(in.is_mesh()));
  const wavejets_demo::Output_columns columns = wavejets_demo::add_output_columns(points, bit);
  // The fits, with each call's neighborhoods passed by `in_core` (In_core, or with --k auto the
  // per-point sizes).
  std::string what;
  auto fit = [&](const auto& in_core) {
    if(bare)   // for normals, this is the command; the others need normals first (order 2)
      estimate_oriented_normals(points, s, bit == NORMALS ? order : 2,
                                bit == NORMALS ? wavejets_demo::Uchar_bool_map{columns.fitted} : wavejets_demo::Uchar_bool_map{},
                                progress, log, in_core);
    if(bit != NORMALS || !bare) {
      const Clock::time_point t = Clock::now();
      const CGAL::Wavejets::Processing_report r =
        wavejets_demo::run_fit_command(points, s, columns, progress.stage(command_stage_label(bit)), in_core);
      progress.done();
      what = command_text(s, r);
      if(bit == CURVATURE) {
        const std::vector<Point_set::Property_map<double> >& c = columns.curvature;
        what += ". Over the fitted points, 5% / median / 95%: H " + percentiles(points, c[0], columns.fitted) + ", K " +
                percentiles(points, c[1], columns.fitted) + ", k1 " + percentiles(points, c[2], columns.fitted) + ", k2 " +
                percentiles(points, c[3], columns.fitted);
      } else if(bit == POSITIONS && in.is_mesh()) {
        // The normals of the moved mesh: from its faces (vertices without a face keep their Wavejet normal).
        std::size_t without_face = 0;
        set_face_normals(points, in.faces, &without_face);
        what += "; normals of the moved mesh from its faces (" + std::to_string(without_face) +
                " vertices without a face keep their Wavejet normal)";
      } else if(bit == POSITIONS) {
        const CGAL::Wavejets::Processing_report rn = wavejets_demo::estimate_normals_of_result(points, s,
          progress.stage("normals of the result"), in_core);
        progress.done();
        what += "; " + result_normals_text(rn);
      }
      what += ".";
      log.fit_seconds += seconds_since(t);
    }
  };
  if(n.automatic) {
    const Clock::time_point t = Clock::now();
    const wavejets_demo::Automatic_scales scales = wavejets_demo::estimate_scales(points, order, bit == CURVATURE,
                                                                                  progress.stage("choosing scales"));
    progress.done();
    log.lines.push_back(scales.summary);
    log.fit_seconds += seconds_since(t);
    fit(scales.tiling());
  } else if(n.columns)
    fit(*n.columns);
  else
    fit(wavejets_demo::In_core{});

  const Clock::time_point tw = Clock::now();
  write_output(points, in.faces, out_path, o.ascii, output_comment(o));
  const double write_seconds = seconds_since(tw);

  if(!o.quiet) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2);
    s << o.command->name << ": read ";
    if(in.is_mesh()) s << "a mesh of " << points.size() << " vertices and " << in.faces.size() << " faces";
    else s << "a point set of " << points.size() << " points";
    s << " from " << in_path << " (" << in.format << ", " << (in.had_normals ? "with" : "without") << " normals) in "
      << in.read_seconds << " s; neighborhoods: "
      << n.description << "; ";
    s << threads_text() << " ";
    for(const std::string& l : log.lines) s << l << " ";
    if(!what.empty()) s << what << " ";
    s << "Fitting took " << log.fit_seconds << " s. Wrote " << out_path << " (";
    const Output_format of = output_format(out_path);
    if(of == Output_format::PLY) {
      s << (o.ascii ? "ASCII" : "binary little-endian") << " PLY";
      if(in.is_mesh()) s << " mesh, " << points.size() << " vertices in input order and the " << in.faces.size() << " input faces";
      else s << ", " << points.size() << " points in input order";
      s << ", properties: x y z";
      for(const std::string& p : points.properties())
        if(p != "index" && p != "point") s << " " << (p == "normal" ? "nx ny nz" : p);
    } else
      s << (of == Output_format::OFF ? "OFF" : "OBJ") << " mesh, " << points.size() << " vertices in input order with "
        << "their normals and the " << in.faces.size() << " input faces; the other properties need a .ply output";
    s << ") in " << write_seconds << " s; total " << seconds_since(t0) << " s.";
    std::cout << s.str() << std::endl;
  }
  return EXIT_SUCCESS;
}

// The package's parameter checks throw std::invalid_argument ("wavejet_xxx: message"): report
// them as a bad command line, naming the input file they were applied to.
int run_fit_command(const Options& o, Progress& progress)
{
  try {
    return run_fit_command_on_input(o, progress);
  } catch(const std::invalid_argument& e) { throw Usage_error(o.files[0] + ": " + e.what()); }
}

// ------------------------------------------------------------------------------------------------
// Rendering.
wavejets_demo::Cloud to_cloud(const std::string& path, const Options& o, Progress& progress)
{
  Input in = read_input(path);
  Point_set& points = in.points;
  wavejets_demo::Cloud c;
  c.spacing = average_spacing(points);
  c.faces = in.faces;
  if(in.is_mesh() && !points.has_normal_map()) set_face_normals(points, in.faces, nullptr);
  if(!points.has_normal_map()) {   // shading needs normals; their orientation does not matter
    points.add_normal_map(Vector(0, 0, 0));
    try {
      CGAL::wavejet_estimate_normals<Concurrency_tag>(points, std::min<unsigned>(18, unsigned(points.size() - 1)),
        WP::order(std::size_t(2)).callback(progress.stage("normals for shading")).point_map(points.point_map()).normal_map(points.normal_map()));
    } catch(const std::invalid_argument& e) {   // e.g. "needs k >= 2": too few points to shade
      throw File_error(path + ": cannot estimate normals for shading (" + e.what() + ")");
    }
    progress.done();
  }
  if(!o.color_by.empty()) {
    std::optional<std::vector<double> > column = wavejets_demo::numeric_column(points, o.color_by);
    if(!column) throw File_error(path + ": has no scalar property '" + o.color_by + "'");
    c.scalar = std::move(*column);
  }
  for(Point_set::Index i : points) {
    const Point& p = points.point(i);
    const Vector& n = points.normal(i);
    c.points.push_back({{p.x(), p.y(), p.z()}});
    c.normals.push_back({{n.x(), n.y(), n.z()}});
  }
  return c;
}

int run_render(const Options& o, Progress& progress)
{
  const Clock::time_point t0 = Clock::now();
  std::vector<wavejets_demo::Cloud> clouds;
  for(std::size_t i = 0; i + 1 < o.files.size(); ++i) clouds.push_back(to_cloud(o.files[i], o, progress));
  std::vector<const wavejets_demo::Cloud*> pointers;
  for(const wavejets_demo::Cloud& c : clouds) pointers.push_back(&c);
  wavejets_demo::View_options view;
  view.width = o.width;
  view.height = o.height;
  view.view = o.view;
  view.up = o.up;
  view.splat = o.splat;
  wavejets_demo::Image image;
  try {
    image = wavejets_demo::render(pointers, view);
  } catch(const std::invalid_argument& e) { throw Usage_error(e.what()); }
  const std::string& out_path = o.files.back();
  {
    wavejets_demo::Output_file out(out_path);
    try {
      wavejets_demo::write_png(image, out.temporary_path());
    } catch(const std::exception& e) { throw File_error(out_path + ": " + e.what()); }
    out.commit();
  }
  if(!o.quiet) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << "render: ";
    auto what = [](const wavejets_demo::Cloud& c) {
      return c.faces.empty() ? std::to_string(c.points.size()) + " points as splats"
                             : "a mesh of " + std::to_string(c.faces.size()) + " faces";
    };
    if(clouds.size() == 1) s << "drew " << what(clouds[0]) << " of " << o.files[0];
    else if(clouds.size() == 2)
      s << "compared " << o.files[0] << " (left, " << what(clouds[0]) << ") with " << o.files[1]
        << " (right, " << what(clouds[1]) << ")";
    else {
      s << "compared, left to right,";
      for(std::size_t i = 0; i < clouds.size(); ++i) s << (i ? "; " : " ") << o.files[i] << " (" << what(clouds[i]) << ")";
    }
    s << "; wrote " << out_path << " (" << image.width << " x " << image.height << " PNG) in " << seconds_since(t0) << " s.";
    std::cout << s.str() << std::endl;
  }
  return EXIT_SUCCESS;
}

} // namespace

int wavejets_demo::run_wavejets_tool(const std::vector<std::string>& args)
{
  std::string input;   // the first input file, named by the errors that do not name one themselves
  try {
    const Options o = parse_command_line(args);
    if(!o.files.empty()) input = o.files[0] + ": ";
#ifdef CGAL_LINKED_WITH_TBB
    std::unique_ptr<tbb::global_control> threads;
    if(o.threads > 0)
      threads.reset(new tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(o.threads)));
#endif
    Progress progress(!o.quiet);
    return o.command->bit == RENDER ? run_render(o, progress) : run_fit_command(o, progress);
  } catch(const Usage_error& e) {
    std::cerr << "wavejets: error: " << e.what() << std::endl;
    return 2;
  } catch(const File_error& e) {
    std::cerr << "wavejets: error: " << e.what() << std::endl;
    return 1;
  } catch(const std::invalid_argument& e) {   // the package's parameter checks (normally caught above)
    std::cerr << "wavejets: error: " << input << e.what() << std::endl;
    return 2;
  } catch(const std::exception& e) {
    std::cerr << "wavejets: error: " << input << e.what() << std::endl;
    return 1;
  }
}
