// The gas quantities that the C2/C3 references (problems/disc_settling/check.py)
// read from snapshots, against values worked out here by hand in cgs from the
// deck: the vertically isothermal sound speed c_s^2 = k_B T / (mu m_H) with
// T = T_ref (R / R_ref)^-q, the alpha viscosity nu = alpha c_s^2 / Omega_K
// (RBO24 sec. 3.4) and the Epstein stopping time t_s = rho_m s / (rho_g
// sqrt(8 / pi) c_s) (RBO24 eq. 14), converted to the au_msun code units (1 au,
// 1 M_sun, G = 1: time unit sqrt(au^3 / G M_sun)). The constants are typed in
// here (CODATA 2018, IAU 2015), not taken from mote's units, so the references
// do not rest on the code's own numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/disc_simulation.hpp"

namespace {

using namespace mote;

constexpr double kG = 6.67430e-8;            // cm^3 g^-1 s^-2
constexpr double kBoltzmann = 1.380649e-16;  // erg K^-1
constexpr double kHydrogen = 1.6735575e-24;  // g
constexpr double kAu = 1.495978707e13;       // cm
constexpr double kGMsun = 1.32712440041e26;  // cm^3 s^-2

const char* kDeck = R"(
[grid]
nr = 8
R_in = 8.0
R_out = 12.0
r_spacing = "log"
ntheta = 8
theta_min = -0.1
theta_max = 0.1
[boundaries]
inner = "closed"
outer = "closed"
lower = "closed"
upper = "closed"
[gas]
R_ref = 10.0
T_ref = 88.5
T_index = 0.5
mu = 2.34
alpha = 1e-2
Sigma0 = 5e-6
[dust]
sizes = [1e-3, 1e-1]
rho_grain = 1.6
)";

template <class V>
auto host(const V& v) {
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
}

}  // namespace

TEST(DiscReferenceValues, SoundSpeedViscosityAndEpsteinStoppingTimeByHand) {
  core::DeckSchema schema;
  disc::DiscSimulation::declare(schema);
  const auto deck = core::Deck::parse(kDeck, "test_disc_reference_values", schema, {});
  const disc::DiscSimulation sim(deck, core::Comm::world(), units::unit_system_by_name("au_msun"),
                                 disc::DiscSimulation::well_mixed({0.01, 0.01}, 1e-40));
  const auto& grid = sim.grid();
  const auto Rc = host(grid.Rc);
  const auto cs2 = host(sim.gas().fields().cs2);
  const auto nu = host(sim.gas().fields().nu);
  const auto rho = host(sim.gas().fields().rho);
  const auto ts = host(sim.dust().stopping_times());

  const double length = kAu, time = std::sqrt(kAu * kAu * kAu / kGMsun), mass = kGMsun / kG;
  const double velocity = length / time;
  const double sizes[2] = {1e-3, 1e-1};
  for (int i = grid.i_begin(); i < grid.i_end(); ++i) {
    const int j = grid.j_begin() + grid.nt / 2;  // just above the mid-plane
    const double R_cm = Rc(i) * kAu;
    const double T = 88.5 * std::pow(Rc(i) / 10.0, -0.5);
    const double cs2_cgs = kBoltzmann * T / (2.34 * kHydrogen);
    const double omega = std::sqrt(kGMsun / (R_cm * R_cm * R_cm));
    const double nu_cgs = 1e-2 * cs2_cgs / omega;
    EXPECT_NEAR(cs2(i, j) * velocity * velocity / cs2_cgs, 1.0, 1e-7) << "R = " << Rc(i);
    EXPECT_NEAR(nu(i, j) * length * length / time / nu_cgs, 1.0, 1e-7) << "R = " << Rc(i);
    const double rho_cgs = rho(i, j) * mass / (length * length * length);
    for (int s = 0; s < 2; ++s) {
      const double ts_cgs = 1.6 * sizes[s] / (rho_cgs * std::sqrt(8.0 / M_PI) * std::sqrt(cs2_cgs));
      EXPECT_NEAR(ts(i, j, s) * time / ts_cgs, 1.0, 1e-7) << "R = " << Rc(i) << ", species " << s;
    }
  }
}
