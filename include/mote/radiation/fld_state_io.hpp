// The temperature and band energies of an FLD state in checkpoints: one
// (nr_total, nt_total, 1, 1 + bands) state dataset (T, then E^b), written and
// read with mesh::write_state / read_state, shared by every simulation that
// holds an FldState (the disc driver's temperature, disc_irradiation,
// fld_benchmarks).
#pragma once

#include <string>

#include "mote/io/h5_file.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/radiation/fld.hpp"

namespace mote::radiation {

/// Writes T and E of `state` (ghost cells included) as the state dataset `name`.
void write_fld_state(io::H5File& file, const std::string& name, const mesh::Grid& grid, const FldState& state);
/// Reads them back into the active cells of `state`.
void read_fld_state(const io::H5File& file, const std::string& name, const mesh::Grid& grid, const FldState& state);

}  // namespace mote::radiation
