#include "tet/tet_locator.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "tet/tet_elements.hpp"

namespace isomuscle::tet {

namespace {

constexpr double kInsideTolerance = 1e-10;  // barycentric round-off still counted as inside
constexpr int kNewtonIterations = 20;

}  // namespace

// Grid of about one cell per element: cell size = bounding box / cbrt(number of elements).
TetLocator::TetLocator(const TetMesh& mesh, double outside_tolerance)
    : mesh_(mesh), outside_tolerance_(outside_tolerance) {
  Eigen::Vector3d lo = mesh.nodes.front(), hi = mesh.nodes.front();
  for (const Eigen::Vector3d& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double pad = 1e-9 * (hi - lo).norm();
  lo_ = lo.array() - pad;
  const Eigen::Vector3d extent = (hi - lo).array() + 2.0 * pad;
  const double n = std::max(1.0, std::cbrt(static_cast<double>(mesh.num_elements())));
  for (int d = 0; d < 3; ++d) {
    cells_[d] = std::max(1, static_cast<int>(std::ceil(n * extent[d] / extent.maxCoeff())));
    cell_size_[d] = extent[d] / cells_[d];
  }
  grid_.assign(static_cast<std::size_t>(cells_.prod()), {});
  for (int e = 0; e < mesh.num_elements(); ++e) {
    Eigen::Vector3d a = mesh.nodes[mesh.element(e)[0]], b = a;
    for (int node : mesh.element(e)) {
      a = a.cwiseMin(mesh.nodes[node]);
      b = b.cwiseMax(mesh.nodes[node]);
    }
    // Grow by the outside tolerance so that points just outside the element still find it.
    const Eigen::Vector3d grow = Eigen::Vector3d::Constant(outside_tolerance_ * (b - a).norm());
    Eigen::Vector3i i0, i1;
    for (int d = 0; d < 3; ++d) {
      i0[d] =
          std::clamp(static_cast<int>((a[d] - grow[d] - lo_[d]) / cell_size_[d]), 0, cells_[d] - 1);
      i1[d] =
          std::clamp(static_cast<int>((b[d] + grow[d] - lo_[d]) / cell_size_[d]), 0, cells_[d] - 1);
    }
    for (int i = i0[0]; i <= i1[0]; ++i)
      for (int j = i0[1]; j <= i1[1]; ++j)
        for (int k = i0[2]; k <= i1[2]; ++k)
          grid_[static_cast<std::size_t>(i + cells_[0] * (j + cells_[1] * k))].push_back(e);
  }
}

// Barycentric coordinates of the corners (exact for 4-node elements), then Newton on
// X(xi) = sum_a N_a(xi) X_a for curved 10-node elements.
TetLocation TetLocator::solve_in(int e, const Eigen::Vector3d& X) const {
  const auto el = mesh_.element(e);
  Eigen::Matrix3d J;
  for (int d = 0; d < 3; ++d)
    J.col(d) = mesh_.nodes[el[d + 1]] - mesh_.nodes[el[0]];
  TetLocation loc;
  loc.element = e;
  loc.xi = J.partialPivLu().solve(X - mesh_.nodes[el[0]]);
  if (mesh_.order == 2) {
    double values[10];
    Eigen::Vector3d gradients[10];
    for (int it = 0; it < kNewtonIterations; ++it) {
      tet_shape_values(2, loc.xi, values);
      tet_shape_gradients(2, loc.xi, gradients);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Matrix3d dx = Eigen::Matrix3d::Zero();
      for (int a = 0; a < 10; ++a) {
        x += values[a] * mesh_.nodes[el[a]];
        dx += mesh_.nodes[el[a]] * gradients[a].transpose();
      }
      const Eigen::Vector3d step = dx.partialPivLu().solve(X - x);
      loc.xi += step;
      if (!(step.norm() > 1e-14))
        break;
    }
  }
  const double l0 = 1.0 - loc.xi.sum();
  loc.outside = std::max(0.0, -std::min({l0, loc.xi[0], loc.xi[1], loc.xi[2]}));
  return loc;
}

std::optional<TetLocation> TetLocator::locate(const Eigen::Vector3d& X) const {
  Eigen::Vector3i c;
  for (int d = 0; d < 3; ++d) {
    const double t = (X[d] - lo_[d]) / cell_size_[d];
    if (!(t >= 0.0) || t > cells_[d] + 1e-9)
      return std::nullopt;
    c[d] = std::min(static_cast<int>(t), cells_[d] - 1);
  }
  std::optional<TetLocation> best;
  for (int e : grid_[static_cast<std::size_t>(c[0] + cells_[0] * (c[1] + cells_[1] * c[2]))]) {
    const TetLocation loc = solve_in(e, X);
    if (!std::isfinite(loc.outside))
      continue;
    if (loc.outside <= kInsideTolerance)
      return loc;
    if (!best || loc.outside < best->outside)
      best = loc;
  }
  if (best && best->outside <= outside_tolerance_)
    return best;
  return std::nullopt;
}

Eigen::Vector3d TetLocator::interpolate(const TetLocation& at, const Eigen::VectorXd& nodal) const {
  double values[10];
  tet_shape_values(mesh_.order, at.xi, values);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const auto el = mesh_.element(at.element);
  for (int a = 0; a < mesh_.nodes_per_element(); ++a)
    sum += values[a] * nodal.segment<3>(3 * el[a]);
  return sum;
}

}  // namespace isomuscle::tet
