// sph_dustybox: the accelerated dustybox of LAB15 sec. 3 (VALIDATION B1-B2)
// with two-fluid dust particles and the semi-implicit pairwise drag (LAB15
// eq. 17-19, or the original eq. 4-6 with dust.drag_scheme = "original"): gas
// and dust on interleaved lattices in the periodic box [-2, 2)^dim, uniform
// rho_G = 1 and rho_D = eps, v_D(0) = v0, v_G(0) = 0, a constant acceleration
// a_D on the dust only, constant stopping time. The time-step is the engine's
// (the gas Courant condition; no drag constraint), so a small t_s gives
// dt >> t_s. check.py compares the dust velocity (dust momentum / dust mass in
// the history) with eq. 31-32. With dust.species = N each species has its own
// lattice and stopping time (dust.stopping_time = [t_1, ..., t_N]) and
// rho_D,j = eps rho_G; check.py --species-ts compares each species' mean
// velocity in the snapshots with the exact solution of the linear system.
#include <sstream>

#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/setups/dustybox.hpp"
#include "mote/setups/sph_problem.hpp"
#include "mote/sph/sph_simulation.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  sph::declare_sph_problem(s, "sph_dustybox", {"", {"two-fluid"}, true});
  s.rule(io::requires_choice("sph_dustybox", "dust.drag", "constant_ts"));
  s.table("dustybox", "Accelerated dustybox (LAB15 sec. 3).");
  s.integer("dustybox.dim").sets_state_size().default_value(1LL).min(1).max(3).doc("Dimension (LAB15: 1 and 3).");
  s.integer("dustybox.n")
      .sets_state_size()
      .default_value(128LL)
      .min(4)
      .doc("Particles per phase along each direction of [-2, 2).");
  s.real("dustybox.eps")
      .default_value(0.01)
      .greater_than(0.0)
      .doc("Dust-to-gas density ratio rho_D / rho_G of each dust species.");
  s.real("dustybox.v_dust").default_value(1.0).unit("code velocity").doc("Initial dust velocity along x.");
  s.real("dustybox.a_dust").default_value(0.1).unit("code acceleration").doc("Acceleration of the dust along x.");
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  sph::DustyBox box;
  box.dim = static_cast<int>(d.integer("dustybox.dim"));
  box.n = static_cast<int>(d.integer("dustybox.n"));
  box.eps = d.real("dustybox.eps");
  box.v_dust = d.real("dustybox.v_dust");
  box.a_dust = d.real("dustybox.a_dust");
  const auto [cfg, ds] = sph::start_sph_problem(ctx, "sph_dustybox", box.dim);
  std::ostringstream ts;
  for (int j = 0; j < ds.nspecies; ++j) ts << (j ? ", " : "") << ds.species_value(ds.stopping_time, j);
  logging::info("sph_dustybox: ", box.dim, "D, ", ds.nspecies + 1, " x ", box.n, "^", box.dim,
                " particles, eps = ", box.eps, " per species, t_s = ", ts.str(), ", drag scheme ",
                ds.drag_scheme == sph::TwoFluidDrag::Improved ? "improved" : "original");
  return std::make_unique<sph::SphSimulation>(sph::make_dustybox(box, cfg, ds), ctx.units);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(argc, argv,
                         {"sph_dustybox", "Accelerated dustybox, two-fluid SPH dust (LAB15 sec. 3)", declare, create});
}
