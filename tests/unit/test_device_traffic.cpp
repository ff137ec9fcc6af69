// No host-device traffic and no View allocation inside a time-step (DESIGN.md,
// Kokkos habits; issue 17): Kokkos Tools callbacks count every deep copy and
// every allocation while an engine takes N steps (max_dt + advance), after a
// few warm-up steps have sized the reusable buffers. A fill of a View with a
// scalar is a device kernel and is not counted. A copy of one value into a host
// scalar (a read-back, the same synchronisation as a reduction) is counted
// apart: a neighbour rebuild needs a few to size its lists, a step without one
// needs none. Bulk copies and allocations must be zero. Cases: SPH one-fluid
// dust with rebuilds on every step (dustyshock) and without (dustywave), the
// disc grid with dust, evolving gas and coagulation on the driver, and the
// disc with the temperature solver (whose BiCGStab reads its convergence
// measures back once per iteration). The
// callbacks fire in every backend, so Serial runs catch what a GPU would pay.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "disc_driver_deck.hpp"
#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/disc_simulation.hpp"
#include "mote/setups/dust_problems.hpp"
#include "mote/setups/dustybox.hpp"
#include "mote/sph/sph_simulation.hpp"

namespace {

using namespace mote;

/// Counts deep copies and allocations between construction and destruction
/// through the Kokkos Tools callbacks; keeps the first few labels for messages.
class TrafficCounter {
 public:
  TrafficCounter() {
    state() = State{};
    Kokkos::Tools::Experimental::set_begin_deep_copy_callback(&on_deep_copy);
    Kokkos::Tools::Experimental::set_allocate_data_callback(&on_allocate);
  }
  ~TrafficCounter() {
    Kokkos::Tools::Experimental::set_begin_deep_copy_callback(nullptr);
    Kokkos::Tools::Experimental::set_allocate_data_callback(nullptr);
  }
  TrafficCounter(const TrafficCounter&) = delete;
  TrafficCounter& operator=(const TrafficCounter&) = delete;

  struct Copy {
    std::string src, dst;
    std::uint64_t bytes;
  };
  int deep_copies() const { return state().copies; }
  const std::vector<Copy>& copy_list() const { return state().copy_list; }
  const std::map<std::string, int>& allocation_labels() const { return state().allocation_labels; }
  int scalar_reads() const { return state().scalar_reads; }
  int allocations() const { return state().allocations; }
  std::string report() const {
    std::ostringstream os;
    os << state().scalar_reads << " scalar read-backs; " << state().copies << " deep copies:";
    for (const auto& [label, count] : state().copy_labels) os << " [" << label << "] x " << count;
    os << "; " << state().allocations << " allocations:";
    for (const auto& [label, count] : state().allocation_labels) os << " [" << label << "] x " << count;
    os << "; " << state().empty_allocations << " of 0 bytes";
    return os.str();
  }

 private:
  struct State {
    int copies = 0, scalar_reads = 0, allocations = 0, empty_allocations = 0;
    std::map<std::string, int> copy_labels, allocation_labels;  // label -> count
    std::vector<Copy> copy_list;
  };
  static State& state() {
    static State s;
    return s;
  }
  static void keep(std::map<std::string, int>& labels, const std::string& label) { ++labels[label]; }
  static void on_deep_copy(Kokkos::Tools::SpaceHandle dst_space, const char* dst_name, const void*,
                           Kokkos::Tools::SpaceHandle src_space, const char* src_name, const void*,
                           std::uint64_t bytes) {
    if (std::string(src_name) == "Scalar") return;  // deep_copy(view, value): a fill kernel, no transfer
    if (std::string(dst_name) == "Scalar") {        // deep_copy(value, view): one value back to the host
      ++state().scalar_reads;
      return;
    }
    ++state().copies;
    state().copy_list.push_back({src_name, dst_name, bytes});
    keep(state().copy_labels, std::string(src_space.name) + ":" + src_name + " -> " + dst_space.name + ":" + dst_name +
                                  " (" + std::to_string(bytes) + " B)");
  }
  static void on_allocate(Kokkos::Tools::SpaceHandle space, const char* name, const void*, std::uint64_t bytes) {
    // Kokkos 4's CUDA team launches report their level-1 team scratch even when it is 0 bytes
    // ("Kokkos::CudaSpace::TeamScratchMemory": cudaMalloc of nothing, no memory): counted apart.
    if (bytes == 0) {
      ++state().empty_allocations;
      return;
    }
    ++state().allocations;
    keep(state().allocation_labels, std::string(space.name) + ":" + name);
  }
};

template <class Sim>
void take_steps(Sim& sim, int steps, double& t) {
  for (int k = 0; k < steps; ++k) {
    const double dt = sim.max_dt();
    sim.advance(t, dt);
    t += dt;
  }
}

/// PL15 sec. 4.2 dustyshock at a tenth of the resolution, three dust species:
/// particles move through the shock, so the neighbour list is rebuilt.
std::unique_ptr<sph::SphSimulation> dusty_shock() {
  sph::SphConfig cfg;
  cfg.kernel = sph::KernelType::M4;
  cfg.gamma = 5.0 / 3.0;
  sph::DustSettings ds;
  ds.nspecies = 3;
  ds.drag = sph::DragLaw::ConstantK;
  ds.k_drag = {1000.0 / 3};
  ds.eps = {0.5 / 3};
  sph::DustyShock shock;
  shock.dx_left = 0.01;
  return std::make_unique<sph::SphSimulation>(sph::dustyshock(shock, cfg, ds).make_system(), units::UnitSystem{});
}

std::unique_ptr<disc::DiscSimulation> coupled_disc(int species) {
  std::ostringstream sizes;
  sizes.precision(17);
  sizes << "dust.sizes=[";
  // 1 to 10 um: 7 bins per mass decade for 22 species (RBO24 sec. 5).
  for (int k = 0; k < species; ++k) sizes << (k ? ", " : "") << 1e-4 * std::pow(10.0, double(k) / (species - 1));
  sizes << "]";
  const auto deck =
      test_decks::disc_driver_deck({"grid.ntheta=16", sizes.str()}, "[coagulation]\nkernel = \"physical\"\n");
  return std::make_unique<disc::DiscSimulation>(
      deck, core::Comm::world(), units::unit_system_by_name("au_msun"),
      disc::DiscSimulation::well_mixed(std::vector<double>(species, 1e-3), 1e-40));
}

}  // namespace

/// PL15 sec. 4.1 dustywave, three species, amplitude 1e-4: no particle moves
/// far enough for a rebuild. `variable`: eps_j, or the S variable with its mass projection.
std::unique_ptr<sph::SphSimulation> dusty_wave(sph::DustVariable variable = sph::DustVariable::Epsilon) {
  sph::SphConfig cfg;
  cfg.kernel = sph::KernelType::M4;
  cfg.gamma = 5.0 / 3.0;
  cfg.alpha = 0.0;
  cfg.alpha_u = 0.0;
  sph::DustSettings ds;
  ds.nspecies = 3;
  ds.drag = sph::DragLaw::ConstantK;
  ds.k_drag = {100.0 / 3};
  ds.eps = {0.5 / 3};
  ds.variable = variable;
  sph::DustyWave wave;
  wave.n = 64;
  return std::make_unique<sph::SphSimulation>(sph::dustywave(wave, cfg, ds).make_system(), units::UnitSystem{});
}

TEST(DeviceTraffic, SphStepsWithRebuildsCopyAndAllocateNothing) {
  auto sim = dusty_shock();
  double t = 0;
  take_steps(*sim, 5, t);
  const int builds0 = sim->system().neighbours().builds();
  constexpr int kSteps = 40;
  TrafficCounter counter;
  take_steps(*sim, kSteps, t);
  const int rebuilds = sim->system().neighbours().builds() - builds0;
  ASSERT_GT(rebuilds, 0) << "the steps must include neighbour rebuilds";
  EXPECT_EQ(counter.deep_copies(), 0) << counter.report();
  EXPECT_EQ(counter.allocations(), 0) << counter.report();
  EXPECT_LE(counter.scalar_reads(), 3 * rebuilds) << counter.report();
}

TEST(DeviceTraffic, SphStepsWithoutRebuildsReadNothingBack) {
  for (const auto variable : {sph::DustVariable::Epsilon, sph::DustVariable::SqrtRhoEps}) {
    SCOPED_TRACE(variable == sph::DustVariable::Epsilon ? "eps" : "S with the mass projection");
    auto sim = dusty_wave(variable);
    double t = 0;
    take_steps(*sim, 5, t);
    const int builds0 = sim->system().neighbours().builds();
    TrafficCounter counter;
    take_steps(*sim, 40, t);
    ASSERT_EQ(sim->system().neighbours().builds(), builds0) << "this case must run without neighbour rebuilds";
    EXPECT_EQ(counter.deep_copies(), 0) << counter.report();
    EXPECT_EQ(counter.scalar_reads(), 0) << counter.report();
    EXPECT_EQ(counter.allocations(), 0) << counter.report();
  }
}

// Two-fluid dust (LAB15): the 3D dustybox, dust sliding through the gas (rebuilds), the drag in every step.
// One species, and two coupled through the mixture correction (mixture_drag.hpp).
TEST(DeviceTraffic, TwoFluidSphStepsCopyAndAllocateNothing) {
  for (const int species : {1, 2}) {
    SCOPED_TRACE(species);
    sph::DustyBox box;
    box.dim = 3;
    box.n = 8;
    sph::SphConfig cfg;
    cfg.eos = sph::EosType::Isothermal;
    sph::DustSettings ds;
    ds.method = sph::DustMethod::TwoFluid;
    ds.nspecies = species;
    ds.drag = sph::DragLaw::ConstantStoppingTime;
    ds.stopping_time = species == 1 ? std::vector<Real>{1e-3} : std::vector<Real>{1e-3, 1e-5};
    sph::SphSimulation sim(sph::make_dustybox(box, cfg, ds), units::UnitSystem{});
    double t = 0;
    take_steps(sim, 30, t);  // the neighbour list's work arrays reach their size (the dust changes the pair counts)
    const int builds0 = sim.system().neighbours().builds();
    TrafficCounter counter;
    take_steps(sim, 40, t);
    const int rebuilds = sim.system().neighbours().builds() - builds0;
    ASSERT_GT(rebuilds, 0) << "the steps must include neighbour rebuilds";
    EXPECT_EQ(counter.deep_copies(), 0) << counter.report();
    EXPECT_EQ(counter.allocations(), 0) << counter.report();
    // The list build's 3, and the two-fluid pair numbering's count of dust-gas pairs.
    EXPECT_LE(counter.scalar_reads(), 4 * rebuilds) << counter.report();
  }
}

TEST(DeviceTraffic, DiscStepsWithDustGasAndCoagulationCopyAndAllocateNothing) {
  auto sim = coupled_disc(22);
  double t = 0;
  take_steps(*sim, 5, t);
  const long long calls0 = sim->driver().calls(0);
  {
    TrafficCounter counter;
    take_steps(*sim, 30, t);
    EXPECT_EQ(counter.deep_copies(), 0) << counter.report();
    EXPECT_EQ(counter.scalar_reads(), 0) << counter.report();
    EXPECT_EQ(counter.allocations(), 0) << counter.report();
  }
  EXPECT_GT(sim->driver().calls(0), calls0) << "the steps must include coagulation calls";
}

TEST(DeviceTraffic, DiscTemperatureUpdatesReadBackOnlyTheSolverConvergenceMeasures) {
  // A temperature update needs, per BiCGStab iteration, one 40-byte copy of
  // the convergence measures to the host (the iteration is driven from the
  // host), and two more per solve (initial and true residual; the L2 guard's
  // reductions there are not copies). Every other copy is between two device
  // Views of equal size (the solver's restore point x0, r = b, the previous T
  // and E, T into the gas, Kokkos Kernels' level pointers): device-internal on
  // a GPU, at most 7 per update. The only allocations are Kokkos Kernels' own
  // work arrays inside the spiluk numeric phase ("iw", "Host level pointers").
  const std::string radiation =
      "[coagulation]\nkernel = \"physical\"\n"
      "[radiation]\nbands = 4\nstellar_bins = 20\ntolerance = 1e-8\n"
      "[temperature]\nmax_growth = 1.5\n";
  for (const std::string means : {"fixed", "local"}) {  // band means at T_binning, or per cell at every update
    SCOPED_TRACE("radiation.band_means = " + means);
    const auto deck = test_decks::disc_driver_deck(
        {"grid.ntheta=16", "dust.sizes=[1e-4, 1e-3]", "radiation.band_means=\"" + means + "\""}, radiation);
    disc::DiscSimulation sim(deck, core::Comm::world(), units::unit_system_by_name("au_msun"),
                             disc::DiscSimulation::well_mixed({1e-2, 1e-2}, 1e-40));
    const auto fld_iterations = [&sim] {
      for (const auto& d : sim.diagnostics())
        if (d.name == "fld_iterations") return d.value;
      return -1.0;
    };
    double t = 0;
    take_steps(sim, 5, t);
    const long long updates0 = sim.temperature()->updates();
    const double iterations0 = fld_iterations();
    TrafficCounter counter;
    take_steps(sim, 30, t);
    const long long updates = sim.temperature()->updates() - updates0;
    const int iterations = static_cast<int>(fld_iterations() - iterations0);
    ASSERT_GT(updates, 0) << "the steps must include temperature updates";
    int read_backs = 0, internal = 0;
    for (const auto& c : counter.copy_list()) {
      if (c.bytes <= 40)
        ++read_backs;
      else
        ++internal;
    }
    std::printf("%lld updates, %d iterations: %d read-backs of <= 40 B, %d device-internal copies; %s\n", updates,
                iterations, read_backs, internal, counter.report().c_str());
    // One per iteration, plus the initial residual and the true-residual confirmation of each solve.
    EXPECT_LE(read_backs, iterations + 2 * updates) << counter.report();
    EXPECT_LE(internal, 7 * updates) << counter.report();
    for (const auto& [label, count] : counter.allocation_labels())
      EXPECT_TRUE(label == "Host:iw" || label == "Host:Host level pointers") << label << " x " << count;
  }
}
