#include "io/iga_surface_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>

namespace isomuscle::io {

namespace {

constexpr std::array<iga::Side, 6> kSides = {iga::Side::u0, iga::Side::u1, iga::Side::v0,
                                             iga::Side::v1, iga::Side::w0, iga::Side::w1};

iga::Side opposite(iga::Side side) {
  return kSides[static_cast<std::size_t>(2 * iga::side_direction(side) + 1 - iga::side_end(side))];
}

// Whether every row of the side along one of its directions is one node (the centreline of a
// shrink solid: each row around it collapsed onto a point of the axis).
bool collapsed(const geometry::NurbsVolume& volume, const iga::DofMap& dofs, iga::Side side) {
  const int d = iga::side_direction(side);
  const int fixed = iga::side_end(side) == 0 ? 0 : volume.count(d) - 1;
  const auto node_at = [&](int d_a, int i_a, int d_b, int i_b) {
    std::array<int, 3> ijk{};
    ijk[static_cast<std::size_t>(d)] = fixed;
    ijk[static_cast<std::size_t>(d_a)] = i_a;
    ijk[static_cast<std::size_t>(d_b)] = i_b;
    return dofs.node(volume.index(ijk[0], ijk[1], ijk[2]));
  };
  for (const int d_a : {(d + 1) % 3, (d + 2) % 3}) {
    const int d_b = 3 - d - d_a;
    bool rows_are_points = true;
    for (int i_b = 0; i_b < volume.count(d_b) && rows_are_points; ++i_b) {
      for (int i_a = 1; i_a < volume.count(d_a); ++i_a) {
        if (node_at(d_a, i_a, d_b, i_b) != node_at(d_a, 0, d_b, i_b)) {
          rows_are_points = false;
          break;
        }
      }
    }
    if (rows_are_points)
      return true;
  }
  return false;
}

bool supported(const std::vector<int>& nodes, const iga::ConstrainedDofs& constraints) {
  return std::all_of(nodes.begin(), nodes.end(), [&](int node) {
    for (int c = 0; c < 3; ++c) {
      if (constraints.free_index(3 * node + c) < 0)
        return true;
    }
    return false;
  });
}

}  // namespace

std::vector<iga::Side> traction_free_sides(const iga::Space& space, const iga::DofMap& dofs,
                                           const iga::ConstrainedDofs& constraints,
                                           const std::vector<iga::Side>& sprung) {
  const geometry::NurbsVolume& volume = space.volume();
  std::vector<iga::Side> sides;
  for (const iga::Side side : kSides) {
    if (collapsed(volume, dofs, side))
      continue;
    const std::vector<int> nodes = iga::nodes_of(dofs, iga::side_control_points(volume, side));
    if (nodes == iga::nodes_of(dofs, iga::side_control_points(volume, opposite(side))))
      continue;  // a closed seam
    if (supported(nodes, constraints) ||
        std::find(sprung.begin(), sprung.end(), side) != sprung.end())
      continue;
    sides.push_back(side);
  }
  return sides;
}

std::optional<SurfaceLocation> locate_surface_point(const iga::Problem& problem,
                                                    const Eigen::Vector3d& near) {
  const iga::Space& space = problem.space();
  const geometry::NurbsVolume& volume = space.volume();
  std::vector<iga::Side> sprung;
  for (const iga::ElasticSupport& s : problem.elastic_supports())
    sprung.push_back(s.side);
  const std::vector<iga::Side> sides =
      traction_free_sides(space, problem.dofs(), problem.constraints(), sprung);
  struct Candidate {
    int element = -1, point = -1;
    double to_near = std::numeric_limits<double>::infinity();
    double depth = std::numeric_limits<double>::infinity();
    Eigen::Vector3d surface = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
    int direction = -1, end = 0;
  } best;
  for (const iga::Side side : sides) {
    const int d = iga::side_direction(side), end = iga::side_end(side);
    const int a = (d + 1) % 3, b = (d + 2) % 3;
    const int layer = end == 0 ? 0 : space.element_counts()[static_cast<std::size_t>(d)] - 1;
    const double xi_side = volume.domain(d)[static_cast<std::size_t>(end)];
    for (int e = 0; e < space.num_elements(); ++e) {
      if (space.element(e).position[static_cast<std::size_t>(d)] != layer)
        continue;
      for (int q = 0; q < space.points_per_element(); ++q) {
        Eigen::Vector3d xi = space.parametric(e, q);
        xi[d] = xi_side;
        Eigen::Vector3d X;
        Eigen::Matrix3d J;
        volume.evaluate_with_jacobian(xi, X, J);
        const double to_near = (X - near).norm();
        const double depth = (space.position(e, q) - X).norm();
        if (to_near > best.to_near || (to_near == best.to_near && depth >= best.depth))
          continue;
        Eigen::Vector3d normal = J.col(a).cross(J.col(b));
        const double scale = J.col(a).norm() * J.col(b).norm();
        if (!(normal.norm() > 1e-8 * scale))
          continue;  // a collapsed edge of the side: no normal
        if (normal.dot(J.col(d)) * (end == 0 ? -1.0 : 1.0) < 0.0)
          normal = -normal;
        best = Candidate{e, q, to_near, depth, X, normal.normalized(), d, end};
      }
    }
  }
  if (best.element < 0)
    return std::nullopt;
  return SurfaceLocation{best.element, best.point,     best.surface,
                         best.normal,  best.direction, best.end};
}

}  // namespace isomuscle::io
