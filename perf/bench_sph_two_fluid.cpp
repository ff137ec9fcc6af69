// Benchmarks of the two-fluid SPH dust (LAB15): on the 3D accelerated
// dustybox of VALIDATION B2 (n^3 gas + n^3 dust particles on interleaved cubic
// lattices in [-2, 2)^3, M4, h_fact 1.2, eps = 0.01, t_s = 1e-3, so
// dt / t_s ~ 72, the `dt_over_ts` counter), the cost of one engine step (density, gas forces, the two
// half-step drag updates) and of one drag update alone (moment tensors, the
// dust and gas pair sums, the apply). The drag's share of a step is
// 2 x drag / step. Args: n per direction; the drag law, 0 constant t_s, 1
// Epstein (grains of s rho_grain = 1.6e-3: t_s about 1e-3 at rho = 1, c_s = 1;
// the stopping time is then a per-pair expression); the number of dust
// species, each its own n^3 lattice (2: t_s = 1e-3 and 1e-5, the species
// coupled through the mixture correction of mixture_drag.hpp).
//   bench_sph_two_fluid --benchmark_out=sph_two_fluid.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "bench_main.hpp"
#include "mote/setups/dustybox.hpp"
#include "mote/sph/two_fluid_dust.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

std::unique_ptr<SphSystem> make_box(int n, int law, int species) {
  DustyBox box;
  box.dim = 3;
  box.n = n;
  SphConfig cfg;
  cfg.dim = 3;
  cfg.eos = EosType::Isothermal;
  cfg.cs_iso = 1.0;
  DustSettings ds;
  ds.method = DustMethod::TwoFluid;
  ds.nspecies = species;
  if (law == 0) {
    ds.drag = DragLaw::ConstantStoppingTime;
    ds.stopping_time = species == 1 ? std::vector<Real>{1e-3} : std::vector<Real>{1e-3, 1e-5};
  } else {
    ds.drag = DragLaw::Epstein;
    ds.sizes = species == 1 ? std::vector<Real>{1e-3} : std::vector<Real>{1e-3, 1e-5};
    ds.rho_grain = 1.6;
  }
  auto sys = make_dustybox(box, cfg, ds);
  sys->initialise();
  sys->step();  // warm up (list sizes)
  return sys;
}

void BM_TwoFluidStep(benchmark::State& state) {
  auto sys =
      make_box(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  for (auto _ : state) {
    sys->step();
    Kokkos::fence();
  }
  state.counters["particles"] = sys->particles().n;
  state.counters["dt_over_ts"] = sys->next_dt() / 1e-3;
  state.counters["particle_updates_per_s"] =
      benchmark::Counter(static_cast<double>(sys->particles().n) * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_TwoFluidDragUpdate(benchmark::State& state) {
  auto sys =
      make_box(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  auto& dust = *sys->module<TwoFluidDust>();
  const Real half = 0.5 * sys->next_dt();
  for (auto _ : state) {
    dust.begin_step(*sys, 2.0 * half);
    dust.apply_drag(*sys, half);
    Kokkos::fence();
  }
  state.counters["particles"] = sys->particles().n;
  state.counters["particle_updates_per_s"] =
      benchmark::Counter(static_cast<double>(sys->particles().n) * state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_TwoFluidStep)
    ->Args({20, 0, 1})
    ->Args({20, 1, 1})
    ->Args({20, 0, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_TwoFluidDragUpdate)
    ->Args({20, 0, 1})
    ->Args({20, 1, 1})
    ->Args({20, 0, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
