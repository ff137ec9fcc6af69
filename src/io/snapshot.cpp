// HDF5 snapshot content and XDMF descriptor (see include/mote/io/snapshot.hpp).
#include "mote/io/snapshot.hpp"

#include <sstream>
#include <stdexcept>

#include "mote/core/log.hpp"

namespace mote::io {

void SnapshotWriter::rectilinear_2d(const std::vector<double>& x_nodes, const std::vector<double>& y_nodes,
                                    int row_begin, int rows) {
  if (x_nodes.size() < 2 || y_nodes.size() < 2) throw std::logic_error("rectilinear_2d: need at least one cell");
  nx_ = static_cast<int>(x_nodes.size()) - 1;
  ny_ = static_cast<int>(y_nodes.size()) - 1;
  row_begin_ = row_begin;
  rows_ = rows;
  mesh_ = Mesh::Rectilinear;
  file_.write("/mesh/x_nodes", Block::whole({x_nodes.size()}), x_nodes.data());
  file_.write("/mesh/y_nodes", Block::whole({y_nodes.size()}), y_nodes.data());
  // The same nodes as a structured mesh, as the XDMF descriptor gives them: this rank's node rows.
  const int node_rows = rows + (row_begin + rows == ny_ ? 1 : 0);
  std::vector<double> xy(static_cast<size_t>(node_rows) * (nx_ + 1) * 2);
  for (int a = 0; a < node_rows; ++a)
    for (int b = 0; b <= nx_; ++b) {
      xy[(static_cast<size_t>(a) * (nx_ + 1) + b) * 2] = x_nodes[b];
      xy[(static_cast<size_t>(a) * (nx_ + 1) + b) * 2 + 1] = y_nodes[row_begin + a];
    }
  write_xy_nodes(xy.data(), node_rows);
}

void SnapshotWriter::write_xy_nodes(const double* xy, int node_rows) {
  Block b;
  b.global_dims = {hsize_t(ny_ + 1), hsize_t(nx_ + 1), 2};
  b.offset = {hsize_t(row_begin_), 0, 0};
  b.count = {hsize_t(node_rows), hsize_t(nx_ + 1), 2};
  file_.write("/mesh/xy_nodes", b, xy);
}

void SnapshotWriter::structured_2d(const double* x_nodes, const double* y_nodes, int rows_total, int cols,
                                   int row_begin, int rows) {
  ny_ = rows_total;
  nx_ = cols;
  row_begin_ = row_begin;
  rows_ = rows;
  mesh_ = Mesh::Structured;
  const bool last = row_begin + rows == rows_total;
  Block b;
  b.global_dims = {hsize_t(rows_total + 1), hsize_t(cols + 1)};
  b.offset = {hsize_t(row_begin), 0};
  b.count = {hsize_t(rows + (last ? 1 : 0)), hsize_t(cols + 1)};
  file_.write("/mesh/x_nodes", b, x_nodes);
  file_.write("/mesh/y_nodes", b, y_nodes);
  const int node_rows = static_cast<int>(b.count[0]);
  std::vector<double> xy(static_cast<size_t>(node_rows) * (cols + 1) * 2);
  for (size_t k = 0; k < xy.size() / 2; ++k) {
    xy[2 * k] = x_nodes[k];
    xy[2 * k + 1] = y_nodes[k];
  }
  write_xy_nodes(xy.data(), node_rows);
}

void SnapshotWriter::cell_field(const std::string& name, const double* data, const FieldUnit& unit) {
  if (mesh_ == Mesh::None) throw std::logic_error("cell_field before the mesh was described");
  Block b;
  b.global_dims = {static_cast<hsize_t>(ny_), static_cast<hsize_t>(nx_)};
  b.offset = {static_cast<hsize_t>(row_begin_), 0};
  b.count = {static_cast<hsize_t>(rows_), static_cast<hsize_t>(nx_)};
  const std::string path = "/fields/" + name;
  file_.write(path, b, data);
  file_.write_attribute(path, "unit", unit.label);
  file_.write_attribute(path, "to_cgs", unit.to_cgs);
  cell_fields_.push_back(name);
}

void SnapshotWriter::particles(long long n_total, long long offset, long long count, const double* xyz) {
  mesh_ = Mesh::Particles;
  n_particles_ = n_total;
  particle_offset_ = offset;
  particle_count_ = count;
  Block b;
  b.global_dims = {hsize_t(n_total), 3};
  b.offset = {hsize_t(offset), 0};
  b.count = {hsize_t(count), 3};
  file_.write("/particles/position", b, xyz);
  // Vertex cells 0..n-1: Xdmf3 makes no cells of a Polyvertex topology without them.
  std::vector<std::int64_t> vertices(static_cast<size_t>(count));
  for (long long k = 0; k < count; ++k) vertices[k] = offset + k;
  Block v;
  v.global_dims = {hsize_t(n_total)};
  v.offset = {hsize_t(offset)};
  v.count = {hsize_t(count)};
  file_.write("/mesh/vertices", v, vertices.data());
}

void SnapshotWriter::particle_field(const std::string& name, const double* data, int components,
                                    const FieldUnit& unit) {
  if (mesh_ != Mesh::Particles) throw std::logic_error("particle_field before particles()");
  Block b;
  b.global_dims = {hsize_t(n_particles_)};
  b.offset = {hsize_t(particle_offset_)};
  b.count = {hsize_t(particle_count_)};
  if (components > 1) {
    b.global_dims.push_back(hsize_t(components));
    b.offset.push_back(0);
    b.count.push_back(hsize_t(components));
  }
  const std::string path = "/particles/" + name;
  file_.write(path, b, data);
  file_.write_attribute(path, "unit", unit.label);
  file_.write_attribute(path, "to_cgs", unit.to_cgs);
  particle_fields_.push_back({name, components, false});
}

void SnapshotWriter::particle_field(const std::string& name, const std::int32_t* data, const FieldUnit& unit) {
  if (mesh_ != Mesh::Particles) throw std::logic_error("particle_field before particles()");
  Block b;
  b.global_dims = {hsize_t(n_particles_)};
  b.offset = {hsize_t(particle_offset_)};
  b.count = {hsize_t(particle_count_)};
  const std::string path = "/particles/" + name;
  file_.write(path, b, data);
  file_.write_attribute(path, "unit", unit.label);
  file_.write_attribute(path, "to_cgs", unit.to_cgs);
  particle_fields_.push_back({name, 1, true});
}

void SnapshotWriter::array(const std::string& name, const Block& block, const double* data, const FieldUnit& unit) {
  const std::string path = "/data/" + name;
  file_.write(path, block, data);
  file_.write_attribute(path, "unit", unit.label);
  file_.write_attribute(path, "to_cgs", unit.to_cgs);
}

std::string SnapshotWriter::xdmf_grid(const std::string& h5_name, double time) const {
  if (mesh_ == Mesh::None) return {};  // no mesh described: nothing for a visualiser
  // Forms both of ParaView's readers (legacy "XDMF Reader", Xdmf3) open correctly, checked
  // with ParaView 5.11 (tests/regression/paraview_readers.py): the legacy reader draws a
  // 2DRectMesh as a line and drops cell data of 3D meshes with one node layer; Xdmf3
  // crashes on 2DSMesh with X_Y geometry and makes no cells of a Polyvertex without
  // connectivity. Both meshes are therefore 2DSMesh with one interleaved XY node array.
  std::ostringstream os;
  os << "  <Grid Name=\"mesh\" GridType=\"Uniform\">\n";
  os << "   <Time Value=\"" << logging::format("%.17g", time) << "\"/>\n";
  const std::string float_item = "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">";
  const std::string int_item = "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">";
  const std::string item = float_item + h5_name;
  if (mesh_ == Mesh::Particles) {
    os << "   <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n_particles_
       << "\" NodesPerElement=\"1\">\n";
    os << "    <DataItem Dimensions=\"" << n_particles_ << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">"
       << h5_name << ":/mesh/vertices</DataItem>\n";
    os << "   </Topology>\n";
    os << "   <Geometry GeometryType=\"XYZ\">\n";
    os << "    <DataItem Dimensions=\"" << n_particles_ << " 3" << item << ":/particles/position</DataItem>\n";
  } else {
    const std::string dims = std::to_string(ny_ + 1) + " " + std::to_string(nx_ + 1);
    os << "   <Topology TopologyType=\"2DSMesh\" Dimensions=\"" << dims << "\"/>\n";
    os << "   <Geometry GeometryType=\"XY\">\n";
    os << "    <DataItem Dimensions=\"" << dims << " 2" << item << ":/mesh/xy_nodes</DataItem>\n";
  }
  os << "   </Geometry>\n";
  for (const auto& f : cell_fields_) {
    os << "   <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
    os << "    <DataItem Dimensions=\"" << ny_ << " " << nx_ << item << ":/fields/" << f << "</DataItem>\n";
    os << "   </Attribute>\n";
  }
  for (const auto& f : particle_fields_) {
    const std::string dims =
        std::to_string(n_particles_) + (f.components > 1 ? " " + std::to_string(f.components) : "");
    const char* type = f.components == 1 ? "Scalar" : f.components == 3 ? "Vector" : "Matrix";
    os << "   <Attribute Name=\"" << f.name << "\" AttributeType=\"" << type << "\" Center=\"Node\">\n";
    os << "    <DataItem Dimensions=\"" << dims << (f.integer ? int_item : float_item) << h5_name << ":/particles/"
       << f.name << "</DataItem>\n";
    os << "   </Attribute>\n";
  }
  os << "  </Grid>\n";
  return os.str();
}

namespace {
const char* const kXdmfHead =
    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
const char* const kXdmfTail = " </Domain>\n</Xdmf>\n";
}  // namespace

std::string SnapshotWriter::xdmf(const std::string& h5_name, double time) const {
  const std::string grid = xdmf_grid(h5_name, time);
  return grid.empty() ? grid : kXdmfHead + grid + kXdmfTail;
}

std::string xdmf_time_series(const std::vector<std::string>& grids) {
  std::string s = kXdmfHead;
  s += "  <Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& g : grids) {
    std::istringstream in(g);  // one level deeper
    for (std::string line; std::getline(in, line);) s += " " + line + "\n";
  }
  s += "  </Grid>\n";
  return s + kXdmfTail;
}

std::string xdmf_grid_of(const std::string& xdmf_text) {
  const size_t begin = xdmf_text.find("  <Grid ");
  const size_t end = xdmf_text.rfind("</Grid>");
  if (begin == std::string::npos || end == std::string::npos || end < begin) return {};
  return xdmf_text.substr(begin, end + 7 - begin) + "\n";
}

}  // namespace mote::io
