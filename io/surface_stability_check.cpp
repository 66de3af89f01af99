#include "io/surface_stability_check.hpp"

#include <Eigen/LU>
#include <chrono>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "materials/surface_stability.hpp"

namespace isomuscle::io {

namespace {

// "(x, y, z)" with `digits` significant digits.
std::string vector_text(const Eigen::Vector3d& v, int digits) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.*g, %.*g, %.*g)", digits, v.x(), digits, v.y(), digits,
                v.z());
  return text;
}

std::string number_text(double x, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

}  // namespace

SurfaceStabilityCheck assess_surface_stability(const SurfacePointAt& point, int directions) {
  const auto begin = std::chrono::steady_clock::now();
  const continuum::SteppedResponse& r = point.response;
  if (!r.ok) {
    throw std::invalid_argument("the law could not be evaluated at the surface point");
  }
  if (!r.isochoric) {
    throw std::invalid_argument(
        "the surface check needs a nearly incompressible law with a volumetric split");
  }
  SurfaceStabilityCheck check;
  check.point = point;
  const double J = r.F.determinant();
  // Nanson: the current normal is along cof F N = J F^-T N.
  check.current_normal = (r.F.inverse().transpose() * point.normal).normalized();
  const Eigen::Vector3d& n = check.current_normal;
  const Eigen::Matrix3d sigma_iso = r.F * r.S * r.F.transpose() / J;
  const Eigen::Vector3d traction = sigma_iso * n;
  check.free_surface_pressure = -n.dot(traction);
  check.shear_traction = (traction - n * n.dot(traction)).norm();
  const materials::SurfaceStabilityResult s =
      materials::surface_stability(r.F, r.S, r.tangent, check.free_surface_pressure, n, directions);
  check.smallest = s.smallest;
  check.direction = s.direction;
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return check;
}

std::string describe(const SurfaceStabilityCheck& check) {
  const double mu = check.point.shear_modulus;
  const auto in_mu = [&](double value) { return number_text(value / mu, 3) + " mu"; };
  const double depth = (check.point.position - check.point.surface_position).norm();
  const std::string state = "slowest surface wave rho c^2 = " + in_mu(check.smallest) + " along " +
                            vector_text(check.direction, 3) + "; at the quadrature point " +
                            number_text(depth, 3) + " m below it, element p~ - p = " +
                            in_mu(check.point.response.pressure - check.free_surface_pressure) +
                            ", shear traction " + in_mu(check.shear_traction);
  std::string text = "the free surface nearest the mode's peak, at " +
                     vector_text(check.point.surface_position, 4) + " m (outward normal " +
                     vector_text(check.current_normal, 3) + "), ";
  if (check.smallest > 0.0) {
    text += "is stable as a deformed half-space (" + state +
            "): the local state does not wrinkle by itself, so the instability needs the body's "
            "geometry (curvature, a thin part, the stress gradient)";
  } else {
    text += "has reached Biot's surface instability as a deformed half-space (" + state +
            "): a wrinkle with no length of its own, whose wavelength and onset the mesh sets";
  }
  return text + " (" + number_text(check.seconds, 3) + " s)";
}

SurfaceLocation checked_probe_location(const std::optional<SurfaceLocation>& where,
                                       const materials::MaterialLaw& law, const std::string& what) {
  if (!law.has_volumetric_split()) {
    throw std::invalid_argument(what +
                                ": kind = \"surface_stability\" needs a nearly incompressible "
                                "law with a volumetric split (" +
                                law.name() + " has none)");
  }
  if (!where)
    throw std::invalid_argument(what + ": the body has no traction-free boundary");
  return *where;
}

double surface_stability_value(const SurfacePointAt& point) {
  if (!point.response.ok)
    return std::numeric_limits<double>::quiet_NaN();
  return assess_surface_stability(point).smallest;
}

std::string describe_probe_location(const std::string& what, const SurfaceLocation& where,
                                    const Eigen::Vector3d& quadrature_point) {
  return what + ": the free surface nearest it is at " + vector_text(where.surface_position, 4) +
         " m, outward normal " + vector_text(where.normal, 3) +
         "; its state is taken at the quadrature point " +
         number_text((quadrature_point - where.surface_position).norm(), 3) + " m below it";
}

}  // namespace isomuscle::io
