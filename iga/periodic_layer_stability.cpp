#include "iga/periodic_layer_stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_volume.hpp"
#include "iga/element_kernels.hpp"
#include "iga/pressure_space.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {
namespace {

// Greville abscissae (1/p) sum_{l=1..p} u_{i+l}: control points there make the B-spline map
// affine, X = sum_d xi_d edge_d (the linear precision of B-splines).
std::vector<double> greville(const geometry::KnotVector& kv) {
  const int p = kv.degree();
  std::vector<double> g(static_cast<std::size_t>(kv.num_basis()));
  for (int i = 0; i < kv.num_basis(); ++i) {
    double sum = 0.0;
    for (int l = 1; l <= p; ++l)
      sum += kv[i + l];
    g[static_cast<std::size_t>(i)] = sum / p;
  }
  return g;
}

// The edge vectors as the columns of the layer's (affine) dX/dxi.
Eigen::Matrix3d edge_matrix(const LayerGeometry& layer) {
  Eigen::Matrix3d E;
  for (int d = 0; d < 3; ++d)
    E.col(d) = layer.edges[d];
  return E;
}

void check_layer(const LayerGeometry& layer, const LayerState& state) {
  if (state.law == nullptr || !state.law->has_volumetric_split())
    throw std::invalid_argument(
        "periodic layer: the mixed element needs a law with a volumetric split");
  if (!(state.F.determinant() > 0.0))
    throw std::invalid_argument("periodic layer: det F = " + std::to_string(state.F.determinant()) +
                                " <= 0");
  if (static_cast<int>(state.history.size()) != state.law->history_size())
    throw std::invalid_argument("periodic layer: the history has " +
                                std::to_string(state.history.size()) + " values, the law " +
                                std::to_string(state.law->history_size()));
  for (int d = 0; d < 3; ++d) {
    if (layer.degrees[d] < 1 || layer.degrees[d] > 10)
      throw std::invalid_argument("periodic layer: degree " + std::to_string(layer.degrees[d]) +
                                  " of direction " + std::to_string(d) + " is not in 1..10");
  }
  if (layer.depth_spans.empty())
    throw std::invalid_argument("periodic layer: no depth spans");
  for (double w : layer.depth_spans) {
    if (!(w > 0.0) || !std::isfinite(w))
      throw std::invalid_argument("periodic layer: a depth span is not positive");
  }
  const Eigen::Matrix3d E = edge_matrix(layer);
  const double scale = E.col(0).norm() * E.col(1).norm() * E.col(2).norm();
  if (!(std::abs(E.determinant()) > 1e-9 * scale))
    throw std::invalid_argument("periodic layer: the edge vectors do not span a volume");
}

}  // namespace

LayerGeometry subdivided(const LayerGeometry& layer, int r) {
  if (r < 1)
    throw std::invalid_argument("periodic layer: subdivision " + std::to_string(r) + " < 1");
  LayerGeometry out = layer;
  out.edges[0] /= r;
  out.edges[1] /= r;
  out.depth_spans.clear();
  for (double w : layer.depth_spans)
    out.depth_spans.insert(out.depth_spans.end(), static_cast<std::size_t>(r), w / r);
  return out;
}

PeriodicLayer::PeriodicLayer(const LayerGeometry& given, const LayerState& state) {
  check_layer(given, state);
  LayerGeometry layer = given;
  if (edge_matrix(layer).determinant() < 0.0) {
    // Space needs det dX/dxi > 0: exchange the surface directions, and their angles in lowest_at.
    std::swap(layer.edges[0], layer.edges[1]);
    std::swap(layer.degrees[0], layer.degrees[1]);
    std::swap(layer.quadrature_points[0], layer.quadrature_points[1]);
    swapped_ = true;
  }

  // 4p + 1 uniform spans in each surface direction: the middle span's functions are uniform
  // interior B-splines, translates of one another, as a periodic layer has them.
  std::array<geometry::KnotVector, 3> knots;
  std::array<int, 2> middle{};
  for (int d = 0; d < 2; ++d) {
    const int n = 4 * layer.degrees[d] + 1;
    knots[d] = geometry::KnotVector::uniform_clamped(layer.degrees[d], n, 0.0, n);
    middle[d] = 2 * layer.degrees[d];
  }
  std::vector<double> interior;
  double depth = 0.0;
  for (std::size_t k = 0; k < layer.depth_spans.size(); ++k) {
    depth += layer.depth_spans[k];
    if (k + 1 < layer.depth_spans.size())
      interior.push_back(depth);
  }
  knots[2] = geometry::KnotVector::clamped(layer.degrees[2], interior, 0.0, depth);

  const std::array<std::vector<double>, 3> g = {greville(knots[0]), greville(knots[1]),
                                                greville(knots[2])};
  const int n0 = knots[0].num_basis();
  const int n1 = knots[1].num_basis();
  depth_rows_ = knots[2].num_basis();
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<std::size_t>(n0 * n1 * depth_rows_));
  for (int k = 0; k < depth_rows_; ++k)
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n0; ++i)
        points.push_back(g[0][static_cast<std::size_t>(i)] * layer.edges[0] +
                         g[1][static_cast<std::size_t>(j)] * layer.edges[1] +
                         g[2][static_cast<std::size_t>(k)] * layer.edges[2]);
  std::vector<double> weights(points.size(), 1.0);
  QuadratureOptions rule;
  rule.points = layer.quadrature_points;
  const Space space(geometry::NurbsVolume(knots, points, std::move(weights)), rule);
  const PressureSpace pressure(space, layer.pressure_degree);

  const materials::MaterialLaw& law = *state.law;
  const int nen = space.functions_per_element();
  const int nqp = space.points_per_element();
  const continuum::UniformMaterialContext material(law, state.fibre, state.history, state.time,
                                                   state.dt, nqp);

  const Eigen::Matrix3d gradient = state.F - Eigen::Matrix3d::Identity();
  ElementWorkspace ws(nen, nqp, pressure.size());
  lumped_ = Eigen::VectorXd::Zero(depth_rows_);
  for (int e = 0; e < space.num_elements(); ++e) {
    const Element& el = space.element(e);
    if (el.position[0] != middle[0] || el.position[1] != middle[1])
      continue;
    const auto cps = space.control_points(e);
    ColumnElement column;
    for (int a = 0; a < nen; ++a) {
      const int cp = cps[static_cast<std::size_t>(a)];
      ws.ue.col(a) = gradient * points[static_cast<std::size_t>(cp)];
      column.row.push_back(cp / (n0 * n1));
      column.offset.emplace_back(cp % n0, (cp / n0) % n1);
    }
    const KernelStatus status =
        mixed_kernel(element_view(space, e), material.context(), pressure, e, nullptr, true, ws);
    if (!status.ok())
      throw std::runtime_error("periodic layer: the mixed element fails at the state: " +
                               continuum::describe_kernel_status(status, law.name()));
    column.tangent = ws.ke;
    for (int q = 0; q < nqp; ++q) {
      const auto values = space.values(e, q);
      for (int a = 0; a < nen; ++a)
        lumped_[column.row[static_cast<std::size_t>(a)]] +=
            values[static_cast<std::size_t>(a)] * space.dv(e, q);
    }
    column_.push_back(std::move(column));
  }
}

PeriodicLayer::PeriodicLayer(std::vector<ColumnElement> column, Eigen::VectorXd lumped)
    : column_(std::move(column)), lumped_(std::move(lumped)) {
  depth_rows_ = static_cast<int>(lumped_.size());
  if (column_.empty() || depth_rows_ < 2)
    throw std::invalid_argument("periodic layer: a column needs elements and two depth rows");
  for (const ColumnElement& el : column_) {
    const Eigen::Index n = 3 * static_cast<Eigen::Index>(el.row.size());
    if (el.offset.size() != el.row.size() || el.tangent.rows() != n || el.tangent.cols() != n)
      throw std::invalid_argument("periodic layer: a column element's tangent is " +
                                  std::to_string(el.tangent.rows()) + " x " +
                                  std::to_string(el.tangent.cols()) + " for " +
                                  std::to_string(el.row.size()) + " functions");
    for (int r : el.row) {
      if (r < 0 || r >= depth_rows_)
        throw std::invalid_argument("periodic layer: depth row " + std::to_string(r) +
                                    " is not among the " + std::to_string(depth_rows_));
    }
  }
  for (int r = 0; r + 1 < depth_rows_; ++r) {
    if (!(lumped_[r] > 0.0))
      throw std::invalid_argument("periodic layer: the lumped volume of depth row " +
                                  std::to_string(r) + " is not positive");
  }
}

BlochMode PeriodicLayer::lowest_at(const Eigen::Vector2d& angles) const {
  const Eigen::Vector2d theta = swapped_ ? Eigen::Vector2d(angles[1], angles[0]) : angles;
  // The clamped row (the last) has no unknowns.
  const int rows = depth_rows_ - 1;
  Eigen::MatrixXcd K = Eigen::MatrixXcd::Zero(3 * rows, 3 * rows);
  for (const ColumnElement& el : column_) {
    const int nen = static_cast<int>(el.row.size());
    for (int a = 0; a < nen; ++a) {
      const int ra = el.row[static_cast<std::size_t>(a)];
      if (ra >= rows)
        continue;
      for (int b = 0; b < nen; ++b) {
        const int rb = el.row[static_cast<std::size_t>(b)];
        if (rb >= rows)
          continue;
        const double phase = theta.dot(el.offset[static_cast<std::size_t>(b)] -
                                       el.offset[static_cast<std::size_t>(a)]);
        const std::complex<double> factor = std::polar(1.0, phase);
        K.block<3, 3>(3 * ra, 3 * rb) += factor * el.tangent.block<3, 3>(3 * a, 3 * b);
      }
    }
  }
  // K U = lambda M U with M the lumped volumes, as M^-1/2 K M^-1/2.
  Eigen::VectorXd scale(3 * rows);
  for (int r = 0; r < rows; ++r)
    scale.segment<3>(3 * r).setConstant(1.0 / std::sqrt(lumped_[r]));
  const Eigen::MatrixXcd H = scale.asDiagonal() * K * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> solver(0.5 * (H + H.adjoint()));
  BlochMode mode;
  mode.eigenvalue = solver.eigenvalues()[0];
  mode.angles = angles;
  const Eigen::VectorXcd U = scale.asDiagonal() * solver.eigenvectors().col(0);
  mode.depth_amplitude.assign(static_cast<std::size_t>(depth_rows_), 0.0);
  double largest = 0.0;
  for (int r = 0; r < rows; ++r) {
    mode.depth_amplitude[static_cast<std::size_t>(r)] = U.segment<3>(3 * r).norm();
    largest = std::max(largest, mode.depth_amplitude[static_cast<std::size_t>(r)]);
  }
  for (double& a : mode.depth_amplitude)
    a /= largest;
  return mode;
}

BlochMode PeriodicLayer::lowest(int samples) const {
  if (samples < 2)
    throw std::invalid_argument("periodic layer: at least 2 samples per half turn");
  const double pi = std::numbers::pi;
  const double step0 = pi / samples;
  BlochMode best;
  best.eigenvalue = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= samples; ++i) {
    for (int j = -samples; j <= samples; ++j) {
      const BlochMode m = lowest_at(Eigen::Vector2d(i * step0, j * step0));
      if (m.eigenvalue < best.eigenvalue)
        best = m;
    }
  }
  // Pattern search about the best sample, inside theta_0 in [0, pi], theta_1 in [-pi, pi].
  for (double step = 0.5 * step0; step > 1e-4; step *= 0.5) {
    for (bool moved = true; moved;) {
      moved = false;
      for (const Eigen::Vector2d& d : {Eigen::Vector2d(step, 0.0), Eigen::Vector2d(-step, 0.0),
                                       Eigen::Vector2d(0.0, step), Eigen::Vector2d(0.0, -step)}) {
        const Eigen::Vector2d theta = best.angles + d;
        if (theta[0] < 0.0 || theta[0] > pi || std::abs(theta[1]) > pi)
          continue;
        const BlochMode m = lowest_at(theta);
        if (m.eigenvalue < best.eigenvalue) {
          best = m;
          moved = true;
        }
      }
    }
  }
  return best;
}

}  // namespace isomuscle::iga
