// Laws and bookkeeping of the one-fluid SPH dust: drag times (PL15 eq. 7, 20;
// HPL18 eq. 14-18), the HPL18 Table 1 size grid (eq. 63), the time-step
// criteria (HPL18 eq. 43-44, PL15 eq. 16, 18), the negative-eps floor with
// mass accounting (PL15 sec. 4.4.2) and the [dust] deck table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mote/core/deck.hpp"
#include "mote/core/deck_schema.hpp"
#include "mote/dust/size_distribution.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "sph_dust_problems.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

TEST(SphDustLaws, StoppingTimesSingleSpecies) {
  // PL15 eq. 7: t_s = eps (1 - eps) rho / K.
  EXPECT_DOUBLE_EQ(ts_constant_k(0.3, 0.3, 2.0, 10.0), 0.3 * 0.7 * 2.0 / 10.0);
  // PL15 eq. 20: t_s = rho_grain s sqrt(pi gamma / 8) / (rho c_s).
  const double g = 5.0 / 3.0;
  EXPECT_NEAR(ts_epstein(3.0, 0.1, 2.0, 0.5, g), 3.0 * 0.1 * std::sqrt(M_PI * g / 8.0) / (2.0 * 0.5), 1e-15);
  // HPL18 eq. 44 limits: Courant with c~_s, and PL15 eq. 16 at large eps T_s.
  EXPECT_NEAR(dt_dust_combined(0.3, 0.01, 1.0, 0.5, 0.0), 0.3 * 0.01 / std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(dt_dust_combined(0.3, 0.01, 1.0, 0.5, 100.0) / dt_dust_diffusion(0.3, 0.01, 1.0, 100.0), 1.0, 1e-6);
}

TEST(SphDustLaws, PowerLawBinsReproduceTable1) {
  // HPL18 Table 1: p = 3.5, s_min = 0.0599 um, s_max = 1.67 mm, eps = 1/101.
  const auto b = mote::dust::power_law_bins(10, 5.99e-6, 0.167, 3.5, 1.0 / 101.0);
  const double s_ref[10] = {1.00e-5, 2.78e-5, 7.74e-5, 2.15e-4, 5.99e-4, 1.67e-3, 4.64e-3, 1.29e-2, 3.59e-2, 1.00e-1};
  const double e_ref[10] = {3.99e-5, 6.65e-5, 1.11e-4, 1.85e-4, 3.09e-4, 5.15e-4, 8.59e-4, 1.43e-3, 2.39e-3, 3.99e-3};
  double sum = 0.0;
  for (int j = 0; j < 10; ++j) {
    EXPECT_NEAR(b.size[j] / s_ref[j], 1.0, 5e-3) << j;
    EXPECT_NEAR(b.fraction[j] / e_ref[j], 1.0, 5e-3) << j;
    sum += b.fraction[j];
  }
  EXPECT_NEAR(sum, 1.0 / 101.0, 1e-15);
}

// N = 3 Epstein species (1e-3, 1e-2, 0.1; eps 0.01, 0.05, 0.1) on a uniform
// periodic 1D box of 50 particles, u = 1, gamma = 5/3.
SphSystem three_species_box(bool limit_ts) {
  SphConfig cfg;
  cfg.dim = 1;
  cfg.eos = EosType::Adiabatic;
  cfg.gamma = 5.0 / 3.0;
  Box box;
  box.dim = 1;
  box.lo[0] = 0.0;
  box.hi[0] = 1.0;
  box.periodic[0] = true;
  ParticleSetup s;
  s.dim = 1;
  for (int i = 0; i < 50; ++i) {
    s.x.push_back((i + 0.5) / 50);
    s.m.push_back(1.0 / 50);
    s.h.push_back(1.2 / 50);
    s.u.push_back(1.0);
  }
  SphSystem sys(cfg, box);
  sys.set_particles(s);
  DustSettings ds;
  ds.nspecies = 3;
  ds.drag = DragLaw::Epstein;
  ds.sizes = {1e-3, 1e-2, 1e-1};
  ds.rho_grain = 3.0;
  ds.eps = {0.01, 0.05, 0.1};
  ds.limit_ts = limit_ts;
  add_one_fluid_dust(sys, ds);
  sys.initialise();
  return sys;
}

// Device values of T_sj and tilde T_sj: T_sj from eq. 13-14 (with the
// limiter at most h / c_s, Ballabio et al. 2018), tilde T_sj from eq. 15 and
// the identity of eq. 18 with the times used.
void check_multigrain_times(bool limit_ts) {
  const SphSystem sys = three_species_box(limit_ts);
  const double gamma = 5.0 / 3.0, eps = 0.16;
  const double sizes[3] = {1e-3, 1e-2, 1e-1}, fractions[3] = {0.01, 0.05, 0.1};
  const OneFluidDust& d = *sys.module<OneFluidDust>();
  const IdOrder by_id(sys.particles().id);  // as the snapshot
  const auto ts = by_id(d.ts);
  const auto coef = by_id(d.coef);
  const auto ets = by_id(d.eps_ts);
  const auto dtot = by_id(d.d_tot);
  const Snapshot snap = sys.snapshot();
  const auto cs = by_id(sys.particles().cs);
  int capped = 0;
  for (int a = 0; a < 50; a += 7) {
    // Gas sound speed from P = (gamma - 1)(1 - eps) rho u (PL15 eq. 14): c_s^2 = gamma (gamma - 1) u.
    EXPECT_NEAR(cs(a), std::sqrt(gamma * (gamma - 1.0) * 1.0), 1e-12);
    double sum = 0.0;
    for (int j = 0; j < 3; ++j) {
      double t = 3.0 * sizes[j] * std::sqrt(M_PI * gamma / 8.0) / (snap.rho(a) * cs(a));
      if (limit_ts && t > snap.h(a) / cs(a)) {
        t = snap.h(a) / cs(a);
        ++capped;
      }
      EXPECT_NEAR(ts(a, j) / t, 1.0, 1e-12);
      sum += fractions[j] * t;
    }
    EXPECT_NEAR(ets(a) / sum, 1.0, 1e-12);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(coef(a, j), fractions[j] * (ts(a, j) - sum) / (1.0 - eps), 1e-14);
    EXPECT_NEAR(dtot(a) / sum, 1.0, 1e-12);  // HPL18 eq. 18
  }
  // h / c_s = 0.032 here: the limiter caps the 0.1 (t_s = 0.33) and 0.01 (0.033) species.
  EXPECT_EQ(capped, limit_ts ? 2 * 8 : 0);
}

TEST(SphDustLaws, EpsteinMultigrainTimes) { check_multigrain_times(false); }

TEST(SphDustLaws, StoppingTimeLimiterCapsAtHOverCs) { check_multigrain_times(true); }

// Dust added to a running (initialised) system is initialised there (SphSystem::add_module), and again by
// SphSystem::initialise (as SphSimulation's constructor calls it): the S variable's q = sqrt(eps) was taken
// twice, q = eps^(1/4) (eps 0.01 became 0.1).
TEST(SphDustLaws, DustAddedToARunningSystemKeepsItsFractionThroughASecondInitialise) {
  for (auto var : {DustVariable::Epsilon, DustVariable::SqrtRhoEps}) {
    SphConfig cfg;
    cfg.gamma = 5.0 / 3.0;
    DustSettings ds;
    ds.variable = var;
    ds.drag = DragLaw::ConstantK;
    ds.k_drag = {100.0};
    ds.eps = {0.01};
    const DustProblem prob = dustywave(DustyWave{}, cfg, ds);
    SphSystem sys(prob.cfg, prob.box);
    sys.set_particles(prob.particles);
    sys.initialise();
    add_one_fluid_dust(sys, prob.dust, {});
    sys.initialise();
    const auto e = sys.module<OneFluidDust>()->snapshot(sys.particles()).eps;
    double worst = 0.0;
    for (size_t i = 0; i < e.extent(0); ++i) worst = std::max(worst, std::fabs(e(i, 0) / 0.01 - 1));
    std::printf("[initialise twice] %s variable: max relative error of eps %.2e\n",
                var == DustVariable::Epsilon ? "eps" : "S", worst);
    EXPECT_LE(worst, 1e-14);
  }
}

// PL15 sec. 4.4.2: eps_j < 0 is set to zero and the removed mass is accounted.
TEST(SphDustLaws, NegativeFloorAccounting) {
  const int n = 6;
  Particles p;
  p.allocate(n, 1);
  Kokkos::deep_copy(p.m, 0.5);
  Kokkos::deep_copy(p.rho, 1.0);
  auto id = Kokkos::create_mirror_view(p.id);
  for (int i = 0; i < n; ++i) id(i) = i;
  Kokkos::deep_copy(p.id, id);
  DustSettings ds;
  ds.nspecies = 2;
  OneFluidDust d(ds, n, 1);
  d.set_eps({0.1, 0.2, 1e-6, 0.0, 0.3, 0.0, 2e-6, 1e-6, 0.0, 0.1, 0.05, 0.05}, p.id);
  d.initialise(p);
  auto dv = Kokkos::create_mirror_view(d.dvar);
  const double rates[12] = {-0.1, 0.1, -4e-5, 0.0, 0.2, -1e-5, 0.0, 0.0, -1e-4, 0.0, 0.0, 0.0};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2; ++j) dv(i, j) = rates[2 * i + j];
  Kokkos::deep_copy(d.dvar, dv);
  const double m0 = d.dust_mass(p);
  const double removed = d.kick(p, 0.1);
  // Negative after the kick: 1e-6 - 4e-6 = -3e-6, 0 - 1e-6, 0 - 1e-5.
  const double expect = 0.5 * (3e-6 + 1e-6 + 1e-5);
  EXPECT_NEAR(removed, expect, 1e-18);
  EXPECT_NEAR(d.floored_mass(), expect, 1e-18);
  auto e = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d.var);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_GE(e(i, j), 0.0);
  // Mass budget: before + sum m dt dvar = after - removed... i.e. after = before + change + removed.
  double change = 0.0;
  for (double r : rates) change += 0.5 * 0.1 * r;
  EXPECT_NEAR(d.dust_mass(p), m0 + change + expect, 1e-15);
}

// PL15 eq. 18 warning count: eps t_s > C h / c_s at weak drag, none at strong drag, and
// with the stopping-time limiter still where the uncapped t_s fails the test.
TEST(SphDustLaws, TerminalVelocityWarning) {
  mote::sph::testing::DustyWaveSetup w;
  w.K = 1.0;
  SphSystem weak = mote::sph::testing::make_dustywave(w);
  EXPECT_EQ(weak.module<OneFluidDust>()->tva_violations(), 100);
  w.K = 1000.0;
  SphSystem strong = mote::sph::testing::make_dustywave(w);
  EXPECT_EQ(strong.module<OneFluidDust>()->tva_violations(), 0);
  // With the stopping-time limiter the check still counts with t_s before the cap: eps = 0.05
  // and K = 0.1 give eps t_s ~ 0.025 against C h / c_s ~ 0.004, while the capped eps h / c_s
  // lies below it (eps < C_cour).
  w.K = 0.1;
  w.eps = 0.05;
  w.limit_ts = true;
  SphSystem capped = mote::sph::testing::make_dustywave(w);
  EXPECT_EQ(capped.module<OneFluidDust>()->tva_violations(), 100);
}

TEST(SphDustLaws, DeckTable) {
  mote::core::DeckSchema schema;
  DustSettings::declare(schema);
  const auto d = mote::core::Deck::parse(
      "[dust]\nspecies = 10\ndrag = \"epstein\"\nsizes_from = \"power_law\"\nrho_grain = 3.0\n"
      "discretisation = \"first_derivatives\"\nvariable = \"sqrt_rho_eps\"\nenergy = \"u_tilde\"\n"
      "pdv = \"gas\"\n",
      "t.toml", schema);
  const DustSettings s = DustSettings::from_deck(d);
  EXPECT_EQ(s.nspecies, 10);
  EXPECT_EQ(s.drag, DragLaw::Epstein);
  EXPECT_EQ(s.discretisation, DustDiscretisation::FirstDerivatives);
  EXPECT_EQ(s.variable, DustVariable::SqrtRhoEps);
  EXPECT_EQ(s.energy, DustEnergy::UTilde);
  EXPECT_EQ(s.pdv, DustPdV::Gas);
  ASSERT_EQ(s.sizes.size(), 10u);
  EXPECT_NEAR(s.sizes[0] / 1e-5, 1.0, 5e-3);
  EXPECT_NEAR(s.eps[9] / 3.99e-3, 1.0, 5e-3);
  // A per-species list of the wrong length is a deck error, with file and line, found by validation itself.
  try {
    mote::core::Deck::parse("[dust]\nspecies = 3\nK = [1.0, 2.0]\n", "t.toml", schema);
    ADD_FAILURE() << "dust.K with 2 entries for 3 species accepted";
  } catch (const mote::core::DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("t.toml:3: key 'dust.K': needs 1 or 3 entries (dust.species = 3 (t.toml:2))"),
              std::string::npos)
        << e.what();
  }
  EXPECT_ANY_THROW(mote::core::Deck::parse("[dust]\npdv = \"total\"\n", "t.toml", schema));
  // One-fluid fractions leave gas (1 - sum eps_j > 1e-9): ten of 0.1 (1 - 1.1e-16) and [0.5, 0.6] are refused,
  // [0.5, 0.3, 0.19] accepted; two-fluid's eps are not fractions of one fluid.
  for (const char* eps : {"species = 10\neps = [0.1]\n", "species = 2\neps = [0.5, 0.6]\n"}) {
    try {
      mote::core::Deck::parse(std::string("[dust]\n") + eps, "t.toml", schema);
      ADD_FAILURE() << eps << " accepted";
    } catch (const mote::core::DeckError& e) {
      EXPECT_NE(std::string(e.what()).find("key 'dust.eps': sums to "), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(mote::core::Deck::parse("[dust]\nspecies = 3\neps = [0.5, 0.3, 0.19]\n", "t.toml", schema));
  EXPECT_NO_THROW(
      mote::core::Deck::parse("[dust]\nmethod = \"two-fluid\"\nspecies = 2\neps = [0.6]\n", "t.toml", schema));
}

}  // namespace

namespace {

// dust.pdv = "gas" changes the PdV work, which an isothermal gas does not have.
TEST(SphDustLaws, GasPdVNeedsAdiabaticGas) {
  for (auto eos : {EosType::Isothermal, EosType::Adiabatic}) {
    SphConfig cfg;
    cfg.dim = 1;
    cfg.eos = eos;
    Box box;
    box.dim = 1;
    box.periodic[0] = true;
    const Lattice lat = cubic_lattice(box, 0.05);
    ParticleSetup s;
    s.dim = 1;
    s.x = lat.x;
    s.v.assign(lat.size(), 0.0);
    s.m = equal_masses(lat.size(), 1.0);
    s.h.assign(lat.size(), 1.2 * lat.dx);
    s.u.assign(lat.size(), 1.0);
    SphSystem sys(cfg, lat.box);
    sys.set_particles(s);
    DustSettings ds;
    ds.pdv = DustPdV::Gas;
    if (eos == EosType::Isothermal) {
      EXPECT_THROW(add_one_fluid_dust(sys, ds), std::invalid_argument);
    } else {
      EXPECT_NO_THROW(add_one_fluid_dust(sys, ds));
    }
  }
}

}  // namespace
