// sph_dustsettle: dust settling in a vertical column of a protoplanetary disc
// with the one-fluid SPH dust (PL15 sec. 4.4, Fig. 7-10; MULTIGRAIN, HPL18
// sec. 4.3; VALIDATION A5-A6). The gas column of settling_column.hpp (eq.
// 53-56) is relaxed gas-only with damping, then every particle receives the
// dust fractions of [dust] (uniform eps_j, e.g. eq. 57 or the HPL18 eq. 63
// power law) and the mixture evolves with Epstein drag (eq. 20). Grain sizes
// and rho_grain are read in cgs (settle.grain_units = "cgs") and converted
// with the run's units (10 au, M_sun, G = 1). check.py compares the dust
// density with the 1D solutions of HPL18 app. A (eq. A3-A5). With
// dust.method = "two-fluid" the dust is a particle per gas particle with the
// semi-implicit drag of LAB15 (VALIDATION B4).
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/core/timers.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/setups/settling_column.hpp"
#include "mote/setups/sph_problem.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_simulation.hpp"
#include "mote/sph/two_fluid_dust.hpp"

namespace {

using namespace mote;

/// Progress lines for the gas-only relaxation, every run.progress_interval wall seconds (none when 0).
std::function<void(const sph::SphSystem&)> relax_progress(Real t_relax, const core::Deck& d) {
  const double interval = d.real("run.progress_interval");
  if (interval <= 0.0) return {};
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last = start;
  return [=](const sph::SphSystem& gas) mutable {
    const auto now = clock::now();
    if (std::chrono::duration<double>(now - last).count() < interval) return;
    last = now;
    const double wall = std::chrono::duration<double>(now - start).count(), done = gas.time() / t_relax;
    logging::info(logging::format("relax %8lld  t = %.6e  dt = %.3e  %5.1f%%  ETA %s", gas.steps(), gas.time(),
                                  gas.next_dt(), 100.0 * done, logging::hms(wall * (1.0 - done) / done).c_str()));
  };
}

void declare(core::DeckSchema& s) {
  sph::declare_sph_problem(s, "sph_dustsettle", {"", {"diffusion", "multigrain", "two-fluid"}, true});
  s.rule(io::requires_choice("sph_dustsettle", "dust.drag", "epstein"));
  s.table("settle", "Disc column of the settling test (PL15 sec. 4.4.1).");
  s.integer("settle.nx")
      .sets_state_size()
      .default_value(32LL)
      .min(4)
      .doc("Particles across x (32: the 32 x 111 column).");
  s.integer("settle.dim")
      .sets_state_size()
      .default_value(2LL)
      .min(2)
      .max(3)
      .doc("2: the (x, z) slab of PL15; 3: the (x, y, z) column of HPL18 (x, y periodic).");
  s.real("settle.width")
      .sets_state_size()
      .default_value(0.5)
      .greater_than(0.0)
      .unit("code length")
      .doc("Periodic extent of x (and y in 3D); the lattice spacing is width / nx.");
  s.real("settle.zmax")
      .sets_state_size()
      .default_value(3.0)
      .greater_than(0.0)
      .unit("H")
      .doc("Half-height of the initial lattice (3: PL15; 2.6: HPL18's 3D column, z in [-0.65, 0.65]).");
  s.real("settle.rho0")
      .default_value(1e-3)
      .greater_than(0.0)
      .unit("code density")
      .doc("Mid-plane gas density (eq. 55).");
  s.real("settle.R0")
      .sets_state_size()
      .default_value(5.0)
      .greater_than(0.0)
      .unit("code length")
      .doc("Radius of the column (eq. 53).");
  s.real("settle.H_over_R")
      .sets_state_size()
      .default_value(0.05)
      .greater_than(0.0)
      .doc("Aspect ratio H / R0, c_s = H Omega0.");
  s.real("settle.relax_time").default_value(1000.0).min(0.0).unit("code time").doc("Gas-only relaxation (eq. 56).");
  s.real("settle.relax_damping").default_value(0.03).min(0.0).doc("Damping f of eq. 56 during the relaxation.");
  s.string("settle.grain_units")
      .default_value(std::string("cgs"))
      .one_of({"cgs", "code"})
      .doc("Units of dust.sizes, dust.s_min, dust.s_max (cm) and dust.rho_grain (g/cm^3).");
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const int dim = static_cast<int>(d.integer("settle.dim"));
  auto [cfg, ds] = sph::start_sph_problem(ctx, "sph_dustsettle", dim);
  if (d.string("settle.grain_units") == "cgs") {
    for (auto& s : ds.sizes) s /= ctx.units.length;
    ds.rho_grain /= ctx.units.density();
  }
  sph::SettlingColumn c;
  c.nx = static_cast<int>(d.integer("settle.nx"));
  c.dim = dim;
  c.width = d.real("settle.width");
  c.z_max = d.real("settle.zmax");
  c.rho0 = d.real("settle.rho0");
  c.r0 = d.real("settle.R0");
  c.h_over_r = d.real("settle.H_over_R");
  c.relax_time = d.real("settle.relax_time");
  c.relax_damping = d.real("settle.relax_damping");
  if (ctx.restarting) {
    // The checkpoint holds the relaxed (and evolved) particles; only the lattice is needed to size the system.
    logging::info("sph_dustsettle: restarting, the gas-only relaxation is skipped");
    c.relax_time = 0.0;
  }
  sph::RelaxedColumn col;
  {
    core::ScopedTimer t(ctx.timers, "relax");
    col = sph::relax_settling_column(c, cfg, relax_progress(c.relax_time, d));
  }
  std::unique_ptr<sph::SphSystem> sys;
  if (ds.method == sph::DustMethod::TwoFluid) {
    // Per species a dust particle per gas particle, holding the fraction dust.eps[j] of the relaxed mass (eq. 57).
    std::vector<Real> eps;
    for (int j = 0; j < ds.nspecies; ++j) eps.push_back(ds.species_value(ds.eps, j));
    sys = col.make_two_fluid_system(eps);
    add_two_fluid_dust(*sys, ds);
  } else {
    sys = col.make_system();
    add_one_fluid_dust(*sys, ds);
  }
  logging::info("sph_dustsettle: ", col.particles.size(), " particles, ", ds.nspecies, " species, orbit = ", c.orbit(),
                ", mid-plane t_s Omega0 of the largest grain = ",
                sph::ts_epstein(ds.rho_grain, ds.sizes.back(), c.rho0, c.sound_speed(), 1.0) * c.omega());
  return std::make_unique<sph::SphSimulation>(std::move(sys), ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"sph_dustsettle", "Dust settling in a disc column, one-fluid SPH dust (PL15 4.4, HPL18 4.3)", declare, create});
}
