// The FLD state in checkpoints (see include/mote/radiation/fld_state_io.hpp).
#include "mote/radiation/fld_state_io.hpp"

#include "mote/mesh/grid_output.hpp"

namespace mote::radiation {

namespace {

View<Real****> packed_view(const mesh::Grid& grid, const FldState& state) {
  return View<Real****>("radiation::fld_state_packed", grid.nr_total(), grid.nt_total(), 1, 1 + state.E.extent(2));
}

}  // namespace

void write_fld_state(io::H5File& file, const std::string& name, const mesh::Grid& grid, const FldState& state) {
  const auto packed = packed_view(grid, state);
  const int nb = static_cast<int>(state.E.extent(2));
  const auto T = state.T;
  const auto E = state.E;
  par_for(
      "radiation::fld_state_pack", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        packed(i, j, 0, 0) = T(i, j);
        for (int b = 0; b < nb; ++b) packed(i, j, 0, 1 + b) = E(i, j, b);
      });
  mesh::write_state(file, name, grid, packed);
}

void read_fld_state(const io::H5File& file, const std::string& name, const mesh::Grid& grid, const FldState& state) {
  const auto packed = packed_view(grid, state);
  mesh::read_state(file, name, grid, packed);
  const int nb = static_cast<int>(state.E.extent(2));
  const auto T = state.T;
  const auto E = state.E;
  par_for(
      "radiation::fld_state_unpack", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        T(i, j) = packed(i, j, 0, 0);
        for (int b = 0; b < nb; ++b) E(i, j, b) = packed(i, j, 0, 1 + b);
      });
}

}  // namespace mote::radiation
