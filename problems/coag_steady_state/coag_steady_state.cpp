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
#include "mote/core/deck.hpp"
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

class CoagSteadyState final : public mote::io::Simulation {
 public:
  CoagSteadyState(const Params& p, const coag::CoagulationSettings& s)
      : p_(p), settings_(s), grid_(coag::MassGrid::from_sizes(s.a_min, s.a_max, s.species, s.rho_m)),
        solver_(grid_, s, p.cells) {
    if (const auto w = grid_.resolution_warning(); !w.empty()) mote::log::warn(w);
    const int n = grid_.size(), nc = p_.cells;
    const Real cs = std::sqrt(cgs::k_B * p_.temperature / (s.mu * cgs::m_H));
    const Real omega = std::sqrt(cgs::G * p_.m_star / (p_.radius * p_.radius * p_.radius));
    coag::GasCells gas;
    gas.sound_speed = mote::RealView1("sound_speed", nc);
    gas.density = mote::RealView1("sigma_gas", nc);
    gas.omega = mote::RealView1("omega", nc);
    gas.alpha = mote::RealView1("alpha", nc);
    gas.headwind = mote::RealView1("headwind", nc);
    Kokkos::deep_copy(gas.sound_speed, cs);
    Kokkos::deep_copy(gas.density, p_.sigma_gas);
    Kokkos::deep_copy(gas.omega, omega);
    Kokkos::deep_copy(gas.alpha, p_.alpha);
    Kokkos::deep_copy(gas.headwind, p_.headwind);
    kernel_ = coag::make_kernel(s, grid_, gas);
    // MRN: dN/da ~ a^-3.5 -> mass per log bin ~ a^0.5, truncated at a_init_max.
    std::vector<double> init(n, 0.0);
    double sum = 0;
    for (int k = 0; k < n; ++k)
      if (grid_.grain_size(k) <= p_.a_init_max * (1 + 1e-12)) sum += init[k] = std::sqrt(grid_.grain_size(k));
    density_ = mote::RealView2("sigma_dust", nc, n);
    auto h = Kokkos::create_mirror_view(density_);
    for (int c = 0; c < nc; ++c)
      for (int k = 0; k < n; ++k) h(c, k) = p_.dust_to_gas * p_.sigma_gas * init[k] / sum;
    Kokkos::deep_copy(density_, h);
    mass0_ = total_mass();
    const Real st_frag = s.v_frag * s.v_frag / (3 * p_.alpha * cs * cs);
    mote::log::info(mote::log::format("coag_steady_state: c_s = %.4e cm/s, Omega = %.4e 1/s, St_frag = %.3e, "
                                      "a_frag = 2 Sigma_g St_frag / (pi rho_m) = %.3e cm",
                                      cs, omega, st_frag, 2 * p_.sigma_gas * st_frag / (M_PI * s.rho_m)));
  }

  double max_dt() override { return p_.call_interval > 0 ? p_.call_interval : 1e300; }

  void advance(double, double dt) override {
    const auto st = solver_.integrate(density_, dt, kernel_);
    substeps_ += st.substeps;
    rejections_ += st.rejections;
    if (st.failed_cells > 0)
      throw std::runtime_error(mote::log::cat("coagulation failed in ", st.failed_cells, " cells (max_substeps reached)"));
  }

  void write_snapshot(mote::io::SnapshotWriter& out) const override {
    const int n = grid_.size(), nc = p_.cells;
    out.array("mass", mote::io::Block::whole({hsize_t(n)}), grid_.masses().data(), {"g", 1.0});
    out.array("mass_edges", mote::io::Block::whole({hsize_t(n + 1)}), grid_.edges().data(), {"g", 1.0});
    out.array("grain_size", mote::io::Block::whole({hsize_t(n)}), grid_.sizes().data(), {"cm", 1.0});
    const auto sig = host_density();
    std::vector<double> sigma_d(sig.size());
    for (int c = 0; c < nc; ++c)
      for (int k = 0; k < n; ++k)
        sigma_d[size_t(c) * n + k] = sig[size_t(c) * n + k] / std::log(grid_.edge(k + 1) / grid_.edge(k));
    out.array("surface_density", mote::io::Block::whole({hsize_t(nc), hsize_t(n)}), sig.data(), {"g/cm^2", 1.0});
    out.array("sigma_d", mote::io::Block::whole({hsize_t(nc), hsize_t(n)}), sigma_d.data(), {"g/cm^2", 1.0});
    auto next = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver_.next_substep());
    out.array("next_substep", mote::io::Block::whole({hsize_t(nc)}), next.data(), {"s", 1.0});
  }

  void save_state(mote::io::H5File& file) const override {
    const auto sig = host_density();
    file.write("/state/surface_density", mote::io::Block::whole({hsize_t(p_.cells), hsize_t(grid_.size())}), sig.data());
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver_.next_substep());
    file.write("/state/next_substep", mote::io::Block::whole({hsize_t(p_.cells)}), h.data());
  }

  void load_state(const mote::io::H5File& file) override {
    const int n = grid_.size();
    std::vector<double> sig(size_t(p_.cells) * n), next(p_.cells);
    file.read("/state/surface_density", mote::io::Block::whole({hsize_t(p_.cells), hsize_t(n)}), sig.data());
    file.read("/state/next_substep", mote::io::Block::whole({hsize_t(p_.cells)}), next.data());
    auto h = Kokkos::create_mirror_view(density_);
    for (int c = 0; c < p_.cells; ++c)
      for (int k = 0; k < n; ++k) h(c, k) = sig[size_t(c) * n + k];
    Kokkos::deep_copy(density_, h);
    auto hn = Kokkos::create_mirror_view(solver_.next_substep());
    for (int c = 0; c < p_.cells; ++c) hn(c) = next[c];
    Kokkos::deep_copy(solver_.next_substep(), hn);
  }

  std::vector<mote::io::Diagnostic> diagnostics() const override {
    const double m = total_mass();
    return {{"dust_surface_density", m}, {"mass_error", (m - mass0_) / mass0_}, {"substeps", double(substeps_)},
            {"rejections", double(rejections_)}};
  }

  std::optional<mote::io::NonFinite> find_non_finite() const override {
    const auto sig = host_density();
    for (size_t i = 0; i < sig.size(); ++i)
      if (!std::isfinite(sig[i]))
        return mote::io::NonFinite{"surface_density", mote::log::cat("cell ", i / grid_.size(), ", species ", i % grid_.size())};
    return std::nullopt;
  }

  void finish(double time) override {
    mote::log::info(mote::log::format("coag_steady_state: t = %.4e yr, mass error = %.3e, substeps = %lld, rejections = %lld",
                                      time / cgs::year, (total_mass() - mass0_) / mass0_, substeps_, rejections_));
  }

 private:
  std::vector<double> host_density() const {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), density_);
    std::vector<double> out(h.size());
    for (int c = 0; c < p_.cells; ++c)
      for (int k = 0; k < grid_.size(); ++k) out[size_t(c) * grid_.size() + k] = h(c, k);
    return out;
  }

  double total_mass() const {
    auto rho = density_;
    double m = 0;
    mote::par_reduce("coag_steady_state::mass", 0, p_.cells, 0, grid_.size(), KOKKOS_LAMBDA(int c, int k, double& s) {
      s += rho(c, k);
    }, m);
    return m / p_.cells;
  }

  Params p_;
  coag::CoagulationSettings settings_;
  coag::MassGrid grid_;
  coag::Coagulation solver_;
  coag::AnyKernel kernel_;
  mote::RealView2 density_;
  double mass0_ = 0;
  long long substeps_ = 0, rejections_ = 0;
};

void declare(mote::core::DeckSchema& s) {
  coag::declare(s);
  s.table("disc", "The disc annulus whose dust grows (cgs).");
  s.real("disc.radius").default_value(20.0).greater_than(0.0).unit("au").doc("Radius R.");
  s.real("disc.star_mass").default_value(1.0).greater_than(0.0).unit("M_sun").doc("Stellar mass.");
  s.real("disc.temperature").default_value(36.0).greater_than(0.0).unit("K").doc("Mid-plane temperature.");
  s.real("disc.sigma_gas").default_value(16.98).greater_than(0.0).unit("g/cm^2").doc("Gas surface density.");
  s.real("disc.alpha").default_value(1e-3).greater_than(0.0).doc("Turbulence parameter alpha.");
  s.real("disc.dust_to_gas").default_value(0.01).greater_than(0.0).doc("Initial dust-to-gas surface density ratio.");
  s.real("disc.a_init_max").default_value(1e-4).greater_than(0.0).unit("cm").doc("Largest grain of the initial MRN distribution.");
  s.real("disc.headwind").default_value(0.0).min(0.0).unit("cm/s").doc("Head-wind speed eta v_K for radial/azimuthal drift estimates (0: none).");
  s.integer("disc.cells").default_value(1LL).min(1).doc("Identical cells integrated side by side.");
  s.real("disc.call_interval").default_value(0.0).min(0.0).unit("s").doc("Time between coagulation calls; 0 = one call per output interval.");
}

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  auto s = coag::settings_from_deck(d);
  if (s.kernel != "physical") throw mote::core::DeckError("coag_steady_state: coagulation.kernel must be \"physical\"");
  if (!s.vertically_integrated)
    throw mote::core::DeckError("coag_steady_state evolves surface densities: set coagulation.vertically_integrated = true");
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
  return std::make_unique<CoagSteadyState>(p, s);
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(argc, argv,
                               {"coag_steady_state", "growth-fragmentation steady state at one radius (RBO24 Fig. 10)", declare,
                                create});
}
