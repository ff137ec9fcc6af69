// The gas disc (RBO24 sec. 3.3-3.5): construction, structure update and the
// viscous step with sources (eq. 26); see include/mote/disc/gas_disc.hpp.
#include "mote/disc/gas_disc.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "mote/core/loops.hpp"
#include "mote/disc/gas_structure.hpp"
#include "mote/disc/gas_viscous.hpp"

namespace mote::disc {

GasDisc::GasDisc(const core::Deck& deck, const mesh::Grid& grid, const units::UnitSystem& units)
    : GasDisc(GasConfig::from_deck(deck, units), grid, units) {}

GasDisc::GasDisc(const GasConfig& config, const mesh::Grid& grid, const units::UnitSystem& units)
    : grid_(grid),
      cfg_(config),
      units_(units),
      halo_(grid),
      gas_(grid.nr_total(), grid.nt_total()),
      scratch_(grid.nr_total(), grid.nt_total()),
      Y_("gas::Y", grid.nr_total()),
      G_("gas::G", grid.nr_total() + 1),
      rate_("gas::source_rate", grid.nr_total()),
      user_ghosts_("gas::user_ghosts", 2 * grid.ng),
      user_ghosts_h_(Kokkos::create_mirror_view(user_ghosts_)) {
  if (grid.geometry != mesh::Geometry::Cylindrical)
    throw core::DeckError("the gas disc needs grid.geometry = \"cylindrical\" (eq. 1-3 volumes for eq. 37)");
  if (grid.nr_global / grid.comm().size() < 2)  // the fewest cells of any rank: every rank refuses
    throw core::DeckError("the gas disc needs at least 2 radial cells per rank");
  j_mid_ = disc::midplane_index(grid);
  gas_.gravity = cfg_.gravity();
  gas_.column_fraction = disc::column_fraction(grid);
  const GasConfig c = cfg_;
  set_surface_density([c](double R) {
    const double x = R / c.R_ref;
    const double taper = c.R_c > 0 ? std::exp(-std::pow(R / c.R_c, 2.0 - c.Sigma_index)) : 1.0;
    const double cavity = c.R_cavity > 0 ? std::exp(-std::pow(c.R_cavity / R, c.cavity_index)) : 1.0;
    return c.Sigma0 * std::pow(x, -c.Sigma_index) * taper * cavity;
  });
}

void GasDisc::set_surface_density(const std::function<double(double R)>& profile) {
  auto host = Kokkos::create_mirror_view(gas_.Sigma);
  for (int i = grid_.i_begin(); i < grid_.i_end(); ++i) host(i) = profile(grid_.Rc_h(i));
  // Ghosts: the profile until fill_sigma_ghosts overwrites them by the boundary rule.
  for (int g = 0; g < grid_.ng; ++g) {
    host(g) = profile(grid_.Rc_h(g));
    host(grid_.i_end() + g) = profile(grid_.Rc_h(grid_.i_end() + g));
  }
  Kokkos::deep_copy(gas_.Sigma, host);
  if (boundary_values_ || (cfg_.inner != GasBoundary::User && cfg_.outer != GasBoundary::User))
    fill_sigma_ghosts(0.0);
  else
    gas_fill_sigma_ghosts(grid_, halo_, cfg_.inner, cfg_.outer, gas_.Sigma);
  update_structure();
}

void GasDisc::set_boundary_values(BoundaryValues values) { boundary_values_ = std::move(values); }

void GasDisc::add_source(SourceHook hook) { sources_.push_back(std::move(hook)); }

void GasDisc::set_temperature(const RealView2& T) {
  Kokkos::deep_copy(gas_.T, T);
  external_temperature_ = true;
}

void GasDisc::fill_sigma_ghosts(double time) {
  sigma_time_ = time;
  gas_fill_sigma_ghosts(grid_, halo_, cfg_.inner, cfg_.outer, gas_.Sigma);
  if (cfg_.inner != GasBoundary::User && cfg_.outer != GasBoundary::User) return;
  if (!boundary_values_)  // decided from the deck alone: every rank throws together
    throw std::logic_error("gas boundary \"user\" without GasDisc::set_boundary_values (the problem declares them)");
  const bool user_in = grid_.has_inner_boundary() && cfg_.inner == GasBoundary::User;
  const bool user_out = grid_.has_outer_boundary() && cfg_.outer == GasBoundary::User;
  if (!user_in && !user_out) return;
  const int ng = grid_.ng, ie = grid_.i_end();
  auto ghost = user_ghosts_;
  auto host = user_ghosts_h_;
  for (int g = 0; g < ng; ++g) {
    host(g) = user_in ? boundary_values_(grid_.Rc_h(g), time) : 0.0;
    host(ng + g) = user_out ? boundary_values_(grid_.Rc_h(ie + g), time) : 0.0;
  }
  Kokkos::deep_copy(ghost, host);
  auto Sigma = gas_.Sigma;
  par_for(
      "disc::gas_user_ghosts", 0, ng, KOKKOS_LAMBDA(int g) {
        if (user_in) Sigma(g) = ghost(g);
        if (user_out) Sigma(ie + g) = ghost(ng + g);
      });
}

void GasDisc::update_structure() {
  if (external_temperature_) {
    halo_.exchange(gas_.T);
    gas_sound_speed_from_temperature(cfg_, gas_.T, gas_.cs2);
  } else {
    gas_temperature_profile(grid_, cfg_, gas_.T, gas_.cs2);
  }
  gas_viscosity(grid_, cfg_, j_mid_, gas_.cs2, gas_.nu, gas_.nu_mid);
  gas_hydrostatic_density(grid_, cfg_.gravity(), gas_.column_fraction, cfg_.rho_floor, j_mid_, gas_.cs2, gas_.Sigma,
                          gas_.rho);
  gas_velocities(grid_, halo_, scratch_, gas_, cfg_.viscous_vR);
}

void GasDisc::evolve_surface_density(double dt, double time) {
  // User boundary values at the start of the step (throws if the problem gave none).
  if (cfg_.inner == GasBoundary::User || cfg_.outer == GasBoundary::User) fill_sigma_ghosts(time);
  gas_viscous_step(grid_, halo_, cfg_.inner, cfg_.outer, gas_.nu_mid, gas_.Sigma, Y_, G_, dt);
  auto Sigma = gas_.Sigma, rate = rate_;
  const Real floor = cfg_.Sigma_floor;
  const bool with_sources = !sources_.empty();
  if (with_sources) {
    Kokkos::deep_copy(rate_, 0.0);
    for (const auto& hook : sources_) hook(time, gas_, rate_);
  }
  // Sources by explicit Euler (sec. 3.3), then the floor.
  par_for(
      "disc::gas_sources", grid_.i_begin(), grid_.i_end(), KOKKOS_LAMBDA(int i) {
        const Real s = with_sources ? Sigma(i) + dt * rate(i) : Sigma(i);
        Sigma(i) = math::max(s, floor);
      });
  fill_sigma_ghosts(time + dt);
}

double GasDisc::max_dt() const {
  return grid_.comm().min(gas_viscous_max_dt(grid_, cfg_.inner, cfg_.outer, gas_.nu_mid, cfg_.cfl));
}

double GasDisc::mass() const {
  auto Sigma = gas_.Sigma;
  auto Re = grid_.Re;
  Real m = 0;
  par_reduce(
      "disc::gas_mass", grid_.i_begin(), grid_.i_end(),
      KOKKOS_LAMBDA(int i, Real& acc) { acc += Sigma(i) * 0.5 * (Re(i + 1) * Re(i + 1) - Re(i) * Re(i)); }, m);
  return 2.0 * math::pi() * grid_.comm().sum(m);
}

}  // namespace mote::disc
