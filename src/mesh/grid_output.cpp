// Grid data in snapshots and checkpoints (see include/mote/mesh/grid_output.hpp).
#include "mote/mesh/grid_output.hpp"

#include <cmath>

namespace mote::mesh {

void describe_grid(io::SnapshotWriter& out, const Grid& grid) {
  const int nr = grid.nr, nt = grid.nt, ng = grid.ng;
  std::vector<double> x((nr + 1) * (nt + 1)), y(x.size());
  for (int a = 0; a <= nr; ++a)
    for (int b = 0; b <= nt; ++b) {
      const double R = grid.Re_h(ng + a), t = grid.te_h(ng + b);
      x[a * (nt + 1) + b] = R;
      y[a * (nt + 1) + b] = R * std::tan(t);
    }
  out.structured_2d(x.data(), y.data(), grid.nr_global, nt, grid.i_offset, nr);
  std::vector<double> rc(grid.nr_global), tc(nt);
  const auto& re = grid.r_edges_global;
  for (int i = 0; i < grid.nr_global; ++i) rc[i] = 0.5 * (re[i] + re[i + 1]);
  for (int j = 0; j < nt; ++j) tc[j] = 0.5 * (grid.theta_edges_global[j] + grid.theta_edges_global[j + 1]);
  out.array("R_centres", io::Block::whole({rc.size()}), rc.data(), {"code length", 1.0});
  out.array("theta_centres", io::Block::whole({tc.size()}), tc.data(), {"rad", 1.0});
}

io::Block cell_block(const Grid& grid) {
  io::Block b;
  b.global_dims = {hsize_t(grid.nr_global), hsize_t(grid.nt)};
  b.offset = {hsize_t(grid.i_offset), 0};
  b.count = {hsize_t(grid.nr), hsize_t(grid.nt)};
  return b;
}

std::vector<double> active_cells(const Grid& grid, const RealView2& field) {
  return active_cells_of_host(grid, Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), field));
}

std::vector<double> active_cells(const Grid& grid, const View<Real****>& state, int s, int k) {
  return active_cells_of_host(grid, Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), state), s, k);
}

namespace {
io::Block state_block(const Grid& grid, const View<Real****>& state) {
  io::Block b;
  const hsize_t ns = state.extent(2), nk = state.extent(3);
  b.global_dims = {hsize_t(grid.nr_global), hsize_t(grid.nt), ns, nk};
  b.offset = {hsize_t(grid.i_offset), 0, 0, 0};
  b.count = {hsize_t(grid.nr), hsize_t(grid.nt), ns, nk};
  return b;
}
}  // namespace

void write_state(io::H5File& file, const std::string& name, const Grid& grid, const View<Real****>& state) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), state);
  const int ns = static_cast<int>(state.extent(2)), nk = static_cast<int>(state.extent(3));
  std::vector<double> buf(static_cast<size_t>(grid.nr) * grid.nt * ns * nk);
  size_t n = 0;
  for (int i = 0; i < grid.nr; ++i)
    for (int j = 0; j < grid.nt; ++j)
      for (int s = 0; s < ns; ++s)
        for (int k = 0; k < nk; ++k) buf[n++] = h(grid.ng + i, grid.ng + j, s, k);
  file.write(name, state_block(grid, state), buf.data());
}

void read_state(const io::H5File& file, const std::string& name, const Grid& grid, const View<Real****>& state) {
  const int ns = static_cast<int>(state.extent(2)), nk = static_cast<int>(state.extent(3));
  std::vector<double> buf(static_cast<size_t>(grid.nr) * grid.nt * ns * nk);
  file.read(name, state_block(grid, state), buf.data());
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), state);
  size_t n = 0;
  for (int i = 0; i < grid.nr; ++i)
    for (int j = 0; j < grid.nt; ++j)
      for (int s = 0; s < ns; ++s)
        for (int k = 0; k < nk; ++k) h(grid.ng + i, grid.ng + j, s, k) = buf[n++];
  Kokkos::deep_copy(state, h);
}

}  // namespace mote::mesh
