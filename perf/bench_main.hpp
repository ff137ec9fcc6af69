// Shared main() for Google Benchmark drivers: initialises MPI (if built with
// it) and Kokkos around the benchmarks. Include once per benchmark executable.
// JSON: <bench> --benchmark_out=result.json --benchmark_out_format=json
#pragma once

#include <benchmark/benchmark.h>

#include "mote/core/runtime.hpp"

int main(int argc, char** argv) {
  mote::core::Runtime runtime(argc, argv);
  benchmark::AddCustomContext("mote_backend", runtime.describe());
  benchmark::AddCustomContext("mote_execution_space", mote::core::Runtime::backend());
  benchmark::AddCustomContext("mote_device", mote::core::Runtime::device_name());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
