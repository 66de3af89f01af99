#pragma once
// Volume and Jacobian measures of a NURBS solid H(u,v,w) (thesis 5.13): the volume by Gauss
// quadrature of det J over the knot spans, the same volume from the boundary by the divergence
// theorem (an independent check), and the range of det J on a sampling grid. Used to validate
// shrink solids against closed forms and by `isomuscle geometry solid`.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "geometry/gauss_legendre.hpp"
#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

// Signed volume V = integral of det(dH/dxi) over the parametric box (m^3 for a solid in metres),
// Gauss–Legendre with n points per direction in every knot span. det J of a rational map is
// rational, so the rule is not exact: compare n and n + 2 to estimate the error.
double solid_volume(const NurbsVolume& volume, int points_per_direction);

// The same signed volume from the six parametric faces, V = 1/3 * closed integral of H . n dA
// (divergence theorem; face area vectors H_v x H_w, H_w x H_u, H_u x H_v with the outward sign),
// n points per direction in every knot span of each face. Collapsed faces contribute zero.
double solid_volume_from_boundary(const NurbsVolume& volume, int points_per_direction);

// The volume with the Gauss rule refined (n = max degree + 2, + 2, ...) until two successive rules
// agree to relative_tolerance or max_points is reached; reports the last change so that a caller
// can show how converged the number is.
struct VolumeEstimate {
  double volume = 0.0;           // m^3 (signed)
  int points_per_direction = 0;  // of the last rule
  double relative_change = 0.0;  // |V_n - V_{n-2}| / |V_n|
};
VolumeEstimate converged_solid_volume(const NurbsVolume& volume, double relative_tolerance = 1e-13,
                                      int max_points = 40);

struct JacobianRange {
  double min = 0.0;  // smallest det J sampled (m^3 per unit parametric volume)
  double max = 0.0;  // largest det J sampled
  Eigen::Vector3d argmin = Eigen::Vector3d::Zero();  // where (u, v, w)
  Eigen::Vector3d argmax = Eigen::Vector3d::Zero();
  int samples = 0;
  int non_positive = 0;  // samples with det J <= 0
};

// det J on a cell-centred grid of samples_per_span^3 points per knot span: parameter
// (k + 1/2) / samples_per_span of each span, k = 0..samples_per_span-1. No sample lies on a span
// boundary, so none lies on the collapsed axis w = 1 of a shrink solid (where det J = 0).
JacobianRange jacobian_range(const NurbsVolume& volume, int samples_per_span);

// The sampling grid of jacobian_range, for other pointwise measures of the map: visit(xi, J,
// cell) at every sample, cell = the parametric volume of the sample's cell (sum over all samples =
// the parametric box's volume), so that det J * cell weights a sample by the volume it stands
// for. Throws std::invalid_argument naming `what` unless 1 <= samples_per_span <= 100.
using CellSampleVisitor =
    std::function<void(const Eigen::Vector3d& xi, const Eigen::Matrix3d& jacobian, double cell)>;
void for_each_cell_sample(const NurbsVolume& volume, int samples_per_span, const char* what,
                          const CellSampleVisitor& visit);

}  // namespace isomuscle::geometry
