// Hydrostatic isothermal disc column, the gas part of the dust settling test
// (PL15 sec. 4.4.1): 2D, x in [-0.25, 0.25] periodic, z in [-3H, 3H] free,
// a_z = -z GM / (R0^2 + z^2)^(3/2) (eq. 53), GM = 1, R0 = 5, H/R0 = 0.05,
// isothermal; hexagonal lattice stretched to rho0 exp(-z^2 / 2H^2) (eq. 54-55),
// rho0 = 1e-3; M6 kernel. Relaxed for t = 1000 with damping f = 0.03 (eq. 56)
// and viscosity, then evolved for 10 orbits without damping: the rms velocity
// must stay below 1e-3 c_s. CI runs 16 x 55 particles (relaxed to t = 1500);
// the paper's 32 x 111 column is in the Slow suite.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "mote/setups/lattice.hpp"
#include "mote/sph/external.hpp"
#include "mote/sph/sph_system.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

struct ColumnResult {
  int n = 0;
  Real cs = 0.0;
  Real vrms_relaxed = 0.0;  ///< at the end of the damped relaxation
  Real vrms_max = 0.0;      ///< max over the 10 undamped orbits
  long long steps = 0;
  double seconds = 0.0;
};

ColumnResult run_column(int nx, Real t_relax, Real n_orbits) {
  const Real gm = 1.0, r0 = 5.0, rho0 = 1e-3;
  const Real omega0 = std::sqrt(gm / (r0 * r0 * r0));
  const Real H = 0.05 * r0;
  const Real cs = H * omega0;
  const Real t_orb = 2.0 * M_PI / omega0;

  SphConfig cfg;
  cfg.dim = 2;
  cfg.kernel = KernelType::M6;
  cfg.eos = EosType::Isothermal;
  cfg.cs_iso = cs;
  cfg.alpha = 1.0;
  cfg.damping = 0.03;
  Box box;
  box.dim = 2;
  box.lo[0] = -0.25;
  box.hi[0] = 0.25;
  box.periodic[0] = true;
  box.lo[1] = -3.0 * H;
  box.hi[1] = 3.0 * H;
  box.periodic[1] = false;
  Lattice lat = hexagonal_lattice(box, 0.5 / nx);
  auto rho = [=](Real z) { return rho0 * std::exp(-z * z / (2.0 * H * H)); };  // PL15 eq. 55
  stretch_map(lat, 1, box.lo[1], box.hi[1], rho);
  const int n = lat.size();
  const Real mass = lat.box.length(0) * integrate_profile(rho, box.lo[1], box.hi[1]);
  ParticleSetup s;
  s.dim = 2;
  s.x = lat.x;
  s.m = equal_masses(n, mass);
  for (int i = 0; i < n; ++i) s.h.push_back(cfg.effective_hfact() * std::sqrt(s.m[i] / rho(lat.x[2 * i + 1])));

  SphSystem sys(cfg, lat.box);
  sys.set_particles(s);
  sys.add_external_force(disc_vertical_gravity(gm, r0));
  const auto t0 = std::chrono::steady_clock::now();
  sys.initialise();
  sys.advance_to(t_relax);
  ColumnResult r;
  r.n = n;
  r.cs = cs;
  r.vrms_relaxed = sys.diagnostics().v_rms;
  sys.config().damping = 0.0;
  const Real t_end = t_relax + n_orbits * t_orb;
  while (sys.time() < t_end) {
    sys.step();
    r.vrms_max = std::max(r.vrms_max, sys.diagnostics().v_rms);
  }
  r.steps = sys.steps();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void report(const char* name, const ColumnResult& r) {
  std::printf(
      "[sph column %s] %d particles, %lld steps, %.1f s: v_rms/c_s after relaxation %.2e, "
      "max over 10 orbits %.2e\n",
      name, r.n, r.steps, r.seconds, r.vrms_relaxed / r.cs, r.vrms_max / r.cs);
}

TEST(SphColumn, ReducedHydrostaticEquilibrium) {
  // The coarse column keeps creeping towards its SPH equilibrium for longer
  // (v_rms/c_s = 4.4e-4 at t = 1000, 2.6e-4 at t = 1500): relax to 1500.
  const ColumnResult r = run_column(16, 1500.0, 10.0);
  report("16x55", r);
  EXPECT_EQ(r.n, 16 * 55);  // PL15 quotes 16 x 56; the hexagonal rows give 55 in 6H
  EXPECT_LT(r.vrms_max / r.cs, 1e-3);
}

TEST(SlowSphColumn, HydrostaticEquilibrium32x111) {
  const ColumnResult r = run_column(32, 1000.0, 10.0);
  report("32x111", r);
  EXPECT_EQ(r.n, 32 * 111);
  EXPECT_LT(r.vrms_max / r.cs, 1e-3);
}

}  // namespace
