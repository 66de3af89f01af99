#include "continuum/point_ellipticity.hpp"

#include <Eigen/LU>
#include <span>
#include <stdexcept>
#include <string>

#include "materials/strong_ellipticity.hpp"
#include "solver/element_colouring.hpp"

namespace isomuscle::continuum {

SteppedResponse stepped_response(const materials::MaterialLaw& law, const Eigen::Matrix3d& F,
                                 const Eigen::Vector3d& fibre, std::span<const double> history,
                                 double time, double dt, double pressure) {
  SteppedResponse out;
  out.F = F;
  out.pressure = pressure;
  out.isochoric = law.has_volumetric_split();
  if (!(F.determinant() > 0.0))
    return out;
  std::vector<double> trial(static_cast<std::size_t>(law.history_size()));
  materials::PointResult result;
  result.history = trial;
  materials::PointInput in;
  in.F = F;
  in.fibre = fibre;
  in.time = time;
  in.dt = dt;
  in.history = history;
  const materials::PointStatus status =
      out.isochoric ? law.evaluate_isochoric(in, result, true) : law.evaluate(in, result, true);
  if (status != materials::PointStatus::ok)
    return out;
  out.ok = true;
  out.S = result.S;
  out.tangent = result.tangent;
  return out;
}

std::vector<PointEllipticity> ellipticity_at_points(const materials::MaterialLaw& law,
                                                    const std::vector<Eigen::Matrix3d>& F,
                                                    const std::vector<Eigen::Vector3d>& fibres,
                                                    const std::vector<double>& history, double time,
                                                    double dt, int normals, int threads) {
  const std::size_t points = F.size();
  const std::size_t hs = static_cast<std::size_t>(law.history_size());
  if (fibres.size() != points || history.size() != points * hs) {
    throw std::invalid_argument("ellipticity_at_points: " + std::to_string(points) +
                                " deformation gradients, " + std::to_string(fibres.size()) +
                                " fibres and " + std::to_string(history.size()) +
                                " history values (" + std::to_string(hs) + " per point)");
  }
  if (normals < 8)
    throw std::invalid_argument("ellipticity_at_points: normals must be at least 8");
  std::vector<PointEllipticity> out(points);
  const long count = static_cast<long>(points);
#pragma omp parallel for num_threads(solver::resolve_thread_count(threads)) schedule(dynamic, 64)
  for (long i = 0; i < count; ++i) {
    const std::size_t p = static_cast<std::size_t>(i);
    const SteppedResponse r = stepped_response(
        law, F[p], fibres[p], std::span<const double>(history.data() + p * hs, hs), time, dt, 0.0);
    if (!r.ok)
      continue;
    const materials::EllipticityResult e =
        materials::refined_isochoric_ellipticity(r.F, r.S, r.tangent, normals);
    out[p] = PointEllipticity{e.smallest, e.normal};
  }
  return out;
}

}  // namespace isomuscle::continuum
