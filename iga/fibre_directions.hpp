#pragma once
// The undeformed fibre direction N at every quadrature point (thesis 5.27–5.30, SPEC §1), by mode:
//
// * isocurve (direction d = u, v or w): N = (dX/dxi_d) / |dX/dxi_d|, the normalised tangent of the
//   isocurve through the point, i.e. column d of the geometry Jacobian tabulated by Space;
// * constant: one given direction everywhere (e.g. z);
// * polyline ("method 1" of thesis 5.6.4–5.6.5): a polyline P_0 ... P_n (n >= 1 straight
//   segments, e.g. from one end of the muscle through its middle to the other end). The body is
//   cut into n pieces by the bisecting (miter) plane of every joint P_i, 0 < i < n: the plane
//   through P_i normal to the mean of the unit directions of the two segments that meet there.
//   X belongs to segment i when it is past the planes of joints 1 .. i and not past that of
//   joint i + 1 (a point on a plane stays with the lower segment), and its fibre is the constant
//   direction (P_i+1 - P_i)/|P_i+1 - P_i| of that segment. For two segments meeting at the
//   middle this is the cut of the thesis figures 5.36 and 5.43. (The nearest segment would not
//   do: on the convex side of a joint both distances are |X - P_i|, an exact tie.)
//   With a parametric cut (cut_direction d >= 0) the pieces are instead xi_d < c_1, c_1 <= xi_d
//   < c_2, ...: the body divided at isoparametric surfaces, as a mesh is divided into parts
//   (the thesis's LS-DYNA models). Where the cuts are knots the fibre jump lies on element
//   boundaries, so Gauss quadrature never integrates across it; a scene's IGA model makes them
//   C^0 knots (io/iga_run_setup.cpp), so the basis can follow the kink of u there too;
// * origin–insertion: the straight line from origin P to insertion Q (LS-DYNA card P25–P30),
//   N = (Q - P)/|Q - P| everywhere (a one-segment polyline).
//
// Fibres are unit vectors; the sign is irrelevant to the laws (they depend on N (x) N).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/nurbs_volume.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {

struct FibreSpec {
  enum class Mode { isocurve, constant, polyline, origin_insertion };
  Mode mode = Mode::constant;
  int direction = 2;                                  // isocurve: 0 = u, 1 = v, 2 = w
  Eigen::Vector3d vector = Eigen::Vector3d::UnitZ();  // constant
  std::vector<Eigen::Vector3d> polyline;              // polyline: n + 1 >= 2 points, m
  int cut_direction = -1;    // polyline: parametric direction of the cuts; -1: miter planes
  std::vector<double> cuts;  // polyline with cut_direction >= 0: n - 1 increasing xi values
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // origin_insertion: P, m
  Eigen::Vector3d insertion = Eigen::Vector3d::UnitZ();  // Q, m

  static FibreSpec isocurve(int direction);
  static FibreSpec constant(const Eigen::Vector3d& v);
  static FibreSpec segments(std::vector<Eigen::Vector3d> points);
  static FibreSpec segments_cut_at(std::vector<Eigen::Vector3d> points, int direction,
                                   std::vector<double> cuts);
  static FibreSpec origin_to_insertion(const Eigen::Vector3d& p, const Eigen::Vector3d& q);

  // Throws std::invalid_argument naming the field: direction outside 0..2, zero or non-finite
  // vectors, fewer than two polyline points, a zero-length segment or a joint where the polyline
  // turns straight back, parametric cuts in a direction outside 0..2, not n - 1 of them or not
  // increasing, P == Q.
  void validate() const;
};

// "isocurve", "constant", "polyline", "origin_insertion".
const char* to_string(FibreSpec::Mode mode);

// N at a point with geometry Jacobian jac (columns dX/dxi_d), position X and parametric
// coordinates xi. Throws std::invalid_argument when the isocurve tangent vanishes there (a
// collapsed direction).
Eigen::Vector3d fibre_direction(const FibreSpec& spec, const Eigen::Matrix3d& jac,
                                const Eigen::Vector3d& X, const Eigen::Vector3d& xi);
// The same for the modes that need no xi; std::invalid_argument for a parametric cut.
Eigen::Vector3d fibre_direction(const FibreSpec& spec, const Eigen::Matrix3d& jac,
                                const Eigen::Vector3d& X);

// N at every quadrature point of the space, flat index e * nqp + q.
std::vector<Eigen::Vector3d> fibre_directions(const Space& space, const FibreSpec& spec);

}  // namespace isomuscle::iga
