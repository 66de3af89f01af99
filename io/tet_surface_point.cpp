#include "io/tet_surface_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>
#include <span>

namespace isomuscle::io {

std::optional<SurfaceLocation> locate_surface_point(const tet::TetProblem& problem,
                                                    const Eigen::Vector3d& near) {
  const tet::TetMesh& mesh = problem.space().mesh();
  const auto prescribed = [&](int node) {
    for (int c = 0; c < 3; ++c) {
      if (problem.free_index(node, c) < 0)
        return true;
    }
    return false;
  };
  const auto X = [&](int node) { return mesh.nodes[static_cast<std::size_t>(node)]; };
  const auto centroid_of = [&](std::span<const int> face) {
    return Eigen::Vector3d((X(face[0]) + X(face[1]) + X(face[2])) / 3.0);
  };
  int best_face = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.num_boundary_faces(); ++f) {
    const auto face = mesh.face(f);
    if (std::all_of(face.begin(), face.end(), prescribed))
      continue;
    const Eigen::Vector3d centroid = centroid_of(face);
    if (const double distance = (centroid - near).norm(); distance < best_distance) {
      best_distance = distance;
      best_face = f;
    }
  }
  if (best_face < 0)
    return std::nullopt;
  const auto face = mesh.face(best_face);
  std::array<int, 3> corners{face[0], face[1], face[2]};
  std::sort(corners.begin(), corners.end());
  // The element with these three corners.
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto el = mesh.element(e);
    int shared = 0, fourth = -1;
    for (int a = 0; a < 4; ++a) {
      if (std::binary_search(corners.begin(), corners.end(), el[static_cast<std::size_t>(a)]))
        ++shared;
      else
        fourth = el[static_cast<std::size_t>(a)];
    }
    if (shared != 3)
      continue;
    const Eigen::Vector3d centroid = centroid_of(face);
    Eigen::Vector3d normal = (X(face[1]) - X(face[0])).cross(X(face[2]) - X(face[0])).normalized();
    if (normal.dot(centroid - X(fourth)) < 0.0)
      normal = -normal;
    int point = 0;
    for (int q = 1; q < problem.space().points_per_element(); ++q) {
      if ((problem.space().position(e, q) - centroid).norm() <
          (problem.space().position(e, point) - centroid).norm())
        point = q;
    }
    return SurfaceLocation{e, point, centroid, normal, -1, 0};
  }
  return std::nullopt;  // a boundary triangle of no element: not a mesh read_msh accepts
}

}  // namespace isomuscle::io
