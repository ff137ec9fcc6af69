// Reordering of the SPH particles into cell order on every neighbour rebuild
// (SphSystem::rebuild_neighbours, ParticleReorder): after a rebuild the
// particles are stored in non-decreasing cell key, the map id -> state of
// every per-particle field (particles, divv_old, the one-fluid dust) is the
// same bit for bit, and the density of the reordered set equals the density
// before the reordering to round-off, particle by particle (matched by id).
// A run that reorders on its rebuilds restarts from its checkpoint bit for
// bit (the storage order travels with the checkpoint). Both hold for the
// one-fluid dust and for two-fluid dust particles (LAB15) with their drag state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "mote/setups/dustybox.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/sph/density.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_simulation.hpp"
#include "mote/sph/two_fluid_dust.hpp"

using namespace mote;
using namespace mote::sph;

namespace {

/// A 2D periodic box on a perturbed lattice with two dust species, set up in
/// a shuffled order with random (transonic) velocities, so that rebuilds
/// reorder a lot.
std::unique_ptr<SphSystem> make_shuffled_dusty_box() {
  SphConfig cfg;
  cfg.dim = 2;
  cfg.kernel = KernelType::M4;
  cfg.eos = EosType::Adiabatic;
  Box box;
  box.dim = 2;
  for (int d = 0; d < 2; ++d) {
    box.lo[d] = 0.0;
    box.hi[d] = 1.0;
    box.periodic[d] = true;
  }
  const Lattice lat = cubic_lattice(box, 1.0 / 24);
  const int n = lat.size();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 rng(7);
  std::shuffle(order.begin(), order.end(), rng);
  std::normal_distribution<Real> g(0.0, 0.5);
  std::uniform_real_distribution<Real> jitter(-0.2, 0.2);
  ParticleSetup s;
  s.dim = 2;
  for (int k : order) {
    for (int d = 0; d < 2; ++d) {
      s.x.push_back(lat.x[2 * k + d] + jitter(rng) * lat.dx);
      s.v.push_back(g(rng));
    }
  }
  s.m = equal_masses(n, 1.0);
  s.h.assign(n, cfg.effective_hfact() * lat.dx);
  s.u.assign(n, 1.0);
  auto sys = std::make_unique<SphSystem>(cfg, lat.box);
  sys->set_particles(s);
  DustSettings ds;
  ds.nspecies = 2;
  ds.drag = DragLaw::ConstantK;
  ds.k_drag = {50.0, 100.0};
  ds.eps = {0.1, 0.2};
  add_one_fluid_dust(*sys, ds);
  sys->initialise();
  return sys;
}

/// Every per-particle field of the engine and of its dust module (one-fluid
/// or two-fluid), as raw bytes in id order.
std::map<std::string, std::vector<unsigned char>> state_by_id(const SphSystem& sys) {
  const Particles& p = sys.particles();
  const IdOrder by_id(p.id);
  std::map<std::string, std::vector<unsigned char>> out;
  auto put = [&out](const std::string& name, const auto& host) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(host.data());
    out[name].assign(bytes, bytes + host.span() * sizeof(*host.data()));
  };
  std::map<std::string, RealView2> fields2 = {{"x", p.x}, {"v", p.v}, {"a", p.a}, {"vpred", p.vpred}};
  std::map<std::string, RealView1> fields1 = {{"m", p.m},
                                              {"h", p.h},
                                              {"rho", p.rho},
                                              {"omega", p.omega},
                                              {"u", p.u},
                                              {"upred", p.upred},
                                              {"dudt", p.dudt},
                                              {"P", p.P},
                                              {"cs", p.cs},
                                              {"alpha", p.alpha},
                                              {"divv", p.divv},
                                              {"vsig", p.vsig},
                                              {"divv_old", sys.divv_old()}};
  if (const OneFluidDust* d = sys.module<OneFluidDust>()) {
    fields2.insert({{"dust_var", d->var},
                    {"dust_var_pred", d->var_pred},
                    {"dust_dvar", d->dvar},
                    {"dust_ts", d->ts},
                    {"dust_coef", d->coef},
                    {"dust_gforce", d->gforce}});
    fields1.insert(
        {{"dust_eps", d->eps_tot}, {"dust_ts_eps", d->eps_ts}, {"dust_dtot", d->d_tot}, {"dust_u", d->uloc}});
  }
  if (const TwoFluidDust* d = sys.module<TwoFluidDust>()) {
    fields2.insert({{"two_fluid_v_start", d->v_start}, {"two_fluid_dv", d->dv}, {"two_fluid_tinv", d->tinv}});
    fields1.insert({{"two_fluid_du", d->du}});
  }
  for (const auto& [name, v] : fields2) put(name, by_id(v));
  for (const auto& [name, v] : fields1) put(name, by_id(v));
  put("type", by_id(p.type));
  put("id", by_id(p.id));
  return out;
}

std::vector<int> host_ids(const Particles& p) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.id);
  return std::vector<int>(h.data(), h.data() + h.extent(0));
}

/// Cell key of every stored particle in the grid of the last build.
std::vector<int> cell_keys(const Particles& p, const NeighbourList& nl) {
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.x);
  std::vector<int> keys(p.n);
  for (int i = 0; i < p.n; ++i) {
    int key = 0, stride = 1;
    for (int d = 0; d < p.dim; ++d) {
      key += stride * nl.grid.coord(x(i, d), d);
      stride *= nl.grid.nc[d];
    }
    keys[i] = key;
  }
  return keys;
}

/// A storage order that is not the cell order: the reverse of the current one.
void reverse_storage(SphSystem& sys) {
  const int n = sys.particles().n;
  View<int*> reverse("reverse", n);
  auto h = Kokkos::create_mirror_view(reverse);
  for (int i = 0; i < n; ++i) h(i) = n - 1 - i;
  Kokkos::deep_copy(reverse, h);
  sys.reorder_particles(reverse);
}

/// Density, h and Omega in id order from one solve on the current list, the
/// particle state left as it was.
std::vector<HostView<Real*>> density_by_id(SphSystem& sys, const NeighbourList& nl) {
  Particles& p = sys.particles();
  RealView1 h0("h0", p.n), rho0("rho0", p.n), omega0("omega0", p.n);
  Kokkos::deep_copy(h0, p.h);
  Kokkos::deep_copy(rho0, p.rho);
  Kokkos::deep_copy(omega0, p.omega);
  const DensityResult r = compute_density(p, nl, sys.box(), sys.config());
  EXPECT_EQ(r.outside_cover, 0);
  EXPECT_EQ(r.max_iterations, 1);  // converged h: the same path whatever the summation order
  const IdOrder by_id(p.id);
  std::vector<HostView<Real*>> out = {by_id(p.rho), by_id(p.h), by_id(p.omega)};
  Kokkos::deep_copy(p.h, h0);
  Kokkos::deep_copy(p.rho, rho0);
  Kokkos::deep_copy(p.omega, omega0);
  return out;
}

/// The dustybox of LAB15 sec. 3 in 2D with two two-fluid dust species
/// (constant K), adiabatic gas, every particle given a random transonic
/// velocity and the storage shuffled, so that rebuilds reorder gas and dust
/// particles alike.
std::unique_ptr<SphSystem> make_shuffled_two_fluid_box() {
  DustyBox box;
  box.dim = 2;
  box.n = 16;
  box.lo = 0.0;
  box.hi = 1.0;
  box.eps = 0.3;
  SphConfig cfg;
  cfg.dim = 2;
  cfg.kernel = KernelType::M4;
  cfg.eos = EosType::Adiabatic;
  DustSettings ds;
  ds.method = DustMethod::TwoFluid;
  ds.nspecies = 2;
  ds.drag = DragLaw::ConstantK;
  ds.k_drag = {5.0, 20.0};
  auto sys = make_dustybox(box, cfg, ds);
  const Particles& p = sys->particles();
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.v);
  std::mt19937 rng(11);
  std::normal_distribution<Real> g(0.0, 0.5);
  for (int i = 0; i < p.n; ++i)
    for (int d = 0; d < 2; ++d) v(i, d) += g(rng);
  Kokkos::deep_copy(p.v, v);
  View<int*> order("shuffle", p.n);
  auto h = Kokkos::create_mirror_view(order);
  std::iota(h.data(), h.data() + p.n, 0);
  std::shuffle(h.data(), h.data() + p.n, rng);
  Kokkos::deep_copy(order, h);
  sys->reorder_particles(order);
  sys->initialise();
  return sys;
}

using SystemFactory = std::unique_ptr<SphSystem> (*)();

/// After three steps and a reversal of the storage, a rebuild sorts the
/// particles by cell, keeps every field of every particle bit for bit, and the
/// density of the new order equals the old order's to round-off.
void expect_rebuild_sorts_and_keeps_state(SystemFactory make) {
  auto sys = make();
  for (int k = 0; k < 3; ++k) sys->step();  // every field holds step data
  reverse_storage(*sys);
  const Particles& p = sys->particles();
  NeighbourList unsorted;
  unsorted.build(sys->particles(), sys->box(), sys->config().kernel, sys->config().skin);
  compute_density(sys->particles(), unsorted, sys->box(), sys->config());  // h converged for this list
  const auto before = state_by_id(*sys);
  const auto rho_before = density_by_id(*sys, unsorted);
  const std::vector<int> ids_before = host_ids(p);

  sys->rebuild_neighbours();
  const std::vector<int> keys = cell_keys(p, sys->neighbours());
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  EXPECT_NE(host_ids(p), ids_before);  // the rebuild did reorder
  const auto after = state_by_id(*sys);
  ASSERT_EQ(after.size(), before.size());
  for (const auto& [name, bytes] : before) EXPECT_TRUE(after.at(name) == bytes) << name << " changed by the reordering";

  const auto rho_after = density_by_id(*sys, sys->neighbours());
  for (int k = 0; k < p.n; ++k) {
    EXPECT_NEAR(rho_after[0](k), rho_before[0](k), 1e-14 * rho_before[0](k)) << "rho of id " << k;
    EXPECT_NEAR(rho_after[1](k), rho_before[1](k), 1e-14 * rho_before[1](k)) << "h of id " << k;
    EXPECT_NEAR(rho_after[2](k), rho_before[2](k), 1e-13) << "Omega of id " << k;
  }
}

/// 20 steps in one go and 10 + 10 through a checkpoint, with rebuilds (and so
/// reorderings) after the restart: the same storage order and the same bits.
void expect_restart_bit_identical(SystemFactory make, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "checkpoint.h5").string();
  const auto comm = core::Comm::world();
  auto run = [](SphSimulation& sim, int steps) {
    for (int k = 0; k < steps; ++k) sim.advance(0.0, sim.max_dt());
  };
  SphSimulation full(make(), units::UnitSystem{});
  run(full, 10);
  const int builds_at_checkpoint = full.system().neighbours().builds();
  run(full, 10);
  EXPECT_GE(full.system().neighbours().builds() - builds_at_checkpoint, 2);  // reorders after the restart

  SphSimulation first(make(), units::UnitSystem{});
  run(first, 10);
  {
    io::H5File f(path, io::H5File::Mode::Create, comm);
    f.create_group("/state");
    first.save_state(f);
  }
  SphSimulation resumed(make(), units::UnitSystem{});
  {
    io::H5File f(path, io::H5File::Mode::Read, comm);
    resumed.load_state(f);
  }
  run(resumed, 10);
  EXPECT_EQ(resumed.system().time(), full.system().time());
  EXPECT_EQ(host_ids(resumed.system().particles()), host_ids(full.system().particles()));  // same storage order
  EXPECT_TRUE(state_by_id(resumed.system()) == state_by_id(full.system()));
  if (const TwoFluidDust* d = full.system().module<TwoFluidDust>())
    EXPECT_EQ(resumed.system().module<TwoFluidDust>()->drag_heating(), d->drag_heating());
}

}  // namespace

TEST(SphReorder, RebuildSortsByCellAndKeepsEveryParticleState) {
  expect_rebuild_sorts_and_keeps_state(make_shuffled_dusty_box);
}

TEST(SphReorder, RebuildKeepsEveryTwoFluidParticleState) {
  expect_rebuild_sorts_and_keeps_state(make_shuffled_two_fluid_box);
}

TEST(SphReorder, RestartOfAReorderingRunIsBitIdentical) {
  expect_restart_bit_identical(make_shuffled_dusty_box, "mote_sph_reorder");
}

TEST(SphReorder, RestartOfAReorderingTwoFluidRunIsBitIdentical) {
  expect_restart_bit_identical(make_shuffled_two_fluid_box, "mote_sph_reorder_two_fluid");
}
