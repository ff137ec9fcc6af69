// sph_dustydiffuse: diffusion of a dust overdensity (PL15 sec. 4.3,
// VALIDATION A3): uniform rho = 1 in [-0.5, 0.5]^3 periodic, isothermal c_s,
// constant stopping time t_s, eps(r, 0) = eps0 (1 - (r / r_c)^2) for r < r_c
// (eq. 52); the particles stay fixed and only the dust equation is evolved
// (PL15 eq. 43, or eq. 26 and 30), each step one kick-predict-kick dust step of
// sph::advance_dust_only. check.py compares eps with the self-similar
// solution eq. 51.
#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/setups/dust_problems.hpp"
#include "mote/setups/sph_problem.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_simulation.hpp"

namespace {

using namespace mote;

/// Dust-only evolution with the particles fixed (PL15 sec. 4.3).
class DiffuseSimulation final : public sph::SphSimulation {
 public:
  using SphSimulation::SphSimulation;
  double max_dt() override {
    return system_->module<sph::OneFluidDust>()->timestep(system_->particles(), system_->config());
  }
  void advance(double, double dt) override { sph::advance_dust_only(*system_, dt); }
};

void declare(core::DeckSchema& s) {
  sph::declare_sph_problem(s, "sph_dustydiffuse", {"isothermal"});
  sph::declare_dust_problem(s, "sph_dustydiffuse", sph::DragLaw::ConstantStoppingTime, false);
  s.table("dustydiffuse", "Dust diffusion with fixed particles (PL15 sec. 4.3).");
  s.integer("dustydiffuse.n")
      .sets_state_size()
      .default_value(50LL)
      .min(4)
      .doc("Particles per unit length along x (spacing 1 / n).");
  s.string("dustydiffuse.lattice")
      .default_value(std::string("close_packed"))
      .one_of({"cubic", "close_packed"})
      .doc("Cubic lattice (n^3) or close-packed (n = 50: 50 x 58 x 62).");
  s.real("dustydiffuse.eps0")
      .default_value(0.1)
      .greater_than(0.0)
      .less_than(1.0)
      .doc("Central dust fraction eps0 (eq. 52).");
  s.real("dustydiffuse.r_c")
      .default_value(0.25)
      .greater_than(0.0)
      .max(0.5)
      .unit("code length")
      .doc("Cloud radius r_c (eq. 52).");
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto [cfg, ds] = sph::start_sph_problem(ctx, "sph_dustydiffuse", 3);
  sph::DustyDiffuse dd;
  dd.n = static_cast<int>(d.integer("dustydiffuse.n"));
  dd.close_packed = d.string("dustydiffuse.lattice") == "close_packed";
  dd.eps0 = d.real("dustydiffuse.eps0");
  dd.r_c = d.real("dustydiffuse.r_c");
  const auto pr = sph::dustydiffuse(dd, cfg, ds);
  logging::info("sph_dustydiffuse: ", pr.particles.size(), " particles, ", ds.nspecies, " dust species");
  return std::make_unique<DiffuseSimulation>(pr.make_system(), ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"sph_dustydiffuse", "Dust diffusion with fixed particles, one-fluid SPH dust (PL15 sec. 4.3)", declare, create});
}
