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
}

void SnapshotWriter::structured_2d(const double* x_nodes, const double* y_nodes, int rows_total, int cols, int row_begin,
                                   int rows) {
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

void SnapshotWriter::array(const std::string& name, const Block& block, const double* data, const FieldUnit& unit) {
  const std::string path = "/data/" + name;
  file_.write(path, block, data);
  file_.write_attribute(path, "unit", unit.label);
  file_.write_attribute(path, "to_cgs", unit.to_cgs);
}

std::string SnapshotWriter::xdmf(const std::string& h5_name, double time) const {
  if (mesh_ == Mesh::None) return {};  // no mesh described: nothing for a visualiser
  std::ostringstream os;
  os << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  os << "  <Grid Name=\"mesh\" GridType=\"Uniform\">\n";
  os << "   <Time Value=\"" << log::format("%.17g", time) << "\"/>\n";
  const std::string item = "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5_name;
  if (mesh_ == Mesh::Rectilinear) {
    os << "   <Topology TopologyType=\"2DRectMesh\" Dimensions=\"" << ny_ + 1 << " " << nx_ + 1 << "\"/>\n";
    os << "   <Geometry GeometryType=\"VXVY\">\n";
    os << "    <DataItem Dimensions=\"" << nx_ + 1 << item << ":/mesh/x_nodes</DataItem>\n";
    os << "    <DataItem Dimensions=\"" << ny_ + 1 << item << ":/mesh/y_nodes</DataItem>\n";
  } else {
    const std::string dims = std::to_string(ny_ + 1) + " " + std::to_string(nx_ + 1);
    os << "   <Topology TopologyType=\"2DSMesh\" Dimensions=\"" << dims << "\"/>\n";
    os << "   <Geometry GeometryType=\"X_Y\">\n";
    os << "    <DataItem Dimensions=\"" << dims << item << ":/mesh/x_nodes</DataItem>\n";
    os << "    <DataItem Dimensions=\"" << dims << item << ":/mesh/y_nodes</DataItem>\n";
  }
  os << "   </Geometry>\n";
  for (const auto& f : cell_fields_) {
    os << "   <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
    os << "    <DataItem Dimensions=\"" << ny_ << " " << nx_ << item << ":/fields/" << f << "</DataItem>\n";
    os << "   </Attribute>\n";
  }
  os << "  </Grid>\n </Domain>\n</Xdmf>\n";
  return os.str();
}

}  // namespace mote::io
