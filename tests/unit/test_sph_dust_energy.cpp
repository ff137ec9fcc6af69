// Total energy of the one-fluid dust method, E = sum m (v^2/2 + (1 - eps) u)
// (PL15 eq. 40, HPL18 eq. 52), is conserved exactly by the semi-discrete
// equations (PL15 eq. 41-42, HPL18 eq. 53-56) for every choice of dust
// variable, discretisation, energy variable, pair coefficient and PdV form
// (dust.pdv = "gas": div v_g plus drag heating). Checked on the instantaneous
// rate dE/dt = sum m (v . a + (1 - eps) du/dt - u sum_j deps_j/dt) of a
// non-linear state (a dusty shock tube after 0.05, three species with
// different drag, viscosity and conductivity on), which must vanish to
// round-off; it is a sum of terms of either sign that are 1e10 times larger.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mote/setups/dust_problems.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_system.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

struct Rate {
  double rate = 0.0, scale = 0.0;
};

Rate energy_rate(DustVariable var, DustDiscretisation disc, DustEnergy en, DustFlux flux, DustPdV pdv) {
  SphConfig cfg;
  cfg.kernel = KernelType::M4;
  cfg.gamma = 5.0 / 3.0;
  DustSettings ds;
  ds.nspecies = 3;
  ds.variable = var;
  ds.discretisation = disc;
  ds.energy = en;
  ds.flux = flux;
  ds.pdv = pdv;
  ds.drag = DragLaw::ConstantK;
  ds.k_drag = {20.0, 50.0, 100.0};
  ds.eps = {0.1, 0.15, 0.25};
  DustyShock shock;
  shock.dx_left = 0.004;
  auto sys = dustyshock(shock, cfg, ds).make_system();
  sys->initialise();
  sys->advance_to(0.05);
  Particles& p = sys->particles();
  OneFluidDust& dust = *sys->module<OneFluidDust>();
  Kokkos::deep_copy(dust.var_pred, dust.var);
  sys->compute_accelerations(p.v, p.u);
  const auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.m);
  const auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.v);
  const auto a = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.a);
  const auto dudt = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.dudt);
  const auto q = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dust.var);
  const auto dq = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dust.dvar);
  const auto eps = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dust.eps_tot);
  const auto ugas = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dust.uloc);
  Rate r;
  for (int i = 0; i < p.n; ++i) {
    const double kin = v(i, 0) * a(i, 0);
    // d/dt of (1 - eps) u: (1 - eps) du/dt - u deps/dt, or du~/dt itself.
    double th = dudt(i);
    if (en == DustEnergy::U) {
      double deps = 0.0;
      for (int j = 0; j < ds.nspecies; ++j) deps += var == DustVariable::Epsilon ? dq(i, j) : 2.0 * q(i, j) * dq(i, j);
      th = (1.0 - eps(i)) * dudt(i) - ugas(i) * deps;
    }
    r.rate += m(i) * (kin + th);
    r.scale += m(i) * std::fabs(kin);
  }
  return r;
}

TEST(SphDustEnergy, SemiDiscreteRateVanishes) {
  for (auto pdv : {DustPdV::Barycentric, DustPdV::Gas}) {
    for (auto var : {DustVariable::Epsilon, DustVariable::SqrtRhoEps}) {
      for (auto disc : {DustDiscretisation::SecondDerivatives, DustDiscretisation::FirstDerivatives}) {
        for (auto en : {DustEnergy::U, DustEnergy::UTilde}) {
          for (auto flux : {DustFlux::Arithmetic, DustFlux::DonorLimited}) {
            const bool limited_applies = var == DustVariable::Epsilon && disc == DustDiscretisation::SecondDerivatives;
            if (flux == DustFlux::DonorLimited && !limited_applies) continue;
            const Rate r = energy_rate(var, disc, en, flux, pdv);
            std::printf("[A7 energy rate] pdv %s, %s, %s, %s%s: dE/dt = %.2e of sum m |v . a| = %.3e\n",
                        pdv == DustPdV::Gas ? "gas" : "barycentric", var == DustVariable::Epsilon ? "eps" : "S",
                        disc == DustDiscretisation::SecondDerivatives ? "second derivatives" : "first derivatives",
                        en == DustEnergy::U ? "u" : "u~", flux == DustFlux::DonorLimited ? ", donor-limited" : "",
                        r.rate / r.scale, r.scale);
            EXPECT_LT(std::fabs(r.rate), 1e-12 * r.scale);
          }
        }
      }
    }
  }
}

}  // namespace
