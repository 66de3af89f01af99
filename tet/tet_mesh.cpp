#include "tet/tet_mesh.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "tet/tet_elements.hpp"

namespace isomuscle::tet {

namespace {

constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
// Faces of a positively oriented tetrahedron, outward normal by the right-hand rule.
constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

double corner_volume(const TetMesh& mesh, std::span<const int> el) {
  const Eigen::Vector3d& x0 = mesh.nodes[el[0]];
  Eigen::Matrix3d J;
  J.col(0) = mesh.nodes[el[1]] - x0;
  J.col(1) = mesh.nodes[el[2]] - x0;
  J.col(2) = mesh.nodes[el[3]] - x0;
  return J.determinant() / 6.0;
}

// Local edge node (4..9) of the edge between corners i and j.
int edge_node(int i, int j) {
  for (int k = 0; k < 6; ++k) {
    if ((kEdges[k][0] == i && kEdges[k][1] == j) || (kEdges[k][0] == j && kEdges[k][1] == i)) {
      return 4 + k;
    }
  }
  return -1;
}

}  // namespace

void TetMesh::validate() const {
  tet_nodes(order);
  const std::size_t npe = static_cast<std::size_t>(nodes_per_element());
  if (elements.size() != npe * element_region.size()) {
    throw std::invalid_argument(
        "TetMesh: " + std::to_string(elements.size()) + " element node entries for " +
        std::to_string(element_region.size()) + " elements of " + std::to_string(npe) + " nodes");
  }
  if (boundary.size() != static_cast<std::size_t>(nodes_per_face()) * boundary_tag.size()) {
    throw std::invalid_argument("TetMesh: boundary node entries do not match the face count");
  }
  for (int e = 0; e < num_elements(); ++e) {
    for (int n : element(e)) {
      if (n < 0 || n >= num_nodes()) {
        throw std::invalid_argument("TetMesh: element " + std::to_string(e) + " names node " +
                                    std::to_string(n) + " of " + std::to_string(num_nodes()));
      }
    }
    const double v = corner_volume(*this, element(e));
    if (!(v > 0.0)) {
      throw std::invalid_argument("TetMesh: element " + std::to_string(e) + " has corner volume " +
                                  std::to_string(v) + " <= 0 (inverted or degenerate)");
    }
  }
  for (int n : boundary) {
    if (n < 0 || n >= num_nodes()) {
      throw std::invalid_argument("TetMesh: a boundary face names node " + std::to_string(n) +
                                  " of " + std::to_string(num_nodes()));
    }
  }
}

// V = sum_e sum_q w_q det(dX/dxi) (header; degree-6 rule: exact for quadratic geometry).
double mesh_volume(const TetMesh& mesh) {
  const int npe = mesh.nodes_per_element();
  const TetRule rule = tet_rule(mesh.order == 1 ? 1 : 6);
  std::vector<std::vector<Eigen::Vector3d>> grads(rule.points.size(),
                                                  std::vector<Eigen::Vector3d>(npe));
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    tet_shape_gradients(mesh.order, rule.points[q], grads[q].data());
  }
  double volume = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto el = mesh.element(e);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int a = 0; a < npe; ++a) {
        J.noalias() += mesh.nodes[el[a]] * grads[q][a].transpose();
      }
      volume += rule.weights[q] * J.determinant();
    }
  }
  return volume;
}

int group_tag(const TetMesh& mesh, const std::string& name) {
  std::string names;
  for (const auto& [tag, n] : mesh.group_names) {
    if (n == name) {
      return tag;
    }
    names += (names.empty() ? "" : ", ") + n;
  }
  throw std::invalid_argument("no physical group named '" + name + "' in the mesh (groups: " +
                              (names.empty() ? std::string("none") : names) + ")");
}

std::vector<int> boundary_nodes(const TetMesh& mesh, int tag) {
  std::vector<int> out;
  for (int f = 0; f < mesh.num_boundary_faces(); ++f) {
    if (mesh.boundary_tag[f] == tag) {
      const auto nodes = mesh.face(f);
      out.insert(out.end(), nodes.begin(), nodes.end());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<int> nodes_on_plane(const TetMesh& mesh, int axis, double coordinate,
                                double tolerance) {
  if (axis < 0 || axis > 2) {
    throw std::invalid_argument("nodes_on_plane: axis " + std::to_string(axis) +
                                " (valid: 0 = x, 1 = y, 2 = z)");
  }
  std::vector<int> out;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (std::abs(mesh.nodes[n][axis] - coordinate) <= tolerance) {
      out.push_back(n);
    }
  }
  return out;
}

// Kuhn triangulation of a structured grid (header).
TetMesh structured_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       const std::array<int, 3>& n, int order) {
  tet_nodes(order);
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1 || !(hi[d] > lo[d])) {
      throw std::invalid_argument("structured_box: need n >= 1 cells and lo < hi in direction " +
                                  std::to_string(d));
    }
  }
  TetMesh mesh;
  mesh.order = order;
  const auto vid = [&](int i, int j, int k) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  for (int k = 0; k <= n[2]; ++k) {
    for (int j = 0; j <= n[1]; ++j) {
      for (int i = 0; i <= n[0]; ++i) {
        const Eigen::Vector3d t(double(i) / n[0], double(j) / n[1], double(k) / n[2]);
        mesh.nodes.push_back(lo + (hi - lo).cwiseProduct(t));
      }
    }
  }
  constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::map<std::pair<int, int>, int> midpoints;
  const int npe = mesh.nodes_per_element();
  std::vector<int> el(npe);
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        for (const auto& p : kPerm) {
          std::array<int, 3> c = {i, j, k};
          el[0] = vid(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            el[s + 1] = vid(c[0], c[1], c[2]);
          }
          if (corner_volume(mesh, std::span<const int>(el.data(), 4)) < 0.0) {
            std::swap(el[1], el[2]);
          }
          if (order == 2) {
            for (int m = 0; m < 6; ++m) {
              const int a = el[kEdges[m][0]];
              const int b = el[kEdges[m][1]];
              const auto key = std::minmax(a, b);
              auto it = midpoints.find(key);
              if (it == midpoints.end()) {
                it = midpoints.emplace(key, mesh.num_nodes()).first;
                mesh.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
              }
              el[4 + m] = it->second;
            }
          }
          mesh.elements.insert(mesh.elements.end(), el.begin(), el.end());
          mesh.element_region.push_back(0);
        }
      }
    }
  }
  // Boundary: the faces on the six planes, oriented outward, tagged 1..6.
  const double tol = 1e-12 * (hi - lo).norm();
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto t = mesh.element(e);
    for (const auto& f : kFaces) {
      for (int side = 0; side < 6; ++side) {
        const int axis = side / 2;
        const double plane = side % 2 == 0 ? lo[axis] : hi[axis];
        bool on = true;
        for (int c : f) {
          on = on && std::abs(mesh.nodes[t[c]][axis] - plane) <= tol;
        }
        if (!on) {
          continue;
        }
        for (int c : f) {
          mesh.boundary.push_back(t[c]);
        }
        if (order == 2) {
          for (int s = 0; s < 3; ++s) {
            mesh.boundary.push_back(t[edge_node(f[s], f[(s + 1) % 3])]);
          }
        }
        mesh.boundary_tag.push_back(side + 1);
      }
    }
  }
  mesh.group_names = {{1, "x_min"}, {2, "x_max"}, {3, "y_min"},
                      {4, "y_max"}, {5, "z_min"}, {6, "z_max"}};
  return mesh;
}

}  // namespace isomuscle::tet
