// Writing (R, theta) grid data into snapshots and checkpoints: the grid as an
// XDMF structured mesh with nodes (R^e_i, R^e_i tan theta^e_j) in the (R, Z)
// plane, and active-cell extraction of device fields into row-major host
// arrays of this rank's rows (R index slow, theta index fast).
#pragma once

#include <vector>

#include "mote/io/h5_file.hpp"
#include "mote/io/snapshot.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::mesh {

/// Describes the grid in a snapshot (nodes + /data/R_centres, /data/theta_centres).
void describe_grid(io::SnapshotWriter& out, const Grid& grid);

/// This rank's block of a (nr_global, ntheta) cell array.
io::Block cell_block(const Grid& grid);

/// Active cells of a field (i, j) as a row-major (nr, nt) host array.
std::vector<double> active_cells(const Grid& grid, const RealView2& field);
/// Active cells of component k of species s of a state View (i, j, s, k); copies
/// the whole state to the host (for one (s, k): use active_cells_of_host for many).
std::vector<double> active_cells(const Grid& grid, const View<Real****>& state, int s, int k);

/// Active cells (i, j, trailing...) of a host copy of a field of any rank, e.g.
/// species s and component k of a state (i, j, s, k): copy a many-species field
/// to the host once per snapshot, then take each (s, k) from that copy.
template <class HostField, class... Trailing>
std::vector<double> active_cells_of_host(const Grid& grid, const HostField& h, Trailing... trailing) {
  std::vector<double> out(static_cast<size_t>(grid.nr) * grid.nt);
  for (int i = 0; i < grid.nr; ++i)
    for (int j = 0; j < grid.nt; ++j) out[i * grid.nt + j] = h(grid.ng + i, grid.ng + j, trailing...);
  return out;
}

/// Writes/reads a whole state View (i, j, s, k) of the active cells exactly
/// (checkpoints): dataset shape (nr_global, ntheta, species, components).
void write_state(io::H5File& file, const std::string& name, const Grid& grid, const View<Real****>& state);
void read_state(const io::H5File& file, const std::string& name, const Grid& grid, const View<Real****>& state);

}  // namespace mote::mesh
