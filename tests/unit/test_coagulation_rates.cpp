// Smoluchowski right-hand side (RBO24 eq. 53-68): mass conservation pair by
// pair, single-pair rates against hand calculations, collision tables.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "mote/coagulation/coagulation.hpp"
#include "mote/core/units.hpp"

namespace coag = mote::coagulation;
using mote::Real;

namespace {

coag::GasCells disc_cells(int cells, Real sigma_gas) {
  namespace cgs = mote::units::cgs;
  coag::GasCells gas;
  gas.sound_speed = mote::RealView1("cs", cells);
  gas.density = mote::RealView1("rho", cells);
  gas.omega = mote::RealView1("omega", cells);
  gas.alpha = mote::RealView1("alpha", cells);
  gas.headwind = mote::RealView1("headwind", cells);
  auto cs = Kokkos::create_mirror_view(gas.sound_speed);
  auto rho = Kokkos::create_mirror_view(gas.density);
  auto om = Kokkos::create_mirror_view(gas.omega);
  auto al = Kokkos::create_mirror_view(gas.alpha);
  auto hw = Kokkos::create_mirror_view(gas.headwind);
  for (int c = 0; c < cells; ++c) {
    const Real R = (5.0 + 3.0 * c) * cgs::au, T = 150.0 * std::pow(R / cgs::au, -0.5);
    cs(c) = std::sqrt(cgs::k_B * T / (2.4 * cgs::m_H));
    om(c) = std::sqrt(cgs::G * cgs::M_sun / (R * R * R));
    rho(c) = sigma_gas * (1.0 + c);
    al(c) = 1e-3 * (1.0 + c);
    hw(c) = 0.05 * cs(c) * (c % 2);
  }
  Kokkos::deep_copy(gas.sound_speed, cs);
  Kokkos::deep_copy(gas.density, rho);
  Kokkos::deep_copy(gas.omega, om);
  Kokkos::deep_copy(gas.alpha, al);
  Kokkos::deep_copy(gas.headwind, hw);
  return gas;
}

}  // namespace

class CoagulationRatesSplit : public ::testing::TestWithParam<const char*> {};

TEST_P(CoagulationRatesSplit, PhysicalKernelConservesMassPairByPair) {
  coag::CoagulationSettings s;
  s.product_split = GetParam();
  s.species = 60;
  s.a_min = 1e-5;
  s.a_max = 10.0;
  s.vertically_integrated = true;
  s.v_frag = 100.0;
  s.cells_per_batch = 2;  // several batches
  const auto grid = coag::MassGrid::from_sizes(s.a_min, s.a_max, s.species, s.rho_m);
  const int cells = 5, n = grid.size();
  coag::Coagulation solver(grid, s, cells);
  const auto kernel = coag::make_kernel(s, grid, disc_cells(cells, 20.0));
  mote::RealView2 rho("rho", cells, n), dydt("dydt", cells, n);
  auto h = Kokkos::create_mirror_view(rho);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int c = 0; c < cells; ++c)
    for (int k = 0; k < n; ++k) h(c, k) = std::pow(u(gen), 3.0) * 1e-2 * (k == 7 ? 0.0 : 1.0);
  Kokkos::deep_copy(rho, h);
  solver.rates(rho, kernel, dydt);
  auto d = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dydt);
  for (int c = 0; c < cells; ++c) {
    double sum = 0, gross = 0;
    for (int k = 0; k < n; ++k) {
      sum += d(c, k);
      gross += std::fabs(d(c, k));
    }
    EXPECT_GT(gross, 0.0);
    EXPECT_LT(std::fabs(sum), 1e-13 * gross) << "cell " << c;
    std::printf("%s split, cell %d: sum of rates %.3e, sum of |rates| %.3e\n", GetParam(), c, sum, gross);
  }
}

INSTANTIATE_TEST_SUITE_P(Splits, CoagulationRatesSplit, ::testing::Values("two-bin", "quadratic"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param) == "two-bin" ? std::string("two_bin")
                                                                       : std::string(info.param);
                         });

TEST(CoagulationRates, TablesDeliverTheCollidingMass) {
  const auto grid = coag::MassGrid::from_masses(1.0, 1e6, 43);
  for (double chi : {0.5, 1.0, 3.0}) {
    const auto t = coag::build_collision_tables(grid, chi, 11.0 / 6.0);
    auto pi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.pair_i);
    auto pj = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.pair_j);
    std::vector<double> coag_mass(t.pairs, 0.0), frag_mass(t.pairs, 0.0);
    auto collect = [&](const coag::GatherList& g, std::vector<double>& out) {
      auto ptr = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.ptr);
      auto pair = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.pair);
      auto w = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.weight);
      for (int e = 0; e < ptr(ptr.extent(0) - 1); ++e) out[pair(e)] += w(e);
    };
    collect(t.coag, coag_mass);
    collect(t.remnant, frag_mass);
    collect(t.fragment, frag_mass);
    auto self = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.self_target);
    int self_pairs = 0;
    for (int p = 0; p < t.pairs; ++p) {
      // Entries landing in the larger grain's bin are net of the mass the pair removes from it.
      const double m = grid.mass(pi(p)) + grid.mass(pj(p));
      const double removed = pi(p) == pj(p) ? 2 * grid.mass(pi(p)) : grid.mass(pi(p));
      EXPECT_NEAR(coag_mass[p] + ((self(p) & 1) ? removed : 0.0), m, 1e-14 * m) << p;
      EXPECT_NEAR(frag_mass[p] + ((self(p) & 2) ? removed : 0.0), m, 1e-14 * m) << p;
      self_pairs += self(p) != 0;
    }
    EXPECT_GT(self_pairs, 0);
    auto share = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.fragment_share);
    for (int l = 0; l < grid.size(); ++l) {
      double sum = 0;
      for (int k = 0; k < grid.size(); ++k) {
        EXPECT_GE(share(l, k), 0.0);
        if (k > l) EXPECT_EQ(share(l, k), 0.0);
        sum += share(l, k);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
}

// RBO24 sec. 5: a fragmenting pair's fragments are spread up to the bin of
// its largest fragment, min(chi_im m_im, m_tar) (the first bin where that is
// below the grid); so no fragment lands in a bin
// whose lower edge is above the target's mass (two equal grains give
// fragments no heavier than either). Placing them by the total fragment mass
// m_i + m_j - m_rem instead put 6 to 68 % of an equal pair's fragments
// above its bin on this grid (7 bins per decade; 14 % mid-grid, most near
// its lowest bin, least at the top where the last bin caps them; computed
// from eq. 67 by hand).
TEST(CoagulationRates, FragmentsAreSpreadUpToTheLargestFragment) {
  const auto grid = coag::MassGrid::from_masses(1.0, 1e6, 43);
  const int n = grid.size();
  for (double chi : {0.5, 1.0, 3.0}) {
    const auto t = coag::build_collision_tables(grid, chi, 11.0 / 6.0);
    auto pi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.pair_i);
    auto pj = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.pair_j);
    auto ptr = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.fragment.ptr);
    auto pair = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.fragment.pair);
    auto share = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.fragment_share);
    std::vector<int> entries(t.pairs, 0);
    for (int l = 0; l < n; ++l)
      for (int e = ptr(l); e < ptr(l + 1); ++e) {
        const int p = pair(e);
        ++entries[p];
        const double m_tar = grid.mass(pi(p)), m_im = grid.mass(pj(p));
        const double largest = std::min(chi * m_im, m_tar);
        if (l > 0) EXPECT_LE(grid.edge(l), largest) << "pair " << pi(p) << ", " << pj(p) << " chi " << chi;
        if (l + 1 < n) EXPECT_GT(grid.edge(l + 1), largest) << "pair " << pi(p) << ", " << pj(p) << " chi " << chi;
        for (int k = 0; k < n; ++k)
          if (grid.edge(k) > m_tar) EXPECT_EQ(share(l, k), 0.0) << "bin " << k << " above the target " << pi(p);
      }
    for (int p = 0; p < t.pairs; ++p) EXPECT_EQ(entries[p], 1) << "pair " << p;
  }
}

TEST(CoagulationRates, QuadraticSplitDeliversNumberMassAndSecondMoment) {
  // Base (Kovetz & Olund) plus full correction (theta = 1) = quadratic Lagrange
  // weights: number 1, mass x and x^2 of every product and remnant; the
  // correction alone carries zero mass and zero number; only its third bin is negative.
  const auto grid = coag::MassGrid::from_masses(1.0, 1e6, 43);
  const int n = grid.size();
  const auto t = coag::build_collision_tables(grid, 0.5, 11.0 / 6.0, coag::ProductSplit::quadratic);
  ASSERT_TRUE(t.has_correction);
  auto pi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.pair_i);
  auto pj = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.pair_j);
  auto self = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.self_target);
  struct Moments {
    std::vector<double> number, mass, second, corr_number, corr_mass, corr_scale;
  };
  auto moments = [&](const coag::GatherList& base, const coag::GatherList& corr, int bit) {
    Moments mo{std::vector<double>(t.pairs, 0.0), std::vector<double>(t.pairs, 0.0), std::vector<double>(t.pairs, 0.0),
               std::vector<double>(t.pairs, 0.0), std::vector<double>(t.pairs, 0.0), std::vector<double>(t.pairs, 0.0)};
    auto add = [&](const coag::GatherList& g, bool correction) {
      auto ptr = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.ptr);
      auto pair = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.pair);
      auto w = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.weight);
      for (int k = 0; k < n; ++k)
        for (int e = ptr(k); e < ptr(k + 1); ++e) {
          const int p = pair(e);
          double wk = w(e);
          if (!correction && (self(p) & bit) && k == pi(p)) wk += pi(p) == pj(p) ? 2 * grid.mass(k) : grid.mass(k);
          const double num = wk / grid.mass(k);
          mo.number[p] += num;
          mo.mass[p] += wk;
          mo.second[p] += num * grid.mass(k) * grid.mass(k);
          if (correction) {
            mo.corr_number[p] += num;
            mo.corr_mass[p] += wk;
            mo.corr_scale[p] += std::fabs(wk);
            const int lim = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.limiter)(e);
            if (wk < 0) EXPECT_EQ(std::abs(k - lim / 2), 1) << "only the third bin, next to the limiter's bin, loses";
          }
        }
    };
    add(base, false);
    add(corr, true);
    return mo;
  };
  const auto co = moments(t.coag, t.coag_correction, 1);
  const auto re = moments(t.remnant, t.remnant_correction, 2);
  int corrected = 0;
  for (int p = 0; p < t.pairs; ++p) {
    const double mi = grid.mass(pi(p)), mj = grid.mass(pj(p));
    const double x = mi + mj, r = coag::remnant_mass(mi, mj, 0.5);
    if (x < grid.mass(n - 1)) {
      EXPECT_NEAR(co.number[p], 1.0, 1e-12) << p;
      EXPECT_NEAR(co.mass[p], x, 1e-13 * x) << p;
      EXPECT_NEAR(co.second[p], x * x, 1e-11 * x * x) << p;
    }
    if (r > grid.mass(0)) {
      EXPECT_NEAR(re.number[p], 1.0, 1e-12) << p;
      EXPECT_NEAR(re.mass[p], r, 1e-13 * r) << p;
      EXPECT_NEAR(re.second[p], r * r, 1e-11 * r * r) << p;
    }
    for (const auto* mo : {&co, &re}) {
      EXPECT_LE(std::fabs(mo->corr_mass[p]), 1e-15 * mo->corr_scale[p]) << p;
      EXPECT_LE(std::fabs(mo->corr_number[p] * x), 1e-13 * mo->corr_scale[p]) << p;
      corrected += mo->corr_scale[p] > 0;
    }
  }
  EXPECT_GT(corrected, t.pairs);
}

TEST(CoagulationRates, QuadraticSplitKeepsEmptyBinsNonNegative) {
  // Populated bins 10..14 only: every empty bin gains or stays (the limiter
  // switches the negative share off where the third bin is empty), and the
  // rates conserve mass.
  const auto grid = coag::MassGrid::from_masses(1.0, 1e4, 29);
  coag::CoagulationSettings s;
  s.kernel = "constant";
  s.product_split = "quadratic";
  coag::Coagulation solver(grid, s, 1);
  mote::RealView2 rho("rho", 1, grid.size()), dydt("dydt", 1, grid.size());
  auto h = Kokkos::create_mirror_view(rho);
  for (int k = 10; k < 15; ++k) h(0, k) = grid.mass(k) * (1.0 + 0.3 * (k % 3));
  Kokkos::deep_copy(rho, h);
  solver.rates(rho, coag::make_kernel(s, grid), dydt);
  auto d = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dydt);
  double sum = 0, gross = 0;
  int gaining = 0;
  for (int k = 0; k < grid.size(); ++k) {
    sum += d(0, k);
    gross += std::fabs(d(0, k));
    if (h(0, k) == 0) EXPECT_GE(d(0, k), 0.0) << "bin " << k;
    gaining += h(0, k) == 0 && d(0, k) > 0;
  }
  EXPECT_EQ(gaining, 3);  // products of bins 10-14 (up to 2 m_14) reach bins 15-17
  EXPECT_LT(std::fabs(sum), 1e-14 * gross);
}

TEST(CoagulationRates, ConstantKernelSinglePair) {
  // Only bin k populated: loss m_k n_k^2 K (eq. 54 with K_kk halved in the gain),
  // gain of 2 m_k n_k^2 K / 2 split between the centres around 2 m_k (eq. 63,
  // the two-bin split; the default quadratic split is tested above).
  const auto grid = coag::MassGrid::from_masses(1.0, 1e3, 31);  // ratio 10^0.1
  coag::CoagulationSettings s;
  s.product_split = "two-bin";
  s.kernel = "constant";
  s.kernel_coefficient = 2.0;
  coag::Coagulation solver(grid, s, 1);
  mote::RealView2 rho("rho", 1, grid.size()), dydt("dydt", 1, grid.size());
  const int k = 10;
  Kokkos::deep_copy(Kokkos::subview(rho, 0, k), 3.0 * grid.mass(k));  // n_k = 3
  solver.rates(rho, coag::make_kernel(s, grid), dydt);
  auto d = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dydt);
  const double loss = grid.mass(k) * 9.0 * 2.0;
  EXPECT_NEAR(d(0, k), -loss, 1e-12 * loss);
  // 2 m_k lies between centres k+3 (x 1.995) and k+4 (x 2.512).
  const double m = 2 * grid.mass(k), ml = grid.mass(k + 3), mu = grid.mass(k + 4);
  const double eps = (mu - m) / (mu - ml);
  EXPECT_NEAR(d(0, k + 3), eps * loss, 1e-12 * loss);
  EXPECT_NEAR(d(0, k + 4), (1 - eps) * loss, 1e-12 * loss);
}

namespace {

/// Rates of the physical kernel on 5 cells with `team_size` threads per cell's team.
std::vector<double> physical_rates(int team_size) {
  coag::CoagulationSettings s;
  s.species = 60;
  s.a_min = 1e-5;
  s.a_max = 10.0;
  s.vertically_integrated = true;
  s.team_size = team_size;
  const auto grid = coag::MassGrid::from_sizes(s.a_min, s.a_max, s.species, s.rho_m);
  const int cells = 5, n = grid.size();
  coag::Coagulation solver(grid, s, cells);
  mote::RealView2 rho("rho", cells, n), dydt("dydt", cells, n);
  auto h = Kokkos::create_mirror_view(rho);
  for (int c = 0; c < cells; ++c)
    for (int k = 0; k < n; ++k) h(c, k) = 1e-2 * std::exp(-0.1 * k) * (1.0 + c);
  Kokkos::deep_copy(rho, h);
  solver.rates(rho, coag::make_kernel(s, grid, disc_cells(cells, 20.0)), dydt);
  auto d = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dydt);
  std::vector<double> out;
  for (int c = 0; c < cells; ++c)
    for (int k = 0; k < n; ++k) out.push_back(d(c, k));
  return out;
}

}  // namespace

TEST(CoagulationTeams, TeamSizeDoesNotChangeTheRates) {
  // Each target bin gathers its pairs in a fixed order whatever the team size:
  // the rates are the same bits for every size the back-end runs.
  const bool host = Kokkos::SpaceAccessibility<Kokkos::HostSpace, mote::ExecSpace::memory_space>::accessible;
  const std::vector<int> sizes =
      host ? std::vector<int>{1, mote::ExecSpace().concurrency()} : std::vector<int>{32, 64, 128, 256};
  const auto reference = physical_rates(0);
  for (int size : sizes) {
    const auto rates = physical_rates(size);
    ASSERT_EQ(rates.size(), reference.size());
    int differ = 0;
    for (std::size_t i = 0; i < rates.size(); ++i) differ += rates[i] != reference[i];
    EXPECT_EQ(differ, 0) << "team size " << size;
  }
}

TEST(CoagulationTeams, LimitsOfTheBackEndAreRefusedAtSetUp) {
  const bool host = Kokkos::SpaceAccessibility<Kokkos::HostSpace, mote::ExecSpace::memory_space>::accessible;
  coag::CoagulationSettings s;
  s.kernel = "constant";
  if (host) {
    // A host team has at most as many threads as the back-end.
    s.team_size = mote::ExecSpace().concurrency() + 1;
    const auto grid = coag::MassGrid::from_masses(1.0, 1e3, 31);
    EXPECT_THROW(coag::Coagulation(grid, s, 1), std::invalid_argument);
  } else {
    // A GPU team's scratch lives in shared memory: 600 species (52.8 KB) do not fit.
    const auto grid = coag::MassGrid::from_masses(1.0, 1e30, 600);
    try {
      coag::Coagulation solver(grid, s, 1);
      ADD_FAILURE() << "600 species were accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("team scratch"), std::string::npos) << e.what();
    }
  }
}
