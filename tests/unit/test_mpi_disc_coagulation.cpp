// On 2 ranks (radial slabs): a coagulation call that fails in the cells of one
// rank only (coagulation.max_substeps = 1; the other rank's cells hold no dust
// above the floor, so they finish in their one sub-step) stops every rank with
// the same NumericalError, naming the cells failed on all ranks, instead of
// leaving the other rank waiting in the next collective.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "disc_driver_deck.hpp"
#include "mote/coagulation/coagulation.hpp"
#include "mote/core/comm.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/disc_coagulation.hpp"
#include "mote/disc/disc_simulation.hpp"

using namespace mote;

TEST(MpiDiscCoagulation, AFailureOnOneRankStopsEveryRank) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  const auto units = units::unit_system_by_name("au_msun");
  std::ostringstream list;  // 1-10 um, 7 bins per mass decade
  list.precision(17);
  for (int s = 0; s < 22; ++s) list << (s ? ", " : "") << 1e-4 * std::pow(10.0, s / 21.0);
  disc::DiscSimulation sim(test_decks::disc_driver_deck({"driver.evolve_gas=false", "dust.sizes=[" + list.str() + "]"}),
                           comm, units, disc::DiscSimulation::well_mixed(std::vector<double>(22, 0.01 / 22), 1e-40));
  if (comm.rank() == 1) Kokkos::deep_copy(sim.dust().Q, 0.0);  // nothing to grow in the outer slab
  coagulation::CoagulationSettings settings;
  settings.max_substeps = 1;
  disc::DiscCoagulation dc(sim.grid(), sim.dust(), settings, units);
  const int inner_cells = comm.rank() == 0 ? sim.grid().nr * sim.grid().nt : 0;
  const long long expected = comm.sum(static_cast<long long>(inner_cells));
  try {
    dc.update(sim.gas().fields(), 2.0 * M_PI * 300.0);
    ADD_FAILURE() << "rank " << comm.rank() << ": one sub-step for 300 yr of growth was accepted";
  } catch (const core::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("disc coagulation failed in " + std::to_string(expected) + " cells"),
              std::string::npos)
        << "rank " << comm.rank() << ": " << e.what();
  }
  EXPECT_EQ(comm.max(comm.rank()), 1);  // both ranks reach the next collective
}
