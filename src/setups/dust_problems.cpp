// Set-ups of the one-fluid dust problems of PL15 sec. 4.1-4.3 (see
// include/mote/setups/dust_problems.hpp).
#include "mote/setups/dust_problems.hpp"

#include <cmath>

#include "mote/core/deck.hpp"
#include "mote/core/log.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/sph/one_fluid_dust.hpp"

namespace mote::sph {

namespace {

Real total_eps(const DustSettings& ds) {
  Real e = 0.0;
  for (int j = 0; j < ds.nspecies; ++j) e += ds.species_value(ds.eps, j);
  return e;
}

/// 1D adiabatic problem in [lo, hi) periodic.
DustProblem tube(SphConfig cfg, const DustSettings& dust, Real lo, Real hi) {
  DustProblem pr;
  cfg.dim = 1;
  cfg.eos = EosType::Adiabatic;
  pr.cfg = cfg;
  pr.dust = dust;
  pr.box.dim = 1;
  pr.box.lo[0] = lo;
  pr.box.hi[0] = hi;
  pr.box.periodic[0] = true;
  pr.particles.dim = 1;
  return pr;
}

}  // namespace

void declare_dust_problem(core::DeckSchema& schema, const std::string& problem, DragLaw drag, bool uniform_eps) {
  DustSettings::declare(schema);
  schema.rule(requires_dust_method(problem, {"diffusion", "multigrain"}));
  const std::string want = drag == DragLaw::ConstantK ? "constant_K"
                           : drag == DragLaw::Epstein ? "epstein"
                                                      : "constant_ts";
  schema.rule([=](const core::Deck& d, core::DeckCheck& check) {
    if (!d.has_table("dust")) return check.fail_missing_table("dust", problem + " needs it");
    if (d.string("dust.drag") != want)
      check.fail("dust.drag", problem + " needs \"" + want + "\" (the reference solution assumes it)");
    // The sum needs consistent per-species lists (DustSettings' own rule, run before this one).
    if (!uniform_eps || !check.errors().empty()) return;
    const Real e = total_eps(DustSettings::from_deck(d));
    if (!(e > 0.0 && e < 1.0)) check.fail("dust.eps", logging::cat("must sum to a value in (0, 1), got ", e));
  });
}

std::unique_ptr<SphSystem> DustProblem::make_system() const {
  ParticleSetup s = particles;
  if (dust.energy == DustEnergy::UTilde) {
    // u~ = (1 - eps) u (HPL18 sec. 2.1.3).
    const int ns = dust.nspecies;
    for (int i = 0; i < s.size(); ++i) {
      Real e = 0.0;
      for (int j = 0; j < ns; ++j) e += eps.empty() ? dust.species_value(dust.eps, j) : eps[i * ns + j];
      s.u[i] *= 1.0 - e;
    }
  }
  auto sys = std::make_unique<SphSystem>(cfg, box);
  sys->set_particles(s);
  add_one_fluid_dust(*sys, dust, eps);
  return sys;
}

DustProblem dustywave(const DustyWave& w, SphConfig cfg, const DustSettings& dust) {
  const Real amp = w.amplitude, kx = 2.0 * M_PI, rhog0 = 1.0, eps0 = total_eps(dust);
  const Real rho0 = rhog0 / (1.0 - eps0);
  const Real P0 = rhog0 / cfg.gamma;  // c_s^2 = gamma P0 / rho_g0 = 1
  const Real u0 = P0 / ((cfg.gamma - 1.0) * rhog0);
  DustProblem pr = tube(cfg, dust, 0.0, 1.0);
  ParticleSetup& s = pr.particles;
  const Real dx = 1.0 / w.n;
  for (int i = 0; i < w.n; ++i) {
    // Equal masses: M(x) = rho0 (x + amp (1 - cos kx) / k) = rho0 x0.
    const Real x0 = (i + 0.5) * dx;
    Real x = x0;
    for (int it = 0; it < 50; ++it) {
      const Real f = x + amp * (1.0 - std::cos(kx * x)) / kx - x0;
      x -= f / (1.0 + amp * std::sin(kx * x));
    }
    s.x.push_back(x);
    s.v.push_back(amp * std::sin(kx * x));
    s.m.push_back(rho0 * dx);
    s.h.push_back(cfg.effective_hfact() * dx);
    s.u.push_back(u0 + P0 / (rhog0 * rhog0) * rhog0 * amp * std::sin(kx * x));
  }
  return pr;
}

DustProblem dustyshock(const DustyShock& sh, SphConfig cfg, const DustSettings& dust) {
  const Real eps0 = total_eps(dust), g1 = cfg.gamma - 1.0;
  DustProblem pr = tube(cfg, dust, -1.0, 1.0);
  ParticleSetup& s = pr.particles;
  const Real dxl = sh.dx_left, dxr = dxl * sh.rhog_left / sh.rhog_right;
  const int nl = static_cast<int>(std::lround(1.0 / dxl)), nr = static_cast<int>(std::lround(1.0 / dxr));
  auto add = [&](Real x0, Real dx, int n, Real rhog, Real P) {
    for (int i = 0; i < n; ++i) {
      s.x.push_back(x0 + (i + 0.5) * dx);
      s.v.push_back(0.0);
      s.m.push_back(rhog / (1.0 - eps0) * dx);
      s.h.push_back(cfg.effective_hfact() * dx);
      s.u.push_back(P / (g1 * rhog));
    }
  };
  add(-1.0, 1.0 / nl, nl, sh.rhog_left, sh.P_left);
  add(0.0, 1.0 / nr, nr, sh.rhog_right, sh.P_right);
  return pr;
}

DustProblem dustydiffuse(const DustyDiffuse& d, SphConfig cfg, const DustSettings& dust) {
  DustProblem pr;
  cfg.dim = 3;
  cfg.eos = EosType::Isothermal;
  pr.cfg = cfg;
  pr.dust = dust;
  Box box;
  box.dim = 3;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = -0.5;
    box.hi[k] = 0.5;
    box.periodic[k] = true;
  }
  const Lattice lat = d.close_packed ? close_packed_lattice(box, 1.0 / d.n) : cubic_lattice(box, 1.0 / d.n);
  pr.box = lat.box;
  const int np = lat.size(), ns = dust.nspecies;
  Real vol = 1.0;
  for (int k = 0; k < 3; ++k) vol *= lat.box.length(k);
  ParticleSetup& s = pr.particles;
  s.dim = 3;
  s.x = lat.x;
  s.v.assign(lat.x.size(), 0.0);
  s.m.assign(np, vol / np);  // rho = 1
  s.h.assign(np, cfg.effective_hfact() * std::cbrt(vol / np));
  s.u.assign(np, 0.0);
  for (int i = 0; i < np; ++i) {
    const Real* x = &lat.x[3 * i];
    const Real e = dustydiffuse_eps(d, 0.0, std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), 0.0);
    for (int j = 0; j < ns; ++j) pr.eps.push_back(e / ns);
  }
  return pr;
}

Real dustydiffuse_eps(const DustyDiffuse& d, Real eta, Real r, Real t) {
  const Real B = d.r_c * d.r_c / d.eps0, A = d.eps0 * std::pow(B, 0.6);
  const Real tau = 10.0 * eta * t + B;
  return std::max(Real(0.0), A * std::pow(std::fabs(tau), -0.6) - r * r / tau);
}

}  // namespace mote::sph
