// Coagulation on every cell of the disc grid (RBO24 sec. 5-6); see
// include/mote/disc/disc_coagulation.hpp.
#include "mote/disc/disc_coagulation.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"

namespace mote::disc {

namespace {

/// The mass grid of the dust species; they must be logarithmically spaced to 0.1 %
/// (the collision kernel uses the grid's exactly logarithmic sizes).
coagulation::MassGrid dust_mass_grid(const DustSettings& dust, const units::UnitSystem& u) {
  const int ns = static_cast<int>(dust.sizes.size());
  if (ns < 2) throw core::DeckError("coagulation in the disc needs at least two dust species (dust.sizes)");
  const auto grid = coagulation::MassGrid::from_sizes(dust.sizes.front() * u.length, dust.sizes.back() * u.length, ns,
                                                      dust.rho_grain * u.density());
  for (int s = 0; s < ns; ++s) {
    const double a = dust.sizes[s] * u.length;
    if (!(std::fabs(grid.grain_size(s) / a - 1.0) <= 1e-3))
      throw core::DeckError(
          logging::cat("coagulation in the disc needs logarithmically spaced dust.sizes (to 0.1 %): species ", s,
                       " has a = ", a, " cm, the logarithmic grid from ", grid.grain_size(0), " to ",
                       grid.grain_size(ns - 1), " cm has ", grid.grain_size(s), " cm"));
  }
  if (!grid.resolution_warning().empty()) logging::warn(grid.resolution_warning());
  return grid;
}

coagulation::CoagulationSettings checked(coagulation::CoagulationSettings s) {
  if (s.vertically_integrated)
    throw core::DeckError(
        "coagulation.vertically_integrated = true needs surface densities; the disc grid holds volume densities");
  return s;
}

}  // namespace

DiscCoagulation::DiscCoagulation(const mesh::Grid& grid, DustDynamics& dust, coagulation::CoagulationSettings settings,
                                 const units::UnitSystem& units)
    : grid_(grid),
      dust_(dust),
      units_(units),
      settings_(checked(std::move(settings))),
      mass_grid_(dust_mass_grid(dust.settings(), units)),
      solver_(mass_grid_, settings_, grid.nr * grid.nt) {
  const int cells = grid.nr * grid.nt, ns = dust.species();
  cells_.sound_speed = RealView1("disc::coag_cs", cells);
  cells_.density = RealView1("disc::coag_rho_g", cells);
  cells_.omega = RealView1("disc::coag_omega", cells);
  cells_.alpha = RealView1("disc::coag_alpha", cells);
  cells_.dust_velocity = View<Real***>("disc::coag_v_dust", cells, ns, 3);
  density_ = RealView2("disc::coag_density", cells, ns);
  before_ = RealView2("disc::coag_density_before", cells, ns);
}

coagulation::CallStatistics DiscCoagulation::update(const GasFields& gas, double elapsed) {
  const int nt = grid_.nt, ib = grid_.i_begin(), jb = grid_.j_begin(), cells = grid_.nr * grid_.nt,
            ns = dust_.species();
  const Real ud = units_.density(), uv = units_.velocity(), ut = units_.time, GM = gas.gravity.GM;
  const Real floor = dust_.settings().floor, floor_ratio = dust_.settings().floor_ratio;
  auto rho_g = gas.rho, cs2 = gas.cs2, nu = gas.nu;
  auto Rc = grid_.Rc;
  auto g_cs = cells_.sound_speed, g_rho = cells_.density, g_om = cells_.omega, g_alpha = cells_.alpha;
  par_for(
      "disc::coagulation_gas", 0, cells, KOKKOS_LAMBDA(int c) {
        const int i = ib + c / nt, j = jb + c % nt;
        const Real om = math::sqrt(GM / (Rc(i) * Rc(i) * Rc(i)));
        g_cs(c) = math::sqrt(cs2(i, j)) * uv;
        g_rho(c) = rho_g(i, j) * ud;
        g_om(c) = om / ut;
        g_alpha(c) = nu(i, j) * om / cs2(i, j);  // nu = alpha c_s^2 / Omega_K
      });
  auto Q = dust_.Q, W = dust_.W;
  auto y = density_, y0 = before_;
  auto v = cells_.dust_velocity;
  par_for(
      "disc::coagulation_load", 0, cells, 0, ns, KOKKOS_LAMBDA(int c, int s) {
        const int i = ib + c / nt, j = jb + c % nt;
        const Real above = math::max(Q(i, j, s, kRho) - dust_floor(floor, floor_ratio, rho_g(i, j)), Real(0)) * ud;
        y(c, s) = above;
        y0(c, s) = above;
        v(c, s, 0) = W(i, j, s, kVR) * uv;  // GasCells order: R, z, phi
        v(c, s, 1) = W(i, j, s, kVZ) * uv;
        v(c, s, 2) = W(i, j, s, kVphi) * uv;
      });
  const auto stats = solver_.integrate(density_, elapsed * ut, coagulation::make_kernel(settings_, mass_grid_, cells_));
  // Summed over the ranks: every rank throws together (a rank that went on would
  // wait in set_next_interval's collective for the others).
  const long long failed = grid_.comm().sum(static_cast<long long>(stats.failed_cells));
  if (failed > 0)
    throw core::NumericalError(logging::cat("disc coagulation failed in ", failed,
                                            " cells (coagulation.max_substeps reached or vanishing sub-step)"));
  par_for(
      "disc::coagulation_store", 0, cells, 0, ns, KOKKOS_LAMBDA(int c, int s) {
        const int i = ib + c / nt, j = jb + c % nt;
        const Real rho_old = Q(i, j, s, kRho);
        const Real rho_new = rho_old + (y(c, s) - y0(c, s)) / ud;
        Q(i, j, s, kRho) = rho_new;
        W(i, j, s, kRho) = rho_new;
        if (rho_old > 0) {
          const Real scale = rho_new / rho_old;  // each species keeps its velocity
          Q(i, j, s, kMomR) *= scale;
          Q(i, j, s, kAngMom) *= scale;
          Q(i, j, s, kMomZ) *= scale;
        } else {
          Q(i, j, s, kMomR) = rho_new * W(i, j, s, kVR);
          Q(i, j, s, kAngMom) = rho_new * W(i, j, s, kVphi) * Rc(i);
          Q(i, j, s, kMomZ) = rho_new * W(i, j, s, kVZ);
        }
      });
  set_next_interval(stats.min_next_substep);
  return stats;
}

Real DiscCoagulation::local_min_next_substep() const {
  auto next = solver_.next_substep();
  Real local = std::numeric_limits<Real>::max();  // also the identity of the Min reduction
  par_reduce(
      "disc::coagulation_next_interval", 0, static_cast<int>(next.extent(0)),
      KOKKOS_LAMBDA(int c, Real& m) {
        if (next(c) > 0) m = math::min(m, next(c));
      },
      Kokkos::Min<Real>(local));
  return local;
}

void DiscCoagulation::set_next_interval(Real local_min) {
  const double global = grid_.comm().min(local_min);
  next_interval_ = global < std::numeric_limits<Real>::max() ? global / units_.time : 0.0;
}

io::Block DiscCoagulation::cell_block() const {
  const hsize_t nt = grid_.nt;
  return {{hsize_t(grid_.nr_global) * nt}, {hsize_t(grid_.i_offset) * nt}, {hsize_t(grid_.nr) * nt}};
}

void DiscCoagulation::save_state(io::H5File& file, const std::string& name) const {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver_.next_substep());
  file.write(name, cell_block(), h.data());
}

void DiscCoagulation::load_state(const io::H5File& file, const std::string& name) {
  auto next = solver_.next_substep();
  auto h = Kokkos::create_mirror_view(next);
  file.read(name, cell_block(), h.data());
  Kokkos::deep_copy(next, h);
  set_next_interval(local_min_next_substep());
}

}  // namespace mote::disc
