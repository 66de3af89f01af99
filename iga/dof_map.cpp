#include "iga/dof_map.hpp"

#include "geometry/coincident_points.hpp"

#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

namespace isomuscle::iga {

namespace {

double net_diagonal(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) {
    return 0.0;
  }
  Eigen::Vector3d lo = points.front();
  Eigen::Vector3d hi = points.front();
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

void check_tolerance(double relative_tolerance) {
  if (!(relative_tolerance >= 0.0 && relative_tolerance <= 1e-3)) {
    throw std::invalid_argument("iga::DofMap: relative coincidence tolerance " +
                                std::to_string(relative_tolerance) +
                                " outside the valid range [0, 1e-3]");
  }
}

}  // namespace

// Groups of coincident control points from geometry::find_coincident_points (spatial hashing,
// transitive), nodes numbered in the order of their first control point; build() then checks every
// group against the tolerance again.
DofMap::DofMap(const geometry::NurbsVolume& volume, double relative_tolerance) {
  check_tolerance(relative_tolerance);
  geometry::CoincidentPoints groups = geometry::find_coincident_points(volume, relative_tolerance);
  build(volume, std::move(groups.group), relative_tolerance);
}

DofMap DofMap::unmerged(const geometry::NurbsVolume& volume) {
  std::vector<int> node_of(volume.num_control_points());
  std::iota(node_of.begin(), node_of.end(), 0);
  return DofMap(volume, std::move(node_of), 0.0);
}

DofMap::DofMap(const geometry::NurbsVolume& volume, std::vector<int> node_of_control_point,
               double relative_tolerance) {
  check_tolerance(relative_tolerance);
  build(volume, std::move(node_of_control_point), relative_tolerance);
}

// Checks the grouping geometrically: every member of a node within tol of the node's first point.
void DofMap::build(const geometry::NurbsVolume& volume, std::vector<int> node_of_control_point,
                   double relative_tolerance) {
  const auto& pts = volume.points();
  const int n = static_cast<int>(pts.size());
  if (static_cast<int>(node_of_control_point.size()) != n) {
    throw std::invalid_argument("iga::DofMap: " + std::to_string(node_of_control_point.size()) +
                                " node indices given for " + std::to_string(n) + " control points");
  }
  int num_nodes = 0;
  for (int i = 0; i < n; ++i) {
    if (node_of_control_point[i] < 0) {
      throw std::invalid_argument("iga::DofMap: control point " + std::to_string(i) +
                                  " has negative node index " +
                                  std::to_string(node_of_control_point[i]));
    }
    num_nodes = std::max(num_nodes, node_of_control_point[i] + 1);
  }
  std::vector<int> count(num_nodes, 0);
  for (int i = 0; i < n; ++i) {
    ++count[node_of_control_point[i]];
  }
  for (int k = 0; k < num_nodes; ++k) {
    if (count[k] == 0) {
      throw std::invalid_argument("iga::DofMap: node " + std::to_string(k) +
                                  " has no control point (node numbers must have no gaps)");
    }
  }
  node_start_.assign(num_nodes + 1, 0);
  for (int k = 0; k < num_nodes; ++k) {
    node_start_[k + 1] = node_start_[k] + count[k];
  }
  members_.assign(n, 0);
  std::vector<int> fill(node_start_.begin(), node_start_.end() - 1);
  for (int i = 0; i < n; ++i) {
    members_[fill[node_of_control_point[i]]++] = i;
  }
  const double tol = relative_tolerance * net_diagonal(pts);
  positions_.resize(num_nodes);
  for (int k = 0; k < num_nodes; ++k) {
    const int first = members_[node_start_[k]];
    positions_[k] = pts[first];
    for (int m = node_start_[k] + 1; m < node_start_[k + 1]; ++m) {
      const double dist = (pts[members_[m]] - pts[first]).norm();
      if (dist > tol) {
        std::ostringstream msg;
        msg << "iga::DofMap: control points " << first << " and " << members_[m] << " share node "
            << k << " but are " << dist << " apart (tolerance " << tol
            << "): they are not the same physical point";
        throw std::invalid_argument(msg.str());
      }
    }
  }
  node_of_ = std::move(node_of_control_point);
}

int DofMap::num_merged_nodes() const {
  int m = 0;
  for (int k = 0; k < num_nodes(); ++k) {
    m += node_start_[k + 1] - node_start_[k] > 1 ? 1 : 0;
  }
  return m;
}

}  // namespace isomuscle::iga
