// See platform.h.
#include "platform.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <stdexcept>

#if defined(_WIN32)
#include <io.h>
#else
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

} // namespace wavejets_demo
