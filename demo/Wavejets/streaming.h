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
  std::optional<CGAL::Wavejets::Processing_report> bare_normals, command, result_normals;
  double scan_seconds = 0., binning_seconds = 0., fit_seconds = 0., write_seconds = 0.;
  std::vector<std::string> columns; // the output's PLY properties, in order
};

/// The tile size that keeps a streamed run's resident memory near `bytes`.
std::size_t tile_size_for_memory(double bytes);

/// Runs the command of `fit` on the point set of `in_path` (PLY, binary or ASCII, or XYZ / PWN) and
/// writes `out_path` (PLY), holding one tile and its halo in memory at a time. Scratch files go
/// next to `out_path` and are unlinked as soon as created (no exit leaves them behind); `out_path`
/// is written through a temporary file renamed at the end. `progress` gets the fraction of the
/// whole run done. Throws File_error for what the in-core run rejects (and for a mesh, a PLY with
/// other elements than vertices, a point set without normals and without `fit.viewpoint`, a full disk).
Streamed_run run_streamed(const std::string& in_path, const std::string& out_path, const Fit_settings& fit,
                          const Streaming_settings& settings, const Callback& progress);

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_STREAMING_H
