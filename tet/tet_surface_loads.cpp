#include "tet/tet_surface_loads.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <span>
#include <stdexcept>

#include "geometry/gauss_legendre.hpp"

namespace isomuscle::tet {

namespace {

constexpr int kPointsPerDirection = 3;

struct TrianglePoint {
  double xi = 0.0, eta = 0.0, weight = 0.0;
};

// Conical product rule on {xi, eta >= 0, xi + eta <= 1}: (a, b) in [0, 1]^2 ->
// (xi, eta) = (a, b (1 - a)), dxi deta = (1 - a) da db.
const std::vector<TrianglePoint>& triangle_rule() {
  static const std::vector<TrianglePoint> rule = [] {
    const geometry::GaussLegendreRule g = geometry::gauss_legendre_rule(kPointsPerDirection);
    std::vector<TrianglePoint> out;
    for (std::size_t i = 0; i < g.points.size(); ++i)
      for (std::size_t j = 0; j < g.points.size(); ++j) {
        const double a = 0.5 * (1.0 + g.points[i]), b = 0.5 * (1.0 + g.points[j]);
        out.push_back({a, b * (1.0 - a), 0.25 * g.weights[i] * g.weights[j] * (1.0 - a)});
      }
    return out;
  }();
  return rule;
}

// Shape functions of the 3- or 6-node triangle and their (xi, eta) derivatives.
void triangle_shape(int order, double xi, double eta, double* N, double* dNx, double* dNe) {
  const double L0 = 1.0 - xi - eta, L1 = xi, L2 = eta;
  if (order == 1) {
    N[0] = L0, N[1] = L1, N[2] = L2;
    dNx[0] = -1.0, dNx[1] = 1.0, dNx[2] = 0.0;
    dNe[0] = -1.0, dNe[1] = 0.0, dNe[2] = 1.0;
    return;
  }
  N[0] = L0 * (2.0 * L0 - 1.0), N[1] = L1 * (2.0 * L1 - 1.0), N[2] = L2 * (2.0 * L2 - 1.0);
  N[3] = 4.0 * L0 * L1, N[4] = 4.0 * L1 * L2, N[5] = 4.0 * L2 * L0;
  dNx[0] = -(4.0 * L0 - 1.0), dNx[1] = 4.0 * L1 - 1.0, dNx[2] = 0.0;
  dNx[3] = 4.0 * (L0 - L1), dNx[4] = 4.0 * L2, dNx[5] = -4.0 * L2;
  dNe[0] = -(4.0 * L0 - 1.0), dNe[1] = 0.0, dNe[2] = 4.0 * L2 - 1.0;
  dNe[3] = -4.0 * L1, dNe[4] = 4.0 * L1, dNe[5] = 4.0 * (L0 - L2);
}

// Calls visit(node indices, N, X, dA) at every rule point of face f.
template <class Visit>
void for_each_point(const TetMesh& mesh, int f, Visit visit) {
  const auto nodes = mesh.face(f);
  const int n = mesh.nodes_per_face();
  double N[6], dNx[6], dNe[6];
  for (const TrianglePoint& p : triangle_rule()) {
    triangle_shape(mesh.order, p.xi, p.eta, N, dNx, dNe);
    Eigen::Vector3d X = Eigen::Vector3d::Zero(), tx = Eigen::Vector3d::Zero(),
                    te = Eigen::Vector3d::Zero();
    for (int a = 0; a < n; ++a) {
      const Eigen::Vector3d& P = mesh.nodes[nodes[a]];
      X += N[a] * P;
      tx += dNx[a] * P;
      te += dNe[a] * P;
    }
    visit(nodes, N, X, p.weight * tx.cross(te).norm());
  }
}

void check_face(const TetMesh& mesh, int f, const std::string& label) {
  if (f < 0 || f >= mesh.num_boundary_faces())
    throw std::invalid_argument(label + ": boundary face " + std::to_string(f) + " out of range (" +
                                std::to_string(mesh.num_boundary_faces()) + " faces)");
}

}  // namespace

void add_surface_loads(const TetMesh& mesh, const std::vector<TetSurfaceLoad>& loads, double t,
                       Eigen::VectorXd& f) {
  for (const TetSurfaceLoad& load : loads) {
    if (!load.traction)
      throw std::invalid_argument(load.label + ": no traction function");
    for (int face : load.faces) {
      check_face(mesh, face, load.label);
      for_each_point(
          mesh, face,
          [&](std::span<const int> nodes, const double* N, const Eigen::Vector3d& X, double dA) {
            const Eigen::Vector3d t0 = load.traction(X, t);
            if (!t0.allFinite())
              throw std::invalid_argument(load.label + ": the traction is not finite at X = (" +
                                          std::to_string(X.x()) + ", " + std::to_string(X.y()) +
                                          ", " + std::to_string(X.z()) + ")");
            for (std::size_t a = 0; a < nodes.size(); ++a)
              f.segment<3>(3 * nodes[a]) += N[a] * dA * t0;
          });
    }
  }
}

double faces_area(const TetMesh& mesh, const std::vector<int>& faces) {
  double area = 0.0;
  for (int face : faces) {
    check_face(mesh, face, "faces_area");
    for_each_point(mesh, face,
                   [&](std::span<const int>, const double*, const Eigen::Vector3d&, double dA) {
                     area += dA;
                   });
  }
  return area;
}

std::vector<int> faces_on_nodes(const TetMesh& mesh, const std::vector<int>& nodes) {
  std::vector<int> out;
  for (int f = 0; f < mesh.num_boundary_faces(); ++f) {
    const auto face = mesh.face(f);
    if (std::all_of(face.begin(), face.end(),
                    [&](int n) { return std::binary_search(nodes.begin(), nodes.end(), n); }))
      out.push_back(f);
  }
  return out;
}

}  // namespace isomuscle::tet
