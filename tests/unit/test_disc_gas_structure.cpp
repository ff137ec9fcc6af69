// Gas structure of the disc (RBO24 sec. 3.3-3.5): the hydrostatic scan of
// eq. 33-37 against the exact vertically isothermal column (VALIDATION C4),
// Sigma recovered from the 2D density, positivity of the scan where the
// density underflows, exactness of the trapezoidal <1/cs^2> (eq. 35) for a
// column whose 1/cs^2 is linear in 1/r, and the velocities of eq. 27-31
// against the thin-disc limits (Keplerian rotation with pressure support,
// mid-plane v_R of Takeuchi & Lin 2002, eq. 11).
#include <gtest/gtest.h>

#include <cmath>

#include "mote/disc/gas_disc.hpp"
#include "mote/mesh/grid.hpp"

using namespace mote;

namespace {

const units::UnitSystem kUnits = units::unit_system_by_name("au_msun");

mesh::GridSpec disc_spec(int nr, int nt, double t0, double t1) {
  mesh::GridSpec s;
  s.nr = nr;
  s.ntheta = nt;
  s.r_edges = mesh::log_edges(1.0, 10.0, nr);
  s.theta_edges = mesh::linear_edges(t0, t1, nt);
  return s;
}

disc::GasConfig config(double h_ref) {
  disc::GasConfig c;
  c.GM = 1.0;
  c.R_ref = 1.0;
  c.T_index = 0.5;
  c.viscosity = disc::ViscosityModel::Alpha;
  c.alpha = 1e-2;
  c.Sigma0 = 1e-4;
  c.Sigma_index = 1.0;
  c.derive(kUnits, h_ref);
  return c;
}

template <class V>
auto host(const V& v) {
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
}

/// max |rho / rho_ref - 1| over active cells with rho_ref > 1e-10 rho_ref(mid), and max |Sigma_back / Sigma - 1|.
std::pair<double, double> hydrostatic_errors(const mesh::Grid& g, const disc::GasDisc& gas) {
  const auto& F = gas.fields();
  auto rho = host(F.rho), cs2 = host(F.cs2), V = host(g.V);
  auto Sigma = host(F.Sigma);
  const int jm = gas.midplane_index();
  double worst = 0, worst_sigma = 0;
  for (int i = g.i_begin(); i < g.i_end(); ++i) {
    const double R = g.Rc_h(i), RdR = 0.5 * (g.Re_h(i + 1) * g.Re_h(i + 1) - g.Re_h(i) * g.Re_h(i));
    std::vector<double> w(g.nt_total());
    double norm = 0, column = 0;
    for (int j = g.j_begin(); j < g.j_end(); ++j) {
      const double r = R / std::cos(g.tc_h(j));
      w[j] = std::exp(F.gravity.GM / cs2(i, j) * (1.0 / r - 1.0 / R));
      norm += w[j] * V(i, j);
      column += rho(i, j) * V(i, j);
    }
    const double scale = F.column_fraction * Sigma(i) * RdR / norm;
    for (int j = g.j_begin(); j < g.j_end(); ++j)
      if (w[j] > 1e-10 * w[jm]) worst = std::max(worst, std::fabs(rho(i, j) / (scale * w[j]) - 1.0));
    worst_sigma = std::max(worst_sigma, std::fabs(column / (F.column_fraction * RdR) / Sigma(i) - 1.0));
  }
  return {worst, worst_sigma};
}

}  // namespace

TEST(DiscGasStructure, IsothermalColumnHalfDisc) {
  const mesh::Grid g(disc_spec(32, 120, 0.0, 0.5), core::Comm::world());
  const disc::GasDisc gas(config(0.05), g, kUnits);
  EXPECT_DOUBLE_EQ(gas.fields().column_fraction, 0.5);
  const auto [rho_err, sigma_err] = hydrostatic_errors(g, gas);
  EXPECT_LT(rho_err, 1e-6);
  EXPECT_LT(sigma_err, 1e-12);
}

TEST(DiscGasStructure, IsothermalColumnFullDisc) {
  const mesh::Grid g(disc_spec(24, 101, -0.4, 0.4), core::Comm::world());
  const disc::GasDisc gas(config(0.05), g, kUnits);
  EXPECT_DOUBLE_EQ(gas.fields().column_fraction, 1.0);
  const auto [rho_err, sigma_err] = hydrostatic_errors(g, gas);
  EXPECT_LT(rho_err, 1e-6);
  EXPECT_LT(sigma_err, 1e-12);
  // Mirror symmetry about the mid-plane.
  auto rho = host(gas.fields().rho);
  const int jm = gas.midplane_index();
  for (int k = 1; k < 40; ++k) EXPECT_NEAR(rho(10, jm + k) / rho(10, jm - k), 1.0, 1e-12);
}

TEST(DiscGasStructure, ThinDiscGravityGivesGaussianColumns) {
  // star.potential = "thin_disc": Phi = -GM/R + GM Z^2 / 2R^3, so an isothermal
  // column is exp(-Z^2 / 2H^2) with H^2 = cs^2 R^3 / GM, which the scan
  // (eq. 34-35) reproduces to round-off (Takeuchi & Lin 2002 gas).
  const mesh::Grid g(disc_spec(8, 150, 0.0, 0.3), core::Comm::world());
  auto cfg = config(0.05);
  cfg.thin_disc_gravity = true;
  const disc::GasDisc gas(cfg, g, kUnits);
  auto rho = host(gas.fields().rho), cs2 = host(gas.fields().cs2), Zc = host(g.Zc);
  const int jm = gas.midplane_index();
  double worst = 0;
  for (int i = g.i_begin(); i < g.i_end(); ++i) {
    const double R = g.Rc_h(i), H2 = cs2(i, jm) * R * R * R;
    for (int j = g.j_begin(); j < g.j_end(); ++j) {
      const double ref = std::exp(-(Zc(i, j) * Zc(i, j) - Zc(i, jm) * Zc(i, jm)) / (2 * H2));
      if (ref > 1e-10) worst = std::max(worst, std::fabs(rho(i, j) / (rho(i, jm) * ref) - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-11);
}

TEST(DiscGasStructure, PositiveWhereTheColumnUnderflows) {
  // h = 0.003: exp(-Z^2 / 2H^2) underflows far below the top of the grid.
  const mesh::Grid g(disc_spec(16, 64, 0.0, 0.6), core::Comm::world());
  auto cfg = config(0.003);
  cfg.rho_floor = 1e-150;
  const disc::GasDisc gas(cfg, g, kUnits);
  auto rho = host(gas.fields().rho), vR = host(gas.fields().vR), vphi = host(gas.fields().vphi);
  for (int i = 0; i < g.nr_total(); ++i)
    for (int j = 0; j < g.nt_total(); ++j) {
      ASSERT_TRUE(std::isfinite(rho(i, j)) && rho(i, j) >= 1e-150) << i << " " << j;
      ASSERT_TRUE(std::isfinite(vR(i, j)) && std::isfinite(vphi(i, j))) << i << " " << j;
    }
  const auto [rho_err, sigma_err] = hydrostatic_errors(g, gas);
  EXPECT_LT(rho_err, 1e-6);
  EXPECT_LT(sigma_err, 1e-12);
}

TEST(DiscGasStructure, TrapezoidalScanExactForLinearInverseSoundSpeed) {
  // 1/cs^2 = A + B u with u = 1/r along each column: eq. 33 integrates to
  // ln P = GM (A u + B u^2 / 2) + const, which the trapezoidal mean of eq. 35 reproduces exactly.
  const mesh::Grid g(disc_spec(12, 80, 0.0, 0.4), core::Comm::world());
  disc::GasDisc gas(config(0.05), g, kUnits);
  const double A = 1.0 / gas.config().cs2_ref, B = -0.3 * A;  // temperature rising with height
  auto T = Kokkos::create_mirror_view(gas.fields().T);
  for (int i = 0; i < g.nr_total(); ++i)
    for (int j = 0; j < g.nt_total(); ++j) {
      const double u = std::cos(g.tc_h(j)) / g.Rc_h(i);
      T(i, j) = gas.config().cs2_to_T / (A + B * u);
    }
  RealView2 Td("T", g.nr_total(), g.nt_total());
  Kokkos::deep_copy(Td, T);
  gas.set_temperature(Td);
  gas.update_structure();
  auto rho = host(gas.fields().rho), V = host(g.V);
  auto Sigma = host(gas.fields().Sigma);
  double worst = 0;
  for (int i = g.i_begin(); i < g.i_end(); ++i) {
    std::vector<double> ref(g.nt_total());
    double norm = 0;
    for (int j = g.j_begin(); j < g.j_end(); ++j) {
      const double u = std::cos(g.tc_h(j)) / g.Rc_h(i), u0 = 1.0 / g.Rc_h(i);
      const double cs2 = 1.0 / (A + B * u);
      ref[j] = std::exp(A * (u - u0) + 0.5 * B * (u * u - u0 * u0)) / cs2;  // GM = 1
      norm += ref[j] * V(i, j);
    }
    const double RdR = 0.5 * (g.Re_h(i + 1) * g.Re_h(i + 1) - g.Re_h(i) * g.Re_h(i));
    for (int j = g.j_begin(); j < g.j_end(); ++j)
      if (ref[j] > 1e-10 * ref[g.j_begin()])
        worst = std::max(worst, std::fabs(rho(i, j) / (0.5 * Sigma(i) * RdR * ref[j] / norm) - 1.0));
  }
  EXPECT_LT(worst, 1e-10);
}

TEST(DiscGasStructure, ThinDiscVelocities) {
  // Sigma ~ R^-1, cs^2 ~ R^-1/2 (nu ~ R): rho_mid ~ R^p with p = -9/4 (thin disc), q' = -1/2.
  // Mid-plane: v_phi^2 = v_K^2 [1 + h^2 (p + q')] and v_R = -(nu / R)(3p + 2q' + 6) = +7/4 nu / R
  // (Takeuchi & Lin 2002, eq. 7 and 11), to O(h^2) for h = 0.02.
  const mesh::Grid g(disc_spec(64, 120, 0.0, 0.15), core::Comm::world());
  const disc::GasDisc gas(config(0.02), g, kUnits);
  const auto& F = gas.fields();
  auto vphi = host(F.vphi), vR = host(F.vR), vZ = host(F.vZ), nu = host(F.nu), cs2 = host(F.cs2);
  const int jm = gas.midplane_index();
  for (int i = g.i_begin(); i < g.i_end(); i += 7) {
    const double R = g.Rc_h(i), vK2 = 1.0 / R, h2 = cs2(i, jm) * R;
    EXPECT_NEAR((vphi(i, jm) * vphi(i, jm) / vK2 - 1.0) / h2, -2.25 - 0.5, 0.02) << "R = " << R;
    EXPECT_NEAR(vR(i, jm) / (nu(i, jm) / R), 1.75, 0.02) << "R = " << R;
    EXPECT_EQ(vZ(i, jm), 0.0);
  }
}
