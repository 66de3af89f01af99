#pragma once
// The [[probe]] entries of a scene on a tetrahedral run: the same columns and units as on an IGA
// run (iga_run_probes.hpp), so that probes.csv of the two discretisations compare column by
// column:
//
//   point_displacement  u at the point (the mesh element holding it, tet_locator.hpp), x|y|z|
//                       magnitude, or normal (u . n, n the outward normal of the solid's surface
//                       w = 0 at the point), m
//   face_reaction       sum of the internal forces at the selected nodes, N
//   volume              int J dV, m^3
//   stress_parts        a . sigma_part . a at the quadrature point nearest to the point (the
//                       law's parts, thesis 3.44; "vol" is p~ I for the mixed formulation), Pa
//   surface_stability   rho c^2 of the slowest surface wave of the free surface nearest the point
//                       as a deformed half-space (the nearest free boundary triangle,
//                       tet_surface_point.hpp), Pa
//   material_ellipticity the law's smallest isochoric wave stiffness over every quadrature point,
//                       the points where it is <= 0 and where the smallest is
//                       (ellipticity_probe.hpp)
//
// Points are given physically or parametrically (xi, scene naming: X = H(xi) of the solid).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "io/run_model.hpp"
#include "io/scene.hpp"
#include "io/tet_run_setup.hpp"
#include "tet/tet_locator.hpp"

namespace isomuscle::io {

class TetProbes {
 public:
  // Throws std::invalid_argument naming the probe when a point lies outside the mesh or a face
  // selects nothing.
  TetProbes(const std::vector<ProbeSettings>& probes, const TetModel& model);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::pair<std::string, Eigen::Vector3d>>& points() const { return points_; }
  // Where surface_stability probes were placed, for the log.
  const std::vector<std::string>& notes() const { return notes_; }

  // The internal force of the converged state (reactions), before it is committed.
  void before_commit(tet::TetProblem& problem, const Eigen::VectorXd& u);
  // Every column at the committed state; std::runtime_error when the law fails at a point.
  void values(const tet::TetProblem& problem, std::vector<double>& out) const;

 private:
  struct Probe {
    ProbeSettings settings;
    int component = 3;  // 0..2 = x..z, 3 = magnitude, 4 = normal
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    tet::TetLocation location;
    int element = -1, point = -1;  // stress_parts: nearest quadrature point
    SurfaceLocation surface;       // surface_stability
    std::vector<int> nodes;
    std::size_t first_column = 0;
  };

  std::unique_ptr<tet::TetLocator> locator_;
  std::vector<Probe> probes_;
  std::vector<std::string> notes_;
  std::vector<std::string> columns_;
  std::vector<std::string> part_names_;
  bool replace_volumetric_ = false;
  bool parts_from_law_ = true;
  bool needs_force_ = false;
  Eigen::VectorXd force_;
  std::vector<std::pair<std::string, Eigen::Vector3d>> points_;
};

}  // namespace isomuscle::io
