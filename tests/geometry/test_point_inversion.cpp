// Point inversion H(xi) = x (thesis 5.13, needed for fibre sampling 5.27–5.30): a distorted
// rational solid and a solid cylinder whose w = 1 face is collapsed onto the axis (det J -> 0
// linearly), points near and on the axis, points just outside and far away. Accuracy is measured
// physically, |H(xi) - x| <= 1e-10 size (size = control-point bounding-box diagonal), and where the
// parameters are determined also parametrically, |xi - xi_true| <= 1e-10 (domains of length 1).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_volume.hpp"
#include "geometry/point_inversion.hpp"
#include "geometry/refinement.hpp"

namespace isomuscle::geometry {
namespace {

const double kS = std::sqrt(0.5);
constexpr double kTol = 1e-10;

double uniform(std::mt19937& rng, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(rng);
}

// Thick shell sector (r in [1, 2] along u, quarter circle along v, z in [0, 1.5] along w), raised
// to degree 2 and refined, then every control point moved by up to 0.04 and weights drawn from
// [0.7, 1.4]: a genuinely rational, curved, non-symmetric solid.
NurbsVolume distorted_volume() {
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  const double wv[3] = {1.0, kS, 1.0};
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 2; ++i) {
        const double r = i == 0 ? 1.0 : 2.0;
        const Eigen::Vector3d arc[3] = {{r, 0, 0}, {r, r, 0}, {0, r, 0}};
        pts.push_back(arc[j] + Eigen::Vector3d(0, 0, 1.5 * k));
        w.push_back(wv[j]);
      }
    }
  }
  const NurbsVolume base(
      {KnotVector::clamped(1, {}), KnotVector::clamped(2, {}), KnotVector::clamped(1, {})}, pts, w);
  const NurbsVolume fine = refine_uniform(elevate_to(base, {2, 2, 2}), {2, 2, 1});
  std::mt19937 rng(31);
  std::vector<Eigen::Vector3d> p2 = fine.points();
  std::vector<double> w2 = fine.weights();
  for (std::size_t a = 0; a < p2.size(); ++a) {
    p2[a] += 0.04 * Eigen::Vector3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    w2[a] *= uniform(rng, 0.7, 1.4);
  }
  return NurbsVolume(fine.all_knots(), p2, w2);
}

// Solid cylinder of radius 1, z in [0, 2]: u = angle (rational full circle), v = height, w from the
// lateral surface (w = 0) to the axis (w = 1, a collapsed face), built with w-degree 1 (the
// shrinking construction of thesis 5.13–5.15 with the exact centre) and elevated to 2, refined
// once. H(u, v, w) = (1 - w) C(u) + (0, 0, 2v) exactly, so det J is proportional to 1 - w.
NurbsVolume collapsed_cylinder() {
  const std::vector<Eigen::Vector3d> circle = {{1, 0, 0},  {1, 1, 0},  {0, 1, 0},
                                               {-1, 1, 0}, {-1, 0, 0}, {-1, -1, 0},
                                               {0, -1, 0}, {1, -1, 0}, {1, 0, 0}};
  const double cw[9] = {1, kS, 1, kS, 1, kS, 1, kS, 1};
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 9; ++i) {
        const Eigen::Vector3d axis(0, 0, 2.0 * j);
        pts.push_back(k == 0 ? Eigen::Vector3d(circle[static_cast<std::size_t>(i)] + axis) : axis);
        w.push_back(cw[i]);
      }
    }
  }
  const NurbsVolume v1({KnotVector::clamped(2, {0.25, 0.25, 0.5, 0.5, 0.75, 0.75}),
                        KnotVector::clamped(1, {}), KnotVector::clamped(1, {})},
                       pts, w);
  return refine_uniform(elevate_degree(v1, 2, 1), 2, 1);
}

// Quarter of a solid torus (centreline radius 3, tube radius 1) with the w = 1 face collapsed onto
// the curved centreline: u = tube angle (rational full circle), v = quarter of the centreline
// (rational arc), w from the torus surface to the centreline, degree 1 elevated to 2. With the
// centreline poles weighted like the surface poles, H = (1 - w) S(u, v) + w C(v) exactly.
NurbsVolume collapsed_torus_quarter() {
  const double X[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
  const double Y[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  const double a[9] = {1, kS, 1, kS, 1, kS, 1, kS, 1};
  const double cx[3] = {1, 1, 0};
  const double cy[3] = {0, 1, 1};
  const double b[3] = {1, kS, 1};
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 9; ++i) {
        const double rho = k == 0 ? 3.0 + X[i] : 3.0;
        const double z = k == 0 ? Y[i] : 0.0;
        pts.emplace_back(rho * cx[j], rho * cy[j], z);
        w.push_back(a[i] * b[j]);
      }
    }
  }
  const NurbsVolume v1({KnotVector::clamped(2, {0.25, 0.25, 0.5, 0.5, 0.75, 0.75}),
                        KnotVector::clamped(2, {}), KnotVector::clamped(1, {})},
                       pts, w);
  return elevate_degree(v1, 2, 1);
}

// Distance from the centreline circle (radius 3 in the xy-plane) of a point of the torus quarter.
double tube_radius(const Eigen::Vector3d& x) {
  return std::hypot(x.head<2>().norm() - 3.0, x.z());
}

Eigen::Vector3d random_xi(std::mt19937& rng) {
  return {uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1)};
}

// Periodic distance in u for the closed cylinder (u = 0 and u = 1 are the same seam).
double seam_distance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 1.0 - d);
}

TEST(PointInversion, DistortedRationalVolumeInterior) {
  const NurbsVolume vol = distorted_volume();
  const PointInverter inv(vol);
  EXPECT_FALSE(inv.closed(0) || inv.closed(1) || inv.closed(2));
  std::mt19937 rng(1);
  // A valid solid: det J > 0 on a grid.
  for (int n = 0; n < 500; ++n) {
    ASSERT_GT(vol.jacobian(random_xi(rng)).determinant(), 0.0);
  }
  std::vector<Eigen::Vector3d> targets;
  for (int n = 0; n < 500; ++n) {
    targets.push_back(random_xi(rng));
  }
  // Faces, edges and corners of the parametric box are inside too.
  for (int n = 0; n < 60; ++n) {
    Eigen::Vector3d xi = random_xi(rng);
    for (int d = 0; d < 3; ++d) {
      if ((n >> d) & 1) {
        xi[d] = (n / 8) % 2 == 0 ? 0.0 : 1.0;
      }
    }
    targets.push_back(xi);
  }
  double worst_x = 0.0;
  double worst_xi = 0.0;
  int iterations = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (const Eigen::Vector3d& xi_true : targets) {
    const Eigen::Vector3d x = vol.evaluate(xi_true);
    const InversionResult res = inv.invert(x);
    ASSERT_TRUE(res.inside) << "xi_true = " << xi_true.transpose() << ", distance " << res.distance;
    EXPECT_LE((vol.evaluate(res.xi) - x).norm(), kTol * inv.size());
    EXPECT_NEAR(res.distance, (vol.evaluate(res.xi) - x).norm(), 1e-15 * inv.size());
    EXPECT_LE((res.xi - xi_true).cwiseAbs().maxCoeff(), kTol) << xi_true.transpose();
    worst_x = std::max(worst_x, res.distance / inv.size());
    worst_xi = std::max(worst_xi, (res.xi - xi_true).cwiseAbs().maxCoeff());
    iterations += res.iterations;
  }
  const double us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
      static_cast<double>(targets.size());
  std::printf(
      "[ measured ] distorted volume: max |H(xi)-x|/size %.2e, max |xi - xi_true| %.2e, "
      "%.1f iterations and %.1f us per point\n",
      worst_x, worst_xi, static_cast<double>(iterations) / targets.size(), us);
}

// Collapsed faces: the solid cylinder (straight axis) and the torus quarter (curved centreline).
// Random interior points, points 1e-6 (relative to the tube radius) from the axis, points on it.
void check_collapsed(const NurbsVolume& vol, const char* name) {
  const PointInverter inv(vol);
  EXPECT_TRUE(inv.closed(0));  // the seam u = 0 = 1 is found geometrically
  EXPECT_FALSE(inv.closed(1));
  EXPECT_FALSE(inv.closed(2));
  std::mt19937 rng(2);
  struct Case {
    Eigen::Vector3d xi;
    bool u_determined;
  };
  std::vector<Case> cases;
  for (int n = 0; n < 300; ++n) {
    cases.push_back({random_xi(rng), false});
  }
  for (int n = 0; n < 100; ++n) {
    cases.push_back({{uniform(rng, 0, 1), uniform(rng, 0, 1), 1.0 - 1e-6}, false});
  }
  for (int n = 0; n < 40; ++n) {  // within 1e-9 of the seam u = 0 = 1, from both sides
    const double u = n % 2 == 0 ? 1e-9 * uniform(rng, 0, 1) : 1.0 - 1e-9 * uniform(rng, 0, 1);
    cases.push_back({{u, uniform(rng, 0, 1), uniform(rng, 0, 1)}, false});
  }
  for (int n = 0; n < 40; ++n) {  // on the axis and on the outer surface
    cases.push_back({{uniform(rng, 0, 1), uniform(rng, 0, 1), n % 2 == 0 ? 1.0 : 0.0}, false});
  }
  for (Case& c : cases) {
    c.u_determined = c.xi[2] <= 0.99;
  }
  double worst_x = 0.0;
  double worst_vw = 0.0;
  double worst_u = 0.0;
  int iterations = 0;
  for (const Case& c : cases) {
    const Eigen::Vector3d x = vol.evaluate(c.xi);
    const InversionResult res = inv.invert(x);
    ASSERT_TRUE(res.inside) << name << ": xi_true = " << c.xi.transpose() << ", distance "
                            << res.distance;
    ASSERT_TRUE(res.xi.allFinite());
    EXPECT_LE((vol.evaluate(res.xi) - x).norm(), kTol * inv.size()) << name << c.xi.transpose();
    const double vw = std::max(std::abs(res.xi[1] - c.xi[1]), std::abs(res.xi[2] - c.xi[2]));
    EXPECT_LE(vw, kTol) << name << c.xi.transpose();
    if (c.u_determined) {
      EXPECT_LE(seam_distance(res.xi[0], c.xi[0]), kTol) << name << c.xi.transpose();
      worst_u = std::max(worst_u, seam_distance(res.xi[0], c.xi[0]));
    }
    worst_x = std::max(worst_x, res.distance / inv.size());
    worst_vw = std::max(worst_vw, vw);
    iterations += res.iterations;
  }
  std::printf(
      "[ measured ] %s: max |H(xi)-x|/size %.2e, max |dv|,|dw| %.2e, "
      "max |du| (w <= 0.99) %.2e, %.1f iterations per point\n",
      name, worst_x, worst_vw, worst_u, static_cast<double>(iterations) / cases.size());
}

TEST(PointInversion, CollapsedFaceCylinderIncludingTheAxis) {
  const NurbsVolume vol = collapsed_cylinder();
  std::mt19937 rng(2);
  // The construction is exact: radius 1 - w.
  for (int n = 0; n < 200; ++n) {
    const Eigen::Vector3d xi = random_xi(rng);
    const Eigen::Vector3d x = vol.evaluate(xi);
    ASSERT_NEAR(x.head<2>().norm(), 1.0 - xi[2], 1e-14);
    ASSERT_NEAR(x.z(), 2.0 * xi[1], 1e-14);
  }
  check_collapsed(vol, "collapsed cylinder");
}

TEST(PointInversion, CollapsedFaceTorusIncludingTheCentreline) {
  const NurbsVolume vol = collapsed_torus_quarter();
  std::mt19937 rng(3);
  for (int n = 0; n < 200; ++n) {  // exact: tube radius 1 - w
    const Eigen::Vector3d xi = random_xi(rng);
    ASSERT_NEAR(tube_radius(vol.evaluate(xi)), 1.0 - xi[2], 1e-14);
  }
  check_collapsed(vol, "collapsed torus quarter");
}

// Exact distance from x to the solid cylinder rho <= 1, 0 <= z <= 2.
double cylinder_distance(const Eigen::Vector3d& x) {
  const double dr = std::max(x.head<2>().norm() - 1.0, 0.0);
  const double dz = std::max({x.z() - 2.0, -x.z(), 0.0});
  return std::hypot(dr, dz);
}

TEST(PointInversion, OutsideTheCollapsedCylinder) {
  const NurbsVolume vol = collapsed_cylinder();
  const PointInverter inv(vol);
  const double delta = 1e-6 * inv.size();
  std::mt19937 rng(3);
  double worst_rel = 0.0;
  for (int n = 0; n < 160; ++n) {
    const double a = uniform(rng, 0, 2 * M_PI);
    const Eigen::Vector2d e(std::cos(a), std::sin(a));
    Eigen::Vector3d x;
    switch (n % 4) {
      case 0:  // just outside the lateral surface
        x << (1.0 + delta) * e, uniform(rng, 0, 2);
        break;
      case 1:  // just above the top
        x << uniform(rng, 0, 1) * e, 2.0 + delta;
        break;
      case 2:  // just beyond the bottom edge
        x << (1.0 + delta * kS) * e, -delta * kS;
        break;
      default:  // just below the bottom, next to the axis
        x << 1e-7 * e, -delta;
        break;
    }
    const InversionResult res = inv.invert(x);
    EXPECT_FALSE(res.inside) << x.transpose();
    EXPECT_GE(res.distance, cylinder_distance(x) * (1.0 - 1e-9));
    EXPECT_NEAR(res.distance, cylinder_distance(x), 1e-3 * delta) << "case " << n % 4;
    worst_rel = std::max(worst_rel, std::abs(res.distance - cylinder_distance(x)) / delta);
    // The same points pulled inside by delta are inside.
    const Eigen::Vector3d y =
        n % 4 == 0   ? Eigen::Vector3d((1.0 - delta) * e.x(), (1.0 - delta) * e.y(), x.z())
        : n % 4 == 1 ? Eigen::Vector3d(x.x(), x.y(), 2.0 - delta)
                     : Eigen::Vector3d(x.x() * (1 - 4e-6), x.y() * (1 - 4e-6), delta);
    EXPECT_TRUE(inv.invert(y).inside) << y.transpose();
  }
  for (int n = 0; n < 40; ++n) {  // far away
    const Eigen::Vector3d dir = Eigen::Vector3d::Random().normalized();
    const Eigen::Vector3d x = Eigen::Vector3d(0, 0, 1) + 10.0 * inv.size() * dir;
    const InversionResult res = inv.invert(x);
    EXPECT_FALSE(res.inside);
    EXPECT_GE(res.distance, cylinder_distance(x) * (1.0 - 1e-12));
    EXPECT_TRUE(res.xi.allFinite());
  }
  std::printf(
      "[ measured ] just outside (delta = 1e-6 size): max |distance - exact| / delta %.2e\n",
      worst_rel);
}

// Just outside the distorted solid: a boundary point moved by delta along the outward normal of
// its face has distance delta (to O(delta^2 curvature)).
TEST(PointInversion, OutsideTheDistortedVolume) {
  const NurbsVolume vol = distorted_volume();
  const PointInverter inv(vol);
  const double delta = 1e-6 * inv.size();
  std::mt19937 rng(4);
  for (int n = 0; n < 120; ++n) {
    const int dir = n % 3;
    const bool upper = (n / 3) % 2 == 1;
    Eigen::Vector3d xi(uniform(rng, 0.05, 0.95), uniform(rng, 0.05, 0.95),
                       uniform(rng, 0.05, 0.95));
    xi[dir] = upper ? 1.0 : 0.0;
    Eigen::Vector3d p;
    Eigen::Matrix3d J;
    vol.evaluate_with_jacobian(xi, p, J);
    Eigen::Vector3d normal = J.col((dir + 1) % 3).cross(J.col((dir + 2) % 3)).normalized();
    if ((normal.dot(J.col(dir)) > 0.0) != upper) {
      normal = -normal;
    }
    const InversionResult out = inv.invert(p + delta * normal);
    EXPECT_FALSE(out.inside);
    EXPECT_NEAR(out.distance, delta, 1e-3 * delta);
    const InversionResult in = inv.invert(p - delta * normal);
    EXPECT_TRUE(in.inside);
    EXPECT_LE(in.distance, kTol * inv.size());
  }
  const InversionResult far = inv.invert(Eigen::Vector3d(50, -40, 30));
  EXPECT_FALSE(far.inside);
  EXPECT_GT(far.distance, 40.0);
}

TEST(PointInversion, RejectsBadInput) {
  const NurbsVolume vol = collapsed_cylinder();
  InversionOptions bad;
  bad.max_starts = 0;
  EXPECT_THROW(PointInverter(vol, bad), std::invalid_argument);
  bad = InversionOptions();
  bad.tolerance = -1.0;
  EXPECT_THROW(PointInverter(vol, bad), std::invalid_argument);
  bad = InversionOptions();
  bad.inside_tolerance = std::nan("");
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  EXPECT_THROW(PointInverter(vol).invert(Eigen::Vector3d(0, std::nan(""), 0)),
               std::invalid_argument);
  EXPECT_TRUE(invert_point(vol, Eigen::Vector3d(0.1, 0.2, 0.3)).inside);
}

}  // namespace
}  // namespace isomuscle::geometry
