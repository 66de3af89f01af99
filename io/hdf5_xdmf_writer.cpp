#include "io/hdf5_xdmf_writer.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/hdf5_support.hpp"
#include "io/setting_check.hpp"

namespace isomuscle::io {

namespace {

using hdf5::create_group;
using hdf5::Handle;
using hdf5::numbered;
using hdf5::write_dataset;
using hdf5::write_scalar_attribute;
using QuietHdf5 = hdf5::Quiet;

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

const char* attribute_type(Eigen::Index columns) {
  return columns == 1 ? "Scalar" : columns == 3 ? "Vector" : "Tensor";
}

}  // namespace

int nodes_per_cell(CellType type) {
  switch (type) {
    case CellType::hexahedron8:
      return 8;
    case CellType::tetrahedron4:
      return 4;
    case CellType::tetrahedron10:
      return 10;
  }
  return 0;
}

const char* xdmf_topology_name(CellType type) {
  switch (type) {
    case CellType::hexahedron8:
      return "Hexahedron";
    case CellType::tetrahedron4:
      return "Tetrahedron";
    case CellType::tetrahedron10:
      return "Tetrahedron_10";
  }
  return "?";
}

Hdf5XdmfWriter::Hdf5XdmfWriter(std::filesystem::path xdmf_path)
    : xdmf_path_(std::move(xdmf_path)), h5_path_(xdmf_path_) {
  if (xdmf_path_.extension() != ".xdmf") {
    throw std::invalid_argument("field output " + xdmf_path_.string() +
                                ": the index file must end in .xdmf");
  }
  h5_path_.replace_extension(".h5");
  std::error_code ec;
  std::filesystem::remove(xdmf_path_, ec);  // a stale index would point into the new .h5
  if (ec) {
    throw std::runtime_error("cannot remove the old " + xdmf_path_.string() + ": " + ec.message());
  }
  QuietHdf5 quiet;
  Handle file(H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
              "creating HDF5 file " + h5_path_.string());
  file.close("closing " + h5_path_.string());
}

void Hdf5XdmfWriter::set_mesh(const OutputMesh& mesh) {
  const std::string where =
      "field output " + h5_path_.string() + ", mesh " + std::to_string(meshes_.size());
  const Eigen::Index nodes = nodes_per_cell(mesh.cell_type);
  if (mesh.points.rows() == 0 || mesh.cells.rows() == 0) {
    throw std::invalid_argument(where + ": a mesh needs points and cells (got " +
                                std::to_string(mesh.points.rows()) + " points, " +
                                std::to_string(mesh.cells.rows()) + " cells)");
  }
  if (mesh.cells.cols() != nodes) {
    throw std::invalid_argument(where + ": " + xdmf_topology_name(mesh.cell_type) + " cells have " +
                                std::to_string(nodes) + " nodes, got " +
                                std::to_string(mesh.cells.cols()) + " columns");
  }
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
    if (!mesh.points.row(i).allFinite()) {
      throw std::invalid_argument(where + ": point " + std::to_string(i) +
                                  " has a non-finite coordinate; refusing to write it");
    }
  }
  for (Eigen::Index c = 0; c < mesh.cells.rows(); ++c) {
    for (Eigen::Index k = 0; k < nodes; ++k) {
      const std::int64_t p = mesh.cells(c, k);
      if (p < 0 || p >= mesh.points.rows()) {
        throw std::invalid_argument(where + ": cell " + std::to_string(c) + " refers to point " +
                                    std::to_string(p) + ", but the mesh has " +
                                    std::to_string(mesh.points.rows()) + " points");
      }
    }
  }
  MeshRecord record{numbered("mesh", meshes_.size()), mesh.points.rows(), mesh.cells.rows(),
                    mesh.cell_type};
  QuietHdf5 quiet;
  Handle file(H5Fopen(h5_path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose,
              "opening HDF5 file " + h5_path_.string());
  {
    Handle group = create_group(file.get(), record.group, h5_path_.string());
    write_dataset(group.get(), "points", static_cast<hsize_t>(record.points), 3, false,
                  H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, mesh.points.data(), where + " points");
    write_dataset(group.get(), "cells", static_cast<hsize_t>(record.cells),
                  static_cast<hsize_t>(nodes), false, H5T_STD_I64LE, H5T_NATIVE_INT64,
                  mesh.cells.data(), where + " cells");
  }
  file.close("closing " + h5_path_.string());
  meshes_.push_back(std::move(record));
}

void Hdf5XdmfWriter::check_step(double time, const std::vector<OutputField>& fields) const {
  const std::string where = "field output " + h5_path_.string() + ", step " +
                            std::to_string(steps_.size()) + " (t = " + format_number(time) + " s)";
  if (meshes_.empty())
    throw std::logic_error(where + ": set_mesh() must come before write_step()");
  if (!std::isfinite(time))
    throw std::invalid_argument(where + ": the time is not finite");
  if (!steps_.empty() && !(time > steps_.back().time)) {
    throw std::invalid_argument(where + ": times must increase (previous step at t = " +
                                format_number(steps_.back().time) + " s)");
  }
  const MeshRecord& mesh = meshes_.back();
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const OutputField& field = fields[f];
    if (!is_plain_name(field.name)) {
      throw std::invalid_argument(where + ": field name \"" + field.name +
                                  "\" must be letters, digits, '_', '.' or '-'");
    }
    for (std::size_t g = 0; g < f; ++g) {
      if (fields[g].name == field.name && fields[g].centre == field.centre) {
        throw std::invalid_argument(where + ": field '" + field.name + "' given twice");
      }
    }
    const bool at_points = field.centre == FieldCentre::point;
    const Eigen::Index rows = at_points ? mesh.points : mesh.cells;
    const char* entity = at_points ? "point" : "cell";
    if (field.values.rows() != rows) {
      throw std::invalid_argument(where + ": field '" + field.name + "' has " +
                                  std::to_string(field.values.rows()) + " rows for " +
                                  std::to_string(rows) + " " + entity + "s");
    }
    const Eigen::Index columns = field.values.cols();
    if (columns != 1 && columns != 3 && columns != 9) {
      throw std::invalid_argument(where + ": field '" + field.name + "' has " +
                                  std::to_string(columns) +
                                  " components; 1 (scalar), 3 (vector) or 9 (3x3 tensor) allowed");
    }
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (Eigen::Index k = 0; k < columns; ++k) {
        if (!std::isfinite(field.values(i, k))) {
          throw std::invalid_argument(where + ": field '" + field.name + "' is " +
                                      format_number(field.values(i, k)) + " at " + entity + " " +
                                      std::to_string(i) + ", component " + std::to_string(k) +
                                      "; refusing to write non-finite results");
        }
      }
    }
  }
}

void Hdf5XdmfWriter::write_step(double time, const std::vector<OutputField>& fields) {
  check_step(time, fields);
  StepRecord step{numbered("step", steps_.size()), time, meshes_.size() - 1, {}};
  const std::string where = "field output " + h5_path_.string() + ", " + step.group;
  {
    QuietHdf5 quiet;
    Handle file(H5Fopen(h5_path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose,
                "opening HDF5 file " + h5_path_.string());
    {
      Handle group = create_group(file.get(), step.group, h5_path_.string());
      write_scalar_attribute(group.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time, where);
      const std::int64_t mesh = static_cast<std::int64_t>(step.mesh);
      write_scalar_attribute(group.get(), "mesh", H5T_STD_I64LE, H5T_NATIVE_INT64, &mesh, where);
      for (FieldCentre centre : {FieldCentre::point, FieldCentre::cell}) {
        const char* sub = centre == FieldCentre::point ? "point" : "cell";
        bool any = false;
        for (const auto& f : fields)
          any = any || f.centre == centre;
        if (!any)
          continue;
        Handle centre_group = create_group(group.get(), sub, h5_path_.string());
        for (const OutputField& f : fields) {
          if (f.centre != centre)
            continue;
          write_dataset(centre_group.get(), f.name, static_cast<hsize_t>(f.values.rows()),
                        static_cast<hsize_t>(f.values.cols()), f.values.cols() == 1, H5T_IEEE_F64LE,
                        H5T_NATIVE_DOUBLE, f.values.data(), where + "/" + sub + "/" + f.name);
          step.fields.push_back({f.name, centre, f.values.rows(), f.values.cols()});
        }
      }
    }
    file.close("closing " + h5_path_.string());
  }
  steps_.push_back(std::move(step));
  write_file_atomically(xdmf_path_, xdmf_text());
}

// XDMF 3 (xdmf.org, "XDMF Model and Format"): a temporal collection of uniform grids, each
// pointing into the .h5 by relative file name so the folder can be moved.
std::string Hdf5XdmfWriter::xdmf_text() const {
  const std::string h5 = xml_escape(h5_path_.filename().string());
  std::ostringstream x;
  // A DataItem naming the dataset /group/sub/name of the .h5 (sub may be empty).
  auto item = [&](const std::string& dims, bool integer, const std::string& group, const char* sub,
                  const std::string& name) {
    x << "          <DataItem Dimensions=\"" << dims << "\" NumberType=\""
      << (integer ? "Int" : "Float") << "\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/" << group
      << "/" << sub << name << "</DataItem>\n";
  };
  x << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    << "<Xdmf Version=\"3.0\">\n  <Domain>\n"
    << "    <Grid Name=\"" << xml_escape(xdmf_path_.stem().string())
    << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const StepRecord& step : steps_) {
    const MeshRecord& mesh = meshes_[step.mesh];
    const int nodes = nodes_per_cell(mesh.cell_type);
    x << "      <Grid Name=\"" << step.group << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << format_number(step.time) << "\"/>\n"
      << "        <Topology TopologyType=\"" << xdmf_topology_name(mesh.cell_type)
      << "\" NumberOfElements=\"" << mesh.cells << "\" NodesPerElement=\"" << nodes << "\">\n";
    item(std::to_string(mesh.cells) + " " + std::to_string(nodes), true, mesh.group, "", "cells");
    x << "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n";
    item(std::to_string(mesh.points) + " 3", false, mesh.group, "", "points");
    x << "        </Geometry>\n";
    for (const FieldRecord& f : step.fields) {
      const bool at_points = f.centre == FieldCentre::point;
      x << "        <Attribute Name=\"" << f.name << "\" AttributeType=\""
        << attribute_type(f.columns) << "\" Center=\"" << (at_points ? "Node" : "Cell") << "\">\n";
      std::string dims = std::to_string(f.rows);
      if (f.columns > 1) {
        dims += ' ';  // (not " " + ...: GCC 12 warns falsely, -Wrestrict)
        dims += std::to_string(f.columns);
      }
      item(dims, false, step.group, at_points ? "point/" : "cell/", f.name);
      x << "        </Attribute>\n";
    }
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return x.str();
}

}  // namespace isomuscle::io
