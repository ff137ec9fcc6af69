// Checkpoint and snapshot of SPH with one-fluid dust through the run-loop
// adapter (sph/sph_simulation.hpp): a run interrupted after 10 steps and
// continued from its checkpoint is bit-identical to 20 uninterrupted steps
// (three dust species, dustywave of PL15 sec. 4.1), and snapshots carry the
// dust fractions per species. A checkpoint of one dust variable (eps_j or
// S_j, stored as sqrt(eps_j)) does not load into a run of the other.
#include <gtest/gtest.h>

#include <filesystem>

#include "mote/io/snapshot.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_simulation.hpp"
#include "sph_dust_problems.hpp"

using namespace mote;
using namespace mote::sph;
using mote::sph::testing::DustyWaveSetup;
using mote::sph::testing::make_dustywave;

namespace {

std::unique_ptr<SphSimulation> make_simulation(DustVariable var = DustVariable::Epsilon) {
  DustyWaveSetup w;
  w.var = var;
  w.nspecies = 3;
  w.n = 64;
  return std::make_unique<SphSimulation>(std::make_unique<SphSystem>(make_dustywave(w)), units::UnitSystem{});
}

void advance(SphSimulation& sim, int steps) {
  for (int k = 0; k < steps; ++k) sim.advance(0.0, sim.max_dt());
}

std::vector<double> host(const RealView2& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  std::vector<double> out;
  for (size_t i = 0; i < h.extent(0); ++i)
    for (size_t j = 0; j < h.extent(1); ++j) out.push_back(h(i, j));
  return out;
}

// 20 steps in one go and 10 + 10 through a checkpoint: identical bits, for both
// dust variables (the S variable's projection reference and the mass totals
// travel with the checkpoint).
/// A new simulation of `var` continued from `sim`'s checkpoint, written to `path`.
std::unique_ptr<SphSimulation> restarted_from(const SphSimulation& sim, DustVariable var, const std::string& path) {
  const auto comm = core::Comm::world();
  {
    io::H5File f(path, io::H5File::Mode::Create, comm);
    f.create_group("/state");
    sim.save_state(f);
  }
  auto resumed = make_simulation(var);
  io::H5File f(path, io::H5File::Mode::Read, comm);
  resumed->load_state(f);
  return resumed;
}

void expect_bit_identical_restart(DustVariable var, const std::string& path) {
  auto full = make_simulation(var);
  advance(*full, 20);

  auto first = make_simulation(var);
  advance(*first, 10);
  auto resumed = restarted_from(*first, var, path);
  advance(*resumed, 10);

  EXPECT_EQ(resumed->system().time(), full->system().time());
  EXPECT_EQ(host(resumed->system().module<OneFluidDust>()->var), host(full->system().module<OneFluidDust>()->var));
  EXPECT_EQ(host(resumed->system().particles().x), host(full->system().particles().x));
  EXPECT_EQ(host(resumed->system().particles().v), host(full->system().particles().v));
  const auto d1 = resumed->system().diagnostics(), d0 = full->system().diagnostics();
  EXPECT_EQ(d1.dust_mass, d0.dust_mass);
  EXPECT_EQ(d1.dust_floored, d0.dust_floored);
  EXPECT_EQ(d1.dust_projected, d0.dust_projected);
  // Non-zero (round-off on this short wave), so the equality checks that it was restored.
  if (var == DustVariable::SqrtRhoEps) EXPECT_NE(d0.dust_projected, 0.0);
}

}  // namespace

TEST(SphDustCheckpoint, RestartIsBitIdentical) {
  const auto dir = std::filesystem::temp_directory_path() / "mote_sph_dust_checkpoint";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "checkpoint.h5").string();
  const auto comm = core::Comm::world();
  expect_bit_identical_restart(DustVariable::SqrtRhoEps, path);
  expect_bit_identical_restart(DustVariable::Epsilon, path);
  auto full = make_simulation();
  advance(*full, 20);

  // The snapshot holds the three dust fractions per particle.
  const std::string snap = (dir / "snapshot.h5").string();
  {
    io::H5File f(snap, io::H5File::Mode::Create, comm);
    io::SnapshotWriter w(f);
    full->write_snapshot(w);
  }
  io::H5File f(snap, io::H5File::Mode::Read, comm);
  EXPECT_EQ(f.dims("/particles/dust_fraction"), (std::vector<hsize_t>{64, 3}));
  std::vector<double> eps(64 * 3);
  f.read("/particles/dust_fraction", io::Block::whole({64, 3}), eps.data());
  EXPECT_NEAR(eps[0] + eps[1] + eps[2], 0.5, 1e-3);  // eps0 = 0.5 split over three bins
}

TEST(SphDustCheckpoint, OtherDustVariableIsRefused) {
  const auto dir = std::filesystem::temp_directory_path() / "mote_sph_dust_checkpoint";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "checkpoint_s.h5").string();
  const auto comm = core::Comm::world();
  {
    auto sim = make_simulation(DustVariable::SqrtRhoEps);
    io::H5File f(path, io::H5File::Mode::Create, comm);
    f.create_group("/state");
    sim->save_state(f);
  }
  io::H5File f(path, io::H5File::Mode::Read, comm);
  EXPECT_EQ(f.read_attribute_string("/state/dust_var", "stored"), "sqrt(eps_j)");
  make_simulation(DustVariable::SqrtRhoEps)->load_state(f);
  try {
    make_simulation(DustVariable::Epsilon)->load_state(f);
    FAIL() << "an S checkpoint loaded into an eps run";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("dust.variable"), std::string::npos) << e.what();
  }
}

namespace {

template <class View>
std::vector<double> flat(const View& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

// A snapshot written right after a restart, before any step (the one a failed write left out), is the one
// the interrupted run would have written: density, pressure, the reconstructed gas velocity and the dust
// drift velocities come with the checkpoint (before, the restart showed the set-up's values in the fresh
// system's order).
TEST(SphDustCheckpoint, SnapshotRightAfterARestartIsTheRunsOwn) {
  const auto dir = std::filesystem::temp_directory_path() / "mote_sph_dust_checkpoint";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "checkpoint_snapshot.h5").string();
  for (const auto var : {DustVariable::Epsilon, DustVariable::SqrtRhoEps}) {
    auto first = make_simulation(var);
    advance(*first, 10);
    const auto resumed = restarted_from(*first, var, path);
    const auto a = first->system().snapshot(), b = resumed->system().snapshot();
    EXPECT_EQ(flat(a.rho), flat(b.rho));
    EXPECT_EQ(flat(a.P), flat(b.P));
    const auto* da = first->system().module<OneFluidDust>();
    const auto* db = resumed->system().module<OneFluidDust>();
    const auto sa = da->snapshot(first->system().particles()), sb = db->snapshot(resumed->system().particles());
    EXPECT_EQ(flat(sa.eps), flat(sb.eps));
    EXPECT_EQ(flat(sa.v_gas), flat(sb.v_gas));
    EXPECT_EQ(flat(sa.dv), flat(sb.dv));
  }
}
