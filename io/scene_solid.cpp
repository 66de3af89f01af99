// The solid of a scene before refinement (scene_solid.hpp).
#include "io/scene_solid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "geometry/extrusion.hpp"
#include "geometry/fibre_field.hpp"
#include "geometry/gauss_legendre.hpp"
#include "geometry/iges.hpp"
#include "geometry/refinement.hpp"
#include "geometry/shrink.hpp"
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

}  // namespace

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
      // Piece i is lo + (hi - lo) [i, i + 1] / n along d, its fibre the chord between the
      // centroids of its end sections.
      std::vector<Eigen::Vector3d> points;
      std::vector<double> cuts;
      for (int i = 0; i <= f.segments; ++i) {
        const double t = lo + (hi - lo) * i / f.segments;
        points.push_back(isoparametric_centroid(volume, d, t));
        if (i > 0 && i < f.segments)
          cuts.push_back(t);
      }
      return iga::FibreSpec::segments_cut_at(std::move(points), d, std::move(cuts));
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

namespace {

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

// Outward unit normal of the face w = 0 (the boundary surface; w runs inwards, towards the
// centreline of a shrink solid, or through the thickness of an extruded sheet) at xi:
// n = +-(H_u x H_v) / |H_u x H_v|, the sign making n . H_w < 0.
Eigen::Vector3d surface_normal(const geometry::NurbsVolume& v, const Eigen::Vector3d& xi,
                               const std::string& what) {
  const Eigen::Matrix3d J = v.jacobian(xi);
  Eigen::Vector3d n = J.col(0).cross(J.col(1));
  const double length = n.norm();
  if (!(length > 0.0)) {
    throw std::invalid_argument(what + ": the surface has no normal at xi = " + describe_point(xi) +
                                " (a collapsed edge)");
  }
  n /= length;
  return n.dot(J.col(2)) < 0.0 ? n : Eigen::Vector3d(-n);
}

SceneSolid build_scene_solid(const GeometrySettings& g) {
  SceneSolid out;
  // IGES surface -> shrink solid or extruded sheet.
  std::vector<geometry::IgesSurface> surfaces = geometry::read_iges_surfaces(g.iges);
  if (g.surface < 0 || g.surface >= static_cast<int>(surfaces.size())) {
    throw std::invalid_argument("[geometry] surface = " + std::to_string(g.surface) + ": " +
                                g.iges.string() + " holds " + std::to_string(surfaces.size()) +
                                " B-spline surface(s), valid indices 0.." +
                                std::to_string(surfaces.size() - 1));
  }
  const geometry::NurbsSurface& surface = surfaces[static_cast<std::size_t>(g.surface)].surface;
  SceneFrame& frame = out.frame;
  if (g.construction == Construction::extrude) {
    try {
      geometry::Extrusion sheet = geometry::extrude(surface, g.extrusion);
      out.volume = std::move(sheet.volume);
      frame.reversed[0] = sheet.u_reversed;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(g.iges.string() + ", surface " + std::to_string(g.surface) +
                                  " extruded by " + describe_point(g.extrusion) + ": " + e.what());
    }
  } else {
    const int closed_direction = g.centreline == Direction::v ? 0 : 1;
    try {
      out.volume = geometry::shrink_to_centreline(surface, closed_direction);
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
        around_reversed(surface, closed_direction, out.volume);
  }
  for (int d = 0; d < 3; ++d)
    frame.domain[static_cast<std::size_t>(d)] = out.volume.domain(d);
  if (g.extracts())
    out.volume = extract_piece(out.volume, g, frame);
  return out;
}

std::string displacement_locking_hint(const materials::MaterialLaw& law, bool displacement) {
  const double mu = law.shear_modulus(), kappa = law.bulk_modulus();
  if (!displacement || !(mu > 0.0) || !(kappa >= 100.0 * mu))
    return {};
  std::ostringstream msg;
  msg << std::setprecision(2) << "the displacement formulation with kappa/mu = " << kappa / mu
      << " (nearly incompressible) locks and is ill-conditioned; [solver] formulation = \"mixed\""
      << " is the formulation for this law";
  return msg.str();
}

}  // namespace isomuscle::io
