#pragma once
// Strong ellipticity of the law at every quadrature point of a state (materials/
// strong_ellipticity.hpp): where the material itself lets a discontinuity of the displacement
// gradient form (e <= 0: a shear band or fold, whose width no mesh resolves, so that the solution
// depends on the mesh however fine), as against where it does not (e > 0 everywhere: an
// instability of the state is then structural, a buckling or wrinkling whose wavelength the body's
// geometry and the mesh set).
//
// The law is evaluated as the assembly evaluated it for the step that reached the state: at its F,
// its time and step size, from the history committed before that step, so that the tangent is the
// algorithmic one the equilibrium was found with (for the Hill laws an incremental potential).
// Laws with a volumetric split give their isochoric part, which alone decides isochoric waves (the
// mixed formulation's pressure drops out; strong_ellipticity.hpp). Laws without give their full
// response, tested on isochoric waves too: a necessary condition then (e <= 0 still means loss).
#include <Eigen/Core>
#include <limits>
#include <span>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::continuum {

// The law's response at one point as the step that reached a committed state evaluated it (above):
// F, the isochoric S and tangent for laws with a volumetric split (else the full ones), and the
// mixed pressure p~ of the point (0 in the displacement formulation). ok is false where the law
// could not be evaluated.
struct SteppedResponse {
  bool ok = false;
  bool isochoric = false;  // S and tangent are the isochoric part
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();  // Pa
  materials::Matrix6d tangent = materials::Matrix6d::Zero();
  double pressure = 0.0;  // p~, Pa
};

// The response at F, fibre and pre-step history (history_size() values), at the step's time and
// dt; pressure is the point's p~, carried into the result.
SteppedResponse stepped_response(const materials::MaterialLaw& law, const Eigen::Matrix3d& F,
                                 const Eigen::Vector3d& fibre, std::span<const double> history,
                                 double time, double dt, double pressure);

struct PointEllipticity {
  // e (Pa): the smallest isochoric wave stiffness; NaN where the law could not be evaluated
  // (J <= 0, a failed local solve).
  double smallest = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // the reference wave normal that gave it
};

// e at every point (element-major, nqp per element): F, fibres and history (history_size() per
// point, may be empty for laws without) are arrays over all points. normals: the coarse set of the
// refined search (at least 8). Runs on solver::resolve_thread_count(threads) threads. Throws
// std::invalid_argument for inconsistent sizes or too few normals.
std::vector<PointEllipticity> ellipticity_at_points(const materials::MaterialLaw& law,
                                                    const std::vector<Eigen::Matrix3d>& F,
                                                    const std::vector<Eigen::Vector3d>& fibres,
                                                    const std::vector<double>& history, double time,
                                                    double dt, int normals, int threads);

}  // namespace isomuscle::continuum
