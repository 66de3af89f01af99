#pragma once
// Whether the material itself became unstable where an equilibrium lost stability: at the first
// unstable step the law's strong ellipticity (continuum/point_ellipticity.hpp) is scanned over
// every quadrature point of the equilibrium, overall and near the unstable mode's peak
// (unstable_mode.hpp). The answer decides what refinement can do:
// * e <= 0 somewhere: the law admits a discontinuity of the displacement gradient (a shear band, a
//   fold). The continuum problem loses its well-posedness, and finer meshes localise ever more
//   narrowly: no mesh converges past that state (a regularisation is needed: a length scale).
// * e > 0 everywhere: the instability is structural. A buckling of the body has the wavelength
//   its geometry sets, and refinement converges it. A wrinkle of a compressed free surface (Biot's
//   surface instability, where the boundary's complementing condition fails, not ellipticity)
//   has none in a continuum without a length scale: it takes the shortest wavelength the mesh
//   resolves, so its onset moves with the mesh. Whether the surface has reached that is checked
//   separately (surface_stability_check.hpp).
// e is measured by the law's initial shear modulus mu.
#include <string>

#include "io/run_model.hpp"
#include "io/unstable_mode.hpp"

namespace isomuscle::io {

struct MaterialEllipticity {
  int normals = 0;                // the search's coarse set
  std::size_t points = 0;         // quadrature points scanned
  std::size_t not_evaluated = 0;  // where the law could not be evaluated
  std::size_t not_elliptic = 0;   // e <= 0
  double shear_modulus = 0.0;     // mu, Pa
  EllipticityAt smallest;         // over all points
  bool near_mode = false;         // a mode was found, so the next three mean something
  double radius = 0.0;            // m: the mode's extent about its peak, at least the nearest point
  std::size_t near_mode_points = 0;  // points within radius of the peak
  EllipticityAt smallest_near_mode;
  double seconds = 0.0;  // scan and assessment
};

// The summary of a scan; mode (may be null, or not ok) places the "near the mode" part. Throws
// std::invalid_argument when no point of the scan could be evaluated.
MaterialEllipticity assess_material_ellipticity(const MaterialEllipticityScan& scan,
                                                const UnstableMode* mode);

// For the log: "the law is strongly elliptic at all 442368 quadrature points (smallest isochoric
// wave stiffness 1.02 mu at (x, y, z) m; 1.9 mu within 0.00071 m of the mode's peak): the
// instability is structural (buckling, wrinkling), not a loss of material stability (0.9 s)", or
// that it has lost it at so many points, and what that means.
std::string describe(const MaterialEllipticity& e);

}  // namespace isomuscle::io
