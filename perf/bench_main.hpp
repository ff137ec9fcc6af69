// Shared main() for Google Benchmark drivers: initialises MPI (if built with
// it) and Kokkos around the benchmarks. Include once per benchmark executable.
// One rank only: on several, each would choose its own iteration counts
// (collective benchmarks could then wait on each other for ever) and all would
// write the same output file.
// JSON: <bench> --benchmark_out=result.json --benchmark_out_format=json
#pragma once

#include <benchmark/benchmark.h>

#include <cstdio>

#include "mote/core/comm.hpp"
#include "mote/core/runtime.hpp"

int main(int argc, char** argv) {
  mote::core::Runtime runtime(argc, argv);
  if (const int ranks = mote::core::Comm::world().size(); ranks > 1) {
    if (mote::core::Comm::world().rank() == 0)
      std::fprintf(stderr, "%s: benchmarks run on one MPI rank, not %d\n", argv[0], ranks);
    return 1;
  }
  benchmark::AddCustomContext("mote_backend", runtime.describe());
  benchmark::AddCustomContext("mote_execution_space", mote::core::Runtime::backend());
  benchmark::AddCustomContext("mote_device", mote::core::Runtime::device_name());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
