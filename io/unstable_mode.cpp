#include "io/unstable_mode.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "io/csv_writer.hpp"
#include "solver/lowest_modes.hpp"

namespace isomuscle::io {

UnstableMode compute_unstable_mode(solver::NonlinearProblem& problem, const Eigen::VectorXd& u,
                                   const FreeDofLayout& layout,
                                   const std::filesystem::path& csv_path, int count) {
  const auto start = std::chrono::steady_clock::now();
  UnstableMode mode;
  const auto finish = [&]() {
    mode.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return mode;
  };
  const int n = problem.size();
  if (static_cast<int>(layout.node_of.size()) != n) {
    mode.message = "the layout of the free unknowns does not match the problem";
    return finish();
  }
  Eigen::VectorXd residual;
  solver::SparseMatrix tangent;
  if (const solver::EvaluationStatus status = problem.evaluate(u, residual, &tangent); !status.ok) {
    mode.message = "the tangent at the equilibrium could not be evaluated: " + status.message;
    return finish();
  }
  Eigen::VectorXd weights(n);
  for (int i = 0; i < n; ++i)
    weights[i] = layout.node_volumes[layout.node_of[static_cast<std::size_t>(i)]];
  const solver::LowestModes modes = solver::lowest_modes(tangent, weights, {.count = count});
  mode.factorizations = modes.factorizations;
  mode.solves = modes.operations;
  mode.shift = modes.shift;
  if (!modes.ok) {
    mode.message = modes.message;
    return finish();
  }
  mode.eigenvalues = modes.eigenvalues;
  mode.negative = modes.negative();

  // Nodal vectors of the lowest mode, its peak and the share of the volume it occupies.
  const std::size_t nodes = layout.node_positions.size();
  std::vector<Eigen::Vector3d> nodal(nodes, Eigen::Vector3d::Zero());
  std::vector<char> has_free(nodes, 0);
  for (int i = 0; i < n; ++i) {
    const auto node = static_cast<std::size_t>(layout.node_of[static_cast<std::size_t>(i)]);
    nodal[node][layout.component_of[static_cast<std::size_t>(i)]] = modes.vectors(i, 0);
    has_free[node] = 1;
  }
  double peak = 0.0;
  for (std::size_t a = 0; a < nodes; ++a) {
    if (const double amplitude = nodal[a].norm(); amplitude > peak) {
      peak = amplitude;
      mode.peak_position = layout.node_positions[a];
    }
  }
  // e_n = V_n |phi_n|^2 sums to 1 (the vectors are W-normalised).
  double sum_e2_over_v = 0.0, radius2 = 0.0;
  for (std::size_t a = 0; a < nodes; ++a) {
    if (!has_free[a])
      continue;
    const double v = layout.node_volumes[static_cast<Eigen::Index>(a)];
    const double e = v * nodal[a].squaredNorm();
    sum_e2_over_v += e * e / v;
    radius2 += e * (layout.node_positions[a] - mode.peak_position).squaredNorm();
  }
  mode.volume_share = 1.0 / (layout.node_volumes.sum() * sum_e2_over_v);
  mode.radius = std::sqrt(radius2);

  CsvWriter csv(csv_path, {"x", "y", "z", "volume", "mode_x", "mode_y", "mode_z"});
  for (std::size_t a = 0; a < nodes; ++a) {
    if (!has_free[a])
      continue;
    const Eigen::Vector3d& X = layout.node_positions[a];
    const Eigen::Vector3d m = nodal[a] / peak;
    csv.write_row({X.x(), X.y(), X.z(), layout.node_volumes[static_cast<Eigen::Index>(a)], m.x(),
                   m.y(), m.z()});
  }
  mode.ok = true;
  return finish();
}

std::string describe(const UnstableMode& mode, const std::string& csv_name) {
  if (!mode.ok)
    return "no mode: " + mode.message;
  char text[360];
  const Eigen::Vector3d& p = mode.peak_position;
  std::snprintf(text, sizeof text,
                "lowest eigenvalue %.4g Pa/m^2 (%d of the %d lowest negative); the mode is largest "
                "at (%.4g, %.4g, %.4g) m, extends %.2g m about it and occupies %.2g %% of the "
                "volume (%s, %.3g s)",
                mode.eigenvalues[0], mode.negative, static_cast<int>(mode.eigenvalues.size()),
                p.x(), p.y(), p.z(), mode.radius, 100.0 * mode.volume_share, csv_name.c_str(),
                mode.seconds);
  return text;
}

}  // namespace isomuscle::io
