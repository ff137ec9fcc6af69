// io::Simulation adapter of the SPH engine (see include/mote/sph/sph_simulation.hpp).
#include "mote/sph/sph_simulation.hpp"

#include <algorithm>
#include <limits>

#include "mote/core/comm.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"

namespace mote::sph {

namespace {

using io::Block;

std::vector<double> to_host(const RealView1& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

/// (n, dim) device array as row-major (n, width) host data, zero-padded.
std::vector<double> to_host(const RealView2& v, int width) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  const int n = static_cast<int>(h.extent(0)), dim = static_cast<int>(h.extent(1));
  std::vector<double> out(static_cast<size_t>(n) * width, 0.0);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < dim; ++d) out[static_cast<size_t>(i) * width + d] = h(i, d);
  return out;
}

void from_host(const std::vector<double>& data, const RealView1& v) {
  auto h = Kokkos::create_mirror_view(v);
  for (size_t i = 0; i < data.size(); ++i) h(i) = data[i];
  Kokkos::deep_copy(v, h);
}

void from_host(const std::vector<double>& data, const RealView2& v) {
  auto h = Kokkos::create_mirror_view(v);
  const int n = static_cast<int>(h.extent(0)), dim = static_cast<int>(h.extent(1));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < dim; ++d) h(i, d) = data[static_cast<size_t>(i) * dim + d];
  Kokkos::deep_copy(v, h);
}

std::vector<std::int32_t> ints_to_host(const IntView1& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  return std::vector<std::int32_t>(h.data(), h.data() + h.extent(0));
}

// Phantom's particle types (igas, idust of its part.F90; the types SPLASH's
// read_data_sphNG.f90 labels): gas is 1, large-grain dust species j is idust + j.
constexpr int kPhantomGas = 1, kPhantomDust = 7;

int phantom_type(int type) { return type == kGas ? kPhantomGas : kPhantomDust + (type - kDust); }

/// Phantom's header counts and masses of the types 1..ntypes (ntypes >= idust).
struct PhantomTypes {
  std::vector<std::int32_t> count;
  std::vector<double> mass;
};

/// The types of `snap`; a core::InputError when the masses within a type differ
/// (a Phantom dump has one mass per type, massoftype).
PhantomTypes phantom_types(const Snapshot& snap) {
  const int n = static_cast<int>(snap.m.extent(0));
  int ntypes = kPhantomDust;
  for (int i = 0; i < n; ++i) ntypes = std::max(ntypes, phantom_type(snap.type(i)));
  if (ntypes > std::numeric_limits<std::int8_t>::max())
    throw core::InputError(
        logging::format("output.sph_format: Phantom's itype is an int*1, which cannot hold the %d "
                        "particle types of this run",
                        ntypes));
  PhantomTypes t{std::vector<std::int32_t>(ntypes, 0), std::vector<double>(ntypes, 0.0)};
  std::vector<int> first(ntypes, -1);
  for (int i = 0; i < n; ++i) {
    const int k = phantom_type(snap.type(i)) - 1;
    if (first[k] >= 0 && snap.m(i) != t.mass[k])
      throw core::InputError(logging::format(
          "output.sph_format: a Phantom dump holds one mass per particle type, but particles %d and %d of mote "
          "type %d have masses %.17g and %.17g; write this problem's snapshots as output.sph_format = \"hdf5\"",
          first[k], i, snap.type(i), t.mass[k], snap.m(i)));
    if (first[k] < 0) first[k] = i;
    t.mass[k] = snap.m(i);
    ++t.count[k];
  }
  return t;
}

/// Column d of an (n, dim) host array, zero for d >= dim (as the HDF5 snapshot pads it).
std::vector<double> component(const HostView<Real**>& a, int d) {
  std::vector<double> c(a.extent(0), 0.0);
  if (d < static_cast<int>(a.extent(1)))
    for (size_t i = 0; i < c.size(); ++i) c[i] = a(i, d);
  return c;
}

void write_phantom_header(const PhantomTypes& types, const SphConfig& cfg, io::PhantomDump& dump) {
  std::int32_t n = 0;
  for (const auto c : types.count) n += c;
  dump.header_int("nparttot", {n});
  dump.header_int("ntypes", {static_cast<std::int32_t>(types.count.size())});
  dump.header_int("npartoftype", types.count);
  dump.header_int("nblocks", {1});
  dump.header_int("nptmass", {0});
  dump.header_int("ndustlarge", {0});  // the dust modules set theirs
  dump.header_int("ndustsmall", {0});
  dump.header_int("idust", {kPhantomDust});
  dump.header_real("gamma", {cfg.eos == EosType::Adiabatic ? cfg.gamma : 1.0});
  dump.header_real("hfact", {cfg.effective_hfact()});
  dump.header_real("massoftype", types.mass);
}

void write_phantom_arrays(const Snapshot& snap, const SphConfig& cfg, io::PhantomDump& dump) {
  const int n = static_cast<int>(snap.m.extent(0));
  std::vector<std::int8_t> itype(n);
  for (int i = 0; i < n; ++i) itype[i] = static_cast<std::int8_t>(phantom_type(snap.type(i)));
  dump.int1_array("itype", std::move(itype));
  const char* const axes[] = {"x", "y", "z"};
  const char* const velocities[] = {"vx", "vy", "vz"};
  for (int d = 0; d < 3; ++d) dump.real_array(axes[d], component(snap.x, d));
  for (int d = 0; d < 3; ++d) dump.real_array(velocities[d], component(snap.v, d));
  if (cfg.eos == EosType::Adiabatic) dump.real_array("u", std::vector<double>(snap.u.data(), snap.u.data() + n));
  std::vector<float> h(n);
  for (int i = 0; i < n; ++i) h[i] = static_cast<float>(snap.h(i));
  dump.real4_array("h", std::move(h));
}

}  // namespace

SphSimulation::SphSimulation(std::unique_ptr<SphSystem> system, const units::UnitSystem& units)
    : system_(std::move(system)), units_(units) {
  system_->initialise();
}

double SphSimulation::max_dt() { return system_->next_dt(); }

void SphSimulation::advance(double, double dt) {
  system_->set_next_dt(dt);
  system_->step();
}

void SphSimulation::write_snapshot(io::SnapshotWriter& out) const {
  const auto snap = system_->snapshot();
  const int n = static_cast<int>(snap.m.extent(0)), dim = static_cast<int>(snap.x.extent(1));
  std::vector<double> xyz(3 * static_cast<size_t>(n), 0.0), vel(xyz.size(), 0.0);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < dim; ++d) {
      xyz[3 * i + d] = snap.x(i, d);
      vel[3 * i + d] = snap.v(i, d);
    }
  auto vec = [](const HostView<Real*>& h) { return std::vector<double>(h.data(), h.data() + h.extent(0)); };
  out.particles(n, 0, n, xyz.data());
  out.particle_field("velocity", vel.data(), 3, {"code velocity", units_.velocity()});
  out.particle_field("h", vec(snap.h).data(), 1, {"code length", units_.length});
  out.particle_field("density", vec(snap.rho).data(), 1, {"code density", units_.density()});
  out.particle_field("u", vec(snap.u).data(), 1, {"code specific energy", units_.specific_energy()});
  out.particle_field("pressure", vec(snap.P).data(), 1, {"code pressure", units_.pressure()});
  out.particle_field("mass", vec(snap.m).data(), 1, {"code mass", units_.mass});
  for (const auto& m : system_->modules()) m->write_snapshot(*system_, out, units_);
  std::vector<std::int32_t> type(snap.type.data(), snap.type.data() + n), id(snap.id.data(), snap.id.data() + n);
  out.particle_field("type", type.data(), {"1", 1.0});
  out.particle_field("id", id.data(), {"1", 1.0});
}

void SphSimulation::save_state(io::H5File& f) const {
  const auto& p = system_->particles();
  const hsize_t n = p.n, dim = p.dim;
  const Block vec = Block::whole({n, dim}), scalar = Block::whole({n});
  f.write("/state/x", vec, to_host(p.x, p.dim).data());
  f.write("/state/v", vec, to_host(p.v, p.dim).data());
  f.write("/state/a", vec, to_host(p.a, p.dim).data());
  f.write("/state/m", scalar, to_host(p.m).data());
  f.write("/state/h", scalar, to_host(p.h).data());
  f.write("/state/u", scalar, to_host(p.u).data());
  f.write("/state/dudt", scalar, to_host(p.dudt).data());
  f.write("/state/divv", scalar, to_host(p.divv).data());
  f.write("/state/divv_old", scalar, to_host(system_->divv_old()).data());
  f.write("/state/alpha", scalar, to_host(p.alpha).data());
  // Not needed to continue (the next step recomputes them), but a snapshot written right after a
  // restart (one a failed write left out) shows them.
  f.write("/state/rho", scalar, to_host(p.rho).data());
  f.write("/state/P", scalar, to_host(p.P).data());
  f.write("/state/type", scalar, ints_to_host(p.type).data());
  f.write("/state/id", scalar, ints_to_host(p.id).data());
  for (const auto& m : system_->modules()) m->save_state(*system_, f);
  const auto& nl = system_->neighbours();
  if (nl.built()) {  // what the list was built from: a restart rebuilds the same list
    f.write("/state/neighbour_x_build", vec, to_host(nl.x_build, p.dim).data());
    f.write("/state/neighbour_h_build", scalar, to_host(nl.h_build).data());
  }
  f.write_attribute("/state", "time", system_->time());
  f.write_attribute("/state", "dt_next", system_->next_dt());
  f.write_attribute("/state", "steps", static_cast<std::int64_t>(system_->steps()));
}

void SphSimulation::load_state(const io::H5File& f) {
  auto& p = system_->particles();
  const hsize_t n = p.n, dim = p.dim;
  if (f.dims("/state/x") != std::vector<hsize_t>{n, dim})
    throw std::runtime_error("checkpoint holds a different number of particles or dimensions than the deck sets up");
  const Block vec = Block::whole({n, dim}), scalar = Block::whole({n});
  std::vector<double> buf2(n * dim), buf(n);
  auto read2 = [&](const char* name, const RealView2& v) {
    f.read(name, vec, buf2.data());
    from_host(buf2, v);
  };
  auto read1 = [&](const char* name, const RealView1& v) {
    f.read(name, scalar, buf.data());
    from_host(buf, v);
  };
  read2("/state/x", p.x);
  read2("/state/v", p.v);
  read2("/state/a", p.a);
  read1("/state/m", p.m);
  read1("/state/h", p.h);
  read1("/state/u", p.u);
  read1("/state/dudt", p.dudt);
  read1("/state/divv", p.divv);
  read1("/state/divv_old", system_->divv_old());
  read1("/state/alpha", p.alpha);
  if (f.exists("/state/rho")) {  // checkpoints before these were stored: the set-up's, until the next step
    read1("/state/rho", p.rho);
    read1("/state/P", p.P);
  }
  for (const auto& m : system_->modules()) m->load_state(*system_, f);
  std::vector<std::int32_t> ibuf(n);
  const std::pair<const char*, IntView1> int_fields[] = {{"/state/type", p.type}, {"/state/id", p.id}};
  for (const auto& [name, view] : int_fields) {
    f.read(name, scalar, ibuf.data());
    auto h = Kokkos::create_mirror_view(view);
    for (hsize_t i = 0; i < n; ++i) h(i) = ibuf[i];
    Kokkos::deep_copy(view, h);
  }
  if (f.exists("/state/neighbour_x_build")) {
    RealView2 xb("sph::x_build", n, dim);
    RealView1 hb("sph::h_build", n);
    read2("/state/neighbour_x_build", xb);
    read1("/state/neighbour_h_build", hb);
    system_->rebuild_neighbours_as_built(xb, hb);
  }
  system_->restore_clock(f.read_attribute_real("/state", "time"), f.read_attribute_real("/state", "dt_next"),
                         f.read_attribute_int("/state", "steps"));
}

void SphSimulation::check_phantom_dump() const { phantom_types(system_->snapshot()); }

void SphSimulation::write_phantom_dump(io::PhantomDump& dump) const {
  const auto snap = system_->snapshot();
  write_phantom_header(phantom_types(snap), system_->config(), dump);
  write_phantom_arrays(snap, system_->config(), dump);
  for (const auto& m : system_->modules()) m->write_phantom_dump(*system_, dump);
}

std::vector<io::Diagnostic> SphSimulation::diagnostics() const {
  const auto d = system_->diagnostics();
  std::vector<io::Diagnostic> out{{"mass", d.mass},
                                  {"momentum_x", d.momentum[0]},
                                  {"momentum_y", d.momentum[1]},
                                  {"momentum_z", d.momentum[2]},
                                  {"momentum_abs", d.momentum_abs},
                                  {"kinetic", d.kinetic},
                                  {"thermal", d.thermal},
                                  {"energy", d.energy},
                                  {"v_rms", d.v_rms}};
  for (const auto& m : system_->modules())
    for (auto& extra : m->history(*system_)) out.push_back(std::move(extra));
  return out;
}

std::optional<io::NonFinite> SphSimulation::find_non_finite() const {
  const auto& p = system_->particles();
  auto x = p.x, v = p.v;
  auto u = p.u, h = p.h;
  const int dim = p.dim;
  int first = std::numeric_limits<int>::max();
  par_reduce(
      "sph::find_non_finite", 0, p.n,
      KOKKOS_LAMBDA(int i, int& f) {
        bool ok = math::isfinite(u(i)) && math::isfinite(h(i));
        for (int d = 0; d < dim; ++d) ok = ok && math::isfinite(x(i, d)) && math::isfinite(v(i, d));
        if (!ok) f = math::min(f, i);
      },
      Kokkos::Min<int>(first));
  if (first == std::numeric_limits<int>::max()) return std::nullopt;
  return io::NonFinite{"particle state (x, v, u, h)", logging::cat("particle index ", first)};
}

}  // namespace mote::sph
