// viscous_ring: the Lynden-Bell & Pringle (1974) self-similar viscous disc
// for the 1D viscous evolution of RBO24 eq. 26 (VALIDATION C5). With
// nu = nu_1 (R / R_1)^gamma,
//   Sigma(R, t) = Sigma_1 x^-gamma T^-(5/2 - gamma)/(2 - gamma) exp(-x^(2 - gamma) / T),
//   x = R / R_1,  T = 1 + t / t_s,  t_s = R_1^2 / (3 (2 - gamma)^2 nu_1)
// (Hartmann et al. 1998, eq. 20-24). The deck's [gas] power laws give the
// initial state (R_ref = R_c = R_1, Sigma_index = nu_index = gamma); "user"
// boundaries take the analytic Sigma in the ghost cells (convergence test),
// "closed" boundaries test exact mass conservation.
#include <cmath>
#include <memory>

#include "mote/core/log.hpp"
#include "mote/disc/gas_simulation.hpp"
#include "mote/io/problem_main.hpp"

namespace {

struct SelfSimilar {
  double Sigma1, R1, gamma, t_s;
  double operator()(double R, double t) const {
    const double x = R / R1, T = 1.0 + t / t_s;
    return Sigma1 * std::pow(x, -gamma) * std::pow(T, -(2.5 - gamma) / (2.0 - gamma)) *
           std::exp(-std::pow(x, 2.0 - gamma) / T);
  }
};

/// The self-similar solution holds for nu ~ R^gamma, Sigma ~ R^-gamma (gamma < 2) and R_c = R_1.
void check_self_similar(const mote::core::Deck& d, mote::core::DeckCheck& check) {
  if (d.string("gas.viscosity") != "power_law") check.fail("gas.viscosity", "viscous_ring needs \"power_law\"");
  const double gamma = d.real("gas.nu_index");
  if (!(gamma < 2.0)) check.fail("gas.nu_index", "viscous_ring needs it < 2");
  if (std::fabs(d.real("gas.Sigma_index") - gamma) > 1e-14)
    check.fail("gas.Sigma_index", "viscous_ring needs it equal to " + check.quote("gas.nu_index"));
  if (std::fabs(d.real("gas.R_c") - d.real("gas.R_ref")) > 1e-14 * d.real("gas.R_ref"))
    check.fail("gas.R_c", "viscous_ring needs it equal to " + check.quote("gas.R_ref"));
}

void declare(mote::core::DeckSchema& s) {
  mote::disc::GasSimulation::declare_with_boundary_values(s);
  s.rule(check_self_similar);
}

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  auto sim = std::make_unique<mote::disc::GasSimulation>(ctx.deck, ctx.comm, ctx.units);
  const auto& c = sim->gas().config();
  const double gamma = c.nu_index;
  const SelfSimilar lbp{c.Sigma0, c.R_ref, gamma, c.R_ref * c.R_ref / (3.0 * (2.0 - gamma) * (2.0 - gamma) * c.nu0)};
  mote::logging::info(mote::logging::format("viscous_ring: gamma = %g, R_1 = %g, nu_1 = %g, t_s = %.10g", gamma,
                                            c.R_ref, c.nu0, lbp.t_s));
  sim->gas().set_boundary_values(lbp);
  sim->gas().set_surface_density([lbp](double R) { return lbp(R, 0.0); });
  return sim;
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(
      argc, argv,
      {"viscous_ring", "Lynden-Bell & Pringle self-similar viscous disc (1D viscous evolution, eq. 26)", declare,
       create});
}
