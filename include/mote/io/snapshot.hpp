// HDF5 snapshots with an XDMF descriptor, so that ParaView and VisIt open the
// output directly. Layout of a snapshot file:
//   /                 attributes: time, step, problem, code_version, deck (resolved TOML),
//                     unit_system, unit_length_cm, unit_mass_g, unit_time_s
//   /mesh/x_nodes, /mesh/y_nodes        node coordinates: 1D for a rectilinear mesh,
//                                       2D (rows + 1, cols + 1) for a structured one
//   /mesh/xy_nodes    (rows + 1, cols + 1, 2): the nodes of either mesh interleaved, which
//                     the XDMF descriptor references (a 2DSMesh with XY geometry)
//   /mesh/vertices    (n) int64 0..n-1: the particles' vertex cells in the XDMF descriptor
//   /fields/<name>    cell data, shape (ny, nx); attributes unit (text), to_cgs (factor)
//   /particles/position (n, 3) and /particles/<name> (n) or (n, 3): particle data
//   /data/<name>      other arrays (grain-size grids, distributions), same attributes
// A Simulation describes its mesh and fields through SnapshotWriter; the run
// loop adds the root attributes and commits the file and its .xmf.
#pragma once

#include <string>
#include <vector>

#include "mote/io/h5_file.hpp"

namespace mote::io {

/// Unit of a field: a label and the factor that converts code values to cgs.
struct FieldUnit {
  std::string label;
  double to_cgs = 1.0;
};

class SnapshotWriter {
 public:
  explicit SnapshotWriter(H5File& file) : file_(file) {}

  /// 2D rectilinear mesh with global node coordinates; this rank holds the
  /// cell rows [row_begin, row_begin + rows) of all nx columns.
  void rectilinear_2d(const std::vector<double>& x_nodes, const std::vector<double>& y_nodes, int row_begin, int rows);
  /// 2D structured (curvilinear) mesh of rows_total x cols cells, e.g. the
  /// (R, theta) disc grid with rows = R cells and cols = theta cells. This rank
  /// holds cell rows [row_begin, row_begin + rows); `x_nodes` and `y_nodes` are
  /// its node coordinates, row-major ((rows + 1) x (cols + 1)); the node row
  /// shared with the next rank is written by the rank that owns the last row.
  void structured_2d(const double* x_nodes, const double* y_nodes, int rows_total, int cols, int row_begin, int rows);
  /// Cell-centred field of this rank's rows, row-major (rows, cols), host memory.
  void cell_field(const std::string& name, const double* data, const FieldUnit& unit);

  /// Particles: n_total particles over all ranks, this rank holding [offset,
  /// offset + count); positions as (count, 3) row-major (unused dimensions 0),
  /// written to /particles/position and described as an XDMF point cloud.
  void particles(long long n_total, long long offset, long long count, const double* xyz);
  /// Per-particle data of this rank: `components` values per particle (1: scalar,
  /// 3: vector, other: one column per component, e.g. dust species).
  void particle_field(const std::string& name, const double* data, int components, const FieldUnit& unit);
  void particle_field(const std::string& name, const std::int32_t* data, const FieldUnit& unit);

  /// Any other array (not part of the XDMF mesh description), e.g. a grain-size
  /// grid or a per-cell size distribution, under "/data/<name>"; `block` is
  /// this rank's part (Block::whole for arrays identical on every rank).
  void array(const std::string& name, const Block& block, const double* data, const FieldUnit& unit);

  /// XDMF text describing the mesh and fields of this snapshot; `h5_name` is
  /// the snapshot's file name relative to the .xmf file. Empty without a mesh.
  std::string xdmf(const std::string& h5_name, double time) const;
  /// The snapshot's <Grid> element alone (what xdmf() wraps), for a time series.
  std::string xdmf_grid(const std::string& h5_name, double time) const;

  H5File& file() { return file_; }

 private:
  enum class Mesh { None, Rectilinear, Structured, Particles };
  void write_xy_nodes(const double* xy, int node_rows);
  H5File& file_;
  Mesh mesh_ = Mesh::None;
  int nx_ = 0, ny_ = 0, row_begin_ = 0, rows_ = 0;  // cells: ny_ rows of nx_ columns
  std::vector<std::string> cell_fields_;
  long long n_particles_ = 0, particle_offset_ = 0, particle_count_ = 0;
  struct ParticleField {
    std::string name;
    int components;
    bool integer;
  };
  std::vector<ParticleField> particle_fields_;
};

/// A temporal collection of snapshot <Grid> elements (SnapshotWriter::xdmf_grid),
/// so that a whole run opens in ParaView as one animation.
std::string xdmf_time_series(const std::vector<std::string>& grids);
/// The <Grid> element of a snapshot's XDMF text (as written by xdmf()), or "".
std::string xdmf_grid_of(const std::string& xdmf_text);

}  // namespace mote::io
