#include "io/tet_run_setup.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/setting_check.hpp"
#include "io/tet_mesh_size.hpp"
#include "tet/tet_fibres.hpp"
#include "tet/tet_meshing.hpp"
#include "tet/tet_surface_loads.hpp"

namespace isomuscle::io {

namespace {

// Parametric tolerance of "on a face" (fraction of the direction's domain): boundary nodes are
// exactly on the IGES surface (gmsh places them on the geometry), their inversion is accurate to
// ~1e-12 of the solid's size.
constexpr double kFaceTolerance = 1e-6;

// Fibres at the quadrature points by mode (iga/fibre_directions.hpp): the isocurve tangent of the
// solid at the inverted parameters (thesis 5.27-5.30), or the position-only modes evaluated at the
// quadrature points.
std::vector<Eigen::Vector3d> fibres_of(const TetModel& model) {
  const iga::FibreSpec& spec = model.fibre_spec;
  switch (spec.mode) {
    case iga::FibreSpec::Mode::isocurve:
      return tet::nurbs_fibres(*model.space, model.solid.volume, spec.direction);
    case iga::FibreSpec::Mode::constant:
      return tet::constant_fibres(*model.space, spec.vector);
    case iga::FibreSpec::Mode::polyline:
    case iga::FibreSpec::Mode::origin_insertion: {
      // Segments cut at isoparametric surfaces need each point's xi in the solid (inverted only
      // for them); the other position-only modes take the position alone.
      const std::vector<Eigen::Vector3d> xi =
          spec.mode == iga::FibreSpec::Mode::polyline && spec.cut_direction >= 0
              ? tet::quadrature_parameters(*model.space, model.solid.volume)
              : std::vector<Eigen::Vector3d>{};
      std::vector<Eigen::Vector3d> out;
      out.reserve(static_cast<std::size_t>(model.space->num_points()));
      for (int e = 0; e < model.space->num_elements(); ++e)
        for (int q = 0; q < model.space->points_per_element(); ++q) {
          const Eigen::Vector3d& X = model.space->position(e, q);
          out.push_back(xi.empty() ? iga::fibre_direction(spec, Eigen::Matrix3d::Identity(), X)
                                   : iga::fibre_direction(spec, Eigen::Matrix3d::Identity(), X,
                                                          xi[out.size()]));
        }
      return out;
    }
  }
  throw std::logic_error("fibres_of: unknown fibre mode");
}

tet::TetDirichlet condition(const TetModel& model, const BoundarySettings& b, int index) {
  const std::string where = b.where.face ? std::string("face ") + to_string(*b.where.face)
                            : b.where.plane
                                ? "plane through " + describe_point(b.where.plane->point)
                                : "at " + describe_point(b.where.point->point);
  const std::string label =
      "[[boundary]] #" + std::to_string(index + 1) + " (" + to_string(b.type) + ", " + where + ")";
  tet::TetDirichlet c;
  c.nodes = selected_tet_nodes(model, b.where, label);
  switch (b.type) {
    case BoundaryType::fixed:
      c.components = b.components;
      break;
    case BoundaryType::displacement:
      c.components = b.components;
      c.value = [b](const Eigen::Vector3d&, double t) { return b.prescribed_displacement(t); };
      break;
    case BoundaryType::elastic:
      throw std::invalid_argument(label +
                                  ": elastic supports are not offered on tetrahedra yet (the "
                                  "springs are integrated over parametric faces of the NURBS "
                                  "solid; discretisation = \"iga\")");
    case BoundaryType::symmetry: {
      if (!b.where.plane) {
        throw std::invalid_argument(label +
                                    ": on tetrahedra a symmetry condition needs a plane selector "
                                    "{ point, normal } whose normal is a coordinate axis");
      }
      const Eigen::Vector3d n = b.where.plane->normal.normalized();
      int axis = -1;
      for (int d = 0; d < 3; ++d)
        if (std::abs(std::abs(n[d]) - 1.0) < 1e-12)
          axis = d;
      if (axis < 0) {
        throw std::invalid_argument(label +
                                    ": on tetrahedra the plane of a symmetry condition "
                                    "must be normal to x, y or z (got normal " +
                                    describe_point(n) + ")");
      }
      c.components = {axis == 0, axis == 1, axis == 2};
      break;
    }
  }
  return c;
}

}  // namespace

std::vector<int> selected_tet_nodes(const TetModel& model, const FaceSelector& where,
                                    const std::string& what) {
  const tet::TetMesh& mesh = *model.mesh;
  std::vector<int> nodes;
  if (where.face) {
    const iga::Side side = model.solid.frame.solid_side(*where.face);
    const int d = static_cast<int>(side) / 2;
    const auto [lo, hi] = model.solid.volume.domain(d);
    const double target = static_cast<int>(side) % 2 == 0 ? lo : hi;
    for (std::size_t i = 0; i < model.boundary_nodes.size(); ++i) {
      if (std::abs(model.boundary_xi[i][d] - target) <= kFaceTolerance * (hi - lo))
        nodes.push_back(model.boundary_nodes[i]);
    }
    if (nodes.empty()) {
      throw std::invalid_argument(what +
                                  ": no boundary node of the tetrahedral mesh lies on face " +
                                  to_string(*where.face) +
                                  " of the solid (is it the collapsed centreline w1, or the "
                                  "seam u0 / u1 inside a closed surface?)");
    }
  } else if (where.plane) {
    const PlaneSelector& p = *where.plane;
    const Eigen::Vector3d n = p.normal.normalized();
    for (int i = 0; i < mesh.num_nodes(); ++i)
      if (std::abs((mesh.nodes[i] - p.point).dot(n)) <= p.tolerance)
        nodes.push_back(i);
    if (nodes.empty()) {
      throw std::invalid_argument(what + ": no mesh node lies within " +
                                  format_number(p.tolerance) + " m of the plane through " +
                                  describe_point(p.point));
    }
  } else {
    const PointSelector& p = *where.point;
    for (int i = 0; i < mesh.num_nodes(); ++i)
      if ((mesh.nodes[i] - p.point).norm() <= p.tolerance)
        nodes.push_back(i);
    if (nodes.empty()) {
      throw std::invalid_argument(what + ": no mesh node lies within " +
                                  format_number(p.tolerance) + " m of " + describe_point(p.point) +
                                  "; raise 'tolerance' to reach the nearest node");
    }
  }
  return nodes;
}

// Solid -> mesh -> space, law, fibres, conditions -> problem (tet_run_setup.hpp).
TetModel build_tet_model(const Scene& scene, int threads) {
  const GeometrySettings& g = scene.geometry;
  if (g.extracts()) {
    throw std::invalid_argument(
        "[geometry] extract is not offered on tetrahedra: gmsh meshes the "
        "whole IGES shape (run the whole body with symmetry planes or "
        "point supports instead)");
  }
  if (g.construction == Construction::extrude) {
    throw std::invalid_argument(
        "[geometry] construction = \"extrude\" is not offered on "
        "tetrahedra: the open IGES sheet bounds no volume for gmsh");
  }
  if (!scene.loads.empty()) {
    throw std::invalid_argument(
        "[[load]] is not offered on tetrahedra yet (loads are integrated "
        "over parametric faces of the NURBS solid)");
  }
  TetModel model;
  model.solid = build_scene_solid(g);
  model.inverter = std::make_unique<geometry::PointInverter>(model.solid.volume);
  const TetrahedraSettings& t = scene.tetrahedra;
  if (t.mesh.empty()) {
    tet::MeshingOptions mo;
    mo.element_size = t.element_size;
    mo.order = t.order;
    mo.quadrature_degree = t.quadrature_degree;
    set_face_refinement(mo, model.solid, t.refine);
    for (const TetRefinement& r : t.refine) {
      model.notes.push_back("elements refined near face " + std::string(to_string(r.face)) + ": " +
                            format_number(r.size) + " m on it, growing to element_size " +
                            format_number(t.element_size) + " m over " + format_number(r.distance) +
                            " m");
    }
    int straightened = 0;
    model.mesh = std::make_unique<tet::TetMesh>(tet::mesh_iges(g.iges, mo, &straightened));
    if (straightened > 0) {
      model.notes.push_back(
          std::to_string(straightened) + " of " + std::to_string(model.mesh->num_elements()) +
          " 10-node tetrahedra folded over where gmsh curved them onto the boundary and were "
          "made straight-sided (the surface turns faster than element_size resolves; a smaller "
          "element_size keeps more of the curvature)");
    }
  } else {
    model.mesh = std::make_unique<tet::TetMesh>(tet::read_msh(t.mesh, t.mesh_unit));
    if (model.mesh->order != t.order) {
      throw std::invalid_argument(
          "[tetrahedra] order = " + std::to_string(t.order) + ": " + t.mesh.string() + " holds " +
          std::to_string(model.mesh->nodes_per_element()) + "-node tetrahedra");
    }
  }
  if (g.refine.degree_elevation != std::array<int, 3>{0, 0, 0} ||
      g.refine.knot_insertion != std::array<int, 3>{0, 0, 0} ||
      !(g.refine.knots[0].empty() && g.refine.knots[1].empty() && g.refine.knots[2].empty()) ||
      g.refine.continuity) {
    model.notes.push_back(
        "[geometry.refine] does not apply to tetrahedra (the mesh is set by "
        "[tetrahedra]); the NURBS solid is used unrefined for fibres and faces");
  }
  model.space = std::make_unique<tet::TetSpace>(*model.mesh, t.quadrature_degree);
  model.law = make_law(scene.material, scene.solver.tangent);

  // Parameters of the boundary nodes in the solid, for face selection.
  for (int f = 0; f < model.mesh->num_boundary_faces(); ++f)
    for (int n : model.mesh->face(f))
      model.boundary_nodes.push_back(n);
  std::sort(model.boundary_nodes.begin(), model.boundary_nodes.end());
  model.boundary_nodes.erase(std::unique(model.boundary_nodes.begin(), model.boundary_nodes.end()),
                             model.boundary_nodes.end());
  for (int n : model.boundary_nodes)
    model.boundary_xi.push_back(model.inverter->invert(model.mesh->nodes[n]).xi);

  model.fibre_spec = fibre_spec(scene.fibres, model.solid.frame, model.solid.volume);
  std::vector<Eigen::Vector3d> fibres = fibres_of(model);
  std::vector<tet::TetDirichlet> conditions;
  for (std::size_t i = 0; i < scene.boundaries.size(); ++i)
    conditions.push_back(condition(model, scene.boundaries[i], static_cast<int>(i)));

  tet::TetProblemOptions options;
  options.threads = threads;
  options.formulation = scene.solver.formulation == Formulation::mixed
                            ? tet::Formulation::mixed
                            : tet::Formulation::displacement;
  if (options.formulation == tet::Formulation::mixed && !model.law->has_volumetric_split()) {
    options.formulation = tet::Formulation::displacement;
    model.notes.push_back("law '" + model.law->name() +
                          "' has no volumetric split: the mixed u-p-J formulation does not apply, "
                          "using the displacement formulation");
  }
  model.failure_hint =
      displacement_locking_hint(*model.law, options.formulation == tet::Formulation::displacement);
  if (!model.failure_hint.empty())
    model.notes.push_back(model.failure_hint);
  if (options.formulation == tet::Formulation::mixed && model.mesh->order == 1) {
    model.notes.push_back(
        "4-node tetrahedra with the mixed formulation: a constant p~, J~ per "
        "element is the displacement formulation again and locks; use order 2");
  }
  model.problem =
      std::make_unique<tet::TetProblem>(*model.space, *model.law, std::move(fibres),
                                        std::move(conditions), tet::VectorField{}, options);
  return model;
}

}  // namespace isomuscle::io
