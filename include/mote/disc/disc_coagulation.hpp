// Coagulation and fragmentation as a sub-solver of the disc driver (RBO24
// sec. 5-6): the Smoluchowski equation (eq. 53-68, mote::coagulation) is
// integrated independently in every active cell of the (R, theta) grid over
// the time elapsed since the last call, with its own adaptive sub-steps.
//  * The species are the dust species of DustDynamics; their sizes must be
//    logarithmically spaced to 0.1 % (they define the mass grid, whose exactly
//    logarithmic sizes the kernel uses), grain density dust.rho_grain.
//  * Physical kernel with volume densities (eq. 56-60): gas density rho_g,
//    c_s = sqrt(cs2), Omega_K = sqrt(GM / R^3) at the cell's cylindrical R,
//    alpha = nu Omega_K / c_s^2 (nu = alpha c_s H), and the laminar relative
//    velocities from the dust primitive velocities (eq. 57). Evaluated in
//    cgs: densities, speeds and the interval are converted with the unit system.
//  * As cuDisc, only the density above the floor takes part (rho - floor,
//    clipped at 0), every species keeps its velocity, so its momenta
//    (rho v_R, rho v_phi R, rho v_Z) scale with its density: a grain that
//    changes bin takes the velocity of the bin it lands in. Mass is conserved
//    per cell to round-off; the dust momentum is not (cuDisc does the same;
//    the drag relaxes the velocities on the stopping time).
//  * next_interval() is the smallest sub-step the cells of all ranks propose
//    for their next call (Coagulation::next_substep, RBO24 sec. 6), for
//    Schedule::adaptive(); the proposals are saved in checkpoints.
#pragma once

#include <string>

#include "mote/coagulation/coagulation.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/dust_dynamics.hpp"
#include "mote/disc/gas_fields.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::disc {

class DiscCoagulation {
 public:
  /// `settings` gives the kernel options and tolerances ([coagulation]); its
  /// grid keys (a_min, a_max, species, rho_m) are replaced by the dust
  /// species. Throws core::DeckError for sizes that are not logarithmically
  /// spaced or a vertically integrated kernel.
  DiscCoagulation(const mesh::Grid& grid, DustDynamics& dust, coagulation::CoagulationSettings settings,
                  const units::UnitSystem& units);

  /// Coagulates every active cell over `elapsed` (code time) with the gas state `gas`.
  coagulation::CallStatistics update(const GasFields& gas, double elapsed);
  /// Smallest proposed next sub-step over the cells of all ranks (code time; 0 before the first call).
  double next_interval() const { return next_interval_; }

  /// The proposed next sub-step of every cell, as `name` ((nr_global nt) values).
  void save_state(io::H5File& file, const std::string& name = "/state/coagulation_next_substep") const;
  void load_state(const io::H5File& file, const std::string& name = "/state/coagulation_next_substep");

  const coagulation::MassGrid& mass_grid() const { return mass_grid_; }
  const coagulation::CoagulationSettings& settings() const { return settings_; }
  const coagulation::Coagulation& solver() const { return solver_; }
  /// Cell index of the coagulation solver for active cell (i, j): (i - i_begin) nt + (j - j_begin).
  int cell(int i, int j) const { return (i - grid_.i_begin()) * grid_.nt + (j - grid_.j_begin()); }

  /// The smallest positive proposal of the solver's cells on this rank (the
  /// largest Real where none proposes one). Public only because nvcc's extended
  /// lambdas may not live in private member functions.
  Real local_min_next_substep() const;

 private:
  /// next_interval_ from this rank's smallest proposal (the global minimum).
  void set_next_interval(Real local_min);

  const mesh::Grid& grid_;
  DustDynamics& dust_;
  units::UnitSystem units_;
  coagulation::CoagulationSettings settings_;
  coagulation::MassGrid mass_grid_;
  coagulation::Coagulation solver_;
  coagulation::GasCells cells_;
  RealView2 density_, before_;  // (cells, species) cgs density above the floor, and its value before the call
  double next_interval_ = 0.0;

  io::Block cell_block() const;
};

}  // namespace mote::disc
