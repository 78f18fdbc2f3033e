// Streamed runs of the `wavejets` tool's fitting commands (--max-memory, --tile-size): point sets
// larger than memory, read in passes and processed in spatial tiles (the library's Wavejets::Tile
// unit), writing the same file as the in-core run, byte for byte.
#ifndef WAVEJETS_DEMO_STREAMING_H
#define WAVEJETS_DEMO_STREAMING_H

#include "fit_command.h"

#include <optional>
#include <string>

namespace wavejets_demo {

/// A streamed run's parameters besides the command's.
struct Streaming_settings
{
  std::size_t tile_size = 0;   // points per tile (the memory of a run grows with it, not with the input)
  bool ascii = false;          // ASCII PLY output (else binary little-endian)
  std::string comment;         // the output's PLY comment, as in core
};

/// What a streamed run did, for the tool's summary.
struct Streamed_run
{
  std::string format;              // "PLY" or "XYZ"
  std::size_t points = 0;
  bool had_normals = false;
  std::size_t tiles = 0;           // tiles of the command's pass
  std::size_t rerun_points = 0;    // points fitted again with a larger halo, over every pass
  std::uint64_t written_fitted = 0; // points written with `fitted` 1 (the tiles' reports must agree)
  std::optional<CGAL::Wavejets::Processing_report> bare_normals, command, result_normals;
  double scan_seconds = 0., binning_seconds = 0., fit_seconds = 0., write_seconds = 0.;
  std::vector<std::string> columns; // the output's PLY properties, in order
};

/// The tile size that keeps a streamed run's resident memory near `bytes`.
std::size_t tile_size_for_memory(double bytes);

/// Runs the command of `fit` on the point set of `in_path` (PLY, binary or ASCII, or XYZ / PWN) and
/// writes `out_path` (PLY, whatever its extension: the caller checks it), holding one tile and its halo in memory at a time. Scratch files go
/// next to `out_path` and are unlinked as soon as created (no exit leaves them behind); `out_path`
/// is written through a temporary file renamed at the end. `progress` gets the fraction of the
/// whole run done. Throws File_error for what the in-core run rejects (and for a mesh, a PLY with
/// other elements than vertices, a point set without normals and without `fit.viewpoint`, a full disk).
Streamed_run run_streamed(const std::string& in_path, const std::string& out_path, const Fit_settings& fit,
                          const Streaming_settings& settings, const Callback& progress);

/// A streamed run in steps that separate processes, or machines sharing the folder `job`, can run
/// (wavejets.distributed runs them as Dask tasks): staged_prepare() (scan IN, bin the first pass),
/// then for each pass P: staged_tile(P, T) for every tile T (independent tasks, in any order),
/// and before the next pass staged_bin(P + 1); finally staged_write() writes OUT, the bytes of
/// run_streamed(). Each step reads what the earlier ones wrote in `job` (an existing folder, left
/// to the caller to remove) and writes its files under temporary names, renamed when complete: a
/// step run again (a lost worker's task) is harmless. Every step gets the same settings.
/// Returns the number of passes.
std::size_t staged_prepare(const std::string& in_path, const std::string& job,
                           const Fit_settings& fit, const Streaming_settings& settings);
/// The number of tiles of pass `pass` (once prepared or binned).
std::size_t staged_tiles(const std::string& job, std::size_t pass);
void staged_tile(const std::string& job, std::size_t pass, std::size_t tile, const Fit_settings& fit,
                 const Streaming_settings& settings);
void staged_bin(const std::string& job, std::size_t pass, const Fit_settings& fit, const Streaming_settings& settings);
/// The run's summary (without timings).
Streamed_run staged_write(const std::string& in_path, const std::string& out_path, const std::string& job,
                          const Fit_settings& fit, const Streaming_settings& settings, const Callback& progress);
/// Or OUT in `parts` steps, where the job's file `run` says `write_in_parts 1` (binary output of a
/// binary PLY): staged_write_part(C, parts) for each C (independent tasks) writes the vertices of
/// part C, then staged_finish() writes the header and moves the file to OUT.
void staged_write_part(const std::string& in_path, const std::string& job, std::size_t part, std::size_t parts,
                       const Fit_settings& fit, const Streaming_settings& settings);
Streamed_run staged_finish(const std::string& in_path, const std::string& out_path, const std::string& job, std::size_t parts,
                           const Fit_settings& fit, const Streaming_settings& settings);

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_STREAMING_H
