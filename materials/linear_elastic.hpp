#pragma once
// "Linear elastic" tissue (thesis chapter 4: skin E = 15 kPa, passive muscle E = 6.2 kPa, cartilage
// and eyeball E = 6.1 MPa, bone E = 6.5 GPa) in a large-deformation solver (SPEC §4): the
// frame-invariant law used is the decoupled compressible neo-Hookean
//   psi = mu/2 (Ī1 - 3) + kappa/2 (J - 1)²,  mu = E / (2(1 + nu)),  kappa = E / (3(1 - 2 nu)),
// whose tangent at F = I is exactly Hooke's isotropic matrix with the same E and nu.
// Why not St Venant–Kirchhoff: its energy is not polyconvex, under uniaxial compression its
// nominal stress peaks at a stretch of 1/sqrt(3) and then falls to zero, so a soft tissue squeezed
// by an expression or a surgical displacement can collapse; the neo-Hookean stiffens instead and
// offers the volumetric split the mixed u–p–J formulation uses (nu = 0.49 gives kappa/mu ~ 50).
#include <memory>
#include <vector>

#include "materials/material_factory.hpp"

namespace isomuscle::materials {

class ParameterValues;

// Parameters "E" (Pa, default 6.2e3: muscle at rest, Duck 1990) and "nu" (default 0.49).
const std::vector<ParameterSpec>& linear_elastic_parameters();
std::unique_ptr<MaterialLaw> make_linear_elastic(const ParameterValues& values);

}  // namespace isomuscle::materials
