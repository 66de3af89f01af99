#pragma once
// Whether the free surface where an equilibrium lost stability has itself become unstable as a
// deformed half-space (Biot's surface instability, materials/surface_stability.hpp): at the
// surface point nearest the unstable mode's peak (RunModel::committed_surface_point), the local
// state (F, the law's isochoric S and tangent as the step evaluated them) is taken as a
// homogeneously deformed half-space bounded by the tangent plane there, and s = rho c^2 of its
// slowest surface wave is computed.
// * s <= 0: the surface has reached Biot's threshold: a wrinkle with no length of its own, whose
//   wavelength and onset the mesh sets.
// * s > 0: the local state alone does not wrinkle; the instability needs the body's geometry (the
//   surface's curvature, a thin layer, the gradient of the stress), a buckling whose wavelength
//   the geometry sets.
// The half-space is traction-free: its pressure is p = -n.sigma_iso.n, which makes the normal
// traction zero. The check reports how far the computed state is from that: the element's p~
// against p, and the shear traction (I - n n) sigma_iso n that a free surface would not carry
// (both nonzero at a quadrature point below a curved, loaded surface; large values say the local
// half-space is a rough model there). Needs a law with a volumetric split (the analysis holds the
// isochoric constraint div u = 0).
#include <Eigen/Core>
#include <optional>
#include <string>

#include "io/run_model.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::io {

struct SurfaceStabilityCheck {
  SurfacePointAt point;
  Eigen::Vector3d current_normal = Eigen::Vector3d::UnitZ();  // cof F N, normalised
  double free_surface_pressure = 0.0;                         // p = -n.sigma_iso.n, Pa
  double shear_traction = 0.0;                                // |(I - n n) sigma_iso n|, Pa
  double smallest = 0.0;                                      // s, Pa
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // the current tangent of the slowest wave
  double seconds = 0.0;
};

// directions: tangents tried over half a turn before the golden-section refinement. Throws
// std::invalid_argument when the law could not be evaluated at the point or has no volumetric
// split.
SurfaceStabilityCheck assess_surface_stability(const SurfacePointAt& point, int directions = 12);

// For the log: "the free surface at (x, y, z) m (outward normal (..)) is stable as a deformed
// half-space: its slowest surface wave has rho c^2 = 0.43 mu along (..) (element p~ - p = ..,
// shear traction .. mu): ..." or that it has reached Biot's threshold, and what that means.
std::string describe(const SurfaceStabilityCheck& check);

// The surface_stability probe (scene.hpp): its place as the discretisation located it, checked
// (std::invalid_argument naming the probe, `what`, when the law has no volumetric split or the
// body no traction-free boundary); its value, s (Pa), NaN where the law could not be evaluated (a
// diagnostic never stops the run); and its note for the log, where it was placed: "[[probe]]
// 'deep': the free surface nearest it is at (x, y, z) m, outward normal (..); its state is taken
// at the quadrature point 0.0004 m below it".
SurfaceLocation checked_probe_location(const std::optional<SurfaceLocation>& where,
                                       const materials::MaterialLaw& law, const std::string& what);
double surface_stability_value(const SurfacePointAt& point);
std::string describe_probe_location(const std::string& what, const SurfaceLocation& where,
                                    const Eigen::Vector3d& quadrature_point);

}  // namespace isomuscle::io
