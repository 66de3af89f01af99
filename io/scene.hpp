#pragma once
// The scene schema: everything a run needs, one struct per TOML table (after deal.II step-44's
// parameter structs), each with its defaults and a validate() that checks the values and their
// consistency and throws InvalidSetting naming the key. scene_loader.hpp fills these structs from
// a file and reports errors with line numbers; programs and tests may build them directly.
//
// Units are SI (m, s, Pa); parametric coordinates are in [0, 1] per direction of the NURBS solid,
// whose w = 0 face is the boundary surface and w = 1 the collapsed centreline (SPEC section 1).
#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace isomuscle::io {

// Parametric directions of the solid H(u, v, w).
enum class Direction { u, v, w };
// The six faces of the parameter cube: u0 is {u = 0}, u1 is {u = 1}, ... (G+Smo's west/east...).
enum class Face { u0, u1, v0, v1, w0, w1 };

const char* to_string(Direction d);
const char* to_string(Face f);
// Lower-case names as written in scenes; parse_* throw InvalidSetting(key, ...) for other names.
Direction parse_direction(const std::string& key, const std::string& name);
Face parse_face(const std::string& key, const std::string& name);
std::vector<std::string> face_names();

// [geometry.refine]: exact refinement of the NURBS solid before analysis (SPEC section 1).
struct RefinementSettings {
  std::array<int, 3> degree_elevation{0, 0, 0};  // degree raised by this much in u, v, w
  std::array<int, 3> knot_insertion{0, 0, 0};    // new knots per existing knot span in u, v, w
  // Knots inserted once each after the uniform insertion, as scene parameters in (0, 1) per
  // direction u, v, w: refinement concentrated where the user wants it (e.g. next to the
  // collapsed centreline, w -> 1 on a shrink solid). Strictly increasing. A value that is
  // already a knot of the refined solid is not inserted again (iga_run_setup.cpp), so a graded
  // mesh can be listed whole.
  std::array<std::vector<double>, 3> knots{};
  // When set, every interior knot is raised to multiplicity p - continuity in each direction after
  // the insertions above, so the basis is only C^continuity across element faces. continuity = 0
  // gives C^0 element faces: the Lagrange finite-element space of the same degree on the same
  // exact geometry and elements (p-refinement instead of k-refinement, Cottrell et al. 2009,
  // §2.1.4), for comparing the smooth spline solution with a classical FE one. Must be below the
  // degree in every direction (checked when the solid is refined).
  std::optional<int> continuity;
  void validate() const;
};

// How the solid is built from the IGES surface.
enum class Construction {
  shrink,   // a closed surface shrunk onto its centreline (thesis 5.13-5.15, geometry/shrink.hpp)
  extrude,  // a sheet swept along a vector: H = B(u, v) + w d (geometry/extrusion.hpp)
};
const char* to_string(Construction c);

// [geometry]: where the solid comes from.
struct GeometrySettings {
  std::filesystem::path iges;  // IGES file; a scene gives it relative to the scene file
  int surface = 0;             // index of the B-spline surface in the file
  Construction construction = Construction::shrink;
  Direction centreline = Direction::v;  // shrink: parametric direction of the surface along the
                                        // muscle
  Eigen::Vector3d extrusion = Eigen::Vector3d::UnitZ();  // extrude: the vector d, m
  RefinementSettings refine;
  // extract = { u = [a, b], ... }: the solid restricted to a parameter sub-range per direction,
  // given as fractions of the knot domain in the scene's naming (as probe xi), cut exactly by knot
  // insertion (geometry::extract) after the shrink and before refinement. [0, 1] keeps the whole
  // direction. Faces, xi and refinement counts then refer to the extracted piece (e.g. the 1/8
  // torus of examples/torus with three symmetry planes).
  std::array<std::array<double, 2>, 3> extract{{{0.0, 1.0}, {0.0, 1.0}, {0.0, 1.0}}};
  bool extracts() const;  // some direction is restricted
  void validate() const;  // also checks that the IGES file exists
};

// [material] with [material.parameters]: a law of materials::material_models() and values for
// any of its parameters (the rest take the defaults of materials::material_parameters(model)).
struct MaterialSettings {
  std::string model;
  std::map<std::string, double> parameters;
  void validate() const;  // model name, parameter names and ranges through the material factory
};

// [fibres]: the undeformed fibre direction field (thesis 5.27-5.30 and its comparison modes).
enum class FibreMode {
  isocurve,  // tangent of the parametric isocurve in `direction` (thesis 5.29)
  constant,  // one direction `vector` everywhere (e.g. z)
  segments,  // body cut at equal steps of `direction` into `segments` pieces, one chord each
  line,      // the straight line from `origin` to `insertion` (LS-DYNA P25-P30)
};
const char* to_string(FibreMode m);

struct FibreSettings {
  FibreMode mode = FibreMode::isocurve;
  // isocurve and segments: parametric direction; a scene that leaves it out gets the centreline.
  Direction direction = Direction::v;
  Eigen::Vector3d vector = Eigen::Vector3d::UnitZ();  // constant mode; unit length after loading
  int segments = 2;                                   // segments mode, >= 1
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // line mode, m
  Eigen::Vector3d insertion = Eigen::Vector3d::UnitZ();
  void validate() const;
};

// A set of boundary points: a face of the parameter cube, or every point within tolerance of a
// plane (for symmetry cuts and meshes without parametric faces).
struct PlaneSelector {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit length after loading
  double tolerance = 1e-6;                            // m, distance from the plane
  void validate() const;
};

// The control points within tolerance of one point (a few point constraints that remove the
// rigid-body modes of a body otherwise free, thesis-style "nodal" supports).
struct PointSelector {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // m
  double tolerance = 1e-6;                          // m
  void validate() const;
};

struct FaceSelector {
  std::optional<Face> face;  // exactly one of face, plane and point
  std::optional<PlaneSelector> plane;
  std::optional<PointSelector> point;  // [[boundary]] only (at = [x, y, z])
  void validate() const;
};

// [[boundary]]: a Dirichlet condition on a face, or springs on it.
enum class BoundaryType {
  fixed,         // the masked components are zero
  displacement,  // the masked components follow u(t) below
  symmetry,      // zero displacement along the face normal (plane faces)
  elastic,       // springs on the masked components: traction -stiffness u per reference area (a
                 // compliant attachment; NURBS solids, parametric faces; iga/elastic_support.hpp)
};
const char* to_string(BoundaryType t);

struct BoundarySettings {
  FaceSelector where;
  BoundaryType type = BoundaryType::fixed;
  std::array<bool, 3> components{true, true, true};       // x, y, z constrained (fixed,
                                                          // displacement, elastic)
  double stiffness = 0.0;                                 // Pa/m, elastic type
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();     // m/s, displacement type
  Eigen::Vector3d value = Eigen::Vector3d::Zero();        // m, constant part, displacement type
  double start = 0.0;                                     // s, motion begins
  double stop = std::numeric_limits<double>::infinity();  // s, motion ends, position then held
  void validate() const;
  // u(t) = 0 before start, else value + velocity * (min(t, stop) - start), m.
  Eigen::Vector3d prescribed_displacement(double time) const;
};

// [[load]]: an external load, dead (fixed in the reference configuration).
enum class LoadType {
  traction,  // nominal traction t0 on a face, Pa = N per m^2 of REFERENCE area
};
const char* to_string(LoadType t);

struct LoadSettings {
  Face face = Face::u1;  // a parametric face (loads are integrated over the face's parameters)
  LoadType type = LoadType::traction;
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();  // Pa, at full load
  double start = 0.0;                                  // s, the load is 0 before
  double ramp_time = 0.0;  // s, linear rise to full load from start; 0: full at start
  void validate() const;
  // Load factor in [0, 1] at time t: 0 before start, (t - start) / ramp_time, then 1.
  double factor(double time) const;
};

// [time]: quasi-static time stepping with cut-back.
struct TimeSettings {
  double end = 1.0;             // s
  double dt = 0.01;             // s, first (and, unless adaptive, every) step
  double dt_min = 0.01 / 1024;  // s, smallest step before the run fails; a scene: dt / 1024
  double dt_max = 0.01;  // s, largest step an adaptive run grows to; a scene defaults it to dt
  // Grow the step after easy convergence up to dt_max; false: steps of dt, a cut step grows back
  // to dt only.
  bool adaptive = true;
  void validate() const;
};

// [solver]
enum class Formulation { mixed, displacement };
enum class LinearSolverKind { cholmod, umfpack };
enum class TangentKind { consistent, frozen_ce };
// What Newton does when Cholesky finds the tangent not positive definite
// (solver/linear_solver.hpp): LU of it, Cholesky of it shifted by a multiple of the identity, or no
// direction (the step is cut). The default is lu: some converged states of these runs have an
// indefinite tangent themselves (the displacement formulation's barrel cells of
// validation/stability, 2026-12-05: with shift they crept to |r| ~ 1e-6 relative and failed, where
// LU's exact Newton direction converges quadratically). shift and cut are cheaper where the
// indefinite tangents are only those of states far from equilibrium (validation/suite/README.md,
// the DAO on tetrahedra).
enum class IndefiniteTangent { lu, shift, cut };
const char* to_string(Formulation f);
const char* to_string(LinearSolverKind k);
const char* to_string(TangentKind k);
const char* to_string(IndefiniteTangent k);

struct SolverSettings {
  Formulation formulation = Formulation::mixed;
  // Defaults and meaning as solver::NewtonSettings.
  int newton_max_iterations = 20;
  double tolerance_residual = 1e-8;  // |r_k| / |r_0|
  double tolerance_energy = 1e-12;   // E_k / E_1 with E_k = |du_k . r_(k-1)|
  bool line_search = true;
  LinearSolverKind linear_solver = LinearSolverKind::cholmod;
  TangentKind tangent = TangentKind::consistent;
  IndefiniteTangent indefinite_tangent = IndefiniteTangent::lu;
  // Consecutive short line-search steps (1/16 or less, |r| not halved) after which a step's
  // Newton solve counts as stalled and the step is cut (solver::NewtonSettings::max_short_steps);
  // 0: never.
  int stall_iterations = 4;
  int threads = 0;  // 0: every available core
  // Threads of the BLAS under CHOLMOD (solver/blas_threads.hpp); 0: the BLAS's own default.
  int blas_threads = 1;
  void validate() const;
};

// [output]: fields for ParaView at chosen times.
struct OutputSettings {
  std::vector<double> times;  // s, increasing; empty: see every
  double every = 0.0;         // s between outputs; 0 with empty times: every converged step
  std::vector<std::string> fields{"displacement", "cauchy_stress", "J"};
  int samples_per_element = 2;  // tessellation: sub-cells per element edge (IGA)
  void validate() const;
  // Output times within the run: times and every at most time.end.
  void check_within(const TimeSettings& time) const;
  static const std::vector<std::string>& field_names();
};

// [[probe]]: a scalar (or a few scalars) recorded every step into probes.csv. surface_stability:
// rho c^2 (Pa) of the slowest surface wave of the free surface nearest the point, taken as a
// deformed half-space (io/surface_stability_check.hpp; <= 0: Biot's surface instability), a few
// seconds a step. element_layer (NURBS solids, mixed formulation): the lowest Bloch eigenvalue
// (Pa/m^2) of the run's element tiled along the free surface nearest the point and deformed to
// its state (io/element_layer_check.hpp; <= 0: the element itself is unstable there), and in
// <name>.column the same for the body's own elements through the depth there, each at its own
// state (io/element_column_check.hpp). material_ellipticity (no point: the whole body): the law's
// smallest isochoric wave stiffness over every quadrature point (Pa), how many points have it
// <= 0 and where the smallest is (io/ellipticity_probe.hpp).
enum class ProbeKind {
  point_displacement,
  face_reaction,
  volume,
  stress_parts,
  surface_stability,
  element_layer,
  material_ellipticity
};
const char* to_string(ProbeKind k);

struct ProbeSettings {
  std::string name;  // column name in probes.csv, [A-Za-z0-9_.-]+
  ProbeKind kind = ProbeKind::volume;
  std::optional<Eigen::Vector3d> point;  // point_displacement, stress_parts, surface_stability,
                                         // element_layer: reference point, m
  std::optional<Eigen::Vector3d> xi;     // ... or parametric point (u, v, w) in [0, 1]^3
  std::optional<FaceSelector> face;      // face_reaction
  std::string component = "magnitude";   // x, y, z or magnitude (point_displacement, reaction);
                                         // normal (point_displacement on the surface w0)
  void validate() const;
  static const std::vector<std::string>& component_names();
};

// discretisation = "iga" | "tet": the NURBS solid itself as the mesh (isogeometric analysis), or
// tetrahedra of the same shape (the comparison runs; tet/).
enum class Discretisation { iga, tet };
const char* to_string(Discretisation d);

// [tetrahedra] (discretisation = "tet"): the IGES boundary meshed by gmsh, or a user's mesh.
// [[tetrahedra.refine]]: smaller elements next to a face of the solid, e.g. a clamped attachment,
// where the fibres shorten against a face that cannot widen: a boundary layer that a uniform
// mesh resolves only at the price of refining the whole muscle (validation/suite/README.md, DAO).
struct TetRefinement {
  Face face = Face::v0;   // a parametric face of the solid, as [[boundary]] names it
  double size = 0.0;      // m, element size on the face (< element_size)
  double distance = 0.0;  // m, over which the size grows linearly back to element_size
  // 0 < size < element_size of its [tetrahedra], distance > 0; InvalidSetting("size" / "distance").
  void validate(double element_size) const;
};

struct TetrahedraSettings {
  double element_size = 0.0;   // m, target edge length when meshing the IGES boundary
  int order = 2;               // 1: 4-node, 2: 10-node (the mixed formulation needs 10 nodes)
  std::filesystem::path mesh;  // a gmsh .msh file instead of meshing (relative to the scene)
  double mesh_unit = 1.0;      // metres per length unit of the .msh file
  std::vector<TetRefinement> refine;  // local refinement when meshing (not with a given mesh)
  // Degree of the element quadrature (tet::tet_rule); 0: the order's default, 1 point for 4-node
  // and 4 points (degree 2) for 10-node tetrahedra. 4 or 5 take 14 points, 6 to 15 a conical
  // product; more points integrate the nonlinear law's stresses closer at more assembly cost.
  int quadrature_degree = 0;
  // element_size > 0 unless a mesh is given, order 1 or 2, each refinement's 0 < size <
  // element_size and distance > 0, quadrature_degree 0 or 1 to 15 but not 3 (the 5-point rule's
  // negative weight), at least 2 for 10-node tetrahedra (one point leaves zero-energy modes).
  void validate() const;
};

struct Scene {
  std::filesystem::path file;  // the scene file, for messages and relative paths
  std::string description;
  Discretisation discretisation = Discretisation::iga;
  TetrahedraSettings tetrahedra;  // discretisation = "tet"
  GeometrySettings geometry;
  MaterialSettings material;
  FibreSettings fibres;
  std::vector<BoundarySettings> boundaries;
  std::vector<LoadSettings> loads;
  TimeSettings time;
  SolverSettings solver;
  OutputSettings output;
  std::vector<ProbeSettings> probes;
  // Every table's validate(), then what spans tables: output times within [0, time.end], unique
  // probe names. Throws InvalidSetting with keys like "output.times" or "probe.name".
  void validate() const;
};

}  // namespace isomuscle::io
