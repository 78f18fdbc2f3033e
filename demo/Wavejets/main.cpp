// The `wavejets` command-line tool (wavejets.cpp). An interrupt (Ctrl-C) removes the output being
// written, and its scratch files go with the process.
#include "platform.h"
#include "render.h"
#include "tool.h"

int main(int argc, char** argv)
{
  wavejets_demo::remove_output_files_on_interrupt();
  wavejets_demo::keep_freed_memory_for_reuse();
  return wavejets_demo::run_wavejets_tool(std::vector<std::string>(argv + 1, argv + argc));
}
