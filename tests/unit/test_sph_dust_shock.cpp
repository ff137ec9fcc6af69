// Dustyshock (PL15 sec. 4.2, VALIDATION A2): Sod tube in the gas, dust-to-gas
// ratio 1 (eps = 0.5) everywhere, K = 1000, gamma = 5/3; at strong drag the
// mixture is an ideal gas of total density rho = rho_g / (1 - eps) with the same
// gamma (the "heavy fluid", PL15 sec. 4.2), compared with the exact Riemann
// solution at t = 0.2. Both discretisations; conservation (A7); N = 10 equal
// bins (A4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mote/setups/riemann_exact.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "sph_dust_problems.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

struct ShockResult {
  double l1 = 0.0;
  int n_measured = 0;
  long long steps = 0;
  double mass_drift = 0.0, dust_drift = 0.0, mom_drift = 0.0, energy_drift = 0.0, floored = 0.0;
  std::vector<double> eps, v, u;
};

/// PL15 sec. 4.2 through the library set-up (x in [-1, 1] periodic, left
/// spacing 0.001, right 0.008: equal masses; M4, alpha = 1, beta = 2, alpha_u = 1).
ShockResult run_dustyshock(DustDiscretisation disc, DustVariable var, int nspecies, double t_end) {
  const double gamma = 5.0 / 3.0, eps0 = 0.5, K = 1000.0;
  const double rhog_l = 1.0, rhog_r = 0.125, p_l = 1.0, p_r = 0.125;
  SphConfig cfg;
  cfg.kernel = KernelType::M4;
  cfg.gamma = gamma;
  DustSettings ds;
  ds.nspecies = nspecies;
  ds.discretisation = disc;
  ds.variable = var;
  ds.drag = DragLaw::ConstantK;
  ds.k_drag = {K / nspecies};  // equal bins of identical grains
  ds.eps = {eps0 / nspecies};
  auto psys = dustyshock(DustyShock{}, cfg, ds).make_system();
  SphSystem& sys = *psys;
  sys.initialise();
  const Diagnostics d0 = sys.diagnostics();
  sys.advance_to(t_end);
  const Diagnostics d1 = sys.diagnostics();
  const Snapshot snap = sys.snapshot();
  const DustSnapshot dsn = sys.module<OneFluidDust>()->snapshot(sys.particles());
  const ExactRiemann exact({rhog_l / (1.0 - eps0), 0.0, p_l}, {rhog_r / (1.0 - eps0), 0.0, p_r}, gamma);
  ShockResult r;
  for (int i = 0; i < sys.particles().n; ++i) {
    const double x = snap.x(i, 0);
    double e = 0.0;
    for (int j = 0; j < nspecies; ++j) e += dsn.eps(i, j);
    r.eps.push_back(e);
    r.v.push_back(snap.v(i, 0));
    r.u.push_back(snap.u(i));
    if (x < -0.5 || x > 0.5) continue;
    r.l1 += std::fabs(snap.rho(i) - exact.sample(x / t_end).rho);
    ++r.n_measured;
  }
  r.l1 /= std::max(r.n_measured, 1);
  r.steps = sys.steps();
  r.mass_drift = std::fabs(d1.mass - d0.mass) / d0.mass;
  r.dust_drift = std::fabs(d1.dust_mass - d1.dust_floored - d0.dust_mass) / d0.dust_mass;
  r.mom_drift = std::fabs(d1.momentum[0] - d0.momentum[0]) / d1.momentum_abs;
  r.energy_drift = std::fabs(d1.energy - d0.energy) / d0.energy;
  r.floored = d1.dust_floored / d0.dust_mass;
  return r;
}

const char* name(DustDiscretisation d) {
  return d == DustDiscretisation::SecondDerivatives ? "second derivatives" : "two first derivatives";
}

TEST(SphDustShock, HeavyFluidRiemann) {
  for (auto disc : {DustDiscretisation::SecondDerivatives, DustDiscretisation::FirstDerivatives}) {
    const ShockResult r = run_dustyshock(disc, DustVariable::Epsilon, 1, 0.2);
    std::printf(
        "[A2 dustyshock] %s: mean |rho - rho_exact| = %.3e over %d particles (%lld steps); drifts mass %.1e "
        "dust %.1e (floored %.1e) momentum %.1e energy %.1e\n",
        name(disc), r.l1, r.n_measured, r.steps, r.mass_drift, r.dust_drift, r.floored, r.mom_drift, r.energy_drift);
    EXPECT_GT(r.n_measured, 500);
    EXPECT_LT(r.l1, 1e-2);
    EXPECT_LT(r.mass_drift, 1e-12);
    EXPECT_LT(r.dust_drift, 1e-12);
    EXPECT_LT(r.mom_drift, 1e-12);
    EXPECT_LT(r.energy_drift, 4e-5);  // measured 4.3e-6 (VALIDATION A7: 1e-3)
  }
}

// A4 on the shock: N = 10 equal bins vs N = 1 (relative to the local value; v relative to c_s = 1).
TEST(SphDustShock, TenEqualBinsEqualOneSpecies) {
  for (auto disc : {DustDiscretisation::SecondDerivatives, DustDiscretisation::FirstDerivatives}) {
    const ShockResult a = run_dustyshock(disc, DustVariable::Epsilon, 1, 0.2);  // the A2 end time
    const ShockResult b = run_dustyshock(disc, DustVariable::Epsilon, 10, 0.2);
    double de = 0.0, dv = 0.0, du = 0.0;
    for (std::size_t i = 0; i < a.eps.size(); ++i) {
      de = std::max(de, std::fabs(a.eps[i] - b.eps[i]) / a.eps[i]);
      dv = std::max(dv, std::fabs(a.v[i] - b.v[i]));
      du = std::max(du, std::fabs(a.u[i] - b.u[i]) / a.u[i]);
    }
    std::printf("[A4 dustyshock t = 0.2] %s: N = 10 vs N = 1 max relative difference eps %.1e, v %.1e, u %.1e\n",
                name(disc), de, dv, du);
    EXPECT_LT(de, 1e-10);
    EXPECT_LT(dv, 1e-10);
    EXPECT_LT(du, 1e-10);
  }
}

}  // namespace
