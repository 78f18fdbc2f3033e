// The `wavejets` tool as a function: main.cpp calls it, and the Python module too (wavejets.distributed
// runs the steps of a streamed run, `--job DIR --stage STEP`, in its Dask workers).
#ifndef WAVEJETS_DEMO_TOOL_H
#define WAVEJETS_DEMO_TOOL_H

#include <string>
#include <vector>

namespace wavejets_demo {

/// Runs the tool on its command-line arguments (without the program's name): prints to std::cout
/// and std::cerr as the tool does, returns its exit status (0, 1 for a file or input error, 2 for
/// a usage error). `--help` and `--version` exit the process.
int run_wavejets_tool(const std::vector<std::string>& args);

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_TOOL_H
