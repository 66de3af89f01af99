#pragma once
// Fields for ParaView: a time series of an unstructured mesh (linear hexahedra or tetrahedra, or
// 10-node tetrahedra) with point and cell fields (scalars, vectors, 3x3 tensors), stored in ONE
// HDF5 file and indexed by an XDMF 3 temporal collection next to it. Output is incremental: each
// write_step() opens the .h5, appends the step, closes it, and rewrites the small .xdmf atomically,
// so a run that fails (or is killed) between steps leaves valid files holding every step so far.
// Non-finite values are refused with an error naming the field and the entry, never written.
//
// HDF5 layout (all datasets little-endian; the .xdmf references them as "<name>.h5:/path"):
//   /mesh_000000/points   float64 [points, 3]        m
//   /mesh_000000/cells    int64   [cells, nodes]     0-based point indices, VTK node order
//   /step_000000          group, attribute "time" (float64, s) and "mesh" (int64)
//   /step_000000/point/<field>  float64 [points] or [points, 3] or [points, 9]
//   /step_000000/cell/<field>   float64 [cells] or [cells, 3] or [cells, 9]
// A 3x3 tensor is stored row-major (xx, xy, xz, yx, ..., zz), as XDMF's "Tensor" reads it.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace isomuscle::io {

enum class CellType {
  hexahedron8,    // XDMF "Hexahedron", VTK_HEXAHEDRON node order
  tetrahedron4,   // XDMF "Tetrahedron"
  tetrahedron10,  // XDMF "Tetrahedron_10", VTK_QUADRATIC_TETRA node order (corners, then edges
                  // 01, 12, 02, 03, 13, 23)
};
int nodes_per_cell(CellType type);
const char* xdmf_topology_name(CellType type);

using PointMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using CellMatrix = Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using FieldMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct OutputMesh {
  PointMatrix points;  // one row per point, m
  CellMatrix cells;    // one row per cell, nodes_per_cell(cell_type) point indices
  CellType cell_type = CellType::hexahedron8;
};

enum class FieldCentre { point, cell };

struct OutputField {
  std::string name;  // [A-Za-z0-9_.-]+, unique within a step
  FieldCentre centre = FieldCentre::point;
  FieldMatrix values;  // one row per point or cell; 1 (scalar), 3 (vector) or 9 (tensor) columns
};

class Hdf5XdmfWriter {
 public:
  // Creates (truncates) the HDF5 file next to xdmf_path (same name, extension .h5) and removes a
  // stale .xdmf of an earlier run; the .xdmf is first written with the first step.
  // std::runtime_error when the file cannot be created.
  explicit Hdf5XdmfWriter(std::filesystem::path xdmf_path);

  // Writes the mesh of the following steps into the .h5. May be called again (e.g. after
  // remeshing): later steps refer to the new mesh. std::invalid_argument for empty meshes, wrong
  // node counts, indices out of range or non-finite coordinates.
  void set_mesh(const OutputMesh& mesh);

  // Appends the fields at time (s, finite, greater than the previous step's) and rewrites the
  // .xdmf. Everything is checked before anything is written: std::invalid_argument names the
  // field and entry for a non-finite value, a wrong row or column count, a repeated or bad name.
  void write_step(double time, const std::vector<OutputField>& fields);

  const std::filesystem::path& xdmf_path() const { return xdmf_path_; }
  const std::filesystem::path& h5_path() const { return h5_path_; }
  std::size_t steps() const { return steps_.size(); }

 private:
  struct MeshRecord {
    std::string group;
    Eigen::Index points;
    Eigen::Index cells;
    CellType cell_type;
  };
  struct FieldRecord {
    std::string name;
    FieldCentre centre;
    Eigen::Index rows;
    Eigen::Index columns;
  };
  struct StepRecord {
    std::string group;
    double time;
    std::size_t mesh;
    std::vector<FieldRecord> fields;
  };

  void check_step(double time, const std::vector<OutputField>& fields) const;
  std::string xdmf_text() const;

  std::filesystem::path xdmf_path_;
  std::filesystem::path h5_path_;
  std::vector<MeshRecord> meshes_;
  std::vector<StepRecord> steps_;
};

}  // namespace isomuscle::io
