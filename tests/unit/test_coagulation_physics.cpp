// Collision physics of RBO24 sec. 5: fragmentation probability (eq. 62),
// remnants (eq. 68), fragment power law (eq. 67), relative velocities
// (eq. 58-60 with the Ormel & Cuzzi 2007 closed forms and the St* fit), mass grid.
#include <gtest/gtest.h>

#include <cmath>

#include "mote/coagulation/fragmentation.hpp"
#include "mote/coagulation/mass_grid.hpp"
#include "mote/coagulation/relative_velocity.hpp"

namespace coag = mote::coagulation;

TEST(CoagulationPhysics, FragmentationProbability) {
  EXPECT_EQ(coag::fragmentation_probability(0.0, 100.0), 0.0);
  EXPECT_LT(coag::fragmentation_probability(10.0, 100.0), 1e-60);
  EXPECT_NEAR(coag::fragmentation_probability(100.0, 100.0), 2.5 * std::exp(-1.5), 1e-15);
  EXPECT_NEAR(coag::fragmentation_probability(1e5, 100.0), 1.0, 1e-10);
  double prev = 0;
  for (double dv = 1; dv < 1e4; dv *= 1.5) {  // monotonic in dv
    const double p = coag::fragmentation_probability(dv, 100.0);
    EXPECT_GE(p, prev);
    prev = p;
  }
}

TEST(CoagulationPhysics, RemnantAndFragments) {
  EXPECT_DOUBLE_EQ(coag::remnant_mass(10.0, 1.0, 1.0), 9.0);
  EXPECT_DOUBLE_EQ(coag::remnant_mass(1.0, 10.0, 2.0), 8.0);
  EXPECT_EQ(coag::remnant_mass(3.0, 3.0, 1.0), 0.0);  // equal masses: all fragments
  EXPECT_EQ(coag::remnant_mass(10.0, 6.0, 2.0), 0.0);
  // eq. 67 with eta = 11/6: cumulative fraction m^(1/6) law.
  const double f = coag::fragment_mass_fraction_below(64.0, 1.0, 4096.0, 11.0 / 6.0);
  EXPECT_NEAR(f, (2.0 - 1.0) / (4.0 - 1.0), 1e-14);
  EXPECT_NEAR(coag::fragment_mass_fraction_below(100.0, 1.0, 1e4, 2.0), 0.5, 1e-14);
}

TEST(CoagulationPhysics, BoundaryStokesFitAndOrmelCuzziLimits) {
  EXPECT_NEAR(coag::boundary_stokes_fit(1e-8) / 1e-8, 1.6, 1e-3);  // OC07 y* = 1.6
  EXPECT_DOUBLE_EQ(coag::boundary_stokes_fit(1.0), 1.0);
  EXPECT_DOUBLE_EQ(coag::boundary_stokes_fit(3.0), 1.0);
  // Intermediate regime, St2 -> 0 (OC07 eq. 28 with eps = 0): V^2 = (2 y* - 1 + 2/(1+y*)) St1.
  const double st = 1e-3, y = coag::boundary_stokes_fit(st) / st;
  const double v2 = coag::turbulent_vrel2(st, 1e-12, 0.0);
  EXPECT_NEAR(v2 / st, 2 * y - 1 + 2 / (1 + y), 0.01);
  EXPECT_NEAR(v2 / st, 2.97, 0.02);
  // Equal particles in the intermediate regime: OC07 eq. 28 with eps = 1.
  const double v2eq = coag::turbulent_vrel2(st, st, 0.0);
  EXPECT_NEAR(v2eq / st, 2 * y - 2 + (1.0 / (1 + y) + 1.0 / (y + 1)), 0.02);
  // Tightly coupled pairs below the Kolmogorov scale (OC07 eq. 27, tiny-particle
  // limit): V^2 = (St1 - St2)^2 / Re^-1/2, here 1e-14; and symmetric.
  EXPECT_NEAR(coag::turbulent_vrel2(1e-9, 2e-9, 1e-4) / 1e-14, 1.0, 1e-3);  // O(St / Re^-1/2, Re^-1/2) terms
  EXPECT_DOUBLE_EQ(coag::turbulent_vrel2(0.3, 0.01, 1e-4), coag::turbulent_vrel2(0.01, 0.3, 1e-4));
  // Heavy-particle limit (OC07 eq. 29, both grains in class I eddies when St* = 1):
  // V^2 = 1 / (1 + St1) + 1 / (1 + St2), up to O(Re^-1/2) = 1e-4 here.
  EXPECT_NEAR(coag::turbulent_vrel2(1e3, 1e-3, 1e-4), 1.0 / (1.0 + 1e3) + 1.0 / (1.0 + 1e-3), 1e-3);
  EXPECT_NEAR(coag::turbulent_vrel2(1e3, 2e3, 1e-4), 1.0 / (1.0 + 1e3) + 1.0 / (1.0 + 2e3), 1e-5);
}

TEST(CoagulationPhysics, BrownianMotion) {
  const double kT = 1.380649e-16 * 100.0, m = 1e-12;
  EXPECT_NEAR(std::sqrt(coag::brownian_dv2(m, m, kT)), std::sqrt(16.0 * kT / (M_PI * m)), 1e-12);
}

TEST(CoagulationPhysics, MassGrid) {
  const auto g = coag::MassGrid::from_sizes(1e-5, 1.0, 151, 1.6);
  EXPECT_EQ(g.size(), 151);
  EXPECT_NEAR(g.grain_size(0), 1e-5, 1e-18);
  EXPECT_NEAR(g.grain_size(150), 1.0, 1e-13);
  EXPECT_NEAR(g.bins_per_mass_decade(), 10.0, 1e-9);
  EXPECT_TRUE(g.resolution_warning().empty());
  for (int k = 0; k < g.size(); ++k) {
    EXPECT_LT(g.edge(k), g.mass(k));
    EXPECT_GT(g.edge(k + 1), g.mass(k));
    EXPECT_NEAR(g.edge(k + 1) / g.edge(k), g.mass(1) / g.mass(0), 1e-10);
  }
  EXPECT_FALSE(coag::MassGrid::from_masses(1.0, 1e6, 30).resolution_warning().empty());  // 5.8 per decade
  EXPECT_THROW(coag::MassGrid::from_masses(1.0, 0.5, 30), std::invalid_argument);
}
