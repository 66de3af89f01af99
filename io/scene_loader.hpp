#pragma once
// Reading a scene file into the Scene structs (scene.hpp). Every error — TOML syntax, unknown
// keys, wrong types, values out of range, inconsistent settings — is a SceneError naming the file
// and line (scene_reader.hpp). The example below is the whole schema with its defaults; a key
// marked (required) has none.
//
//   description = "barrel, isometric contraction"
//   discretisation = "iga"       # "iga": the NURBS solid is the mesh; "tet": tetrahedra of the
//                                # same shape (then [tetrahedra] is required)
//   # [tetrahedra]
//   # element_size = 0.002       # m, gmsh meshes the IGES boundary (required unless mesh)
//   # order = 2                  # 1: 4-node, 2: 10-node tetrahedra
//   # mesh = "barrel.msh"        # instead: a gmsh mesh of the same shape; mesh_unit = 1.0 (m)
//
//   [geometry]
//   iges = "barrel.igs"          # (required) relative to the scene file
//   surface = 0                  # index of the B-spline surface in the file
//   construction = "shrink"      # "shrink": a closed surface shrunk onto its centreline;
//                                # "extrude": a sheet swept along `extrusion`
//   centreline = "v"             # shrink: "u" | "v", surface direction along the muscle
//   # extrusion = [0, 0, 0.001]  # extrude (required there): the sweep vector d, m; w = 0 is the
//                                # surface, w = 1 the surface moved by d
//   # extract = { u = [0.0, 0.5], v = [0.0, 0.25] }  # sub-range per direction (u, v, w) as
//   #                            fractions of the domain, 0 <= a < b <= 1, cut exactly before the
//   #                            refinement; faces, xi and refinement then refer to the piece
//   [geometry.refine]
//   degree_elevation = [0, 0, 1] # degree raised in u, v, w (0..10)
//   knot_insertion = [1, 3, 1]   # new knots per existing span in u, v, w (0..1000)
//
//   [material]
//   model = "lu2010"             # (required) one of materials::material_models()
//   [material.parameters]        # any parameters of the model, SI units; others take defaults
//   sigma0 = 7.0e5              # inf is allowed where the model allows it (t1 = inf)
//
//   [fibres]
//   mode = "isocurve"            # "isocurve" | "constant" | "segments" | "line"
//   direction = "v"              # isocurve, segments: "u" | "v" | "w"; default: the centreline
//   # vector = [0, 0, 1]         # constant (required there); normalised
//   # segments = 2               # segments (required there), >= 1
//   # origin = [0, 0, 0]         # line (required there), m
//   # insertion = [0, 0, 0.05]   # line (required there), m
//
//   [[boundary]]                 # (at least one)
//   face = "v0"                  # "u0" | "u1" | "v0" | "v1" | "w0" | "w1", or a plane:
//                                # { point = [x, y, z], normal = [x, y, z], tolerance = 1e-6 }
//   # at = [0.017, 0, 0]         # instead of face: the control points within `tolerance`
//   # tolerance = 1e-6           #   (m) of a point, e.g. to remove rigid-body modes
//   type = "fixed"               # (required) "fixed" | "displacement" | "symmetry"
//   components = ["x", "y", "z"] # fixed, displacement: constrained components
//   # velocity = [0, 0, 0.005]   # displacement: m/s from start to stop
//   # value = [0, 0, 0]          # displacement: m, constant part from start on
//   # start = 0.0                # displacement: s
//   # stop = 2.4                 # displacement: s, position held afterwards (default: never)
//
//   [[load]]                     # (any number) dead loads
//   face = "u1"                  # (required) a face name
//   type = "traction"            # (required) nominal traction, Pa per m^2 of reference area
//   traction = [0, 0.05, 0]      # (required) Pa at full load
//   start = 0.0                  # s, zero before
//   ramp_time = 1.0              # s, linear rise from start to full load; 0: full at start
//
//   [time]
//   end = 0.2                    # (required) s
//   dt = 0.005                   # (required) s, <= end
//   dt_min = 4.8828125e-06       # s, default dt / 1024
//   dt_max = 0.005               # s, default dt
//   adaptive = true
//
//   [solver]
//   formulation = "mixed"        # "mixed" | "displacement"
//   newton_max_iterations = 20
//   tolerance_residual = 1e-8    # |r_k| / |r_0|
//   tolerance_energy = 1e-12     # E_k / E_1, E_k = |du_k . r_(k-1)|
//   line_search = true
//   linear_solver = "cholmod"    # "cholmod" | "umfpack"
//   tangent = "consistent"       # "consistent" | "frozen_ce"
//   indefinite_tangent = "lu"    # when Cholesky fails: "lu" | "shift" (Cholesky of K + beta I)
//                                # | "cut" (cut the step) (solver/linear_solver.hpp)
//   stall_iterations = 4         # short line-search steps in a row that cut the step; 0: never
//   threads = 0                  # assembly threads, 0: all cores
//   blas_threads = 1             # threads of the BLAS under CHOLMOD, 0: the BLAS's default
//
//   [output]
//   times = [0.05, 0.1, 0.2]     # s; or every = 0.01; neither: every converged step
//   fields = ["displacement", "cauchy_stress", "J"]  # also "fibre", "activation"
//   samples_per_element = 2      # 1..16
//
//   [[probe]]
//   name = "tip_z"               # (required) CSV column, [A-Za-z0-9_.-]+, unique
//   kind = "point_displacement"  # (required) | "face_reaction" | "volume" | "stress_parts"
//   point = [0, 0, 0.05]         # point_displacement, stress_parts: m; or xi = [u, v, w]
//   # face = "v1"                # face_reaction: a face name or plane, as in [[boundary]]
//   component = "z"              # point_displacement, face_reaction: "x"|"y"|"z"|"magnitude";
//                                # point_displacement on the surface w0 also "normal" (outward)
#include <filesystem>
#include <string_view>

#include "io/scene.hpp"

namespace isomuscle::io {

// Reads, checks and returns the scene in the file; relative paths in it are resolved against the
// file's folder.
Scene load_scene(const std::filesystem::path& path);
// The same for scene text; path names it in messages and gives the folder for relative paths.
Scene parse_scene(std::string_view text, const std::filesystem::path& path);

}  // namespace isomuscle::io
