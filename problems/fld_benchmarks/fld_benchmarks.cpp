// fld_benchmarks: the multi-band flux-limited diffusion solver of RBO24 sec.
// 4.1 (eq. 39-43, 47-49) on its own, in the two media of VALIDATION D3 and D4:
//   case = "diffusion" (D3): a Gaussian of radiation energy in a uniform,
//     optically thick, purely scattering medium (no exchange with the matter),
//     E = A exp(-((R - R_0)^2 + Z^2) / 2 s^2), s^2 = s_0^2 + 2 D t,
//     A = s_0^2 / s^2, with D = c / (3 chi): the limiter is 1/3 there, so FLD
//     is the heat equation; reflecting sides, planar cells skewed by the theta
//     coordinate.
//   case = "equilibrium" (D4): a uniform medium with reflecting sides, matter
//     at T_init and no radiation, relaxing to radiative equilibrium in every
//     band, f^b(T) 4 sigma T^4 = c E^b; chi^b = rosseland_factor kappa_P^b rho.
// The medium's opacities and heat capacity come from [fld_test]; the star and
// opacity keys of [radiation] are not used. check.py asserts the D3 errors
// and orders against the analytic Gaussian and the D4 equilibrium and energy.
#include <cmath>
#include <memory>
#include <vector>

#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/mesh/grid_output.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/fld_state_io.hpp"
#include "mote/radiation/settings.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  mesh::GridSpec::declare(s);
  radiation::declare(s);
  s.table("fld_test", "The medium of fld_benchmarks (VALIDATION D3, D4).");
  s.string("fld_test.case").one_of({"diffusion", "equilibrium"}).doc("D3: thick diffusion; D4: radiative equilibrium.");
  s.real("fld_test.dt").greater_than(0.0).unit("code time").doc("Time-step (backward Euler).");
  s.real("fld_test.diffusivity")
      .default_value(1.0)
      .greater_than(0.0)
      .unit("code length^2 / code time")
      .doc("diffusion: D = c / (3 chi), which sets the extinction chi.");
  s.real("fld_test.width").default_value(0.15).greater_than(0.0).unit("code length").doc("diffusion: s_0.");
  s.real("fld_test.R_0").default_value(2.0).unit("code length").doc("diffusion: centre R of the Gaussian (Z = 0).");
  s.real("fld_test.rho").default_value(1e-12).greater_than(0.0).unit("code density").doc("equilibrium: density.");
  s.real_array("fld_test.kappa_planck")
      .default_value(std::vector<double>{10.0, 3.0, 1.0, 0.3})
      .greater_than(0.0)
      .unit("code length^2 / code mass")
      .doc("equilibrium: Planck mean absorption opacity per band.");
  s.real("fld_test.rosseland_factor")
      .default_value(2.0)
      .greater_than(0.0)
      .doc("equilibrium: kappa_R^b / kappa_P^b (scattering adds to the total).");
  s.real("fld_test.heat_capacity")
      .default_value(1e-8)
      .greater_than(0.0)
      .unit("code energy / code volume / K")
      .doc("equilibrium: rho c_V.");
  s.real("fld_test.T_init").default_value(100.0).greater_than(0.0).unit("K").doc("equilibrium: initial T.");
  s.rule(io::requires_table("fld_benchmarks", "radiation"));
  s.rule([](const core::Deck& d, core::DeckCheck& check) {
    if (d.string("fld_test.case") == "equilibrium" &&
        static_cast<long long>(d.real_array("fld_test.kappa_planck").size()) != d.integer("radiation.bands"))
      check.fail("fld_test.kappa_planck", "needs one value per band (radiation.bands)");
    if (d.string("fld_test.case") == "diffusion" && d.string("grid.geometry") != "planar")
      check.fail("grid.geometry", "the diffusion case needs \"planar\" (its reference is the planar heat kernel)");
  });
}

/// The D3 Gaussian, the 2D heat kernel, at R, Z and t.
KOKKOS_INLINE_FUNCTION Real heat_kernel(Real R, Real Z, Real R0, Real s0, Real D, Real t) {
  const Real s2 = s0 * s0 + 2.0 * D * t;
  return s0 * s0 / s2 * math::exp(-((R - R0) * (R - R0) + Z * Z) / (2.0 * s2));
}

class FldBenchmark : public io::Simulation {
 public:
  FldBenchmark(const core::Deck& deck, const core::Comm& comm, const units::UnitSystem& units)
      : units_(units),
        diffusion_(deck.string("fld_test.case") == "diffusion"),
        dt_(deck.real("fld_test.dt")),
        rd_(radiation::from_deck(deck, units)),
        grid_(mesh::GridSpec::from_deck(deck), comm),
        fld_(grid_, rd_.fld, radiation::RadiationConstants::in(units)),
        fields_(fld_.make_fields()),
        state_(fld_.make_state()) {
    Kokkos::deep_copy(fields_.heating, 0.0);
    Kokkos::deep_copy(fields_.scattering_source, 0.0);
    if (diffusion_)
      set_up_diffusion(deck);
    else
      set_up_equilibrium(deck);
  }

  void set_up_diffusion(const core::Deck& deck) {
    Kokkos::deep_copy(fields_.heat_capacity, 1.0);
    Kokkos::deep_copy(fields_.absorption, 0.0);  // no exchange with the matter: pure diffusion of E
    Kokkos::deep_copy(fields_.extinction, fld_.constants().c / (3.0 * deck.real("fld_test.diffusivity")));
    Kokkos::deep_copy(state_.T, 10.0);
    const Real R0 = deck.real("fld_test.R_0"), s0 = deck.real("fld_test.width");
    const auto Rc = grid_.Rc;
    const auto Zc = grid_.Zc;
    const auto E = state_.E;
    par_for(
        "fld_benchmarks::gaussian", 0, grid_.nr_total(), 0, grid_.nt_total(),
        KOKKOS_LAMBDA(int i, int j) { E(i, j, 0) = heat_kernel(Rc(i), Zc(i, j), R0, s0, 1.0, 0.0); });
  }

  void set_up_equilibrium(const core::Deck& deck) {
    const Real rho = deck.real("fld_test.rho"), factor = deck.real("fld_test.rosseland_factor");
    const auto kappa_h = deck.real_array("fld_test.kappa_planck");
    RealView1 kappa("fld_benchmarks::kappa_planck", kappa_h.size());
    auto k = Kokkos::create_mirror_view(kappa);
    for (size_t b = 0; b < kappa_h.size(); ++b) k(b) = kappa_h[b];
    Kokkos::deep_copy(kappa, k);
    const auto absorption = fields_.absorption, extinction = fields_.extinction;
    const int nb = fld_.bands();
    par_for(
        "fld_benchmarks::uniform_medium", 0, grid_.nr_total(), 0, grid_.nt_total(), KOKKOS_LAMBDA(int i, int j) {
          for (int b = 0; b < nb; ++b) {
            absorption(i, j, b) = rho * kappa(b);
            extinction(i, j, b) = factor * rho * kappa(b);
          }
        });
    Kokkos::deep_copy(fields_.heat_capacity, deck.real("fld_test.heat_capacity"));
    Kokkos::deep_copy(state_.T, deck.real("fld_test.T_init"));
    Kokkos::deep_copy(state_.E, 0.0);
  }

  double max_dt() override { return dt_; }
  std::string dt_limit() const override { return "fld_test.dt"; }

  /// The solver's failures are core::NumericalError (exit 3), thrown on every rank together.
  void advance(double, double dt) override {
    last_ = fld_.step(dt, fields_, state_);
    iterations_ += last_.total_iterations();
    if (last_.attempts.size() > 1) logging::warn("fld_benchmarks: ", last_.summary());
  }

  void write_snapshot(io::SnapshotWriter& out) const override {
    mesh::describe_grid(out, grid_);
    out.cell_field("T", mesh::active_cells(grid_, state_.T).data(), {"K", 1.0});
    for (int b = 0; b < fld_.bands(); ++b) {
      const auto E_b = Kokkos::subview(state_.E, Kokkos::ALL, Kokkos::ALL, b);
      RealView2 copy("fld_benchmarks::E_band", grid_.nr_total(), grid_.nt_total());
      Kokkos::deep_copy(copy, E_b);
      out.cell_field("E_" + std::to_string(b), mesh::active_cells(grid_, copy).data(),
                     {"code energy / volume", units_.pressure()});
    }
    // The cells' geometry, for check.py's analytic solution and volume weights.
    out.cell_field("Z", mesh::active_cells(grid_, grid_.Zc).data(), {"code length", units_.length});
    out.cell_field("volume", mesh::active_cells(grid_, grid_.V).data(), {"code volume", std::pow(units_.length, 3)});
  }

  void save_state(io::H5File& file) const override {
    radiation::write_fld_state(file, "/state/radiation", grid_, state_);
    file.write_attribute("/state", "fld_iterations", static_cast<std::int64_t>(iterations_));
  }

  void load_state(const io::H5File& file) override {
    radiation::read_fld_state(file, "/state/radiation", grid_, state_);
    iterations_ = file.read_attribute_int("/state", "fld_iterations");
  }

  std::vector<io::Diagnostic> diagnostics() const override {
    const bool stepped = !last_.attempts.empty();
    return {{"fld_iterations", double(iterations_)},
            {"fld_step_iterations", stepped ? double(last_.total_iterations()) : 0.0},
            {"fld_step_residual", stepped ? last_.last().residual : 0.0},
            {"fld_attempts", double(last_.attempts.size())}};
  }

  std::optional<io::NonFinite> find_non_finite() const override {
    const auto T = state_.T;
    const auto E = state_.E;
    const int nb = fld_.bands();
    int bad = 0;
    par_reduce(
        "fld_benchmarks::non_finite", grid_.i_begin(), grid_.i_end(), grid_.j_begin(), grid_.j_end(),
        KOKKOS_LAMBDA(int i, int j, int& n) {
          bool ok = math::isfinite(T(i, j));
          for (int b = 0; b < nb; ++b) ok = ok && math::isfinite(E(i, j, b));
          n += ok ? 0 : 1;
        },
        bad);
    if (bad == 0) return std::nullopt;
    return io::NonFinite{"T or E", std::to_string(bad) + " cells"};
  }

 private:
  units::UnitSystem units_;
  bool diffusion_;
  double dt_;
  radiation::RadiationDeck rd_;
  mesh::Grid grid_;
  radiation::FldSolver fld_;
  radiation::FldFields fields_;
  radiation::FldState state_;
  linalg::SolveReport last_;
  long long iterations_ = 0;
};

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  return std::make_unique<FldBenchmark>(ctx.deck, ctx.comm, ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"fld_benchmarks", "multi-band FLD alone: thick diffusion (D3) and radiative equilibrium (D4)", declare, create});
}
