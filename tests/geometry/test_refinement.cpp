// Exact refinement (thesis 5.3; The NURBS Book A5.4, A5.9): knot insertion, degree elevation,
// periodic -> clamped conversion, splitting and extraction keep every curve, surface and volume
// within 1e-12 of its size (bounding-box diagonal of the control points) at 1000 random points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "geometry/nurbs_volume.hpp"
#include "geometry/refinement.hpp"

namespace isomuscle::geometry {
namespace {

const double kS = std::sqrt(0.5);
constexpr int kSamples = 1000;
constexpr double kTol = 1e-12;

// Largest relative deviation measured by the current test (printed by the fixture).
double g_worst = 0.0;
double record(double d) {
  g_worst = std::max(g_worst, d);
  return d;
}

class Refinement : public ::testing::Test {
 protected:
  void SetUp() override { g_worst = 0.0; }
  void TearDown() override {
    std::printf("[ measured ] largest deviation / size: %.2e\n", g_worst);
  }
};

template <class Points>
double diagonal(const Points& pts) {
  Eigen::Vector3d lo = pts.front();
  Eigen::Vector3d hi = pts.front();
  for (const Eigen::Vector3d& x : pts) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

NurbsCurve quarter_circle(double r) {
  return NurbsCurve(KnotVector::clamped(2, {}), {{r, 0, 0}, {r, r, 0}, {0, r, 0}}, {1, kS, 1});
}

NurbsCurve full_circle(double r) {
  std::vector<Eigen::Vector3d> pts = {{r, 0, 0},   {r, r, 0},  {0, r, 0},  {-r, r, 0}, {-r, 0, 0},
                                      {-r, -r, 0}, {0, -r, 0}, {r, -r, 0}, {r, 0, 0}};
  return NurbsCurve(KnotVector::clamped(2, {0.25, 0.25, 0.5, 0.5, 0.75, 0.75}), pts,
                    {1, kS, 1, kS, 1, kS, 1, kS, 1});
}

NurbsCurve random_curve(const KnotVector& kv, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> wd(0.4, 2.5);
  std::uniform_real_distribution<double> xd(-1.0, 1.0);
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int i = 0; i < kv.num_basis(); ++i) {
    pts.emplace_back(xd(rng), xd(rng), xd(rng));
    w.push_back(wd(rng));
  }
  return NurbsCurve(kv, pts, w);
}

std::vector<NurbsCurve> test_curves() {
  return {quarter_circle(2.0),
          full_circle(1.0),
          random_curve(KnotVector::clamped(1, {0.3, 0.5, 0.7}), 1),
          random_curve(KnotVector::clamped(2, {0.2, 0.4, 0.4, 0.7}, -1.0, 1.0), 2),
          random_curve(KnotVector::clamped(3, {0.1, 0.5, 0.5, 0.5, 0.6}, 0.0, 2.0), 3),
          random_curve(KnotVector::uniform_clamped(4, 3), 4)};
}

// Thick cylindrical shell sector (r in [r0, r1] along u, quarter circle along v, z along w).
NurbsVolume shell_sector(double r0, double r1, double h) {
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  const double wv[3] = {1.0, kS, 1.0};
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 2; ++i) {
        const double r = i == 0 ? r0 : r1;
        const Eigen::Vector3d arc[3] = {{r, 0, 0}, {r, r, 0}, {0, r, 0}};
        pts.push_back(arc[j] + Eigen::Vector3d(0, 0, k * h));
        w.push_back(wv[j]);
      }
    }
  }
  return NurbsVolume(
      {KnotVector::clamped(1, {}), KnotVector::clamped(2, {}), KnotVector::clamped(1, {})}, pts, w);
}

// Ring (torus-like solid with rectangular section): radius along u, full circle along v, z along w.
NurbsVolume ring(double r0, double r1, double h) {
  const NurbsCurve c = full_circle(1.0);
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < c.count(); ++j) {
      for (int i = 0; i < 2; ++i) {
        pts.push_back(c.point(j) * (i == 0 ? r0 : r1) + Eigen::Vector3d(0, 0, k * h));
        w.push_back(c.weight(j));
      }
    }
  }
  return NurbsVolume({KnotVector::clamped(1, {}), c.knots(), KnotVector::clamped(1, {})}, pts, w);
}

NurbsVolume random_volume(std::array<KnotVector, 3> kv, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> wd(0.5, 2.0);
  std::uniform_real_distribution<double> xd(-0.1, 0.1);
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int k = 0; k < kv[2].num_basis(); ++k) {
    for (int j = 0; j < kv[1].num_basis(); ++j) {
      for (int i = 0; i < kv[0].num_basis(); ++i) {
        pts.emplace_back(i + xd(rng), j + xd(rng), k + xd(rng));
        w.push_back(wd(rng));
      }
    }
  }
  return NurbsVolume(std::move(kv), pts, w);
}

NurbsVolume general_volume() {
  return random_volume(
      {KnotVector::clamped(2, {0.3, 0.3, 0.6}), KnotVector::clamped(1, {0.5}, -1.0, 1.0),
       KnotVector::clamped(3, {0.2, 0.7, 0.7}, 0.0, 2.0)},
      21);
}

double uniform(std::mt19937& rng, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(rng);
}

// max |a(u) - b(u)| / size over kSamples random u in [lo, hi].
double deviation(const NurbsCurve& a, const NurbsCurve& b, double lo, double hi) {
  std::mt19937 rng(99);
  double worst = 0.0;
  for (int s = 0; s < kSamples; ++s) {
    const double u = uniform(rng, lo, hi);
    worst = std::max(worst, (a.evaluate(u) - b.evaluate(u)).norm());
  }
  worst = std::max(worst, (a.evaluate(lo) - b.evaluate(lo)).norm());
  worst = std::max(worst, (a.evaluate(hi) - b.evaluate(hi)).norm());
  return record(worst / diagonal(a.points()));
}
double deviation(const NurbsCurve& a, const NurbsCurve& b) {
  return deviation(a, b, a.domain()[0], a.domain()[1]);
}

double deviation(const NurbsSurface& a, const NurbsSurface& b) {
  std::mt19937 rng(98);
  double worst = 0.0;
  for (int s = 0; s < kSamples; ++s) {
    const double u = uniform(rng, a.knots_u().domain_begin(), a.knots_u().domain_end());
    const double v = uniform(rng, a.knots_v().domain_begin(), a.knots_v().domain_end());
    worst = std::max(worst, (a.evaluate(u, v) - b.evaluate(u, v)).norm());
  }
  return record(worst / diagonal(a.points()));
}

// Over the box lo..hi of parameters (default: a's domain).
double deviation(const NurbsVolume& a, const NurbsVolume& b, Eigen::Vector3d lo,
                 Eigen::Vector3d hi) {
  std::mt19937 rng(97);
  double worst = 0.0;
  for (int s = 0; s < kSamples; ++s) {
    const Eigen::Vector3d xi(uniform(rng, lo[0], hi[0]), uniform(rng, lo[1], hi[1]),
                             uniform(rng, lo[2], hi[2]));
    worst = std::max(worst, (a.evaluate(xi) - b.evaluate(xi)).norm());
  }
  worst = std::max(worst, (a.evaluate(lo) - b.evaluate(lo)).norm());
  worst = std::max(worst, (a.evaluate(hi) - b.evaluate(hi)).norm());
  return record(worst / diagonal(a.points()));
}
double deviation(const NurbsVolume& a, const NurbsVolume& b) {
  const Eigen::Vector3d lo(a.domain(0)[0], a.domain(1)[0], a.domain(2)[0]);
  const Eigen::Vector3d hi(a.domain(0)[1], a.domain(1)[1], a.domain(2)[1]);
  return deviation(a, b, lo, hi);
}

TEST_F(Refinement, CurveKnotInsertion) {
  std::mt19937 rng(1);
  for (const NurbsCurve& c : test_curves()) {
    const auto dom = c.domain();
    const double u = uniform(rng, dom[0], dom[1]);
    const NurbsCurve once = insert_knot(c, u);
    EXPECT_EQ(once.count(), c.count() + 1);
    EXPECT_EQ(once.knots().multiplicity(u), 1);
    EXPECT_LE(deviation(c, once), kTol);
    // Up to full multiplicity p + 1 at a fresh value and at an existing interior knot.
    const NurbsCurve full = insert_knot(c, u, c.degree() + 1);
    EXPECT_EQ(full.knots().multiplicity(u), c.degree() + 1);
    EXPECT_LE(deviation(c, full), kTol);
    const std::vector<double> bp = c.knots().breakpoints();
    if (bp.size() > 2) {
      const double k = bp[1];
      const int room = c.degree() + 1 - c.knots().multiplicity(k);
      if (room > 0) {
        const NurbsCurve at_knot = insert_knot(c, k, room);
        EXPECT_EQ(at_knot.knots().multiplicity(k), c.degree() + 1);
        EXPECT_LE(deviation(c, at_knot), kTol);
      }
    }
    // Many knots at once, unsorted, with repeats.
    std::vector<double> X = {uniform(rng, dom[0], dom[1]), uniform(rng, dom[0], dom[1]),
                             uniform(rng, dom[0], dom[1])};
    X.push_back(X[1]);
    const NurbsCurve many = refine_knots(c, X);
    EXPECT_EQ(many.count(), c.count() + 4);
    EXPECT_LE(deviation(c, many), kTol);
    const NurbsCurve uni = refine_uniform(c, 3);
    EXPECT_EQ(uni.knots().breakpoints().size(), 4 * (bp.size() - 1) + 1);
    EXPECT_LE(deviation(c, uni), kTol);
  }
}

// Degree elevation by t: degree p + t, every distinct knot's multiplicity grows by t, same curve.
TEST_F(Refinement, CurveDegreeElevation) {
  for (const NurbsCurve& c : test_curves()) {
    for (int t = 1; t <= 3; ++t) {
      const NurbsCurve e = elevate_degree(c, t);
      ASSERT_EQ(e.degree(), c.degree() + t);
      for (double k : c.knots().breakpoints()) {
        EXPECT_EQ(e.knots().multiplicity(k), c.knots().multiplicity(k) + t)
            << "p = " << c.degree() << ", t = " << t << ", knot " << k;
      }
      EXPECT_LE(deviation(c, e), kTol) << "p = " << c.degree() << ", t = " << t;
    }
    EXPECT_EQ(elevate_degree(c, 0).knots().knots(), c.knots().knots());
    EXPECT_LE(deviation(c, elevate_degree(c, 0)), kTol);
  }
  // k-refinement: elevate, then insert; and the elevated circle is still exactly round.
  const NurbsCurve k = refine_uniform(elevate_degree(full_circle(3.0), 2), 2);
  std::mt19937 rng(2);
  for (int s = 0; s < kSamples; ++s) {
    EXPECT_NEAR(k.evaluate(uniform(rng, 0, 1)).norm(), 3.0, 3.0 * kTol);
  }
}

// Unclamped (e.g. periodic) curves become clamped without moving: random knots and rational poles,
// a closed periodic cubic (wrapped poles) that must stay closed, one-sided unclamping.
TEST_F(Refinement, CurvePeriodicToClamped) {
  std::vector<NurbsCurve> curves = {
      random_curve(KnotVector({-3, -2, -1, 0, 1, 2, 3, 4, 5, 6}, 3), 5),
      random_curve(KnotVector({-0.5, -0.2, 0.0, 0.3, 0.3, 0.9, 1.0, 1.4, 1.5}, 2), 6),
      random_curve(KnotVector({0, 0, 0, 1, 2, 3, 3.5}, 2), 7),
      random_curve(KnotVector({-1, 0, 0, 0, 1, 2, 3, 4, 5, 6}, 3), 8),  // u_p has multiplicity p
  };
  // Periodic closed cubic: n + 1 = 8 poles of which the last 3 repeat the first 3.
  std::vector<Eigen::Vector3d> pts;
  const int distinct = 5;
  for (int i = 0; i < distinct + 3; ++i) {
    const double a = 2.0 * M_PI * (i % distinct) / distinct;
    pts.emplace_back(std::cos(a), std::sin(a), 0.3 * ((i % distinct) % 2));
  }
  std::vector<double> U;
  for (int i = 0; i <= 11; ++i) {
    U.push_back(i);
  }
  const NurbsCurve periodic(KnotVector(U, 3), pts, std::vector<double>(pts.size(), 1.0));
  curves.push_back(periodic);
  for (const NurbsCurve& c : curves) {
    ASSERT_FALSE(c.knots().is_clamped());
    const NurbsCurve k = make_clamped(c);
    EXPECT_TRUE(k.knots().is_clamped());
    EXPECT_EQ(k.knots().domain_begin(), c.knots().domain_begin());
    EXPECT_EQ(k.knots().domain_end(), c.knots().domain_end());
    EXPECT_EQ(k.knots().breakpoints(), c.knots().breakpoints());
    EXPECT_LE(deviation(c, k), kTol);
    EXPECT_LE((k.point(0) - c.evaluate(c.domain()[0])).norm(), kTol * diagonal(c.points()));
    EXPECT_LE((k.point(k.count() - 1) - c.evaluate(c.domain()[1])).norm(),
              kTol * diagonal(c.points()));
    // Insertion at both domain ends and splitting also work on the unclamped form.
    const int room_begin = c.degree() + 1 - c.knots().multiplicity(c.domain()[0]);
    const int room_end = c.degree() + 1 - c.knots().multiplicity(c.domain()[1]);
    ASSERT_GT(room_begin + room_end, 0);
    if (room_begin > 0) {
      EXPECT_LE(deviation(c, insert_knot(c, c.domain()[0], room_begin)), kTol);
    }
    if (room_end > 0) {
      EXPECT_LE(deviation(c, insert_knot(c, c.domain()[1], room_end)), kTol);
    }
    const double mid = 0.5 * (c.domain()[0] + c.domain()[1]);
    const auto halves = split(c, mid);
    EXPECT_EQ(halves.first.knots().is_clamped(), room_begin == 0);
    EXPECT_LE(deviation(halves.first, c, c.domain()[0], mid), kTol);
    EXPECT_LE(deviation(halves.second, c, mid, c.domain()[1]), kTol);
  }
  const NurbsCurve closed = make_clamped(periodic);
  EXPECT_LE((closed.point(0) - closed.point(closed.count() - 1)).norm(), 1e-14);
  EXPECT_LE((closed.derivative(3.0) - closed.derivative(8.0)).norm(), 1e-13);  // C^1 seam kept
  EXPECT_EQ(make_clamped(full_circle(1.0)).knots().knots(), full_circle(1.0).knots().knots());
}

TEST_F(Refinement, CurveSplitAndExtract) {
  for (const NurbsCurve& c : test_curves()) {
    const auto dom = c.domain();
    const double u = dom[0] + 0.37 * (dom[1] - dom[0]);
    const auto [left, right] = split(c, u);
    EXPECT_EQ(left.domain()[0], dom[0]);
    EXPECT_EQ(left.domain()[1], u);
    EXPECT_EQ(right.domain()[0], u);
    EXPECT_EQ(right.domain()[1], dom[1]);
    EXPECT_TRUE(left.knots().is_clamped());
    EXPECT_TRUE(right.knots().is_clamped());
    EXPECT_LE(deviation(left, c, dom[0], u), kTol);
    EXPECT_LE(deviation(right, c, u, dom[1]), kTol);
    EXPECT_EQ(left.point(left.count() - 1), right.point(0));
    const double a = dom[0] + 0.2 * (dom[1] - dom[0]);
    const double b = dom[0] + 0.65 * (dom[1] - dom[0]);
    const NurbsCurve piece = extract(c, a, b);
    EXPECT_EQ(piece.domain()[0], a);
    EXPECT_EQ(piece.domain()[1], b);
    EXPECT_LE(deviation(piece, c, a, b), kTol);
    EXPECT_LE(deviation(extract(c, dom[0], b), c, dom[0], b), kTol);
    EXPECT_LE(deviation(extract(c, a, dom[1]), c, a, dom[1]), kTol);
  }
  // Splitting at an existing knot of full multiplicity needs no insertion.
  const auto halves = split(full_circle(1.0), 0.5);
  EXPECT_EQ(halves.first.count(), 5);
  EXPECT_EQ(halves.second.count(), 5);
}

TEST_F(Refinement, SurfaceOperations) {
  const NurbsCurve circle = full_circle(1.0);
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (double z : {0.0, 1.0, 1.5, 3.0}) {
    for (int i = 0; i < circle.count(); ++i) {
      pts.push_back(circle.point(i) * (1.0 + 0.2 * z) + Eigen::Vector3d(0, 0, z));
      w.push_back(circle.weight(i) * (1.0 + 0.3 * z));
    }
  }
  const NurbsSurface s(circle.knots(), KnotVector::clamped(2, {0.4}), pts, w);
  for (int dir = 0; dir < 2; ++dir) {
    EXPECT_LE(deviation(s, insert_knot(s, dir, 0.33, 2)), kTol);
    EXPECT_LE(deviation(s, refine_knots(s, dir, {0.1, 0.4, 0.9})), kTol);
    EXPECT_LE(deviation(s, refine_uniform(s, dir, 2)), kTol);
    const NurbsSurface e = elevate_degree(s, dir, 2);
    EXPECT_EQ((dir == 0 ? e.knots_u() : e.knots_v()).degree(), 4);
    EXPECT_LE(deviation(s, e), kTol);
    const auto [a, b] = split(s, dir, 0.3);
    const NurbsSurface mid = extract(s, dir, 0.3, 0.8);
    std::mt19937 rng(3);
    for (int n = 0; n < kSamples; ++n) {
      const double t = uniform(rng, 0.0, 0.3);
      const double f = uniform(rng, 0.0, 1.0);
      const double m = uniform(rng, 0.3, 0.8);
      const Eigen::Vector3d xa = dir == 0 ? a.evaluate(t, f) : a.evaluate(f, t);
      const Eigen::Vector3d xs = dir == 0 ? s.evaluate(t, f) : s.evaluate(f, t);
      EXPECT_LE((xa - xs).norm(), kTol * 6.0);
      const Eigen::Vector3d xm = dir == 0 ? mid.evaluate(m, f) : mid.evaluate(f, m);
      const Eigen::Vector3d xt = dir == 0 ? s.evaluate(m, f) : s.evaluate(f, m);
      EXPECT_LE((xm - xt).norm(), kTol * 6.0);
    }
    EXPECT_EQ((dir == 0 ? b.knots_u() : b.knots_v()).domain_begin(), 0.3);
  }
  EXPECT_TRUE(refine_uniform(s, 0, 1).is_closed(0));
  // Unclamped in v: clamped without moving.
  const KnotVector open_v({-2, -1, 0, 1, 2, 3, 4}, 2);
  std::vector<Eigen::Vector3d> p2;
  std::vector<double> w2;
  for (int j = 0; j < open_v.num_basis(); ++j) {
    for (int i = 0; i < 3; ++i) {
      p2.emplace_back(i, j + 0.1 * i * i, std::sin(i + j));
      w2.push_back(1.0 + 0.25 * ((i + j) % 3));
    }
  }
  const NurbsSurface open(KnotVector::clamped(2, {}), open_v, p2, w2);
  const NurbsSurface clamped = make_clamped(open);
  EXPECT_TRUE(clamped.knots_v().is_clamped());
  EXPECT_LE(deviation(open, clamped), kTol);
}

TEST_F(Refinement, VolumeInsertionAndElevation) {
  const std::vector<NurbsVolume> volumes = {shell_sector(1.0, 1.6, 2.0), general_volume()};
  std::mt19937 rng(4);
  for (const NurbsVolume& v : volumes) {
    for (int dir = 0; dir < 3; ++dir) {
      const auto dom = v.domain(dir);
      const double u = uniform(rng, dom[0], dom[1]);
      const NurbsVolume ins = insert_knot(v, dir, u, 2);
      EXPECT_EQ(ins.count(dir), v.count(dir) + 2);
      EXPECT_LE(deviation(v, ins), kTol) << "dir " << dir;
      const NurbsVolume uni = refine_uniform(v, dir, 3);
      EXPECT_EQ(uni.knots(dir).breakpoints().size(),
                4 * (v.knots(dir).breakpoints().size() - 1) + 1);
      EXPECT_LE(deviation(v, uni), kTol) << "dir " << dir;
      const NurbsVolume e = elevate_degree(v, dir, 2);
      EXPECT_EQ(e.degree(dir), v.degree(dir) + 2);
      EXPECT_EQ(e.degree((dir + 1) % 3), v.degree((dir + 1) % 3));
      EXPECT_LE(deviation(v, e), kTol) << "dir " << dir;
    }
    const NurbsVolume all = refine_uniform(elevate_to(v, {3, 3, 3}), {1, 2, 3});
    for (int dir = 0; dir < 3; ++dir) {
      EXPECT_EQ(all.degree(dir), std::max(3, v.degree(dir)));
    }
    EXPECT_LE(deviation(v, all), kTol);
  }
  // The refined shell sector is still exact: radius 1 + 0.6 u.
  const NurbsVolume fine =
      refine_uniform(elevate_to(shell_sector(1.0, 1.6, 2.0), {2, 3, 2}), {2, 3, 1});
  for (int n = 0; n < kSamples; ++n) {
    const Eigen::Vector3d xi(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
    EXPECT_NEAR(fine.evaluate(xi).head<2>().norm(), 1.0 + 0.6 * xi[0], 1.6 * kTol);
  }
}

// The example suite cuts closed solids into symmetric pieces: a full ring split at v = 1/4 (90°)
// and 1/2, extracted pieces, and unclamped volumes clamped.
TEST_F(Refinement, VolumeSplitExtractAndClamp) {
  const NurbsVolume r = ring(1.0, 1.5, 0.5);
  const auto [quarter, rest] = split(r, 1, 0.25);
  EXPECT_EQ(quarter.domain(1)[1], 0.25);
  EXPECT_EQ(rest.domain(1)[0], 0.25);
  EXPECT_LE(deviation(r, quarter, {0, 0, 0}, {1, 0.25, 1}), kTol);
  EXPECT_LE(deviation(r, rest, {0, 0.25, 0}, {1, 1, 1}), kTol);
  // Split where no knot was (v = 0.1 cuts inside the first span), then an eighth of a half.
  const auto [a, b] = split(r, 1, 0.1);
  EXPECT_LE(deviation(r, a, {0, 0, 0}, {1, 0.1, 1}), kTol);
  EXPECT_LE(deviation(r, b, {0, 0.1, 0}, {1, 1, 1}), kTol);
  const NurbsVolume eighth = extract(extract(r, 1, 0.0, 0.125), 2, 0.0, 0.5);
  std::mt19937 rng(5);
  for (int n = 0; n < kSamples; ++n) {
    const Eigen::Vector3d xi(uniform(rng, 0, 1), uniform(rng, 0, 0.125), uniform(rng, 0, 0.5));
    const Eigen::Vector3d x = eighth.evaluate(xi);
    EXPECT_LE((x - r.evaluate(xi)).norm(), kTol * 3.2);
    EXPECT_NEAR(x.head<2>().norm(), 1.0 + 0.5 * xi[0], 1.5 * kTol);
    EXPECT_GE(x.y(), -1e-15);
    EXPECT_LE(std::atan2(x.y(), x.x()), M_PI / 4 + 1e-14);
  }
  const NurbsVolume g = general_volume();
  for (int dir = 0; dir < 3; ++dir) {
    const auto dom = g.domain(dir);
    const double lo = dom[0] + 0.15 * (dom[1] - dom[0]);
    const double hi = dom[0] + 0.8 * (dom[1] - dom[0]);
    const NurbsVolume piece = extract(g, dir, lo, hi);
    Eigen::Vector3d blo(g.domain(0)[0], g.domain(1)[0], g.domain(2)[0]);
    Eigen::Vector3d bhi(g.domain(0)[1], g.domain(1)[1], g.domain(2)[1]);
    blo[dir] = lo;
    bhi[dir] = hi;
    EXPECT_LE(deviation(g, piece, blo, bhi), kTol) << "dir " << dir;
  }
  const NurbsVolume open =
      random_volume({KnotVector::clamped(1, {}), KnotVector({-2, -1, 0, 1, 2, 3, 4, 5}, 2),
                     KnotVector({-0.4, -0.1, 0.0, 0.5, 1.0, 1.1}, 1)},
                    22);
  const NurbsVolume clamped = make_clamped(open);
  for (int dir = 0; dir < 3; ++dir) {
    EXPECT_TRUE(clamped.knots(dir).is_clamped());
    EXPECT_EQ(clamped.domain(dir), open.domain(dir));
  }
  EXPECT_LE(deviation(open, clamped), kTol);
}

TEST_F(Refinement, RejectsBadRequests) {
  const NurbsCurve c = full_circle(1.0);
  const NurbsVolume v = general_volume();
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([&] { insert_knot(c, 1.5); }).find("outside the parametric domain"),
            std::string::npos);
  EXPECT_NE(message([&] { insert_knot(c, 0.25, 2); }).find("multiplicity 4 > degree + 1 = 3"),
            std::string::npos);
  EXPECT_NE(message([&] { insert_knot(c, 0.3, 0); }).find("times = 0"), std::string::npos);
  EXPECT_NE(message([&] { insert_knot(c, 0.3, 1000000000); }).find("times = 1000000000"),
            std::string::npos);
  EXPECT_NE(message([&] { insert_knot(v, 3, 0.3); }).find("direction 3 must be in 0..2"),
            std::string::npos);
  EXPECT_NE(message([&] { elevate_degree(v, 1, -1); }).find("t = -1"), std::string::npos);
  EXPECT_NE(message([&] { elevate_degree(c, 9); }).find("exceeds the supported maximum"),
            std::string::npos);
  const NurbsCurve open = random_curve(KnotVector({-2, -1, 0, 1, 2, 3, 4}, 2), 9);
  EXPECT_NE(message([&] { elevate_degree(open, 1); }).find("make_clamped"), std::string::npos);
  const NurbsCurve broken = random_curve(KnotVector::clamped(1, {0.5, 0.5}), 10);
  EXPECT_NE(message([&] { elevate_degree(broken, 1); }).find("split there first"),
            std::string::npos);
  EXPECT_NE(message([&] { split(c, 1.0); }).find("strictly inside"), std::string::npos);
  EXPECT_NE(message([&] { split(v, 2, -1.0); }).find("volume, direction 2"), std::string::npos);
  EXPECT_NE(message([&] { extract(c, 0.6, 0.4); }).find("sub-domain"), std::string::npos);
  EXPECT_NE(message([&] { refine_uniform(v, 0, -1); }).find("n_per_span"), std::string::npos);
}

}  // namespace
}  // namespace isomuscle::geometry
