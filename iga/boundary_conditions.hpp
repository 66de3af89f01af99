#pragma once
// Dirichlet conditions on control points, and the split of the DOFs into free and prescribed.
//
// Selecting control points: by parametric side of the solid (u0 = the face u = u_min, ..., w1),
// the control points of that face; or geometrically, the control points within a distance of a
// plane. Prescribing control-point displacements on a face is exact for homogeneous/affine face
// motions (u(X) = sum_a R_a u_a = A X + b when u_a = A X_a + b, since sum_a R_a = 1 and
// sum_a R_a X_a = X): what the patch test needs. For curved non-affine data it is an
// interpolation of the control values, not of the field.
//
// Kinds: fixed (u = 0), prescribed u(X, t) (e.g. constant velocity u = v t), symmetry on a
// coordinate-aligned plane (normal component zero), single point constraints (to remove rigid
// modes). A DOF prescribed twice must be prescribed to zero both times (fixed, symmetry), else the
// conditions conflict and building ConstrainedDofs throws, naming the node and component.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/nurbs_volume.hpp"
#include "iga/dof_map.hpp"

namespace isomuscle::iga {

enum class Side { u0, u1, v0, v1, w0, w1 };

const char* to_string(Side side);
// "u0" ... "w1"; throws std::invalid_argument listing the valid names.
Side parse_side(std::string_view name);
// Parametric direction (0, 1, 2) and end (0 = min, 1 = max) of a side.
int side_direction(Side side);
int side_end(Side side);

// Control points of a parametric side, in the volume's index order.
std::vector<int> side_control_points(const geometry::NurbsVolume& volume, Side side);
// Control points X with |(X - point) . n| <= tolerance (m), n = normal / |normal|. Throws
// std::invalid_argument for a zero normal or negative tolerance.
std::vector<int> plane_control_points(const geometry::NurbsVolume& volume,
                                      const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                      double tolerance);
// The distinct nodes of a set of control points, ascending.
std::vector<int> nodes_of(const DofMap& dofs, std::span<const int> control_points);

using ComponentMask = std::array<bool, 3>;
inline constexpr ComponentMask kAllComponents = {true, true, true};
// Displacement (m) of a control point with reference position X (m) at time t (s).
using DisplacementFunction = std::function<Eigen::Vector3d(const Eigen::Vector3d& X, double t)>;

struct DirichletCondition {
  std::string label;       // for messages, e.g. "fixed end (v0)"
  std::vector<int> nodes;  // nodes of the DofMap
  ComponentMask components = kAllComponents;
  DisplacementFunction displacement;  // empty: zero (fixed, symmetry)
};

class DirichletConditions {
 public:
  // u = 0 on the selected components.
  void fix(std::string label, std::vector<int> nodes, ComponentMask components = kAllComponents);
  // u = f(X, t) on the selected components.
  void prescribe(std::string label, std::vector<int> nodes, DisplacementFunction f,
                 ComponentMask components = kAllComponents);
  // u = velocity * t (m/s): a face pulled at constant speed.
  void move_with_velocity(std::string label, std::vector<int> nodes,
                          const Eigen::Vector3d& velocity,
                          ComponentMask components = kAllComponents);
  // Symmetry plane with unit normal along a coordinate axis: u . n = 0. Throws
  // std::invalid_argument when the normal is not coordinate-aligned (|n_i| < 1 - 1e-9 for all i):
  // a rotated symmetry plane would need rotated (local-basis) constraints, not implemented.
  void symmetry(std::string label, std::vector<int> nodes, const Eigen::Vector3d& normal);
  // Single node, selected components zero (rigid-mode removal).
  void fix_point(std::string label, int node, ComponentMask components);

  const std::vector<DirichletCondition>& conditions() const { return conditions_; }

 private:
  std::vector<DirichletCondition> conditions_;
};

// The free/prescribed split of the DOFs ("all" numbering 3 node + c) and the prescribed values.
class ConstrainedDofs {
 public:
  ConstrainedDofs() = default;
  // Throws std::invalid_argument for a node outside the DofMap or conflicting conditions.
  ConstrainedDofs(const DofMap& dofs, const DirichletConditions& conditions);

  int num_dofs() const { return static_cast<int>(free_index_.size()); }
  int num_free() const { return num_free_; }
  // Free index of a DOF, or -1 (solver::kPrescribed) when prescribed.
  int free_index(int dof) const { return free_index_[dof]; }
  const std::vector<int>& free_indices() const { return free_index_; }
  // The DOF of each free index.
  const std::vector<int>& free_dofs() const { return free_dofs_; }
  const std::vector<int>& prescribed_dofs() const { return prescribed_; }

  // Writes the prescribed values at time t into `full` (size num_dofs()), leaving free entries.
  void apply_prescribed(double t, Eigen::VectorXd& full) const;
  // full = prescribed values at t, free entries from u_free.
  void expand(const Eigen::VectorXd& u_free, double t, Eigen::VectorXd& full) const;
  // The free entries of a full vector.
  void restrict_to_free(const Eigen::VectorXd& full, Eigen::VectorXd& free) const;

 private:
  struct Rule {
    int dof;
    int condition;  // index into conditions_, -1 for zero
    Eigen::Vector3d X;
  };
  std::vector<int> free_index_;
  std::vector<int> free_dofs_;
  std::vector<int> prescribed_;
  std::vector<Rule> rules_;
  std::vector<DisplacementFunction> functions_;
  int num_free_ = 0;
};

}  // namespace isomuscle::iga
