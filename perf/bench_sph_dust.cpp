// Benchmarks of the one-fluid SPH dust (PL15; MULTIGRAIN, HPL18 sec. 4.3.3):
// cost of one full step (density, dusty EOS and drag times, forces with the
// dust terms, second neighbour loop for two first derivatives, kick-drift-kick
// of eps_j) on a 3D periodic box (M4, h_fact 1.2, cubic lattice, subsonic
// noise, eps = 0.01 in N equal bins, Epstein drag) with N = 0 (pure gas),
// 1, 10, 100, for both discretisations of the dust equation and the two PdV
// forms and both dust variables (args: N, disc 0 = direct second derivatives,
// 1 = two first derivatives; pdv 0 = div v of PL15 eq. 13, 1 = div v_g,
// dust.pdv = "gas"; var 0 = eps_j, 1 = S_j with its dust-mass projection).
// Counter: particle-updates/s; the seconds per step are the "time" column.
//   bench_sph_dust --benchmark_out=sph_dust.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <memory>
#include <random>

#include "bench_main.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_system.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

std::unique_ptr<SphSystem> make_dusty_box(int n_side, int nspecies, int disc, int pdv, int var) {
  SphConfig cfg;
  cfg.dim = 3;
  cfg.kernel = KernelType::M4;
  cfg.eos = EosType::Adiabatic;
  Box box;
  box.dim = 3;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = 0.0;
    box.hi[d] = 1.0;
    box.periodic[d] = true;
  }
  const Lattice lat = cubic_lattice(box, 1.0 / n_side);
  const int n = lat.size();
  ParticleSetup s;
  s.dim = 3;
  s.x = lat.x;
  s.m = equal_masses(n, 1.0);
  s.h.assign(n, cfg.effective_hfact() * lat.dx);
  s.u.assign(n, 1.0);
  std::mt19937 rng(1);
  std::normal_distribution<Real> g(0.0, 0.05);
  for (int i = 0; i < 3 * n; ++i) s.v.push_back(g(rng));
  auto sys = std::make_unique<SphSystem>(cfg, lat.box);
  sys->set_particles(s);
  if (nspecies > 0) {
    DustSettings ds;
    ds.nspecies = nspecies;
    ds.discretisation = disc == 0 ? DustDiscretisation::SecondDerivatives : DustDiscretisation::FirstDerivatives;
    ds.pdv = pdv == 0 ? DustPdV::Barycentric : DustPdV::Gas;
    ds.variable = var == 0 ? DustVariable::Epsilon : DustVariable::SqrtRhoEps;
    ds.drag = DragLaw::Epstein;
    ds.rho_grain = 1.0;
    ds.sizes.clear();
    for (int j = 0; j < nspecies; ++j) ds.sizes.push_back(1e-4 * (1.0 + j));
    ds.eps = {0.01 / nspecies};
    add_one_fluid_dust(*sys, ds);
  }
  sys->initialise();
  return sys;
}

void BM_SphDustStep(benchmark::State& state) {
  const int nspecies = static_cast<int>(state.range(0));
  const int disc = static_cast<int>(state.range(1));
  auto sys = make_dusty_box(32, nspecies, disc, static_cast<int>(state.range(2)), static_cast<int>(state.range(3)));
  sys->step();  // warm up (list sizes)
  long long steps = 0;
  for (auto _ : state) {
    sys->step();
    Kokkos::fence();
    ++steps;
  }
  state.counters["particles"] = sys->particles().n;
  state.counters["species"] = nspecies;
  state.counters["particle_updates_per_s"] =
      benchmark::Counter(static_cast<double>(sys->particles().n) * steps, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_SphDustStep)
    ->Args({0, 0, 0, 0})
    ->Args({1, 0, 0, 0})
    ->Args({1, 1, 0, 0})
    ->Args({1, 0, 0, 1})
    ->Args({10, 0, 0, 0})
    ->Args({10, 0, 1, 0})
    ->Args({10, 1, 0, 0})
    ->Args({10, 0, 0, 1})
    ->Args({100, 0, 0, 0})
    ->Args({100, 1, 0, 0})
    ->Args({100, 0, 0, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
