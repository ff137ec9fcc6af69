// coag_kernels: the Smoluchowski equation with the constant, additive and
// product kernels (selected by coagulation.kernel) from an exponential initial
// distribution, against the analytic solutions (VALIDATION E1/E2; RBO24
// sec. 5.1). Dimensionless: m0 = N0 = 1 by default, so the kernel's time
// variable is T = K0 N0 m0^k t. The cell is repeated `analytic.cells` times
// (identical results) to exercise the one-team-per-cell kernels.
#include <algorithm>
#include <cmath>
#include <vector>

#include "mote/coagulation/analytic.hpp"
#include "mote/coagulation/coagulation.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/io/problem_main.hpp"

namespace {

namespace coag = mote::coagulation;
using mote::Real;

struct Params {
  std::string kernel;
  Real K0 = 1, N0 = 1, m0 = 1;
  Real x_min = 1e-4, x_max = 1e7, bins_per_decade = 10;
  int cells = 1;
  Real call_interval = 0;
};

class CoagKernels final : public mote::io::Simulation {
 public:
  CoagKernels(const Params& p, const coag::CoagulationSettings& s, const coag::MassGrid& grid)
      : p_(p), grid_(grid), solver_(grid, s, p.cells), kernel_(coag::make_kernel(s, grid)) {
    const int n = grid_.size();
    density_ = mote::RealView2("density", p_.cells, n);
    auto h = Kokkos::create_mirror_view(density_);
    for (int c = 0; c < p_.cells; ++c)
      for (int k = 0; k < n; ++k) h(c, k) = reference(k, 0.0);
    Kokkos::deep_copy(density_, h);
    mass0_ = total_mass();
    if (const auto w = grid_.resolution_warning(); !w.empty()) mote::log::warn(w);
  }

  double max_dt() override { return p_.call_interval > 0 ? p_.call_interval : 1e300; }

  void advance(double, double dt) override {
    const auto st = solver_.integrate(density_, dt, kernel_);
    substeps_ += st.substeps;
    rejections_ += st.rejections;
    if (st.failed_cells > 0)
      throw std::runtime_error(mote::log::cat("coagulation failed in ", st.failed_cells, " cells (max_substeps reached)"));
    tau_ += dt;
  }

  void write_snapshot(mote::io::SnapshotWriter& out) const override {
    const int n = grid_.size();
    out.array("mass", mote::io::Block::whole({hsize_t(n)}), grid_.masses().data(), {"code mass", 1.0});
    out.array("mass_edges", mote::io::Block::whole({hsize_t(n + 1)}), grid_.edges().data(), {"code mass", 1.0});
    const auto rho = host_density();
    out.array("density", mote::io::Block::whole({hsize_t(p_.cells), hsize_t(n)}), rho.data(), {"code density", 1.0});
    std::vector<double> ref(n);
    for (int k = 0; k < n; ++k) ref[k] = reference(k, tau_);
    out.array("analytic_density", mote::io::Block::whole({hsize_t(n)}), ref.data(), {"code density", 1.0});
  }

  void save_state(mote::io::H5File& file) const override {
    const int n = grid_.size();
    const auto rho = host_density();
    file.write("/state/density", mote::io::Block::whole({hsize_t(p_.cells), hsize_t(n)}), rho.data());
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver_.next_substep());
    file.write("/state/next_substep", mote::io::Block::whole({hsize_t(p_.cells)}), h.data());
    file.write_attribute("/state", "tau", tau_);
  }

  void load_state(const mote::io::H5File& file) override {
    const int n = grid_.size();
    std::vector<double> rho(size_t(p_.cells) * n), next(p_.cells);
    file.read("/state/density", mote::io::Block::whole({hsize_t(p_.cells), hsize_t(n)}), rho.data());
    file.read("/state/next_substep", mote::io::Block::whole({hsize_t(p_.cells)}), next.data());
    tau_ = file.read_attribute_real("/state", "tau");
    auto h = Kokkos::create_mirror_view(density_);
    for (int c = 0; c < p_.cells; ++c)
      for (int k = 0; k < n; ++k) h(c, k) = rho[size_t(c) * n + k];
    Kokkos::deep_copy(density_, h);
    auto hn = Kokkos::create_mirror_view(solver_.next_substep());
    for (int c = 0; c < p_.cells; ++c) hn(c) = next[c];
    Kokkos::deep_copy(solver_.next_substep(), hn);
  }

  std::vector<mote::io::Diagnostic> diagnostics() const override {
    const double m = total_mass();
    return {{"mass", m}, {"mass_error", (m - mass0_) / mass0_}, {"substeps", double(substeps_)}, {"rejections", double(rejections_)}};
  }

  std::optional<mote::io::NonFinite> find_non_finite() const override {
    const auto rho = host_density();
    for (size_t i = 0; i < rho.size(); ++i)
      if (!std::isfinite(rho[i]))
        return mote::io::NonFinite{"density", mote::log::cat("cell ", i / grid_.size(), ", species ", i % grid_.size())};
    return std::nullopt;
  }

  void finish(double) override {
    const int n = grid_.size();
    const auto rho = host_density();
    double num = 0, den = 0;
    for (int k = 0; k < n; ++k) {
      const double ref = reference(k, tau_);
      num += std::fabs(rho[k] - ref);
      den += ref;
    }
    mote::log::info(mote::log::format("coag_kernels: kernel = %s, t = %g, bins per decade = %.2f, L1_rel = %.6e, "
                                      "mass error = %.3e, substeps = %lld, rejections = %lld",
                                      p_.kernel.c_str(), tau_, grid_.bins_per_mass_decade(), num / den,
                                      (total_mass() - mass0_) / mass0_, substeps_, rejections_));
  }

 private:
  /// Analytic mass density of bin k at time t.
  double reference(int k, double t) const {
    return p_.N0 * p_.m0 *
           coag::analytic::bin_mass(p_.kernel, grid_.edge(k) / p_.m0, grid_.edge(k + 1) / p_.m0, t, p_.K0, p_.N0, p_.m0);
  }

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
    mote::par_reduce("coag_kernels::mass", 0, p_.cells, 0, grid_.size(), KOKKOS_LAMBDA(int c, int k, double& s) {
      s += rho(c, k);
    }, m);
    return m / p_.cells;
  }

  Params p_;
  coag::MassGrid grid_;
  coag::Coagulation solver_;
  coag::AnyKernel kernel_;
  mote::RealView2 density_;
  double tau_ = 0, mass0_ = 0;
  long long substeps_ = 0, rejections_ = 0;
};

void declare(mote::core::DeckSchema& s) {
  coag::declare(s);
  s.table("analytic", "Exponential initial distribution and mass grid (units of m0).");
  s.real("analytic.N0").default_value(1.0).greater_than(0.0).doc("Initial number density N0.");
  s.real("analytic.m0").default_value(1.0).greater_than(0.0).doc("Initial mean mass m0.");
  s.real("analytic.x_min").default_value(1e-4).greater_than(0.0).doc("First centre mass / m0.");
  s.real("analytic.x_max").default_value(1e7).greater_than(0.0).doc("Last centre mass / m0.");
  s.real("analytic.bins_per_decade").default_value(10.0).greater_than(1.0).doc("Bins per mass decade.");
  s.integer("analytic.cells").default_value(1LL).min(1).doc("Identical cells integrated side by side.");
  s.real("analytic.call_interval").default_value(0.0).min(0.0).unit("code time").doc("Time between coagulation calls; 0 = one call per output interval.");
}

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto s = coag::settings_from_deck(d);
  if (s.kernel == "physical") throw mote::core::DeckError("coag_kernels: coagulation.kernel must be constant, additive or product");
  Params p;
  p.kernel = s.kernel;
  p.K0 = s.kernel_coefficient;
  p.N0 = d.real("analytic.N0");
  p.m0 = d.real("analytic.m0");
  p.x_min = d.real("analytic.x_min");
  p.x_max = d.real("analytic.x_max");
  p.bins_per_decade = d.real("analytic.bins_per_decade");
  p.cells = static_cast<int>(d.integer("analytic.cells"));
  p.call_interval = d.real("analytic.call_interval");
  if (!(p.x_max > p.x_min)) throw mote::core::DeckError("analytic.x_max must exceed analytic.x_min");
  const int n = static_cast<int>(std::lround(std::log10(p.x_max / p.x_min) * p.bins_per_decade)) + 1;
  const auto grid = coag::MassGrid::from_masses(p.x_min * p.m0, p.x_max * p.m0, n);
  return std::make_unique<CoagKernels>(p, s, grid);
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(argc, argv,
                               {"coag_kernels", "Smoluchowski equation with constant/additive/product kernels vs analytic solutions",
                                declare, create});
}
