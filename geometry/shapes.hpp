#pragma once
// Closed NURBS boundary surfaces of the example suite (SPEC §5, thesis §5.6), in metres. Each is
// exact (rational quadratic circles), clamped, closed in u (around the centreline) with the
// centreline running along v, ready for the shrinking construction (shrink.hpp). Circles follow
// Piegl & Tiller, The NURBS Book §7.5 (nine-point square and seven-point triangle forms) and
// surfaces of revolution §8.5. examples/geometry/README.md documents every shape.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_surface.hpp"

namespace isomuscle::geometry {

// SPEC §5 dimensions (thesis §5.6), metres.
inline constexpr double kConeBottomDiameter = 0.040;
inline constexpr double kConeTopDiameter = 0.008;
inline constexpr double kConeHeight = 0.050;
inline constexpr double kBarrelLength = 0.050;
inline constexpr double kBarrelEndDiameter = 0.009;
inline constexpr double kBarrelMiddleDiameter = 0.0175;
inline constexpr double kTorusInnerRadius = 0.009;  // ring - tube
inline constexpr double kTorusOuterRadius = 0.017;  // ring + tube
inline constexpr double kHalfTorusInnerRadius = 0.007;
inline constexpr double kHalfTorusOuterRadius = 0.013;

enum class CircleForm {
  kNinePoint,   // four 90-degree arcs on a square, weights 1, sqrt(2)/2
  kSevenPoint,  // three 120-degree arcs on an equilateral triangle, weights 1, 1/2
};

// A planar rational B-spline curve: knots, control points in a plane, weights.
struct PlanarCurve {
  KnotVector knots;
  std::vector<Eigen::Vector2d> points;
  std::vector<double> weights;
};

// Unit circle about the origin from (1, 0), counter-clockwise, rational quadratic, clamped on
// [0, 1]; first and last control points coincide (closed).
PlanarCurve unit_circle(CircleForm form = CircleForm::kNinePoint);
// Unit half circle from (1, 0) through (0, 1) to (-1, 0): two 90-degree arcs, five points.
PlanarCurve unit_half_circle();

// Surface of revolution about the z axis: the profile lies in the (r, z) half-plane and is swept
// through `sweep`, a unit circle or arc in the xy plane: P_ij = (r_j s_i, z_j), w_ij = w_i w_j.
// u runs along the sweep, v along the profile.
NurbsSurface revolve(const PlanarCurve& profile_rz, const PlanarCurve& sweep);

// Tube with elliptical cross-sections around a centreline: P_ij = C_j + c_i.x A_j + c_i.y B_j,
// w_ij = w_i (c = unit circle), so the section at any v is the ellipse C(v) + X(u) A(v) + Y(u)
// B(v) centred on the centreline C(v) = sum_j N_j(v) C_j (A_j, B_j: semi-axis vectors). u around,
// v along the centreline (non-rational, knots `along`).
NurbsSurface elliptic_tube(const KnotVector& along, const std::vector<Eigen::Vector3d>& centres,
                           const std::vector<Eigen::Vector3d>& first_semi_axes,
                           const std::vector<Eigen::Vector3d>& second_semi_axes,
                           CircleForm form = CircleForm::kNinePoint);

// Lateral surface of a cone frustum on the z axis from z = 0 (radius bottom_radius) to
// z = height (top_radius); profile a straight quadratic Bezier with linear parametrisation.
NurbsSurface cone_frustum(double bottom_radius, double top_radius, double height,
                          CircleForm form = CircleForm::kNinePoint);
// V = pi h (R1^2 + R1 R2 + R2^2) / 3.
double cone_frustum_volume(double bottom_radius, double top_radius, double height);

// Barrel on the z axis from z = 0 to length, profile the parabola
// r(z) = r_e + 4 (r_m - r_e) (z / L) (1 - z / L): a quadratic Bezier with control points
// (r_e, 0), (2 r_m - r_e, L / 2), (r_e, L), so z = L v exactly.
NurbsSurface barrel(double length, double end_radius, double middle_radius,
                    CircleForm form = CircleForm::kNinePoint);
// V = pi L (r_e^2 + 4/3 r_e (r_m - r_e) + 8/15 (r_m - r_e)^2), the integral of pi r(z)^2.
double barrel_volume(double length, double end_radius, double middle_radius);

// Whole torus about the z axis: u around the tube circle (closed), v around the ring (closed, the
// centreline). Ring radius R (centre of the tube), tube radius r < R.
NurbsSurface torus(double ring_radius, double tube_radius,
                   CircleForm form = CircleForm::kNinePoint);
double torus_volume(double ring_radius, double tube_radius);  // 2 pi^2 R r^2
// Half torus: the ring is the half circle from angle 0 to pi (y >= 0).
NurbsSurface half_torus(double ring_radius, double tube_radius,
                        CircleForm form = CircleForm::kNinePoint);
double half_torus_volume(double ring_radius, double tube_radius);  // pi^2 R r^2

// Synthetic depressor anguli oris (stand-in for the thesis's forensic shape; design in
// examples/geometry/README.md): a curved fan from a broad origin on the lower jaw (3.0 cm wide,
// 2 mm thick) to the mouth corner (6 mm wide, 4 mm thick), about 3.5 cm long; elliptical sections
// on a cubic centreline. Frame: x lateral along the jaw, y anterior, z superior; origin at the
// centre of the base.
NurbsSurface depressor_anguli_oris(CircleForm form = CircleForm::kNinePoint);

// Cook's membrane (R. D. Cook, Improved two-dimensional finite element, J. Struct. Div. ASCE 100,
// 1974): the tapered panel with corners (0, 0), (48, 44), (48, 60), (0, 44) in the xy plane as a
// bilinear B-spline patch, u along x (from the clamped edge x = 0 to the loaded edge x = 48), v
// upwards, normal +z. The benchmark is unit-free; the numbers are written as metres. A sheet, not
// a tube: scenes extrude it (examples/cook).
NurbsSurface cook_membrane_surface();

struct ExampleShape {
  std::string name;         // file stem: cone, barrel, torus, half_torus, dao
  std::string description;  // one line
  NurbsSurface surface;     // metres; closed in u, the centreline along v
  int centreline_direction = 1;
  std::optional<double> exact_volume;  // m^3 of the shrink solid where a closed form exists
};

// The five SPEC §5 examples in the order cone, barrel, torus, half_torus, dao.
std::vector<ExampleShape> example_shapes(CircleForm form = CircleForm::kNinePoint);

}  // namespace isomuscle::geometry
