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
#include "mote/coagulation/standalone_cells.hpp"
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

/// Analytic mass density of bin k at time t (exponential initial distribution).
double reference(const Params& p, const coag::MassGrid& grid, int k, double t) {
  return p.N0 * p.m0 *
         coag::analytic::bin_mass(p.kernel, grid.edge(k) / p.m0, grid.edge(k + 1) / p.m0, t, p.K0, p.N0, p.m0);
}

std::vector<double> initial(const Params& p, const coag::MassGrid& grid) {
  std::vector<double> rho(grid.size());
  for (int k = 0; k < grid.size(); ++k) rho[k] = reference(p, grid, k, 0.0);
  return rho;
}

class CoagKernels final : public coag::StandaloneCells {
 public:
  CoagKernels(const Params& p, const coag::CoagulationSettings& s, const coag::MassGrid& grid)
      : StandaloneCells(grid, s, p.cells, coag::make_kernel(s, grid), initial(p, grid), p.call_interval,
                        {"code density", 1.0}),
        p_(p) {}

  void write_snapshot(mote::io::SnapshotWriter& out) const override {
    write_distribution(out, {"code mass", 1.0}, {"code length", 1.0});
    std::vector<double> ref(grid_.size());
    for (int k = 0; k < grid_.size(); ++k) ref[k] = reference(p_, grid_, k, elapsed_);
    out.array("analytic_density", mote::io::Block::whole({hsize_t(ref.size())}), ref.data(), {"code density", 1.0});
  }

  void finish(double) override {
    const auto rho = host_density();
    double num = 0, den = 0;
    for (int k = 0; k < grid_.size(); ++k) {
      const double ref = reference(p_, grid_, k, elapsed_);
      num += std::fabs(rho[k] - ref);
      den += ref;
    }
    mote::logging::info(
        mote::logging::format("coag_kernels: kernel = %s, t = %g, bins per decade = %.2f, L1_rel = %.6e, ",
                              p_.kernel.c_str(), elapsed_, grid_.bins_per_mass_decade(), num / den),
        summary());
  }

 private:
  Params p_;
};

/// An analytic kernel on a mass range of positive width; the product kernel's
/// solution holds before gelation only, T = K0 N0 m0^2 t < 1 at run.t_end (past it
/// the solution is the sol's alone, whose mass is no longer the total).
void check_analytic(const mote::core::Deck& d, mote::core::DeckCheck& check) {
  if (!d.has_table("coagulation"))
    check.fail_missing_table("coagulation", "coag_kernels needs it, with kernel = constant, additive or product");
  else if (d.string("coagulation.kernel") == "physical")
    check.fail("coagulation.kernel", "coag_kernels needs constant, additive or product");
  else if (d.string("coagulation.kernel") == "product") {
    const double m0 = d.real("analytic.m0");
    const double T = d.real("coagulation.kernel_coefficient") * d.real("analytic.N0") * m0 * m0 * d.real("run.t_end");
    if (!(T < 1.0))
      check.fail("run.t_end", mote::logging::format("gives T = K0 N0 m0^2 t_end = %g: the product kernel's solution "
                                                    "holds before gelation, T < 1",
                                                    T));
  }
  if (!(d.real("analytic.x_max") > d.real("analytic.x_min")))
    check.fail("analytic.x_max", "must exceed " + check.quote("analytic.x_min"));
}

void declare(mote::core::DeckSchema& s) {
  coag::declare(s);
  s.table("analytic", "Exponential initial distribution and mass grid (units of m0).");
  s.real("analytic.N0").default_value(1.0).greater_than(0.0).doc("Initial number density N0.");
  s.real("analytic.m0").default_value(1.0).greater_than(0.0).doc("Initial mean mass m0.");
  s.real("analytic.x_min").default_value(1e-4).greater_than(0.0).doc("First centre mass / m0.");
  s.real("analytic.x_max").default_value(1e7).greater_than(0.0).doc("Last centre mass / m0.");
  s.real("analytic.bins_per_decade").default_value(10.0).greater_than(1.0).doc("Bins per mass decade.");
  s.integer("analytic.cells")
      .sets_state_size()
      .default_value(1LL)
      .min(1)
      .doc("Identical cells integrated side by side.");
  s.real("analytic.call_interval")
      .default_value(0.0)
      .min(0.0)
      .unit("code time")
      .doc("Time between coagulation calls; 0 = one call per output interval.");
  s.rule(check_analytic);
}

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto s = coag::settings_from_deck(d);
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
  const int n = static_cast<int>(std::lround(std::log10(p.x_max / p.x_min) * p.bins_per_decade)) + 1;
  const auto grid = coag::MassGrid::from_masses(p.x_min * p.m0, p.x_max * p.m0, n);
  return std::make_unique<CoagKernels>(p, s, grid);
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(
      argc, argv,
      {"coag_kernels", "Smoluchowski equation with constant/additive/product kernels vs analytic solutions", declare,
       create});
}
