// One full dust step (RBO24 sec. 3.1 i-viii: two flux sweeps, two stages,
// ghost cells) on a 256 x 256 (R, theta) grid with 10 and 100 species, drag,
// gravity and diffusion on. Reports cell-species updates per second and the
// effective bandwidth from a traffic model of the compulsory array accesses:
// per cell-species and stage, the flux sweeps read W and write the two face
// fluxes (4 x 32 bytes) and the stage kernel reads Q, both fluxes and the
// source primitives and writes the new primitives (5 x 32 bytes), plus the
// final conserved state (32 bytes): 608 bytes per cell-species update.
#include <cmath>

#include "bench_main.hpp"
#include "mote/core/loops.hpp"
#include "mote/disc/dust_dynamics.hpp"

namespace {

using namespace mote;

constexpr double kBytesPerUpdate = 608.0;

void BM_DustStep(benchmark::State& state) {
  const int n = 256, ns = static_cast<int>(state.range(0));
  mesh::GridSpec spec;
  spec.nr = n;
  spec.ntheta = n;
  spec.r_edges = mesh::log_edges(3.0, 20.0, n);
  spec.theta_edges = mesh::linear_edges(0.0, 0.6, n);
  const mesh::Grid grid(spec, core::Comm::world());
  disc::DustSettings st;
  for (int s = 0; s < ns; ++s) st.sizes.push_back(1e-5 * std::pow(1e4, double(s) / ns));
  st.schmidt.assign(ns, 1.0);
  st.star.GM = 1.0;
  disc::DustDynamics dust(grid, st);
  disc::GasFields gas(grid.nr_total(), grid.nt_total());
  auto Rc = grid.Rc;
  auto rho = gas.rho, cs2 = gas.cs2, nu = gas.nu, vphi = gas.vphi;
  par_for(
      "bench::gas", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        rho(i, j) = 1e-3 * math::exp(-0.5 * math::square(0.1 * j)) / Rc(i);
        cs2(i, j) = 2.5e-3 / Rc(i);
        nu(i, j) = 1e-3 * 0.05 * Rc(i);
        vphi(i, j) = 1.0 / math::sqrt(Rc(i));
      });
  dust.set_gas(gas);
  auto W = dust.W;
  par_for(
      "bench::dust", 0, grid.nr_total(), 0, grid.nt_total(), 0, ns, KOKKOS_LAMBDA(int i, int j, int s) {
        W(i, j, s, disc::kRho) = 0.01 * rho(i, j);
        W(i, j, s, disc::kVR) = 0.0;
        W(i, j, s, disc::kVphi) = vphi(i, j);
        W(i, j, s, disc::kVZ) = 0.0;
      });
  dust.initialise_from_primitives();
  const double dt = 1e-4;
  for (auto _ : state) {
    dust.step(dt);
    Kokkos::fence();
  }
  const double updates = double(n) * n * ns;
  state.counters["cell_species_updates_per_s"] =
      benchmark::Counter(updates, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["model_bytes_per_s"] =
      benchmark::Counter(updates * kBytesPerUpdate, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_DustStep)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
