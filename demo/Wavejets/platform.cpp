// See platform.h.
#include "platform.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <stdexcept>

#if defined(_WIN32)
#include <io.h>
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace wavejets_demo {
namespace {
const char* g_interrupt_path = nullptr;

extern "C" void remove_and_exit(int sig)
{
  if(g_interrupt_path && g_interrupt_path[0] != 0) std::remove(g_interrupt_path);
  static const char message[] = "\nwavejets: interrupted, nothing written\n";
#if defined(_WIN32)
  std::fputs(message, stderr);
#else
  const ssize_t ignored = write(2, message, sizeof(message) - 1); // async-signal-safe
  (void)ignored;
#endif
  std::_Exit(128 + sig);
}
} // namespace

bool stderr_is_terminal()
{
#if defined(_WIN32)
  return _isatty(_fileno(stderr)) != 0;
#else
  return isatty(2) != 0;
#endif
}

std::string create_unique_file(const std::string& prefix)
{
  static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device device;
  std::mt19937 random(device());
  std::uniform_int_distribution<int> pick(0, int(sizeof(letters)) - 2);
  int error = 0;
  for(int attempt = 0; attempt < 100; ++attempt)
  {
    std::string name = prefix;
    for(int c = 0; c < 6; ++c) name += letters[pick(random)];
    errno = 0;
    if(std::FILE* f = std::fopen(name.c_str(), "wbx")) // C11 / C++17: fails if the file exists
    {
      std::fclose(f);
      return name;
    }
    error = errno;
    if(error != EEXIST) break;
  }
  throw std::runtime_error("cannot create a file named " + prefix + "... (" + std::strerror(error) + ")");
}

void remove_on_interrupt(const char* path)
{
  g_interrupt_path = path;
  std::signal(SIGINT, remove_and_exit);
  std::signal(SIGTERM, remove_and_exit);
}

Scratch_file::Scratch_file(const std::string& near)
{
#if defined(_WIN32)
  (void)near;
  throw std::runtime_error("streamed runs need a POSIX system (scratch files without a name)");
#else
  const std::size_t slash = near.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : near.substr(0, slash + 1 == 1 ? 1 : slash);
  std::string name;
  try {
    name = create_unique_file(dir + "/.wavejets-scratch-");
  } catch(const std::runtime_error& e) {
    throw std::runtime_error("cannot create a scratch file in " + dir + " (" + e.what() + ")");
  }
  fd_ = ::open(name.c_str(), O_RDWR);
  const int error = errno;
  ::unlink(name.c_str());
  if(fd_ < 0) throw std::runtime_error("cannot open a scratch file in " + dir + " (" + std::strerror(error) + ")");
#endif
}

void keep_freed_memory_for_reuse()
{
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

Scratch_file* Scratch_file::open_named(const std::string& path, bool create)
{
  Scratch_file* f = new Scratch_file();
#if !defined(_WIN32)
  f->fd_ = create ? ::open(path.c_str(), O_RDWR | O_CREAT, 0666) : ::open(path.c_str(), O_RDWR);
  if(f->fd_ < 0) {
    const int error = errno;
    delete f;
    throw std::runtime_error("cannot open " + path + " (" + std::strerror(error) + ")");
  }
#else
  (void)create;
  delete f;
  throw std::runtime_error("staged runs need a POSIX system");
#endif
  return f;
}

std::uint64_t Scratch_file::size() const
{
#if !defined(_WIN32)
  struct stat st;
  if(::fstat(fd_, &st) != 0) throw std::runtime_error(std::string("cannot read a scratch file (") + std::strerror(errno) + ")");
  return std::uint64_t(st.st_size);
#else
  return 0;
#endif
}

Scratch_file::~Scratch_file()
{
#if !defined(_WIN32)
  if(fd_ >= 0) ::close(fd_);
#endif
}

void Scratch_file::write(const void* data, std::size_t bytes, std::uint64_t offset)
{
#if !defined(_WIN32)
  const char* p = static_cast<const char*>(data);
  while(bytes > 0) {
    const ssize_t n = ::pwrite(fd_, p, bytes, off_t(offset));
    if(n < 0 && errno == EINTR) continue;
    if(n <= 0) throw std::runtime_error(std::string("cannot write a scratch file (") + (n < 0 ? std::strerror(errno) : "no space") + ")");
    p += n; bytes -= std::size_t(n); offset += std::uint64_t(n);
  }
#else
  (void)data; (void)bytes; (void)offset;
#endif
}

void Scratch_file::read(void* data, std::size_t bytes, std::uint64_t offset) const
{
#if !defined(_WIN32)
  char* p = static_cast<char*>(data);
  while(bytes > 0) {
    const ssize_t n = ::pread(fd_, p, bytes, off_t(offset));
    if(n < 0 && errno == EINTR) continue;
    if(n <= 0) throw std::runtime_error(std::string("cannot read a scratch file (") + (n < 0 ? std::strerror(errno) : "too short") + ")");
    p += n; bytes -= std::size_t(n); offset += std::uint64_t(n);
  }
#else
  (void)data; (void)bytes; (void)offset;
#endif
}

} // namespace wavejets_demo
