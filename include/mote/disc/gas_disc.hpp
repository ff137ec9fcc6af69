// The gas disc of RBO24 sec. 3.3-3.5 on the (R, theta) grid: the surface
// density evolves by the 1D viscous equation (eq. 26, gas_viscous.hpp) plus
// source hooks; the 2D state (temperature, cs^2, nu, hydrostatic rho of
// eq. 33-37, velocities of eq. 27-31) is rebuilt from it by update_structure().
// The dust solver reads fields() (GasFields, ghost cells filled).
//
// Typical use in a driver:
//   disc::GasDisc gas(deck, grid, units);        // initial Sigma from [gas], structure built
//   dt = min(dt_dust, gas.max_dt());
//   gas.evolve_surface_density(dt, time);         // eq. 26 + sources; Sigma ghosts refilled
//   gas.update_structure();                       // rho, cs2, nu, vR, vphi for the dust
//   mesh::describe_grid(out, grid); gas.write_snapshot(out);
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/gas_config.hpp"
#include "mote/disc/gas_fields.hpp"
#include "mote/disc/gas_velocities.hpp"
#include "mote/io/simulation.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/mesh/halo.hpp"

namespace mote::disc {

class GasDisc {
 public:
  /// Adds a surface-density source rate S_g (code surface density / code time)
  /// into `rate` on the active cells (e.g. wind mass loss, negative). Applied
  /// after the viscous step by explicit Euler (RBO24 sec. 3.3).
  using SourceHook = std::function<void(double time, const GasFields& gas, const RealView1& rate)>;
  /// Sigma at radius R and time t, for the ghost cells of "user" boundaries:
  /// a host function, so its 2 ng values are copied to the device on every
  /// gas sub-step (the one host-device copy inside a step, with "user" only).
  using BoundaryValues = std::function<double(double R, double time)>;

  /// Tables [gas] and [star]; "user" boundaries for a problem that calls set_boundary_values.
  static void declare(core::DeckSchema& schema, bool problem_boundary_values = false) {
    GasConfig::declare(schema, problem_boundary_values);
  }

  GasDisc(const core::Deck& deck, const mesh::Grid& grid, const units::UnitSystem& units);
  GasDisc(const GasConfig& config, const mesh::Grid& grid, const units::UnitSystem& units);

  const GasConfig& config() const { return cfg_; }
  const GasFields& fields() const { return gas_; }
  const mesh::Grid& grid() const { return grid_; }
  /// Local theta index of the cell nearest the mid-plane (reference of the scan, nu_mid).
  int midplane_index() const { return j_mid_; }

  /// Replaces Sigma by profile(R) on the active cells, refills the ghosts and rebuilds the structure.
  void set_surface_density(const std::function<double(double R)>& profile);
  /// Ghost values for "user" boundaries (required when one is selected).
  void set_boundary_values(BoundaryValues values);
  void add_source(SourceHook hook);
  /// Replaces the deck's temperature profile from now on (e.g. by the radiation
  /// solver): T (K, ghosts included) is copied; update_structure() then uses it.
  void set_temperature(const RealView2& T);

  /// T -> cs2, nu (sec. 3.4), hydrostatic rho (eq. 33-37), velocities (eq. 27-31).
  void update_structure();
  /// Advances Sigma by dt from `time` (eq. 26, then the sources), floors it and
  /// refills its ghosts. The 2D structure is not rebuilt (call update_structure()).
  void evolve_surface_density(double dt, double time = 0.0);
  /// Explicit limit of eq. 26 times gas.cfl, identical on every rank.
  double max_dt() const;

  /// Total gas mass 2 pi sum Sigma (R dR) over the active cells of all ranks.
  double mass() const;
  /// Checkpoint: Sigma (the evolved state) under `group`/Sigma.
  void save_state(io::H5File& file, const std::string& group = "/state/gas") const;
  /// Restores Sigma, refills the ghosts and rebuilds the structure.
  void load_state(const io::H5File& file, const std::string& group = "/state/gas");
  /// Cell fields gas_rho, gas_cs2, gas_T, gas_nu, gas_vR, gas_vphi, gas_vZ (nr, ntheta) on
  /// the mesh, which the caller describes first (mesh::describe_grid); /data arrays
  /// gas_Sigma, gas_nu_mid (nr).
  void write_snapshot(io::SnapshotWriter& out) const;
  /// The first active cell (i-major) with a field that fails first_failing_gas_field,
  /// in field order: one reduction.
  std::optional<io::NonFinite> find_non_finite() const;
  /// The report of gas field `field` (GasCheckField) failing at active cell `cell`
  /// ((i - i_begin) nt + j - j_begin).
  io::NonFinite describe_non_finite(int field, int cell) const;

  /// Ghost cells of Sigma from the boundary conditions at `time`. Public only
  /// because nvcc's extended lambdas may not live in private member functions.
  void fill_sigma_ghosts(double time);

 private:
  const mesh::Grid& grid_;
  GasConfig cfg_;
  units::UnitSystem units_;
  mesh::RadialHalo halo_;
  GasFields gas_;
  GasVelocityScratch scratch_;
  RealView1 Y_, G_, rate_;
  RealView1 user_ghosts_;  // Sigma of "user" boundary ghosts (inner ng, outer ng)
  HostView<Real*> user_ghosts_h_;
  int j_mid_ = 0;
  double sigma_time_ = 0.0;  // time of Sigma's user-boundary ghosts (checkpointed)
  bool external_temperature_ = false;
  BoundaryValues boundary_values_;
  std::vector<SourceHook> sources_;
};

}  // namespace mote::disc
