// sph_dustywave: the linear dusty wave of PL15 sec. 4.1 (VALIDATION A1) with
// the one-fluid dust method (PL15; N equal bins: HPL18 sec. 4.1): x in [0, 1)
// periodic, rho_g0 = 1, eps0 = sum of dust.eps, v = A sin(2 pi x),
// rho = rho0 (1 + A sin(2 pi x)), du = P0 / rho_g0^2 drho_g, adiabatic with
// c_s = 1, constant drag K_j. check.py compares the gas and dust velocities
// with the linear two-fluid solution (LP11).
#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/setups/dust_problems.hpp"
#include "mote/setups/sph_problem.hpp"
#include "mote/sph/sph_simulation.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  sph::declare_sph_problem(s, "sph_dustywave", {"adiabatic"});
  sph::declare_dust_problem(s, "sph_dustywave", sph::DragLaw::ConstantK, true);
  s.table("dustywave", "Linear dusty wave (PL15 sec. 4.1).");
  s.integer("dustywave.n").sets_state_size().default_value(100LL).min(8).doc("Number of particles in [0, 1).");
  s.real("dustywave.amplitude")
      .default_value(1e-4)
      .greater_than(0.0)
      .max(1e-2)
      .doc("Amplitude A of v / c_s and drho / rho0.");
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto [cfg, ds] = sph::start_sph_problem(ctx, "sph_dustywave", 1);
  sph::DustyWave w;
  w.n = static_cast<int>(d.integer("dustywave.n"));
  w.amplitude = d.real("dustywave.amplitude");
  logging::info("sph_dustywave: ", w.n, " particles, ", ds.nspecies, " dust species");
  return std::make_unique<sph::SphSimulation>(sph::dustywave(w, cfg, ds).make_system(), ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(argc, argv,
                         {"sph_dustywave", "Linear dusty wave, one-fluid SPH dust (PL15 sec. 4.1)", declare, create});
}
