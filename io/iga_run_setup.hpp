#pragma once
// From a scene to an isogeometric model ready to step (DESIGN "The way data flows in an IGA run"):
//
//   IGES surface -> shrink_to_centreline (thesis 5.13-5.15) or extrusion (scene_solid.hpp) ->
//   exact refinement (degree elevation,
//   then knot insertion: k-refinement, thesis 5.3) -> iga::Space + iga::DofMap (coincident seam
//   and axis control points merged) -> fibres (thesis 5.27-5.30) -> material law (factory) ->
//   Dirichlet conditions -> iga::Problem.
//
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
#include "io/scene_solid.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::io {

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
  std::vector<iga::ElasticSupport> supports;  // [[boundary]] type = "elastic"
  std::unique_ptr<iga::Problem> problem;
  std::vector<std::string> notes;  // decisions a user should know about, for the log
  std::string failure_hint;        // appended to the reason of a failed run (empty: none)
};

// Builds the model of a scene (checked by Scene::validate beforehand). threads: assembly threads
// (0 = all cores). Throws std::runtime_error / std::invalid_argument with a message naming the
// scene setting at fault (IGES file, surface index, face, material parameter, ...).
IgaModel build_iga_model(const Scene& scene, int threads);

// The nodes a face selector picks: a parametric face, or the control points within tolerance of a
// plane. Throws std::invalid_argument (naming `what`) when the selection is empty.
std::vector<int> selected_nodes(const IgaModel& model, const FaceSelector& where,
                                const std::string& what);

}  // namespace isomuscle::io
