// Point inversion H(xi) = x on a NURBS solid (thesis 5.13) by a bound-constrained Newton /
// Levenberg–Marquardt iteration (Marquardt 1963, diagonal scaling) started from the nearest
// sample of a parametric grid.
#include "geometry/point_inversion.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace isomuscle::geometry {

namespace {

// Parameters of the start grid in one direction: per_span points at the centres of equal
// sub-intervals of every knot span, or cap evenly spaced points if that would be more.
std::vector<double> sample_parameters(const KnotVector& kv, int per_span, int cap) {
  const std::vector<double> bp = kv.breakpoints();
  const int spans = static_cast<int>(bp.size()) - 1;
  std::vector<double> out;
  if (spans * per_span <= cap) {
    for (int s = 0; s < spans; ++s) {
      for (int k = 0; k < per_span; ++k) {
        out.push_back(bp[static_cast<std::size_t>(s)] +
                      (bp[static_cast<std::size_t>(s + 1)] - bp[static_cast<std::size_t>(s)]) *
                          (k + 0.5) / per_span);
      }
    }
  } else {
    for (int k = 0; k < cap; ++k) {
      out.push_back(kv.domain_begin() + (kv.domain_end() - kv.domain_begin()) * (k + 0.5) / cap);
    }
  }
  return out;
}

// Step for the residual r with Jacobian J (NURBS Book 6.1 for the Newton step; Marquardt for the
// damped one): lambda = 0 and no fixed component gives the Newton step -J^{-1} r when J is
// regular; otherwise (J^T J + lambda D) s = -J^T r with D = diag(J^T J) (floored), restricted to
// the free components. Returns false when no finite step exists.
bool compute_step(const Eigen::Matrix3d& J, const Eigen::Vector3d& r, const bool fixed[3],
                  double lambda, Eigen::Vector3d& step) {
  const bool all_free = !fixed[0] && !fixed[1] && !fixed[2];
  if (lambda == 0.0 && all_free) {
    const double det = J.determinant();
    const double scale = J.col(0).norm() * J.col(1).norm() * J.col(2).norm();
    if (std::abs(det) > 1e-13 * scale) {
      step.noalias() = -(J.inverse() * r);
      return step.allFinite();
    }
    return false;
  }
  Eigen::Matrix3d A;
  A.noalias() = J.transpose() * J;
  Eigen::Vector3d b;
  b.noalias() = -(J.transpose() * r);
  const double floor = 1e-12 * std::max(A.trace(), 1e-300);
  for (int d = 0; d < 3; ++d) {
    A(d, d) += lambda * std::max(A(d, d), floor);
  }
  for (int d = 0; d < 3; ++d) {
    if (fixed[d]) {
      A.row(d).setZero();
      A.col(d).setZero();
      A(d, d) = 1.0;
      b[d] = 0.0;
    }
  }
  step = A.ldlt().solve(b);
  return step.allFinite();
}

// A clamped direction d is a seam when the faces xi_d = begin and xi_d = end coincide with the same
// parametrisation: equal control points (within 1e-10 size) and proportional weights.
bool is_closed_seam(const NurbsVolume& vol, int d, double size) {
  if (!vol.knots(d).is_clamped()) {
    return false;
  }
  const int a = (d + 1) % 3;
  const int b = (d + 2) % 3;
  double ratio = 0.0;
  for (int j = 0; j < vol.count(b); ++j) {
    for (int i = 0; i < vol.count(a); ++i) {
      std::array<int, 3> first{};
      first[a] = i;
      first[b] = j;
      std::array<int, 3> last = first;
      last[d] = vol.count(d) - 1;
      const auto k0 = static_cast<std::size_t>(vol.index(first[0], first[1], first[2]));
      const auto k1 = static_cast<std::size_t>(vol.index(last[0], last[1], last[2]));
      if ((vol.points()[k0] - vol.points()[k1]).norm() > 1e-10 * size) {
        return false;
      }
      const double r = vol.weights()[k1] / vol.weights()[k0];
      if (i == 0 && j == 0) {
        ratio = r;
      } else if (std::abs(r - ratio) > 1e-10 * ratio) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

void InversionOptions::validate() const {
  auto fail = [](const std::string& field, const std::string& range) {
    throw std::invalid_argument("InversionOptions: " + field + " must be " + range);
  };
  if (samples_per_span < 1) {
    fail("samples_per_span", ">= 1");
  }
  if (max_samples_per_direction < 1) {
    fail("max_samples_per_direction", ">= 1");
  }
  if (max_iterations < 1) {
    fail("max_iterations", ">= 1");
  }
  if (max_starts < 1) {
    fail("max_starts", ">= 1");
  }
  if (!(tolerance > 0.0 && std::isfinite(tolerance))) {
    fail("tolerance", "finite and > 0");
  }
  if (!(inside_tolerance > 0.0 && std::isfinite(inside_tolerance))) {
    fail("inside_tolerance", "finite and > 0");
  }
}

PointInverter::PointInverter(const NurbsVolume& volume, InversionOptions options)
    : volume_(volume), options_(options) {
  options_.validate();
  if (volume_.num_control_points() <= 0 || volume_.points().empty()) {
    throw std::invalid_argument("PointInverter: the volume has no control points");
  }
  for (int d = 0; d < 3; ++d) {
    lo_[d] = volume_.domain(d)[0];
    hi_[d] = volume_.domain(d)[1];
  }
  std::tie(box_lo_, box_hi_) = volume_.bounding_box();
  size_ = (box_hi_ - box_lo_).norm();
  if (!(size_ > 0.0)) {
    throw std::invalid_argument("PointInverter: all control points coincide (zero size)");
  }
  for (int d = 0; d < 3; ++d) {
    closed_[d] = is_closed_seam(volume_, d, size_);
  }
  std::array<std::vector<double>, 3> params;
  for (int d = 0; d < 3; ++d) {
    params[d] = sample_parameters(volume_.knots(d), options_.samples_per_span,
                                  options_.max_samples_per_direction);
  }
  for (int d = 0; d < 3; ++d) {
    scan_[d] = params[d];
    for (int k = 0; k < 16; ++k) {
      scan_[d].push_back(lo_[d] + (hi_[d] - lo_[d]) * (k + 0.5) / 16.0);
    }
  }
  for (double w : params[2]) {
    for (double v : params[1]) {
      for (double u : params[0]) {
        sample_xi_.emplace_back(u, v, w);
        sample_x_.push_back(volume_.evaluate(sample_xi_.back()));
      }
    }
  }
}

// Minimises |H(xi) - x| over the parametric box from one start: accepted steps decrease the
// residual strictly; components at a bound whose gradient component J^T r points outward are held
// fixed (active set); lambda grows tenfold after a rejected trial and shrinks after an accepted
// one. Stops at |r| <= tolerance * size, or when no trial decreases |r| (a stationary point, e.g.
// the closest boundary point of an outside x). Length units of the control points.
InversionResult PointInverter::solve_from(const Eigen::Vector3d& x, Eigen::Vector3d xi) const {
  const double tol = options_.tolerance * size_;
  Eigen::Vector3d p;
  Eigen::Matrix3d J;
  volume_.evaluate_with_jacobian(xi, p, J);
  Eigen::Vector3d r = p - x;
  double f = r.norm();
  double lambda = 0.0;
  int it = 0;
  while (it < options_.max_iterations && f > tol) {
    ++it;
    Eigen::Vector3d g;
    g.noalias() = J.transpose() * r;
    bool fixed[3];
    for (int d = 0; d < 3; ++d) {
      fixed[d] =
          !closed_[d] && ((xi[d] <= lo_[d] && g[d] > 0.0) || (xi[d] >= hi_[d] && g[d] < 0.0));
    }
    bool accepted = false;
    for (int attempt = 0; attempt < 20 && !accepted; ++attempt) {
      Eigen::Vector3d step;
      if (compute_step(J, r, fixed, lambda, step)) {
        for (int d = 0; d < 3; ++d) {  // never jump further than the domain length
          step[d] = std::clamp(step[d], lo_[d] - hi_[d], hi_[d] - lo_[d]);
        }
        Eigen::Vector3d trial = xi + step;
        for (int d = 0; d < 3; ++d) {  // across a seam, or projected onto the domain
          const double period = hi_[d] - lo_[d];
          if (closed_[d]) {
            trial[d] += trial[d] < lo_[d] ? period : (trial[d] > hi_[d] ? -period : 0.0);
          }
          trial[d] = std::clamp(trial[d], lo_[d], hi_[d]);
        }
        if (trial == xi) {
          break;  // the projected step does not move: stationary on the boundary
        }
        Eigen::Vector3d pt;
        Eigen::Matrix3d Jt;
        volume_.evaluate_with_jacobian(trial, pt, Jt);
        const Eigen::Vector3d rt = pt - x;
        const double ft = rt.norm();
        if (ft < f) {
          xi = trial;
          J = Jt;
          r = rt;
          f = ft;
          lambda = lambda < 1e-6 ? 0.0 : 0.1 * lambda;
          accepted = true;
          continue;
        }
      }
      lambda = lambda == 0.0 ? 1e-6 : 10.0 * lambda;
    }
    if (!accepted) {
      break;
    }
  }
  InversionResult out;
  out.xi = xi;
  out.distance = f;
  out.iterations = it;
  out.inside = f <= options_.inside_tolerance * size_;
  return out;
}

// Nearest samples first; a point farther than the inside tolerance from the control-point box
// (which contains the solid, convex hull property) gets one start only, for its distance.
InversionResult PointInverter::invert(const Eigen::Vector3d& x) const {
  if (!x.allFinite()) {
    throw std::invalid_argument("PointInverter::invert: the point is not finite");
  }
  const int starts = std::min<int>(options_.max_starts, static_cast<int>(sample_x_.size()));
  std::vector<std::pair<double, int>> nearest;  // (squared distance, sample), ascending
  nearest.reserve(static_cast<std::size_t>(starts) + 1);
  for (std::size_t s = 0; s < sample_x_.size(); ++s) {
    const double d2 = (sample_x_[s] - x).squaredNorm();
    if (static_cast<int>(nearest.size()) < starts || d2 < nearest.back().first) {
      auto pos = std::upper_bound(nearest.begin(), nearest.end(), std::make_pair(d2, -1),
                                  [](const auto& a, const auto& b) { return a.first < b.first; });
      nearest.insert(pos, {d2, static_cast<int>(s)});
      if (static_cast<int>(nearest.size()) > starts) {
        nearest.pop_back();
      }
    }
  }
  const Eigen::Vector3d outside_box = (box_lo_ - x).cwiseMax(0.0) + (x - box_hi_).cwiseMax(0.0);
  const bool far = outside_box.norm() > options_.inside_tolerance * size_;
  InversionResult best;
  best.distance = std::numeric_limits<double>::infinity();
  int total = 0;
  Eigen::Vector3d restart;
  // A start "converges" at 1000 x tolerance; until then further starts are tried even when the
  // point already counts as inside (e.g. stuck on a seam or axis within the inside tolerance).
  const double converged = 1e3 * options_.tolerance * size_;
  for (int s = 0; s < (far ? 1 : starts) && best.distance > converged; ++s) {
    InversionResult res = solve_from(
        x, sample_xi_[static_cast<std::size_t>(nearest[static_cast<std::size_t>(s)].second)]);
    total += res.iterations;
    if (res.distance > converged && !far && collapsed_face_restart(x, res.xi, restart)) {
      const InversionResult again = solve_from(x, restart);
      total += again.iterations;
      if (again.distance < res.distance) {
        res = again;
      }
    }
    if (res.distance < best.distance) {
      best = res;
    }
  }
  best.iterations = total;
  return best;
}

// A start can end on a collapsed face (a boundary face xi_d = bound on which the tangent of another
// direction c vanishes, e.g. the centreline face w = 1 of a shrink solid, thesis 5.13–5.15) on the
// wrong side of the axis: there xi_c has no first-order effect and no descent step exists. The
// restart moves 1 % of the domain off the face and picks xi_c by a scan of the residual.
bool PointInverter::collapsed_face_restart(const Eigen::Vector3d& x, const Eigen::Vector3d& xi,
                                           Eigen::Vector3d& start) const {
  const Eigen::Matrix3d J = volume_.jacobian(xi);
  bool found = false;
  start = xi;
  for (int d = 0; d < 3; ++d) {
    const bool at_lo = xi[d] <= lo_[d];
    const bool at_hi = xi[d] >= hi_[d];
    if (closed_[d] || (!at_lo && !at_hi)) {
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      if (c == d || J.col(c).norm() * (hi_[c] - lo_[c]) > 1e-8 * size_) {
        continue;
      }
      const double offset = 0.01 * (hi_[d] - lo_[d]);
      start[d] = at_lo ? lo_[d] + offset : hi_[d] - offset;
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d y = start;
      for (double t : scan_[c]) {
        y[c] = t;
        const double f = (volume_.evaluate(y) - x).norm();
        if (f < best) {
          best = f;
          start[c] = t;
        }
      }
      found = true;
    }
  }
  return found;
}

InversionResult invert_point(const NurbsVolume& volume, const Eigen::Vector3d& x,
                             const InversionOptions& options) {
  return PointInverter(volume, options).invert(x);
}

}  // namespace isomuscle::geometry
