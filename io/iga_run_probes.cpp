#include "io/iga_run_probes.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/point_inversion.hpp"
#include "iga/pressure_space.hpp"
#include "iga/quadrature_point_interpolation.hpp"
#include "io/element_layer_check.hpp"
#include "io/ellipticity_probe.hpp"
#include "io/iga_surface_point.hpp"
#include "io/setting_check.hpp"
#include "io/surface_stability_check.hpp"

namespace isomuscle::io {

namespace {

// A point closer to the collapsed axis than this fraction of the element's largest det J (which
// falls linearly to 0 there) is evaluated at the nearest quadrature point instead: F = I + du/dX
// needs J^-1 of the parametrisation.
constexpr double kSingularFraction = 1e-3;

int component_index(const std::string& name) {
  if (name == "x")
    return 0;
  if (name == "y")
    return 1;
  if (name == "z")
    return 2;
  if (name == "normal")
    return 4;
  return 3;
}

// x, y, z, |v| or v . n.
double pick(const Eigen::Vector3d& v, int component, const Eigen::Vector3d& normal) {
  return component < 3 ? v[component] : component == 3 ? v.norm() : v.dot(normal);
}

// The quadrature point of element e nearest to xi, in the element's reference coordinates.
int nearest_point(const iga::Space& space, int e, const Eigen::Vector3d& xi) {
  const iga::Element& el = space.element(e);
  const Eigen::Vector3d t = iga::element_reference_coordinates(el, xi);
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int q = 0; q < space.points_per_element(); ++q) {
    const double d =
        (iga::element_reference_coordinates(el, space.parametric(e, q)) - t).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = q;
    }
  }
  return best;
}

}  // namespace

IgaProbes::IgaProbes(const std::vector<ProbeSettings>& probes, const IgaModel& model) {
  const iga::Space& space = *model.space;
  const iga::Problem& problem = *model.problem;
  const materials::MaterialLaw& law = *model.law;
  std::unique_ptr<geometry::PointInverter> inverter;
  part_names_ = law.cauchy_part_names();
  const bool mixed = problem.formulation() == iga::Formulation::mixed;
  const bool has_vol =
      std::find(part_names_.begin(), part_names_.end(), "vol") != part_names_.end();
  parts_from_law_ = !(part_names_.size() == 1 && part_names_[0] == "total") && (!mixed || has_vol);
  replace_volumetric_ = mixed && has_vol;

  for (const ProbeSettings& s : probes) {
    Probe p;
    p.settings = s;
    p.component = component_index(s.component);
    p.first_column = columns_.size();
    const std::string what = "[[probe]] '" + s.name + "'";
    if (s.kind == ProbeKind::surface_stability || s.kind == ProbeKind::element_layer) {
      // Any point near the surface will do (a control point of a mode may lie outside).
      const Eigen::Vector3d X =
          s.xi ? space.volume().evaluate(model.frame.solid_xi(*s.xi)) : *s.point;
      points_.emplace_back(s.name, X);
      p.surface = checked_probe_location(locate_surface_point(problem, X), law, what);
      notes_.push_back(describe_probe_location(what, p.surface,
                                               space.position(p.surface.element, p.surface.point)));
      if (s.kind == ProbeKind::element_layer && !mixed)
        throw std::invalid_argument(what +
                                    ": kind = \"element_layer\" checks the mixed element; this run "
                                    "uses the displacement formulation ([solver] formulation)");
    }
    if (s.kind == ProbeKind::point_displacement || s.kind == ProbeKind::stress_parts) {
      if (s.xi) {
        for (int d = 0; d < 3; ++d) {
          if (!((*s.xi)[d] >= 0.0 && (*s.xi)[d] <= 1.0)) {
            throw std::invalid_argument(what + ": xi = " + describe_point(*s.xi) +
                                        " must lie in [0, 1] in every direction");
          }
        }
        p.xi = model.frame.solid_xi(*s.xi);
      } else {
        if (!inverter)
          inverter = std::make_unique<geometry::PointInverter>(space.volume());
        const geometry::InversionResult r = inverter->invert(*s.point);
        if (!r.inside) {
          throw std::invalid_argument(what + ": point " + describe_point(*s.point) +
                                      " m lies outside the solid (nearest point of the solid is " +
                                      format_number(r.distance) + " m away)");
        }
        p.xi = r.xi;
      }
      p.element = space.locate(p.xi);
      points_.emplace_back(s.name, space.volume().evaluate(p.xi));
      if (p.component == 4) {
        const auto [w0, w1] = space.volume().domain(2);
        if (std::abs(p.xi[2] - w0) > 1e-9 * (w1 - w0)) {
          throw std::invalid_argument(
              what +
              ": component = \"normal\" needs a point on the boundary surface (the face "
              "w0: xi = [u, v, 0]); this point lies inside, at w = " +
              format_number((p.xi[2] - w0) / (w1 - w0)));
        }
        p.xi[2] = w0;
        p.normal = surface_normal(space.volume(), p.xi, what);
      }
    }
    switch (s.kind) {
      case ProbeKind::point_displacement:
      case ProbeKind::volume:
      case ProbeKind::surface_stability:
        columns_.push_back(s.name);
        break;
      case ProbeKind::element_layer:
        columns_.push_back(s.name);
        columns_.push_back(s.name + ".column");
        break;
      case ProbeKind::material_ellipticity:
        for (std::string& column : ellipticity_probe_columns(s.name))
          columns_.push_back(std::move(column));
        break;
      case ProbeKind::face_reaction:
        p.nodes = selected_nodes(model, *s.face, what);
        needs_force_ = true;
        columns_.push_back(s.name);
        break;
      case ProbeKind::stress_parts: {
        double largest = 0.0;
        for (int q = 0; q < space.points_per_element(); ++q)
          largest = std::max(largest, space.jacobian(p.element, q).determinant());
        const double here = space.volume().jacobian(p.xi).determinant();
        if (!(here > kSingularFraction * largest)) {
          p.point = nearest_point(space, p.element, p.xi);
          notes_.push_back(what +
                           ": the point lies on the collapsed axis of the solid, where F is "
                           "undefined; stresses are taken at the nearest quadrature point, "
                           "X = " +
                           describe_point(space.position(p.element, p.point)) + " m");
          p.weights.assign(static_cast<std::size_t>(space.points_per_element()), 0.0);
          p.weights[static_cast<std::size_t>(p.point)] = 1.0;
        } else {
          p.weights = iga::quadrature_point_weights(space, p.element, p.xi);
        }
        if (parts_from_law_) {
          for (const std::string& part : part_names_) {
            if (part != "total")
              columns_.push_back(s.name + "." + part);
          }
        }
        columns_.push_back(s.name + ".total");
        break;
      }
    }
    probes_.push_back(std::move(p));
  }
}

void IgaProbes::before_commit(iga::Problem& problem, const Eigen::VectorXd& u) {
  if (needs_force_) {
    const solver::EvaluationStatus status = problem.internal_force(u, force_);
    if (!status.ok)
      throw std::runtime_error("face reaction probes: " + status.message);
  }
}

// a . sigma_part . a of every part and the total (thesis 3.44, 5.30, 5.41); returns the total. The
// parts are the law's at each quadrature point of the element, split with its converged F and the
// committed history (the trial history the law wrote in the converged evaluation: exactly the
// assembled stress, the law not evaluated again), interpolated to the point, and a is the deformed
// fibre of the interpolated state there.
double IgaProbes::stress_column_values(const iga::Problem& problem, const Probe& p,
                                       std::vector<double>& out, std::size_t at) const {
  const std::vector<iga::PointState> states = problem.element_states(p.element);
  const iga::PointState st = p.point >= 0 ? states[static_cast<std::size_t>(p.point)]
                                          : problem.interpolate_state(p.element, states, p.xi);
  const Eigen::Vector3d& a = st.fibre_deformed;
  if (parts_from_law_) {
    const materials::MaterialLaw& law = problem.law();
    std::vector<Eigen::Matrix3d> parts(part_names_.size(), Eigen::Matrix3d::Zero());
    std::vector<Eigen::Matrix3d> point_parts(part_names_.size());
    materials::PointInput in;
    in.time = problem.committed_time();
    in.dt = problem.committed_dt();
    for (std::size_t q = 0; q < states.size(); ++q) {
      if (p.weights[q] == 0.0)
        continue;
      in.F = states[q].field.F;
      in.fibre = states[q].fibre;
      std::fill(point_parts.begin(), point_parts.end(), Eigen::Matrix3d::Zero());
      law.cauchy_parts(in, problem.committed_history(p.element, static_cast<int>(q)), point_parts);
      for (std::size_t i = 0; i < parts.size(); ++i) {
        if (replace_volumetric_ && part_names_[i] == "vol")
          point_parts[i] = states[q].p_bar * Eigen::Matrix3d::Identity();
        parts[i] += p.weights[q] * point_parts[i];
      }
    }
    for (std::size_t i = 0; i < part_names_.size(); ++i) {
      if (part_names_[i] != "total")
        out[at++] = a.dot(parts[i] * a);
    }
  }
  const double total = a.dot(st.cauchy * a);
  out[at] = total;
  return total;
}

void IgaProbes::values(const iga::Problem& problem, std::vector<double>& out) const {
  out.assign(columns_.size(), 0.0);
  const Eigen::VectorXd& u_full = problem.committed_displacement();
  for (const Probe& p : probes_) {
    switch (p.settings.kind) {
      case ProbeKind::point_displacement:
        out[p.first_column] = pick(problem.displacement_at(u_full, p.xi), p.component, p.normal);
        break;
      case ProbeKind::face_reaction:
        out[p.first_column] = pick(problem.sum_over_nodes(force_, p.nodes), p.component, p.normal);
        break;
      case ProbeKind::volume:
        out[p.first_column] = problem.current_volume(u_full);
        break;
      case ProbeKind::stress_parts:
        stress_column_values(problem, p, out, p.first_column);
        break;
      case ProbeKind::surface_stability:
        out[p.first_column] = surface_stability_value(surface_point_at(problem, p.surface));
        break;
      case ProbeKind::element_layer:
        out[p.first_column] = element_layer_value(problem, p.surface);
        out[p.first_column + 1] = element_column_value(problem, p.surface);
        break;
      case ProbeKind::material_ellipticity:
        ellipticity_probe_values(
            committed_ellipticity_of(problem, kEllipticityProbeNormals),
            std::span<double>(out).subspan(p.first_column, kEllipticityProbeColumns));
        break;
    }
  }
}

}  // namespace isomuscle::io
