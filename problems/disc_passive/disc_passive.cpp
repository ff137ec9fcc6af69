// disc_passive: the temperature of a passive, settled dusty disc from the
// coupled temperature solver (RBO24 sec. 4 and 6; VALIDATION D5: the CI-sized
// disc_passive.toml and the Pinte et al. 2009 benchmark of RBO24 sec. 4.3 in
// pinte_*.toml). The gas is a static alpha disc (GasDisc); the dust species,
// MRN-weighted (mass per logarithmic size interval proportional to a^1/2,
// i.e. n(a) ~ a^-3.5), start in settling-mixing equilibrium as RBO24 eq. 50-52:
//   rho_i = F_i eps Sigma_g / (sqrt(2 pi) h_i) exp(-Z^2 / 2 h_i^2)
// (as cell averages over Z),
//   h_i = H sqrt(alpha / (alpha + St_i)),
// H = c_s / Omega_K at the mid-plane, with St_i either the Epstein mid-plane
// value pi rho_m a_i / (2 Sigma_g) or RBO24's St_i = 0.05 a_i (R / au).
// The driver solves for the steady temperature at the first step (stellar
// ray tracing, eq. 45-46, and multi-band FLD, eq. 48-49), hands it to the
// gas (c_s, hydrostatic density, velocities) and the dust (stopping times).
// check.py asserts the energy balance, the super-heated surface layer, the
// optically thin surface limit, the dust mass and, given a second run at
// 1.5x the resolution, convergence.
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
  s.string("passive.stokes")
      .default_value(std::string("epstein"))
      .one_of({"epstein", "linear"})
      .doc(
          "Stokes numbers of eq. 52: the Epstein mid-plane value pi rho_grain a / (2 Sigma_g), or "
          "stokes_coefficient (a / cm) (R / au) (RBO24 sec. 4.3).");
  s.real("passive.stokes_coefficient")
      .default_value(0.05)
      .greater_than(0.0)
      .doc("St = stokes_coefficient (a / cm) (R / au) for stokes = \"linear\".");
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

/// Stokes numbers St(i, s) of eq. 52 in every column: Epstein at the mid-plane.
RealView2 epstein_stokes(const mesh::Grid& grid, const disc::GasFields& gas, const RealView1& sizes, Real factor) {
  RealView2 St("passive::stokes", grid.nr_total(), sizes.extent(0));
  const auto Sigma = gas.Sigma;
  par_for(
      "passive::epstein_stokes", 0, grid.nr_total(), 0, static_cast<int>(sizes.extent(0)),
      KOKKOS_LAMBDA(int i, int s) { St(i, s) = factor * sizes(s) / Sigma(i); });
  return St;
}

/// Stokes numbers St(i, s) = coefficient (a / cm) (R / au), RBO24 sec. 4.3.
RealView2 linear_stokes(const mesh::Grid& grid, const RealView1& sizes_cm, Real coefficient, Real au_in_code) {
  RealView2 St("passive::stokes", grid.nr_total(), sizes_cm.extent(0));
  const auto Rc = grid.Rc;
  par_for(
      "passive::linear_stokes", 0, grid.nr_total(), 0, static_cast<int>(sizes_cm.extent(0)),
      KOKKOS_LAMBDA(int i, int s) { St(i, s) = coefficient * sizes_cm(s) * Rc(i) / au_in_code; });
  return St;
}

struct SettledDust {
  Real eps, alpha, floor;
};

/// erf(b) - erf(a) for a <= b, from the tail (erfc) where both lie on one
/// side of zero, so that cells high above the mid-plane keep their density.
KOKKOS_INLINE_FUNCTION Real erf_difference(Real a, Real b) {
  if (a >= 0.0) return math::erfc(a) - math::erfc(b);
  if (b <= 0.0) return math::erfc(-b) - math::erfc(-a);
  return math::erf(b) - math::erf(a);
}

/// The kernel of the settled initial dust (eq. 50-52), every cell with ghosts:
/// the Gaussian of eq. 50 averaged over the cell's height Z = R tan(theta) at
/// its centre R, so that each column holds its share of Sigma however thin
/// the settled layer is against the cells.
void fill_settled_dust(const mesh::Grid& grid, const disc::GasFields& gas, const View<Real****>& W, const RealView1& F,
                       const RealView2& St, SettledDust p) {
  const int j_mid = disc::midplane_index(grid);
  const auto Rc = grid.Rc;
  const auto tan_te = grid.tan_te;
  const auto Sigma = gas.Sigma;
  const auto cs2 = gas.cs2;
  const auto vR = gas.vR, vphi = gas.vphi, vZ = gas.vZ;
  const Real GM = gas.gravity.GM;
  par_for(
      "passive::settled_dust", 0, grid.nr_total(), 0, grid.nt_total(), 0, static_cast<int>(W.extent(2)),
      KOKKOS_LAMBDA(int i, int j, int s) {
        const Real omega = math::sqrt(GM / (Rc(i) * Rc(i) * Rc(i)));
        const Real H = math::sqrt(cs2(i, j_mid)) / omega;
        const Real h = H * math::sqrt(p.alpha / (p.alpha + St(i, s)));
        const Real Z0 = Rc(i) * tan_te(j), Z1 = Rc(i) * tan_te(j + 1);
        const Real scale = math::sqrt(2.0) * h;
        // A grid on one side of the mid-plane holds half of the column, as the gas (eq. 37).
        const Real rho = F(s) * p.eps * Sigma(i) * erf_difference(Z0 / scale, Z1 / scale) / (2.0 * (Z1 - Z0));
        W(i, j, s, disc::kRho) = math::max(rho, p.floor);
        W(i, j, s, disc::kVR) = vR(i, j);
        W(i, j, s, disc::kVphi) = vphi(i, j);
        W(i, j, s, disc::kVZ) = vZ(i, j);
      });
}

/// `v` / `unit` on the device.
RealView1 to_device(const std::string& name, const std::vector<double>& v, double unit) {
  RealView1 d(name, v.size());
  auto h = Kokkos::create_mirror_view(d);
  for (size_t s = 0; s < v.size(); ++s) h(s) = v[s] / unit;
  Kokkos::deep_copy(d, h);
  return d;
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto& u = ctx.units;
  const std::vector<double> sizes = disc::grain_sizes_cm(d);  // cm, as dust.sizes or dust.sizes_from gives them
  const SettledDust p{d.real("passive.dust_to_gas"), d.real("gas.alpha"), d.real("dust.floor")};
  const bool linear = d.string("passive.stokes") == "linear";
  const Real coefficient = d.real("passive.stokes_coefficient");
  const Real epstein_factor = 0.5 * math::pi() * d.real("dust.rho_grain") / u.density();
  auto initial = [=](const mesh::Grid& grid, const disc::GasFields& gas, const View<Real****>& W) {
    const RealView2 St =
        linear ? linear_stokes(grid, to_device("passive::sizes_cm", sizes, 1.0), coefficient, units::cgs::au / u.length)
               : epstein_stokes(grid, gas, to_device("passive::sizes", sizes, u.length), epstein_factor);
    fill_settled_dust(grid, gas, W, mrn_fractions(sizes), St, p);
  };
  return std::make_unique<disc::DiscSimulation>(d, ctx.comm, ctx.units, initial);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"disc_passive", "passive settled disc: temperature from ray tracing + multi-band FLD", declare, create});
}
