#pragma once
// The material_ellipticity probe: the law's strong ellipticity over the whole body at every
// converged step (continuum/point_ellipticity.hpp, assessed as material_ellipticity.hpp does), so
// that a run shows when and where the material itself first lets a shear band or fold form, not
// only at the first unstable equilibrium. Where e <= 0 the continuum problem has lost its
// well-posedness and results past that time depend on the mesh however fine; a stalled Newton
// solve or a refinement study that will not converge is then explained by the material, not by
// the solver. Columns:
//
//   <name>               e, the smallest isochoric wave stiffness over every quadrature point, Pa
//                        (the law's initial shear modulus mu at rest for the isotropic laws)
//   <name>.not_elliptic  how many quadrature points have e <= 0
//   <name>.x|y|z         the reference position of the smallest, m
//
// Points where the law cannot be evaluated are left out; where none can be, every column is NaN.
// Costs one scan of the 96-normal coarse set per point per step, refined at each point.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "io/run_model.hpp"

namespace isomuscle::io {

// The coarse set of wave normals of the probe's scan (the refined search is exact to round-off).
inline constexpr int kEllipticityProbeNormals = 96;

// How many columns the probe writes.
inline constexpr std::size_t kEllipticityProbeColumns = 5;

// The probe's column names, in the order ellipticity_probe_values writes them.
std::vector<std::string> ellipticity_probe_columns(const std::string& name);

// The probe's values from a scan of the committed state, written to out
// (kEllipticityProbeColumns values).
void ellipticity_probe_values(const MaterialEllipticityScan& scan, std::span<double> out);

}  // namespace isomuscle::io
