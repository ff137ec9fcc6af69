// Memory bandwidth of this machine as seen by Kokkos: the STREAM triad
// a = b + s c over n doubles (3 x 8 bytes per element), the yardstick for the
// bandwidth-bound grid kernels (bench_disc_dust).
#include "bench_main.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/core/loops.hpp"

namespace {

void BM_StreamTriad(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  mote::RealView1 a("a", n), b("b", n), c("c", n);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  const mote::Real s = 3.0;
  for (auto _ : state) {
    mote::par_for(
        "bench::triad", 0, n, KOKKOS_LAMBDA(int i) { a(i) = b(i) + s * c(i); });
    Kokkos::fence();
  }
  state.counters["bytes_per_s"] =
      benchmark::Counter(3.0 * sizeof(mote::Real) * n, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_StreamTriad)->Arg(1 << 24)->Unit(benchmark::kMillisecond)->UseRealTime();
