// The benchmarks' source folder (bench_common.h), from CMake's WAVEJETS_BENCHMARK_SOURCE_DIR.
#include "bench_common.h"

std::string wavejets_bench::source_dir() { return WAVEJETS_BENCHMARK_SOURCE_DIR; }
