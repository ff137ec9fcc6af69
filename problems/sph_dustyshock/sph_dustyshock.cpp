// sph_dustyshock: the dusty Sod shock tube of PL15 sec. 4.2 (VALIDATION A2)
// with the one-fluid dust method: gas (rho_g, v, P) = (1, 0, 1) | (0.125, 0,
// 0.125), uniform eps (dust-to-gas ratio 1), constant drag K = 1000, gamma =
// 5/3, equal-mass particles (left spacing 0.001) in x in [-1, 1] periodic.
// check.py compares the total density at t = 0.2 with the exact Riemann
// solution of the "heavy fluid" of density rho_g / (1 - eps) (PL15 sec. 4.2).
#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/setups/dust_problems.hpp"
#include "mote/setups/sph_problem.hpp"
#include "mote/sph/sph_simulation.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  sph::declare_sph_problem(s, "sph_dustyshock", {"adiabatic"});
  sph::declare_dust_problem(s, "sph_dustyshock", sph::DragLaw::ConstantK, true);
  s.table("dustyshock", "Dusty Sod shock tube (PL15 sec. 4.2); gas states.");
  s.real("dustyshock.dx_left")
      .sets_state_size()
      .default_value(0.001)
      .greater_than(0.0)
      .max(0.1)
      .unit("code length")
      .doc("Particle spacing on the left.");
  s.real("dustyshock.rhog_left")
      .sets_state_size()
      .default_value(1.0)
      .greater_than(0.0)
      .unit("code density")
      .doc("Left gas density.");
  s.real("dustyshock.P_left").default_value(1.0).greater_than(0.0).unit("code pressure").doc("Left pressure.");
  s.real("dustyshock.rhog_right")
      .sets_state_size()
      .default_value(0.125)
      .greater_than(0.0)
      .unit("code density")
      .doc("Right gas density.");
  s.real("dustyshock.P_right").default_value(0.125).greater_than(0.0).unit("code pressure").doc("Right pressure.");
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto [cfg, ds] = sph::start_sph_problem(ctx, "sph_dustyshock", 1);
  sph::DustyShock sh;
  sh.dx_left = d.real("dustyshock.dx_left");
  sh.rhog_left = d.real("dustyshock.rhog_left");
  sh.P_left = d.real("dustyshock.P_left");
  sh.rhog_right = d.real("dustyshock.rhog_right");
  sh.P_right = d.real("dustyshock.P_right");
  const auto pr = sph::dustyshock(sh, cfg, ds);
  logging::info("sph_dustyshock: ", pr.particles.size(), " particles, ", ds.nspecies, " dust species");
  return std::make_unique<sph::SphSimulation>(pr.make_system(), ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv, {"sph_dustyshock", "Dusty Sod shock tube, one-fluid SPH dust (PL15 sec. 4.2)", declare, create});
}
