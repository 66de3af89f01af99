#include "io/iga_run_setup.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "geometry/extrusion.hpp"
#include "geometry/fibre_field.hpp"
#include "geometry/iges.hpp"
#include "geometry/refinement.hpp"
#include "geometry/shrink.hpp"
#include "geometry/volume_measures.hpp"
#include "io/setting_check.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::io {

namespace {

constexpr int kCentroidGaussPoints = 4;  // per knot span and direction, for segment end points

iga::Side side_of(int solid_direction, int end) {
  static constexpr iga::Side sides[3][2] = {{iga::Side::u0, iga::Side::u1},
                                            {iga::Side::v0, iga::Side::v1},
                                            {iga::Side::w0, iga::Side::w1}};
  return sides[solid_direction][end];
}

// Whether the shrink construction reversed the surface's closed direction: the solid's w = 0 face
// is the surface, H(a', b, 0) = B(a, b) with a' = a (kept) or a' = lo + hi - a (reversed).
bool around_reversed(const geometry::NurbsSurface& surface, int closed_direction,
                     const geometry::NurbsVolume& volume) {
  const geometry::KnotVector& kc = closed_direction == 0 ? surface.knots_u() : surface.knots_v();
  const geometry::KnotVector& ka = closed_direction == 0 ? surface.knots_v() : surface.knots_u();
  const double lo = kc.domain_begin(), hi = kc.domain_end();
  const double a = lo + 0.3 * (hi - lo);
  const double b = ka.domain_begin() + 0.4 * (ka.domain_end() - ka.domain_begin());
  const Eigen::Vector3d on_surface =
      closed_direction == 0 ? surface.evaluate(a, b) : surface.evaluate(b, a);
  const double kept = (volume.evaluate({a, b, volume.domain(2)[0]}) - on_surface).norm();
  const double flipped =
      (volume.evaluate({lo + hi - a, b, volume.domain(2)[0]}) - on_surface).norm();
  return flipped < kept;
}

// Centroid of the isoparametric surface xi_d = t of a solid (area-weighted, Gauss quadrature in
// every knot span of the other two directions), m: the end points of fibre segments ("method 1",
// thesis 5.6.4), which on a shrink solid cut along the centreline lie on the centreline.
Eigen::Vector3d isoparametric_centroid(const geometry::NurbsVolume& volume, int d, double t) {
  const int a = (d + 1) % 3, b = (d + 2) % 3;
  const geometry::GaussLegendreRule rule = geometry::gauss_legendre_rule(kCentroidGaussPoints);
  const std::vector<double> ka = volume.knots(a).breakpoints();
  const std::vector<double> kb = volume.knots(b).breakpoints();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < ka.size(); ++i) {
    for (std::size_t j = 0; j + 1 < kb.size(); ++j) {
      const double ha = 0.5 * (ka[i + 1] - ka[i]), hb = 0.5 * (kb[j + 1] - kb[j]);
      for (std::size_t p = 0; p < rule.points.size(); ++p) {
        for (std::size_t q = 0; q < rule.points.size(); ++q) {
          Eigen::Vector3d xi;
          xi[d] = t;
          xi[a] = ka[i] + ha * (1.0 + rule.points[p]);
          xi[b] = kb[j] + hb * (1.0 + rule.points[q]);
          Eigen::Vector3d x;
          Eigen::Matrix3d jac;
          volume.evaluate_with_jacobian(xi, x, jac);
          const double dA =
              jac.col(a).cross(jac.col(b)).norm() * ha * hb * rule.weights[p] * rule.weights[q];
          moment += dA * x;
          area += dA;
        }
      }
    }
  }
  if (!(area > 0.0)) {
    throw std::invalid_argument("fibres: the isoparametric surface at " +
                                std::string(geometry::parametric_direction_name(d)) + " = " +
                                format_number(t) + " has zero area; segments cannot be built");
  }
  return moment / area;
}

iga::FibreSpec fibre_spec(const FibreSettings& f, const SceneFrame& frame,
                          const geometry::NurbsVolume& volume) {
  switch (f.mode) {
    case FibreMode::isocurve:
      return iga::FibreSpec::isocurve(frame.solid(f.direction));
    case FibreMode::constant:
      return iga::FibreSpec::constant(f.vector.normalized());
    case FibreMode::segments: {
      const int d = frame.solid(f.direction);
      const auto [lo, hi] = volume.domain(d);
      std::vector<Eigen::Vector3d> points;
      for (int i = 0; i <= f.segments; ++i) {
        points.push_back(isoparametric_centroid(volume, d, lo + (hi - lo) * i / f.segments));
      }
      return iga::FibreSpec::segments(std::move(points));
    }
    case FibreMode::line:
      return iga::FibreSpec::origin_to_insertion(f.origin, f.insertion);
  }
  throw std::logic_error("fibre_spec: unknown fibre mode");
}

// The material law with the scene's tangent choice: frozen_ce is the Hill laws' parameter
// frozen_ce_tangent = 1 (thesis 5.54, CE length frozen within the step).
std::unique_ptr<materials::MaterialLaw> make_law(const MaterialSettings& m, TangentKind tangent) {
  std::map<std::string, double> parameters = m.parameters;
  const auto& specs = materials::material_parameters(m.model);
  const bool has_switch = std::any_of(specs.begin(), specs.end(),
                                      [](const auto& s) { return s.name == "frozen_ce_tangent"; });
  const double wanted = tangent == TangentKind::frozen_ce ? 1.0 : 0.0;
  if (has_switch) {
    const auto given = parameters.find("frozen_ce_tangent");
    if (given != parameters.end() && given->second != wanted) {
      throw std::invalid_argument(
          "[material.parameters] frozen_ce_tangent = " + format_number(given->second) +
          " contradicts [solver] tangent = \"" + to_string(tangent) +
          "\"; set the tangent in [solver] only");
    }
    parameters["frozen_ce_tangent"] = wanted;
  } else if (tangent == TangentKind::frozen_ce) {
    throw std::invalid_argument(
        "[solver] tangent = \"frozen_ce\" applies only to the Hill muscle "
        "laws (lu2010, tang2009), not to '" +
        m.model + "'; use tangent = \"consistent\"");
  }
  return materials::make_material(m.model, parameters);
}

// Unit normal of the plane through the control points of a face; std::invalid_argument when they
// do not lie in one plane (a symmetry condition needs a plane face).
Eigen::Vector3d face_plane_normal(const geometry::NurbsVolume& volume, std::span<const int> cps,
                                  const std::string& what) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i : cps)
    mean += volume.points()[i];
  mean /= static_cast<double>(cps.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i : cps) {
    const Eigen::Vector3d d = volume.points()[i] - mean;
    scatter.noalias() += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d normal = eig.eigenvectors().col(0);
  const auto [lo, hi] = volume.bounding_box();
  const double size = (hi - lo).norm();
  double off = 0.0;
  for (int i : cps)
    off = std::max(off, std::abs((volume.points()[i] - mean).dot(normal)));
  if (off > 1e-8 * size) {
    throw std::invalid_argument(what +
                                ": a symmetry condition needs a plane face, but its control "
                                "points lie up to " +
                                format_number(off) +
                                " m off their best plane; select the face by a plane instead");
  }
  return normal;
}

void add_boundary(IgaModel& model, const BoundarySettings& b, int index) {
  const std::string where = b.where.face ? std::string("face ") + to_string(*b.where.face)
                            : b.where.plane
                                ? "plane through " + describe_point(b.where.plane->point)
                                : "at " + describe_point(b.where.point->point);
  const std::string label =
      "[[boundary]] #" + std::to_string(index + 1) + " (" + to_string(b.type) + ", " + where + ")";
  std::vector<int> nodes = selected_nodes(model, b.where, label);
  switch (b.type) {
    case BoundaryType::fixed:
      model.conditions.fix(label, std::move(nodes), b.components);
      break;
    case BoundaryType::displacement:
      model.conditions.prescribe(
          label, std::move(nodes),
          [b](const Eigen::Vector3d&, double t) { return b.prescribed_displacement(t); },
          b.components);
      break;
    case BoundaryType::symmetry: {
      Eigen::Vector3d normal;
      if (b.where.point) {
        throw std::invalid_argument(label +
                                    ": a symmetry condition needs a face or a plane, "
                                    "not a point");
      }
      if (b.where.plane) {
        normal = b.where.plane->normal.normalized();
      } else {
        const geometry::NurbsVolume& v = model.space->volume();
        normal = face_plane_normal(
            v, iga::side_control_points(v, model.frame.solid_side(*b.where.face)), label);
      }
      model.conditions.symmetry(label, std::move(nodes), normal);
      break;
    }
  }
}

// [geometry] extract: the solid restricted to the scene's parameter sub-ranges (fractions of the
// knot domain in scene naming, mirrored where the frame reverses a direction), cut exactly by knot
// insertion to full multiplicity (Piegl & Tiller 5.3, geometry::extract); the parameter values are
// kept, so frame.domain becomes the piece's domain and xi / faces refer to the piece.
geometry::NurbsVolume extract_piece(const geometry::NurbsVolume& solid, const GeometrySettings& g,
                                    SceneFrame& frame) {
  geometry::NurbsVolume piece = solid;
  for (int d = 0; d < 3; ++d) {
    auto [a, b] = g.extract[static_cast<std::size_t>(d)];
    if (a == 0.0 && b == 1.0)
      continue;
    const int s = frame.solid_direction[static_cast<std::size_t>(d)];
    auto& domain = frame.domain[static_cast<std::size_t>(s)];
    if (frame.reversed[static_cast<std::size_t>(s)]) {
      const double lower = 1.0 - b;
      b = 1.0 - a;
      a = lower;
    }
    const double lo = domain[0] + a * (domain[1] - domain[0]);
    const double hi = domain[0] + b * (domain[1] - domain[0]);
    try {
      piece = geometry::extract(piece, s, lo, hi);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("[geometry] extract.") +
                                  to_string(static_cast<Direction>(d)) + ": " + e.what());
    }
    domain = piece.domain(s);
  }
  return piece;
}

}  // namespace

std::string describe_point(const Eigen::Vector3d& x) {
  std::string s = "(";
  s += format_number(x.x());
  s += ", ";
  s += format_number(x.y());
  s += ", ";
  s += format_number(x.z());
  s += ")";
  return s;
}

iga::Side SceneFrame::solid_side(Face f) const {
  const int scene_dir = static_cast<int>(f) / 2;
  int end = static_cast<int>(f) % 2;
  const int s = solid_direction[static_cast<std::size_t>(scene_dir)];
  if (reversed[static_cast<std::size_t>(s)])
    end = 1 - end;
  return side_of(s, end);
}

Eigen::Vector3d SceneFrame::solid_xi(const Eigen::Vector3d& scene_xi) const {
  Eigen::Vector3d xi;
  for (int d = 0; d < 3; ++d) {
    const std::size_t s = static_cast<std::size_t>(solid_direction[static_cast<std::size_t>(d)]);
    const double t = reversed[s] ? 1.0 - scene_xi[d] : scene_xi[d];
    xi[static_cast<Eigen::Index>(s)] = domain[s][0] + t * (domain[s][1] - domain[s][0]);
  }
  return xi;
}

std::vector<int> selected_nodes(const IgaModel& model, const FaceSelector& where,
                                const std::string& what) {
  const geometry::NurbsVolume& volume = model.space->volume();
  std::vector<int> cps;
  if (where.face) {
    cps = iga::side_control_points(volume, model.frame.solid_side(*where.face));
  } else if (where.point) {
    const PointSelector& p = *where.point;
    for (int i = 0; i < volume.num_control_points(); ++i) {
      if ((volume.points()[i] - p.point).norm() <= p.tolerance)
        cps.push_back(i);
    }
    if (cps.empty()) {
      throw std::invalid_argument(what + ": no control point lies within " +
                                  format_number(p.tolerance) + " m of " + describe_point(p.point) +
                                  "; the point must be a control point of the refined solid "
                                  "(isomuscle geometry solid --json lists them), or raise "
                                  "'tolerance'");
    }
  } else {
    const PlaneSelector& p = *where.plane;
    cps = iga::plane_control_points(volume, p.point, p.normal, p.tolerance);
    if (cps.empty()) {
      throw std::invalid_argument(
          what + ": no control point lies within " + format_number(p.tolerance) +
          " m of the plane through " + describe_point(p.point) + " with normal " +
          describe_point(p.normal) + "; check the plane or raise 'tolerance'");
    }
  }
  return iga::nodes_of(*model.dofs, cps);
}

// Geometry -> solid -> refinement -> space, DOFs, fibres, law, conditions -> problem (the data flow
// of DESIGN.md; thesis 5.13-5.15 for the solid, 5.27-5.30 for the fibres).
IgaModel build_iga_model(const Scene& scene, int threads) {
  IgaModel model;
  const GeometrySettings& g = scene.geometry;

  // IGES surface -> shrink solid or extruded sheet.
  std::vector<geometry::IgesSurface> surfaces = geometry::read_iges_surfaces(g.iges);
  if (g.surface < 0 || g.surface >= static_cast<int>(surfaces.size())) {
    throw std::invalid_argument("[geometry] surface = " + std::to_string(g.surface) + ": " +
                                g.iges.string() + " holds " + std::to_string(surfaces.size()) +
                                " B-spline surface(s), valid indices 0.." +
                                std::to_string(surfaces.size() - 1));
  }
  const geometry::NurbsSurface& surface = surfaces[static_cast<std::size_t>(g.surface)].surface;
  SceneFrame& frame = model.frame;
  if (g.construction == Construction::extrude) {
    try {
      geometry::Extrusion sheet = geometry::extrude(surface, g.extrusion);
      model.unrefined = std::move(sheet.volume);
      frame.reversed[0] = sheet.u_reversed;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(g.iges.string() + ", surface " + std::to_string(g.surface) +
                                  " extruded by " + describe_point(g.extrusion) + ": " + e.what());
    }
  } else {
    const int closed_direction = g.centreline == Direction::v ? 0 : 1;
    try {
      model.unrefined = geometry::shrink_to_centreline(surface, closed_direction);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(g.iges.string() + ", surface " + std::to_string(g.surface) +
                                  " with centreline = \"" + to_string(g.centreline) +
                                  "\": " + e.what());
    }
    if (g.centreline == Direction::u) {
      frame.solid_direction = {geometry::kAlongCentreline, geometry::kAroundCentreline,
                               geometry::kTowardsCentreline};
    }
    frame.reversed[geometry::kAroundCentreline] =
        around_reversed(surface, closed_direction, model.unrefined);
  }
  for (int d = 0; d < 3; ++d)
    frame.domain[static_cast<std::size_t>(d)] = model.unrefined.domain(d);
  if (g.extracts())
    model.unrefined = extract_piece(model.unrefined, g, frame);

  // Exact refinement: degree elevation first, then knot insertion (k-refinement, thesis 5.3).
  geometry::NurbsVolume volume = model.unrefined;
  for (int d = 0; d < 3; ++d) {
    const int s = frame.solid_direction[static_cast<std::size_t>(d)];
    if (g.refine.degree_elevation[static_cast<std::size_t>(d)] > 0)
      volume = geometry::elevate_degree(volume, s,
                                        g.refine.degree_elevation[static_cast<std::size_t>(d)]);
  }
  for (int d = 0; d < 3; ++d) {
    const int s = frame.solid_direction[static_cast<std::size_t>(d)];
    if (g.refine.knot_insertion[static_cast<std::size_t>(d)] > 0)
      volume =
          geometry::refine_uniform(volume, s, g.refine.knot_insertion[static_cast<std::size_t>(d)]);
  }
  model.space = std::make_unique<iga::Space>(std::move(volume));
  model.dofs = std::make_unique<iga::DofMap>(model.space->volume());

  // Material, fibres, boundary conditions.
  model.law = make_law(scene.material, scene.solver.tangent);
  model.fibre_spec = fibre_spec(scene.fibres, frame, model.space->volume());
  std::vector<Eigen::Vector3d> fibres = iga::fibre_directions(*model.space, model.fibre_spec);
  for (std::size_t i = 0; i < scene.boundaries.size(); ++i) {
    add_boundary(model, scene.boundaries[i], static_cast<int>(i));
  }

  iga::Loads loads;
  for (std::size_t i = 0; i < scene.loads.size(); ++i) {
    const LoadSettings& l = scene.loads[i];
    const std::string label = "[[load]] #" + std::to_string(i + 1) + " (" + to_string(l.type) +
                              ", face " + to_string(l.face) + ")";
    loads.surface.push_back(
        {label, frame.solid_side(l.face), [l](const Eigen::Vector3d&, double t) -> Eigen::Vector3d {
           return l.factor(t) * l.traction;
         }});
  }

  iga::ProblemOptions options;
  options.threads = threads;
  options.formulation = scene.solver.formulation == Formulation::mixed
                            ? iga::Formulation::mixed
                            : iga::Formulation::displacement;
  if (options.formulation == iga::Formulation::mixed && !model.law->has_volumetric_split()) {
    options.formulation = iga::Formulation::displacement;
    model.notes.push_back("law '" + model.law->name() +
                          "' has no volumetric split: the mixed u-p-J formulation does not apply, "
                          "using the displacement formulation");
  }
  model.problem =
      std::make_unique<iga::Problem>(*model.space, *model.dofs, *model.law, std::move(fibres),
                                     model.conditions, std::move(loads), options);
  return model;
}

}  // namespace isomuscle::io
