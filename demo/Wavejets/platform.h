// The operating-system services of the `wavejets` tool, in one place: everything else in demo/Wavejets
// is standard C++17. POSIX systems get the full behaviour; elsewhere (e.g. Windows) the standard
// library's equivalents, noted at each function.
#ifndef WAVEJETS_DEMO_PLATFORM_H
#define WAVEJETS_DEMO_PLATFORM_H

#include <cstddef>
#include <cstdint>
#include <string>

namespace wavejets_demo {

/// Whether standard error is a terminal (the progress bar is drawn only then).
bool stderr_is_terminal();

/// Creates a new empty file whose name is `prefix` followed by random characters, with the
/// permissions a new file gets by default (fopen's "x" mode: never an existing file); returns its
/// name. Throws std::runtime_error if the folder does not take new files.
std::string create_unique_file(const std::string& prefix);

/// For a process that allocates and frees buffers of megabytes again and again (the tool's streamed
/// passes): memory freed is kept for the next allocation instead of being returned to the system
/// and faulted in again (glibc: allocations up to 32 MB from the heap, no trimming below 1 GB).
/// Measured on a streamed run's writing step: 9.6 s -> 4.1 s at 10^7 points. Elsewhere: nothing.
void keep_freed_memory_for_reuse();

/// On SIGINT and SIGTERM: removes the file named in `path` (if not empty), prints that nothing was
/// written, and exits with 128 + the signal number. `path` must stay valid; it is read by the handler.
void remove_on_interrupt(const char* path);

/// A scratch file of a streamed run, in the folder of `near` (the output: same disk), unlinked as
/// soon as it is created: it has no name, and the system frees it when the process exits, however
/// (an error, an interrupt, a kill). Reads and writes at byte offsets; errors (a full disk) throw
/// std::runtime_error with the reason.
class Scratch_file
{
public:
  explicit Scratch_file(const std::string& near);
  /// A named file of a staged streamed run (wavejets.distributed), opened for reading and writing
  /// (created empty if `create` and missing; never truncated) and left in place.
  static Scratch_file* open_named(const std::string& path, bool create = false);
  ~Scratch_file();
  Scratch_file(const Scratch_file&) = delete;
  Scratch_file& operator=(const Scratch_file&) = delete;
  void write(const void* data, std::size_t bytes, std::uint64_t offset);
  void read(void* data, std::size_t bytes, std::uint64_t offset) const;
  std::uint64_t size() const;
private:
  Scratch_file() = default;
  int fd_ = -1;
};

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_PLATFORM_H
