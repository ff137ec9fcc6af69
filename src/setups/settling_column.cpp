// Disc column of the dust settling test, PL15 sec. 4.4.1 eq. 53-57 (see
// include/mote/setups/settling_column.hpp).
#include "mote/setups/settling_column.hpp"

#include <cmath>
#include <stdexcept>

#include "mote/setups/lattice.hpp"
#include "mote/sph/external.hpp"

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

std::unique_ptr<SphSystem> RelaxedColumn::make_two_fluid_system(const std::vector<Real>& eps) const {
  Real eps_total = 0.0;
  for (const Real e : eps) {
    if (!(e > 0.0)) throw std::invalid_argument("settling column: every species' dust fraction must be positive");
    eps_total += e;
  }
  if (eps.empty() || !(eps_total < 1.0))
    throw std::invalid_argument("settling column: the dust fractions must sum to less than 1");
  ParticleSetup s = particles;
  const int n = particles.size(), dim = particles.dim, species = static_cast<int>(eps.size());
  s.type.assign(n, kGas);
  s.u.resize(n, 0.0);  // isothermal: the set-up may leave u empty
  for (int i = 0; i < n; ++i) s.m[i] *= 1.0 - eps_total;
  for (int j = 0; j < species; ++j) {
    const Real shift = (j + 1.0) / (species + 1.0) * column.width / column.nx;
    for (int i = 0; i < n; ++i) {
      for (int d = 0; d < dim; ++d) {
        s.x.push_back(particles.x[dim * i + d] + (d == 0 ? shift : 0.0));  // wrapped by set_particles
        s.v.push_back(0.0);
      }
      s.m.push_back(eps[j] * particles.m[i]);
      s.h.push_back(particles.h[i]);
      s.u.push_back(0.0);
      s.type.push_back(kDust + j);
    }
  }
  auto sys = std::make_unique<SphSystem>(cfg, box);
  sys->set_particles(s);
  sys->add_external_force(disc_vertical_gravity(column.gm, column.r0));  // eq. 53, on gas and dust
  return sys;
}

RelaxedColumn relax_settling_column(const SettlingColumn& c, SphConfig cfg,
                                    const std::function<void(const SphSystem&)>& after_step) {
  if (c.dim != 2 && c.dim != 3) throw std::invalid_argument("settling column: dim must be 2 or 3");
  if (!(c.z_max > 0.0)) throw std::invalid_argument("settling column: z_max must be positive");
  const Real H = c.scale_height();
  const int dim = c.dim, zax = dim - 1;
  cfg.dim = dim;
  cfg.eos = EosType::Isothermal;
  cfg.cs_iso = c.sound_speed();
  Box box;
  box.dim = dim;
  for (int d = 0; d < zax; ++d) {
    box.lo[d] = -0.5 * c.width;
    box.hi[d] = 0.5 * c.width;
    box.periodic[d] = true;
  }
  box.lo[zax] = -c.z_max * H;
  box.hi[zax] = c.z_max * H;
  const Real dx = c.width / c.nx;
  Lattice lat = dim == 2 ? hexagonal_lattice(box, dx) : close_packed_lattice(box, dx);
  auto rho = [&c](Real z) { return c.gas_density(z); };
  stretch_map(lat, zax, box.lo[zax], box.hi[zax], rho);  // eq. 54
  const int n = lat.size();
  ParticleSetup s;
  s.dim = dim;
  s.x = lat.x;
  s.v.assign(static_cast<std::size_t>(dim) * n, 0.0);
  Real area = 1.0;
  for (int d = 0; d < zax; ++d) area *= lat.box.length(d);
  s.m = equal_masses(n, area * integrate_profile(rho, box.lo[zax], box.hi[zax]));
  for (int i = 0; i < n; ++i)
    s.h.push_back(cfg.effective_hfact() * std::pow(s.m[i] / rho(lat.x[dim * i + zax]), 1.0 / dim));

  cfg.damping = c.relax_damping;  // eq. 56
  SphSystem gas(cfg, lat.box);
  gas.set_particles(s);
  gas.add_external_force(disc_vertical_gravity(c.gm, c.r0));
  gas.initialise();
  gas.advance_to(c.relax_time, after_step);
  const Snapshot sn = gas.snapshot();
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) {
      s.x[dim * i + d] = sn.x(i, d);
      s.v[dim * i + d] = sn.v(i, d);
    }
    s.h[i] = sn.h(i);
  }
  cfg.damping = 0.0;
  return {c, cfg, gas.box(), s};
}

}  // namespace mote::sph
