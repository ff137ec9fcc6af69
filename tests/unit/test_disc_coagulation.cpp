// Coagulation as a disc sub-solver (RBO24 sec. 5-6; disc_coagulation.hpp):
// mass conserved in every cell through a call, every cell identical to the
// standalone solver fed with that cell's gas and dust state, species velocities
// kept, the adaptive driver schedule, the gas's mean molecular weight, and
// deck errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "mote/coagulation/coagulation.hpp"
#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/disc_coagulation.hpp"
#include "mote/disc/disc_simulation.hpp"
#include "reduction_counter.hpp"

namespace {

using namespace mote;
using test_tools::ReductionCounter;
namespace coag = mote::coagulation;

constexpr int kSpecies = 22;  // 1 to 10 micron: 7 bins per mass decade

std::string deck_text() {
  std::ostringstream sizes;
  sizes.precision(17);
  for (int s = 0; s < kSpecies; ++s) sizes << (s ? ", " : "") << 1e-4 * std::pow(10.0, s / 21.0);
  return R"(
[grid]
nr = 3
R_in = 8.0
R_out = 12.0
r_spacing = "log"
ntheta = 4
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
alpha = 1e-2
Sigma0 = 5e-4
inner_boundary = "closed"
outer_boundary = "closed"
[dust]
rho_grain = 1.6
sizes = [)" +
         sizes.str() + "]\n";
}

const core::DeckSchema& schema() {
  static const core::DeckSchema s = [] {
    core::DeckSchema d;
    disc::DiscSimulation::declare(d);
    return d;
  }();
  return s;
}

struct Fixture {
  units::UnitSystem units = units::unit_system_by_name("au_msun");
  disc::DiscSimulation sim;
  coag::CoagulationSettings settings;

  explicit Fixture(std::string text = deck_text())
      : sim(core::Deck::parse(text, "test_disc_coagulation", schema(), {}), core::Comm::world(), units,
            disc::DiscSimulation::well_mixed(std::vector<double>(kSpecies, 0.01 / kSpecies), 1e-40)) {
    settings.product_split = "quadratic";
    double t = 0;
    for (int n = 0; n < 5; ++n) {  // species velocities differ after a few dust steps
      const double dt = sim.max_dt();
      sim.advance(t, dt);
      t += dt;
    }
  }
  /// Host copy of the dust state (a copy also where Q is in host memory).
  auto Q() const {
    auto h = Kokkos::create_mirror(Kokkos::HostSpace(), sim.dust().Q);
    Kokkos::deep_copy(h, sim.dust().Q);
    return h;
  }
};

const double kElapsed = 2.0 * M_PI * 300.0;  // 300 yr in au_msun time units (yr / 2 pi)

}  // namespace

TEST(DiscCoagulation, ConservesMassPerCellAndKeepsSpeciesVelocities) {
  Fixture f;
  disc::DiscCoagulation dc(f.sim.grid(), f.sim.dust(), f.settings, f.units);
  const auto before = f.Q();
  const auto stats = dc.update(f.sim.gas().fields(), kElapsed);
  const auto after = f.Q();
  const auto& g = f.sim.grid();
  double max_change = 0;
  for (int i = g.i_begin(); i < g.i_end(); ++i)
    for (int j = g.j_begin(); j < g.j_end(); ++j) {
      double m0 = 0, m1 = 0;
      for (int s = 0; s < kSpecies; ++s) {
        m0 += before(i, j, s, disc::kRho);
        m1 += after(i, j, s, disc::kRho);
        max_change = std::max(max_change, std::fabs(after(i, j, s, disc::kRho) / before(i, j, s, disc::kRho) - 1));
        for (int k : {disc::kMomR, disc::kAngMom, disc::kMomZ}) {
          const double v0 = before(i, j, s, k) / before(i, j, s, disc::kRho),
                       v1 = after(i, j, s, k) / after(i, j, s, disc::kRho);
          EXPECT_NEAR(v1, v0, 1e-13 * std::fabs(v0) + 1e-300) << i << " " << j << " " << s << " " << k;
        }
      }
      EXPECT_NEAR(m1 / m0 - 1, 0.0, 1e-12) << "cell " << i << " " << j;
    }
  EXPECT_GT(max_change, 0.05);  // the call changes the size distribution
  EXPECT_GT(dc.next_interval(), 0.0);
  EXPECT_EQ(stats.failed_cells, 0);
  std::printf(
      "disc coagulation: %lld sub-steps, largest relative change of a species density %.3f, next interval %.3e\n",
      stats.substeps, max_change, dc.next_interval());
}

// A call's totals (sub-steps, rejections, failed cells, the smallest proposed
// sub-step that schedules the next call) come from one reduction, and agree
// with the solver's per-cell arrays.
TEST(DiscCoagulation, CallTotalsInOneReduction) {
  Fixture f;
  disc::DiscCoagulation dc(f.sim.grid(), f.sim.dust(), f.settings, f.units);
  coag::CallStatistics stats;
  int reductions = 0;
  {
    ReductionCounter counter;
    stats = dc.update(f.sim.gas().fields(), kElapsed);
    reductions = counter.reductions();
  }
  EXPECT_EQ(reductions, 1);
  const auto steps = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dc.solver().substeps());
  const auto rejected = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dc.solver().rejections());
  const auto next = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dc.solver().next_substep());
  long long sum_steps = 0, sum_rejected = 0;
  double smallest = std::numeric_limits<double>::max();
  for (size_t c = 0; c < steps.extent(0); ++c) {
    sum_steps += steps(c);
    sum_rejected += rejected(c);
    if (next(c) > 0) smallest = std::min(smallest, next(c));
  }
  EXPECT_GT(sum_steps, static_cast<long long>(steps.extent(0)));  // more than one sub-step per cell
  EXPECT_EQ(stats.substeps, sum_steps);
  EXPECT_EQ(stats.rejections, sum_rejected);
  EXPECT_EQ(stats.failed_cells, 0);
  EXPECT_EQ(stats.min_next_substep, smallest);
  EXPECT_EQ(dc.next_interval(), smallest / f.units.time);
}

TEST(DiscCoagulation, EveryCellEqualsTheStandaloneSolver) {
  Fixture f;
  const auto& g = f.sim.grid();
  const auto& gas = f.sim.gas().fields();
  const auto before = f.Q();
  auto W = Kokkos::create_mirror(Kokkos::HostSpace(), f.sim.dust().W);
  Kokkos::deep_copy(W, f.sim.dust().W);
  const auto rho = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), gas.rho);
  const auto cs2 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), gas.cs2);
  const auto nu = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), gas.nu);
  const auto Rc = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.Rc);
  disc::DiscCoagulation dc(g, f.sim.dust(), f.settings, f.units);
  dc.update(gas, kElapsed);
  const auto after = f.Q();
  const double floor = f.sim.dust().settings().floor, ud = f.units.density(), uv = f.units.velocity();
  for (int i : {g.i_begin(), g.i_end() - 1})
    for (int j : {g.j_begin(), g.j_begin() + 1}) {
      // One standalone cell in cgs, built here from the disc state.
      coag::GasCells one;
      one.sound_speed = RealView1("cs", 1);
      one.density = RealView1("rho", 1);
      one.omega = RealView1("omega", 1);
      one.alpha = RealView1("alpha", 1);
      one.dust_velocity = View<Real***>("v", 1, kSpecies, 3);
      const double om = std::sqrt(gas.gravity.GM / std::pow(Rc(i), 3));
      Kokkos::deep_copy(one.sound_speed, std::sqrt(cs2(i, j)) * uv);
      Kokkos::deep_copy(one.density, rho(i, j) * ud);
      Kokkos::deep_copy(one.omega, om / f.units.time);
      Kokkos::deep_copy(one.alpha, nu(i, j) * om / cs2(i, j));
      auto v = Kokkos::create_mirror_view(one.dust_velocity);
      RealView2 y("y", 1, kSpecies);
      auto yh = Kokkos::create_mirror_view(y);
      for (int s = 0; s < kSpecies; ++s) {
        v(0, s, 0) = W(i, j, s, disc::kVR) * uv;
        v(0, s, 1) = W(i, j, s, disc::kVZ) * uv;
        v(0, s, 2) = W(i, j, s, disc::kVphi) * uv;
        yh(0, s) = std::max(before(i, j, s, disc::kRho) - floor, 0.0) * ud;
      }
      Kokkos::deep_copy(one.dust_velocity, v);
      Kokkos::deep_copy(y, yh);
      std::vector<double> y0(yh.data(), yh.data() + kSpecies);
      coag::Coagulation solo(dc.mass_grid(), f.settings, 1);
      solo.integrate(y, kElapsed * f.units.time, coag::make_kernel(f.settings, dc.mass_grid(), one));
      Kokkos::deep_copy(yh, y);
      double total = 0;
      for (int s = 0; s < kSpecies; ++s) total += before(i, j, s, disc::kRho);
      for (int s = 0; s < kSpecies; ++s) {
        const double want = before(i, j, s, disc::kRho) + (yh(0, s) - y0[s]) / ud;
        EXPECT_NEAR(after(i, j, s, disc::kRho), want, 1e-12 * total) << "cell " << i << " " << j << ", species " << s;
      }
    }
}

TEST(DiscCoagulation, AdaptiveDriverSchedule) {
  Fixture f;
  disc::DiscCoagulation dc(f.sim.grid(), f.sim.dust(), f.settings, f.units);
  f.sim.driver().add({"coagulation", disc::Schedule::adaptive(),
                      [&](double, double elapsed) { dc.update(f.sim.gas().fields(), elapsed); },
                      [&] { return dc.next_interval(); }});
  double total0 = 0;
  for (int s = 0; s < kSpecies; ++s) total0 += f.sim.dust().mass(s);
  double t = 0;
  for (int n = 0; n < 20; ++n) {
    const double dt = f.sim.max_dt();
    f.sim.advance(t, dt);
    t += dt;
  }
  double total = 0;
  for (int s = 0; s < kSpecies; ++s) total += f.sim.dust().mass(s);
  const int k = static_cast<int>(f.sim.driver().sub_solvers().size()) - 1;
  EXPECT_GE(f.sim.driver().calls(k), 1);
  // Coagulation conserves the total; the floor's additions are accounted in the budget.
  const auto budget = f.sim.dust().mass_budget();
  std::printf("coagulation schedule: floor added %.3e, outflow %.3e of the dust mass\n", budget.floor_added / total0,
              budget.outflow / total0);
  EXPECT_NEAR((total - budget.floor_added + budget.outflow) / total0 - 1, 0.0, 1e-12);
  EXPECT_GE(f.sim.min_dust_density(), f.sim.dust().settings().floor);
}

TEST(DiscCoagulation, CheckpointRestoresTheProposedSubsteps) {
  Fixture f;
  disc::DiscCoagulation dc(f.sim.grid(), f.sim.dust(), f.settings, f.units);
  dc.update(f.sim.gas().fields(), kElapsed);
  const std::string path = ::testing::TempDir() + "disc_coagulation_state.h5";
  {
    io::H5File file(path, io::H5File::Mode::Create, core::Comm::world());
    dc.save_state(file);
  }
  disc::DiscCoagulation restored(f.sim.grid(), f.sim.dust(), f.settings, f.units);
  EXPECT_EQ(restored.next_interval(), 0.0);
  restored.load_state(io::H5File(path, io::H5File::Mode::Read, core::Comm::world()));
  EXPECT_EQ(restored.next_interval(), dc.next_interval());
  auto a = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dc.solver().next_substep());
  auto b = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), restored.solver().next_substep());
  ASSERT_EQ(a.extent(0), b.extent(0));
  for (size_t c = 0; c < a.extent(0); ++c) EXPECT_EQ(a(c), b(c));
  std::remove(path.c_str());
}

// A cell that runs out of coagulation.max_substeps stops the run with a numerical
// error naming the number of cells (exit code 3 in a problem), not a silent
// half-integrated span.
TEST(DiscCoagulation, ExhaustedSubstepsAreANumericalError) {
  Fixture f;
  f.settings.max_substeps = 1;
  disc::DiscCoagulation dc(f.sim.grid(), f.sim.dust(), f.settings, f.units);
  try {
    dc.update(f.sim.gas().fields(), kElapsed);
    ADD_FAILURE() << "one sub-step for 300 yr of growth was accepted";
  } catch (const core::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("disc coagulation failed in 12 cells"), std::string::npos) << e.what();
  }
}

TEST(DiscCoagulation, DeckErrors) {
  std::string text = deck_text();
  text.replace(text.find("sizes = ["), 9, "sizes = [0.9e-4, ");  // not logarithmically spaced
  EXPECT_THROW(
      {
        disc::DiscSimulation sim(core::Deck::parse(text, "bad", schema(), {}), core::Comm::world(),
                                 units::unit_system_by_name("au_msun"),
                                 disc::DiscSimulation::well_mixed(std::vector<double>(kSpecies + 1, 1e-4), 1e-40));
        disc::DiscCoagulation dc(sim.grid(), sim.dust(), {}, units::unit_system_by_name("au_msun"));
      },
      core::DeckError);
  Fixture f;
  coag::CoagulationSettings s;
  s.vertically_integrated = true;
  EXPECT_THROW(disc::DiscCoagulation(f.sim.grid(), f.sim.dust(), s, f.units), core::DeckError);
  // An absolute tolerance of the cell's whole dust density would accept any sub-step.
  try {
    core::Deck::parse(deck_text() + "[coagulation]\nabs_tol = 1.0\n", "abs_tol", schema(), {});
    ADD_FAILURE() << "coagulation.abs_tol = 1 accepted";
  } catch (const core::DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("coagulation.abs_tol"), std::string::npos) << e.what();
  }
}

// On the disc the collisions' k_B T = mu m_H c_s^2 takes gas.mu, the mean
// molecular weight of the gas's c_s^2 = k_B T / (mu m_H) (with the two keys'
// defaults, 2.34 and 2.4, it took 2.4: T 2.6 % high); a coagulation.mu given
// in the deck must equal gas.mu.
TEST(DiscCoagulation, TakesTheGasMeanMolecularWeight) {
  const auto units = units::unit_system_by_name("au_msun");
  auto make = [&](const std::string& coagulation_table, const std::vector<std::string>& overrides) {
    return std::make_unique<disc::DiscSimulation>(
        core::Deck::parse(deck_text() + "[coagulation]\nkernel = \"physical\"\n" + coagulation_table, "mu", schema(),
                          overrides),
        core::Comm::world(), units,
        disc::DiscSimulation::well_mixed(std::vector<double>(kSpecies, 0.01 / kSpecies), 1e-40));
  };
  ASSERT_NE(make("", {})->coagulation(), nullptr);
  EXPECT_EQ(make("", {})->coagulation()->settings().mu, 2.34);
  EXPECT_EQ(make("", {"gas.mu=2.4"})->coagulation()->settings().mu, 2.4);
  EXPECT_EQ(make("mu = 2.4\n", {"gas.mu=2.4"})->coagulation()->settings().mu, 2.4);
  try {
    make("mu = 2.4\n", {});
    ADD_FAILURE() << "coagulation.mu = 2.4 with gas.mu = 2.34 accepted";
  } catch (const core::DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("coagulation.mu"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("gas.mu"), std::string::npos) << e.what();
  }
}

// driver.coagulation_max_interval (cuDisc's 50 yr cap) becomes the coagulation schedule's longest wait
// (DiscDriver.SchedulesCallSubSolversWhenDue holds what the cap does).
TEST(DiscCoagulation, MaxIntervalReachesItsSchedule) {
  auto make = [](const std::vector<std::string>& overrides) {
    return std::make_unique<disc::DiscSimulation>(
        core::Deck::parse(deck_text() + "[coagulation]\nkernel = \"physical\"\n", "cap", schema(), overrides),
        core::Comm::world(), units::unit_system_by_name("au_msun"),
        disc::DiscSimulation::well_mixed(std::vector<double>(kSpecies, 0.01 / kSpecies), 1e-40));
  };
  const auto schedule = [](disc::DiscSimulation& sim) { return sim.driver().sub_solvers().back().schedule; };
  EXPECT_EQ(schedule(*make({"driver.coagulation_max_interval=3.0"})).interval, 3.0);
  EXPECT_EQ(schedule(*make({})).interval, 0.0);
  EXPECT_EQ(schedule(*make({})).kind, disc::Schedule::Kind::Adaptive);
}
