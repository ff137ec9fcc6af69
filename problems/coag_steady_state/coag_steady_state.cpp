// coag_steady_state: growth-fragmentation equilibrium of the dust size
// distribution at one radius of a disc (RBO24 sec. 5.1, Fig. 10; VALIDATION E3):
// vertically integrated physical kernel (eq. 56-60 divided by
// sqrt(2 pi (h_i^2 + h_j^2))), Maxwellian fragmentation probability (eq. 62),
// power-law fragments (eq. 66-67), dust dynamics off. The evolved quantity is
// the surface density of every species; snapshots hold
// sigma_d(m) = m dSigma_d/dm (eq. 69) = Sigma_k / ln(m^e_{k+1} / m^e_k).
// Initial condition: MRN, n(a) ~ a^-3.5 up to analytic.a_init_max, with
// Sigma_d = dust_to_gas Sigma_g. Units: cgs.
#include <cmath>
#include <vector>

#include "mote/coagulation/coagulation.hpp"
#include "mote/coagulation/standalone_cells.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/core/units.hpp"
#include "mote/io/problem_main.hpp"

namespace {

namespace coag = mote::coagulation;
namespace cgs = mote::units::cgs;
using mote::Real;

struct Params {
  Real radius = 20 * cgs::au, m_star = cgs::M_sun, temperature = 36, sigma_gas = 16.98, alpha = 1e-3;
  Real dust_to_gas = 0.01, a_init_max = 1e-4, headwind = 0, call_interval = 0;
  int cells = 1;
};

Real sound_speed(const Params& p, const coag::CoagulationSettings& s) {
  return std::sqrt(cgs::k_B * p.temperature / (s.mu * cgs::m_H));
}

coag::GasCells gas_cells(const Params& p, const coag::CoagulationSettings& s) {
  const int nc = p.cells;
  const Real omega = std::sqrt(cgs::G * p.m_star / (p.radius * p.radius * p.radius));
  coag::GasCells gas;
  gas.sound_speed = mote::RealView1("sound_speed", nc);
  gas.density = mote::RealView1("sigma_gas", nc);
  gas.omega = mote::RealView1("omega", nc);
  gas.alpha = mote::RealView1("alpha", nc);
  gas.headwind = mote::RealView1("headwind", nc);
  Kokkos::deep_copy(gas.sound_speed, sound_speed(p, s));
  Kokkos::deep_copy(gas.density, p.sigma_gas);
  Kokkos::deep_copy(gas.omega, omega);
  Kokkos::deep_copy(gas.alpha, p.alpha);
  Kokkos::deep_copy(gas.headwind, p.headwind);
  return gas;
}

/// MRN: dN/da ~ a^-3.5, i.e. mass per logarithmic bin ~ a^0.5, truncated at a_init_max
/// (which must reach the grid's first bin).
std::vector<double> mrn(const Params& p, const coag::MassGrid& grid) {
  std::vector<double> init(grid.size(), 0.0);
  double sum = 0;
  for (int k = 0; k < grid.size(); ++k)
    if (grid.grain_size(k) <= p.a_init_max * (1 + 1e-12)) sum += init[k] = std::sqrt(grid.grain_size(k));
  if (sum == 0)
    throw mote::core::InputError(mote::logging::format(
        "disc.a_init_max = %g cm is below the grid's smallest grain, %g cm (coagulation.a_min): no initial dust",
        p.a_init_max, grid.grain_size(0)));
  for (auto& v : init) v *= p.dust_to_gas * p.sigma_gas / sum;
  return init;
}

class CoagSteadyState final : public coag::StandaloneCells {
 public:
  CoagSteadyState(const Params& p, const coag::CoagulationSettings& s, const coag::MassGrid& grid)
      : StandaloneCells(grid, s, p.cells, coag::make_kernel(s, grid, gas_cells(p, s)), mrn(p, grid), p.call_interval,
                        {"g/cm^2", 1.0}) {
    const Real cs = sound_speed(p, s);
    const Real st_frag = s.v_frag * s.v_frag / (3 * p.alpha * cs * cs);
    mote::logging::info(
        mote::logging::format("coag_steady_state: c_s = %.4e cm/s, St_frag = %.3e, "
                              "a_frag = 2 Sigma_g St_frag / (pi rho_m) = %.3e cm",
                              cs, st_frag, 2 * p.sigma_gas * st_frag / (M_PI * s.rho_m)));
  }

  void write_snapshot(mote::io::SnapshotWriter& out) const override {
    write_distribution(out, {"g", 1.0}, {"cm", 1.0});
    const int n = grid_.size();
    const auto sig = host_density();
    std::vector<double> sigma_d(sig.size());
    for (size_t i = 0; i < sig.size(); ++i) {
      const int k = static_cast<int>(i % n);
      sigma_d[i] = sig[i] / std::log(grid_.edge(k + 1) / grid_.edge(k));  // eq. 69
    }
    out.array("sigma_d", mote::io::Block::whole({hsize_t(cells_), hsize_t(n)}), sigma_d.data(), {"g/cm^2", 1.0});
    auto next = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver_.next_substep());
    out.array("next_substep", mote::io::Block::whole({hsize_t(cells_)}), next.data(), {"s", 1.0});
  }

  void finish(double time) override {
    mote::logging::info(mote::logging::format("coag_steady_state: t = %.4e yr, ", time / cgs::year), summary());
  }
};

/// The physical kernel on surface densities.
void check_surface_growth(const mote::core::Deck& d, mote::core::DeckCheck& check) {
  if (!d.has_table("coagulation")) return check.fail_missing_table("coagulation", "coag_steady_state needs it");
  if (d.string("coagulation.kernel") != "physical")
    check.fail("coagulation.kernel", "coag_steady_state needs \"physical\"");
  if (!d.boolean("coagulation.vertically_integrated"))
    check.fail("coagulation.vertically_integrated", "coag_steady_state evolves surface densities: set it to true");
}

void declare(mote::core::DeckSchema& s) {
  coag::declare(s);
  s.table("disc", "The disc annulus whose dust grows (cgs).");
  s.real("disc.radius").default_value(20.0).greater_than(0.0).unit("au").doc("Radius R.");
  s.real("disc.star_mass").default_value(1.0).greater_than(0.0).unit("M_sun").doc("Stellar mass.");
  s.real("disc.temperature").default_value(36.0).greater_than(0.0).unit("K").doc("Mid-plane temperature.");
  s.real("disc.sigma_gas").default_value(16.98).greater_than(0.0).unit("g/cm^2").doc("Gas surface density.");
  s.real("disc.alpha").default_value(1e-3).greater_than(0.0).doc("Turbulence parameter alpha.");
  s.real("disc.dust_to_gas").default_value(0.01).greater_than(0.0).doc("Initial dust-to-gas surface density ratio.");
  s.real("disc.a_init_max")
      .default_value(1e-4)
      .greater_than(0.0)
      .unit("cm")
      .doc("Largest grain of the initial MRN distribution.");
  s.real("disc.headwind")
      .default_value(0.0)
      .min(0.0)
      .unit("cm/s")
      .doc("Head-wind speed eta v_K for radial/azimuthal drift estimates (0: none).");
  s.integer("disc.cells").sets_state_size().default_value(1LL).min(1).doc("Identical cells integrated side by side.");
  s.real("disc.call_interval")
      .default_value(0.0)
      .min(0.0)
      .unit("s")
      .doc("Time between coagulation calls; 0 = one call per output interval.");
  s.rule(check_surface_growth);
}

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  auto s = coag::settings_from_deck(d);
  Params p;
  p.radius = d.real("disc.radius") * cgs::au;
  p.m_star = d.real("disc.star_mass") * cgs::M_sun;
  p.temperature = d.real("disc.temperature");
  p.sigma_gas = d.real("disc.sigma_gas");
  p.alpha = d.real("disc.alpha");
  p.dust_to_gas = d.real("disc.dust_to_gas");
  p.a_init_max = d.real("disc.a_init_max");
  p.headwind = d.real("disc.headwind");
  p.cells = static_cast<int>(d.integer("disc.cells"));
  p.call_interval = d.real("disc.call_interval");
  if (ctx.units.length != 1.0 || ctx.units.mass != 1.0 || ctx.units.time != 1.0)
    throw mote::core::DeckError("coag_steady_state works in cgs: set run.units = \"cgs\"");
  return std::make_unique<CoagSteadyState>(p, s, coag::MassGrid::from_sizes(s.a_min, s.a_max, s.species, s.rho_m));
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(
      argc, argv,
      {"coag_steady_state", "growth-fragmentation steady state at one radius (RBO24 Fig. 10)", declare, create});
}
