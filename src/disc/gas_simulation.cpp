// A gas-only disc simulation for the run loop (RBO24 sec. 3.3-3.5); see
// include/mote/disc/gas_simulation.hpp.
#include "mote/disc/gas_simulation.hpp"

#include "mote/core/loops.hpp"
#include "mote/mesh/grid_output.hpp"

namespace mote::disc {

void GasSimulation::declare(core::DeckSchema& schema) {
  mesh::GridSpec::declare(schema);
  GasDisc::declare(schema);
}

void GasSimulation::declare_with_boundary_values(core::DeckSchema& schema) {
  mesh::GridSpec::declare(schema);
  GasDisc::declare(schema, /*problem_boundary_values=*/true);
}

GasSimulation::GasSimulation(const core::Deck& deck, const core::Comm& comm, const units::UnitSystem& units)
    : units_(units),
      grid_(std::make_unique<mesh::Grid>(mesh::GridSpec::from_deck(deck), comm)),
      gas_(std::make_unique<GasDisc>(deck, *grid_, units)) {}

double GasSimulation::max_dt() { return gas_->max_dt(); }

void GasSimulation::advance(double time, double dt) {
  gas_->evolve_surface_density(dt, time);
  gas_->update_structure();
}

void GasSimulation::write_snapshot(io::SnapshotWriter& out) const {
  mesh::describe_grid(out, *grid_);
  gas_->write_snapshot(out);
}

void GasSimulation::save_state(io::H5File& file) const { gas_->save_state(file); }

void GasSimulation::load_state(const io::H5File& file) { gas_->load_state(file); }

std::vector<io::Diagnostic> GasSimulation::diagnostics() const {
  auto Sigma = gas_->fields().Sigma;
  Real smin = 0;
  par_reduce(
      "disc::gas_sigma_min", grid_->i_begin(), grid_->i_end(),
      KOKKOS_LAMBDA(int i, Real& m) { m = math::min(m, Sigma(i)); }, Kokkos::Min<Real>(smin));
  return {{"gas_mass", gas_->mass()}, {"Sigma_min", grid_->comm().min(smin)}};
}

std::optional<io::NonFinite> GasSimulation::find_non_finite() const { return gas_->find_non_finite(); }

}  // namespace mote::disc
