// disc_settling: vertical settling-diffusion equilibrium and the radial drift
// of dust versus height (RBO24 sec. 3.6, Fig. 7-8; VALIDATION C2, C3, C6).
// A static, vertically isothermal alpha disc (GasDisc: hydrostatic rho of eq.
// 33-37, velocities of eq. 27-31) at R = 10 au with dust species well mixed
// at a dust-to-gas ratio settling.dust_to_gas, evolved by the coupled driver
// (DiscSimulation). With dust.radial_fluxes = false every column relaxes to
// the Takeuchi & Lin (2002) equilibrium
//   rho_d / rho_g = C exp[-(St_mid / alpha)(exp(Z^2 / 2H^2) - 1)]      (Sc = 1)
// (check.py, C2); with radial fluxes on, v_R of the dust approaches the
// test-particle drift (v_gR - 2 St (v_K - v_gphi)) / (1 + St^2) (check.py --drift, C3).
// With closed boundaries the dust mass of every species is conserved (C6).
#include <memory>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/disc/disc_simulation.hpp"
#include "mote/io/problem_main.hpp"

namespace {

using namespace mote;

/// One initial dust-to-gas ratio per species, or none (0.01 each).
void check_dust_to_gas(const core::Deck& d, core::DeckCheck& check) {
  const size_t n = d.real_array("settling.dust_to_gas").size(), ns = disc::grain_sizes_cm(d).size();
  if (n != 0 && n != ns)
    check.fail("settling.dust_to_gas", mote::logging::cat("has ", n, " values for ", ns, " dust species"));
}

void declare(core::DeckSchema& s) {
  disc::DiscSimulation::declare(s);
  s.table("settling", "Initial dust of the settling test (RBO24 sec. 3.6).");
  s.real_array("settling.dust_to_gas")
      .default_value(std::vector<double>{})
      .greater_than(0.0)
      .doc("Initial (well-mixed) dust-to-gas ratio per species; empty: 0.01 for every species.");
  s.rule(check_dust_to_gas);
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const size_t ns = disc::grain_sizes_cm(d).size();
  auto eps = d.real_array("settling.dust_to_gas");
  if (eps.empty()) eps.assign(ns, 0.01);
  return std::make_unique<disc::DiscSimulation>(d, ctx.comm, ctx.units,
                                                disc::DiscSimulation::well_mixed(eps, d.real("dust.floor")));
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"disc_settling", "RBO24 C2/C3: dust settling-diffusion equilibrium and drift versus height", declare, create});
}
