#include "io/run_comparison.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/LU>

#include "geometry/gauss_legendre.hpp"
#include "io/run_summary.hpp"
#include "io/setting_check.hpp"
#include "io/solution_sampler.hpp"

namespace isomuscle::io {

namespace fs = std::filesystem;

namespace {

RunSide read_side(const fs::path& run) {
  RunSide side;
  side.run = run;
  const RunSummary s = read_summary(run / "summary.json");
  side.discretisation = s.discretisation;
  side.status = s.converged ? "converged" : "failed";
  side.dofs = s.dofs;
  side.wall_seconds = s.wall_seconds.total;
  side.volume_initial_m3 = s.volume_initial_m3;
  side.volume_final_m3 = s.volume_final_m3;
  return side;
}

// The step of `solution` stored at time t (to 1e-9 relative), or a message listing its times.
std::size_t step_at(const StoredSolution& solution, double t) {
  for (std::size_t k = 0; k < solution.times.size(); ++k) {
    if (std::abs(solution.times[k] - t) <= 1e-9 * std::max(1.0, std::abs(t)))
      return k;
  }
  std::ostringstream msg;
  msg << solution.path.string() << " holds no step at t = " << format_number(t) << " s (times:";
  for (double x : solution.times)
    msg << " " << format_number(x);
  msg << "); pick a common output time with --time";
  throw std::runtime_error(msg.str());
}

}  // namespace

void ComparisonOptions::validate() const {
  if (subdivisions < 1 || subdivisions > 64)
    throw std::invalid_argument("subdivisions must be in 1..64 (got " +
                                std::to_string(subdivisions) + ")");
  if (points < 1 || points > 16)
    throw std::invalid_argument("points must be in 1..16 (got " + std::to_string(points) + ")");
  if (time && !std::isfinite(*time))
    throw std::invalid_argument("time must be finite");
}

double RunComparison::relative_max() const {
  return max_displacement_a_m > 0.0 ? max_difference_m / max_displacement_a_m : 0.0;
}

double RunComparison::relative_l2() const {
  return l2_displacement_a > 0.0 ? l2_difference / l2_displacement_a : 0.0;
}

// Gauss grid over A's geometry; u_A at xi, u_B at X (run_comparison.hpp).
RunComparison compare_runs(const fs::path& run_a, const fs::path& run_b,
                           const ComparisonOptions& options) {
  options.validate();
  RunComparison c;
  c.a = read_side(run_a);
  c.b = read_side(run_b);
  const StoredSolution sa = read_solution(run_a / "solution.h5");
  const StoredSolution sb = read_solution(run_b / "solution.h5");
  if (sa.times.empty())
    throw std::runtime_error(sa.path.string() +
                             " holds no step (the run stopped before its "
                             "first output time)");
  c.time = options.time.value_or(sa.times.back());
  const std::size_t ka = step_at(sa, c.time);
  const std::size_t kb = step_at(sb, c.time);
  const SolutionSampler ua(sa);
  const SolutionSampler ub(sb);

  const geometry::NurbsVolume& g = sa.geometry;
  const geometry::GaussLegendreRule rule = geometry::gauss_legendre_rule(options.points);
  std::array<std::vector<double>, 3> cuts;  // sub-cell boundaries per direction
  for (int d = 0; d < 3; ++d) {
    const std::vector<double> b = g.knots(d).breakpoints();
    for (std::size_t i = 0; i + 1 < b.size(); ++i)
      for (int s = 0; s < options.subdivisions; ++s)
        cuts[d].push_back(b[i] + (b[i + 1] - b[i]) * s / options.subdivisions);
    cuts[d].push_back(b.back());
  }
  double sum_diff = 0.0, sum_a = 0.0;
  const std::size_t n = rule.points.size();
  for (std::size_t i = 0; i + 1 < cuts[0].size(); ++i)
    for (std::size_t j = 0; j + 1 < cuts[1].size(); ++j)
      for (std::size_t k = 0; k + 1 < cuts[2].size(); ++k)
        for (std::size_t p = 0; p < n * n * n; ++p) {
          const std::size_t q[3] = {p % n, (p / n) % n, p / (n * n)};
          const std::size_t cell[3] = {i, j, k};
          Eigen::Vector3d xi;
          double weight = 1.0;
          for (int d = 0; d < 3; ++d) {
            const double lo = cuts[d][cell[d]], hi = cuts[d][cell[d] + 1];
            xi[d] = lo + 0.5 * (hi - lo) * (1.0 + rule.points[q[d]]);
            weight *= 0.5 * (hi - lo) * rule.weights[q[d]];
          }
          Eigen::Vector3d X;
          Eigen::Matrix3d J;
          g.evaluate_with_jacobian(xi, X, J);
          weight *= std::abs(J.determinant());
          ++c.samples;
          const std::optional<Eigen::Vector3d> b = ub.at_point(X, kb);
          if (!b) {
            ++c.outside_b;
            continue;
          }
          const std::optional<Eigen::Vector3d> ax = ua.at_parameter(xi, ka);
          if (!ax) {  // a tetrahedral A whose mesh misses this point of its own solid
            ++c.outside_a;
            continue;
          }
          const Eigen::Vector3d& a = *ax;
          const double diff = (a - *b).norm();
          if (diff > c.max_difference_m) {
            c.max_difference_m = diff;
            c.max_difference_at = X;
          }
          c.max_displacement_a_m = std::max(c.max_displacement_a_m, a.norm());
          sum_diff += weight * diff * diff;
          sum_a += weight * a.squaredNorm();
        }
  if (c.outside_b + c.outside_a == c.samples) {
    throw std::runtime_error("no material point of " + run_a.string() +
                             " lies inside the solid of " + run_b.string() +
                             ": are they the same body?");
  }
  c.l2_difference = std::sqrt(sum_diff);
  c.l2_displacement_a = std::sqrt(sum_a);
  return c;
}

nlohmann::ordered_json to_json(const RunComparison& c) {
  using Json = nlohmann::ordered_json;
  const auto side = [](const RunSide& s) {
    const auto optional = [](const std::optional<double>& v) {
      return v ? Json(*v) : Json(nullptr);
    };
    return Json{{"run", s.run.string()},
                {"discretisation", s.discretisation},
                {"status", s.status},
                {"dofs", s.dofs},
                {"wall_seconds", s.wall_seconds},
                {"volume_initial_m3", optional(s.volume_initial_m3)},
                {"volume_final_m3", optional(s.volume_final_m3)}};
  };
  return Json{{"time_s", c.time},
              {"samples", c.samples},
              {"outside_b", c.outside_b},
              {"outside_a", c.outside_a},
              {"max_difference_m", c.max_difference_m},
              {"max_difference_at_m",
               {c.max_difference_at.x(), c.max_difference_at.y(), c.max_difference_at.z()}},
              {"max_displacement_a_m", c.max_displacement_a_m},
              {"relative_max_difference", c.relative_max()},
              {"relative_l2_difference", c.relative_l2()},
              {"wall_time_ratio_b_over_a",
               c.a.wall_seconds > 0.0 ? Json(c.b.wall_seconds / c.a.wall_seconds) : Json(nullptr)},
              {"a", side(c.a)},
              {"b", side(c.b)}};
}

}  // namespace isomuscle::io
