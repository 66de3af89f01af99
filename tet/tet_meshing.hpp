#pragma once
// Tetrahedral meshes from gmsh 4.8 (TOOLING.md): a closed boundary given as an IGES file, meshed
// with a target element size, or a user's .msh file. gmsh is one global library: every call here
// holds a process-wide lock and initialises/finalises gmsh around its work (GmshSession), silences
// its messages, and turns its errors (thrown as std::string) into std::runtime_error naming the
// file.
#include <Eigen/Core>

#include <filesystem>
#include <functional>

#include "tet/tet_mesh.hpp"

namespace isomuscle::tet {

struct MeshingOptions {
  double element_size = 0.0;  // target edge length, m (> 0)
  int order = 1;              // 1: 4-node, 2: 10-node (high-order nodes on the curved boundary)
  int threads = 1;            // gmsh meshing threads
  // The degree of the rule the analysis will integrate with (tet_rule; 0: the order's default):
  // folded curved elements are found at its points (curved_tet_repair.hpp).
  int quadrature_degree = 0;
  // Local refinement: the target edge length (m) at a point (m) where it is to be smaller than
  // element_size (larger values are cut to element_size); empty: element_size everywhere. gmsh
  // calls it from its meshing threads, so it must not change shared state.
  std::function<double(const Eigen::Vector3d&)> local_size;
  double finest_size = 0.0;  // the smallest value local_size returns, m (gmsh's lower bound)
  // Throws std::invalid_argument naming the option.
  void validate() const;
};

// Meshes the volume bounded by the surfaces of an IGES file (faces mode: entity 128/144 surfaces
// forming a closed boundary; or a B-rep solid). The surfaces are healed and sewn into a shell, a
// volume is made from it and meshed. OpenCASCADE converts the file's unit to metres
// (Geometry.OCCTargetUnit = "M"). Boundary triangles are tagged by the gmsh surface entity.
// 10-node elements that gmsh curved until they fold over are made straight-sided
// (curved_tet_repair.hpp); their number is written to *straightened when given.
// Throws std::runtime_error naming the file when it cannot be read, does not bound a volume, or
// gmsh fails.
TetMesh mesh_iges(const std::filesystem::path& file, const MeshingOptions& options,
                  int* straightened = nullptr);

// Reads a gmsh .msh file (any version gmsh reads) holding 4- or 10-node tetrahedra: physical
// volume groups become element regions, physical surface groups the boundary tags (entity tags
// when the file has no physical groups). Lengths are multiplied by metres_per_unit. Throws
// std::runtime_error naming the file when it cannot be read, holds no tetrahedra, or mixes orders.
TetMesh read_msh(const std::filesystem::path& file, double metres_per_unit = 1.0);

}  // namespace isomuscle::tet
