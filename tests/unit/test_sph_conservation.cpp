// Conservation properties of the SPH engine (PL15 sec. 3.3): total linear
// momentum (eq. 36) to round-off, and total energy (eq. 40-42 without dust)
// up to the O(dt^2) error of the kick-drift-kick integrator, checked by halving
// the Courant number. Random supersonic velocities on a periodic 2D lattice
// (shocks, viscosity and conductivity all active) and a 3D close-packed box.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mote/setups/lattice.hpp"
#include "mote/sph/forces.hpp"
#include "mote/sph/sph_system.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

struct ConservationResult {
  Real momentum_err = 0.0;  ///< max_t |P(t) - P(0)| / sum m |v|
  Real energy_drift = 0.0;  ///< |E(t_end) - E(0)| / E(0)
  long long steps = 0;
};

ConservationResult run_box(int dim, Real c_cour, Real t_end, bool cullen_dehnen) {
  SphConfig cfg;
  cfg.dim = dim;
  cfg.kernel = KernelType::M4;
  cfg.eos = EosType::Adiabatic;
  cfg.gamma = 5.0 / 3.0;
  cfg.c_cour = c_cour;
  cfg.c_force = 0.25 * c_cour / 0.3;
  cfg.cullen_dehnen = cullen_dehnen;
  Box box;
  box.dim = dim;
  for (int d = 0; d < dim; ++d) {
    box.lo[d] = 0.0;
    box.hi[d] = 1.0;
    box.periodic[d] = true;
  }
  const Lattice lat = dim == 2 ? hexagonal_lattice(box, 1.0 / 32) : close_packed_lattice(box, 1.0 / 12);
  Real vol = 1.0;
  for (int d = 0; d < dim; ++d) vol *= lat.box.length(d);
  const int n = lat.size();
  ParticleSetup s;
  s.dim = dim;
  s.x = lat.x;
  s.m = equal_masses(n, vol);
  s.h.assign(n, cfg.effective_hfact() * lat.dx);
  std::mt19937 rng(42);
  std::normal_distribution<Real> gauss(0.0, 1.0);
  std::uniform_real_distribution<Real> uni(0.5, 1.5);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) s.v.push_back(0.8 * gauss(rng) + (d == 0 ? 0.3 : 0.0));  // bulk drift too
    s.u.push_back(uni(rng));
  }
  SphSystem sys(cfg, lat.box);
  sys.set_particles(s);
  sys.initialise();
  const Diagnostics d0 = sys.diagnostics();
  ConservationResult r;
  while (sys.time() < t_end) {
    sys.step();
    const Diagnostics dg = sys.diagnostics();
    Real dp2 = 0.0;
    for (int d = 0; d < dim; ++d) dp2 += std::pow(dg.momentum[d] - d0.momentum[d], 2);
    r.momentum_err = std::max(r.momentum_err, std::sqrt(dp2) / d0.momentum_abs);
  }
  r.energy_drift = std::fabs(sys.diagnostics().energy - d0.energy) / d0.energy;
  r.steps = sys.steps();
  return r;
}

TEST(SphConservation, MomentumAndEnergy2D) {
  const ConservationResult a = run_box(2, 0.3, 0.1, false);
  const ConservationResult b = run_box(2, 0.15, 0.1, false);
  std::printf("[sph conservation 2D] C=0.30: %lld steps, momentum error %.2e, energy drift %.3e\n", a.steps,
              a.momentum_err, a.energy_drift);
  std::printf("[sph conservation 2D] C=0.15: %lld steps, momentum error %.2e, energy drift %.3e (ratio %.2f)\n",
              b.steps, b.momentum_err, b.energy_drift, a.energy_drift / b.energy_drift);
  EXPECT_LT(a.momentum_err, 1e-12);
  EXPECT_LT(b.momentum_err, 1e-12);
  EXPECT_LT(a.energy_drift, 2e-3);
  // Second-order integrator: halving dt would reduce the drift by 4; measured 3.3
  // (order 1.7, docs/sph.md), asserted as order >= 1.58.
  EXPECT_GT(a.energy_drift / b.energy_drift, 3.0);
}

// Phantom's local viscosity (Price et al. 2018, eq. 40-41, xi = 1): 10 h^2 A / c_s^2
// between alpha_min and alpha_max, A only where div v falls; alpha_min (not
// 0 / 0) where c_s = 0.
TEST(SphCullenDehnen, LocalViscosityAsPhantom) {
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-5.0, 0.1, 1.0, 0.0, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-5.0, 0.1, 2.0, 0.0, 1.0), 0.125);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-500.0, 0.1, 1.0, 0.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(5.0, 0.1, 1.0, 0.02, 1.0), 0.02);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(0.0, 0.1, 0.0, 0.02, 1.0), 0.02);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-5.0, 0.1, 0.0, 0.0, 1.0), 0.0);
}

TEST(SphConservation, MomentumAndEnergy3DCullenDehnen) {
  const ConservationResult a = run_box(3, 0.3, 0.05, true);
  std::printf("[sph conservation 3D, Cullen-Dehnen] %lld steps, momentum error %.2e, energy drift %.3e\n", a.steps,
              a.momentum_err, a.energy_drift);
  EXPECT_LT(a.momentum_err, 1e-12);
  EXPECT_LT(a.energy_drift, 2e-3);
}

}  // namespace
