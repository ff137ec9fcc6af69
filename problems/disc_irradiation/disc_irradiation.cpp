// disc_irradiation: the temperature of a passive disc heated by its star
// (RBO24 sec. 4; VALIDATION D2, and the set-up of the D5 family): a fixed gas
// density rho_g = rho_0 (R / R_0)^p exp(-Z^2 / 2 H^2), H = h R, with one dust
// species at dust_to_gas; stellar heating by ray tracing (eq. 45-46) and the
// multi-band FLD of eq. 48-49, relaxed to the steady state at the first step
// ([irradiation] steady = true) or stepped with the run's time-step.
// check.py compares T with the optically thin T_star (R_star / 2 r)^(1/2)
// where the stellar optical depth is below thin_tau, and checks the energy
// balance of the absorbed starlight.
#include <cmath>
#include <limits>
#include <memory>

#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/mesh/grid_output.hpp"
#include "mote/radiation/dust_opacities.hpp"
#include "mote/radiation/fld_state_io.hpp"
#include "mote/radiation/settings.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  mesh::GridSpec::declare(s);
  radiation::declare(s);
  s.table("irradiation", "The disc of disc_irradiation: fixed gas and dust densities.");
  s.real("irradiation.rho_0").greater_than(0.0).unit("g/cm^3").doc("Mid-plane gas density at R_0.");
  s.real("irradiation.R_0").default_value(1.0).greater_than(0.0).unit("code length").doc("Reference radius.");
  s.real("irradiation.p").default_value(-2.25).doc("rho_mid proportional to R^p.");
  s.real("irradiation.h").default_value(0.05).greater_than(0.0).doc("Aspect ratio H / R of the gas.");
  s.real("irradiation.dust_to_gas").default_value(0.01).greater_than(0.0).doc("Dust-to-gas mass ratio.");
  s.real("irradiation.a_grain").default_value(1e-4).greater_than(0.0).unit("cm").doc("Grain size of the species.");
  s.real("irradiation.c_V").default_value(3.6e7).greater_than(0.0).unit("erg/g/K").doc("Specific heat of the gas.");
  s.real("irradiation.T_init").default_value(20.0).greater_than(0.0).unit("K").doc("Initial temperature.");
  s.boolean("irradiation.steady").default_value(true).doc("Relax to the steady state at the first step.");
  s.rule(io::requires_table("disc_irradiation", "radiation"));
  // Its opacities are filled once, at set-up: band means at a temperature known then.
  s.rule(io::requires_choice("disc_irradiation", "radiation.band_means", "fixed"));
}

/// rho_g = rho_0 (R / R_0)^p exp(-Z^2 / 2 H^2), H = h R, and rho_d = dust_to_gas rho_g
/// in every cell (ghosts included); rho_0 in code units.
void disc_densities(const mesh::Grid& grid, Real rho0, Real R0, Real p, Real h, Real dust_to_gas,
                    const RealView2& rho_g, const RealView3& rho_d) {
  const auto Rc = grid.Rc;
  const auto Zc = grid.Zc;
  par_for(
      "irradiation::densities", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        const Real H = h * Rc(i), z = Zc(i, j) / H;
        rho_g(i, j) = rho0 * math::pow(Rc(i) / R0, p) * math::exp(-0.5 * z * z);
        rho_d(i, j, 0) = dust_to_gas * rho_g(i, j);
      });
}

/// C(i, j) = rho_g(i, j) c_V.
void heat_capacity(const RealView2& rho_g, Real c_V, const RealView2& C) {
  par_for(
      "irradiation::heat_capacity", 0, static_cast<int>(C.extent(0)), 0, static_cast<int>(C.extent(1)),
      KOKKOS_LAMBDA(int i, int j) { C(i, j) = rho_g(i, j) * c_V; });
}

class IrradiatedDisc : public io::Simulation {
 public:
  IrradiatedDisc(const core::Deck& deck, const core::Comm& comm, const units::UnitSystem& units)
      : units_(units),
        t_end_(deck.real("run.t_end")),
        steady_(deck.boolean("irradiation.steady")),
        rd_(radiation::from_deck(deck, units)),
        grid_(mesh::GridSpec::from_deck(deck), comm),
        constants_(radiation::RadiationConstants::in(units)),
        fld_(grid_, rd_.fld, constants_),
        star_(grid_, rd_.star, rd_.stellar_bin_edges_cm, rd_.fld.band_edges_cm, constants_),
        fields_(fld_.make_fields()),
        state_(fld_.make_state()) {
    rho_gas_ = RealView2("irradiation::rho_gas", grid_.nr_total(), grid_.nt_total());
    rho_dust_ = RealView3("irradiation::rho_dust", grid_.nr_total(), grid_.nt_total(), 1);
    disc_densities(grid_, deck.real("irradiation.rho_0") / units.density(), deck.real("irradiation.R_0"),
                   deck.real("irradiation.p"), deck.real("irradiation.h"), deck.real("irradiation.dust_to_gas"),
                   rho_gas_, rho_dust_);
    const auto table = rd_.opacities({deck.real("irradiation.a_grain")});
    const auto kappa = radiation::DustOpacities::from_table(table, rd_.stellar_bin_edges_cm, rd_.fld.band_edges_cm,
                                                            rd_.T_binning, units);
    const double kappa_gas = rd_.kappa_gas * units.mass / (units.length * units.length);
    radiation::fill_fld_opacities(kappa, rho_dust_, rho_gas_, kappa_gas, fields_);
    RealView3 ext("irradiation::k_ext", grid_.nr_total(), grid_.nt_total(), star_.bins());
    RealView3 abs("irradiation::k_abs", grid_.nr_total(), grid_.nt_total(), star_.bins());
    radiation::fill_stellar_opacities(kappa, rho_dust_, rho_gas_, kappa_gas, ext, abs);
    star_.heat(ext, abs, fields_.heating, fields_.scattering_source);
    const double c_V = deck.real("irradiation.c_V") / units.specific_energy();  // per K
    heat_capacity(rho_gas_, c_V, fields_.heat_capacity);
    Kokkos::deep_copy(state_.T, deck.real("irradiation.T_init"));
    Kokkos::deep_copy(state_.E, 0.0);
    open_luminosity_ = fld_.open_boundary_luminosity(state_);
  }

  double max_dt() override { return t_end_; }
  std::string dt_limit() const override { return "run.t_end (one step per output)"; }

  /// The solver's failures are core::NumericalError (exit 3), thrown on every rank together.
  void advance(double, double dt) override {
    if (steady_ && relaxed_) return;  // nothing left to solve
    if (steady_) {
      relaxation_ = fld_.relax_to_steady_state(fields_, state_);
      relaxed_ = true;
      logging::info("radiation: steady state after ", relaxation_.solves, " solves, ", relaxation_.iterations,
                    " BiCGStab iterations, ", relaxation_.solve_seconds, " s in the linear solver");
    } else {
      logging::info("radiation: ", fld_.step(dt, fields_, state_).summary());
    }
    open_luminosity_ = fld_.open_boundary_luminosity(state_);
  }

  void write_snapshot(io::SnapshotWriter& out) const override {
    mesh::describe_grid(out, grid_);
    out.cell_field("T", mesh::active_cells(grid_, state_.T).data(), {"K", 1.0});
    out.cell_field("heating", mesh::active_cells(grid_, fields_.heating).data(),
                   {"code energy / volume / time", units_.pressure() / units_.time});
    out.cell_field("rho_gas", mesh::active_cells(grid_, rho_gas_).data(), {"code density", units_.density()});
    out.cell_field("E_total", mesh::active_cells(grid_, radiation::total_energy_density(state_.E)).data(),
                   {"code energy / volume", units_.pressure()});
  }

  void save_state(io::H5File& file) const override {
    radiation::write_fld_state(file, "/state/radiation", grid_, state_);
    file.write_attribute("/state", "relaxed", relaxed_ ? 1.0 : 0.0);
    file.write_attribute("/state", "open_luminosity", open_luminosity_);
  }

  void load_state(const io::H5File& file) override {
    radiation::read_fld_state(file, "/state/radiation", grid_, state_);
    relaxed_ = file.read_attribute_real("/state", "relaxed") > 0.5;
    // The luminosity of the last solve, with that solve's coefficients (the solver's own are set up
    // anew here: a steady run makes no solve after its restart).
    if (file.has_attribute("/state", "open_luminosity")) {
      open_luminosity_ = file.read_attribute_real("/state", "open_luminosity");
    } else {
      open_luminosity_ = std::numeric_limits<double>::quiet_NaN();
      logging::warn("the checkpoint predates its stored open_luminosity: the history gives nan until the next solve");
    }
  }

  std::vector<io::Diagnostic> diagnostics() const override {
    return {{"absorbed_star", radiation::absorbed_power(grid_, fields_)},
            {"open_luminosity", open_luminosity_},
            {"steady_solves", double(relaxation_.solves)},
            {"fld_iterations", double(relaxation_.iterations)},
            {"fld_solve_s", relaxation_.solve_seconds}};
  }

  std::optional<io::NonFinite> find_non_finite() const override {
    const auto T = state_.T;
    int bad = 0;
    par_reduce(
        "irradiation::non_finite", grid_.i_begin(), grid_.i_end(), grid_.j_begin(), grid_.j_end(),
        KOKKOS_LAMBDA(int i, int j, int& n) { n += math::isfinite(T(i, j)) ? 0 : 1; }, bad);
    if (bad == 0) return std::nullopt;
    return io::NonFinite{"T", std::to_string(bad) + " cells"};
  }

 private:
  units::UnitSystem units_;
  double t_end_;
  bool steady_, relaxed_ = false;
  double open_luminosity_ = 0.0;  // through the open sides after the last solve (history)
  radiation::FldSolver::Relaxation relaxation_;
  radiation::RadiationDeck rd_;
  mesh::Grid grid_;
  radiation::RadiationConstants constants_;
  radiation::FldSolver fld_;
  radiation::StellarIrradiation star_;
  radiation::FldFields fields_;
  radiation::FldState state_;
  RealView2 rho_gas_;
  RealView3 rho_dust_;
};

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  return std::make_unique<IrradiatedDisc>(ctx.deck, ctx.comm, ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"disc_irradiation", "passive disc heated by its star: ray tracing + multi-band FLD", declare, create});
}
