// Exact NURBS boundary surfaces of the example suite (SPEC §5); see shapes.hpp.
#include "geometry/shapes.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace isomuscle::geometry {

namespace {

void require_positive(double value, const char* name, const char* shape) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string(shape) + ": " + name + " = " + std::to_string(value) +
                                " must be finite and positive (metres)");
  }
}

}  // namespace

// Piegl & Tiller §7.5: a rational quadratic arc of angle theta has middle weight cos(theta / 2)
// and its middle control point at the intersection of the end tangents, distance
// 1 / cos(theta / 2) from the centre. Nine-point: theta = 90 degrees; seven-point: 120 degrees.
PlanarCurve unit_circle(CircleForm form) {
  const int arcs = form == CircleForm::kNinePoint ? 4 : 3;
  const double theta = 2.0 * std::numbers::pi / arcs;
  const double middle_weight = std::cos(0.5 * theta);
  PlanarCurve circle;
  std::vector<double> interior;
  for (int k = 1; k < arcs; ++k) {
    interior.push_back(static_cast<double>(k) / arcs);
    interior.push_back(static_cast<double>(k) / arcs);
  }
  circle.knots = KnotVector::clamped(2, interior);
  for (int k = 0; k < arcs; ++k) {
    const double a0 = k * theta;
    const double am = a0 + 0.5 * theta;
    circle.points.emplace_back(std::cos(a0), std::sin(a0));
    circle.weights.push_back(1.0);
    circle.points.emplace_back(std::cos(am) / middle_weight, std::sin(am) / middle_weight);
    circle.weights.push_back(middle_weight);
  }
  circle.points.push_back(circle.points.front());  // exactly closed
  circle.weights.push_back(1.0);
  if (form == CircleForm::kNinePoint) {
    // Exact square corners and axis points (cos/sin of multiples of 90 degrees are not exact).
    const double s = std::numbers::sqrt2 / 2.0;
    circle.points = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    circle.weights = {1, s, 1, s, 1, s, 1, s, 1};
  }
  return circle;
}

PlanarCurve unit_half_circle() {
  const double s = std::numbers::sqrt2 / 2.0;
  PlanarCurve arc;
  arc.knots = KnotVector::clamped(2, {0.5, 0.5});
  arc.points = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}};
  arc.weights = {1, s, 1, s, 1};
  return arc;
}

// Piegl & Tiller §8.5 (A8.1): P_ij = (r_j s_i.x, r_j s_i.y, z_j), w_ij = w^sweep_i w^profile_j.
NurbsSurface revolve(const PlanarCurve& profile_rz, const PlanarCurve& sweep) {
  const int nu = static_cast<int>(sweep.points.size());
  const int nv = static_cast<int>(profile_rz.points.size());
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  points.reserve(static_cast<std::size_t>(nu * nv));
  weights.reserve(static_cast<std::size_t>(nu * nv));
  for (int j = 0; j < nv; ++j) {
    const Eigen::Vector2d& rz = profile_rz.points[j];
    for (int i = 0; i < nu; ++i) {
      points.emplace_back(rz.x() * sweep.points[i].x(), rz.x() * sweep.points[i].y(), rz.y());
      weights.push_back(sweep.weights[i] * profile_rz.weights[j]);
    }
  }
  return NurbsSurface(sweep.knots, profile_rz.knots, std::move(points), std::move(weights));
}

NurbsSurface elliptic_tube(const KnotVector& along, const std::vector<Eigen::Vector3d>& centres,
                           const std::vector<Eigen::Vector3d>& first_semi_axes,
                           const std::vector<Eigen::Vector3d>& second_semi_axes, CircleForm form) {
  const std::size_t nv = centres.size();
  if (static_cast<int>(nv) != along.num_basis() || first_semi_axes.size() != nv ||
      second_semi_axes.size() != nv) {
    throw std::invalid_argument("elliptic_tube: the knot vector along the centreline needs " +
                                std::to_string(along.num_basis()) + " stations, got " +
                                std::to_string(nv) + " centres, " +
                                std::to_string(first_semi_axes.size()) + " first and " +
                                std::to_string(second_semi_axes.size()) + " second semi-axes");
  }
  const PlanarCurve circle = unit_circle(form);
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  for (std::size_t j = 0; j < nv; ++j) {
    if (first_semi_axes[j].cross(second_semi_axes[j]).norm() <= 0.0) {
      throw std::invalid_argument("elliptic_tube: the semi-axes of station " + std::to_string(j) +
                                  " are parallel or zero");
    }
    for (std::size_t i = 0; i < circle.points.size(); ++i) {
      points.push_back(centres[j] + circle.points[i].x() * first_semi_axes[j] +
                       circle.points[i].y() * second_semi_axes[j]);
      weights.push_back(circle.weights[i]);
    }
  }
  return NurbsSurface(circle.knots, along, std::move(points), std::move(weights));
}

NurbsSurface cone_frustum(double bottom_radius, double top_radius, double height, CircleForm form) {
  require_positive(bottom_radius, "bottom radius", "cone_frustum");
  require_positive(top_radius, "top radius", "cone_frustum");
  require_positive(height, "height", "cone_frustum");
  PlanarCurve profile;
  profile.knots = KnotVector::clamped(2, {});
  profile.points = {{bottom_radius, 0.0},
                    {0.5 * (bottom_radius + top_radius), 0.5 * height},
                    {top_radius, height}};
  profile.weights = {1.0, 1.0, 1.0};
  return revolve(profile, unit_circle(form));
}

double cone_frustum_volume(double bottom_radius, double top_radius, double height) {
  return std::numbers::pi * height *
         (bottom_radius * bottom_radius + bottom_radius * top_radius + top_radius * top_radius) /
         3.0;
}

NurbsSurface barrel(double length, double end_radius, double middle_radius, CircleForm form) {
  require_positive(length, "length", "barrel");
  require_positive(end_radius, "end radius", "barrel");
  require_positive(middle_radius, "middle radius", "barrel");
  PlanarCurve profile;
  profile.knots = KnotVector::clamped(2, {});
  profile.points = {
      {end_radius, 0.0}, {2.0 * middle_radius - end_radius, 0.5 * length}, {end_radius, length}};
  profile.weights = {1.0, 1.0, 1.0};
  return revolve(profile, unit_circle(form));
}

// pi L int_0^1 (a + b s)^2 dt with s = 4 t (1 - t): int s = 2/3, int s^2 = 8/15.
double barrel_volume(double length, double end_radius, double middle_radius) {
  const double a = end_radius;
  const double b = middle_radius - end_radius;
  return std::numbers::pi * length * (a * a + 4.0 / 3.0 * a * b + 8.0 / 15.0 * b * b);
}

// Revolving the tube circle (profile in the (r, z) plane centred at (R, 0)) gives u = ring,
// v = tube; transposed so that u goes around the tube and the ring is the centreline v.
NurbsSurface torus(double ring_radius, double tube_radius, CircleForm form) {
  require_positive(ring_radius, "ring radius", "torus");
  require_positive(tube_radius, "tube radius", "torus");
  if (!(tube_radius < ring_radius)) {
    throw std::invalid_argument("torus: tube radius " + std::to_string(tube_radius) +
                                " must be smaller than the ring radius " +
                                std::to_string(ring_radius));
  }
  PlanarCurve tube = unit_circle(form);
  for (Eigen::Vector2d& p : tube.points)
    p = Eigen::Vector2d(ring_radius, 0.0) + tube_radius * p;
  return revolve(tube, unit_circle(form)).transposed();
}

double torus_volume(double ring_radius, double tube_radius) {
  return 2.0 * std::numbers::pi * std::numbers::pi * ring_radius * tube_radius * tube_radius;
}

NurbsSurface half_torus(double ring_radius, double tube_radius, CircleForm form) {
  require_positive(ring_radius, "ring radius", "half_torus");
  require_positive(tube_radius, "tube radius", "half_torus");
  if (!(tube_radius < ring_radius)) {
    throw std::invalid_argument("half_torus: tube radius " + std::to_string(tube_radius) +
                                " must be smaller than the ring radius " +
                                std::to_string(ring_radius));
  }
  PlanarCurve tube = unit_circle(form);
  for (Eigen::Vector2d& p : tube.points)
    p = Eigen::Vector2d(ring_radius, 0.0) + tube_radius * p;
  return revolve(tube, unit_half_circle()).transposed();
}

double half_torus_volume(double ring_radius, double tube_radius) {
  return std::numbers::pi * std::numbers::pi * ring_radius * tube_radius * tube_radius;
}

// Design (examples/geometry/README.md): six stations of a cubic centreline bowing up to 4.7 mm
// forward (following the convex chin) and drifting 4 mm laterally; the width semi-axis runs along
// the jaw (x projected normal to the centreline), the thickness semi-axis normal to the skin.
NurbsSurface depressor_anguli_oris(CircleForm form) {
  const std::vector<Eigen::Vector3d> centres = {{0.0000, 0.0000, 0.0000}, {0.0010, 0.0025, 0.0070},
                                                {0.0020, 0.0045, 0.0145}, {0.0030, 0.0050, 0.0220},
                                                {0.0035, 0.0040, 0.0290}, {0.0040, 0.0020, 0.0340}};
  const std::vector<double> width = {0.0150, 0.0125, 0.0095, 0.0065, 0.0045, 0.0030};
  const std::vector<double> thickness = {0.0010, 0.0011, 0.0013, 0.0016, 0.0019, 0.0020};
  const std::size_t n = centres.size();
  std::vector<Eigen::Vector3d> first(n);
  std::vector<Eigen::Vector3d> second(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Vector3d chord = centres[std::min(j + 1, n - 1)] - centres[j == 0 ? 0 : j - 1];
    const Eigen::Vector3d t = chord.normalized();
    const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - t.x() * t).normalized();
    const Eigen::Vector3d e2 = t.cross(e1);
    first[j] = width[j] * e1;
    second[j] = thickness[j] * e2;
  }
  const KnotVector along = KnotVector::clamped(3, {1.0 / 3.0, 2.0 / 3.0});
  return elliptic_tube(along, centres, first, second, form);
}

NurbsSurface cook_membrane_surface() {
  const KnotVector linear = KnotVector::clamped(1, {});
  // Index i + 2 j: (u, v) = (0, 0), (1, 0), (0, 1), (1, 1).
  std::vector<Eigen::Vector3d> points = {
      {0.0, 0.0, 0.0}, {48.0, 44.0, 0.0}, {0.0, 44.0, 0.0}, {48.0, 60.0, 0.0}};
  return NurbsSurface(linear, linear, std::move(points), std::vector<double>(4, 1.0));
}

std::vector<ExampleShape> example_shapes(CircleForm form) {
  std::vector<ExampleShape> shapes;
  const double rb = 0.5 * kConeBottomDiameter;
  const double rt = 0.5 * kConeTopDiameter;
  shapes.push_back(
      {"cone", "cone frustum: bottom diameter 4.0 cm, top 0.8 cm, height 5.0 cm (z axis)",
       cone_frustum(rb, rt, kConeHeight, form), 1, cone_frustum_volume(rb, rt, kConeHeight)});
  const double re = 0.5 * kBarrelEndDiameter;
  const double rm = 0.5 * kBarrelMiddleDiameter;
  shapes.push_back({"barrel",
                    "barrel: length 5.0 cm, end diameters 0.9 cm, middle 1.75 cm, parabolic "
                    "profile (z axis)",
                    barrel(kBarrelLength, re, rm, form), 1, barrel_volume(kBarrelLength, re, rm)});
  const double tR = 0.5 * (kTorusOuterRadius + kTorusInnerRadius);
  const double tr = 0.5 * (kTorusOuterRadius - kTorusInnerRadius);
  shapes.push_back({"torus",
                    "whole torus: inner radius 0.9 cm, outer 1.7 cm (ring 1.3 cm, tube 0.4 cm) "
                    "about the z axis",
                    torus(tR, tr, form), 1, torus_volume(tR, tr)});
  const double hR = 0.5 * (kHalfTorusOuterRadius + kHalfTorusInnerRadius);
  const double hr = 0.5 * (kHalfTorusOuterRadius - kHalfTorusInnerRadius);
  shapes.push_back({"half_torus",
                    "half torus: inner radius 0.7 cm, outer 1.3 cm (ring 1.0 cm, tube 0.3 cm), "
                    "ring from +x through +y to -x",
                    half_torus(hR, hr, form), 1, half_torus_volume(hR, hr)});
  shapes.push_back({"dao",
                    "synthetic depressor anguli oris: curved fan 3.0 cm wide and 2 mm thick at "
                    "the jaw, 6 mm wide and 4 mm thick at the mouth corner, about 3.5 cm long",
                    depressor_anguli_oris(form), 1, std::nullopt});
  return shapes;
}

}  // namespace isomuscle::geometry
