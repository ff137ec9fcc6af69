// Disc column of the dust settling test, PL15 sec. 4.4.1 eq. 53-57 (see
// include/mote/sph/settling_column.hpp).
#include "mote/sph/settling_column.hpp"

#include <cmath>

#include "mote/sph/external.hpp"
#include "mote/sph/lattice.hpp"

namespace mote::sph {

Real SettlingColumn::omega() const { return std::sqrt(gm / (r0 * r0 * r0)); }
Real SettlingColumn::scale_height() const { return h_over_r * r0; }
Real SettlingColumn::sound_speed() const { return scale_height() * omega(); }
Real SettlingColumn::orbit() const { return 2.0 * M_PI / omega(); }
Real SettlingColumn::gas_density(Real z) const {
  const Real H = scale_height();
  return rho0 * std::exp(-z * z / (2.0 * H * H));
}

std::unique_ptr<SphSystem> RelaxedColumn::make_system() const {
  auto sys = std::make_unique<SphSystem>(cfg, box);
  sys->set_particles(particles);
  sys->add_external_force(disc_vertical_gravity(column.gm, column.r0));  // eq. 53
  return sys;
}

RelaxedColumn relax_settling_column(const SettlingColumn& c, SphConfig cfg) {
  const Real H = c.scale_height();
  cfg.dim = 2;
  cfg.eos = EosType::Isothermal;
  cfg.cs_iso = c.sound_speed();
  Box box;
  box.dim = 2;
  box.lo[0] = -0.25;
  box.hi[0] = 0.25;
  box.periodic[0] = true;
  box.lo[1] = -3.0 * H;
  box.hi[1] = 3.0 * H;
  Lattice lat = hexagonal_lattice(box, (box.hi[0] - box.lo[0]) / c.nx);
  auto rho = [&c](Real z) { return c.gas_density(z); };
  stretch_map(lat, 1, box.lo[1], box.hi[1], rho);  // eq. 54
  const int n = lat.size();
  ParticleSetup s;
  s.dim = 2;
  s.x = lat.x;
  s.v.assign(2 * n, 0.0);
  s.m = equal_masses(n, lat.box.length(0) * integrate_profile(rho, box.lo[1], box.hi[1]));
  for (int i = 0; i < n; ++i) s.h.push_back(cfg.effective_hfact() * std::sqrt(s.m[i] / rho(lat.x[2 * i + 1])));

  cfg.damping = c.relax_damping;  // eq. 56
  SphSystem gas(cfg, lat.box);
  gas.set_particles(s);
  gas.add_external_force(disc_vertical_gravity(c.gm, c.r0));
  gas.initialise();
  gas.advance_to(c.relax_time);
  const Snapshot sn = gas.snapshot();
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 2; ++d) {
      s.x[2 * i + d] = sn.x(i, d);
      s.v[2 * i + d] = sn.v(i, d);
    }
    s.h[i] = sn.h(i);
  }
  cfg.damping = 0.0;
  return {c, cfg, gas.box(), s};
}

}  // namespace mote::sph
