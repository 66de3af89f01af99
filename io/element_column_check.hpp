#pragma once
// Whether the body's own column of elements through the depth below a free-surface point, tiled
// along the surface, has an unstable wave: the Bloch analysis of iga/periodic_layer_stability.hpp
// on the real elements (their geometry as refined, tapering to the axis of a shrink solid) rather
// than on a uniform layer. It is run twice:
// * each element at its own committed state (the state's variation through the depth in);
// * the same elements all at the surface point's homogeneous state (committed_layer_state).
// Read with the uniform layer (element_layer_check.hpp), which has the surface point's state and
// the surface element's shape through the whole depth:
// * the column stable: a wave periodic along the surface is stable even with the depth's
//   gradients; the instability needs variation along the surface too (a localised state, the
//   body's shape in plan);
// * unstable at its own states and stable at the surface point's: the variation of the state
//   through the depth makes it;
// * unstable at the surface point's state too: the shapes of the body's elements through the
//   depth make it.
// A column is translated, not bent: in-plane stresses varying through the depth (bending) are
// taken as they are, without the curvature that balances them in the body.
#include <Eigen/Core>
#include <limits>
#include <stdexcept>
#include <string>

#include "iga/periodic_layer_stability.hpp"
#include "io/surface_location.hpp"

namespace isomuscle::iga {
class Problem;
}

namespace isomuscle::io {

struct ElementColumnCheck {
  int elements = 0;            // in the column, through the depth
  iga::BlochMode lowest;       // each element at its own committed state
  iga::BlochMode homogeneous;  // all at the surface point's state
};

// The column of elements through the depth below `where` (the elements sharing its span indices
// along the surface), tiled along the surface; rows from the free surface, the opposite side's row
// clamped. Each element at its committed state, or with `homogeneous` at that state. Throws
// std::invalid_argument when the location is not on a NURBS side, std::runtime_error naming the
// element when its kernel fails.
iga::PeriodicLayer element_column_at(const iga::Problem& problem, const SurfaceLocation& where,
                                     const iga::LayerState* homogeneous = nullptr);

// Both analyses above; throws as element_column_at.
ElementColumnCheck assess_element_column(const iga::Problem& problem, const SurfaceLocation& where);

// The lowest Bloch eigenvalue of the layer that make_layer() builds (Pa/m^2), NaN where an element
// fails at its state (std::runtime_error): the element_layer probe's values, which a failed check
// must not end the run for.
template <class MakeLayer>
double lowest_eigenvalue_or_nan(MakeLayer&& make_layer) {
  try {
    return make_layer().lowest().eigenvalue;
  } catch (const std::runtime_error&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

// The element_layer probe's second column (scene.hpp): the column's lowest Bloch eigenvalue at the
// committed states (Pa/m^2), NaN where an element fails at its state.
double element_column_value(const iga::Problem& problem, const SurfaceLocation& where);

// For the log: the two eigenvalues and waves, and which reading above holds.
std::string describe(const ElementColumnCheck& check, double shear_modulus);

}  // namespace isomuscle::io
