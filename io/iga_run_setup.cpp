#include "io/iga_run_setup.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "geometry/refinement.hpp"
#include "io/setting_check.hpp"

namespace isomuscle::io {

namespace {

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
    case BoundaryType::elastic:
      // Springs are integrated over the face (iga/elastic_support.hpp): a parametric face.
      if (!b.where.face) {
        throw std::invalid_argument(label +
                                    ": an elastic support acts on a parametric face of the solid "
                                    "(face = \"u0\" ... \"w1\"), not on a plane or a point");
      }
      model.supports.push_back(
          {label, model.frame.solid_side(*b.where.face), b.stiffness, b.components});
      break;
  }
}

}  // namespace

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

// The knot of `volume` in direction d within round-off (1e-12 of the domain's length) of t, if
// any: a uniform refinement computes its knots, so a knot meant to be at t need not be exactly t.
std::optional<double> knot_near(const geometry::NurbsVolume& volume, int d, double t) {
  const auto [lo, hi] = volume.domain(d);
  for (double knot : volume.knots(d).breakpoints()) {
    if (std::abs(knot - t) <= 1e-12 * (hi - lo))
      return knot;
  }
  return std::nullopt;
}

// The scene's explicit knots say where the mesh has element faces: a value that is already a knot
// of the refined solid (knot_near) is left out, not inserted once more, which would lower the
// continuity there instead of refining. So a graded mesh can be written as the list of all its
// knots, the solid's own among them (the DAO's centreline has knots at 1/3 and 2/3), and a
// refinement study can halve every span of that list.
std::vector<double> knots_not_yet_there(const geometry::NurbsVolume& volume, int d,
                                        const std::vector<double>& knots) {
  std::vector<double> fresh;
  for (double t : knots) {
    if (!knot_near(volume, d, t))
      fresh.push_back(t);
  }
  return fresh;
}

// "Method 1" segments (fibre_directions.hpp) are pieces of different fibre direction meeting at
// isoparametric surfaces: the active stress jumps there and the strain has a kink, which a basis
// that is C^1 or smoother across the cut cannot follow (the error then decays slowly and not
// monotonically). Each cut becomes a knot of multiplicity p, so the pieces meet at C^0 element
// faces, as the parts of a mesh do. A knot already at the cut to round-off (knot_near) is raised
// in place, so no span of round-off length is made.
geometry::NurbsVolume with_c0_segment_cuts(geometry::NurbsVolume volume,
                                           const iga::FibreSpec& spec) {
  if (spec.mode != iga::FibreSpec::Mode::polyline || spec.cut_direction < 0)
    return volume;
  const int d = spec.cut_direction;
  for (double cut : spec.cuts) {
    cut = knot_near(volume, d, cut).value_or(cut);
    const int missing = volume.degree(d) - volume.knots(d).multiplicity(cut);
    if (missing > 0)
      volume = geometry::insert_knot(volume, d, cut, missing);
  }
  return volume;
}

// [geometry.refine] continuity = c: every interior knot raised to multiplicity p - c, so the basis
// is C^c across every element face (c = 0: the Lagrange FE space of degree p on the same elements;
// the geometry and the elements do not change, knot insertion is exact). Throws
// std::invalid_argument when c is not below the degree in some direction.
geometry::NurbsVolume with_continuity(geometry::NurbsVolume volume, int continuity,
                                      const SceneFrame& frame) {
  std::string degrees;
  for (int d = 0; d < 3; ++d)
    degrees += (d ? ", " : "") + std::to_string(volume.degree(frame.solid(Direction(d))));
  for (int d = 0; d < 3; ++d) {
    const int s = frame.solid(Direction(d));
    const int multiplicity = volume.degree(s) - continuity;
    if (multiplicity < 1) {
      throw std::invalid_argument("[geometry.refine] continuity = " + std::to_string(continuity) +
                                  " must be below the degree in every direction; the refined "
                                  "solid has degree (" +
                                  degrees + ") in u, v, w");
    }
    // All missing copies at once: one refinement pass per direction, not one per knot.
    const geometry::KnotVector& knots = volume.knots(s);
    const std::vector<double> breaks = knots.breakpoints();
    std::vector<double> missing;
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
      missing.insert(
          missing.end(),
          static_cast<std::size_t>(std::max(0, multiplicity - knots.multiplicity(breaks[i]))),
          breaks[i]);
    if (!missing.empty())
      volume = geometry::refine_knots(volume, s, missing);
  }
  return volume;
}

// Geometry -> solid -> refinement -> space, DOFs, fibres, law, conditions -> problem (the data flow
// of DESIGN.md; thesis 5.13-5.15 for the solid, 5.27-5.30 for the fibres).
IgaModel build_iga_model(const Scene& scene, int threads) {
  IgaModel model;
  const GeometrySettings& g = scene.geometry;

  // IGES surface -> shrink solid or extruded sheet (scene_solid.hpp).
  SceneSolid solid = build_scene_solid(g);
  model.unrefined = std::move(solid.volume);
  model.frame = solid.frame;
  const SceneFrame& frame = model.frame;

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
  for (int d = 0; d < 3; ++d) {
    const std::vector<double>& t = g.refine.knots[static_cast<std::size_t>(d)];
    if (t.empty())
      continue;
    const int s = frame.solid_direction[static_cast<std::size_t>(d)];
    std::vector<double> solid_knots;
    for (double scene_t : t) {
      Eigen::Vector3d xi = Eigen::Vector3d::Constant(0.5);
      xi[d] = scene_t;
      solid_knots.push_back(frame.solid_xi(xi)[s]);
    }
    std::sort(solid_knots.begin(), solid_knots.end());  // a reversed direction reverses them
    const std::vector<double> fresh = knots_not_yet_there(volume, s, solid_knots);
    if (!fresh.empty())
      volume = geometry::refine_knots(volume, s, fresh);
  }
  if (g.refine.continuity)
    volume = with_continuity(std::move(volume), *g.refine.continuity, frame);
  model.fibre_spec = fibre_spec(scene.fibres, frame, volume);
  model.space =
      std::make_unique<iga::Space>(with_c0_segment_cuts(std::move(volume), model.fibre_spec));
  model.dofs = std::make_unique<iga::DofMap>(model.space->volume());

  // Material, fibres, boundary conditions.
  model.law = make_law(scene.material, scene.solver.tangent);
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
  model.failure_hint =
      displacement_locking_hint(*model.law, options.formulation == iga::Formulation::displacement);
  if (!model.failure_hint.empty())
    model.notes.push_back(model.failure_hint);
  model.problem =
      std::make_unique<iga::Problem>(*model.space, *model.dofs, *model.law, std::move(fibres),
                                     model.conditions, std::move(loads), options);
  if (!model.supports.empty())
    model.problem->set_elastic_supports(model.supports);
  return model;
}

}  // namespace isomuscle::io
