// disc_hydrostatic: a vertically isothermal gas disc on the (R, theta) grid
// (RBO24 sec. 3.3-3.5, VALIDATION C4). Sigma proportional to R^-1 with
// nu = alpha c_s H proportional to R is a steady accretion disc of eq. 26; its
// 2D density comes from the hydrostatic scan (eq. 33-37) and its velocities
// from eq. 27-31. check.py compares rho with
//   rho proportional to exp[(G M / c_s^2)(1/r - 1/R)], normalised to Sigma,
// v_phi with the exact rotation of a vertically isothermal disc, v_R with
// Takeuchi & Lin (2002, eq. 11) and its mass-weighted mean with -3 nu / (2R).
#include <memory>

#include "mote/disc/gas_simulation.hpp"
#include "mote/io/problem_main.hpp"

namespace {

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  return std::make_unique<mote::disc::GasSimulation>(ctx.deck, ctx.comm, ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(
      argc, argv,
      {"disc_hydrostatic", "hydrostatic vertically isothermal gas disc with viscous velocities",
       mote::disc::GasSimulation::declare, create});
}
