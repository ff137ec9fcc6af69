// Kick-drift-kick leapfrog driver of the SPH engine (see sph_system.hpp).
#include "mote/sph/sph_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/sph/density.hpp"
#include "mote/sph/forces.hpp"
#include "mote/sph/timestep.hpp"

namespace mote::sph {

namespace {

/// Drift after the first half kick, predict v and u to the end of the step,
/// and h from dh/dt = h div v / d (continuity equation, PL15 eq. 10) as the
/// starting guess of the h-rho iteration.
void drift(const Particles& p, bool energy, Real dt) {
  const int dim = p.dim;
  const auto x = p.x;
  const auto v = p.v;
  const auto a = p.a;
  const auto vpred = p.vpred;
  const auto u = p.u;
  const auto upred = p.upred;
  const auto dudt = p.dudt;
  const auto h = p.h;
  const auto divv = p.divv;
  const Real hdt = 0.5 * dt;
  par_for(
      "sph::drift", 0, p.n, KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < dim; ++d) {
          x(i, d) += dt * v(i, d);  // wrapped into the box at the next list rebuild
          vpred(i, d) = v(i, d) + hdt * a(i, d);
        }
        h(i) *= math::exp(dt * divv(i) / dim);
        upred(i) = energy ? u(i) + hdt * dudt(i) : u(i);
      });
}

/// Half kick with the current accelerations (before the drift and after the new forces).
void kick(const Particles& p, bool energy, Real hdt) {
  const int dim = p.dim;
  const auto v = p.v;
  const auto a = p.a;
  const auto u = p.u;
  const auto dudt = p.dudt;
  par_for(
      "sph::kick", 0, p.n, KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < dim; ++d) v(i, d) += hdt * a(i, d);
        if (energy) u(i) += hdt * dudt(i);
      });
}

}  // namespace

SphSystem::SphSystem(const SphConfig& cfg, const Box& box) : cfg_(cfg), box_(box) {
  if (cfg_.dim < 1 || cfg_.dim > 3) throw std::invalid_argument("sph: dimension must be 1, 2 or 3");
  box_.dim = cfg_.dim;
}

void SphSystem::set_particles(const ParticleSetup& s) {
  const int n = s.size();
  const int dim = cfg_.dim;
  if (s.dim != dim) throw std::invalid_argument("sph: particle set-up dimension differs from the configuration");
  if (n <= 0 || static_cast<int>(s.x.size()) != n * dim || static_cast<int>(s.h.size()) != n) {
    throw std::invalid_argument("sph: particle set-up needs x (n*dim), m (n) and h (n)");
  }
  const auto sized = [n](std::size_t size, int per) { return size == 0 || size == static_cast<std::size_t>(n) * per; };
  if (!sized(s.v.size(), dim) || !sized(s.u.size(), 1) || !sized(s.type.size(), 1))
    throw std::invalid_argument("sph: particle set-up v (n*dim), u (n) and type (n) must be empty or complete");
  p_.allocate(n, dim);
  auto x = Kokkos::create_mirror_view(p_.x);
  auto v = Kokkos::create_mirror_view(p_.v);
  auto m = Kokkos::create_mirror_view(p_.m);
  auto h = Kokkos::create_mirror_view(p_.h);
  auto u = Kokkos::create_mirror_view(p_.u);
  auto type = Kokkos::create_mirror_view(p_.type);
  auto id = Kokkos::create_mirror_view(p_.id);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) {
      x(i, d) = box_.wrap(s.x[i * dim + d], d);
      v(i, d) = s.v.empty() ? 0.0 : s.v[i * dim + d];
    }
    m(i) = s.m[i];
    h(i) = s.h[i];
    u(i) = s.u.empty() ? 0.0 : s.u[i];
    type(i) = s.type.empty() ? kGas : s.type[i];
    id(i) = i;
  }
  Kokkos::deep_copy(p_.x, x);
  Kokkos::deep_copy(p_.v, v);
  Kokkos::deep_copy(p_.m, m);
  Kokkos::deep_copy(p_.h, h);
  Kokkos::deep_copy(p_.u, u);
  Kokkos::deep_copy(p_.type, type);
  Kokkos::deep_copy(p_.id, id);
  Kokkos::deep_copy(p_.alpha, cfg_.alpha);
  Kokkos::deep_copy(p_.omega, 1.0);
  divv_old_ = RealView1("sph::divv_old", n);
  nl_ = NeighbourList();
  modules_.clear();
  gas_forces_ = nullptr;
  time_ = 0.0;
  dt_next_ = 0.0;
  steps_ = 0;
}

void SphSystem::add_module(std::shared_ptr<SphModule> module) {
  if (p_.n == 0) throw std::runtime_error("sph: add_module() before set_particles()");
  const std::string group = module->exclusive_group();
  for (const auto& m : modules_)
    if (!group.empty() && m->exclusive_group() == group)
      throw std::invalid_argument("sph: " + module->name() + " and " + m->name() + " are both a " + group +
                                  ": one per run");
  if (module->replaces_gas_forces()) {
    if (gas_forces_)
      throw std::invalid_argument("sph: " + module->name() + " and " + gas_forces_->name() +
                                  " both replace the gas forces: one dust method per run");
    gas_forces_ = module.get();
  }
  modules_.push_back(std::move(module));
  if (dt_next_ > 0.0) {  // added to a running (e.g. relaxed) system
    modules_.back()->initialise(*this);
    compute_accelerations(p_.v, p_.u);
    dt_next_ = timestep();
  }
}

void SphSystem::rebuild_neighbours() {
  // Host callback of the build: the particles move into cell order.
  nl_.build(p_, box_, cfg_.kernel, cfg_.skin, [this](const View<int*>& order) { reorder_particles(order); });
}

void SphSystem::reorder_particles(const View<int*>& order) {
  reorder_.set_order(order);
  reorder_.apply(p_);
  reorder_.apply(divv_old_);
  for (const auto& m : modules_) m->reorder(reorder_);
  reorder_.release_order();
}

void SphSystem::update_density() {
  density_passes_ = 0.0;
  for (int pass = 0; pass < 20; ++pass) {
    if (nl_.needs_rebuild(p_, box_)) rebuild_neighbours();
    const DensityResult r = compute_density(p_, nl_, box_, cfg_);
    density_passes_ += r.mean_iterations;
    if (r.outside_cover == 0) {
      if (r.not_converged > 0) {
        throw core::NumericalError("sph: h-rho iteration did not converge for " + std::to_string(r.not_converged) +
                                   " particles");
      }
      return;
    }
  }
  throw core::NumericalError("sph: smoothing lengths kept outgrowing the neighbour list");
}

void SphSystem::compute_accelerations(const RealView2& vel, const RealView1& u) {
  update_density();
  if (gas_forces_) {
    gas_forces_->compute_forces(*this, vel, u);
  } else {
    update_eos(p_, cfg_, u);
    compute_forces(p_, nl_, box_, cfg_, vel, u);
  }
  for (const auto& m : modules_)
    if (m.get() != gas_forces_) m->compute_forces(*this, vel, u);
  for (const auto& f : external_) f(p_, vel, time_);
  if (cfg_.damping > 0.0) apply_damping(p_, vel, cfg_.damping);
}

void SphSystem::initialise() {
  if (p_.n == 0) throw std::runtime_error("sph: initialise() before set_particles()");
  if (!modules_.empty()) {
    update_density();
    for (const auto& m : modules_) m->initialise(*this);
  }
  compute_accelerations(p_.v, p_.u);
  Kokkos::deep_copy(divv_old_, p_.divv);
  dt_next_ = timestep();
}

Real SphSystem::timestep() {
  Real dt = compute_timestep(p_, cfg_);
  dt_limit_ = "SPH gas Courant/force/damping condition (PL15 eq. 32, 56)";
  auto take = [&](Real candidate, const char* limit) {
    if (candidate < dt) {
      dt = candidate;
      dt_limit_ = limit;
    }
  };
  for (const auto& c : dt_hooks_) take(c(p_), "time-step constraint of the problem");
  for (const auto& m : modules_) {
    const std::string limit = m->timestep_name();
    take(m->timestep(*this), limit.c_str());
  }
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw core::NumericalError(logging::cat("sph: invalid time-step ", dt, " from the ", dt_limit_));
  return dt;
}

Real SphSystem::step() {
  const Real dt = dt_next_;
  const Real hdt = 0.5 * dt;
  const bool energy = cfg_.eos == EosType::Adiabatic;
  for (const auto& m : modules_) m->begin_step(*this, dt);
  kick(p_, energy, hdt);
  for (const auto& m : modules_) m->after_first_kick(*this, hdt);
  drift(p_, energy, dt);
  for (const auto& m : modules_) m->after_drift(*this, hdt);
  time_ += dt;
  // A neighbour rebuild in here reorders the particles (new Views).
  compute_accelerations(p_.vpred, p_.upred);
  kick(p_, energy, hdt);
  for (const auto& m : modules_) m->after_kick(*this, hdt);
  if (cfg_.cullen_dehnen) update_cullen_dehnen(p_, divv_old_, cfg_, dt);
  ++steps_;
  dt_next_ = timestep();
  return dt;
}

void SphSystem::rebuild_neighbours_as_built(const RealView2& x_build, const RealView1& h_build) {
  const RealView2 x = p_.x;
  const RealView1 h = p_.h;
  p_.x = RealView2("sph::x_rebuild", p_.n, p_.dim);
  p_.h = RealView1("sph::h_rebuild", p_.n);
  Kokkos::deep_copy(p_.x, x_build);
  Kokkos::deep_copy(p_.h, h_build);
  // The wrap is the identity on built positions, and the checkpointed
  // particles are in the cell order of that build (cells of the same x and h
  // extremes), so the build needs no reordering.
  nl_.build(p_, box_, cfg_.kernel, cfg_.skin);
  p_.x = x;
  p_.h = h;
}

int SphSystem::advance_to(Real t_end, const std::function<void(const SphSystem&)>& after_step) {
  int n = 0;
  while (time_ < t_end * (1.0 - 1e-14)) {
    if (time_ + dt_next_ > t_end) dt_next_ = t_end - time_;
    step();
    ++n;
    if (after_step) after_step(*this);
  }
  return n;
}

Diagnostics SphSystem::diagnostics() const {
  const auto m = p_.m;
  const auto v = p_.v;
  const auto u = p_.u;
  const int dim = p_.dim;
  const bool energy = cfg_.eos == EosType::Adiabatic;
  Diagnostics dg;
  par_reduce(
      "sph::diag_mass", 0, p_.n, KOKKOS_LAMBDA(int i, Real& s) { s += m(i); }, dg.mass);
  for (int d = 0; d < dim; ++d) {
    Real s = 0.0;
    par_reduce(
        "sph::diag_momentum", 0, p_.n, KOKKOS_LAMBDA(int i, Real& acc) { acc += m(i) * v(i, d); }, s);
    dg.momentum[d] = s;
  }
  Real v2sum = 0.0;
  par_reduce(
      "sph::diag_kinetic", 0, p_.n,
      KOKKOS_LAMBDA(int i, Real& s) {
        Real v2 = 0.0;
        for (int d = 0; d < dim; ++d) v2 += v(i, d) * v(i, d);
        s += m(i) * v2;
      },
      v2sum);
  par_reduce(
      "sph::diag_momentum_abs", 0, p_.n,
      KOKKOS_LAMBDA(int i, Real& s) {
        Real v2 = 0.0;
        for (int d = 0; d < dim; ++d) v2 += v(i, d) * v(i, d);
        s += m(i) * math::sqrt(v2);
      },
      dg.momentum_abs);
  if (energy) {
    par_reduce(
        "sph::diag_thermal", 0, p_.n, KOKKOS_LAMBDA(int i, Real& s) { s += m(i) * u(i); }, dg.thermal);
  }
  for (const auto& mod : modules_) mod->add_diagnostics(*this, dg);
  dg.kinetic = 0.5 * v2sum;
  dg.energy = dg.kinetic + dg.thermal;
  dg.v_rms = dg.mass > 0.0 ? std::sqrt(v2sum / dg.mass) : 0.0;
  return dg;
}

Snapshot SphSystem::snapshot() const {
  const IdOrder by_id(p_.id);
  Snapshot s;
  s.time = time_;
  s.x = by_id(p_.x);
  for (int i = 0; i < p_.n; ++i)
    for (int d = 0; d < p_.dim; ++d) s.x(i, d) = box_.wrap(s.x(i, d), d);
  s.v = by_id(p_.v);
  s.h = by_id(p_.h);
  s.rho = by_id(p_.rho);
  s.u = by_id(p_.u);
  for (const auto& m : modules_) m->to_gas_specific_energy(*this, s.u);
  s.P = by_id(p_.P);
  s.m = by_id(p_.m);
  s.type = by_id(p_.type);
  s.id = by_id(p_.id);
  return s;
}

double SphSystem::bytes_per_particle() const {
  if (p_.n == 0) return 0.0;
  const double particle = static_cast<double>(p_.bytes_per_particle()) + sizeof(Real);  // + divv_old
  return particle + static_cast<double>(nl_.bytes()) / p_.n;
}

}  // namespace mote::sph
