// The temperature solver (RBO24 sec. 4.1) on an n x n (R, theta) disc with nb
// FLD bands: one implicit step (Planck factors, limiter, Wu coefficients per
// band, assembly, ILU(k) numeric, BiCGStab), with the assembly's and the
// solve's shares; apart, the set-up, and the ILU(k) symbolic and numeric
// phases alone on the step's matrix. The disc: R in [1, 100] au (log), theta in [0, 0.5],
// rho kappa^b = 1e-14 (R / au)^-2 exp(-theta^2 / 2 0.05^2) w_b + 1e-22 cm^-1
// (thick mid-plane, thin atmosphere), heated by a 2 R_sun, 4000 K star in 100
// bins; dt = 1e-3 yr. Counters: unknowns, non-zeros, BiCGStab iterations per
// solve, seconds per iteration, and the modelled bytes of one iteration
// (2 spmv + 2 ILU applications + the vector passes below) per second, to set against
// bench_stream. RBO24's set-up is 150 x 150 cells with 20 bands (472,500
// unknowns); the band scaling runs at that size with 5-40 bands.
#include <chrono>
#include <cmath>

#include "bench_main.hpp"
#include "mote/core/units.hpp"
#include "mote/linalg/ilu.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/irradiation.hpp"
#include "mote/radiation/planck.hpp"

namespace {

using namespace mote;

mesh::GridSpec disc(int n) {
  mesh::GridSpec s;
  s.nr = n;
  s.ntheta = n;
  s.r_edges = mesh::log_edges(units::cgs::au, 100.0 * units::cgs::au, n);
  s.theta_edges = mesh::linear_edges(0.0, 0.5, n);
  return s;
}

std::vector<double> log_edges_cm(double lo, double hi, int n) {
  std::vector<double> e;
  for (int k = 0; k <= n; ++k) e.push_back(lo * std::pow(hi / lo, double(k) / n));
  return e;
}

/// rho kappa per band (n_bands = extent 2) with the band weight 1 / (1 + b).
void disc_opacity(const mesh::Grid& grid, const RealView3& k) {
  const auto Rc = grid.Rc;
  const auto tc = grid.tc;
  const int nb = static_cast<int>(k.extent(2));
  const double au = units::cgs::au;
  par_for(
      "bench::disc_opacity", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        const Real x = Rc(i) / au, t = tc(j) / 0.05;
        for (int b = 0; b < nb; ++b) k(i, j, b) = 1e-14 / (x * x) * math::exp(-0.5 * t * t) / (1.0 + b) + 1e-22;
      });
}

radiation::FldSettings settings(int nb, int fill_level, int sweeps) {
  radiation::FldSettings s;
  s.band_edges_cm = log_edges_cm(1e-5, 0.3, nb);
  s.boundaries.T_ext = 10.0;
  s.solver.preconditioning = {fill_level};
  s.solver.triangular_sweeps = sweeps;
  return s;
}

/// T everywhere, E^b = f^b(T) 4 sigma T^4 / c (radiative equilibrium).
void equilibrium(const radiation::FldSolver& fld, const std::vector<double>& edges, double T,
                 radiation::FldState& state) {
  Kokkos::deep_copy(state.T, T);
  auto E = Kokkos::create_mirror_view(state.E);
  const int nb = fld.bands();
  const auto& k = fld.constants();
  for (std::size_t i = 0; i < E.extent(0); ++i)
    for (std::size_t j = 0; j < E.extent(1); ++j)
      for (int b = 0; b < nb; ++b)
        E(i, j, b) = radiation::band_fraction(b == 0 ? 0.0 : edges[b], b == nb - 1 ? 0.0 : edges[b + 1], T) * 4.0 *
                     k.sigma * std::pow(T, 4) / k.c;
  Kokkos::deep_copy(state.E, E);
}

/// An FLD solver on the benchmark disc, its fields and a state one step on.
struct SteppedDisc {
  mesh::Grid grid;
  radiation::FldSolver fld;
  radiation::FldFields fields;
  radiation::FldState state;
  double dt = 1e-3 * units::cgs::year;

  SteppedDisc(int n, int nb, int fill, int sweeps)
      : grid(disc(n), core::Comm::world()),
        fld(grid, settings(nb, fill, sweeps), radiation::RadiationConstants::in(units::UnitSystem::cgs_units())),
        fields(fld.make_fields()),
        state(fld.make_state()) {
    disc_opacity(grid, fields.absorption);
    disc_opacity(grid, fields.extinction);
    Kokkos::deep_copy(fields.heat_capacity, 1e-12);
    radiation::StellarIrradiation star(grid, {2.0 * units::cgs::R_sun, 4000.0}, log_edges_cm(1e-5, 0.3, 100),
                                       settings(nb, fill, sweeps).band_edges_cm, fld.constants());
    RealView3 k_star("bench::k_star", grid.nr_total(), grid.nt_total(), star.bins());
    disc_opacity(grid, k_star);
    star.heat(k_star, k_star, fields.heating, fields.scattering_source);
    equilibrium(fld, settings(nb, fill, sweeps).band_edges_cm, 30.0, state);
    fld.step(dt, fields, state);  // warm-up: first numeric phases, lagged D from a non-zero E
  }
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_FldStep(benchmark::State& bench) {
  const int n = static_cast<int>(bench.range(0)), nb = static_cast<int>(bench.range(1));
  const int fill = static_cast<int>(bench.range(2)), sweeps = static_cast<int>(bench.range(3));
  SteppedDisc d(n, nb, fill, sweeps);
  auto& fld = d.fld;
  // Every iteration steps from the same state: continuing from the last one,
  // the disc would relax towards equilibrium and the solves would need fewer
  // iterations the more steps the library chose to time.
  const radiation::FldState start_state = fld.make_state();
  Kokkos::deep_copy(start_state.T, d.state.T);
  Kokkos::deep_copy(start_state.E, d.state.E);
  long iterations = 0, solves = 0;
  double solve_seconds = 0.0, step_seconds = 0.0;
  for (auto _ : bench) {
    bench.PauseTiming();
    Kokkos::deep_copy(d.state.T, start_state.T);
    Kokkos::deep_copy(d.state.E, start_state.E);
    Kokkos::fence();
    bench.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    const auto report = fld.step(d.dt, d.fields, d.state);
    Kokkos::fence();
    step_seconds += seconds_since(start);
    iterations += report.total_iterations();
    for (const auto& a : report.attempts) solve_seconds += a.seconds;
    ++solves;
  }
  const double rows = fld.unknowns(), nnz = fld.nonzeros(), nnz_ilu = fld.ilu_nonzeros();
  // Exact triangular solves read each factor once per application; m sweeps read L m times and U m + 1 times.
  const double factor_passes = sweeps > 0 ? sweeps + 0.5 : 1.0;
  // The vector passes of one iteration (linalg/solver.cpp), 8 bytes each: the direction reads r, p, v and
  // writes p (4); the half step's (r_hat, v) and s = r - alpha v (5); the full step's (t, s), (t, t) and the
  // update of x and r from p_hat, s_hat, x, s, t (10); the measure's residual reads r, b, x and the unknown
  // floors and gathers the diagonal (4, plus 12 bytes a row), its (r, r) and (r_hat, r) (3).
  const double vector_bytes = (4 + 5 + 10 + 7) * 8.0 + 12.0;
  const double per_iteration =
      2.0 * (nnz * 12 + rows * 16) + 2.0 * factor_passes * (nnz_ilu * 12 + rows * 24) + vector_bytes * rows;
  bench.counters["unknowns"] = rows;
  bench.counters["nnz"] = nnz;
  bench.counters["iterations_per_solve"] = double(iterations) / solves;
  bench.counters["solve_s"] = solve_seconds / solves;
  // The step outside the solver's timed attempts: Planck factors, limiter, Wu
  // coefficients, matrix values, Jacobi scaling, the finite-value scan, the
  // initial guess and the write-back of T and E.
  bench.counters["assembly_s"] = (step_seconds - solve_seconds) / solves;
  bench.counters["s_per_iteration"] = solve_seconds / std::max<long>(iterations, 1);
  bench.counters["iteration_bytes_per_s"] = per_iteration * iterations / std::max(solve_seconds, 1e-30);
}

void BM_FldSetUp(benchmark::State& bench) {
  const int n = static_cast<int>(bench.range(0)), nb = static_cast<int>(bench.range(1));
  const int fill = static_cast<int>(bench.range(2)), sweeps = static_cast<int>(bench.range(3));
  const auto constants = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  const mesh::Grid grid(disc(n), core::Comm::world());
  for (auto _ : bench) {
    radiation::FldSolver fld(grid, settings(nb, fill, sweeps), constants);
    Kokkos::fence();
  }
}

/// The ILU(k) phases alone on the FLD pattern and the matrix of a step:
/// symbolic (level-of-fill pattern, Kokkos Kernels spiluk) and numeric.
void BM_FldIlu(benchmark::State& bench) {
  const int n = static_cast<int>(bench.range(0)), nb = static_cast<int>(bench.range(1));
  const int fill = static_cast<int>(bench.range(2)), sweeps = static_cast<int>(bench.range(3));
  SteppedDisc d(n, nb, fill, sweeps);
  double symbolic = 0.0, numeric = 0.0;
  long calls = 0;
  for (auto _ : bench) {
    auto start = std::chrono::steady_clock::now();
    linalg::IluFactors ilu("bench::ilu", d.fld.pattern(), fill, sweeps);
    Kokkos::fence();
    symbolic += seconds_since(start);
    start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(ilu.factorise(d.fld.matrix()));
    Kokkos::fence();
    numeric += seconds_since(start);
    ++calls;
  }
  bench.counters["symbolic_s"] = symbolic / calls;
  bench.counters["numeric_s"] = numeric / calls;
}

/// (n, bands, ILU fill level, triangular sweeps: 0 exact triangular solves)
void sizes(benchmark::internal::Benchmark* b) {
  for (int nb : {5, 10, 20}) b->Args({32, nb, 0, 0});
  b->Args({32, 5, 1, 0});
  b->Args({32, 20, 0, 3});
  b->Args({64, 5, 0, 0});
  b->Args({64, 10, 0, 0});
  b->Args({64, 10, 0, 3});
  for (int nb : {5, 10, 20, 40}) b->Args({150, nb, 0, 0});
  for (int sweeps : {3, 6}) b->Args({150, 20, 0, sweeps});
}

/// The factorisation does not depend on the sweeps: (n, bands, fill level, 0).
void ilu_sizes(benchmark::internal::Benchmark* b) {
  for (int nb : {5, 10, 20}) b->Args({32, nb, 0, 0});
  b->Args({32, 5, 1, 0});
  b->Args({64, 10, 0, 0});
  for (int nb : {5, 10, 20, 40}) b->Args({150, nb, 0, 0});
}

}  // namespace

BENCHMARK(BM_FldStep)->Apply(sizes)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FldSetUp)->Apply(sizes)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FldIlu)->Apply(ilu_sizes)->Unit(benchmark::kMillisecond)->UseRealTime();
