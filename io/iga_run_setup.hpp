#pragma once
// From a scene to an isogeometric model ready to step (DESIGN "The way data flows in an IGA run"):
//
//   IGES surface -> shrink_to_centreline (thesis 5.13-5.15) -> exact refinement (degree elevation,
//   then knot insertion: k-refinement, thesis 5.3) -> iga::Space + iga::DofMap (coincident seam
//   and axis control points merged) -> fibres (thesis 5.27-5.30) -> material law (factory) ->
//   Dirichlet conditions -> iga::Problem.
//
// Parametric names in a scene. The scene names the directions as the IGES SURFACE does, plus w:
// `centreline` says which surface direction (u or v) runs along the muscle, the other one closes
// around it, and w runs from the surface (w = 0) to the collapsed centreline (w = 1). The shrink
// solid always puts "around" first and "along" second (geometry/shrink.hpp), so for a surface with
// centreline = "v" (all files in examples/geometry) the scene's u, v, w are the solid's; for
// centreline = "u" the scene's u is the solid's v and vice versa. Faces (u0 ... w1), refinement
// counts, fibre directions and probe coordinates xi (in [0, 1] per direction, scaled to the knot
// domain) all follow this naming. Where the shrink construction reversed the direction around the
// centreline (to keep det J > 0), xi is mirrored in it and u0/u1 are exchanged, so a scene always
// means the surface's own parametrisation.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "geometry/nurbs_volume.hpp"
#include "iga/boundary_conditions.hpp"
#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga/space.hpp"
#include "io/scene.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::io {

// The map from a scene's parametric names to the solid's directions (see above).
struct SceneFrame {
  std::array<int, 3> solid_direction{0, 1, 2};  // scene direction (u, v, w) -> solid direction
  std::array<bool, 3> reversed{false, false, false};  // per SOLID direction
  std::array<std::array<double, 2>, 3> domain{};      // knot domain per SOLID direction

  int solid(Direction d) const { return solid_direction[static_cast<std::size_t>(d)]; }
  iga::Side solid_side(Face f) const;
  // Scene parametric point in [0, 1]^3 -> parameters of the solid (knot domain).
  Eigen::Vector3d solid_xi(const Eigen::Vector3d& scene_xi) const;
};

// Everything a run keeps alive: the Problem refers to the space, DOF map and law, so they are held
// by pointer and never move.
struct IgaModel {
  geometry::NurbsVolume unrefined;  // the shrink solid (its [geometry] extract piece) unrefined
  SceneFrame frame;
  std::unique_ptr<iga::Space> space;
  std::unique_ptr<iga::DofMap> dofs;
  std::unique_ptr<materials::MaterialLaw> law;
  iga::FibreSpec fibre_spec;
  iga::DirichletConditions conditions;
  std::unique_ptr<iga::Problem> problem;
  std::vector<std::string> notes;  // decisions a user should know about, for the log
};

// Builds the model of a scene (checked by Scene::validate beforehand). threads: assembly threads
// (0 = all cores). Throws std::runtime_error / std::invalid_argument with a message naming the
// scene setting at fault (IGES file, surface index, face, material parameter, ...).
IgaModel build_iga_model(const Scene& scene, int threads);

// "(x, y, z)" with the shortest exact numbers, for messages.
std::string describe_point(const Eigen::Vector3d& x);

// The nodes a face selector picks: a parametric face, or the control points within tolerance of a
// plane. Throws std::invalid_argument (naming `what`) when the selection is empty.
std::vector<int> selected_nodes(const IgaModel& model, const FaceSelector& where,
                                const std::string& what);

}  // namespace isomuscle::io
