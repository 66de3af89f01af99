#pragma once
// What a total Lagrangian element kernel reads and writes, independent of the discretisation
// (NURBS knot-span elements in iga/, tetrahedra in tet/): the element's tabulated reference data,
// the material context of its points, the failure status, and a workspace sized once per thread
// so that kernels never allocate (DESIGN line 2: kernels separate from the loop that scatters
// them). Local DOF order: 3 a + i (function a, component i).
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::continuum {

// One element's tabulated reference data (views owned by the discretisation).
struct ElementView {
  int nen = 0;
  int nqp = 0;
  const double* values = nullptr;              // nqp x nen shape function values (optional)
  const Eigen::Vector3d* gradients = nullptr;  // nqp x nen, dN/dX (1/m)
  const double* dv = nullptr;                  // nqp, w det(dX/dxi) (m^3)
  // Mixed formulation only: the element pressure/dilatation functions at the points.
  int pressure_size = 0;             // m
  const double* pressure = nullptr;  // nqp x m
};

// What the material points of one element need besides F.
struct MaterialContext {
  const materials::MaterialLaw* law = nullptr;
  const Eigen::Vector3d* fibres = nullptr;    // nqp unit reference fibre directions
  double time = 0.0;                          // t + dt, s
  double dt = 0.0;                            // s
  const double* history_committed = nullptr;  // nqp x history_size (nullptr when 0)
  double* history_trial = nullptr;            // nqp x history_size (nullptr when 0)
  // The trial history holds what the law wrote at this element's current F in the pass before
  // (materials::PointInput::trial_is_current).
  bool trial_is_current = false;
};

// The context of element e (nqp points per element): fibres and committed history are arrays over
// all elements (element-major), history_trial is this element's own nqp x history_size block.
MaterialContext element_material_context(const materials::MaterialLaw& law,
                                         const std::vector<Eigen::Vector3d>& fibres, int e, int nqp,
                                         double time, double dt,
                                         const std::vector<double>& history_committed,
                                         double* history_trial);

// The material context of an element whose nqp points all hold one state (a homogeneous
// deformation: the stability checks' layers and columns): the state's fibre and committed history
// repeated at every point, with trial scratch. context points into this object, which therefore
// neither copies nor moves.
class UniformMaterialContext {
 public:
  UniformMaterialContext(const materials::MaterialLaw& law, const Eigen::Vector3d& fibre,
                         const std::vector<double>& history, double time, double dt, int nqp);
  UniformMaterialContext(const UniformMaterialContext&) = delete;
  UniformMaterialContext& operator=(const UniformMaterialContext&) = delete;
  const MaterialContext& context() const { return context_; }

 private:
  std::vector<Eigen::Vector3d> fibres_;
  std::vector<double> committed_, trial_;
  MaterialContext context_;
};

// Why a kernel failed, without allocation; the discretisation turns it into a message naming the
// element (describe_kernel_status gives the part after the location).
struct KernelStatus {
  enum class Kind { ok, inverted, inverted_dilatation, material, not_finite };
  Kind kind = Kind::ok;
  int point = -1;      // local quadrature point (or -1)
  double value = 0.0;  // J, J~ or the offending value
  materials::PointStatus material = materials::PointStatus::ok;
  bool ok() const { return kind == Kind::ok; }
};

// "J = det F = ... <= 0 (inverted)", "material law 'name' failed (...) at J = ...", ...
std::string describe_kernel_status(const KernelStatus& status, std::string_view law_name);

class ElementWorkspace {
 public:
  ElementWorkspace() = default;
  ElementWorkspace(int nen, int nqp, int pressure_size);

  // Input: element displacements, column a = u_a (m).
  Eigen::Matrix<double, 3, Eigen::Dynamic> ue;
  // Outputs: internal force (N) and tangent (N/m).
  Eigen::VectorXd fe;
  Eigen::MatrixXd ke;
  // Per-point results kept for outputs: F, S (Pa) at every point; J~ and p~ (Pa) when mixed.
  std::vector<Eigen::Matrix3d> F;
  std::vector<Eigen::Matrix3d> S;
  std::vector<double> J;
  std::vector<double> J_bar;
  std::vector<double> p_bar;

  // Scratch.
  Eigen::Matrix<double, 6, Eigen::Dynamic> B;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dJ;
  // A group of points' factors of the stiffness, stacked (rows 6s.. and 3s.. for slot s), so that
  // K += B^T C B dV and H += dN/dX . S dN/dX dV over the group are one product each
  // (point_contributions.hpp, kPointsPerProduct points).
  Eigen::MatrixXd B_points, CB_points;     // 6 kPointsPerProduct x 3 n_en: B and C B dV
  Eigen::MatrixXd grad_points, SG_points;  // 3 kPointsPerProduct x n_en: dN/dX and S dN/dX dV
  Eigen::MatrixXd H;
  Eigen::MatrixXd G;               // m x 3 n_en
  Eigen::MatrixXd K_JJ, X, A, AG;  // m x m, m x m, m x m, m x 3 n_en
  Eigen::VectorXd theta, pi, rhs;  // m
  Eigen::VectorXd R_pi, R_theta;   // m, local residuals
  materials::PointResult result;
};

}  // namespace isomuscle::continuum
