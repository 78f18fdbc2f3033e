// See streaming.h. A streamed run, in passes over files, never holding the whole point set:
//  1. scan: IN is read in chunks (CGAL's own reader on each chunk, so that every value is the
//     in-core one), checked as in core (NaN, coinciding points, normals), and copied as records
//     (index, position, normal, fitted, curvature) into a scratch file;
//  2. per pass of the library (normals of a point set without normals; the command; for
//     enhance-positions the normals of the moved points): a histogram of the records on a grid,
//     tiles as median splits of the grid's cells, the records binned by cell (a tile's cells
//     contiguous), then per tile: the points within its halo are read back in global order and
//     the library function runs on them with Wavejets::parameters::tile(); the points whose
//     neighborhood reaches past the halo are run again with a halo twice as large. Every pass
//     writes one record per point, tile after tile, each tile's records in index order;
//  3. write: IN is read again in chunks, each chunk gets its records (a merge of the tiles' sorted
//     runs) and is written by CGAL's PLY writer; the first header (its vertex count set to the
//     whole count) and the bodies make the file the in-core run writes, byte for byte.
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
    if(ext == "ply") {
      check_ply_coordinate_types(path);
      read_ply_header();
    }
    else format_ = "XYZ";
  }
  const std::string& format() const { return format_; }

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
    std::ostringstream cgal_messages;
    std::streambuf* saved = std::cerr.rdbuf(cgal_messages.rdbuf());
    bool ok = false;
    try {
      ok = format_ == "PLY" ? CGAL::IO::read_PLY(is, chunk) : CGAL::IO::read_XYZ(is, chunk);
    } catch(const std::exception& e) { cgal_messages << e.what() << "\n"; }
    std::cerr.rdbuf(saved);
    if(!ok || (format_ == "PLY" && chunk.size() != count)) {
      std::string why = cgal_messages.str();
      why = why.substr(0, why.find('\n'));
      if(why.compare(0, 7, "Error: ") == 0) why = why.substr(7);
      throw File_error(path_ + ": not a valid " + format_ + " file (" + (why.empty() ? "malformed or truncated" : why) + ")");
    }
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
  void read_ply_header()
  {
    format_ = "PLY";
    std::string line, header;
    bool vertex_seen = false, ended = false;
    for(int i = 0; i < 100000 && std::getline(is_, line); ++i) {
      const std::string raw = line + "\n";
      if(!line.empty() && line.back() == '\r') line.pop_back();
      std::istringstream s(line);
      std::string word, a, b;
      s >> word;
      if(word == "format") {
        s >> a;
        binary_ = a != "ascii";
        little_endian_ = a == "binary_little_endian";
      } else if(word == "element") {
        s >> a >> b;
        if(vertex_seen || a != "vertex")
          throw File_error(path_ + ": a streamed run reads PLY point sets (one vertex element); this file has a '" + a +
                           "' element (give no --max-memory / --tile-size to process a mesh in memory)");
        vertex_seen = true;
        char* end = nullptr;
        remaining_ = std::strtoull(b.c_str(), &end, 10);
        before_count_ = header;
        header.clear();
        continue;
      } else if(word == "property" && vertex_seen) {
        s >> a;
        if(a == "list") throw File_error(path_ + ": a streamed run reads PLY vertices without list properties");
        const std::size_t bytes = a == "char" || a == "uchar" || a == "int8" || a == "uint8" ? 1
                                : a == "short" || a == "ushort" || a == "int16" || a == "uint16" ? 2
                                : a == "int" || a == "uint" || a == "float" || a == "int32" || a == "uint32" || a == "float32" ? 4
                                : a == "double" || a == "float64" ? 8 : 0;
        if(bytes == 0) throw File_error(path_ + ": not a valid PLY file (unknown property type '" + a + "')");
        s >> b;
        const bool floating = a == "float" || a == "float32" || a == "double" || a == "float64";
        for(int f = 0; f < 6; ++f)
          if(b == field_names[f]) fields_[f] = Field{record_bytes_, floating ? bytes : 0, true};
        record_bytes_ += bytes;
      }
      header += raw;
      if(word == "end_header") { ended = true; break; }
    }
    if(!ended || !vertex_seen || record_bytes_ == 0)
      throw File_error(path_ + ": not a valid PLY file (no end_header, or no vertex element with properties)");
    after_count_ = header;
    announced_ = remaining_;
    const std::uint16_t one = 1;
    unsigned char first_byte;
    std::memcpy(&first_byte, &one, 1);
    direct_ = binary_ && little_endian_ && first_byte == 1;
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
  std::uint64_t remaining_ = 0, announced_ = 0;
};

// ------------------------------------------------------------------------------------------------
// One point between passes: its index in the input, position, normal and fitted flag (64 bytes).
struct Record
{
  std::uint64_t index;
  double position[3], normal[3];
  std::uint64_t fitted;
};
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
  bool done() const { return next_ == end_ && at_ == size_; }
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

// Whether the run may use more than one thread (not with --threads 1: a sequential run).
bool more_than_one_thread()
{
#ifdef CGAL_LINKED_WITH_TBB
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
#else
  return false;
#endif
}

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
    vec(tiles_); vec(cell_first_); vec(cell_count_); vec(tile_first_); vec(tile_of_); vec(tile_box_);
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
    vec(tiles_); vec(cell_first_); vec(cell_count_); vec(tile_first_); vec(tile_of_); vec(tile_box_);
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
    // Cells in tile order: a tile's records are contiguous in the bins, each cell's too.
    cell_first_.assign(grid_.size(), 0);
    tile_of_.assign(grid_.size(), 0);
    std::vector<std::uint32_t>& tile_of = tile_of_;
    std::uint64_t next = 0;
    for(std::size_t t = 0; t < tiles_.size(); ++t) {
      tile_first_.push_back(next);
      const Cell_box& b = tiles_[t];
      for(long x = b.lo[0]; x < b.hi[0]; ++x)
        for(long y = b.lo[1]; y < b.hi[1]; ++y)
          for(long z = b.lo[2]; z < b.hi[2]; ++z) {
            const std::size_t c = std::size_t((x * grid_.n[1] + y) * grid_.n[2] + z);
            cell_first_[c] = next;
            tile_of[c] = std::uint32_t(t);
            next += counts[c];
          }
    }
    tile_first_.push_back(next);
    cell_count_ = std::move(counts);
    // Each tile buffers its records, then writes them at their cells' next places.
    // 64 MB of buffers in all, at least 64 records per tile.
    const std::size_t per_tile = std::max<std::size_t>(64, (std::size_t(64) << 20) / sizeof(Record) / tiles_.size());
    std::vector<std::vector<Record> > buffers(tiles_.size());
    tile_box_.assign(tiles_.size(), CGAL::Bbox_3());
    std::vector<std::uint64_t> cursor = cell_first_;
    std::vector<char> bytes;
    auto flush = [&](std::vector<Record>& buffer) {
      std::vector<std::pair<std::uint64_t, const Record*> > placed;
      for(const Record& r : buffer) placed.emplace_back(cursor[grid_.cell_of(r.position)]++, &r);
      std::sort(placed.begin(), placed.end());
      for(std::size_t i = 0; i < placed.size();) {
        std::size_t j = i + 1;
        while(j < placed.size() && placed[j].first == placed[j - 1].first + 1) ++j;
        bytes.resize((j - i) * sizeof(Record));
        for(std::size_t m = i; m < j; ++m) std::memcpy(&bytes[(m - i) * sizeof(Record)], placed[m].second, sizeof(Record));
        bins_->write(bytes.data(), bytes.size(), placed[i].first * sizeof(Record));
        i = j;
      }
      buffer.clear();
    };
    for_each_input(in, [&](const Record& r) {
      const std::uint32_t t = tile_of[grid_.cell_of(r.position)];
      tile_box_[t] += CGAL::Bbox_3(r.position[0], r.position[1], r.position[2], r.position[0], r.position[1], r.position[2]);
      std::vector<Record>& buffer = buffers[t];
      if(buffer.empty()) buffer.reserve(per_tile);
      buffer.push_back(r);
      if(buffer.size() == per_tile) flush(buffer);
    });
    for(std::vector<Record>& buffer : buffers) flush(buffer);
  }

private:
  static constexpr std::uint64_t plan_magic = 0x57564a5053504c31ull;   // "WVJPSPL1"

  template <class F> static void for_each_input(const Record_file& in, const F& f)
  {
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
    std::uint64_t count = 0;
    for(long x = from[0]; x < to[0]; ++x)
      for(long y = from[1]; y < to[1]; ++y)
        for(long z = from[2]; z < to[2]; ++z) count += cell_count_[std::size_t((x * grid_.n[1] + y) * grid_.n[2] + z)];
    std::vector<Record> found;
    found.reserve(std::size_t(count));
    std::vector<Record> cell;
    for(long x = from[0]; x < to[0]; ++x)
      for(long y = from[1]; y < to[1]; ++y)
        for(long z = from[2]; z < to[2]; ++z) {
          const std::size_t c = std::size_t((x * grid_.n[1] + y) * grid_.n[2] + z);
          if(cell_count_[c] == 0) continue;
          cell.resize(std::size_t(cell_count_[c]));
          bins_->read(cell.data(), cell.size() * sizeof(Record), cell_first_[c] * sizeof(Record));
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
    const std::size_t tile_points = std::size_t(tile_first_[t + 1] - tile_first_[t]);
    g.halo = first_halo(box, tile_points);
    const double h = g.halo;
    g.extent = CGAL::Bbox_3(box.xmin() - h, box.ymin() - h, box.zmin() - h, box.xmax() + h, box.ymax() + h, box.zmax() + h);
    g.points = points_in(g.extent);
    g.targets.reserve(tile_points);
    for(std::size_t i = 0; i < g.points.size(); ++i)
      if(tile_of_[grid_.cell_of(g.points[i].position)] == t) g.targets.push_back(i);
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
  std::vector<std::uint64_t> cell_first_, cell_count_, tile_first_;
  std::vector<std::uint32_t> tile_of_;   // per cell
  std::vector<CGAL::Bbox_3> tile_box_;   // of each tile's points
  std::shared_ptr<Scratch_file> bins_;
  std::uint64_t done_points_ = 0, rerun_ = 0;
  std::vector<char> results_;      // of the current tile, result_bytes_ each, in index order
  std::size_t result_bytes_ = sizeof(Record);
};

// Chunks of at most this many points are read and written at a time.
const std::size_t chunk_points = 1 << 16;

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
    Record r;
    std::memset(&r, 0, sizeof r);
    r.index = f.count;
    r.position[0] = x; r.position[1] = y; r.position[2] = z;
    if(normal) {
      r.normal[0] = normal[0]; r.normal[1] = normal[1]; r.normal[2] = normal[2];
      const double l = normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2];
      any_normal = any_normal || (std::isfinite(l) && l > 0);
    }
    const CGAL::Bbox_3 b(x, y, z, x, y, z);
    if(f.count == 0) { first_point[0] = x; first_point[1] = y; first_point[2] = z; f.bounds = b; }
    else { f.bounds += b; all_same = all_same && x == first_point[0] && y == first_point[1] && z == first_point[2]; }
    writer.put(&r);
    ++f.count;
  };
  if(chunks.reads_directly()) {
    std::vector<double> v;
    while(chunks.next_values(v, chunk_points))
      for(std::size_t i = 0; i < v.size(); i += 6) add(v[i], v[i + 1], v[i + 2], chunks.has_normals() ? &v[i + 3] : nullptr);
  } else {
    Point_set chunk;
    while(chunks.next(chunk, chunk_points))
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
  f.runs.push_back(Record_run{file, 0, f.count});
  log.scan_seconds = seconds_since(t0);
  return f;
}

// The records of the indices [first, first + out.size()), from the runs of `f` (each sorted).
class Record_merge
{
public:
  explicit Record_merge(const Record_file& f)
  {
    const std::size_t bytes = f.bytes;
    // 32 MB of buffers in all, at least 64 records per run.
    const std::size_t buffered = std::max<std::size_t>(64, (std::size_t(32) << 20) / bytes / std::max<std::size_t>(1, f.runs.size()));
    for(const Record_run& run : f.runs) streams_.emplace_back(new Record_stream(*run.file, bytes, run.first, run.end, buffered));
  }
  void next(std::uint64_t first, std::vector<Result>& out)
  {
    for(auto& s : streams_)
      while(!s->done() && s->peek().record.index < first + out.size()) {
        const Result& r = s->take();
        out[std::size_t(r.record.index - first)] = r;
      }
  }
private:
  std::vector<std::unique_ptr<Record_stream> > streams_;
};

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
  if(output_format(out_path) != Output_format::PLY)
    throw File_error(out_path + ": a streamed run writes a .ply file");
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

// Writing: the input again, chunk by chunk, with the records' values.
void write_output(const std::string& in_path, const std::string& out_path, const Fit_settings& s,
                  const Streaming_settings& settings, const Record_file& records, Streamed_run& log, const Callback& progress)
{
  const Clock::time_point tw = Clock::now();
  Output_file out(out_path);
  {
    std::ofstream os(out.temporary_path(), std::ios::binary);
    if(!os) throw File_error(out_path + ": cannot write (" + std::strerror(errno) + ")");
    Input_chunks chunks(in_path);
    Record_merge merge(records);
    Point_set chunk;
    std::uint64_t first = 0;
    bool header_written = false;
    std::vector<Result> values;
    while(chunks.next(chunk, chunk_points)) {
      if(chunk.empty()) continue;
      if(log.had_normals && !chunk.has_normal_map()) chunk.add_normal_map(Vector(0, 0, 0));
      if(!log.had_normals && chunk.has_normal_map()) chunk.remove_normal_map();
      const Output_columns columns = add_output_columns(chunk, s.command);
      values.assign(chunk.size(), Result());
      merge.next(first, values);
      std::size_t j = 0;
      for(Point_set::Index i : chunk) {
        const Result& v = values[j++];
        const Record& r = v.record;
        if(s.command == POSITIONS) chunk.point(i) = Point(r.position[0], r.position[1], r.position[2]);
        chunk.normal(i) = Vector(r.normal[0], r.normal[1], r.normal[2]);
        columns.fitted[i] = (unsigned char)(r.fitted);
        for(std::size_t c = 0; c < columns.curvature.size(); ++c) columns.curvature[c][i] = v.curvature[c];
      }
      const std::string text = ply_text(chunk, settings.ascii, settings.comment);
      const std::size_t body = text.find("end_header\n") + 11;
      if(!header_written) {
        std::string header = text.substr(0, body);
        const std::string count = "element vertex " + std::to_string(chunk.size()) + "\n";
        header.replace(header.find(count), count.size(), "element vertex " + std::to_string(log.points) + "\n");
        os.write(header.data(), std::streamsize(header.size()));
        header_written = true;
        for(const std::string& p : chunk.properties())
          if(p != "index" && p != "point") log.columns.push_back(p == "normal" ? "nx ny nz" : p);
      }
      os.write(text.data() + body, std::streamsize(text.size() - body));
      first += chunk.size();
      if(!os) break;
      progress(0.9 + 0.1 * double(first) / double(log.points));
    }
    os.close();
    if(!os) throw File_error(out_path + ": cannot write (disk full or not writable?)");
    if(first != log.points) throw File_error(in_path + ": changed while it was read (" + std::to_string(first) + " points read again, " +
                                             std::to_string(log.points) + " before)");
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
//   pass-P.bins    the records of pass P binned by cell; pass-P.plan: the tiles; pass-P.tiles: their number (text)
//   pass-P.tile-T  the results of tile T of pass P (in index order), then a Tile_trailer
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

// Bins `in` for `pass` into the job folder.
void bin_into_job(const std::string& job, std::size_t pass, Pass kind, const Record_file& in, const Fit_settings& s,
                  const Streaming_settings& settings)
{
  Output_file bins(pass_path(job, pass, "bins"));
  Streamed_pass p(kind, s, settings.tile_size, [](double) { return true; });
  p.bin(in, std::shared_ptr<Scratch_file>(Scratch_file::open_named(bins.temporary_path())));
  bins.commit();
  p.save_plan(pass_path(job, pass, "plan"));
  write_whole_file(pass_path(job, pass, "tiles"), std::to_string(p.number_of_tiles()) + "\n");
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

std::size_t staged_prepare(const std::string& in_path, const std::string& out_path, const std::string& job,
                           const Fit_settings& s, const Streaming_settings& settings)
{
  return in_job(job, [&] {
    if(output_format(out_path) != Output_format::PLY) throw File_error(out_path + ": a streamed run writes a .ply file");
    Streamed_run log;
    Output_file records(job_path(job, "records"));
    const std::shared_ptr<Scratch_file> file(Scratch_file::open_named(records.temporary_path()));
    const Record_file scanned = scan(in_path, file, s, log);
    records.commit();
    const std::vector<Pass> passes = passes_of(s, log.had_normals);
    bin_into_job(job, 0, passes[0], scanned, s, settings);
    write_whole_file(job_path(job, "run"), "format " + log.format + "\npoints " + std::to_string(log.points) + "\nnormals " +
                                           std::to_string(int(log.had_normals)) + "\npasses " + std::to_string(passes.size()) + "\n");
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
    const Job_info info = read_job(job);
    Streamed_run log;
    log.format = info.format;
    log.points = std::size_t(info.points);
    log.had_normals = info.had_normals;
    const std::vector<Pass> passes = passes_of(s, info.had_normals);
    Record_file records;
    for(std::size_t p = 0; p < passes.size(); ++p) records = tile_results(job, passes, p, log);
    if(records.count != info.points)
      throw std::runtime_error("the tiles hold " + std::to_string(records.count) + " points, the input " + std::to_string(info.points));
    write_output(in_path, out_path, s, settings, records, log, progress);
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
