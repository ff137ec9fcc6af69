// Accelerated dustybox set-up and exact solution (LAB15 sec. 3, eq. 31-32);
// see include/mote/setups/dustybox.hpp.
#include "mote/setups/dustybox.hpp"

#include <cmath>
#include <stdexcept>

#include "mote/core/loops.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/sph/two_fluid_dust.hpp"

namespace mote::sph {

void apply_dust_acceleration(Particles& p, Real a_dust) {
  const auto a = p.a;
  const auto type = p.type;
  par_for(
      "sph::dust_acceleration", 0, p.n, KOKKOS_LAMBDA(int i) {
        if (type(i) != kGas) a(i, 0) += a_dust;
      });
}

ExternalForce dust_acceleration(Real a) {
  return [a](Particles& p, const RealView2&, Real) { apply_dust_acceleration(p, a); };
}

std::unique_ptr<SphSystem> make_dustybox(const DustyBox& b, SphConfig cfg, const DustSettings& dust) {
  if (dust.method != DustMethod::TwoFluid || dust.nspecies < 1)
    throw std::invalid_argument("dustybox: needs dust.method = \"two-fluid\" with at least one species");
  if (b.n < 4 || !(b.eps > 0.0) || !(b.hi > b.lo))
    throw std::invalid_argument("dustybox: needs n >= 4, eps > 0 and hi > lo");
  cfg.dim = b.dim;
  Box box;
  box.dim = b.dim;
  for (int d = 0; d < b.dim; ++d) {
    box.lo[d] = b.lo;
    box.hi[d] = b.hi;
    box.periodic[d] = true;
  }
  const Real dx = (b.hi - b.lo) / b.n;
  const Lattice lat = cubic_lattice(box, dx);
  const int np = lat.size();
  const Real volume = std::pow(b.hi - b.lo, b.dim);
  const Real m_gas = volume * b.rho_gas / np, m_dust = b.eps * m_gas;
  const Real h = cfg.effective_hfact() * dx;
  const int ns = dust.nspecies;
  ParticleSetup s;
  s.dim = b.dim;
  for (int phase = 0; phase <= ns; ++phase) {  // the gas, then species j = phase - 1
    const Real shift = dx * phase / (ns + 1);  // one species: half a spacing
    for (int i = 0; i < np; ++i) {
      for (int d = 0; d < b.dim; ++d) {
        s.x.push_back(lat.x[i * b.dim + d] + shift);
        s.v.push_back(phase > 0 && d == 0 ? b.v_dust : 0.0);
      }
      s.m.push_back(phase > 0 ? m_dust : m_gas);
      s.h.push_back(h);
      s.u.push_back(phase > 0 ? 0.0 : b.u_gas);
      s.type.push_back(phase > 0 ? kDust + phase - 1 : kGas);
    }
  }
  auto sys = std::make_unique<SphSystem>(cfg, lat.box);
  sys->set_particles(s);
  add_two_fluid_dust(*sys, dust);
  sys->add_external_force(dust_acceleration(b.a_dust));
  return sys;
}

Real dustybox_dust_velocity(Real t, Real v0, Real a_dust, Real eps, Real ts) {
  const Real xi = -std::expm1(-t / ts) / (1.0 + eps);
  return v0 * (1.0 - xi) + (eps * t / (1.0 + eps) + xi * ts) * a_dust;
}

}  // namespace mote::sph
