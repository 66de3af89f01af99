#pragma once
// Whether the element itself is unstable where an equilibrium lost stability: the run's knot-span
// element tiled periodically along the free surface nearest the unstable mode's peak, a few spans
// deep as the body is there, deformed homogeneously to the state of the quadrature point below that
// surface point (iga/periodic_layer_stability.hpp). Read with the two continuum checks at the same
// place (material_ellipticity.hpp, surface_stability_check.hpp), which hold for every wavelength:
// * the element's layer unstable, and the same wave on elements subdivided r = 2, 4 times stable:
//   the instability belongs to the discretisation (a spurious mode of the element, whose
//   wavelength and onset follow the mesh), not to the muscle;
// * the same wave unstable on the subdivided elements too: the continuum's own instability there;
// * the element's layer stable: the instability needs the body itself (its geometry, the
//   gradients of its state), not the local state alone.
// NURBS solids with the mixed formulation only. The layer is uniform: the element's edge vectors
// at that quadrature point (dX/dxi times the span widths), maximal continuity along the surface,
// the body's knot spans through the depth from that side to the opposite one, whose far face is
// clamped (a clamp only stiffens: a negative eigenvalue is the element's own).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "iga/periodic_layer_stability.hpp"
#include "io/element_column_check.hpp"
#include "io/surface_location.hpp"

namespace isomuscle::iga {
class Problem;
}

namespace isomuscle::io {

struct ElementLayerCheck {
  Eigen::Vector3d surface_position = Eigen::Vector3d::Zero();  // reference, m
  iga::LayerGeometry layer;
  double shear_modulus = 0.0;  // mu of the law, Pa
  // The lowest Bloch mode of the element's own layer, and of the layer with elements halved (all
  // angles; about 4 times the first when the mode follows the mesh).
  iga::BlochMode lowest, lowest_halved;
  // The eigenvalue (Pa/m^2) of lowest's wave on elements subdivided r = 2 and 4 times (theta / r).
  std::vector<std::pair<int, double>> same_wave;
  // The body's own elements through the depth there, tiled the same way
  // (element_column_check.hpp): whether the depth's gradients or element shapes make it unstable.
  ElementColumnCheck column;
  double seconds = 0.0;
};

// The layer of the element at a surface location (above). Throws std::invalid_argument when the
// location is not on a NURBS side or the problem is not mixed.
iga::LayerGeometry element_layer_at(const iga::Problem& problem, const SurfaceLocation& where);

// Throws as element_layer_at, and std::invalid_argument when the law has no volumetric split;
// std::runtime_error when the element fails at the state.
ElementLayerCheck assess_element_layer(const iga::Problem& problem, const SurfaceLocation& where);

// The element_layer probe (scene.hpp): the lowest Bloch eigenvalue of the element's own layer at
// the committed state (Pa/m^2), NaN where the element fails at the state (a diagnostic never stops
// the run).
double element_layer_value(const iga::Problem& problem, const SurfaceLocation& where);

// For the log: what the layer is, its lowest eigenvalue and wave, the same wave on finer
// elements, and which of the three readings above holds.
std::string describe(const ElementLayerCheck& check);

}  // namespace isomuscle::io
