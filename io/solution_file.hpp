#pragma once
// solution.h5: the discrete solution of a run, kept so that it can be evaluated exactly at any
// point afterwards (`isomuscle compare`, validation scripts). fields.h5 holds a tessellation for
// viewing; interpolating that would add the tessellation's own error to every comparison.
//
// Layout (float64 and int64, row-major):
//   /                attributes: discretisation ("iga"), format (1)
//   /geometry        the analysis geometry BEFORE refinement (the shrink or extruded solid, or
//                    its extracted piece): the parameter space in which comparisons sample
//                    material points. Datasets degrees [3], knots_u, knots_v, knots_w,
//                    points [n, 3] (m), weights [n].
//   /iga             the refined solid whose basis is the displacement space (IGA runs): same
//                    datasets. Exact refinement keeps the geometry and the parametrisation, so a
//                    parameter of /geometry is the same material point in /iga.
//   /tet             the tetrahedral mesh whose nodal field is the displacement (tet runs):
//                    attribute order (1 | 2), datasets nodes [n, 3] (m), elements [c, 4 | 10]
//                    (gmsh's node order, tet/tet_mesh.hpp)
//   /step_000000     attribute time (s); dataset displacement [control points of /iga or nodes of
//                    /tet, 3] (m): the coefficients u_a of u(xi) = sum_a R_a(xi) u_a (merged
//                    control points, seam and axis, repeated with their node's value), or the
//                    nodal values.
// Steps are appended as the run goes (open, write, close), so a run that fails keeps the file
// valid with every step written before.
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "geometry/nurbs_volume.hpp"
#include "tet/tet_mesh.hpp"

namespace isomuscle::io {

using DisplacementRows = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

class SolutionWriter {
 public:
  // Creates (truncates) the file and writes the geometry and the IGA space; std::runtime_error
  // when it cannot be written.
  SolutionWriter(std::filesystem::path path, const geometry::NurbsVolume& geometry,
                 const geometry::NurbsVolume& iga_space);
  // The same for a tetrahedral run: the geometry and the mesh.
  SolutionWriter(std::filesystem::path path, const geometry::NurbsVolume& geometry,
                 const tet::TetMesh& mesh);

  // Appends the control-point displacements at `time` (s, increasing). std::invalid_argument for
  // a wrong row count, a non-finite value or a time that does not increase.
  void write_step(double time, const DisplacementRows& displacement);

  const std::filesystem::path& path() const { return path_; }
  std::size_t steps() const { return steps_; }
  double last_time() const { return last_time_; }  // s, of the last step written

 private:
  std::filesystem::path path_;
  Eigen::Index rows_ = 0;
  std::size_t steps_ = 0;
  double last_time_ = 0.0;
};

struct StoredSolution {
  std::filesystem::path path;
  std::string discretisation;                // "iga" or "tet"
  geometry::NurbsVolume geometry;            // before refinement
  std::optional<geometry::NurbsVolume> iga;  // the displacement space of an IGA run
  std::optional<tet::TetMesh> tet;           // the mesh of a tetrahedral run
  std::vector<double> times;                 // s, one per step
  std::vector<DisplacementRows> displacement;
};

// Reads solution.h5; std::runtime_error naming the file and what is missing or malformed.
StoredSolution read_solution(const std::filesystem::path& path);

}  // namespace isomuscle::io
