#pragma once
// The [[probe]] entries of a scene on an IGA run: scalar time series, one value per column per
// converged step (probes.csv). Columns and units:
//
//   point_displacement  <name>              u(X) at the point, component x|y|z or |u|, m, or
//                                           "normal": u . n with n the outward unit normal of the
//                                           reference surface there (points on the face w = 0,
//                                           the IGES surface: a dent shows as a negative value)
//   face_reaction       <name>              sum of the internal forces at the face's nodes, N:
//                                           the force the support exerts on the body (at
//                                           equilibrium f_int = f_ext + reactions; no loads here)
//   volume              <name>              int J dV, m^3
//   stress_parts        <name>.<part> ...   a . sigma_part . a, the normal Cauchy stress along the
//                                           deformed fibre a = F N / |F N| (thesis 5.30, 5.41) of
//                                           each part of the law (thesis 3.44: see, pe, matrix,
//                                           vol for the Hill laws), Pa, and <name>.total
//   surface_stability   <name>              rho c^2 of the slowest surface wave of the free
//                                           surface nearest the point as a deformed half-space,
//                                           Pa (io/surface_stability_check.hpp; <= 0: Biot's
//                                           surface instability; NaN where the law fails)
//   element_layer       <name>              the lowest Bloch eigenvalue of the run's element
//                                           tiled along the free surface nearest the point and
//                                           deformed to its state, Pa/m^2
//                                           (io/element_layer_check.hpp; <= 0: the element
//                                           itself is unstable there; mixed formulation only)
//                       <name>.column       the same for the body's own column of elements
//                                           through the depth there, each at its state
//                                           (io/element_column_check.hpp)
//   material_ellipticity <name>, <name>.not_elliptic, <name>.x|y|z
//                                           the law's smallest isochoric wave stiffness over
//                                           every quadrature point (Pa), how many points have
//                                           it <= 0 (a material instability: shear band, fold)
//                                           and the smallest's reference position, m
//                                           (io/ellipticity_probe.hpp)
//
// Points are given physically (point inversion, geometry/point_inversion.hpp) or parametrically
// (xi in [0, 1]^3, scene naming: iga_run_setup.hpp). Stress parts are the law's converged parts at
// the quadrature points of the point's element, interpolated to the point
// (iga/quadrature_point_interpolation.hpp, as iga::Problem::state_at interpolates sigma) and taken
// along the deformed fibre there; on the collapsed axis of a shrink solid, where F is undefined,
// at the nearest quadrature point instead (a note says where). For the mixed formulation the
// volumetric part is p~ I (the element's pressure), so the parts always sum to the total stress
// of the solution.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "iga/problem.hpp"
#include "io/iga_run_setup.hpp"
#include "io/run_model.hpp"
#include "io/scene.hpp"

namespace isomuscle::io {

class IgaProbes {
 public:
  // Resolves points and faces on the model. Throws std::invalid_argument naming the probe when a
  // point lies outside the solid or a face selects nothing.
  IgaProbes(const std::vector<ProbeSettings>& probes, const IgaModel& model);

  // Column names, in the order of the scene's probes.
  const std::vector<std::string>& columns() const { return columns_; }
  // Where points were moved (axis) and other decisions, for the log.
  const std::vector<std::string>& notes() const { return notes_; }
  // The reference position (m) of every point probe, by name (summary.json "probe_points").
  const std::vector<std::pair<std::string, Eigen::Vector3d>>& points() const { return points_; }

  // Called with the converged free values BEFORE the problem commits them: the internal force
  // (reactions) of exactly the converged state.
  void before_commit(iga::Problem& problem, const Eigen::VectorXd& u);
  // The value of every column at the committed state (after commit_step). Throws
  // std::runtime_error when the law cannot be evaluated at a stress point.
  void values(const iga::Problem& problem, std::vector<double>& out) const;

 private:
  struct Probe {
    ProbeSettings settings;
    int component = 3;  // 0..2 = x..z, 3 = magnitude
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // component "normal": outward unit normal
    int element = -1;
    int point = -1;  // >= 0: evaluate at this quadrature point of element (axis fallback)
    std::vector<int> nodes;
    std::vector<double> weights;  // stress point: interpolation weights of the element's points
    SurfaceLocation surface;      // surface_stability, element_layer
    std::size_t first_column = 0;
  };

  double stress_column_values(const iga::Problem& problem, const Probe& probe,
                              std::vector<double>& out, std::size_t at) const;

  std::vector<Probe> probes_;
  std::vector<std::string> columns_;
  std::vector<std::string> part_names_;  // the law's Cauchy parts used by stress probes
  bool replace_volumetric_ = false;      // mixed formulation: the "vol" part is p~ I
  bool parts_from_law_ = true;           // false: only the total
  bool needs_force_ = false;
  Eigen::VectorXd force_;  // internal force of the converged state, all DOFs
  std::vector<std::string> notes_;
  std::vector<std::pair<std::string, Eigen::Vector3d>> points_;
};

}  // namespace isomuscle::io
