// See streaming.h. A streamed run, in passes over files, never holding the whole point set:
//  1. scan: IN is read in chunks (CGAL's own reader on each chunk, so that every value is the
//     in-core one; a binary little-endian PLY of float or double coordinates is read directly, to
//     the same values), checked as in core (NaN, coinciding points, normals), and copied as records
//     (index, position, normal, fitted, curvature) into a scratch file (read directly: read again);
//  2. per pass of the library (normals of a point set without normals; the command; for
//     enhance-positions the normals of the moved points): a histogram of the records on a grid,
//     tiles as median splits of the grid's cells, the records binned by cell (a tile's cells
//     contiguous), then per tile: the points within its halo are read back in global order and
//     the library function runs on them with Wavejets::parameters::tile(); the points whose
//     neighborhood reaches past the halo are run again with a halo twice as large. Every pass
//     writes one record per point, tile after tile, each tile's records in index order;
//  3. write: IN is read again in chunks, each chunk gets its records (a merge of the tiles' sorted
//     runs) and is written by CGAL's PLY writer (or, where that gives the same bytes, directly);
//     the first header (its vertex count set to the whole count) and the bodies make the file the
//     in-core run writes, byte for byte. Binary output of a binary PLY is written in parts, each at
//     its place in the file.
#include "streaming.h"
#include "platform.h"

#include <CGAL/Point_set_3/IO.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/Wavejets/internal/tiled_driver.h> // estimated_halo
#include <CGAL/for_each.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/parallel_sort.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <future>
#include <iostream>
#include <limits>
#include <numeric>
#include <sstream>

namespace wavejets_demo {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Chunks of at most this many points are read and written at a time: 65,536, or the environment's
// WAVEJETS_CHUNK_POINTS (a test's knob: any size gives the same output, and small ones put chunk
// boundaries into small inputs).
std::size_t chunk_points()
{
  const char* v = std::getenv("WAVEJETS_CHUNK_POINTS");
  const long long n = v ? std::atoll(v) : 0;
  return n > 0 ? std::size_t(n) : std::size_t(1) << 16;
}

bool machine_is_little_endian()
{
  const std::uint16_t one = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &one, 1);
  return first_byte == 1;
}

// ------------------------------------------------------------------------------------------------
// The input, chunk by chunk.
class Input_chunks
{
public:
  explicit Input_chunks(const std::string& path) : path_(path), is_(path, std::ios::binary)
  {
    const std::string ext = lower_extension(path);
    if(ext != "ply" && ext != "xyz" && ext != "pwn")
      throw File_error(path + ": a streamed run reads .ply, .xyz or .pwn point sets (give no --max-memory / --tile-size "
                       "to process a ." + ext + " file in memory)");
    if(!is_) throw File_error(path + ": cannot open (" + std::strerror(errno) + ")");
    if(is_.peek() == std::ifstream::traits_type::eof()) throw File_error(path + ": the file is empty");
    if(ext == "ply") read_header();
    else format_ = "XYZ";
  }
  const std::string& format() const { return format_; }
  // Binary PLY: every vertex has the same bytes, so that a reader can start at any of them.
  bool is_binary() const { return binary_; }

  // Binary PLY: the next chunk starts at vertex `first`.
  void skip_to(std::uint64_t first)
  {
    if(!binary_) throw std::logic_error("streamed run: only a binary PLY is read from a given vertex");
    if(first > announced_) throw std::logic_error("streamed run: no vertex " + std::to_string(first));
    is_.clear();
    is_.seekg(std::streamoff(data_start_ + first * record_bytes_));
    remaining_ = announced_ - first;
    first_ = false;
  }

  // The next chunk of at most `lines` points (XYZ: lines) into `chunk`, emptied first; false at the end.
  bool next(Point_set& chunk, std::size_t lines)
  {
    chunk.clear();
    std::string text;
    std::size_t count = 0;
    if(binary_) {
      count = std::size_t(std::min<std::uint64_t>(lines, remaining_));
      std::string body(count * record_bytes_, '\0');
      is_.read(&body[0], std::streamsize(body.size()));
      const std::size_t got = std::size_t(is_.gcount()) / record_bytes_;
      if(got < count) truncated(got);
      text = header_with_count(count) + body;
    } else {
      std::string line, body;
      const bool ply = format_ == "PLY";
      while(count < (ply ? std::min<std::uint64_t>(lines, remaining_) : lines) && std::getline(is_, line)) {
        body += line;
        body += '\n';
        ++count;
      }
      if(ply && count < std::min<std::uint64_t>(lines, remaining_)) truncated(count);
      // Line 1 of an XYZ file may be a point count: a later chunk starts with a comment line, so
      // that a number alone there is the error it is in core.
      text = ply ? header_with_count(count) : (first_ ? "" : "#\n") + body;
      if(ply) text += body;
    }
    first_ = false;
    if(count == 0) return false;
    if(format_ == "PLY") remaining_ -= count;
    std::istringstream is(text);
    std::string why;
    const bool ok = call_cgal_io([&] { return format_ == "PLY" ? CGAL::IO::read_PLY(is, chunk) : CGAL::IO::read_XYZ(is, chunk); }, why);
    if(!ok || (format_ == "PLY" && chunk.size() != count))
      throw File_error(path_ + ": not a valid " + format_ + " file (" + (why.empty() ? "malformed or truncated" : why) + ")");
    return true;
  }

  // Binary little-endian PLY whose x, y, z (and nx, ny, nz if any) are float or double, on a
  // little-endian machine: next_values() reads them as CGAL's reader would, without it.
  bool reads_directly() const { return direct_; }
  bool has_normals() const { return has_normals_; }
  // The next chunk of at most `points` points as 6 doubles each (x, y, z, nx, ny, nz; normals 0
  // without has_normals()); false at the end.
  bool next_values(std::vector<double>& values, std::size_t points)
  {
    const std::size_t count = std::size_t(std::min<std::uint64_t>(points, remaining_));
    if(count == 0) return false;
    buffer_.resize(count * record_bytes_);
    is_.read(buffer_.data(), std::streamsize(buffer_.size()));
    const std::size_t got = std::size_t(is_.gcount()) / record_bytes_;
    if(got < count) truncated(got);
    values.assign(count * 6, 0.);
    const int fields = has_normals_ ? 6 : 3;
    for(std::size_t i = 0; i < count; ++i)
      for(int f = 0; f < fields; ++f) values[6 * i + std::size_t(f)] = value(&buffer_[i * record_bytes_], fields_[f]);
    remaining_ -= count;
    first_ = false;
    return true;
  }

private:
  void read_header()
  {
    format_ = "PLY";
    const Ply_header h = read_ply_header(is_);
    check_ply_coordinate_types(h, path_);
    for(std::size_t e = 0; e < h.elements.size(); ++e)
      if(e > 0 || h.elements[e].name != "vertex")
        throw File_error(path_ + ": a streamed run reads PLY point sets (one vertex element); this file has a '" + h.elements[e].name +
                         "' element (give no --max-memory / --tile-size to process a mesh in memory)");
    if(!h.complete || h.elements.empty() || h.elements[0].properties.empty())
      throw File_error(path_ + ": not a valid PLY file (no end_header, or no vertex element with properties)");
    const Ply_header::Element& vertex = h.elements[0];
    binary_ = h.format != "ascii";
    little_endian_ = h.format == "binary_little_endian";
    for(const Ply_header::Property& p : vertex.properties) {
      const std::string& a = p.type;
      if(a == "list") throw File_error(path_ + ": a streamed run reads PLY vertices without list properties");
      const std::size_t bytes = a == "char" || a == "uchar" || a == "int8" || a == "uint8" ? 1
                              : a == "short" || a == "ushort" || a == "int16" || a == "uint16" ? 2
                              : a == "int" || a == "uint" || a == "float" || a == "int32" || a == "uint32" || a == "float32" ? 4
                              : a == "double" || a == "float64" ? 8 : 0;
      if(bytes == 0) throw File_error(path_ + ": not a valid PLY file (unknown property type '" + a + "')");
      const bool floating = a == "float" || a == "float32" || a == "double" || a == "float64";
      for(int f = 0; f < 6; ++f)
        if(p.name == field_names[f]) fields_[f] = Field{record_bytes_, floating ? bytes : 0, true};
      record_bytes_ += bytes;
    }
    // The header around the vertex count, to give each chunk its own.
    for(std::size_t l = 0; l < h.lines.size(); ++l)
      if(l < vertex.line) before_count_ += h.lines[l];
      else if(l > vertex.line) after_count_ += h.lines[l];
    remaining_ = announced_ = vertex.count;
    data_start_ = std::uint64_t(is_.tellg());
    direct_ = binary_ && little_endian_ && machine_is_little_endian();
    int normals = 0;
    for(int f = 0; f < 6; ++f) {
      if(fields_[f].present && fields_[f].bytes == 0) direct_ = false;   // an integer coordinate: CGAL converts it
      if(f < 3 && !fields_[f].present) direct_ = false;
      if(f >= 3 && fields_[f].present) ++normals;
    }
    if(normals != 0 && normals != 3) direct_ = false;
    has_normals_ = normals == 3;
  }
  std::string header_with_count(std::size_t count) const
  {
    return before_count_ + "element vertex " + std::to_string(count) + "\n" + after_count_;
  }
  [[noreturn]] void truncated(std::size_t got) const
  {
    throw File_error(path_ + ": truncated PLY (the header announces " + std::to_string(announced_) + " vertices, " +
                     std::to_string(announced_ - remaining_ + got) + " could be read)");
  }

  // x, y, z, nx, ny, nz in a binary record: offset and size (4: float, 8: double, 0: another type).
  struct Field { std::size_t offset = 0, bytes = 0; bool present = false; };
  static constexpr const char* field_names[6] = {"x", "y", "z", "nx", "ny", "nz"};
  static double value(const char* record, const Field& f)
  {
    if(f.bytes == 4) { float v; std::memcpy(&v, record + f.offset, 4); return double(v); }
    double v;
    std::memcpy(&v, record + f.offset, 8);
    return v;
  }

  std::string path_, format_, before_count_, after_count_;
  std::ifstream is_;
  Field fields_[6];
  std::vector<char> buffer_;
  bool binary_ = false, little_endian_ = false, direct_ = false, has_normals_ = false, first_ = true;
  std::size_t record_bytes_ = 0;
  std::uint64_t remaining_ = 0, announced_ = 0, data_start_ = 0;
};

// ------------------------------------------------------------------------------------------------
// One point between passes: its index in the input, position, normal and fitted flag (64 bytes).
struct Record
{
  std::uint64_t index;
  double position[3], normal[3];
  std::uint64_t fitted;
};
// The record of the input's point `index`: its position and normal (zero where `normal` is null), fitted 0.
Record input_record(std::uint64_t index, const double* position, const double* normal)
{
  Record r;
  std::memset(&r, 0, sizeof r);
  r.index = index;
  std::memcpy(r.position, position, sizeof r.position);
  if(normal) std::memcpy(r.normal, normal, sizeof r.normal);
  return r;
}

// A point after the command's pass: with the curvature command, its curvature columns too.
struct Result
{
  Record record;
  double curvature[11];
};
// Bytes of a pass's output records in the scratch files: without the curvature unless the command computes it.
std::size_t result_bytes(unsigned command) { return command == CURVATURE ? sizeof(Result) : sizeof(Record); }

// Results (their first `bytes`: records) read from, or written to, a scratch file sequentially, through a buffer.
class Record_stream
{
public:
  Record_stream(Scratch_file& file, std::size_t bytes, std::uint64_t first, std::uint64_t end, std::size_t buffered = 1 << 14)
    : file_(file), bytes_(bytes), next_(first), end_(end), buffer_(buffered * bytes) {}
  // Every record was taken: none is left in the file or the buffer, nor peeked and not taken yet.
  bool done() const { return !loaded_ && next_ == end_ && at_ == size_; }
  const Result& peek() { fill(); return current_; }
  const Result& take() { fill(); loaded_ = false; return current_; }
  void put(const void* r)
  {
    std::memcpy(&buffer_[size_], r, bytes_);
    size_ += bytes_;
    if(size_ == buffer_.size()) flush();
  }
  void flush()
  {
    if(size_) file_.write(buffer_.data(), size_, next_ * bytes_);
    next_ += size_ / bytes_;
    size_ = 0;
  }
private:
  void fill()
  {
    if(loaded_) return;
    if(at_ == size_) {
      const std::size_t n = std::size_t(std::min<std::uint64_t>(buffer_.size() / bytes_, end_ - next_));
      file_.read(buffer_.data(), n * bytes_, next_ * bytes_);
      next_ += n; at_ = 0; size_ = n * bytes_;
    }
    std::memcpy(&current_, &buffer_[at_], bytes_);
    at_ += bytes_;
    loaded_ = true;
  }
  Scratch_file& file_;
  std::size_t bytes_;
  std::uint64_t next_, end_;
  std::vector<char> buffer_;
  std::size_t at_ = 0, size_ = 0;
  Result current_ = Result();
  bool loaded_ = false;
};

// Records [first, end) of a file, in index order.
struct Record_run
{
  std::shared_ptr<Scratch_file> file;
  std::uint64_t first = 0, end = 0;
};

// The records of a pass: runs (the scan's one, then one per tile), each in index order.
struct Record_file
{
  std::size_t bytes = sizeof(Record);   // of each record
  std::uint64_t count = 0;
  // Not empty: the records are this input's points, read directly again (Input_chunks::reads_directly()), not runs.
  std::string input;
  std::vector<Record_run> runs;
  CGAL::Bbox_3 bounds;
};

// ------------------------------------------------------------------------------------------------
// Tiles: a grid of cubic cells over the points' bounding box, and boxes of cells cut at median
// counts until a box holds at most tile_size points (or is one cell).
struct Grid
{
  double lo[3] = {0, 0, 0}, cell = 1.;
  long n[3] = {1, 1, 1};
  long cell_index(const double p[3], int axis) const
  {
    const double c = std::floor((p[axis] - lo[axis]) / cell);
    return c < 0 ? 0 : c >= double(n[axis]) ? n[axis] - 1 : long(c);
  }
  std::size_t cell_of(const double p[3]) const
  {
    return std::size_t((cell_index(p, 0) * n[1] + cell_index(p, 1)) * n[2] + cell_index(p, 2));
  }
  std::size_t size() const { return std::size_t(n[0] * n[1] * n[2]); }
};

struct Cell_box { long lo[3], hi[3]; std::uint64_t count; };   // cells [lo, hi) per axis

Grid make_grid(const CGAL::Bbox_3& b, std::uint64_t points, std::size_t tile_size)
{
  Grid g;
  const double extent[3] = {b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()};
  const double largest = std::max({extent[0], extent[1], extent[2]});
  // Cells of about 4096 points (at most a 16th of a tile) on a surface (occupied cells ~ 2 x side^2):
  // the unit of the reads around a tile; a grid of at most 200^3 cells.
  const double cell_points = std::max(1., std::min(4096., double(tile_size) / 16.));
  const double side = std::min(200., std::max(1., std::ceil(std::sqrt(double(points) / (2. * cell_points)))));
  g.cell = largest > 0 ? largest / side : 1.;
  for(int a = 0; a < 3; ++a) {
    g.lo[a] = a == 0 ? b.xmin() : a == 1 ? b.ymin() : b.zmin();
    g.n[a] = std::max(1L, std::min(200L, long(std::ceil(extent[a] / g.cell))));
  }
  return g;
}

std::uint64_t box_count(const Grid& g, const std::vector<std::uint64_t>& counts, const long lo[3], const long hi[3])
{
  std::uint64_t c = 0;
  for(long x = lo[0]; x < hi[0]; ++x)
    for(long y = lo[1]; y < hi[1]; ++y)
      for(long z = lo[2]; z < hi[2]; ++z) c += counts[std::size_t((x * g.n[1] + y) * g.n[2] + z)];
  return c;
}

void split_tiles(const Grid& g, const std::vector<std::uint64_t>& counts, Cell_box box, std::size_t tile_size,
                 std::vector<Cell_box>& tiles)
{
  if(box.count == 0) return;
  int axis = 0;
  for(int a = 1; a < 3; ++a)
    if(box.hi[a] - box.lo[a] > box.hi[axis] - box.lo[axis]) axis = a;
  if(box.count <= tile_size || box.hi[axis] - box.lo[axis] < 2) { tiles.push_back(box); return; }
  // The cut: the cell layer where the count below it reaches half of the box's.
  std::uint64_t below = 0;
  long cut = box.lo[axis] + 1;
  for(long c = box.lo[axis]; c + 1 < box.hi[axis]; ++c) {
    long lo[3] = {box.lo[0], box.lo[1], box.lo[2]}, hi[3] = {box.hi[0], box.hi[1], box.hi[2]};
    lo[axis] = c; hi[axis] = c + 1;
    below += box_count(g, counts, lo, hi);
    cut = c + 1;
    if(2 * below >= box.count) break;
  }
  Cell_box a = box, b = box;
  a.hi[axis] = cut; b.lo[axis] = cut;
  a.count = box_count(g, counts, a.lo, a.hi);
  b.count = box.count - a.count;
  split_tiles(g, counts, a, tile_size, tiles);
  split_tiles(g, counts, b, tile_size, tiles);
}

void sort_by_index(std::vector<Record>& records)
{
  auto less = [](const Record& a, const Record& b) { return a.index < b.index; };
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_sort(records.begin(), records.end(), less);
#else
  std::sort(records.begin(), records.end(), less);
#endif
}

// ------------------------------------------------------------------------------------------------
enum class Pass { BARE_NORMALS, COMMAND, RESULT_NORMALS };

// The threads the run may use (1 with --threads 1: a sequential run).
std::size_t threads_allowed()
{
#ifdef CGAL_LINKED_WITH_TBB
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
#else
  return 1;
#endif
}
bool more_than_one_thread() { return threads_allowed() > 1; }

// The passes of a run: normals of a point set without normals, the command (unless that was
// all: normals), then for enhance-positions the normals of the moved points.
std::vector<Pass> passes_of(const Fit_settings& s, bool had_normals)
{
  std::vector<Pass> passes;
  if(!had_normals) passes.push_back(Pass::BARE_NORMALS);
  if(s.command != NORMALS || had_normals) passes.push_back(Pass::COMMAND);
  if(s.command == POSITIONS) passes.push_back(Pass::RESULT_NORMALS);
  return passes;
}

void add_pass_report(Streamed_run& log, Pass pass, const CGAL::Wavejets::Processing_report& r, std::uint64_t rerun, std::size_t tiles)
{
  log.rerun_points += std::size_t(rerun);
  if(pass == Pass::COMMAND) log.tiles = tiles;
  std::optional<CGAL::Wavejets::Processing_report>& slot =
    pass == Pass::BARE_NORMALS ? log.bare_normals : pass == Pass::COMMAND ? log.command : log.result_normals;
  if(!slot) slot = r;
  else add_report(*slot, r);
}

// A whole small file (a staged run's plan), written under a temporary name and renamed.
void write_whole_file(const std::string& path, const std::string& bytes)
{
  Output_file out(path);
  {
    std::ofstream os(out.temporary_path(), std::ios::binary);
    os.write(bytes.data(), std::streamsize(bytes.size()));
    os.close();
    if(!os) throw std::runtime_error("cannot write " + path);
  }
  out.commit();
}
std::string read_whole_file(const std::string& path)
{
  std::ifstream is(path, std::ios::binary);
  if(!is) throw std::runtime_error("cannot read " + path + " (" + std::strerror(errno) + ")");
  std::ostringstream s;
  s << is.rdbuf();
  return s.str();
}

class Streamed_pass
{
public:
  Streamed_pass(Pass pass, const Fit_settings& s, std::size_t tile_size, const std::function<bool(double)>& progress)
    : pass_(pass), s_(s), tile_size_(tile_size), progress_(progress) {}

  // Bins the records by tile into a scratch file near `near`, runs the tiles, returns their records.
  Record_file run(const Record_file& in, const std::string& near, Streamed_run& log)
  {
    const Clock::time_point t0 = Clock::now();
    bin(in, std::make_shared<Scratch_file>(near));
    log.binning_seconds += seconds_since(t0);
    const Clock::time_point t1 = Clock::now();
    Record_file out;
    const std::shared_ptr<Scratch_file> file = std::make_shared<Scratch_file>(near);
    out.count = count_;
    out.bytes = output_bytes();
    CGAL::Wavejets::Processing_report report;
    // With more than one thread, the next tile's points are read while the current one is fitted.
    const std::launch gathering = more_than_one_thread() ? std::launch::async : std::launch::deferred;
    std::future<Gathered> next = std::async(gathering, [this] { return gather(0); });
    std::uint64_t written = 0;
    for(std::size_t t = 0; t < tiles_.size(); ++t) {
      const Gathered tile = next.get();
      if(t + 1 < tiles_.size()) next = std::async(gathering, [this, t] { return gather(t + 1); });
      run_tile(tile, report);
      const std::size_t n = tile.targets.size();
      out.bounds += results_bounds(n);
      file->write(results_.data(), n * out.bytes, written * out.bytes);
      out.runs.push_back(Record_run{file, written, written + n});
      written += n;
    }
    log.fit_seconds += seconds_since(t1);
    add_pass_report(log, pass_, report, rerun_, tiles_.size());
    return out;
  }

  std::size_t output_bytes() const { return pass_ == Pass::COMMAND ? result_bytes(s_.command) : sizeof(Record); }
  std::size_t number_of_tiles() const { return tiles_.size(); }
  std::uint64_t points_of_tile(std::size_t t) const { return tile_first_[t + 1] - tile_first_[t]; }

  // A staged run (staged_*()): the plan of the pass (what bin() decided), saved next to its bins.
  void save_plan(const std::string& path) const
  {
    std::string b;
    auto pod = [&](const auto& v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); };
    auto vec = [&](const auto& v) {
      pod(std::uint64_t(v.size()));
      if(!v.empty()) b.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0]));
    };
    pod(plan_magic); pod(count_); pod(bounds_); pod(grid_);
    vec(tiles_); vec(cells_); vec(tile_first_); vec(tile_box_);
    write_whole_file(path, b);
  }
  void load_plan(const std::string& path, std::shared_ptr<Scratch_file> bins)
  {
    const std::string b = read_whole_file(path);
    std::size_t at = 0;
    auto pod = [&](auto& v) {
      if(at + sizeof v > b.size()) throw std::runtime_error(path + ": truncated");
      std::memcpy(&v, b.data() + at, sizeof v);
      at += sizeof v;
    };
    auto vec = [&](auto& v) {
      std::uint64_t n = 0;
      pod(n);
      if(at + n * sizeof(v[0]) > b.size()) throw std::runtime_error(path + ": truncated");
      v.resize(std::size_t(n));
      if(n) std::memcpy(v.data(), b.data() + at, std::size_t(n) * sizeof(v[0]));
      at += std::size_t(n) * sizeof(v[0]);
    };
    std::uint64_t magic = 0;
    pod(magic);
    if(magic != plan_magic) throw std::runtime_error(path + ": not a pass plan of this version");
    pod(count_); pod(bounds_); pod(grid_);
    vec(tiles_); vec(cells_); vec(tile_first_); vec(tile_box_);
    bins_ = std::move(bins);
  }

  // A staged run: tile `t` alone. Its results (`output_bytes()` each, in index order), then its report.
  std::string run_one_tile(std::size_t t, CGAL::Wavejets::Processing_report& report, std::uint64_t& rerun, CGAL::Bbox_3& bounds)
  {
    if(t >= tiles_.size()) throw std::runtime_error("no tile " + std::to_string(t) + " (" + std::to_string(tiles_.size()) + " tiles)");
    const Gathered tile = gather(t);
    run_tile(tile, report);
    rerun = rerun_;
    bounds = results_bounds(tile.targets.size());
    return std::string(results_.data(), tile.targets.size() * output_bytes());
  }

  // Sorts the records of `in` into bins by cell, tile after tile, in `bins`; decides the tiles.
  void bin(const Record_file& in, std::shared_ptr<Scratch_file> bins)
  {
    count_ = in.count;
    bounds_ = in.bounds;
    bins_ = std::move(bins);
    grid_ = make_grid(bounds_, count_, tile_size_);
    std::vector<std::uint64_t> counts(grid_.size(), 0);
    for_each_input(in, [&](const Record& r) { ++counts[grid_.cell_of(r.position)]; });
    Cell_box all{{0, 0, 0}, {grid_.n[0], grid_.n[1], grid_.n[2]}, count_};
    split_tiles(grid_, counts, all, tile_size_, tiles_);
    // Cells in tile order: a tile's records are contiguous in the bins, each cell's too. The
    // occupied cells are kept (by cell number), and `counts` becomes each cell's place among them.
    std::uint64_t next = 0;
    for(std::size_t t = 0; t < tiles_.size(); ++t) {
      tile_first_.push_back(next);
      const Cell_box& b = tiles_[t];
      for(long x = b.lo[0]; x < b.hi[0]; ++x)
        for(long y = b.lo[1]; y < b.hi[1]; ++y)
          for(long z = b.lo[2]; z < b.hi[2]; ++z) {
            const std::size_t c = std::size_t((x * grid_.n[1] + y) * grid_.n[2] + z);
            if(counts[c] == 0) continue;
            cells_.push_back(Occupied_cell{next, counts[c], std::uint32_t(c), std::uint32_t(t)});
            next += counts[c];
          }
    }
    tile_first_.push_back(next);
    std::sort(cells_.begin(), cells_.end(), [](const Occupied_cell& a, const Occupied_cell& b) { return a.cell < b.cell; });
    std::vector<std::uint64_t>& place = counts;
    for(std::size_t i = 0; i < cells_.size(); ++i) place[cells_[i].cell] = i;
    // Each tile buffers its records (and their cells), then writes them at their cells' next places.
    // 64 MB of buffers in all, at least 64 records per tile.
    const std::size_t per_tile = std::max<std::size_t>(64, (std::size_t(64) << 20) / sizeof(Record) / tiles_.size());
    // A buffered record's place in the bins and its place in the buffer, as one sort key.
    const int buffer_bits = 20;
    static_assert((std::size_t(64) << 20) / sizeof(Record) <= (std::size_t(1) << buffer_bits), "buffer places fit in the key");
    if(count_ >> (64 - buffer_bits)) throw std::runtime_error("more points than a streamed run bins (2^44)");
    std::vector<std::vector<Record> > buffers(tiles_.size());
    std::vector<std::vector<std::uint32_t> > buffer_cells(tiles_.size());
    tile_box_.assign(tiles_.size(), CGAL::Bbox_3());
    std::vector<std::uint64_t> cursor(cells_.size()), placed;
    for(std::size_t i = 0; i < cells_.size(); ++i) cursor[i] = cells_[i].first;
    std::vector<char> bytes;
    auto flush = [&](std::size_t t) {
      std::vector<Record>& buffer = buffers[t];
      placed.clear();
      for(std::size_t i = 0; i < buffer.size(); ++i) placed.push_back((cursor[buffer_cells[t][i]]++ << buffer_bits) | i);
      std::sort(placed.begin(), placed.end());
      for(std::size_t i = 0; i < placed.size();) {
        std::size_t j = i + 1;
        while(j < placed.size() && (placed[j] >> buffer_bits) == (placed[j - 1] >> buffer_bits) + 1) ++j;
        bytes.resize((j - i) * sizeof(Record));
        for(std::size_t m = i; m < j; ++m)
          std::memcpy(&bytes[(m - i) * sizeof(Record)], &buffer[placed[m] & ((std::uint64_t(1) << buffer_bits) - 1)], sizeof(Record));
        bins_->write(bytes.data(), bytes.size(), (placed[i] >> buffer_bits) * sizeof(Record));
        i = j;
      }
      buffer.clear();
      buffer_cells[t].clear();
    };
    for_each_input(in, [&](const Record& r) {
      const std::size_t cell = std::size_t(place[grid_.cell_of(r.position)]);
      const std::uint32_t t = cells_[cell].tile;
      tile_box_[t] += CGAL::Bbox_3(r.position[0], r.position[1], r.position[2], r.position[0], r.position[1], r.position[2]);
      std::vector<Record>& buffer = buffers[t];
      if(buffer.empty()) { buffer.reserve(per_tile); buffer_cells[t].reserve(per_tile); }
      buffer.push_back(r);
      buffer_cells[t].push_back(std::uint32_t(cell));
      if(buffer.size() == per_tile) flush(t);
    });
    for(std::size_t t = 0; t < tiles_.size(); ++t) flush(t);
  }

private:
  static constexpr std::uint64_t plan_magic = 0x57564a5053504c32ull;   // "WVJPSPL2"

  template <class F> static void for_each_input(const Record_file& in, const F& f)
  {
    if(!in.input.empty()) {
      Input_chunks chunks(in.input);
      std::vector<double> v;
      std::uint64_t index = 0;
      while(chunks.next_values(v, chunk_points()))
        for(std::size_t i = 0; i < v.size(); i += 6) f(input_record(index++, &v[i], &v[i + 3]));
      if(index != in.count)
        throw File_error(in.input + ": changed while it was read (" + std::to_string(index) + " points read again, " + std::to_string(in.count) + " before)");
      return;
    }
    for(const Record_run& run : in.runs) {
      Record_stream reader(*run.file, in.bytes, run.first, run.end);
      while(!reader.done()) f(reader.take().record);
    }
  }

  CGAL::Bbox_3 results_bounds(std::size_t n) const
  {
    CGAL::Bbox_3 b;
    for(std::size_t i = 0; i < n; ++i) {
      const double* p = reinterpret_cast<const Record*>(&results_[i * result_bytes_])->position;
      b += CGAL::Bbox_3(p[0], p[1], p[2], p[0], p[1], p[2]);
    }
    return b;
  }

  // The records of the points in the closed box `extent`, in index order.
  std::vector<Record> points_in(const CGAL::Bbox_3& extent) const
  {
    const double lo[3] = {extent.xmin(), extent.ymin(), extent.zmin()}, hi[3] = {extent.xmax(), extent.ymax(), extent.zmax()};
    // The cells of the box grown by far more than the rounding error of a point's cell (so that a
    // point of the box in a neighbor cell by rounding is read too).
    double grown_lo[3], grown_hi[3];
    for(int a = 0; a < 3; ++a) {
      const double e = 1e-9 * (std::abs(lo[a]) + std::abs(hi[a]) + std::abs(grid_.lo[a]) + grid_.cell);
      grown_lo[a] = lo[a] - e;
      grown_hi[a] = hi[a] + e;
    }
    long from[3], to[3];
    for(int a = 0; a < 3; ++a) {
      from[a] = grid_.cell_index(grown_lo, a);
      to[a] = grid_.cell_index(grown_hi, a) + 1;
    }
    // The occupied cells of the box: for each row of cells along z, those between its ends.
    std::vector<const Occupied_cell*> occupied;
    std::uint64_t count = 0;
    auto by_cell = [](const Occupied_cell& c, std::uint64_t cell) { return c.cell < cell; };
    for(long x = from[0]; x < to[0]; ++x)
      for(long y = from[1]; y < to[1]; ++y) {
        const std::uint64_t row = std::uint64_t((x * grid_.n[1] + y) * grid_.n[2]);
        for(auto c = std::lower_bound(cells_.begin(), cells_.end(), row + std::uint64_t(from[2]), by_cell);
            c != cells_.end() && c->cell < row + std::uint64_t(to[2]); ++c) {
          occupied.push_back(&*c);
          count += c->count;
        }
      }
    std::vector<Record> found;
    found.reserve(std::size_t(count));
    std::vector<Record> cell;
    for(const Occupied_cell* c : occupied) {
      cell.resize(std::size_t(c->count));
      bins_->read(cell.data(), cell.size() * sizeof(Record), c->first * sizeof(Record));
      for(const Record& r : cell) {
        bool inside = true;
        for(int a = 0; a < 3; ++a) inside = inside && r.position[a] >= lo[a] && r.position[a] <= hi[a];
        if(inside) found.push_back(r);
      }
    }
    sort_by_index(found);
    return found;
  }

  // The first halo of a tile: the library's own first guess in a tiled run, or a millionth of the
  // diagonal where that is 0 (the tile's points coincide).
  double first_halo(const CGAL::Bbox_3& box, std::size_t count) const
  {
    const double extent[3] = {box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()};
    const double h = CGAL::Wavejets::internal::estimated_halo(extent, count, s_.k, s_.radius);
    const double diagonal = std::sqrt(CGAL::square(bounds_.xmax() - bounds_.xmin()) +
                                      CGAL::square(bounds_.ymax() - bounds_.ymin()) +
                                      CGAL::square(bounds_.zmax() - bounds_.zmin()));
    return h > 0 ? h : 1e-6 * diagonal;
  }

  // A tile's points and those within its first halo, in index order, and the positions among them
  // of the tile's own points (the targets).
  struct Gathered
  {
    double halo = 0.;
    CGAL::Bbox_3 extent;
    std::vector<Record> points;
    std::vector<std::size_t> targets;
  };
  Gathered gather(std::size_t t) const
  {
    Gathered g;
    const CGAL::Bbox_3& box = tile_box_[t];
    const std::size_t tile_points = std::size_t(points_of_tile(t));
    g.halo = first_halo(box, tile_points);
    const double h = g.halo;
    g.extent = CGAL::Bbox_3(box.xmin() - h, box.ymin() - h, box.zmin() - h, box.xmax() + h, box.ymax() + h, box.zmax() + h);
    g.points = points_in(g.extent);
    g.targets.reserve(tile_points);
    const Cell_box& cells = tiles_[t];   // the tile's points: those of its cells
    for(std::size_t i = 0; i < g.points.size(); ++i) {
      bool own = true;
      for(int a = 0; a < 3; ++a) {
        const long c = grid_.cell_index(g.points[i].position, a);
        own = own && c >= cells.lo[a] && c < cells.hi[a];
      }
      if(own) g.targets.push_back(i);
    }
    if(g.targets.size() != tile_points) throw std::logic_error("streamed run: a tile's point is missing from its own extent");
    return g;
  }

  // A point whose fit is still to be done: its record and the slot of its result in results_.
  struct Pending
  {
    Record record;
    std::size_t slot;
  };

  // Writes the records (`bytes` of each Result) of the tile's points after the pass to results_, in
  // index order.
  void run_tile(const Gathered& tile, CGAL::Wavejets::Processing_report& report)
  {
    const std::size_t tile_points = tile.targets.size();
    result_bytes_ = output_bytes();
    results_.resize(tile_points * result_bytes_);   // reused from tile to tile
    std::vector<std::size_t> slots(tile_points);
    std::iota(slots.begin(), slots.end(), std::size_t(0));
    std::vector<Pending> outside = fit_targets(tile.points, tile.targets, slots, tile.extent, report, tile_points);
    rerun_ += outside.size();
    // The points whose neighborhood left the halo (few, where the sampling is sparse), cell by
    // cell, each group within a halo twice as large as the last, until none is left.
    std::sort(outside.begin(), outside.end(), [&](const Pending& a, const Pending& b) {
      const std::size_t ca = grid_.cell_of(a.record.position), cb = grid_.cell_of(b.record.position);
      return ca != cb ? ca < cb : a.record.index < b.record.index;
    });
    for(std::size_t i = 0; i < outside.size();) {
      std::size_t j = i + 1;
      while(j < outside.size() && grid_.cell_of(outside[j].record.position) == grid_.cell_of(outside[i].record.position)) ++j;
      std::vector<Pending> group(outside.begin() + std::ptrdiff_t(i), outside.begin() + std::ptrdiff_t(j));
      for(double larger = 2 * tile.halo; !group.empty(); larger *= 2) group = fit_within(group, larger, report, tile_points);
      i = j;
    }
    done_points_ += tile_points;
  }

  // Fits the points of `group` (in index order) among the points within `halo` of their bounding
  // box: writes their results where exact, returns the others.
  std::vector<Pending> fit_within(const std::vector<Pending>& group, double halo, CGAL::Wavejets::Processing_report& report,
                                  std::size_t tile_points)
  {
    CGAL::Bbox_3 b;
    for(const Pending& g : group) b += CGAL::Bbox_3(g.record.position[0], g.record.position[1], g.record.position[2],
                                                    g.record.position[0], g.record.position[1], g.record.position[2]);
    const CGAL::Bbox_3 extent(b.xmin() - halo, b.ymin() - halo, b.zmin() - halo, b.xmax() + halo, b.ymax() + halo, b.zmax() + halo);
    const std::vector<Record> points = points_in(extent);
    std::vector<std::size_t> targets, slots;
    std::size_t j = 0;
    for(std::size_t i = 0; i < points.size() && j < group.size(); ++i)
      if(points[i].index == group[j].record.index) {
        targets.push_back(i);
        slots.push_back(group[j].slot);
        ++j;
      }
    if(j != group.size()) throw std::logic_error("streamed run: a point is missing from its own extent");
    return fit_targets(points, targets, slots, extent, report, tile_points);
  }

  // One library call on `points` (in index order, those within `extent`) for those at the positions
  // `targets` (increasing): writes their records to their `slots` in results_ where exact, returns
  // the others.
  std::vector<Pending> fit_targets(const std::vector<Record>& points, const std::vector<std::size_t>& targets,
                                   const std::vector<std::size_t>& slots, const CGAL::Bbox_3& extent,
                                   CGAL::Wavejets::Processing_report& report, std::size_t tile_points)
  {
    Point_set ps;
    ps.add_normal_map();
    ps.resize(points.size());
    const bool input_normals = pass_ != Pass::BARE_NORMALS;   // else none: the normals are estimated
    CGAL::for_each<Concurrency_tag>(CGAL::make_counting_range<std::size_t>(0, points.size()), [&](std::size_t i) {
      const Record& r = points[i];
      const Point_set::Index key(static_cast<Point_set::Index::size_type>(i));
      ps.point(key) = Point(r.position[0], r.position[1], r.position[2]);
      ps.normal(key) = input_normals ? Vector(r.normal[0], r.normal[1], r.normal[2]) : CGAL::NULL_VECTOR;
      return true;
    });
    const Output_columns columns = add_output_columns(ps, s_.command);
    In_tile tiling{CGAL::Wavejets::Tile{extent, bounds_}, ps.add_property_map<unsigned char>("owned", 0).first,
                   ps.add_property_map<unsigned char>("outside", 0).first};
    auto key = [](std::size_t i) { return Point_set::Index(static_cast<Point_set::Index::size_type>(i)); };
    for(std::size_t i : targets) tiling.owned[key(i)] = 1;
    const double base = double(done_points_);
    const Callback cb = [&](double x) { return progress_((base + x * double(tile_points)) / double(count_)); };
    CGAL::Wavejets::Processing_report r;
    if(pass_ == Pass::BARE_NORMALS)
      r = estimate_normals_of_bare_points(ps, s_, s_.command == NORMALS ? s_.order : 2,
                                          s_.command == NORMALS ? Uchar_bool_map{columns.fitted} : Uchar_bool_map{}, cb, tiling);
    else if(pass_ == Pass::COMMAND) r = run_fit_command(ps, s_, columns, cb, tiling);
    else r = estimate_normals_of_result(ps, s_, cb, tiling);
    if(r.interrupted) throw File_error("interrupted");
    add_report(report, r);
    const bool writes_fitted = pass_ == Pass::COMMAND || (pass_ == Pass::BARE_NORMALS && s_.command == NORMALS);
    std::vector<Pending> outside;
    for(std::size_t j = 0; j < targets.size(); ++j) {
      const Point_set::Index i = key(targets[j]);
      if(tiling.outside[i]) { outside.push_back(Pending{points[targets[j]], slots[j]}); continue; }
      Result out;
      out.record = points[targets[j]];
      Record& rec = out.record;
      const Vector& n = ps.normal(i);
      rec.normal[0] = n.x(); rec.normal[1] = n.y(); rec.normal[2] = n.z();
      if(writes_fitted) rec.fitted = columns.fitted[i];
      if(pass_ == Pass::COMMAND) {
        const Point& p = ps.point(i);
        rec.position[0] = p.x(); rec.position[1] = p.y(); rec.position[2] = p.z();
        for(std::size_t c = 0; c < columns.curvature.size(); ++c) out.curvature[c] = columns.curvature[c][i];
      }
      std::memcpy(&results_[slots[j] * result_bytes_], &out, result_bytes_);
    }
    return outside;
  }

  Pass pass_;
  const Fit_settings& s_;
  std::size_t tile_size_;
  std::function<bool(double)> progress_;
  std::uint64_t count_ = 0;   // points of the pass
  CGAL::Bbox_3 bounds_;       // of all of them
  Grid grid_;
  std::vector<Cell_box> tiles_;
  // An occupied cell of the grid: where its records are in the bins, its number, its tile.
  struct Occupied_cell
  {
    std::uint64_t first, count;
    std::uint32_t cell, tile;
  };
  std::vector<Occupied_cell> cells_;   // by increasing cell number
  std::vector<std::uint64_t> tile_first_;
  std::vector<CGAL::Bbox_3> tile_box_;   // of each tile's points
  std::shared_ptr<Scratch_file> bins_;
  std::uint64_t done_points_ = 0, rerun_ = 0;
  std::vector<char> results_;      // of the current tile, result_bytes_ each, in index order
  std::size_t result_bytes_ = sizeof(Record);
};

// Pass 1: the input's points as records, checked as the in-core reader checks them.
Record_file scan(const std::string& in_path, const std::shared_ptr<Scratch_file>& file, const Fit_settings& s, Streamed_run& log)
{
  const Clock::time_point t0 = Clock::now();
  Input_chunks chunks(in_path);
  log.format = chunks.format();
  Record_file f;
  Record_stream writer(*file, sizeof(Record), 0, std::numeric_limits<std::uint64_t>::max());
  bool all_same = true, any_normal = false;
  double first_point[3] = {0, 0, 0};
  auto add = [&](double x, double y, double z, const double* normal) {
    if(!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      throw File_error(in_path + ": point " + std::to_string(f.count) + " has a NaN or infinite coordinate (remove such points first)");
    const double position[3] = {x, y, z};
    const Record r = input_record(f.count, position, normal);
    if(normal) {
      const double l = normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2];
      any_normal = any_normal || (std::isfinite(l) && l > 0);
    }
    const CGAL::Bbox_3 b(x, y, z, x, y, z);
    if(f.count == 0) { first_point[0] = x; first_point[1] = y; first_point[2] = z; f.bounds = b; }
    else { f.bounds += b; all_same = all_same && x == first_point[0] && y == first_point[1] && z == first_point[2]; }
    if(f.input.empty()) writer.put(&r);
    ++f.count;
  };
  if(chunks.reads_directly()) {
    f.input = in_path;   // read again by the binning, not copied
    std::vector<double> v;
    while(chunks.next_values(v, chunk_points()))
      for(std::size_t i = 0; i < v.size(); i += 6) add(v[i], v[i + 1], v[i + 2], chunks.has_normals() ? &v[i + 3] : nullptr);
  } else {
    Point_set chunk;
    while(chunks.next(chunk, chunk_points()))
      for(Point_set::Index i : chunk) {
        const Point& p = chunk.point(i);
        const Vector n = chunk.has_normal_map() ? chunk.normal(i) : CGAL::NULL_VECTOR;
        const double normal[3] = {n.x(), n.y(), n.z()};
        add(p.x(), p.y(), p.z(), chunk.has_normal_map() ? normal : nullptr);
      }
  }
  writer.flush();
  if(f.count == 0) throw File_error(in_path + ": contains no points");
  if(all_same)
    throw File_error(in_path + (f.count == 1 ? std::string(": contains a single point") : ": all " + std::to_string(f.count) + " points coincide") +
                     " (no surface to fit)");
  log.points = std::size_t(f.count);
  log.had_normals = any_normal;
  if(!any_normal) {
    if(!s.viewpoint)
      throw File_error(in_path + ": has no normals; a streamed run orients estimated normals toward a viewpoint: give "
                       "--orient-toward X,Y,Z (e.g. the scanner's position), or process it in memory (no --max-memory / "
                       "--tile-size: oriented by a minimum spanning tree)");
    // Normals that are all zero or not finite count as none, as in core: the records keep them,
    // the first pass (Pass::BARE_NORMALS) does not read them.
  }
  if(f.input.empty()) f.runs.push_back(Record_run{file, 0, f.count});
  log.scan_seconds = seconds_since(t0);
  return f;
}

// The records of the indices [first, first + out.size()), from the runs of `f` (each in index
// order), for increasing `first` from `start` on.
class Record_merge
{
public:
  Record_merge(const Record_file& f, std::uint64_t start)
  {
    const std::size_t bytes = f.bytes;
    // 32 MB of buffers in all, at least 64 records per run.
    const std::size_t buffered = std::max<std::size_t>(64, (std::size_t(32) << 20) / bytes / std::max<std::size_t>(1, f.runs.size()));
    for(const Record_run& run : f.runs) {
      // The run's first record of index >= start.
      std::uint64_t lo = run.first, hi = run.end;
      while(lo < hi) {
        const std::uint64_t mid = lo + (hi - lo) / 2;
        std::uint64_t index = 0;
        run.file->read(&index, sizeof index, mid * bytes + offsetof(Record, index));
        if(index < start) lo = mid + 1;
        else hi = mid;
      }
      streams_.emplace_back(new Record_stream(*run.file, bytes, lo, run.end, buffered));
    }
  }
  // Every index of the window has exactly one record in the runs: a missing or repeated one is a
  // defect of the run, reported rather than written (a missing record would be written as zeros).
  void next(std::uint64_t first, std::vector<Result>& out)
  {
    std::size_t filled = 0;
    filled_.assign(out.size(), 0);
    for(auto& s : streams_)
      while(!s->done() && s->peek().record.index < first + out.size()) {
        const Result& r = s->take();
        const std::uint64_t at = r.record.index - first;
        if(r.record.index < first || filled_[at]) throw std::logic_error("streamed run: a pass's records are out of index order");
        out[std::size_t(at)] = r;
        filled_[at] = 1;
        ++filled;
      }
    if(filled != out.size())
      throw std::logic_error("streamed run: " + std::to_string(filled) + " records for the " + std::to_string(out.size()) +
                             " points from index " + std::to_string(first));
  }
private:
  std::vector<std::unique_ptr<Record_stream> > streams_;
  std::vector<unsigned char> filled_;   // of the window: 1 where a record was found
};

// ------------------------------------------------------------------------------------------------
// Writing OUT: IN read again, each vertex with its record's values, in the bytes CGAL's PLY writer
// gives the in-core point set. In binary from a binary PLY every vertex has the same bytes: the
// vertices are written in parts, each at its place in the file (by threads, or by the steps of a
// staged run).

// A chunk of IN as the in-core point set is after the command: the output's columns, the records' values.
void fill_chunk(Point_set& chunk, const Fit_settings& s, bool had_normals, const std::vector<Result>& values)
{
  if(had_normals && !chunk.has_normal_map()) chunk.add_normal_map(Vector(0, 0, 0));
  if(!had_normals && chunk.has_normal_map()) chunk.remove_normal_map();
  const Output_columns columns = add_output_columns(chunk, s.command);
  std::size_t j = 0;
  for(Point_set::Index i : chunk) {
    const Result& v = values[j++];
    const Record& r = v.record;
    if(s.command == POSITIONS) chunk.point(i) = Point(r.position[0], r.position[1], r.position[2]);
    chunk.normal(i) = Vector(r.normal[0], r.normal[1], r.normal[2]);
    columns.fitted[i] = (unsigned char)(r.fitted);
    for(std::size_t c = 0; c < columns.curvature.size(); ++c) columns.curvature[c][i] = v.curvature[c];
  }
}

// Where the vertices start in a PLY written by ply_text().
std::size_t ply_body_offset(const std::string& ply) { return ply.find("end_header\n") + 11; }

// The output's PLY header and the bytes of each vertex.
struct Output_layout
{
  std::string header;                 // announcing every point
  std::uint64_t points = 0;
  std::size_t vertex_bytes = 0;       // binary output: of every vertex (0: ASCII)
  std::vector<std::string> columns;   // the vertices' properties, for the summary
};

Output_layout output_layout(const std::string& in_path, const Fit_settings& s, const Streaming_settings& settings,
                            bool had_normals, std::uint64_t points)
{
  Input_chunks chunks(in_path);
  Point_set chunk;
  while(chunks.next(chunk, 1) && chunk.empty()) {}   // an XYZ file's comment lines
  if(chunk.empty()) throw File_error(in_path + ": changed while it was read (no point read again)");
  fill_chunk(chunk, s, had_normals, std::vector<Result>(chunk.size()));
  const std::string text = ply_text(chunk, settings.ascii, settings.comment);
  const std::size_t body = ply_body_offset(text);
  Output_layout l;
  l.points = points;
  l.header = text.substr(0, body);
  const std::string count = "element vertex " + std::to_string(chunk.size()) + "\n";
  l.header.replace(l.header.find(count), count.size(), "element vertex " + std::to_string(points) + "\n");
  if(!settings.ascii) l.vertex_bytes = (text.size() - body) / chunk.size();
  for(const std::string& p : chunk.properties())
    if(p != "index" && p != "point") l.columns.push_back(p == "normal" ? "nx ny nz" : p);
  return l;
}

// Whether OUT is written in parts: binary output, IN a binary PLY.
bool writes_in_parts(const std::string& in_path, const Streaming_settings& settings)
{
  return !settings.ascii && Input_chunks(in_path).is_binary();
}

// The binary vertices of OUT straight from IN's coordinates (as Input_chunks::next_values() reads
// them) and the records, without CGAL's reader and writer (several times faster): where every
// vertex property of the output header is one of x y z nx ny nz, fitted and the curvature columns.
// write_vertices() uses it once it gave CGAL's bytes on a first chunk.
class Direct_vertices
{
public:
  // None unless `header` is binary little-endian (on a little-endian machine) and its vertex
  // properties are all known.
  static std::optional<Direct_vertices> of(const std::string& header, bool positions_from_records)
  {
    std::istringstream is(header);
    const Ply_header h = read_ply_header(is);
    const Ply_header::Element* vertex = h.element("vertex");
    if(!machine_is_little_endian() || h.format != "binary_little_endian" || !vertex) return std::nullopt;
    Direct_vertices d;
    d.positions_from_records_ = positions_from_records;
    const std::vector<std::string>& curvature = curvature_column_names();
    static const char* const fields[7] = {"x", "y", "z", "nx", "ny", "nz", "fitted"};
    for(const Ply_header::Property& p : vertex->properties) {
      Column c;
      c.type = p.type == "double" ? DOUBLE : p.type == "float" ? FLOAT : p.type == "uchar" ? UCHAR : NONE;
      c.source = int(std::find(fields, fields + 7, p.name) - fields);
      if(c.source == 7) {
        c.curvature = std::size_t(std::find(curvature.begin(), curvature.end(), p.name) - curvature.begin());
        if(c.curvature == curvature.size()) return std::nullopt;
      }
      if(c.type == NONE) return std::nullopt;
      d.columns_.push_back(c);
    }
    return d;
  }

  // Appends the bytes of a vertex of IN coordinates `in` (x, y, z) and result `r`.
  void append(std::string& out, const double* in, const Result& r) const
  {
    for(const Column& c : columns_) {
      const double v = c.source < 3 ? (positions_from_records_ ? r.record.position[c.source] : in[c.source])
                     : c.source < 6 ? r.record.normal[c.source - 3]
                     : c.source == 6 ? double((unsigned char)(r.record.fitted)) : r.curvature[c.curvature];
      if(c.type == DOUBLE) out.append(reinterpret_cast<const char*>(&v), sizeof v);
      else if(c.type == FLOAT) { const float f = float(v); out.append(reinterpret_cast<const char*>(&f), sizeof f); }
      else out.push_back(char((unsigned char)(v)));
    }
  }

private:
  enum Type { NONE, DOUBLE, FLOAT, UCHAR };
  struct Column
  {
    Type type = NONE;
    int source = 0;            // x y z nx ny nz fitted, 7: a curvature column
    std::size_t curvature = 0;
  };
  std::vector<Column> columns_;
  bool positions_from_records_ = false;
};

// Writes the vertices [first, end) of OUT (as `layout` says) at `offset` of `out`: IN read again
// from vertex `first` (0 unless IN is a binary PLY), each vertex with its record's values.
// `progress` gets the fraction written. Returns how many of them have `fitted` 1 in OUT.
std::uint64_t write_vertices(const std::string& in_path, std::uint64_t first, std::uint64_t end, const Output_layout& layout,
                    const Record_file& records, const Fit_settings& s, const Streaming_settings& settings, bool had_normals,
                    Scratch_file& out, std::uint64_t offset, const std::function<void(double)>& progress)
{
  Input_chunks chunks(in_path);
  if(first > 0) chunks.skip_to(first);
  Record_merge merge(records, first);
  std::optional<Direct_vertices> direct;
  if(chunks.reads_directly() && !settings.ascii) direct = Direct_vertices::of(layout.header, s.command == POSITIONS);
  bool checked = false;   // the direct bytes were CGAL's on the first chunk
  std::uint64_t at = first;
  Point_set chunk;
  std::vector<Result> values;
  std::vector<double> in;
  std::string bytes, direct_bytes;
  std::uint64_t fitted = 0;
  while(at < end) {
    const std::size_t wanted = std::size_t(std::min<std::uint64_t>(chunk_points(), end - at));
    bytes.clear();
    if(direct && checked) {
      if(!chunks.next_values(in, wanted)) break;
      values.assign(in.size() / 6, Result());
      merge.next(at, values);
      for(std::size_t i = 0; i < values.size(); ++i) direct->append(bytes, &in[6 * i], values[i]);
    } else {
      if(!chunks.next(chunk, wanted)) break;
      if(chunk.empty()) continue;
      values.assign(chunk.size(), Result());
      merge.next(at, values);
      fill_chunk(chunk, s, had_normals, values);
      const std::string text = ply_text(chunk, settings.ascii, settings.comment);
      bytes.assign(text, ply_body_offset(text), std::string::npos);
      if(direct) {
        direct_bytes.clear();
        std::size_t j = 0;
        for(Point_set::Index i : chunk) {
          const double p[3] = {chunk.point(i).x(), chunk.point(i).y(), chunk.point(i).z()};
          direct->append(direct_bytes, p, values[j++]);
        }
        checked = direct_bytes == bytes;
        if(!checked) direct.reset();
      }
    }
    out.write(bytes.data(), bytes.size(), offset);
    offset += bytes.size();
    at += values.size();
    for(const Result& v : values) fitted += (unsigned char)(v.record.fitted) != 0;
    progress(double(at - first) / double(end - first));
  }
  bool more = false;
  if(at == end && end == layout.points)
    while(!more && chunks.next(chunk, chunk_points())) more = !chunk.empty();
  if(at != end || more)
    throw File_error(in_path + ": changed while it was read (" + (more ? "more than " : "") + std::to_string(at) + " points read again, " +
                     std::to_string(end) + " before)");
  return fitted;
}

// The report whose points make OUT's `fitted` column: the command's, or for normals of a point set
// without normals the estimation's.
const std::optional<CGAL::Wavejets::Processing_report>& fitted_column_report(const Streamed_run& log)
{
  return log.command ? log.command : log.bare_normals;
}

// The summary's counts are those of OUT: its `fitted` column, counted as written, must be what the
// library reported for the tiles; else the run is a defect, reported before OUT is written.
void check_written_counts(Streamed_run& log, std::uint64_t written_fitted)
{
  log.written_fitted = written_fitted;
  const std::optional<CGAL::Wavejets::Processing_report>& r = fitted_column_report(log);
  const std::uint64_t reported = r ? r->number_of_fitted_points + r->number_of_unfitted_points : 0;
  if(!r || r->number_of_fitted_points != written_fitted || reported != log.points)
    throw std::logic_error("streamed run: OUT would hold " + std::to_string(written_fitted) + " fitted points of " +
                           std::to_string(log.points) + " while the tiles reported " +
                           (r ? std::to_string(r->number_of_fitted_points) + " of " + std::to_string(reported) : std::string("none")) +
                           " (a defect of the streamed run: OUT is not written)");
}

} // namespace

std::size_t tile_size_for_memory(double bytes)
{
  // About 600 bytes per point of a tile and its halo (the Point_set, the records, the library's
  // k-d tree and fits), and 200 MB for the rest (grid, buffers).
  const double points = (bytes - 200e6) / 600.;
  return std::size_t(std::max(1000., points));
}

namespace {

void write_output(const std::string& in_path, const std::string& out_path, const Fit_settings& s,
                  const Streaming_settings& settings, const Record_file& records, Streamed_run& log, const Callback& progress);

Streamed_run run(const std::string& in_path, const std::string& out_path, const Fit_settings& s,
                 const Streaming_settings& settings, const Callback& progress)
{
  Streamed_run log;
  Record_file records = scan(in_path, std::make_shared<Scratch_file>(out_path), s, log);
  const std::vector<Pass> passes = passes_of(s, log.had_normals);
  std::size_t pass_index = 0;
  auto pass_progress = [&](double x) {   // the whole run: scan 5%, passes 85%, writing 10%
    return progress(0.05 + 0.85 * (double(pass_index) + std::min(1., x)) / double(passes.size()));
  };
  for(; pass_index < passes.size(); ++pass_index) {
    Streamed_pass pass(passes[pass_index], s, settings.tile_size, pass_progress);
    Record_file next = pass.run(records, out_path, log);
    records = std::move(next);
  }
  write_output(in_path, out_path, s, settings, records, log, progress);
  return log;
}

// Writing: the header, then the vertices (in parts written by threads where writes_in_parts()).
void write_output(const std::string& in_path, const std::string& out_path, const Fit_settings& s,
                  const Streaming_settings& settings, const Record_file& records, Streamed_run& log, const Callback& progress)
{
  const Clock::time_point tw = Clock::now();
  const Output_layout layout = output_layout(in_path, s, settings, log.had_normals, log.points);
  log.columns = layout.columns;
  Output_file out(out_path);
  {
    const std::unique_ptr<Scratch_file> file(Scratch_file::open_named(out.temporary_path()));
    file->write(layout.header.data(), layout.header.size(), 0);
    const std::uint64_t n = log.points;
    const std::size_t parts = writes_in_parts(in_path, settings)
                            ? std::size_t(std::max<std::uint64_t>(1, std::min<std::uint64_t>(threads_allowed(), n / chunk_points()))) : 1;
    auto part = [&](std::size_t p, const std::function<void(double)>& part_progress) {
      const std::uint64_t first = n * p / parts, end = n * (p + 1) / parts;
      return write_vertices(in_path, first, end, layout, records, s, settings, log.had_normals, *file,
                            layout.header.size() + first * layout.vertex_bytes, part_progress);
    };
    std::vector<std::future<std::uint64_t> > others;
    for(std::size_t p = 1; p < parts; ++p) others.push_back(std::async(std::launch::async, part, p, [](double) {}));
    std::uint64_t fitted = part(0, [&](double x) { progress(0.9 + 0.1 * x); });   // the parts progress alike
    for(std::future<std::uint64_t>& f : others) fitted += f.get();
    check_written_counts(log, fitted);
  }
  out.commit();
  log.write_seconds = seconds_since(tw);
}

} // namespace

namespace {

// ------------------------------------------------------------------------------------------------
// Staged runs: the files of a job folder.
//   run            what the scan found (text: format, points, normals, passes)
//   records        the scan's records
//   pass-P.bins    the records of pass P binned by cell; pass-P.plan: the tiles; pass-P.tiles: their number,
//                  then the points of each (text)
//   pass-P.tile-T  the results of tile T of pass P (in index order), then a Tile_trailer
//   output         OUT's vertices written in parts (staged_write_part()), its header last; output.part-C-of-N: part C written
// Every file is written under a temporary name and renamed when complete: a step run twice (a
// worker lost and its task run again) writes the same file again.
std::string job_path(const std::string& job, const std::string& name) { return job + "/" + name; }
std::string pass_path(const std::string& job, std::size_t pass, const std::string& what)
{
  return job_path(job, "pass-" + std::to_string(pass) + "." + what);
}

struct Tile_trailer
{
  CGAL::Wavejets::Processing_report report;
  std::uint64_t rerun = 0, count = 0, bytes = 0;
  CGAL::Bbox_3 bounds;
  std::uint64_t magic = 0x57564a5454494c31ull;   // "WVJTTIL1"
};

struct Job_info
{
  std::string format;
  std::uint64_t points = 0;
  bool had_normals = false;
};

Job_info read_job(const std::string& job)
{
  std::istringstream is(read_whole_file(job_path(job, "run")));
  Job_info info;
  std::string key;
  while(is >> key) {
    if(key == "format") is >> info.format;
    else if(key == "points") is >> info.points;
    else if(key == "normals") is >> info.had_normals;
    else is >> key;   // a value read for another key
  }
  if(info.format.empty()) throw std::runtime_error(job_path(job, "run") + ": not a job description");
  return info;
}

// The results of every tile of `pass`, as the records of the next pass (or of the output); adds
// the tiles' reports to `log`.
Record_file tile_results(const std::string& job, const std::vector<Pass>& passes, std::size_t pass, Streamed_run& log)
{
  Record_file f;
  const std::size_t tiles = staged_tiles(job, pass);
  CGAL::Wavejets::Processing_report report;
  std::uint64_t rerun = 0;
  for(std::size_t t = 0; t < tiles; ++t) {
    const std::string path = pass_path(job, pass, "tile-" + std::to_string(t));
    std::shared_ptr<Scratch_file> file(Scratch_file::open_named(path));
    Tile_trailer trailer;
    const std::uint64_t size = file->size();
    if(size < sizeof trailer) throw std::runtime_error(path + ": truncated");
    file->read(&trailer, sizeof trailer, size - sizeof trailer);
    if(trailer.magic != Tile_trailer().magic || size != trailer.count * trailer.bytes + sizeof trailer)
      throw std::runtime_error(path + ": not the results of a tile");
    f.bytes = std::size_t(trailer.bytes);
    f.runs.push_back(Record_run{file, 0, trailer.count});
    f.count += trailer.count;
    f.bounds += trailer.bounds;
    add_report(report, trailer.report);
    rerun += trailer.rerun;
  }
  add_pass_report(log, passes[pass], report, rerun, tiles);
  return f;
}

// The results of the last pass (the output's records); `log` gets the job's description and the passes' reports.
Record_file last_results(const std::string& job, const Fit_settings& s, Streamed_run& log)
{
  const Job_info info = read_job(job);
  log.format = info.format;
  log.points = std::size_t(info.points);
  log.had_normals = info.had_normals;
  const std::vector<Pass> passes = passes_of(s, info.had_normals);
  Record_file records;
  for(std::size_t p = 0; p < passes.size(); ++p) records = tile_results(job, passes, p, log);
  if(records.count != info.points)
    throw std::runtime_error("the tiles hold " + std::to_string(records.count) + " points, the input " + std::to_string(info.points));
  return records;
}

// A part of the output written: an empty file of this name.
std::string output_part_path(const std::string& job, std::size_t part, std::size_t parts)
{
  return job_path(job, "output.part-" + std::to_string(part) + "-of-" + std::to_string(parts));
}

// Bins `in` for `pass` into the job folder.
void bin_into_job(const std::string& job, std::size_t pass, Pass kind, const Record_file& in, const Fit_settings& s,
                  const Streaming_settings& settings)
{
  Output_file bins(pass_path(job, pass, "bins"));
  Streamed_pass p(kind, s, settings.tile_size, [](double) { return true; });
  p.bin(in, std::shared_ptr<Scratch_file>(Scratch_file::open_named(bins.temporary_path())));
  bins.commit();
  p.save_plan(pass_path(job, pass, "plan"));
  std::string tiles = std::to_string(p.number_of_tiles()) + "\n";
  for(std::size_t t = 0; t < p.number_of_tiles(); ++t) tiles += std::to_string(p.points_of_tile(t)) + "\n";
  write_whole_file(pass_path(job, pass, "tiles"), tiles);
}

// Runs `f` and names the job folder in the scratch files' errors (a full disk).
template <class F> auto in_job(const std::string& job, const F& f)
{
  try {
    return f();
  } catch(const File_error&) {
    throw;
  } catch(const std::runtime_error& e) {
    throw File_error(job + ": " + e.what());
  }
}

} // namespace

std::size_t staged_prepare(const std::string& in_path, const std::string& job,
                           const Fit_settings& s, const Streaming_settings& settings)
{
  return in_job(job, [&] {
    Streamed_run log;
    Output_file records(job_path(job, "records"));
    const std::shared_ptr<Scratch_file> file(Scratch_file::open_named(records.temporary_path()));
    const Record_file scanned = scan(in_path, file, s, log);
    records.commit();
    const std::vector<Pass> passes = passes_of(s, log.had_normals);
    bin_into_job(job, 0, passes[0], scanned, s, settings);
    write_whole_file(job_path(job, "run"), "format " + log.format + "\npoints " + std::to_string(log.points) + "\nnormals " +
                                           std::to_string(int(log.had_normals)) + "\npasses " + std::to_string(passes.size()) +
                                           "\nwrite_in_parts " + std::to_string(int(writes_in_parts(in_path, settings))) + "\n");
    return passes.size();
  });
}

std::size_t staged_tiles(const std::string& job, std::size_t pass)
{
  std::istringstream is(read_whole_file(pass_path(job, pass, "tiles")));
  std::size_t n = 0;
  if(!(is >> n)) throw std::runtime_error(pass_path(job, pass, "tiles") + ": no tile count");
  return n;
}

void staged_tile(const std::string& job, std::size_t pass, std::size_t tile, const Fit_settings& s, const Streaming_settings& settings)
{
  in_job(job, [&] {
    const std::vector<Pass> passes = passes_of(s, read_job(job).had_normals);
    if(pass >= passes.size()) throw std::runtime_error("no pass " + std::to_string(pass));
    Streamed_pass p(passes[pass], s, settings.tile_size, [](double) { return true; });
    p.load_plan(pass_path(job, pass, "plan"), std::shared_ptr<Scratch_file>(Scratch_file::open_named(pass_path(job, pass, "bins"))));
    Tile_trailer trailer;
    std::string bytes;
    try {
      bytes = p.run_one_tile(tile, trailer.report, trailer.rerun, trailer.bounds);
    } catch(const std::runtime_error& e) {
      throw std::runtime_error("tile " + std::to_string(tile) + " of pass " + std::to_string(pass) + ": " + e.what());
    }
    trailer.bytes = p.output_bytes();
    trailer.count = bytes.size() / trailer.bytes;
    bytes.append(reinterpret_cast<const char*>(&trailer), sizeof trailer);
    write_whole_file(pass_path(job, pass, "tile-" + std::to_string(tile)), bytes);
    return 0;
  });
}

void staged_bin(const std::string& job, std::size_t pass, const Fit_settings& s, const Streaming_settings& settings)
{
  in_job(job, [&] {
    const std::vector<Pass> passes = passes_of(s, read_job(job).had_normals);
    if(pass == 0 || pass >= passes.size()) throw std::runtime_error("no pass " + std::to_string(pass) + " to bin");
    Streamed_run unused;
    bin_into_job(job, pass, passes[pass], tile_results(job, passes, pass - 1, unused), s, settings);
    return 0;
  });
}

Streamed_run staged_write(const std::string& in_path, const std::string& out_path, const std::string& job,
                          const Fit_settings& s, const Streaming_settings& settings, const Callback& progress)
{
  return in_job(job, [&] {
    Streamed_run log;
    const Record_file records = last_results(job, s, log);
    write_output(in_path, out_path, s, settings, records, log, progress);
    return log;
  });
}

void staged_write_part(const std::string& in_path, const std::string& job, std::size_t part, std::size_t parts,
                       const Fit_settings& s, const Streaming_settings& settings)
{
  in_job(job, [&] {
    if(part >= parts) throw std::runtime_error("no part " + std::to_string(part) + " of " + std::to_string(parts));
    if(!writes_in_parts(in_path, settings)) throw std::runtime_error("the output is written in parts only in binary from a binary PLY");
    Streamed_run log;
    const Record_file records = last_results(job, s, log);
    const Output_layout layout = output_layout(in_path, s, settings, log.had_normals, log.points);
    const std::uint64_t first = layout.points * part / parts, end = layout.points * (part + 1) / parts;
    const std::unique_ptr<Scratch_file> out(Scratch_file::open_named(job_path(job, "output"), true));
    const std::uint64_t fitted = write_vertices(in_path, first, end, layout, records, s, settings, log.had_normals, *out,
                                                layout.header.size() + first * layout.vertex_bytes, [](double) {});
    write_whole_file(output_part_path(job, part, parts), std::to_string(fitted));   // the part's fitted points
    return 0;
  });
}

Streamed_run staged_finish(const std::string& in_path, const std::string& out_path, const std::string& job, std::size_t parts,
                           const Fit_settings& s, const Streaming_settings& settings)
{
  return in_job(job, [&] {
    Streamed_run log;
    last_results(job, s, log);   // the tiles' reports
    const Output_layout layout = output_layout(in_path, s, settings, log.had_normals, log.points);
    log.columns = layout.columns;
    std::uint64_t fitted = 0;
    for(std::size_t p = 0; p < parts; ++p) {
      std::ifstream marker(output_part_path(job, p, parts));
      std::uint64_t part_fitted = 0;
      if(!(marker >> part_fitted)) throw std::runtime_error("part " + std::to_string(p) + " of " + std::to_string(parts) + " of the output is not written");
      fitted += part_fitted;
    }
    check_written_counts(log, fitted);
    const std::string written = job_path(job, "output");
    {
      const std::unique_ptr<Scratch_file> out(Scratch_file::open_named(written));
      if(out->size() != layout.header.size() + layout.points * layout.vertex_bytes)
        throw std::runtime_error(written + ": not the size of the output (not written in " + std::to_string(parts) + " parts?)");
      out->write(layout.header.data(), layout.header.size(), 0);
    }
    if(std::rename(written.c_str(), out_path.c_str()) != 0)
      throw File_error(out_path + ": cannot move " + written + " to it (" + std::strerror(errno) + "; the job folder must be on the output's file system)");
    return log;
  });
}

Streamed_run run_streamed(const std::string& in_path, const std::string& out_path, const Fit_settings& s,
                          const Streaming_settings& settings, const Callback& progress)
{
  try {
    return run(in_path, out_path, s, settings, progress);
  } catch(const File_error&) {
    throw;
  } catch(const std::runtime_error& e) {   // the scratch files' errors (a full disk): name the output
    throw File_error(out_path + ": " + e.what());
  }
}

} // namespace wavejets_demo
