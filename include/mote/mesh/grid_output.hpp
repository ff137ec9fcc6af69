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
/// Active cells of component k of species s of a state View (i, j, s, k).
std::vector<double> active_cells(const Grid& grid, const View<Real****>& state, int s, int k);

/// Writes/reads a whole state View (i, j, s, k) of the active cells exactly
/// (checkpoints): dataset shape (nr_global, ntheta, species, components).
void write_state(io::H5File& file, const std::string& name, const Grid& grid, const View<Real****>& state);
void read_state(const io::H5File& file, const std::string& name, const Grid& grid, const View<Real****>& state);

}  // namespace mote::mesh
