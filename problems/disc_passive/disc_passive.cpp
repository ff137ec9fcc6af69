// disc_passive: the temperature of a passive, settled dusty disc from the
// coupled temperature solver (RBO24 sec. 4 and 6, the set-up of sec. 4.3 /
// VALIDATION D5 on a CI-sized grid). The gas is a static alpha disc (GasDisc);
// the dust species, MRN-weighted (mass per logarithmic size interval
// proportional to a^1/2, i.e. n(a) ~ a^-3.5), start in settling-mixing
// equilibrium as RBO24 eq. 50-52:
//   rho_i = F_i eps Sigma_g / (sqrt(2 pi) h_i) exp(-Z^2 / 2 h_i^2),
//   h_i = H sqrt(alpha / (alpha + St_i)),  St_i = pi rho_m a_i / (2 Sigma_g)
// (the Epstein mid-plane Stokes number), H = c_s / Omega_K at the mid-plane.
// The driver solves for the steady temperature at the first step (stellar
// ray tracing, eq. 45-46, and multi-band FLD, eq. 48-49), hands it to the
// gas (c_s, hydrostatic density, velocities) and the dust (stopping times).
// check.py asserts the energy balance, the super-heated surface layer and,
// given a second run at 1.5x the resolution, convergence.
#include <cmath>
#include <memory>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/loops.hpp"
#include "mote/disc/disc_simulation.hpp"
#include "mote/disc/gas_structure.hpp"
#include "mote/io/problem_main.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  disc::DiscSimulation::declare(s);
  s.table("passive", "Initial dust of disc_passive: MRN weights, settled (RBO24 eq. 50-52).");
  s.real("passive.dust_to_gas").default_value(0.01).greater_than(0.0).doc("Dust-to-gas ratio of the column.");
  s.rule(io::requires_table("disc_passive", "radiation"));
}

/// Mass fraction F_i of each species: a_i^1/2 normalised (MRN per logarithmic bin).
RealView1 mrn_fractions(const std::vector<double>& sizes) {
  RealView1 F("passive::mrn_fractions", sizes.size());
  auto F_h = Kokkos::create_mirror_view(F);
  double sum = 0.0;
  for (double a : sizes) sum += std::sqrt(a);
  for (size_t s = 0; s < sizes.size(); ++s) F_h(s) = std::sqrt(sizes[s]) / sum;
  Kokkos::deep_copy(F, F_h);
  return F;
}

struct SettledDust {
  Real eps, alpha, floor;
  Real stokes_factor;  // pi rho_m / 2 in code units: St = stokes_factor a / Sigma_g
};

/// The kernel of the settled initial dust (eq. 50-52), every cell with ghosts.
void fill_settled_dust(const mesh::Grid& grid, const disc::GasFields& gas, const View<Real****>& W, const RealView1& F,
                       const RealView1& sizes, SettledDust p) {
  const int j_mid = disc::midplane_index(grid);
  const auto Rc = grid.Rc;
  const auto Zc = grid.Zc;
  const auto Sigma = gas.Sigma;
  const auto cs2 = gas.cs2;
  const auto vR = gas.vR, vphi = gas.vphi, vZ = gas.vZ;
  const Real GM = gas.gravity.GM;
  par_for(
      "passive::settled_dust", 0, grid.nr_total(), 0, grid.nt_total(), 0, static_cast<int>(W.extent(2)),
      KOKKOS_LAMBDA(int i, int j, int s) {
        const Real omega = math::sqrt(GM / (Rc(i) * Rc(i) * Rc(i)));
        const Real H = math::sqrt(cs2(i, j_mid)) / omega;
        const Real St = p.stokes_factor * sizes(s) / Sigma(i);
        const Real h = H * math::sqrt(p.alpha / (p.alpha + St));
        const Real z = Zc(i, j) / h;
        // A grid on one side of the mid-plane holds half of the column, as the gas (eq. 37).
        const Real rho = F(s) * p.eps * Sigma(i) / (math::sqrt(2.0 * math::pi()) * h) * math::exp(-0.5 * z * z);
        W(i, j, s, disc::kRho) = math::max(rho, p.floor);
        W(i, j, s, disc::kVR) = vR(i, j);
        W(i, j, s, disc::kVphi) = vphi(i, j);
        W(i, j, s, disc::kVZ) = vZ(i, j);
      });
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto& u = ctx.units;
  std::vector<double> sizes = d.real_array("dust.sizes");  // cm
  const SettledDust p{d.real("passive.dust_to_gas"), d.real("gas.alpha"), d.real("dust.floor"),
                      0.5 * math::pi() * d.real("dust.rho_grain") / u.density()};
  auto initial = [sizes, p, u](const mesh::Grid& grid, const disc::GasFields& gas, const View<Real****>& W) {
    RealView1 sizes_code("passive::sizes", sizes.size());
    auto h = Kokkos::create_mirror_view(sizes_code);
    for (size_t s = 0; s < sizes.size(); ++s) h(s) = sizes[s] / u.length;
    Kokkos::deep_copy(sizes_code, h);
    fill_settled_dust(grid, gas, W, mrn_fractions(sizes), sizes_code, p);
  };
  return std::make_unique<disc::DiscSimulation>(d, ctx.comm, ctx.units, initial);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"disc_passive", "passive settled disc: temperature from ray tracing + multi-band FLD", declare, create});
}
