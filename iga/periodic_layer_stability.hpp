#pragma once
// Discrete stability of the element itself: whether the run's own knot-span element (its B-spline
// degrees, its quadrature, the condensed mixed u–p–J kernel with p~, J~ per span), tiled
// periodically along a traction-free surface and deformed homogeneously to one point's state, has
// an incremental displacement that lowers the energy.
//
// The layer: parallelepiped elements with the edge vectors of one element in the two surface
// directions, a few spans deep (the depth spans of the body below that surface), the bottom
// clamped. Its uniform interior B-splines are translates of one another, so an incremental
// displacement periodic along the surface up to a phase (Bloch, Floquet),
//
//   u_(i, j, k) = U_k e^{i (theta_0 i + theta_1 j)},   theta in [-pi, pi]^2 (radians per span),
//
// has, per cell, the Hermitian energy U^H K(theta) U with K(theta) = sum over the elements of one
// column through the depth of their tangent K_e, each entry phased by the in-plane offset of its
// two functions (the same sum an assembly over the infinite layer makes). The measure is the lowest
// eigenvalue of K(theta) against the lumped volumes (the mass of unstable_mode.hpp, Pa/m^2) over
// all theta: an eigenvalue <= 0 is an incremental mode the discrete layer has.
//
// Reading it. The continuum at that state is stable for every wave when the law is strongly
// elliptic (materials/strong_ellipticity.hpp) and the free surface has rho c^2 > 0
// (materials/surface_stability.hpp). If the element's layer is unstable there all the same, the
// mode belongs to the discretisation: mixed and enhanced elements have such modes in compression
// (Wriggers & Reese 1996; the F-bar family). Two properties tell it apart: the frozen layer has no
// length of its own, so its lowest eigenvalue scales as 1 / h^2 with the element size h (the mode
// follows the mesh); and the same physical wave on elements subdivided r times (theta / r) has the
// continuum's positive energy once r is large enough.
#include <Eigen/Core>
#include <array>
#include <complex>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::iga {

struct LayerGeometry {
  // B-spline degrees: the two surface directions, then the depth direction (each 1..10).
  std::array<int, 3> degrees = {2, 2, 2};
  // Reference edge vectors of one element (m): the two surface directions, then the depth edge of a
  // span of relative width 1, pointing into the body.
  std::array<Eigen::Vector3d, 3> edges = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                          -Eigen::Vector3d::UnitZ()};
  // Relative widths of the spans through the depth, from the free surface inward; the last span's
  // far face is clamped.
  std::vector<double> depth_spans = {1.0, 1.0, 1.0, 1.0};
  // The element pressure space's degree (iga/pressure_space.hpp; 0: mean dilatation) and the
  // Gauss points per direction (0: degree + 1, as iga::QuadratureOptions).
  int pressure_degree = 0;
  std::array<int, 3> quadrature_points = {0, 0, 0};
};

// The same layer with every element cut into r x r x r: edges / r in the surface, each depth span
// in r. The total depth stays.
LayerGeometry subdivided(const LayerGeometry& layer, int r);

// The homogeneous state: the law (with a volumetric split), F (its determinant is the J~ the
// mixed kernel projects, so p~ = U'(det F)), the reference fibre, the history before the step
// (history_size() values) and the step's time and dt.
struct LayerState {
  const materials::MaterialLaw* law = nullptr;
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  Eigen::Vector3d fibre = Eigen::Vector3d::UnitZ();
  std::vector<double> history;
  double time = 0.0;
  double dt = 0.0;
};

struct BlochMode {
  double eigenvalue = 0.0;                           // Pa/m^2
  Eigen::Vector2d angles = Eigen::Vector2d::Zero();  // theta, radians per span
  std::vector<double> depth_amplitude;               // |U_k| per depth row, the largest 1
};

// One element of a column through the depth, as the Bloch sum takes it: its tangent K_e (3 n_en
// square, symmetric up to round-off), and for each local function its depth row (0 at the free
// surface) and its in-plane index (i, j) along the two surface directions.
struct ColumnElement {
  Eigen::MatrixXd tangent;
  std::vector<int> row;
  std::vector<Eigen::Vector2d> offset;
};

class PeriodicLayer {
 public:
  // Builds the layer and its column's element tangents with the mixed kernel. Throws
  // std::invalid_argument for a law without a volumetric split, det F <= 0, edges that do not span
  // a volume, or bad degrees, spans or counts; std::runtime_error naming the failure when the
  // kernel fails at the state (J <= 0, the law's local solve).
  PeriodicLayer(const LayerGeometry& layer, const LayerState& state);
  // A column given element by element (a body's own elements, each at its own state), tiled by
  // translation along the surface. lumped: the volume of each depth row per cell (m^3); the last
  // row is clamped. Throws std::invalid_argument for an empty column, a tangent whose size does
  // not match its functions, a row outside the lumped rows, or a non-positive lumped volume.
  PeriodicLayer(std::vector<ColumnElement> column, Eigen::VectorXd lumped);

  // The lowest eigenvalue (and its depth profile) of K(theta) against the lumped volumes.
  BlochMode lowest_at(const Eigen::Vector2d& angles) const;
  // The lowest over theta: a grid of `samples` steps per half turn in each direction, the best
  // refined by a pattern search to 1e-4 rad. theta_0 >= 0 (theta and -theta give conjugate
  // matrices, the same eigenvalues).
  BlochMode lowest(int samples = 16) const;

  // Rows of control points through the depth (the surface row first, the clamped one last).
  int depth_rows() const { return depth_rows_; }

 private:
  std::vector<ColumnElement> column_;
  Eigen::VectorXd lumped_;  // volume per cell of each depth row, m^3
  int depth_rows_ = 0;
  bool swapped_ = false;  // the surface directions exchanged to make the layer right-handed
};

}  // namespace isomuscle::iga
