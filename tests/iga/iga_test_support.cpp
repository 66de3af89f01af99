#include "iga_test_support.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <stdexcept>

#include "geometry/refinement.hpp"
#include "geometry/shapes.hpp"
#include "geometry/shrink.hpp"

namespace isomuscle::iga::testing {

using geometry::KnotVector;
using geometry::NurbsVolume;

namespace {

NurbsVolume refine_to(const NurbsVolume& v, const std::array<int, 3>& degree,
                      const std::array<int, 3>& elements) {
  NurbsVolume out = geometry::elevate_to(v, degree);
  for (int d = 0; d < 3; ++d) {
    std::vector<double> knots;
    for (int i = 1; i < elements[d]; ++i) {
      knots.push_back(static_cast<double>(i) / elements[d]);
    }
    if (!knots.empty()) {
      out = geometry::refine_knots(out, d, knots);
    }
  }
  return out;
}

NurbsVolume trilinear(const std::array<Eigen::Vector3d, 8>& corners) {
  std::array<KnotVector, 3> kv = {KnotVector::clamped(1, {}), KnotVector::clamped(1, {}),
                                  KnotVector::clamped(1, {})};
  std::vector<Eigen::Vector3d> pts(corners.begin(), corners.end());
  return NurbsVolume(kv, pts, std::vector<double>(8, 1.0));
}

}  // namespace

NurbsVolume box(const Eigen::Vector3d& size, const std::array<int, 3>& degree,
                const std::array<int, 3>& elements) {
  std::array<Eigen::Vector3d, 8> c;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) {
        c[i + 2 * (j + 2 * k)] = Eigen::Vector3d(i * size[0], j * size[1], k * size[2]);
      }
    }
  }
  return refine_to(trilinear(c), degree, elements);
}

NurbsVolume distorted_rational_block(int p, int n, double amplitude, unsigned seed, bool rational) {
  const NurbsVolume cube = box(Eigen::Vector3d(1, 1, 1), {p, p, p}, {n, n, n});
  std::vector<Eigen::Vector3d> pts = cube.points();
  double spacing = 1.0;
  for (int i = 0; i + 1 < cube.count(0); ++i) {
    spacing = std::min(spacing, (pts[cube.index(i + 1, 0, 0)] - pts[cube.index(i, 0, 0)]).norm());
  }
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> wdist(0.7, 1.3);
  std::vector<double> w(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    Eigen::Vector3d d(unit(gen), unit(gen), unit(gen));
    if (d.norm() > 1.0) {
      d.normalize();
    }
    pts[i] += amplitude * spacing * d;
    const double wi = wdist(gen);
    w[i] = rational ? wi : 1.0;
  }
  return NurbsVolume(cube.all_knots(), pts, w);
}

NurbsVolume shrink_cylinder(double radius, double height, int p,
                            const std::array<int, 3>& n_per_span) {
  const geometry::NurbsSurface s = geometry::cone_frustum(radius, radius, height);
  NurbsVolume v = geometry::shrink_to_centreline(s, 0);
  v = geometry::elevate_to(v, {p, p, p});
  return geometry::refine_uniform(v, n_per_span);
}

NurbsVolume polynomial_shrink_cylinder(double radius, double height, int p,
                                       const std::array<int, 3>& n_per_span) {
  geometry::PlanarCurve octagon;
  octagon.knots = KnotVector::uniform_clamped(2, 7);
  for (int i = 0; i <= 8; ++i) {
    const double a = 2.0 * std::numbers::pi * (i % 8) / 8.0;
    octagon.points.emplace_back(std::cos(a), std::sin(a));
    octagon.weights.push_back(1.0);
  }
  geometry::PlanarCurve profile;
  profile.knots = KnotVector::clamped(1, {});
  profile.points = {{radius, 0.0}, {radius, height}};
  profile.weights = {1.0, 1.0};
  NurbsVolume v = geometry::shrink_to_centreline(geometry::revolve(profile, octagon), 0);
  v = geometry::elevate_to(v, {p, p, p});
  return geometry::refine_uniform(v, n_per_span);
}

NurbsVolume shrink_barrel(int p, const std::array<int, 3>& n_per_span) {
  const geometry::NurbsSurface s =
      geometry::barrel(geometry::kBarrelLength, 0.5 * geometry::kBarrelEndDiameter,
                       0.5 * geometry::kBarrelMiddleDiameter);
  NurbsVolume v = geometry::shrink_to_centreline(s, 0);
  v = geometry::elevate_to(v, {p, p, p});
  return geometry::refine_uniform(v, n_per_span);
}

NurbsVolume annular_sector(double r0, double r1, double h, double angle, int p, int n, int nz) {
  // u radial (degree 1), v the 90-degree arc (rational quadratic), w along z (degree 1).
  std::array<KnotVector, 3> kv = {KnotVector::clamped(1, {}), KnotVector::clamped(2, {}),
                                  KnotVector::clamped(1, {})};
  if (!(angle > 0.0 && angle <= 0.5 * std::numbers::pi)) {
    throw std::invalid_argument("annular_sector: angle must be in (0, pi/2]");
  }
  const double half = 0.5 * angle;
  const std::array<Eigen::Vector2d, 3> arc = {Eigen::Vector2d(1, 0),
                                              Eigen::Vector2d(1, std::tan(half)),
                                              Eigen::Vector2d(std::cos(angle), std::sin(angle))};
  const std::array<double, 3> aw = {1.0, std::cos(half), 1.0};
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 2; ++i) {
        const double r = i == 0 ? r0 : r1;
        pts.emplace_back(r * arc[j].x(), r * arc[j].y(), k * h);
        w.push_back(aw[j]);
      }
    }
  }
  const NurbsVolume v(kv, pts, w);
  return refine_to(v, {p, std::max(p, 2), p}, {n, n, nz});
}

NurbsVolume cook_membrane(int p, int nu, int nv, int nw, double thickness) {
  const Eigen::Vector2d A(0, 0), B(48, 44), C(48, 60), D(0, 44);
  std::array<Eigen::Vector3d, 8> c;
  for (int k = 0; k < 2; ++k) {
    const double z = k * thickness;
    c[0 + 4 * k] = Eigen::Vector3d(A.x(), A.y(), z);
    c[1 + 4 * k] = Eigen::Vector3d(B.x(), B.y(), z);
    c[2 + 4 * k] = Eigen::Vector3d(D.x(), D.y(), z);
    c[3 + 4 * k] = Eigen::Vector3d(C.x(), C.y(), z);
  }
  return refine_to(trilinear(c), {p, p, p}, {nu, nv, nw});
}

solver::NewtonSettings tight_newton(double rtol) {
  solver::NewtonSettings s;
  s.max_iterations = 30;
  s.relative_residual_tolerance = rtol;
  s.relative_energy_tolerance = rtol;
  // Floors at round-off for problems of unit size and stiffness (the verification set-ups).
  s.absolute_residual_tolerance = 1e-13;
  s.absolute_energy_tolerance = 1e-26;
  // Round-off acceptance (NewtonSettings::correction_tolerance): with tiny moduli the residual's
  // round-off floor can sit above the energy floor (measured: |r| stagnating at 7.5e-15 on the
  // rational shrink cylinder, p = 3, mixed, 7 points), and the solve must not fail there.
  s.correction_tolerance = 1e-12;
  return s;
}

bool solve_steps(solver::NonlinearProblem& problem, Eigen::VectorXd& u, int steps,
                 const solver::NewtonSettings& settings, std::string* message,
                 std::vector<solver::NewtonResult>* results) {
  solver::NewtonSolver newton(settings);
  if (u.size() != problem.size()) {
    u = Eigen::VectorXd::Zero(problem.size());
  }
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    problem.begin_step(t, 1.0 / steps);
    if (const solver::EvaluationStatus p = problem.predict(u); !p.ok) {
      if (message != nullptr) {
        *message = "step " + std::to_string(k) + ": " + p.message;
      }
      return false;
    }
    const solver::NewtonResult r = newton.solve(problem, u);
    if (results != nullptr) {
      results->push_back(r);
    }
    if (std::getenv("ISOMUSCLE_TEST_VERBOSE") != nullptr) {
      std::printf("step %d: %s\n", k, r.message.c_str());
      for (const auto& it : r.history) {
        std::printf("  it %2d |r| %.3e alpha %.3g halvings %d contraction %.2e order %.2f\n",
                    it.iteration, it.residual_norm, it.step_length, it.line_search_halvings,
                    it.contraction, it.observed_order);
      }
    }
    if (!r.converged) {
      if (message != nullptr) {
        *message = "step " + std::to_string(k) + ": " + r.message;
      }
      return false;
    }
    problem.commit_step(u);
  }
  return true;
}

}  // namespace isomuscle::iga::testing
