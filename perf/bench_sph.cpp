// Benchmarks of the SPH engine (PL15 sec. 3 hydrodynamics), Serial or any
// Kokkos backend: one full step (neighbour check, density + Omega, EOS,
// forces, external forces, kick-drift-kick) on
//   * a 3D uniform periodic box of ~1e5 particles (M4, h_fact 1.2; and M6,
//     h_fact 1.0, ~113 neighbours, to compare with Phantom's settling column),
//   * the 2D settling column of PL15 sec. 4.4 (32 x 111, M6, isothermal,
//     disc gravity eq. 53),
//   * the 3D settling column of HPL18 sec. 4.3 as problems/sph_dustsettle's
//     sph_dustsettle_multigrain_3d.toml sets it up (25 x 30 x 80 = 60,000
//     particles, M6, h = dx, alpha = 1, beta = 2) with one dust species (1 mm,
//     S variable), from the lattice: 49 steps after a warm-up step, timed
//     separately for steps with and without a neighbour rebuild,
// plus the three phases separately (list build, density, forces) on the 3D
// box, and the list build (SphSystem::rebuild_neighbours) and one density
// solve on the 3D column.
// Counters: particle-updates/s (particles x steps / wall time), neighbour
// pairs/s (pairs inside the kernel support, counted from both sides, per
// step), bytes/particle (particle data + neighbour list).
//   bench_sph --benchmark_out=sph.json --benchmark_out_format=json
#include <chrono>
#include <cmath>
#include <memory>
#include <random>

#include "bench_main.hpp"
#include "mote/core/units.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/setups/settling_column.hpp"
#include "mote/sph/density.hpp"
#include "mote/sph/external.hpp"
#include "mote/sph/forces.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_system.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

std::unique_ptr<SphSystem> make_box(KernelType kernel, int n_side, Real skin = 0.1) {
  SphConfig cfg;
  cfg.skin = skin;
  cfg.dim = 3;
  cfg.kernel = kernel;
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
  for (int i = 0; i < 3 * n; ++i) s.v.push_back(g(rng));  // subsonic noise: lists get reused
  auto sys = std::make_unique<SphSystem>(cfg, lat.box);
  sys->set_particles(s);
  sys->initialise();
  return sys;
}

std::unique_ptr<SphSystem> make_column(int nx) {
  const Real gm = 1.0, r0 = 5.0, rho0 = 1e-3, H = 0.25;
  const Real cs = H * std::sqrt(gm / (r0 * r0 * r0));
  SphConfig cfg;
  cfg.dim = 2;
  cfg.kernel = KernelType::M6;
  cfg.eos = EosType::Isothermal;
  cfg.cs_iso = cs;
  cfg.damping = 0.03;
  Box box;
  box.dim = 2;
  box.lo[0] = -0.25;
  box.hi[0] = 0.25;
  box.periodic[0] = true;
  box.lo[1] = -3 * H;
  box.hi[1] = 3 * H;
  Lattice lat = hexagonal_lattice(box, 0.5 / nx);
  auto rho = [=](Real z) { return rho0 * std::exp(-z * z / (2 * H * H)); };
  stretch_map(lat, 1, box.lo[1], box.hi[1], rho);
  const int n = lat.size();
  ParticleSetup s;
  s.dim = 2;
  s.x = lat.x;
  s.m = equal_masses(n, lat.box.length(0) * integrate_profile(rho, box.lo[1], box.hi[1]));
  for (int i = 0; i < n; ++i) s.h.push_back(std::sqrt(s.m[i] / rho(lat.x[2 * i + 1])));
  auto sys = std::make_unique<SphSystem>(cfg, lat.box);
  sys->set_particles(s);
  sys->add_external_force(disc_vertical_gravity(gm, r0));
  sys->initialise();
  for (int i = 0; i < 20; ++i) sys->step();  // leave the start-up transient
  return sys;
}

/// The 3D column of sph_dustsettle_multigrain_3d.toml on its lattice (no
/// relaxation) with one 1 mm species (Epstein, S variable, t_s limited).
std::unique_ptr<SphSystem> make_column_3d() {
  SettlingColumn c;
  c.dim = 3;
  c.nx = 25;
  c.width = 0.5;
  c.z_max = 2.6;
  c.relax_time = 0.0;
  SphConfig cfg;
  cfg.kernel = KernelType::M6;
  cfg.hfact = 1.0;
  cfg.alpha = 1.0;
  cfg.beta = 2.0;
  auto sys = relax_settling_column(c, cfg).make_system();
  const mote::units::UnitSystem units = mote::units::unit_system_by_name("10au_msun");
  DustSettings ds;
  ds.nspecies = 1;
  ds.drag = DragLaw::Epstein;
  ds.variable = DustVariable::SqrtRhoEps;
  ds.sizes = {0.1 / units.length};  // 1 mm
  ds.rho_grain = 3.0 / units.density();
  ds.eps = {0.01};
  ds.limit_ts = true;
  add_one_fluid_dust(*sys, ds);
  sys->initialise();
  return sys;
}

void set_counters(benchmark::State& state, const SphSystem& sys) {
  const Real n = sys.particles().n;
  const Real pairs = static_cast<Real>(
      count_interacting_pairs(sys.particles(), sys.neighbours(), sys.box(), const_cast<SphSystem&>(sys).config()));
  state.counters["particles"] = n;
  state.counters["neighbours_per_particle"] = pairs / n;
  state.counters["particle_updates_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["pairs_per_s"] = benchmark::Counter(pairs, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_particle"] = sys.bytes_per_particle();
  state.counters["list_builds"] = sys.neighbours().builds();
  state.counters["density_passes"] = sys.density_passes();
}

void BM_SphStep3DBox(benchmark::State& state) {
  const KernelType kernel = state.range(0) == 0 ? KernelType::M4 : KernelType::M6;
  auto sys = make_box(kernel, static_cast<int>(state.range(1)), 0.01 * state.range(2));
  for (auto _ : state) {
    sys->step();
    Kokkos::fence();
  }
  set_counters(state, *sys);
}

void BM_SphStep2DColumn(benchmark::State& state) {
  auto sys = make_column(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    sys->step();
    Kokkos::fence();
  }
  set_counters(state, *sys);
}

void BM_SphPhases3DBox(benchmark::State& state) {
  auto sys = make_box(KernelType::M4, static_cast<int>(state.range(1)));
  Particles& p = sys->particles();
  NeighbourList nl = sys->neighbours();
  const SphConfig cfg = sys->config();
  for (auto _ : state) {
    switch (state.range(0)) {
      case 0:
        nl.build(p, sys->box(), cfg.kernel, cfg.skin);
        break;
      case 1:
        compute_density(p, nl, sys->box(), cfg);
        break;
      default:
        compute_forces(p, nl, sys->box(), cfg, p.v, p.u);
        break;
    }
    Kokkos::fence();
  }
  state.SetLabel(state.range(0) == 0 ? "neighbour build" : (state.range(0) == 1 ? "density" : "forces"));
  state.counters["particle_updates_per_s"] = benchmark::Counter(p.n, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_SphStepColumn3D(benchmark::State& state) {
  auto sys = make_column_3d();
  sys->step();  // warm up (list sizes)
  double rebuild_s = 0.0, plain_s = 0.0;
  int rebuilds = 0, plain = 0;
  for (auto _ : state) {
    const int builds = sys->neighbours().builds();
    const auto t0 = std::chrono::steady_clock::now();
    sys->step();
    Kokkos::fence();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (sys->neighbours().builds() > builds) {
      rebuild_s += s;
      ++rebuilds;
    } else {
      plain_s += s;
      ++plain;
    }
  }
  set_counters(state, *sys);
  state.counters["steps_with_rebuild"] = rebuilds;
  state.counters["s_per_step_with_rebuild"] = rebuilds > 0 ? rebuild_s / rebuilds : 0.0;
  state.counters["s_per_step_without_rebuild"] = plain > 0 ? plain_s / plain : 0.0;
}

void BM_SphPhasesColumn3D(benchmark::State& state) {
  auto sys = make_column_3d();
  const SphConfig cfg = sys->config();
  // Untimed: the first single-traversal rebuild after the exact first build
  // allocates and first touches its segment arrays; later ones reuse them.
  sys->rebuild_neighbours();
  compute_density(sys->particles(), sys->neighbours(), sys->box(), cfg);
  for (auto _ : state) {
    if (state.range(0) == 0) {
      sys->rebuild_neighbours();
    } else {
      compute_density(sys->particles(), sys->neighbours(), sys->box(), cfg);
    }
    Kokkos::fence();
  }
  state.SetLabel(state.range(0) == 0 ? "neighbour build" : "density");
  state.counters["particle_updates_per_s"] =
      benchmark::Counter(sys->particles().n, benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(BM_SphStep3DBox)
    ->Args({0, 46, 10})
    ->Args({1, 46, 10})
    ->Args({0, 46, 5})
    ->Args({0, 46, 20})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10)
    ->UseRealTime();
BENCHMARK(BM_SphStep2DColumn)->Arg(32)->Unit(benchmark::kMillisecond)->Iterations(200)->UseRealTime();
BENCHMARK(BM_SphPhases3DBox)
    ->Args({0, 46})
    ->Args({1, 46})
    ->Args({2, 46})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();
BENCHMARK(BM_SphStepColumn3D)->Unit(benchmark::kMillisecond)->Iterations(49)->UseRealTime();
BENCHMARK(BM_SphPhasesColumn3D)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

}  // namespace
