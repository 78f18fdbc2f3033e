// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

// _run_tool: the `wavejets` tool (demo/Wavejets/tool.h) in this process, its output captured: the
// steps of wavejets.distributed's runs (`--job DIR --stage STEP`) in Dask workers. Only pybind11
// and tool.h here: a light translation unit.
#include "platform.h"
#include "tool.h"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace py = pybind11;

namespace wavejets_python {

void bind_tool(py::module_& m)
{
  m.def("_keep_freed_memory_for_reuse", &wavejets_demo::keep_freed_memory_for_reuse,
        "In a process that runs the tool's steps (a Dask worker): keep freed memory for the next "
        "allocation (glibc's malloc settings; see demo/Wavejets/platform.h).");
  m.def("_run_tool", [](const std::vector<std::string>& args) {
    // One call at a time in a process: the tool prints to std::cout / std::cerr, redirected here,
    // and each call already uses every thread it is given.
    static std::mutex one_at_a_time;
    std::ostringstream out, err;
    int status = 0;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(one_at_a_time);
      std::streambuf* saved_out = std::cout.rdbuf(out.rdbuf());
      std::streambuf* saved_err = std::cerr.rdbuf(err.rdbuf());
      try {
        status = wavejets_demo::run_wavejets_tool(args);
      } catch(...) {
        std::cout.rdbuf(saved_out);
        std::cerr.rdbuf(saved_err);
        throw;
      }
      std::cout.rdbuf(saved_out);
      std::cerr.rdbuf(saved_err);
    }
    return py::make_tuple(status, out.str(), err.str());
  }, py::arg("args"),
  "Runs the wavejets tool on its arguments (without the program's name) in this process: "
  "(exit status, standard output, standard error). For wavejets.distributed.");
}

} // namespace wavejets_python
