// Dustydiffuse (PL15 sec. 4.3, VALIDATION A3): uniform rho = 1, isothermal
// c_s = 1, constant t_s = 0.1, particles fixed, only the dust equation evolved;
// eps(r, 0) = eps0 (1 - (r / r_c)^2) for r < r_c against the self-similar solution
// PL15 eq. 51, eps = A |10 eta t + B|^(-3/5) - r^2 / (10 eta t + B), eta = t_s c_s^2,
// with B = r_c^2 / eps0 and A = eps0 B^(3/5) (eq. 52 at t = 0; the transcribed
// "B = eps0 / r_c^2" does not reproduce eq. 52). L2 error over r < 0.2 on cubic
// lattices 8^3, 16^3, 32^3 (CI): second order, and direct second derivatives at
// least 2x more accurate than two first derivatives. Also N = 10 equal bins (A4)
// and the S = sqrt(rho eps) variable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "mote/sph/one_fluid_dust.hpp"
#include "sph_dust_problems.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

double g_rmax = 0.2;
double g_hfact = 1.2;
KernelType g_kernel = KernelType::M4;
constexpr double kEps0 = 0.1, kTs = 0.1;  // eta = t_s c_s^2 = 0.1

double exact_eps(double r, double t) { return dustydiffuse_eps(DustyDiffuse{}, kTs, r, t); }

struct DiffuseResult {
  double l2 = 0.0;
  int steps = 0;
  double dust_drift = 0.0;
  std::vector<double> eps;
};

DiffuseResult run_diffuse(int n, DustDiscretisation disc, DustVariable var, int nspecies, double t_end,
                          double c0 = 0.3) {
  SphConfig cfg;
  cfg.kernel = g_kernel;
  cfg.hfact = g_hfact;
  cfg.cs_iso = 1.0;
  DustSettings ds;
  ds.nspecies = nspecies;
  ds.discretisation = disc;
  ds.variable = var;
  ds.drag = DragLaw::ConstantStoppingTime;
  ds.stopping_time = {kTs};
  ds.c_dust = c0;
  DustyDiffuse dd;
  dd.n = n;
  auto psys = dustydiffuse(dd, cfg, ds).make_system();
  SphSystem& sys = *psys;
  const int np = sys.particles().n;
  sys.initialise();
  const Diagnostics d0 = sys.diagnostics();
  DiffuseResult res;
  res.steps = advance_dust_only(sys, t_end);
  const Diagnostics d1 = sys.diagnostics();
  res.dust_drift = std::fabs(d1.dust_mass - d1.dust_floored - d0.dust_mass) / d0.dust_mass;
  const Snapshot snap = sys.snapshot();
  const DustSnapshot dsn = sys.module<OneFluidDust>()->snapshot(sys.particles());
  double e2 = 0.0;
  int cnt = 0;
  for (int i = 0; i < np; ++i) {
    double e = 0.0;
    for (int j = 0; j < nspecies; ++j) e += dsn.eps(i, j);
    res.eps.push_back(e);
    const double r = std::sqrt(snap.x(i, 0) * snap.x(i, 0) + snap.x(i, 1) * snap.x(i, 1) + snap.x(i, 2) * snap.x(i, 2));
    if (r >= g_rmax) continue;
    const double d = e - exact_eps(r, t_end);
    e2 += d * d;
    ++cnt;
  }
  res.l2 = std::sqrt(e2 / std::max(cnt, 1));
  return res;
}

const char* name(DustDiscretisation d) {
  return d == DustDiscretisation::SecondDerivatives ? "second derivatives" : "two first derivatives";
}

// M4 with h = 1.5 dx: with h = 1.2 dx the zeroth-order (lattice normalisation)
// error of the SPH second derivative sets a floor near 2e-4 at 32^3 (measured
// orders 1.92, 1.46 and a first/second ratio of 1.6 at 32^3; docs/sph_dust.md).
// The close-packed set-up of the paper's run (n = 50): 50 x 58 x 62 particles,
// PL15's 50 x 58 x 60 but for z, whose 61.2 layers the periodic hcp lattice
// rounds to an even 62 (the box 1.0125 long in z, the density 1 all the same).
TEST(SphDustDiffuseSetup, ClosePackedPaperLattice) {
  SphConfig cfg;
  cfg.cs_iso = 1.0;
  DustSettings ds;
  ds.drag = DragLaw::ConstantStoppingTime;
  ds.stopping_time = {kTs};
  DustyDiffuse dd;
  dd.n = 50;
  dd.close_packed = true;
  const DustProblem p = dustydiffuse(dd, cfg, ds);
  EXPECT_EQ(p.particles.size(), 50 * 58 * 62);
  EXPECT_NEAR(p.box.length(2), 62 * 0.02 * std::sqrt(2.0 / 3.0), 1e-12);
  double mass = 0.0;
  for (Real m : p.particles.m) mass += m;
  EXPECT_NEAR(mass / (p.box.length(0) * p.box.length(1) * p.box.length(2)), 1.0,
              1e-10);  // summed over 179,800 particles
}

TEST(SphDustDiffuse, ConvergenceCubicLattices) {
  const double t_end = 0.1;
  g_hfact = 1.5;
  double l2[2][3];
  int k = 0;
  for (auto disc : {DustDiscretisation::SecondDerivatives, DustDiscretisation::FirstDerivatives}) {
    int m = 0;
    for (int n : {8, 16, 32}) {
      const DiffuseResult r = run_diffuse(n, disc, DustVariable::Epsilon, 1, t_end);
      l2[k][m++] = r.l2;
      std::printf(
          "[A3 dustydiffuse] %s, %d^3, M4 h = 1.5 dx, t = %.2f: L2(eps, r < 0.2) = %.3e (%d steps), dust mass "
          "drift %.1e\n",
          name(disc), n, t_end, r.l2, r.steps, r.dust_drift);
      EXPECT_LT(r.dust_drift, 1e-12);
    }
    const double o1 = std::log2(l2[k][0] / l2[k][1]), o2 = std::log2(l2[k][1] / l2[k][2]);
    std::printf("[A3 dustydiffuse] %s: order 8->16 %.2f, 16->32 %.2f\n", name(disc), o1, o2);
    if (disc == DustDiscretisation::SecondDerivatives) {
      EXPECT_GT(o1, 1.8);
      EXPECT_GT(o2, 1.8);
      EXPECT_LT(l2[k][2], 5e-4);
    } else {
      EXPECT_GT(o1, 1.4);
      EXPECT_GT(o2, 1.4);
    }
    ++k;
  }
  for (int m = 0; m < 3; ++m) {
    std::printf("[A3 dustydiffuse] L2 ratio two first / direct second derivatives at %d^3: %.2f\n", 8 << m,
                l2[1][m] / l2[0][m]);
    EXPECT_GT(l2[1][m] / l2[0][m], 2.0);
  }
  g_hfact = 1.2;
}

// S = sqrt(rho eps) (PL15 app. B; HPL18 eq. 51) and N = 10 equal bins (A4) on the diffusion problem.
TEST(SphDustDiffuse, SqrtVariableAndTenBins) {
  g_hfact = 1.5;
  for (auto disc : {DustDiscretisation::SecondDerivatives, DustDiscretisation::FirstDerivatives}) {
    const DiffuseResult e1 = run_diffuse(16, disc, DustVariable::Epsilon, 1, 0.1);
    const DiffuseResult e10 = run_diffuse(16, disc, DustVariable::Epsilon, 10, 0.1);
    const DiffuseResult s1 = run_diffuse(16, disc, DustVariable::SqrtRhoEps, 1, 0.1);
    double dmax = 0.0;
    for (std::size_t i = 0; i < e1.eps.size(); ++i) dmax = std::max(dmax, std::fabs(e1.eps[i] - e10.eps[i]) / kEps0);
    std::printf(
        "[A3/A4 dustydiffuse 16^3] %s: L2 eps %.3e, S %.3e (ratio %.2f); N = 10 vs N = 1 max |d eps| / eps0 "
        "%.1e; S dust mass drift %.1e\n",
        name(disc), e1.l2, s1.l2, s1.l2 / e1.l2, dmax, s1.dust_drift);
    EXPECT_LT(dmax, 1e-10);
    EXPECT_LT(s1.l2, 5.0 * e1.l2);
    EXPECT_LT(s1.dust_drift, 1e-12);  // exact with the projection (dust.project_mass)
  }
  g_hfact = 1.2;
}

}  // namespace
