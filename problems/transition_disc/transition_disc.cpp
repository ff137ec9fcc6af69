// transition_disc: grain growth in a steady-state transition disc (RBO24 sec. 7,
// Table 1, Fig. 12-21; VALIDATION F1). A static gas disc with an inner cavity,
//   Sigma_g = Sigma_0 (R / au)^-1 exp[-(5 au / R)^10]          (gas.R_cavity, gas.cavity_index)
// (RBO24 sec. 7), alpha viscosity, hydrostatic in 2D (eq. 33-37), v_R = 0 and
// v_phi in force balance (driver.evolve_gas = false). Dust species on a
// logarithmic size grid (dust.sizes_from = "log") start well mixed with the gas
// at a total dust-to-gas ratio transition.dust_to_gas, shared between the
// species as the MRN distribution n(a) da ~ a^-q da (Mathis et al. 1977, q =
// 3.5): the mass per logarithmic bin goes as a^(4 - q). The coupled driver
// (DiscSimulation) then moves the dust (RBO24 sec. 3), grows and fragments it
// ([coagulation], sec. 5) and, with a [radiation] table, solves the temperature
// (sec. 4) on the schedule of sec. 6. The problem supplies only the initial dust,
// or takes it from a checkpoint of another run on the same grid and size grid
// (transition.dust_from: e.g. the non-isothermal run from the isothermal run's
// grown, settled and trapped dust).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/disc/disc_simulation.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/io/restart.hpp"
#include "mote/mesh/grid_output.hpp"

namespace {

using namespace mote;

/// An initial size limit below the smallest grain would leave no species to hold the initial dust.
void check_initial_a_max(const core::Deck& d, core::DeckCheck& check) {
  const double a_max = d.real("transition.initial_a_max");
  if (a_max > 0 && a_max < disc::grain_sizes_cm(d).front())
    check.fail("transition.initial_a_max", "below the smallest grain of the size grid: no species would hold the dust");
}

void declare(core::DeckSchema& s) {
  disc::DiscSimulation::declare(s);
  s.table("transition", "Initial dust of the transition disc (RBO24 sec. 7).");
  s.real("transition.dust_to_gas")
      .default_value(0.01)
      .greater_than(0.0)
      .less_than(1.0)
      .doc("Total initial dust-to-gas ratio, well mixed (RBO24: 0.01).");
  s.real("transition.dust_R_in")
      .default_value(0.0)
      .min(0.0)
      .unit("code length")
      .doc(
          "Inner edge of the initial dust, a factor exp[-(dust_R_in / R)^10] on the dust-to-gas ratio (cuDisc's "
          "steadyTD set-up: 6 au); 0: dust wherever the gas is.");
  s.real("transition.initial_a_max")
      .default_value(0.0)
      .min(0.0)
      .unit("cm")
      .doc(
          "Largest grain of the initial MRN distribution: larger species start at the floor, the total "
          "dust_to_gas shared among the others (RBO24 sec. 7: MRN up to 0.5 cm; the v_frag = 1000 cm/s grid "
          "reaches 20 cm for the grains grown later); 0: every species of the grid.");
  s.real("transition.mrn_index")
      .default_value(3.5)
      .doc("q of the initial size distribution n(a) ~ a^-q (MRN: 3.5); mass per log bin ~ a^(4 - q).");
  s.rule(check_initial_a_max);
  s.string("transition.dust_from")
      .default_value(std::string(""))
      .doc(
          "A checkpoint of a transition_disc run whose dust (densities and velocities of every species) is the "
          "initial dust, in place of the well-mixed MRN dust; its deck must have the same [grid], run.units and "
          "size grid (dust.species, a_min, a_max, sizes, sizes_from, rho_grain), checked at set-up; the gas is not "
          "compared (another gas disc changes the dust-to-gas ratio). The clock starts at 0; a restart does not read "
          "the file again.");
}

/// The deck keys that give a checkpoint's dust state its meaning (transition.dust_from).
const std::vector<std::string> kDustStateKeys = {"grid.",      "run.units",  "dust.species",    "dust.a_min",
                                                 "dust.a_max", "dust.sizes", "dust.sizes_from", "dust.rho_grain"};

/// The initial dust fills the gas disc, not its floor: cells whose gas is within
/// this factor of gas.rho_floor (the cavity) start with floor dust only.
constexpr double kGasFloorMargin = 10.0;

/// Dust-to-gas ratio per species: total * a_s^(4 - q) / sum_k a_k^(4 - q), the sums over
/// the sizes up to a_max (larger species get 0; a_max = 0: every size).
std::vector<double> mrn_dust_to_gas(const std::vector<double>& sizes, double total, double q, double a_max) {
  std::vector<double> eps;
  double sum = 0.0;
  for (double a : sizes) {
    eps.push_back(a_max > 0 && a > a_max ? 0.0 : std::pow(a / sizes.front(), 4.0 - q));
    sum += eps.back();
  }
  for (double& e : eps) e *= total / sum;
  return eps;
}

/// Multiplies the dust densities by exp[-(R_d / R)^10] (the floor is restored by
/// DustDynamics::initialise_from_primitives).
void cut_inner_dust(const mesh::Grid& grid, const View<Real****>& W, Real R_d) {
  auto Rc = grid.Rc;
  par_for(
      "transition::inner_dust_edge", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(), 0,
      static_cast<int>(W.extent(2)),
      KOKKOS_LAMBDA(int i, int j, int s) { W(i, j, s, disc::kRho) *= math::exp(-math::pow(R_d / Rc(i), Real(10))); });
}

/// The initial dust: every species' primitive state (i, j, s, k) of a checkpoint (transition.dust_from).
disc::DiscSimulation::InitialDust dust_from_checkpoint(const std::string& path, const core::Comm& comm) {
  return [path, &comm](const mesh::Grid& grid, const disc::GasFields&, const View<Real****>& W) {
    const io::H5File file(path, io::H5File::Mode::Read, comm);
    mesh::read_state(file, "/state/dust_W", grid, W);
  };
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  // A restart overwrites the initial dust: the source checkpoint is not read again.
  if (const auto& from = d.string("transition.dust_from"); !from.empty() && !ctx.restarting) {
    io::check_initial_state_source(from, "transition.dust_from", d, "transition_disc", kDustStateKeys, ctx.comm);
    return std::make_unique<disc::DiscSimulation>(d, ctx.comm, ctx.units, dust_from_checkpoint(from, ctx.comm));
  }
  const auto sizes = disc::grain_sizes_cm(d);
  const double a_max = d.real("transition.initial_a_max");
  const auto eps = mrn_dust_to_gas(sizes, d.real("transition.dust_to_gas"), d.real("transition.mrn_index"), a_max);
  const auto mixed =
      disc::DiscSimulation::well_mixed(eps, d.real("dust.floor"), kGasFloorMargin * d.real("gas.rho_floor"));
  const double R_d = d.real("transition.dust_R_in");
  auto initial = [mixed, R_d](const mesh::Grid& grid, const disc::GasFields& gas, const View<Real****>& W) {
    mixed(grid, gas, W);
    if (R_d > 0) cut_inner_dust(grid, W, R_d);
  };
  return std::make_unique<disc::DiscSimulation>(d, ctx.comm, ctx.units, initial);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"transition_disc", "RBO24 sec. 7 / F1: dust growth and trapping in a transition disc", declare, create});
}
