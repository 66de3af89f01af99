#include "io/tet_run_probes.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "io/ellipticity_probe.hpp"
#include "io/setting_check.hpp"
#include "io/surface_stability_check.hpp"
#include "io/tet_surface_point.hpp"

namespace isomuscle::io {

namespace {

int component_index(const std::string& name) {
  return name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : name == "normal" ? 4 : 3;
}

double pick(const Eigen::Vector3d& v, int component, const Eigen::Vector3d& normal) {
  return component < 3 ? v[component] : component == 3 ? v.norm() : v.dot(normal);
}

}  // namespace

TetProbes::TetProbes(const std::vector<ProbeSettings>& probes, const TetModel& model) {
  const tet::TetSpace& space = *model.space;
  const materials::MaterialLaw& law = *model.law;
  locator_ = std::make_unique<tet::TetLocator>(*model.mesh);
  part_names_ = law.cauchy_part_names();
  const bool mixed = model.problem->formulation() == tet::Formulation::mixed;
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
    if (s.kind == ProbeKind::element_layer)
      throw std::invalid_argument(what +
                                  ": kind = \"element_layer\" checks the knot-span element of a "
                                  "NURBS solid; this run is on tetrahedra (discretisation)");
    if (s.kind == ProbeKind::surface_stability) {
      const Eigen::Vector3d X =
          s.xi ? model.solid.volume.evaluate(model.solid.frame.solid_xi(*s.xi)) : *s.point;
      points_.emplace_back(s.name, X);
      p.surface = checked_probe_location(locate_surface_point(*model.problem, X), law, what);
      notes_.push_back(describe_probe_location(what, p.surface,
                                               space.position(p.surface.element, p.surface.point)));
    }
    if (s.kind == ProbeKind::point_displacement || s.kind == ProbeKind::stress_parts) {
      Eigen::Vector3d X;
      Eigen::Vector3d xi;
      if (s.xi) {
        xi = model.solid.frame.solid_xi(*s.xi);
        X = model.solid.volume.evaluate(xi);
      } else {
        X = *s.point;
        xi = model.inverter->invert(X).xi;
      }
      points_.emplace_back(s.name, X);
      if (p.component == 4) {
        const auto [w0, w1] = model.solid.volume.domain(2);
        if (std::abs(xi[2] - w0) > 1e-9 * (w1 - w0)) {
          throw std::invalid_argument(
              what +
              ": component = \"normal\" needs a point on the boundary surface (the face "
              "w0: xi = [u, v, 0])");
        }
        p.normal = surface_normal(model.solid.volume, xi, what);
      }
      if (s.kind == ProbeKind::point_displacement) {
        const std::optional<tet::TetLocation> at = locator_->locate(X);
        if (!at) {
          throw std::invalid_argument(what + ": point " + describe_point(X) +
                                      " m lies outside the tetrahedral mesh");
        }
        p.location = *at;
      } else {
        double best = std::numeric_limits<double>::infinity();
        for (int e = 0; e < space.num_elements(); ++e)
          for (int q = 0; q < space.points_per_element(); ++q) {
            const double d = (space.position(e, q) - X).squaredNorm();
            if (d < best) {
              best = d;
              p.element = e;
              p.point = q;
            }
          }
      }
    }
    switch (s.kind) {
      case ProbeKind::point_displacement:
      case ProbeKind::volume:
      case ProbeKind::surface_stability:
      case ProbeKind::element_layer:  // refused above
        columns_.push_back(s.name);
        break;
      case ProbeKind::material_ellipticity:
        for (std::string& column : ellipticity_probe_columns(s.name))
          columns_.push_back(std::move(column));
        break;
      case ProbeKind::face_reaction:
        p.nodes = selected_tet_nodes(model, *s.face, what);
        needs_force_ = true;
        columns_.push_back(s.name);
        break;
      case ProbeKind::stress_parts:
        if (parts_from_law_) {
          for (const std::string& part : part_names_)
            if (part != "total")
              columns_.push_back(s.name + "." + part);
        }
        columns_.push_back(s.name + ".total");
        break;
    }
    probes_.push_back(std::move(p));
  }
}

void TetProbes::before_commit(tet::TetProblem& problem, const Eigen::VectorXd& u) {
  if (!needs_force_)
    return;
  const solver::EvaluationStatus status = problem.internal_force(u, force_);
  if (!status.ok)
    throw std::runtime_error("face reaction probes: " + status.message);
  force_ -= problem.external_force();
}

void TetProbes::values(const tet::TetProblem& problem, std::vector<double>& out) const {
  out.assign(columns_.size(), 0.0);
  const Eigen::VectorXd& u = problem.committed_displacement();
  for (const Probe& p : probes_) {
    std::size_t at = p.first_column;
    switch (p.settings.kind) {
      case ProbeKind::point_displacement:
        out[at] = pick(locator_->interpolate(p.location, u), p.component, p.normal);
        break;
      case ProbeKind::face_reaction:
        out[at] = pick(problem.sum_over_nodes(force_, p.nodes), p.component, p.normal);
        break;
      case ProbeKind::volume:
        out[at] = problem.current_volume(u);
        break;
      case ProbeKind::surface_stability:
        out[at] = surface_stability_value(surface_point_at(problem, p.surface));
        break;
      case ProbeKind::element_layer:  // refused at set-up
        break;
      case ProbeKind::material_ellipticity:
        ellipticity_probe_values(committed_ellipticity_of(problem, kEllipticityProbeNormals),
                                 std::span<double>(out).subspan(at, kEllipticityProbeColumns));
        break;
      case ProbeKind::stress_parts: {
        // The converged state at the quadrature point; its parts from the committed (converged)
        // history, a = F N / |F N| (thesis 5.30, 5.41, 3.44).
        const tet::TetPointState st = problem.state_at_point(p.element, p.point);
        const Eigen::Vector3d& a = st.fibre_deformed;
        if (parts_from_law_) {
          const materials::MaterialLaw& law = problem.law();
          materials::PointInput in;
          in.F = st.F;
          in.fibre = st.fibre;
          in.time = problem.committed_time();
          const auto history = problem.committed_history(p.element, p.point);
          std::vector<Eigen::Matrix3d> parts(part_names_.size(), Eigen::Matrix3d::Zero());
          law.cauchy_parts(in, history, parts);
          for (std::size_t i = 0; i < part_names_.size(); ++i) {
            if (part_names_[i] == "total")
              continue;
            if (replace_volumetric_ && part_names_[i] == "vol")
              parts[i] = st.p_bar * Eigen::Matrix3d::Identity();
            out[at++] = a.dot(parts[i] * a);
          }
        }
        out[at] = a.dot(st.cauchy * a);
        break;
      }
    }
  }
}

}  // namespace isomuscle::io
