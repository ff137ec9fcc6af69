// State, integration, time-step, floor and diagnostics of the one-fluid dust
// (PL15 sec. 2.2, 3.3, 4.4.2, app. B; HPL18 sec. 2.2, eq. 24-25, 43-44, 52);
// the particle loops are in dust_forces.cpp. See one_fluid_dust.hpp.
#include "mote/sph/one_fluid_dust.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/phantom_dump.hpp"
#include "mote/io/snapshot.hpp"

namespace mote::sph {

namespace {
constexpr int kMassBlock = 64;  // particles per partial sum of the species masses
}  // namespace

OneFluidDust::OneFluidDust(const DustSettings& s, int n, int dim) : s_(s) {
  s_.validate();
  const int ns = s_.nspecies;
  var = RealView2("sph::dust_var", n, ns);
  var_pred = RealView2("sph::dust_var_pred", n, ns);
  dvar = RealView2("sph::dust_dvar", n, ns);
  if (s_.variable == DustVariable::SqrtRhoEps) s_pairs = RealView2("sph::dust_s", n, ns);
  ts = RealView2("sph::dust_ts", n, ns);
  coef = RealView2("sph::dust_coef", n, ns);
  eps_tot = RealView1("sph::dust_eps", n);
  eps_ts = RealView1("sph::dust_eps_ts", n);
  eps_ts_free = RealView1("sph::dust_eps_ts_free", s_.limit_ts ? n : 0);
  d_tot = RealView1("sph::dust_dtot", n);
  uloc = RealView1("sph::dust_u", n);
  gforce = RealView2("sph::dust_gforce", n, dim);
  mass_partial_ = RealView2("sph::dust_mass_partial", (n + kMassBlock - 1) / kMassBlock, ns);
  mass_now_ = RealView1("sph::dust_species_mass", ns);
  mass_ref_ = RealView1("sph::dust_mass_reference", ns);
  projected_ = RealView1("sph::dust_projected_mass", 1);
  const SpeciesDrag drag = s_.species_drag("sph::dust");
  kdrag_ = drag.k_drag;
  size_ = drag.size;
  tstop_ = drag.stopping_time;
  if (!s_.eps.empty()) {
    auto he = Kokkos::create_mirror_view(var);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < ns; ++j) he(i, j) = stored_fraction(s_.species_value(s_.eps, j));
    Kokkos::deep_copy(var, he);
  }
}

Real OneFluidDust::stored_fraction(Real eps) const {
  return s_.variable == DustVariable::SqrtRhoEps ? std::sqrt(std::max(eps, Real(0))) : eps;
}

void OneFluidDust::set_eps(const std::vector<Real>& eps, const IntView1& id) {
  const int n = static_cast<int>(var.extent(0)), ns = s_.nspecies;
  if (static_cast<int>(eps.size()) != n * ns) throw std::invalid_argument("dust: eps needs n x N values");
  auto he = Kokkos::create_mirror_view(var);
  auto hid = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), id);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < ns; ++j) he(i, j) = stored_fraction(eps[static_cast<std::size_t>(hid(i)) * ns + j]);
  Kokkos::deep_copy(var, he);
}

void OneFluidDust::reorder(ParticleReorder& r) {
  for (RealView2* v : {&var, &var_pred, &dvar, &s_pairs, &ts, &coef, &gforce}) r.apply(*v);
  for (RealView1* v : {&eps_tot, &eps_ts, &d_tot, &uloc}) r.apply(*v);
  if (s_.limit_ts) r.apply(eps_ts_free);
}

void OneFluidDust::initialise(const Particles&) {
  // var holds the evolved variable since set-up (stored_fraction), so that a second call (SphSystem::add_module
  // on a running system, then SphSystem::initialise) leaves it as it is.
  Kokkos::deep_copy(var_pred, var);
  Kokkos::deep_copy(dvar, 0.0);
  floored_mass_ = 0.0;
  Kokkos::deep_copy(projected_, 0.0);
  reference_set_ = false;
}

Real OneFluidDust::projected_mass() const {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), projected_);
  return h(0);
}

OneFluidDust::MassAccounts OneFluidDust::mass_accounts() const {
  MassAccounts a{floored_mass_, projected_mass(), {}};
  if (reference_set_) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), mass_ref_);
    a.reference.assign(h.data(), h.data() + h.extent(0));
  }
  return a;
}

void OneFluidDust::restore_mass_accounts(const MassAccounts& a) {
  if (!a.reference.empty() && static_cast<int>(a.reference.size()) != s_.nspecies)
    throw std::invalid_argument("dust: the projection reference needs one mass per species");
  floored_mass_ = a.floored;
  Kokkos::deep_copy(projected_, a.projected);
  reference_set_ = !a.reference.empty();
  if (reference_set_)
    Kokkos::deep_copy(mass_ref_, Kokkos::View<const Real*, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(
                                     a.reference.data(), a.reference.size()));
}

bool OneFluidDust::projecting() const { return s_.project_mass && s_.variable == DustVariable::SqrtRhoEps; }

void OneFluidDust::species_mass(const Particles& p) const {
  // Partial sums over blocks of particles (each block reads its rows of var once,
  // from cache), then over the blocks: deterministic, no atomics.
  constexpr int kBlock = kMassBlock;
  const int ns = s_.nspecies, n = p.n, nblock = (n + kBlock - 1) / kBlock;
  const auto v = var;
  const auto m = p.m;
  const bool svar = s_.variable == DustVariable::SqrtRhoEps;
  const auto partial = mass_partial_;
  par_for(
      "sph::dust_mass_blocks", 0, nblock, KOKKOS_LAMBDA(int b) {
        const int a1 = b * kBlock + kBlock < n ? b * kBlock + kBlock : n;
        for (int j = 0; j < ns; ++j) {
          Real s = 0.0;
          for (int a = b * kBlock; a < a1; ++a) s += m(a) * (svar ? v(a, j) * v(a, j) : v(a, j));
          partial(b, j) = s;
        }
      });
  const auto out = mass_now_;
  par_for(
      "sph::dust_mass_species", 0, ns, KOKKOS_LAMBDA(int j) {
        Real s = 0.0;
        for (int b = 0; b < nblock; ++b) s += partial(b, j);
        out(j) = s;
      });
}

void OneFluidDust::set_mass_reference() {
  const auto now = mass_now_;
  const auto ref = mass_ref_;
  par_for(
      "sph::dust_mass_reference", 0, s_.nspecies, KOKKOS_LAMBDA(int j) { ref(j) = now(j); });
  reference_set_ = true;
}

void OneFluidDust::project_mass(const Particles& p) {
  species_mass(p);
  const auto now = mass_now_;
  const auto ref = mass_ref_;
  const auto projected = projected_;
  const auto scale = mass_partial_;  // row 0 holds the scale factors (the partial sums are used up)
  const int ns = s_.nspecies;
  par_for(
      "sph::dust_projection_scale", 0, 1, KOKKOS_LAMBDA(int) {
        for (int j = 0; j < ns; ++j) {  // in species order: the running total's bits as before
          scale(0, j) = now(j) > 0.0 ? math::sqrt(ref(j) / now(j)) : 1.0;
          projected(0) += now(j) - ref(j);
        }
      });
  const auto v = var;
  par_for(
      "sph::dust_project", 0, p.n, KOKKOS_LAMBDA(int a) {
        for (int j = 0; j < ns; ++j) v(a, j) *= scale(0, j);
      });
}

void OneFluidDust::kick_predict(const Particles& p, Real hdt) {
  // The reference is the mass of the first step after initialise() or a restart.
  if (projecting() && !reference_set_) {
    species_mass(p);
    set_mass_reference();
  }
  const auto v = var;
  const auto vp = var_pred;
  const auto dv = dvar;
  const int ns = s_.nspecies;
  par_for(
      "sph::dust_kick_predict", 0, static_cast<int>(var.extent(0)), KOKKOS_LAMBDA(int a) {
        for (int j = 0; j < ns; ++j) {
          const Real vh = v(a, j) + hdt * dv(a, j);
          v(a, j) = vh;
          vp(a, j) = vh + hdt * dv(a, j);
        }
      });
}

Real OneFluidDust::kick(const Particles& p, Real hdt) {
  const auto v = var;
  const auto dv = dvar;
  const auto m = p.m;
  const int ns = s_.nspecies;
  const bool floor = s_.floor_negative && s_.variable == DustVariable::Epsilon;
  Real removed = 0.0;
  par_reduce(
      "sph::dust_kick", 0, p.n,
      KOKKOS_LAMBDA(int a, Real& rm) {
        for (int j = 0; j < ns; ++j) {
          Real e = v(a, j) + hdt * dv(a, j);
          if (floor && e < 0.0) {  // PL15 sec. 4.4.2
            rm -= m(a) * e;
            e = 0.0;
          }
          v(a, j) = e;
        }
      },
      removed);
  floored_mass_ += removed;
  if (projecting()) project_mass(p);
  return removed;
}

Real OneFluidDust::timestep(const Particles& p, const SphConfig& cfg) {
  const auto h = p.h;
  const auto cs = p.cs;
  const auto type = p.type;
  const auto e = eps_tot;
  const auto ets = eps_ts;
  const auto free_ets = s_.limit_ts ? eps_ts_free : eps_ts;  // the eq. 18 check: t_s before the limiter
  const Real c0 = s_.c_dust;
  const Real ccour = cfg.c_cour;
  const bool combined = s_.timestep == DustTimestep::Combined;
  // The diffusion rate of the coupled (eps, u) system is (gamma - 1) D u = D c_s^2 / gamma with
  // PL15's div v, but D c_s^2 with the gas PdV (dust.pdv = "gas", whose energy term diffuses u
  // as well): the diffusion part of eq. 44 / 16 is then scaled by gamma to keep PL15's margin
  // (the K = 1 dustywave is unstable at C0 = 0.25 without it).
  const Real dscale = (cfg.eos == EosType::Adiabatic && s_.pdv == DustPdV::Gas) ? cfg.gamma : 1.0;
  Real dt = 1e300;
  par_reduce(
      "sph::dust_timestep", 0, p.n,
      KOKKOS_LAMBDA(int a, Real& dmin) {
        if (type(a) != kGas) return;
        const Real d = combined ? dt_dust_combined(c0, h(a), cs(a), e(a), dscale * ets(a))
                                : dt_dust_diffusion(c0, h(a), cs(a), dscale * ets(a));
        dmin = d < dmin ? d : dmin;
      },
      Kokkos::Min<Real>(dt));
  int bad = 0;
  par_reduce(
      "sph::dust_tva_check", 0, p.n,
      KOKKOS_LAMBDA(int a, int& c) {
        if (type(a) == kGas && free_ets(a) > ccour * h(a) / cs(a)) ++c;  // PL15 eq. 18
      },
      bad);
  tva_violations_ = bad;
  if (bad > 0 && !warned_) {
    logging::warn("sph dust: eps T_s exceeds the Courant time-step on ", bad,
                  " particles: the terminal-velocity approximation is inaccurate there (PL15 sec. 2.2)",
                  s_.limit_ts ? " (dust.limit_stopping_time caps each T_sj at h / c_s)" : "");
    warned_ = true;
  }
  return dt;
}

RealView2 OneFluidDust::eps(const Particles& p) const {
  RealView2 out("sph::dust_eps_out", var.extent(0), var.extent(1));
  const auto v = var;
  const int ns = s_.nspecies;
  const bool svar = s_.variable == DustVariable::SqrtRhoEps;
  par_for(
      "sph::dust_eps", 0, p.n, KOKKOS_LAMBDA(int a) {
        for (int j = 0; j < ns; ++j) out(a, j) = svar ? v(a, j) * v(a, j) : v(a, j);
      });
  return out;
}

Real OneFluidDust::dust_mass(const Particles& p) const {
  const auto v = var;
  const auto m = p.m;
  const int ns = s_.nspecies;
  const bool svar = s_.variable == DustVariable::SqrtRhoEps;
  Real md = 0.0;
  par_reduce(
      "sph::dust_mass", 0, p.n,
      KOKKOS_LAMBDA(int a, Real& s) {
        Real e = 0.0;
        for (int j = 0; j < ns; ++j) e += svar ? v(a, j) * v(a, j) : v(a, j);
        s += m(a) * e;
      },
      md);
  return md;
}

Real OneFluidDust::thermal_energy(const Particles& p, const SphConfig& cfg) const {
  if (cfg.eos != EosType::Adiabatic) return 0.0;
  const auto v = var;
  const auto m = p.m;
  const auto u = p.u;
  const int ns = s_.nspecies;
  const bool svar = s_.variable == DustVariable::SqrtRhoEps;
  const bool utilde = s_.energy == DustEnergy::UTilde;
  Real eth = 0.0;
  par_reduce(
      "sph::dust_thermal", 0, p.n,
      KOKKOS_LAMBDA(int a, Real& s) {
        Real e = 0.0;
        for (int j = 0; j < ns; ++j) e += svar ? v(a, j) * v(a, j) : v(a, j);
        s += m(a) * (utilde ? u(a) : (1.0 - e) * u(a));  // PL15 eq. 40, HPL18 eq. 52
      },
      eth);
  return eth;
}

DustSnapshot OneFluidDust::snapshot(const Particles& p) const {
  DustSnapshot s;
  const int n = p.n, ns = s_.nspecies, dim = p.dim;
  const IdOrder by_id(p.id);
  s.eps = by_id(eps(p));
  const auto hv = by_id(p.v);
  const auto hg = by_id(gforce);
  const auto hts = by_id(ts);
  s.v_gas = HostView<Real**>("sph::dust_vgas", n, dim);
  s.dv = HostView<Real***>("sph::dust_dv", n, ns, dim);
  for (int a = 0; a < n; ++a) {
    Real et = 0.0;
    for (int j = 0; j < ns; ++j) et += s.eps(a, j);
    for (int d = 0; d < dim; ++d) {
      Real sum = 0.0;
      for (int j = 0; j < ns; ++j) {
        // HPL18 eq. 24: Dv_j = T_sj grad P / rho_g, grad P / rho_g = g / (1 - eps).
        const Real dvj = hts(a, j) * hg(a, d) / (1.0 - et);
        s.dv(a, j, d) = dvj;
        sum += s.eps(a, j) * dvj;
      }
      s.v_gas(a, d) = hv(a, d) - sum;  // v_g = v - eps Dv (HPL18 eq. 10, 25)
    }
  }
  return s;
}

void OneFluidDust::compute_forces(SphSystem& sys, const RealView2& vel, const RealView1& u) {
  mixture_forces(sys.particles(), sys.neighbours(), sys.box(), sys.config(), vel, u);
}

Real OneFluidDust::timestep(SphSystem& sys) { return timestep(sys.particles(), sys.config()); }

void OneFluidDust::add_diagnostics(const SphSystem& sys, Diagnostics& dg) const {
  dg.thermal = thermal_energy(sys.particles(), sys.config());
  dg.dust_mass = dust_mass(sys.particles());
  dg.dust_floored = floored_mass();
  dg.dust_projected = projected_mass();
}

std::vector<io::Diagnostic> OneFluidDust::history(const SphSystem& sys) const {
  const Real mass = dust_mass(sys.particles());
  return {{"dust_mass", mass},
          {"dust_mass_unfloored", mass - floored_mass()},
          {"dust_projected", projected_mass()},
          {"tva_violations", static_cast<Real>(tva_violations_)}};
}

void OneFluidDust::to_gas_specific_energy(const SphSystem& sys, const HostView<Real*>& u) const {
  if (s_.energy != DustEnergy::UTilde) return;
  const auto e = IdOrder(sys.particles().id)(eps(sys.particles()));
  for (size_t a = 0; a < u.extent(0); ++a) {
    Real total = 0.0;
    for (int j = 0; j < s_.nspecies; ++j) total += e(a, j);
    u(a) /= 1.0 - total;
  }
}

void OneFluidDust::write_snapshot(const SphSystem& sys, io::SnapshotWriter& out, const units::UnitSystem& units) const {
  const DustSnapshot ds = snapshot(sys.particles());
  const int n = sys.particles().n, dim = sys.particles().dim, ns = nspecies();
  std::vector<double> eps(static_cast<size_t>(n) * ns), vg(3 * static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < ns; ++k) eps[static_cast<size_t>(i) * ns + k] = ds.eps(i, k);
    for (int d = 0; d < dim; ++d) vg[3 * i + d] = ds.v_gas(i, d);
  }
  out.particle_field("dust_fraction", eps.data(), ns, {"1", 1.0});
  out.particle_field("gas_velocity", vg.data(), 3, {"code velocity", units.velocity()});
  if (!s_.write_velocities) return;
  std::vector<double> vd(static_cast<size_t>(n) * ns * 3, 0.0);  // v_dj = v_g + Dv_j, column 3 j + d
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < ns; ++k)
      for (int d = 0; d < dim; ++d) vd[(static_cast<size_t>(i) * ns + k) * 3 + d] = ds.v_gas(i, d) + ds.dv(i, k, d);
  out.particle_field("dust_velocity", vd.data(), 3 * ns, {"code velocity", units.velocity()});
}

void OneFluidDust::write_phantom_dump(const SphSystem& sys, io::PhantomDump& dump) const {
  const DustSnapshot ds = snapshot(sys.particles());
  const int n = sys.particles().n, ns = nspecies();
  dump.header_int("ndustsmall", {ns});
  dump.header_real("grainsize", s_.grain_sizes());
  dump.header_real("graindens", s_.grain_densities());
  for (int k = 0; k < ns; ++k) {
    std::vector<double> eps(n);
    for (int i = 0; i < n; ++i) eps[i] = ds.eps(i, k);
    dump.real_array("dustfrac", std::move(eps));
  }
}

namespace {

/// What the checkpointed dust variable holds (the S variable is stored as S_j / sqrt(rho) = sqrt(eps_j)).
std::string dust_storage(const DustSettings& s) {
  return s.variable == DustVariable::Epsilon ? "eps_j" : "sqrt(eps_j)";
}

/// (n, N) device array as row-major host data.
std::vector<double> host_rows(const RealView2& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  std::vector<double> out(h.extent(0) * h.extent(1));
  for (size_t i = 0; i < h.extent(0); ++i)
    for (size_t j = 0; j < h.extent(1); ++j) out[i * h.extent(1) + j] = h(i, j);
  return out;
}

}  // namespace

void OneFluidDust::save_state(const SphSystem&, io::H5File& f) const {
  const hsize_t n = var.extent(0), ns = var.extent(1);
  const io::Block block = io::Block::whole({n, ns});
  f.write("/state/dust_var", block, host_rows(var).data());
  f.write("/state/dust_dvar", block, host_rows(dvar).data());
  // For a snapshot right after a restart (gas and dust velocities, HPL18 eq. 24-25); the next step
  // recomputes them.
  f.write("/state/dust_ts", block, host_rows(ts).data());
  f.write("/state/dust_gforce", io::Block::whole({n, gforce.extent(1)}), host_rows(gforce).data());
  f.write_attribute("/state/dust_var", "stored", dust_storage(s_));
  f.write_attribute("/state/dust_var", "floored_mass", floored_mass_);
  const MassAccounts accounts = mass_accounts();
  f.write_attribute("/state/dust_var", "projected_mass", accounts.projected);
  if (!accounts.reference.empty())
    f.write("/state/dust_mass_reference", io::Block::whole({ns}), accounts.reference.data());
}

void OneFluidDust::load_state(SphSystem&, const io::H5File& f) {
  const hsize_t n = var.extent(0), ns = var.extent(1);
  if (f.dims("/state/dust_var") != std::vector<hsize_t>{n, ns})
    throw std::runtime_error("checkpoint holds a different number of dust species than the deck sets up");
  const std::string stored = f.has_attribute("/state/dust_var", "stored")
                                 ? f.read_attribute_string("/state/dust_var", "stored")
                                 : std::string("unlabelled (written before S_j was stored as sqrt(eps_j))");
  if (stored != dust_storage(s_))
    throw std::runtime_error("checkpoint dust variable is " + stored + ", the deck evolves " + dust_storage(s_) +
                             " (dust.variable): restart with the deck that wrote it");
  const auto read_rows = [&](const char* name, const RealView2& view) {
    const hsize_t cols = view.extent(1);
    std::vector<double> buf(n * cols);
    f.read(name, io::Block::whole({n, cols}), buf.data());
    auto h = Kokkos::create_mirror_view(view);
    for (hsize_t i = 0; i < n; ++i)
      for (hsize_t j = 0; j < cols; ++j) h(i, j) = buf[i * cols + j];
    Kokkos::deep_copy(view, h);
  };
  read_rows("/state/dust_var", var);
  read_rows("/state/dust_dvar", dvar);
  if (f.exists("/state/dust_ts")) {  // checkpoints before these were stored: the set-up's, until the next step
    read_rows("/state/dust_ts", ts);
    read_rows("/state/dust_gforce", gforce);
  }
  MassAccounts acc;
  if (f.has_attribute("/state/dust_var", "floored_mass")) {
    acc.floored = f.read_attribute_real("/state/dust_var", "floored_mass");
    acc.projected = f.read_attribute_real("/state/dust_var", "projected_mass");
  }
  if (f.exists("/state/dust_mass_reference")) {
    acc.reference.resize(ns);
    f.read("/state/dust_mass_reference", io::Block::whole({ns}), acc.reference.data());
  }
  restore_mass_accounts(acc);
}

OneFluidDust& add_one_fluid_dust(SphSystem& sys, const DustSettings& settings, const std::vector<Real>& eps) {
  const Particles& p = sys.particles();
  if (p.n == 0) throw std::runtime_error("sph: one-fluid dust added before set_particles()");
  if (settings.pdv == DustPdV::Gas && sys.config().eos != EosType::Adiabatic)
    throw std::invalid_argument("dust.pdv = \"gas\" needs sph.eos = \"adiabatic\" (no PdV work when isothermal)");
  auto dust = std::make_shared<OneFluidDust>(settings, p.n, p.dim);
  if (!eps.empty()) dust->set_eps(eps, p.id);
  OneFluidDust& module = *dust;
  sys.add_module(std::move(dust));
  return module;
}

int advance_dust_only(SphSystem& sys, Real t_end) {
  OneFluidDust* dust = sys.module<OneFluidDust>();
  if (!dust) throw std::runtime_error("sph: advance_dust_only() needs the one-fluid dust");
  Particles& p = sys.particles();
  Real t = 0.0;
  int steps = 0;
  while (t < t_end * (1.0 - 1e-14)) {
    Real dt = dust->timestep(p, sys.config());
    if (t + dt > t_end) dt = t_end - t;
    dust->kick_predict(p, 0.5 * dt);
    sys.compute_accelerations(p.v, p.u);
    dust->kick(p, 0.5 * dt);
    t += dt;
    ++steps;
  }
  return steps;
}

}  // namespace mote::sph
