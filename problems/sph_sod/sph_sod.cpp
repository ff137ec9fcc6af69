// sph_sod: the Sod shock tube with the SPH engine (PL15 sec. 3 without dust;
// issue 6): left (rho, v, P) = (rho_l, 0, P_l), right (rho_r, 0, P_r), equal
// particle masses on cubic lattices (spacing ratio (rho_l / rho_r)^(1/d)),
// periodic in x over [-1, 1] so that the second interface at x = +-1 does not
// reach [-0.5, 0.5] before t = 0.2; 1D, or 3D with periodic y, z. The exact
// Riemann solution is compared in check.py; finish() prints the mean absolute
// density error over [-0.5, 0.5] from the C++ exact solver.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/setups/riemann_exact.hpp"
#include "mote/setups/sph_problem.hpp"
#include "mote/sph/sph_simulation.hpp"

namespace {

using namespace mote;

struct SodState {
  double rho, P;
};

class SodSimulation final : public sph::SphSimulation {
 public:
  SodSimulation(std::unique_ptr<sph::SphSystem> sys, const units::UnitSystem& u, SodState l, SodState r)
      : SphSimulation(std::move(sys), u), left_(l), right_(r) {}

  void finish(double time) override {
    const auto& cfg = system_->config();
    const sph::ExactRiemann exact({left_.rho, 0.0, left_.P}, {right_.rho, 0.0, right_.P}, cfg.gamma);
    const auto snap = system_->snapshot();
    double l1 = 0;
    int n = 0;
    for (int i = 0; i < static_cast<int>(snap.m.extent(0)); ++i) {
      const double x = system_->box().wrap(snap.x(i, 0), 0);
      if (x < -0.5 || x > 0.5) continue;
      l1 += std::fabs(snap.rho(i) - exact.sample(x / time).rho);
      ++n;
    }
    logging::info(logging::format("mean |rho - rho_exact| over x in [-0.5, 0.5]: %.4e (%d particles)", l1 / n, n));
  }

 private:
  SodState left_, right_;
};

void declare(core::DeckSchema& s) {
  sph::declare_sph_problem(s, "sph_sod", {"adiabatic"});
  s.table("sod", "Shock-tube set-up.");
  s.integer("sod.dim").sets_state_size().default_value(1LL).min(1).max(3).doc("Dimension (y, z periodic for dim > 1).");
  s.real("sod.dx_left")
      .sets_state_size()
      .default_value(0.002)
      .greater_than(0.0)
      .unit("code length")
      .doc("Particle spacing on the left.");
  s.real("sod.cross_section")
      .sets_state_size()
      .default_value(0.1)
      .greater_than(0.0)
      .unit("code length")
      .doc("Box length in y, z (dim > 1), rounded to whole rows of both halves' spacings.");
  s.real("sod.rho_left")
      .sets_state_size()
      .default_value(1.0)
      .greater_than(0.0)
      .unit("code density")
      .doc("Left density.");
  s.real("sod.P_left").default_value(1.0).greater_than(0.0).unit("code pressure").doc("Left pressure.");
  s.real("sod.rho_right")
      .sets_state_size()
      .default_value(0.125)
      .greater_than(0.0)
      .unit("code density")
      .doc("Right density.");
  s.real("sod.P_right").default_value(0.1).greater_than(0.0).unit("code pressure").doc("Right pressure.");
}

/// In 2D and 3D both halves fill one periodic cross-section: whole rows of the
/// right spacing and of the left, which needs dx_right / dx_left = (rho_left /
/// rho_right)^(1/dim) to be a whole number (2 for Sod's densities in 3D). The
/// cross-section is rounded to the nearest whole number of right rows.
double shared_cross_section(double cross, double dx_l, double dx_r) {
  const double width = std::max(1.0, std::round(cross / dx_r)) * dx_r, rows_l = std::round(width / dx_l);
  if (std::fabs(rows_l * dx_l - width) > 1e-9 * width)
    throw core::DeckError(logging::cat(
        "sod.dim > 1: the two halves' lattices cannot share a periodic cross-section: their spacings' ratio (",
        "sod.rho_left / sod.rho_right)^(1/dim) = ", dx_r / dx_l,
        " is not a whole number (it is 2 for the default densities in 3D)"));
  return width;
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const int dim = static_cast<int>(d.integer("sod.dim"));
  auto cfg = sph::start_sph_problem(ctx, "sph_sod", dim).cfg;
  const SodState l{d.real("sod.rho_left"), d.real("sod.P_left")}, r{d.real("sod.rho_right"), d.real("sod.P_right")};
  sph::Box box;
  box.dim = dim;
  box.lo[0] = -1.0;
  box.hi[0] = 1.0;
  for (int k = 0; k < dim; ++k) box.periodic[k] = true;
  const double dx_l = d.real("sod.dx_left"), dx_r = dx_l * std::pow(l.rho / r.rho, 1.0 / dim);
  if (dim > 1) {
    const double width = shared_cross_section(d.real("sod.cross_section"), dx_l, dx_r);
    for (int k = 1; k < dim; ++k) box.hi[k] = width;
  }
  sph::Box lb = box, rb = box;
  lb.hi[0] = 0.0;
  rb.lo[0] = 0.0;
  const auto ll = sph::cubic_lattice(lb, dx_l), lr = sph::cubic_lattice(rb, dx_r);
  for (int k = 1; k < dim; ++k) {
    if (std::fabs(ll.box.length(k) - lr.box.length(k)) > 1e-9 * ll.box.length(k))
      throw std::logic_error("sph_sod: the halves' lattices differ in their cross-section");
    box.lo[k] = ll.box.lo[k];
    box.hi[k] = ll.box.hi[k];
  }
  sph::ParticleSetup s;
  s.dim = dim;
  s.x = ll.x;
  s.x.insert(s.x.end(), lr.x.begin(), lr.x.end());
  double vol_l = 1, vol_r = 1;
  for (int k = 0; k < dim; ++k) {
    vol_l *= ll.box.length(k);
    vol_r *= lr.box.length(k);
  }
  const double hfact = cfg.effective_hfact(), g1 = cfg.gamma - 1.0;
  for (int i = 0; i < ll.size(); ++i) {
    s.m.push_back(l.rho * vol_l / ll.size());
    s.h.push_back(hfact * ll.dx);
    s.u.push_back(l.P / (g1 * l.rho));
  }
  for (int i = 0; i < lr.size(); ++i) {
    s.m.push_back(r.rho * vol_r / lr.size());
    s.h.push_back(hfact * lr.dx);
    s.u.push_back(r.P / (g1 * r.rho));
  }
  s.v.assign(s.x.size(), 0.0);
  auto sys = std::make_unique<sph::SphSystem>(cfg, box);
  sys->set_particles(s);
  logging::info("sph_sod: ", s.size(), " particles in ", dim, "D");
  return std::make_unique<SodSimulation>(std::move(sys), ctx.units, l, r);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(argc, argv,
                         {"sph_sod", "Sod shock tube with the SPH engine (exact Riemann comparison)", declare, create});
}
