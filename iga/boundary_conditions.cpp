#include "iga/boundary_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace isomuscle::iga {

namespace {

constexpr const char* kSideNames[6] = {"u0", "u1", "v0", "v1", "w0", "w1"};
const char* kComponent[3] = {"x", "y", "z"};

}  // namespace

const char* to_string(Side side) {
  return kSideNames[static_cast<int>(side)];
}

Side parse_side(std::string_view name) {
  for (int s = 0; s < 6; ++s) {
    if (name == kSideNames[s]) {
      return static_cast<Side>(s);
    }
  }
  throw std::invalid_argument("unknown parametric side '" + std::string(name) +
                              "' (valid: u0, u1, v0, v1, w0, w1)");
}

int side_direction(Side side) {
  return static_cast<int>(side) / 2;
}
int side_end(Side side) {
  return static_cast<int>(side) % 2;
}

// Control points i_d = 0 (side end 0) or n_d - 1 (end 1); for a clamped knot vector these are
// exactly the points that carry the boundary face.
std::vector<int> side_control_points(const geometry::NurbsVolume& volume, Side side) {
  const int d = side_direction(side);
  const int fixed = side_end(side) == 0 ? 0 : volume.count(d) - 1;
  std::vector<int> out;
  for (int k = 0; k < volume.count(2); ++k) {
    for (int j = 0; j < volume.count(1); ++j) {
      for (int i = 0; i < volume.count(0); ++i) {
        const std::array<int, 3> ijk = {i, j, k};
        if (ijk[d] == fixed) {
          out.push_back(volume.index(i, j, k));
        }
      }
    }
  }
  return out;
}

std::vector<int> plane_control_points(const geometry::NurbsVolume& volume,
                                      const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                      double tolerance) {
  const double len = normal.norm();
  if (!(len > 0.0) || !std::isfinite(len)) {
    throw std::invalid_argument("plane selector: the normal must be a finite non-zero vector");
  }
  if (!(tolerance >= 0.0)) {
    throw std::invalid_argument("plane selector: tolerance must be >= 0 (m)");
  }
  const Eigen::Vector3d n = normal / len;
  std::vector<int> out;
  const auto& pts = volume.points();
  for (int i = 0; i < static_cast<int>(pts.size()); ++i) {
    if (std::abs((pts[i] - point).dot(n)) <= tolerance) {
      out.push_back(i);
    }
  }
  return out;
}

std::vector<int> nodes_of(const DofMap& dofs, std::span<const int> control_points) {
  std::vector<int> out;
  out.reserve(control_points.size());
  for (int cp : control_points) {
    if (cp < 0 || cp >= dofs.num_control_points()) {
      throw std::invalid_argument("nodes_of: control point " + std::to_string(cp) + " outside 0.." +
                                  std::to_string(dofs.num_control_points() - 1));
    }
    out.push_back(dofs.node(cp));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void DirichletConditions::fix(std::string label, std::vector<int> nodes, ComponentMask components) {
  conditions_.push_back({std::move(label), std::move(nodes), components, {}});
}

void DirichletConditions::prescribe(std::string label, std::vector<int> nodes,
                                    DisplacementFunction f, ComponentMask components) {
  if (!f) {
    throw std::invalid_argument("Dirichlet condition '" + label +
                                "': empty displacement function (use fix for u = 0)");
  }
  conditions_.push_back({std::move(label), std::move(nodes), components, std::move(f)});
}

// u(t) = v t (constant velocity, m/s).
void DirichletConditions::move_with_velocity(std::string label, std::vector<int> nodes,
                                             const Eigen::Vector3d& velocity,
                                             ComponentMask components) {
  if (!velocity.allFinite()) {
    throw std::invalid_argument("Dirichlet condition '" + label + "': velocity is not finite");
  }
  prescribe(
      std::move(label), std::move(nodes),
      [velocity](const Eigen::Vector3d&, double t) -> Eigen::Vector3d { return velocity * t; },
      components);
}

// Symmetry: u . n = 0 with n = +-e_i.
void DirichletConditions::symmetry(std::string label, std::vector<int> nodes,
                                   const Eigen::Vector3d& normal) {
  const double len = normal.norm();
  if (!(len > 0.0) || !std::isfinite(len)) {
    throw std::invalid_argument("symmetry condition '" + label +
                                "': the normal must be a finite non-zero vector");
  }
  const Eigen::Vector3d n = normal / len;
  int axis = -1;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(n[i]) >= 1.0 - 1e-9) {
      axis = i;
    }
  }
  if (axis < 0) {
    std::ostringstream msg;
    msg << "symmetry condition '" << label << "': normal (" << n[0] << ", " << n[1] << ", " << n[2]
        << ") is not along a coordinate axis; only planes x = c, y = c or z = c are supported "
           "(a rotated plane needs rotated constraints, not implemented)";
    throw std::invalid_argument(msg.str());
  }
  ComponentMask mask = {false, false, false};
  mask[axis] = true;
  fix(std::move(label), std::move(nodes), mask);
}

void DirichletConditions::fix_point(std::string label, int node, ComponentMask components) {
  fix(std::move(label), std::vector<int>{node}, components);
}

ConstrainedDofs::ConstrainedDofs(const DofMap& dofs, const DirichletConditions& conditions) {
  const int ndof = dofs.num_dofs();
  // -2: free; -1: zero; >= 0: condition index.
  std::vector<int> rule_of(ndof, -2);
  const auto& list = conditions.conditions();
  for (int c = 0; c < static_cast<int>(list.size()); ++c) {
    const DirichletCondition& cond = list[c];
    for (int node : cond.nodes) {
      if (node < 0 || node >= dofs.num_nodes()) {
        throw std::invalid_argument("Dirichlet condition '" + cond.label + "': node " +
                                    std::to_string(node) + " outside 0.." +
                                    std::to_string(dofs.num_nodes() - 1));
      }
      for (int k = 0; k < 3; ++k) {
        if (!cond.components[k]) {
          continue;
        }
        const int dof = DofMap::dof(node, k);
        const int rule = cond.displacement ? c : -1;
        if (rule_of[dof] == -2 || (rule_of[dof] == -1 && rule == -1)) {
          rule_of[dof] = rule;
        } else {
          const std::string other =
              rule_of[dof] >= 0 ? list[rule_of[dof]].label : "a zero condition";
          const Eigen::Vector3d& x = dofs.position(node);
          std::ostringstream msg;
          msg << "Dirichlet conditions '" << cond.label << "' and '" << other
              << "' both prescribe component " << kComponent[k] << " of node " << node << " at ("
              << x[0] << ", " << x[1] << ", " << x[2]
              << "); a DOF may be prescribed twice only to zero";
          throw std::invalid_argument(msg.str());
        }
      }
    }
  }
  free_index_.assign(ndof, -1);
  for (int dof = 0; dof < ndof; ++dof) {
    if (rule_of[dof] == -2) {
      free_index_[dof] = num_free_++;
      free_dofs_.push_back(dof);
    } else {
      prescribed_.push_back(dof);
      rules_.push_back({dof, rule_of[dof], dofs.position(dof / 3)});
    }
  }
  functions_.reserve(list.size());
  for (const DirichletCondition& cond : list) {
    functions_.push_back(cond.displacement);
  }
}

void ConstrainedDofs::apply_prescribed(double t, Eigen::VectorXd& full) const {
  if (full.size() != num_dofs()) {
    full.resize(num_dofs());
    full.setZero();
  }
  for (const Rule& r : rules_) {
    if (r.condition < 0) {
      full[r.dof] = 0.0;
    } else {
      const Eigen::Vector3d u = functions_[r.condition](r.X, t);
      if (!std::isfinite(u[r.dof % 3])) {
        std::ostringstream msg;
        msg << "Dirichlet condition " << r.condition << " gives a non-finite displacement at X = ("
            << r.X[0] << ", " << r.X[1] << ", " << r.X[2] << "), t = " << t << " s";
        throw std::invalid_argument(msg.str());
      }
      full[r.dof] = u[r.dof % 3];
    }
  }
}

void ConstrainedDofs::expand(const Eigen::VectorXd& u_free, double t, Eigen::VectorXd& full) const {
  if (u_free.size() != num_free_) {
    throw std::invalid_argument("ConstrainedDofs::expand: vector of size " +
                                std::to_string(u_free.size()) + ", expected " +
                                std::to_string(num_free_));
  }
  full.resize(num_dofs());
  for (int i = 0; i < num_free_; ++i) {
    full[free_dofs_[i]] = u_free[i];
  }
  apply_prescribed(t, full);
}

void ConstrainedDofs::restrict_to_free(const Eigen::VectorXd& full, Eigen::VectorXd& free) const {
  free.resize(num_free_);
  for (int i = 0; i < num_free_; ++i) {
    free[i] = full[free_dofs_[i]];
  }
}

}  // namespace isomuscle::iga
