#pragma once
// The solid a scene describes, before any discretisation: the IGES surface shrunk onto its
// centreline (thesis 5.13-5.15, geometry/shrink.hpp) or extruded (geometry/extrusion.hpp), cut to
// its [geometry] extract piece, with the map from the scene's parametric names to the solid's
// directions. The IGA discretisation refines it exactly and uses it as the mesh
// (iga_run_setup.hpp); the tetrahedral one meshes the same IGES boundary and uses the solid for
// fibres, faces and parametric points (tet_run_setup.hpp). Also what both take from a scene in the
// same way: the fibre specification and the material law.
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

#include "geometry/nurbs_volume.hpp"
#include "iga/boundary_conditions.hpp"
#include "iga/fibre_directions.hpp"
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

struct SceneSolid {
  geometry::NurbsVolume volume;  // unrefined (the extract piece where the scene cuts one)
  SceneFrame frame;
};

// Reads the IGES surface and builds the solid. Throws std::runtime_error / std::invalid_argument
// naming the file, the surface index or the setting at fault.
SceneSolid build_scene_solid(const GeometrySettings& geometry);

// The fibre field of [fibres] on a solid (segment end points are centroids of its isoparametric
// sections); throws std::invalid_argument when a section has zero area.
iga::FibreSpec fibre_spec(const FibreSettings& fibres, const SceneFrame& frame,
                          const geometry::NurbsVolume& volume);

// The law of [material] with the [solver] tangent choice (frozen_ce: the Hill laws' parameter
// frozen_ce_tangent = 1, thesis 5.54); std::invalid_argument for a contradiction.
std::unique_ptr<materials::MaterialLaw> make_law(const MaterialSettings& material,
                                                 TangentKind tangent);

// What a user must know when the displacement formulation meets a nearly incompressible law
// (kappa/mu >= 100, nu >= 0.495): it locks (far too stiff on any practical mesh) and its tangent's
// condition grows with kappa/mu, so Newton stalls at a residual floor; empty otherwise. Said at
// set-up as a note and appended to the reason when such a run fails.
std::string displacement_locking_hint(const materials::MaterialLaw& law, bool displacement);

// "(x, y, z)" with the shortest exact numbers, for messages.
std::string describe_point(const Eigen::Vector3d& x);

// Outward unit normal of the face w = 0 of the solid (its boundary surface; w runs inwards) at xi:
// +-(H_u x H_v) normalised, the sign making n . H_w < 0. std::invalid_argument naming `what` where
// the surface has no normal (a collapsed edge).
Eigen::Vector3d surface_normal(const geometry::NurbsVolume& volume, const Eigen::Vector3d& xi,
                               const std::string& what);

}  // namespace isomuscle::io
