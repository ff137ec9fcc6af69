// A set of independent cells whose size distributions evolve by coagulation
// and fragmentation alone (no dust dynamics): the io::Simulation shared by the
// standalone coagulation problems (VALIDATION E1-E3). The state is the mass
// (or surface) density of every species in every cell, density(cell, species);
// each advance() is one coagulation call over the interval (RBO24 sec. 6), and
// the last proposed sub-step of every cell is checkpointed with the densities
// so that restarts continue identically.
#pragma once

#include <string>
#include <vector>

#include "mote/coagulation/coagulation.hpp"
#include "mote/io/simulation.hpp"

namespace mote::coagulation {

class StandaloneCells : public io::Simulation {
 public:
  /// `initial` is one cell's distribution (species values), copied to every cell;
  /// `call_interval` <= 0 means one call per output interval.
  StandaloneCells(const MassGrid& grid, const CoagulationSettings& settings, int cells, AnyKernel kernel,
                  const std::vector<double>& initial, double call_interval, io::FieldUnit density_unit);

  double max_dt() override;
  void advance(double time, double dt) override;
  void save_state(io::H5File& file) const override;
  void load_state(const io::H5File& file) override;
  std::vector<io::Diagnostic> diagnostics() const override;
  std::optional<io::NonFinite> find_non_finite() const override;
  /// Total density of one cell (all cells are identical in these problems: the mean).
  double total_density() const;

 protected:
  /// Writes the mass grid (/data/mass, /data/mass_edges, /data/grain_size) and
  /// the densities (/data/density, cells x species).
  void write_distribution(io::SnapshotWriter& out, const io::FieldUnit& mass_unit,
                          const io::FieldUnit& size_unit) const;
  /// Row-major (cells, species) host copy of the densities.
  std::vector<double> host_density() const;
  /// Mass error relative to the initial state and call statistics, for messages.
  std::string summary() const;

  MassGrid grid_;
  Coagulation solver_;
  AnyKernel kernel_;
  RealView2 density_;
  int cells_;
  double call_interval_;
  io::FieldUnit density_unit_;
  double total0_ = 0.0;
  double elapsed_ = 0.0;  // time integrated so far (checkpointed)
  long long substeps_ = 0, rejections_ = 0;
};

}  // namespace mote::coagulation
