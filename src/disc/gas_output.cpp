// Snapshots, checkpoints and non-finite checks of the gas disc (RBO24 sec. 3.3-3.5);
// see include/mote/disc/gas_disc.hpp. 2D fields are cell fields of the grid
// described by mesh::describe_grid, (nr, ntheta); 1D arrays are /data/<name>
// with this rank's radial block (offset i_offset).
#include <climits>
#include <vector>

#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/disc/gas_disc.hpp"
#include "mote/disc/gas_structure.hpp"
#include "mote/mesh/grid_output.hpp"

namespace mote::disc {

namespace {

io::Block block_1d(const mesh::Grid& g) {
  io::Block b;
  b.global_dims = {hsize_t(g.nr_global)};
  b.offset = {hsize_t(g.i_offset)};
  b.count = {hsize_t(g.nr)};
  return b;
}

std::vector<double> active_1d(const mesh::Grid& g, const RealView1& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  std::vector<double> out(g.nr);
  for (int i = 0; i < g.nr; ++i) out[i] = h(g.i_begin() + i);
  return out;
}

}  // namespace

void GasDisc::write_snapshot(io::SnapshotWriter& out) const {
  const auto& u = units_;
  const double nu_unit = u.length * u.length / u.time;
  out.array("gas_Sigma", block_1d(grid_), active_1d(grid_, gas_.Sigma).data(),
            {"code surface density", u.surface_density()});
  out.array("gas_nu_mid", block_1d(grid_), active_1d(grid_, gas_.nu_mid).data(),
            {"code length^2 / code time", nu_unit});
  out.cell_field("gas_rho", mesh::active_cells(grid_, gas_.rho).data(), {"code density", u.density()});
  out.cell_field("gas_cs2", mesh::active_cells(grid_, gas_.cs2).data(),
                 {"code velocity^2", u.velocity() * u.velocity()});
  out.cell_field("gas_T", mesh::active_cells(grid_, gas_.T).data(), {"K", 1.0});
  out.cell_field("gas_nu", mesh::active_cells(grid_, gas_.nu).data(), {"code length^2 / code time", nu_unit});
  out.cell_field("gas_vR", mesh::active_cells(grid_, gas_.vR).data(), {"code velocity", u.velocity()});
  out.cell_field("gas_vphi", mesh::active_cells(grid_, gas_.vphi).data(), {"code velocity", u.velocity()});
  out.cell_field("gas_vZ", mesh::active_cells(grid_, gas_.vZ).data(), {"code velocity", u.velocity()});
}

void GasDisc::save_state(io::H5File& file, const std::string& group) const {
  file.create_group(group);
  file.write(group + "/Sigma", block_1d(grid_), active_1d(grid_, gas_.Sigma).data());
  file.write_attribute(group, "ghost_time", sigma_time_);
}

void GasDisc::load_state(const io::H5File& file, const std::string& group) {
  std::vector<double> sigma(grid_.nr);
  file.read(group + "/Sigma", block_1d(grid_), sigma.data());
  auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), gas_.Sigma);
  for (int i = 0; i < grid_.nr; ++i) host(grid_.i_begin() + i) = sigma[i];
  Kokkos::deep_copy(gas_.Sigma, host);
  fill_sigma_ghosts(file.read_attribute_real(group, "ghost_time"));
  update_structure();
}

std::optional<io::NonFinite> GasDisc::find_non_finite() const {
  const int ib = grid_.i_begin(), jb = grid_.j_begin(), nt = grid_.nt, cells = grid_.nr * grid_.nt;
  const GasFields g = gas_;
  int first = INT_MAX;  // field * cells + cell
  par_reduce(
      "disc::gas_non_finite", ib, grid_.i_end(), jb, grid_.j_end(),
      KOKKOS_LAMBDA(int i, int j, int& f) {
        const int field = first_failing_gas_field(g, i, j);
        if (field != kGasCheckFields) f = math::min(f, field * cells + (i - ib) * nt + (j - jb));
      },
      Kokkos::Min<int>(first));
  if (first == INT_MAX) return std::nullopt;
  return describe_non_finite(first / cells, first % cells);
}

io::NonFinite GasDisc::describe_non_finite(int field, int cell) const {
  const int i = cell / grid_.nt, j = cell % grid_.nt;
  if (field == kCheckSigma)
    return {"gas_Sigma",
            logging::format("radial cell %d, R = %g", i + grid_.i_offset, grid_.Rc_h(i + grid_.i_begin()))};
  const char* names[] = {"gas_rho", "gas_vR", "gas_vphi"};
  return {names[field - kCheckRho], logging::format("cell (i, j) = (%d, %d), R = %g, theta = %g", i + grid_.i_offset, j,
                                                    grid_.Rc_h(i + grid_.i_begin()), grid_.tc_h(j + grid_.j_begin()))};
}

}  // namespace mote::disc
