#pragma once
// Stability of a traction-free surface of a homogeneously deformed, nearly incompressible solid
// (Biot's surface instability): whether an incremental displacement that is periodic along the
// surface and decays into the body can lower the energy. Strong ellipticity
// (strong_ellipticity.hpp) can hold in the interior while this fails: the boundary's
// complementing condition (Simpson & Spector, Arch. Ration. Mech. Anal. 98, 1987) is a separate
// condition, and its failure is a wrinkling whose wavelength no term of the continuum sets.
//
// Current configuration, outward unit normal n, ν = -n into the body. The incremental energy of a
// displacement u with div u = 0, for the mixed law sigma = sigma_iso + p~ I (p~ the pressure of
// the u-p-J formulation), per unit current volume, is
//
//   W2 = 1/2 ( A0_ijkl u_i,j u_k,l - p~ u_j,i u_i,j + p~ (u_i,i)^2 ),
//   A0_ijkl = J^-1 F_jJ F_lL A_iJkL   (A the isochoric first elasticity, strong_ellipticity.hpp),
//
// whose traction, n_j (A0_ijkl u_k,l - p~ u_j,i) + Δp~ n_i, is the linearised traction of the
// mixed formulation. With u = Re(U(y) e^{i k t.x}) for a unit tangent t and depth y along ν
// (k = 1: the half-space has no length, so the answer holds for every wavelength), the energy per
// unit area is a Hermitian form in U. It is discretised in depth by 40 quadratic elements graded
// from the surface to a clamped bottom at depth 60 / k, with div u = 0 held weakly by linear
// pressures (Taylor–Hood), and the measure is
//
//   s = min over t, and over admissible U, of  E2(U) / ∫ |U|^2 dy      (Pa)
//
// the lowest eigenvalue of the energy against the mass: rho c^2 of the slowest surface (Rayleigh)
// wave along the surface, for a density rho. s > 0: the surface is stable for every tangential
// direction; s <= 0: a surface wave of zero speed exists, the surface wrinkles. Checked
// (tests/materials/test_surface_stability.cpp) against the incompressible neo-Hookean half-space:
// 0.9126 mu at rest (the Rayleigh speed of an incompressible solid, c^2 = 0.9126 mu / rho), zero
// at Biot's critical stretches 0.5437 in plane strain and 0.666 in equibiaxial compression.
#include <Eigen/Core>

#include "materials/material_law.hpp"

namespace isomuscle::materials {

struct SurfaceStabilityResult {
  double smallest = 0.0;                                 // s, Pa
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // the current tangent t that gave it
};

// s for the isochoric S and tangent of a law at F (Voigt convention of material_law.hpp), the
// mixed pressure p~ (Pa; sigma = J^-1 F S F^T + p~ I) and the current outward unit normal of the
// surface. directions: tangents tried over half a turn (at least 4), the best refined by golden
// section. Throws std::invalid_argument for det F <= 0, a normal not of unit length or too few
// directions.
SurfaceStabilityResult surface_stability(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                         const Matrix6d& tangent, double pressure,
                                         const Eigen::Vector3d& normal, int directions = 36);

}  // namespace isomuscle::materials
