// Coagulation benchmarks (RBO24 sec. 5; issue 4): kernel-pair evaluations per
// second of the Smoluchowski right-hand side (one team per cell, pairs in the
// inner ranges; both product splits), wall time of one coagulation call (adaptive BS32 sub-steps)
// for a grid of cells with 100 species, and the single-cell E3 run
// (200 species, 20 au, to 1e5 yr).
//   bin/perf/bench_coagulation --benchmark_out=coag.json --benchmark_out_format=json
#include <cmath>
#include <string>

#include "bench_main.hpp"
#include "mote/coagulation/coagulation.hpp"
#include "mote/core/units.hpp"

namespace {

namespace coag = mote::coagulation;
namespace cgs = mote::units::cgs;
using mote::Real;

/// Cells spread over 3-20 au at the mid-plane (surface densities, vertically integrated kernel).
struct Setup {
  coag::CoagulationSettings s;
  coag::MassGrid grid;
  coag::GasCells gas;
  mote::RealView2 sigma;
  Setup(int cells, int species, Real a_max) : grid(coag::MassGrid::from_sizes(1e-5, a_max, species, 1.6)) {
    s.species = species;
    s.a_min = 1e-5;
    s.a_max = a_max;
    s.vertically_integrated = true;
    s.cells_per_batch = 4096;
    const auto mk = [&](const char* n) { return mote::RealView1(std::string(n), cells); };
    gas.sound_speed = mk("cs");
    gas.density = mk("sigma_g");
    gas.omega = mk("omega");
    gas.alpha = mk("alpha");
    sigma = mote::RealView2("sigma_d", cells, species);
    auto cs = Kokkos::create_mirror_view(gas.sound_speed);
    auto sg = Kokkos::create_mirror_view(gas.density);
    auto om = Kokkos::create_mirror_view(gas.omega);
    auto al = Kokkos::create_mirror_view(gas.alpha);
    auto sd = Kokkos::create_mirror_view(sigma);
    for (int c = 0; c < cells; ++c) {
      const Real R = (3.0 + 17.0 * c / std::max(1, cells - 1)) * cgs::au, T = 36.0 * std::pow(R / (20 * cgs::au), -0.5);
      cs(c) = std::sqrt(cgs::k_B * T / (2.4 * cgs::m_H));
      om(c) = std::sqrt(cgs::G * cgs::M_sun / (R * R * R));
      sg(c) = 16.98 * (20 * cgs::au / R);
      al(c) = 1e-3;
      double norm = 0;
      for (int k = 0; k < species; ++k) norm += std::sqrt(grid.grain_size(k)) * std::exp(-grid.grain_size(k) / 1e-2);
      for (int k = 0; k < species; ++k)
        sd(c, k) = 0.01 * sg(c) * std::sqrt(grid.grain_size(k)) * std::exp(-grid.grain_size(k) / 1e-2) / norm;
    }
    Kokkos::deep_copy(gas.sound_speed, cs);
    Kokkos::deep_copy(gas.density, sg);
    Kokkos::deep_copy(gas.omega, om);
    Kokkos::deep_copy(gas.alpha, al);
    Kokkos::deep_copy(sigma, sd);
  }
};

void BM_CoagulationRates(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0)), species = static_cast<int>(state.range(1));
  Setup setup(cells, species, 1.0);
  setup.s.product_split = state.range(2) ? "quadratic" : "two-bin";
  setup.s.team_size = static_cast<int>(state.range(3));
  coag::Coagulation solver(setup.grid, setup.s, cells);
  const auto kernel = coag::make_kernel(setup.s, setup.grid, setup.gas);
  mote::RealView2 dydt("dydt", cells, species);
  for (auto _ : state) {
    solver.rates(setup.sigma, kernel, dydt);
    Kokkos::fence();
  }
  // Each call evaluates the kernel policy once per unordered pair and the RHS visits each ordered pair once.
  const double pairs = double(cells) * species * (species + 1) / 2;
  state.counters["pair_evaluations_per_s"] = benchmark::Counter(pairs, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["cell_species_updates_per_s"] =
      benchmark::Counter(double(cells) * species, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_CoagulationStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), species = static_cast<int>(state.range(1));
  const int cells = n * n;
  Setup setup(cells, species, 1.0);
  setup.s.team_size = static_cast<int>(state.range(2));
  coag::Coagulation solver(setup.grid, setup.s, cells);
  const auto kernel = coag::make_kernel(setup.s, setup.grid, setup.gas);
  const Real dt = 100 * cgs::year;
  solver.integrate(setup.sigma, dt, kernel);  // warm start: per-cell step sizes
  long long sub = 0;
  for (auto _ : state) {
    sub += solver.integrate(setup.sigma, dt, kernel).substeps;
    Kokkos::fence();
  }
  state.counters["cells"] = cells;
  state.counters["team_size"] = setup.s.team_size;
  state.counters["substeps_per_cell_per_call"] = double(sub) / (double(state.iterations()) * cells);
  state.counters["pair_rhs_per_s"] =
      benchmark::Counter(double(sub) * 3 * species * (species + 1) / 2, benchmark::Counter::kIsRate);
}

void BM_CoagulationSteadyStateE3(benchmark::State& state) {
  const int species = 200;
  for (auto _ : state) {
    state.PauseTiming();
    coag::CoagulationSettings s;
    s.vertically_integrated = true;
    const auto grid = coag::MassGrid::from_sizes(5e-5, 0.1, species, 1.6);
    coag::GasCells gas;
    const auto mk = [](const char* n, Real v) {
      mote::RealView1 x(std::string(n), 1);
      Kokkos::deep_copy(x, v);
      return x;
    };
    const Real R = 20 * cgs::au;
    gas.sound_speed = mk("cs", std::sqrt(cgs::k_B * 36.0 / (2.4 * cgs::m_H)));
    gas.density = mk("sigma_g", 16.98);
    gas.omega = mk("omega", std::sqrt(cgs::G * cgs::M_sun / (R * R * R)));
    gas.alpha = mk("alpha", 1e-3);
    coag::Coagulation solver(grid, s, 1);
    const auto kernel = coag::make_kernel(s, grid, gas);
    mote::RealView2 sigma("sigma", 1, species);
    auto h = Kokkos::create_mirror_view(sigma);
    double norm = 0;
    for (int k = 0; k < species; ++k) norm += grid.grain_size(k) <= 1e-4 ? std::sqrt(grid.grain_size(k)) : 0.0;
    for (int k = 0; k < species; ++k)
      h(0, k) = grid.grain_size(k) <= 1e-4 ? 0.1698 * std::sqrt(grid.grain_size(k)) / norm : 0.0;
    Kokkos::deep_copy(sigma, h);
    state.ResumeTiming();
    long long sub = 0;
    for (int call = 0; call < 20; ++call) sub += solver.integrate(sigma, 5e3 * cgs::year, kernel).substeps;
    Kokkos::fence();
    state.counters["substeps"] = double(sub);
  }
}

}  // namespace

// Arguments: cells, species, product split (0 two-bin, 1 quadratic), team size (0: the back-end's choice).
BENCHMARK(BM_CoagulationRates)
    ->Args({1, 100, 0, 0})
    ->Args({1, 200, 0, 0})
    ->Args({256, 100, 0, 0})
    ->Args({1, 200, 1, 0})
    ->Args({256, 100, 1, 0})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
// Arguments: n (n x n cells), species, team size.
BENCHMARK(BM_CoagulationStep)
    ->Args({32, 100, 0})
    ->Args({150, 100, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
#if defined(KOKKOS_ENABLE_CUDA)
// The team size of a GPU's cell teams (issue 17): fixed sizes against Kokkos's choice.
BENCHMARK(BM_CoagulationRates)
    ->ArgsProduct({{4096}, {100}, {1}, {0, 32, 64, 128, 256}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_CoagulationStep)
    ->ArgsProduct({{150}, {100}, {32, 64, 128, 256}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
#endif
BENCHMARK(BM_CoagulationSteadyStateE3)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
