// On 2 ranks (radial slabs): DustDynamics::step_limit() names the same
// constraint, species and cell on every rank, wherever the binding cell lies,
// and its step is max_dt(). One species in one cell is given a radial velocity
// whose CFL step (RBO24 eq. 18) is a thousandth of the present one, first in a
// cell of the inner slab, then of the outer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "disc_driver_deck.hpp"
#include "mote/core/comm.hpp"
#include "mote/core/log.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/disc_simulation.hpp"

using namespace mote;

TEST(MpiDiscStepLimit, EveryRankNamesTheBindingCellOfEitherSlab) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  const auto units = units::unit_system_by_name("au_msun");
  const std::vector<double> global_Re = [] {
    std::vector<double> e(13);
    for (int k = 0; k <= 12; ++k) e[k] = 8.0 * std::pow(12.0 / 8.0, k / 12.0);
    return e;
  }();
  for (const int ig : {2, 9}) {
    disc::DiscSimulation sim(test_decks::disc_driver_deck({"driver.evolve_gas=false"}), comm, units,
                             disc::DiscSimulation::well_mixed({0.01, 0.01, 0.01}, 1e-40));
    const auto& g = sim.grid();
    const double dt0 = sim.max_dt();
    const int j = 5, s = 2;
    const double vR = 0.4 * (global_Re[ig + 1] - global_Re[ig]) / (1e-3 * dt0);
    const int i = ig - g.i_offset + g.ng;
    if (ig >= g.i_offset && ig < g.i_offset + g.nr) {
      auto W = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), sim.dust().W);
      W(i, j + g.ng, s, disc::kVR) = vR;
      Kokkos::deep_copy(sim.dust().W, W);
    }
    const auto limit = sim.dust().step_limit();
    EXPECT_EQ(limit.kind, disc::DustDynamics::StepLimit::kAdvectionR) << "cell " << ig;
    EXPECT_EQ(limit.species, s);
    EXPECT_EQ(limit.i, ig);
    EXPECT_EQ(limit.j, j);
    EXPECT_EQ(limit.dt, sim.max_dt());
    EXPECT_NEAR(limit.dt / (1e-3 * dt0), 1.0, 1e-9);
    EXPECT_NEAR(limit.R / std::sqrt(global_Re[ig] * global_Re[ig + 1]), 1.0, 0.01);
    EXPECT_NE(sim.dt_limit().find(logging::format("(cell %d, %d)", ig, j)), std::string::npos) << sim.dt_limit();
  }
}
