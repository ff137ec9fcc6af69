// The physical collision kernel with volume densities (RBO24 eq. 56-60, 62,
// not vertically integrated) against an evaluation written out here:
// Epstein Stokes numbers, k_B T from the temperature, the turbulent Reynolds
// number from the mean free path, Brownian (eq. 58), turbulent (eq. 59-60;
// the Ormel & Cuzzi closed forms themselves are tested in
// test_coagulation_physics.cpp), laminar drift and settling or dynamics
// velocities (eq. 57), cross-section (eq. 56) and p_frag (eq. 62); and its
// consistency with the vertically integrated kernel (RBO24 sec. 5.1) for equal
// grains at the mid-plane density rho_0 = Sigma / (sqrt(2 pi) H).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "mote/coagulation/coagulation.hpp"
#include "mote/core/units.hpp"

namespace coag = mote::coagulation;
namespace cgs = mote::units::cgs;
using mote::Real;

namespace {

constexpr double kMu = 2.4, kRhoM = 1.6, kVfrag = 100.0;

struct Cell {
  double T, R, rho_g, alpha, headwind, z;
  double cs() const { return std::sqrt(cgs::k_B * T / (kMu * cgs::m_H)); }
  double omega() const { return std::sqrt(cgs::G * cgs::M_sun / (R * R * R)); }
};

/// Two cells (the second is the one tested, so cell indexing is exercised).
coag::GasCells gas_cells(const Cell& other, const Cell& cell, bool with_height) {
  coag::GasCells gas;
  gas.sound_speed = mote::RealView1("cs", 2);
  gas.density = mote::RealView1("rho", 2);
  gas.omega = mote::RealView1("omega", 2);
  gas.alpha = mote::RealView1("alpha", 2);
  gas.headwind = mote::RealView1("headwind", 2);
  if (with_height) gas.height = mote::RealView1("z", 2);
  auto cs = Kokkos::create_mirror_view(gas.sound_speed);
  auto rho = Kokkos::create_mirror_view(gas.density);
  auto om = Kokkos::create_mirror_view(gas.omega);
  auto al = Kokkos::create_mirror_view(gas.alpha);
  auto hw = Kokkos::create_mirror_view(gas.headwind);
  auto z = Kokkos::create_mirror_view(gas.height);
  const Cell cells[2] = {other, cell};
  for (int c = 0; c < 2; ++c) {
    cs(c) = cells[c].cs();
    rho(c) = cells[c].rho_g;
    om(c) = cells[c].omega();
    al(c) = cells[c].alpha;
    hw(c) = cells[c].headwind;
    if (with_height) z(c) = cells[c].z;
  }
  Kokkos::deep_copy(gas.sound_speed, cs);
  Kokkos::deep_copy(gas.density, rho);
  Kokkos::deep_copy(gas.omega, om);
  Kokkos::deep_copy(gas.alpha, al);
  Kokkos::deep_copy(gas.headwind, hw);
  if (with_height) Kokkos::deep_copy(gas.height, z);
  return gas;
}

coag::PhysicalKernel physical_kernel(const coag::MassGrid& grid, const coag::GasCells& gas, bool integrated) {
  coag::CoagulationSettings s;
  s.mu = kMu;
  s.v_frag = kVfrag;
  s.vertically_integrated = integrated;
  return std::get<coag::PhysicalKernel>(coag::make_kernel(s, grid, gas));
}

/// K and p_frag of the pairs in cell c, evaluated on the device.
std::vector<coag::PairRate> evaluate(const coag::PhysicalKernel& kernel, int c,
                                     const std::vector<std::pair<int, int>>& pairs) {
  const int np = static_cast<int>(pairs.size());
  mote::IntView1 pi("pi", np), pj("pj", np);
  mote::RealView1 K("K", np), pf("pf", np);
  auto hi = Kokkos::create_mirror_view(pi);
  auto hj = Kokkos::create_mirror_view(pj);
  for (int p = 0; p < np; ++p) {
    hi(p) = pairs[p].first;
    hj(p) = pairs[p].second;
  }
  Kokkos::deep_copy(pi, hi);
  Kokkos::deep_copy(pj, hj);
  Kokkos::parallel_for(
      "test::physical_kernel", Kokkos::RangePolicy<mote::ExecSpace>(0, np), KOKKOS_LAMBDA(int p) {
        const coag::PairRate r = kernel(c, pi(p), pj(p));
        K(p) = r.K;
        pf(p) = r.p_frag;
      });
  auto hK = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), K);
  auto hf = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pf);
  std::vector<coag::PairRate> out(np);
  for (int p = 0; p < np; ++p) out[p] = {hK(p), hf(p)};
  return out;
}

/// Hand evaluation of eq. 56-62 for grains a, b (volume densities); `dv_lam2`
/// < 0: drift and settling estimates, else the given laminar dv^2.
coag::PairRate by_hand(const Cell& cell, double a, double b, double dv_lam2 = -1) {
  const double cs = cell.cs(), om = cell.omega(), H = cs / om;
  const double ma = 4.0 / 3.0 * M_PI * kRhoM * a * a * a, mb = 4.0 / 3.0 * M_PI * kRhoM * b * b * b;
  const double v_th = std::sqrt(8.0 / M_PI) * cs;
  const double st_a = kRhoM * a / (cell.rho_g * v_th) * om, st_b = kRhoM * b / (cell.rho_g * v_th) * om;
  const double dv_bm2 = 8.0 * cgs::k_B * cell.T * (ma + mb) / (M_PI * ma * mb);
  const double mfp = kMu * cgs::m_H / (cell.rho_g * 2e-15);
  const double re = cell.alpha * cs * H / (0.5 * v_th * mfp);
  const double dv_turb2 = cell.alpha * cs * cs * coag::turbulent_vrel2(st_a, st_b, 1.0 / std::sqrt(re));
  if (dv_lam2 < 0) {
    const double hw = cell.headwind;
    const double dvr = -2 * hw * (st_a / (1 + st_a * st_a) - st_b / (1 + st_b * st_b));
    const double dvphi = -hw * (1 / (1 + st_a * st_a) - 1 / (1 + st_b * st_b));
    const double dvz = om * cell.z * (std::min(st_a, 0.5) - std::min(st_b, 0.5));
    dv_lam2 = dvr * dvr + dvphi * dvphi + dvz * dvz;
  }
  const double dv = std::sqrt(dv_bm2 + dv_turb2 + dv_lam2);
  const double x = 1.5 * (kVfrag / dv) * (kVfrag / dv);
  return {M_PI * (a + b) * (a + b) * dv, (x + 1) * std::exp(-x)};
}

const Cell kOther{300.0, 1.0 * cgs::au, 1e-9, 1e-2, 0.0, 0.0};
const Cell kCell{100.0, 5.0 * cgs::au, 1e-11, 1e-3, 3e3, 2e12};
const std::vector<std::pair<int, int>> kPairs = {{40, 10}, {10, 40}, {5, 2}, {50, 49}, {30, 30}, {50, 0}};

}  // namespace

TEST(CoagulationPhysicalKernel, VolumeKernelMatchesHandEvaluation) {
  const auto grid = coag::MassGrid::from_sizes(1e-5, 1.0, 51, kRhoM);  // a_k = 1e-5 10^(k/10) cm
  const auto kernel = physical_kernel(grid, gas_cells(kOther, kCell, true), false);
  const auto got = evaluate(kernel, 1, kPairs);
  int fragmenting = 0;
  for (size_t p = 0; p < kPairs.size(); ++p) {
    const auto [i, j] = kPairs[p];
    const auto want = by_hand(kCell, grid.grain_size(i), grid.grain_size(j));
    EXPECT_NEAR(got[p].K, want.K, 1e-12 * want.K) << i << " " << j;
    EXPECT_NEAR(got[p].p_frag, want.p_frag, 1e-12) << i << " " << j;
    fragmenting += want.p_frag > 1e-3 && want.p_frag < 0.999;
    std::printf("a = %.3e, %.3e cm: K = %.6e cm^3/s (hand %.6e), p_frag = %.6f\n", grid.grain_size(i),
                grid.grain_size(j), got[p].K, want.K, got[p].p_frag);
  }
  EXPECT_GE(fragmenting, 1);  // the cell is chosen so that eq. 62 is tested away from 0 and 1
  EXPECT_EQ(got[0].K, got[1].K);
}

// K_ij = K_ji bit for bit for every pair of the grid, in both the volume and the
// vertically integrated forms (the drift and settling estimates included).
TEST(CoagulationPhysicalKernel, KernelIsSymmetricBitForBit) {
  const auto grid = coag::MassGrid::from_sizes(1e-5, 1.0, 51, kRhoM);
  std::vector<std::pair<int, int>> pairs, swapped;
  for (int i = 0; i < grid.size(); ++i)
    for (int j = 0; j < i; ++j) {
      pairs.emplace_back(i, j);
      swapped.emplace_back(j, i);
    }
  for (const bool integrated : {false, true}) {
    const auto kernel = physical_kernel(grid, gas_cells(kOther, kCell, true), integrated);
    const auto ij = evaluate(kernel, 1, pairs), ji = evaluate(kernel, 1, swapped);
    int asymmetric = 0;
    for (size_t p = 0; p < pairs.size(); ++p) asymmetric += ij[p].K != ji[p].K || ij[p].p_frag != ji[p].p_frag;
    EXPECT_EQ(asymmetric, 0) << "of " << pairs.size() << " pairs (vertically integrated: " << integrated << ")";
  }
}

TEST(CoagulationPhysicalKernel, VolumeKernelUsesDynamicsVelocities) {
  const auto grid = coag::MassGrid::from_sizes(1e-5, 1.0, 51, kRhoM);
  auto gas = gas_cells(kOther, kCell, true);
  gas.dust_velocity = mote::RealView3("v_dust", 2, grid.size(), 3);
  auto v = Kokkos::create_mirror_view(gas.dust_velocity);
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < grid.size(); ++k)
      for (int d = 0; d < 3; ++d) v(c, k, d) = (c + 1) * std::sin(0.7 * k + 2.1 * d) * 40.0;
  Kokkos::deep_copy(gas.dust_velocity, v);
  const auto got = evaluate(physical_kernel(grid, gas, false), 1, kPairs);
  for (size_t p = 0; p < kPairs.size(); ++p) {
    const auto [i, j] = kPairs[p];
    double lam2 = 0;
    for (int d = 0; d < 3; ++d) lam2 += std::pow(v(1, i, d) - v(1, j, d), 2);
    const auto want = by_hand(kCell, grid.grain_size(i), grid.grain_size(j), lam2);
    EXPECT_NEAR(got[p].K, want.K, 1e-12 * want.K) << i << " " << j;
    EXPECT_NEAR(got[p].p_frag, want.p_frag, 1e-12) << i << " " << j;
  }
}

TEST(CoagulationPhysicalKernel, EqualGrainsMatchTheVerticallyIntegratedKernel) {
  // Equal grains have no drift or settling difference, so the integrated kernel
  // with Sigma_g is the volume kernel at rho_0 = Sigma_g / (sqrt(2 pi) H)
  // divided by sqrt(2 pi (2 h^2)), h = H / sqrt(1 + St/alpha), St = pi rho_m a / (2 Sigma_g).
  const auto grid = coag::MassGrid::from_sizes(1e-5, 10.0, 61, kRhoM);
  const double sigma = 20.0, H = kCell.cs() / kCell.omega();
  Cell mid = kCell;
  mid.rho_g = sigma / (std::sqrt(2 * M_PI) * H);
  Cell surface = kCell;
  surface.rho_g = sigma;
  const auto vol = physical_kernel(grid, gas_cells(kOther, mid, true), false);
  const auto integ = physical_kernel(grid, gas_cells(kOther, surface, false), true);
  std::vector<std::pair<int, int>> equal;
  for (int k = 0; k < grid.size(); k += 3) equal.push_back({k, k});
  const auto kv = evaluate(vol, 1, equal), ki = evaluate(integ, 1, equal);
  for (size_t p = 0; p < equal.size(); ++p) {
    const double a = grid.grain_size(equal[p].first), st = 0.5 * M_PI * kRhoM * a / sigma;
    const double h = H / std::sqrt(1 + st / kCell.alpha);
    EXPECT_NEAR(ki[p].K * std::sqrt(4 * M_PI) * h, kv[p].K, 1e-12 * kv[p].K) << "a = " << a;
    EXPECT_NEAR(ki[p].p_frag, kv[p].p_frag, 1e-12) << "a = " << a;
  }
}
