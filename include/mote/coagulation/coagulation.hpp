// The coagulation solver (RBO24 sec. 5-6): the Smoluchowski equation with
// fragmentation (eq. 53-68) integrated independently in every cell with
// adaptive Bogacki-Shampine 3(2) sub-steps (bs32.hpp).
// Work is done in batches of cells: for each batch one team per cell first
// evaluates the kernel policy for all species pairs (stored per pair as
// K p_coag and K p_frag, halved for i = j), then one team per cell integrates
// its densities over the call's interval with its own sub-steps, the pair
// loops running over the team's threads with the state in team scratch.
// The proposal for the next sub-step of every cell is kept (next_substep) so
// the driver can schedule the next call (RBO24 sec. 6) and the next call
// starts from it.
#pragma once

#include <variant>

#include "mote/coagulation/cell_rates.hpp"
#include "mote/coagulation/collision_tables.hpp"
#include "mote/coagulation/kernels.hpp"
#include "mote/coagulation/mass_grid.hpp"
#include "mote/coagulation/settings.hpp"
#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

using AnyKernel = std::variant<ConstantKernel, AdditiveKernel, ProductKernel, PhysicalKernel>;

/// Builds the kernel policy named by settings.kernel; `gas` is used by the physical kernel.
AnyKernel make_kernel(const CoagulationSettings& settings, const MassGrid& grid, const GasCells& gas = {});

/// Totals of one call over all cells.
struct CallStatistics {
  long long substeps = 0;     // accepted sub-steps
  long long rejections = 0;   // rejected sub-steps
  int failed_cells = 0;       // cells that hit max_substeps or a vanishing step
  Real min_next_substep = 0;  // smallest proposed next sub-step (driver scheduling)
};

class Coagulation {
 public:
  /// Solver for `cells` cells on `grid`, options from `settings` (tolerances,
  /// fragments, chi_im, batch size).
  Coagulation(const MassGrid& grid, const CoagulationSettings& settings, int cells);

  /// Advances density(cell, species) (mass density per species) by dt.
  CallStatistics integrate(const RealView2& density, Real dt, const AnyKernel& kernel);
  template <class Kernel>
  CallStatistics integrate_with(const RealView2& density, Real dt, const Kernel& kernel);

  /// d(density)/dt of every cell (no integration), e.g. for tests.
  void rates(const RealView2& density, const AnyKernel& kernel, const RealView2& dydt);
  template <class Kernel>
  void rates_with(const RealView2& density, const Kernel& kernel, const RealView2& dydt);

  /// Proposed next sub-step per cell (0 before the first call); restored on restart.
  RealView1 next_substep() const { return next_substep_; }
  /// Accepted and rejected sub-steps per cell in the last call.
  IntView1 substeps() const { return substeps_; }
  IntView1 rejections() const { return rejections_; }

  const MassGrid& grid() const { return grid_; }
  const CollisionTables& tables() const { return tables_; }
  int cells() const { return cells_; }
  const CoagulationSettings& settings() const { return settings_; }

  /// Stores K p_coag and K p_frag of every pair of cells [first, first + count) in the batch arrays.
  template <class Kernel>
  void evaluate_pairs(int first, int count, const Kernel& kernel);

 private:
  MassGrid grid_;
  CoagulationSettings settings_;
  int cells_ = 0, batch_ = 0, team_size_ = 0;
  CollisionTables tables_;
  PairCoefficients k_coag_, k_frag_;
  RealView1 next_substep_;
  IntView1 substeps_, rejections_, failed_;
};

}  // namespace mote::coagulation
