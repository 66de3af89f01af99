#include "io/material_ellipticity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace isomuscle::io {

MaterialEllipticity assess_material_ellipticity(const MaterialEllipticityScan& scan,
                                                const UnstableMode* mode) {
  MaterialEllipticity out;
  out.normals = scan.normals;
  out.points = scan.points.size();
  out.shear_modulus = scan.shear_modulus;
  out.smallest.smallest = std::numeric_limits<double>::infinity();
  for (const EllipticityAt& p : scan.points) {
    if (std::isnan(p.smallest)) {
      ++out.not_evaluated;
      continue;
    }
    if (p.smallest <= 0.0)
      ++out.not_elliptic;
    if (p.smallest < out.smallest.smallest)
      out.smallest = p;
  }
  if (out.not_evaluated == out.points)
    throw std::invalid_argument("the law could not be evaluated at any quadrature point");
  if (mode == nullptr || !mode->ok)
    return out;

  // The points within the mode's radius of its peak, or the nearest one when none is.
  out.near_mode = true;
  double nearest = std::numeric_limits<double>::infinity();
  for (const EllipticityAt& p : scan.points) {
    if (!std::isnan(p.smallest))
      nearest = std::min(nearest, (p.position - mode->peak_position).norm());
  }
  out.radius = std::max(mode->radius, nearest);
  out.smallest_near_mode.smallest = std::numeric_limits<double>::infinity();
  for (const EllipticityAt& p : scan.points) {
    if (std::isnan(p.smallest) || (p.position - mode->peak_position).norm() > out.radius)
      continue;
    ++out.near_mode_points;
    if (p.smallest < out.smallest_near_mode.smallest)
      out.smallest_near_mode = p;
  }
  return out;
}

std::string describe(const MaterialEllipticity& e) {
  const double mu = e.shear_modulus;
  const Eigen::Vector3d& x = e.smallest.position;
  char where[160], near[160] = "";
  std::snprintf(where, sizeof where, "%.3g mu at (%.4g, %.4g, %.4g) m", e.smallest.smallest / mu,
                x.x(), x.y(), x.z());
  if (e.near_mode) {
    std::snprintf(near, sizeof near, "; %.3g mu within %.2g m of the mode's peak",
                  e.smallest_near_mode.smallest / mu, e.radius);
  }
  char text[640];
  if (e.not_elliptic > 0) {
    std::snprintf(text, sizeof text,
                  "the law has lost strong ellipticity at %zu of %zu quadrature points (smallest "
                  "isochoric wave stiffness %s%s): a material instability, a shear band or fold "
                  "whose width no mesh resolves, so results past it depend on the mesh however "
                  "fine",
                  e.not_elliptic, e.points - e.not_evaluated, where, near);
  } else {
    std::snprintf(text, sizeof text,
                  "the law is strongly elliptic at all %zu quadrature points (smallest isochoric "
                  "wave stiffness %s%s): the instability is structural (buckling, wrinkling), not "
                  "a loss of material stability",
                  e.points - e.not_evaluated, where, near);
  }
  std::string out = text;
  if (e.not_evaluated > 0)
    out += " (" + std::to_string(e.not_evaluated) + " points could not be evaluated)";
  char seconds[48];
  std::snprintf(seconds, sizeof seconds, " (%.3g s)", e.seconds);
  return out + seconds;
}

}  // namespace isomuscle::io
