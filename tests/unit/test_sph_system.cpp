// SphSystem API: snapshots (positions wrapped into the box, ids, all fields),
// extra time-step constraints, external accelerations and damping (PL15
// eq. 53, 56), and particle types as data (a second type neither enters the
// gas density sum nor feels the gas pressure force).
#include <gtest/gtest.h>

#include <cmath>

#include "mote/setups/lattice.hpp"
#include "mote/sph/external.hpp"
#include "mote/sph/sph_system.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

// Kernels are launched from named functions, never from a lambda or a TEST
// body (CUDA extended-lambda rules).
void push_up(Particles& p, Real g) {
  const auto a = p.a;
  Kokkos::parallel_for(
      "test::push", Kokkos::RangePolicy<mote::ExecSpace>(0, p.n), KOKKOS_LAMBDA(int i) { a(i, 1) += g; });
}

struct SystemSetup {
  SphConfig cfg;
  Lattice lat;
  ParticleSetup s;
};

SystemSetup periodic_2d(int nx) {
  SystemSetup st;
  st.cfg.dim = 2;
  st.cfg.kernel = KernelType::M4;
  st.cfg.eos = EosType::Isothermal;
  st.cfg.cs_iso = 1.0;
  Box box;
  box.dim = 2;
  for (int d = 0; d < 2; ++d) {
    box.lo[d] = 0.0;
    box.hi[d] = 1.0;
    box.periodic[d] = true;
  }
  st.lat = cubic_lattice(box, 1.0 / nx);
  const int n = st.lat.size();
  st.s.dim = 2;
  st.s.x = st.lat.x;
  st.s.m = equal_masses(n, 1.0);
  st.s.h.assign(n, st.cfg.effective_hfact() * st.lat.dx);
  return st;
}

TEST(SphSystem, SnapshotAndTimestepHook) {
  SystemSetup st = periodic_2d(16);
  const int n = st.lat.size();
  for (int i = 0; i < n; ++i) {
    st.s.v.push_back(0.3);  // uniform drift across the periodic boundary
    st.s.v.push_back(-0.2);
  }
  SphSystem sys(st.cfg, st.lat.box);
  sys.set_particles(st.s);
  sys.add_timestep_constraint([](const Particles&) { return 1e-3; });
  sys.initialise();
  EXPECT_DOUBLE_EQ(sys.next_dt(), 1e-3);
  for (int k = 0; k < 200; ++k) EXPECT_DOUBLE_EQ(sys.step(), 1e-3);
  const Snapshot snap = sys.snapshot();
  EXPECT_NEAR(snap.time, 0.2, 1e-12);
  std::vector<int> seen(n, 0);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 2; ++d) {
      EXPECT_GE(snap.x(i, d), 0.0);
      EXPECT_LT(snap.x(i, d), 1.0);
    }
    EXPECT_NEAR(snap.v(i, 0), 0.3, 1e-12);  // uniform flow stays uniform
    EXPECT_NEAR(snap.rho(i), 1.0, 1e-3);
    EXPECT_NEAR(snap.P(i), 1.0 * snap.rho(i), 1e-14);
    EXPECT_EQ(snap.type(i), kGas);
    ++seen[snap.id(i)];
  }
  for (int i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1);
  // The whole lattice moved by v t (modulo the box).
  EXPECT_NEAR(std::fmod(snap.x(0, 0) - st.lat.x[0] + 10.0, 1.0), 0.06, 1e-9);
}

TEST(SphSystem, DampingAndExternalForce) {
  SystemSetup st = periodic_2d(16);
  st.cfg.damping = 0.5;
  const int n = st.lat.size();
  for (int i = 0; i < n; ++i) {
    st.s.v.push_back(1.0);
    st.s.v.push_back(0.0);
  }
  SphSystem sys(st.cfg, st.lat.box);
  sys.set_particles(st.s);
  sys.add_external_force([](Particles& p, const mote::RealView2&, Real) { push_up(p, 0.25); });
  sys.initialise();
  sys.advance_to(20.0);
  // dv/dt = -f v (PL15 eq. 56): v_x = exp(-f t); v_y -> g / f = 0.5.
  const Diagnostics d = sys.diagnostics();
  EXPECT_NEAR(d.momentum[0] / d.mass, std::exp(-0.5 * 20.0), 1e-4);
  EXPECT_NEAR(d.momentum[1] / d.mass, 0.5 * (1.0 - std::exp(-0.5 * 20.0)), 1e-3);
}

TEST(SphSystem, DiscGravityEq53) {
  Particles p;
  p.allocate(3, 2);
  auto x = Kokkos::create_mirror_view(p.x);
  const Real z[3] = {-1.0, 0.0, 2.0};
  for (int i = 0; i < 3; ++i) {
    x(i, 0) = 0.1;
    x(i, 1) = z[i];
  }
  Kokkos::deep_copy(p.x, x);
  disc_vertical_gravity(1.0, 5.0)(p, p.v, 0.0);
  auto a = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.a);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(a(i, 0), 0.0);
    EXPECT_NEAR(a(i, 1), -z[i] / std::pow(25.0 + z[i] * z[i], 1.5), 1e-15);
  }
}

TEST(SphSystem, ParticleTypesAreData) {
  // Gas lattice plus a second-type lattice offset by half a cell: the gas
  // density and forces must not see the other type.
  SystemSetup st = periodic_2d(16);
  const int n = st.lat.size();
  SphSystem gas_only(st.cfg, st.lat.box);
  gas_only.set_particles(st.s);
  gas_only.initialise();
  const Snapshot ref = gas_only.snapshot();

  ParticleSetup mixed = st.s;
  mixed.type.assign(n, kGas);
  for (int i = 0; i < n; ++i) {
    mixed.x.push_back(st.lat.x[2 * i] + 0.5 * st.lat.dx + 0.01 * st.lat.dx * (i % 7));
    mixed.x.push_back(st.lat.x[2 * i + 1] + 0.5 * st.lat.dx);
    mixed.m.push_back(0.01 * st.s.m[i]);
    mixed.h.push_back(st.s.h[i]);
    mixed.type.push_back(kDust);
  }
  SphSystem sys(st.cfg, st.lat.box);
  sys.set_particles(mixed);
  sys.initialise();
  const Snapshot snap = sys.snapshot();
  const auto a = IdOrder(sys.particles().id)(sys.particles().a);  // as the snapshot
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(snap.rho(i), ref.rho(i), 1e-12 * ref.rho(i));
    EXPECT_NEAR(a(i, 0), 0.0, 1e-9);     // uniform gas lattice: no net force
    EXPECT_DOUBLE_EQ(a(n + i, 0), 0.0);  // no hydro force on the other type
  }
}

}  // namespace
