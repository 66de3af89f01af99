#include "io/scene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/setting_check.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::io {

namespace {

bool all_finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

std::string format_vector(const Eigen::Vector3d& v) {
  return "[" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) +
         "]";
}

void check_vector(const std::string& key, const Eigen::Vector3d& v, bool nonzero) {
  if (!all_finite(v)) {
    throw InvalidSetting(key, "must hold finite numbers (got " + format_vector(v) + ")");
  }
  if (nonzero && v.norm() == 0.0)
    throw InvalidSetting(key, "must not be the zero vector");
}

// Runs a validate() and prefixes the keys of its errors: "dt" -> "time.dt".
template <class Settings>
void validate_in(const std::string& prefix, const Settings& settings) {
  try {
    settings.validate();
  } catch (const InvalidSetting& e) {
    throw InvalidSetting(prefix + "." + e.key(), e.detail());
  }
}

}  // namespace

// ---- names ---------------------------------------------------------------------------------

const char* to_string(Direction d) {
  switch (d) {
    case Direction::u:
      return "u";
    case Direction::v:
      return "v";
    case Direction::w:
      return "w";
  }
  return "?";
}

const char* to_string(Face f) {
  static const char* names[] = {"u0", "u1", "v0", "v1", "w0", "w1"};
  return names[static_cast<int>(f)];
}

std::vector<std::string> face_names() {
  return {"u0", "u1", "v0", "v1", "w0", "w1"};
}

Direction parse_direction(const std::string& key, const std::string& name) {
  check_choice(key, name, {"u", "v", "w"});
  return name == "u" ? Direction::u : name == "v" ? Direction::v : Direction::w;
}

Face parse_face(const std::string& key, const std::string& name) {
  const std::vector<std::string> names = face_names();
  check_choice(key, name, names);
  return static_cast<Face>(std::find(names.begin(), names.end(), name) - names.begin());
}

const char* to_string(Discretisation d) {
  return d == Discretisation::iga ? "iga" : "tet";
}

const char* to_string(Construction c) {
  return c == Construction::shrink ? "shrink" : "extrude";
}

const char* to_string(LoadType) {
  return "traction";
}

const char* to_string(FibreMode m) {
  static const char* names[] = {"isocurve", "constant", "segments", "line"};
  return names[static_cast<int>(m)];
}

const char* to_string(BoundaryType t) {
  static const char* names[] = {"fixed", "displacement", "symmetry", "elastic"};
  return names[static_cast<int>(t)];
}

const char* to_string(Formulation f) {
  return f == Formulation::mixed ? "mixed" : "displacement";
}

const char* to_string(LinearSolverKind k) {
  return k == LinearSolverKind::cholmod ? "cholmod" : "umfpack";
}

const char* to_string(TangentKind k) {
  return k == TangentKind::consistent ? "consistent" : "frozen_ce";
}

const char* to_string(IndefiniteTangent k) {
  switch (k) {
    case IndefiniteTangent::lu:
      return "lu";
    case IndefiniteTangent::shift:
      return "shift";
    case IndefiniteTangent::cut:
      return "cut";
  }
  return "unknown";
}

const char* to_string(ProbeKind k) {
  static const char* names[] = {"point_displacement",  "face_reaction",     "volume",
                                "stress_parts",        "surface_stability", "element_layer",
                                "material_ellipticity"};
  return names[static_cast<int>(k)];
}

// ---- validation ----------------------------------------------------------------------------

void RefinementSettings::validate() const {
  if (continuity) {
    const std::string c = range_violation(*continuity, Range::closed(0, 9));
    if (!c.empty())
      throw InvalidSetting("continuity", c);
  }
  // Degrees beyond ~10 and more than 1000 knots per span are typing mistakes, not refinement.
  for (int i = 0; i < 3; ++i) {
    const std::string element = "element " + std::to_string(i + 1) + " ";
    const std::string d = range_violation(degree_elevation[i], Range::closed(0, 10));
    if (!d.empty())
      throw InvalidSetting("degree_elevation", element + d);
    const std::string k = range_violation(knot_insertion[i], Range::closed(0, 1000));
    if (!k.empty())
      throw InvalidSetting("knot_insertion", element + k);
    const std::vector<double>& t = knots[static_cast<std::size_t>(i)];
    for (std::size_t j = 0; j < t.size(); ++j) {
      if (!(t[j] > 0.0 && t[j] < 1.0) || (j > 0 && !(t[j] > t[j - 1])))
        throw InvalidSetting("knots", std::string(1, "uvw"[i]) +
                                          " must be strictly increasing values in (0, 1) (got " +
                                          format_number(t[j]) + " at position " +
                                          std::to_string(j + 1) + ")");
    }
  }
}

void GeometrySettings::validate() const {
  if (iges.empty())
    throw InvalidSetting("iges", "must name an IGES file");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(iges, ec)) {
    throw InvalidSetting("iges", "names no readable file (looked for " + iges.string() + ")");
  }
  check_range("surface", surface, Range::non_negative());
  if (construction == Construction::extrude)
    check_vector("extrusion", extrusion, true);
  if (centreline == Direction::w) {
    throw InvalidSetting("centreline", "must be one of u, v (got \"w\")");
  }
  validate_in("refine", refine);
  for (int d = 0; d < 3; ++d) {
    const auto& [a, b] = extract[static_cast<std::size_t>(d)];
    const std::string key = std::string("extract.") + to_string(static_cast<Direction>(d));
    if (!(std::isfinite(a) && std::isfinite(b) && a >= 0.0 && b <= 1.0 && a < b)) {
      throw InvalidSetting(key,
                           "must be a range [a, b] of the parameter domain scaled to [0, 1] "
                           "with 0 <= a < b <= 1 (got [" +
                               format_number(a) + ", " + format_number(b) + "])");
    }
  }
}

bool GeometrySettings::extracts() const {
  return std::any_of(extract.begin(), extract.end(),
                     [](const auto& r) { return r[0] != 0.0 || r[1] != 1.0; });
}

void MaterialSettings::validate() const {
  check_choice("model", model, materials::material_models());
  const auto& specs = materials::material_parameters(model);
  std::vector<std::string> names;
  for (const auto& spec : specs)
    names.push_back(spec.name);
  for (const auto& [name, value] : parameters) {
    const std::string key = "parameters." + name;
    // An init-capture: clang 14 (scripts/fuzz.sh) cannot capture a structured binding.
    const auto spec = std::find_if(specs.begin(), specs.end(),
                                   [&name = name](const auto& s) { return s.name == name; });
    if (spec == specs.end()) {
      std::string detail = "is not a parameter of model \"" + model + "\"";
      const std::string near = closest_match(name, names);
      if (!near.empty())
        detail += "; did you mean '" + near + "'?";
      throw InvalidSetting(key, detail + "; valid parameters: " + join(names));
    }
    if (!materials::in_range(*spec, value)) {
      throw InvalidSetting(key, std::string("must be ") + (spec->integer_flag ? "" : "in ") +
                                    materials::describe_range(*spec) + " (got " +
                                    format_number(value) + ")" +
                                    (spec->unit.empty() ? "" : ", unit " + spec->unit));
    }
  }
  // The factory's own checks (e.g. relations between parameters) with its message.
  try {
    (void)materials::make_material(model, parameters);
  } catch (const std::invalid_argument& e) {
    throw InvalidSetting("parameters", std::string("are rejected by the material: ") + e.what());
  }
}

void FibreSettings::validate() const {
  switch (mode) {
    case FibreMode::isocurve:
      break;
    case FibreMode::constant:
      check_vector("vector", vector, true);
      break;
    case FibreMode::segments:
      check_range("segments", segments, Range::closed(1, 1000));
      break;
    case FibreMode::line:
      check_vector("origin", origin, false);
      check_vector("insertion", insertion, false);
      if ((insertion - origin).norm() == 0.0) {
        throw InvalidSetting("insertion",
                             "must differ from 'origin' (both are " + format_vector(origin) + ")");
      }
      break;
  }
}

void PlaneSelector::validate() const {
  check_vector("point", point, false);
  check_vector("normal", normal, true);
  check_range("tolerance", tolerance, Range::positive());
}

void PointSelector::validate() const {
  check_vector("at", point, false);
  check_range("tolerance", tolerance, Range::positive());
}

void FaceSelector::validate() const {
  if (int(face.has_value()) + int(plane.has_value()) + int(point.has_value()) != 1) {
    throw InvalidSetting("face", "must be either a face name (" + join(face_names()) +
                                     ") or a plane { point, normal, tolerance }, or (for a "
                                     "boundary condition) a point 'at' instead");
  }
  if (plane)
    plane->validate();
  if (point)
    point->validate();
}

void BoundarySettings::validate() const {
  validate_in("face", where);
  check_vector("velocity", velocity, false);
  check_vector("value", value, false);
  if (type != BoundaryType::displacement && (velocity.norm() > 0.0 || value.norm() > 0.0)) {
    throw InvalidSetting("velocity", std::string("and 'value' apply only to type = "
                                                 "\"displacement\" (type is \"") +
                                         to_string(type) + "\")");
  }
  if (type == BoundaryType::symmetry) {
    if (where.point)
      throw InvalidSetting("at", "cannot carry a symmetry condition: it needs a face or a plane");
    return;
  }
  if (type == BoundaryType::elastic) {
    if (!where.face) {
      throw InvalidSetting(where.point ? "at" : "face",
                           "of an elastic support must be a face name (" + join(face_names()) +
                               "): the springs are spread over the face's area");
    }
    check_range("stiffness", stiffness, Range::positive());
  } else if (stiffness != 0.0) {
    throw InvalidSetting(
        "stiffness",
        std::string("applies only to type = \"elastic\" (type is \"") + to_string(type) + "\")");
  }
  if (!components[0] && !components[1] && !components[2]) {
    throw InvalidSetting("components", "must constrain at least one of x, y, z");
  }
  const char* axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!components[i] && (velocity[i] != 0.0 || value[i] != 0.0)) {
      throw InvalidSetting("components", std::string("leaves ") + axes[i] +
                                             " free, but the prescribed motion moves along " +
                                             axes[i]);
    }
  }
  check_range("start", start, Range::non_negative());
  if (!(stop > start)) {
    throw InvalidSetting(
        "stop", "must be > start (" + format_number(start) + ") (got " + format_number(stop) + ")");
  }
}

// u(t) of a displacement condition: value + v (min(t, stop) - start) from start on, m.
Eigen::Vector3d BoundarySettings::prescribed_displacement(double time) const {
  if (type != BoundaryType::displacement || time < start)
    return Eigen::Vector3d::Zero();
  const double moving = std::min(time, stop) - start;
  Eigen::Vector3d u = value + velocity * moving;
  for (int i = 0; i < 3; ++i) {
    if (!components[i])
      u[i] = 0.0;
  }
  return u;
}

void TetrahedraSettings::validate() const {
  if (mesh.empty()) {
    check_range("element_size", element_size, Range::positive());
  } else {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(mesh, ec))
      throw InvalidSetting("mesh", "names no readable file (looked for " + mesh.string() + ")");
    check_range("mesh_unit", mesh_unit, Range::positive());
    if (!refine.empty())
      throw InvalidSetting("refine", "and 'mesh' exclude each other: the mesh is given");
  }
  check_range("order", order, Range::closed(1, 2));
  if (quadrature_degree != 0) {
    check_range("quadrature_degree", quadrature_degree, Range::closed(1, 15));
    if (quadrature_degree == 3)
      throw InvalidSetting(
          "quadrature_degree",
          "3 is Keast's 5-point rule, whose negative weight makes the tangent of a "
          "stable material indefinite; take 2 (4 points), 4 (14 points) or more");
    if (order == 2 && quadrature_degree < 2)
      throw InvalidSetting("quadrature_degree",
                           "1 (one point) leaves 10-node tetrahedra with zero-energy modes; take 2 "
                           "(4 points, the default) or more");
  }
  for (const TetRefinement& r : refine) {
    try {
      r.validate(element_size);
    } catch (const InvalidSetting& e) {
      throw InvalidSetting("refine." + e.key(), e.detail());
    }
  }
}

void TetRefinement::validate(double element_size) const {
  check_range("size", size, Range::positive());
  check_range("distance", distance, Range::positive());
  if (!(size < element_size))
    throw InvalidSetting("size", "must be smaller than [tetrahedra] element_size (" +
                                     format_number(element_size) + " m), got " +
                                     format_number(size));
}

void LoadSettings::validate() const {
  check_vector("traction", traction, false);
  check_range("start", start, Range::non_negative());
  check_range("ramp_time", ramp_time, Range::non_negative());
}

double LoadSettings::factor(double time) const {
  if (time < start)
    return 0.0;
  if (!(ramp_time > 0.0))
    return 1.0;
  return std::min(1.0, (time - start) / ramp_time);
}

void TimeSettings::validate() const {
  check_range("end", end, Range::positive());
  check_range("dt", dt, Range{0.0, end, true, false});
  check_range("dt_min", dt_min, Range{0.0, dt, true, false});
  check_range("dt_max", dt_max, Range::at_least(dt));
}

void SolverSettings::validate() const {
  check_range("newton_max_iterations", newton_max_iterations, Range::closed(1, 1000));
  check_range("stall_iterations", stall_iterations, Range::closed(0, 1000));
  check_range("tolerance_residual", tolerance_residual, Range{0.0, 1.0, true, true});
  check_range("tolerance_energy", tolerance_energy, Range{0.0, 1.0, true, true});
  check_range("threads", threads, Range::closed(0, 4096));
  check_range("blas_threads", blas_threads, Range::closed(0, 4096));
}

const std::vector<std::string>& OutputSettings::field_names() {
  static const std::vector<std::string> names{"displacement", "cauchy_stress", "J", "fibre",
                                              "activation"};
  return names;
}

void OutputSettings::validate() const {
  for (std::size_t i = 0; i < times.size(); ++i) {
    const std::string element = "element " + std::to_string(i + 1) + " ";
    const double lower = i == 0 ? 0.0 : times[i - 1];
    const std::string d = range_violation(times[i], Range{lower, HUGE_VAL, i > 0, false});
    if (!d.empty()) {
      throw InvalidSetting("times", element + d + (i > 0 ? "; times must increase" : ""));
    }
  }
  check_range("every", every, Range::non_negative());
  if (!times.empty() && every > 0.0) {
    throw InvalidSetting("every", "cannot be combined with 'times'; give one of them");
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    check_choice("fields", fields[i], field_names());
    if (std::find(fields.begin(), fields.begin() + static_cast<long>(i), fields[i]) !=
        fields.begin() + static_cast<long>(i)) {
      throw InvalidSetting("fields", "repeats \"" + fields[i] + "\"");
    }
  }
  check_range("samples_per_element", samples_per_element, Range::closed(1, 16));
}

void OutputSettings::check_within(const TimeSettings& time) const {
  if (!times.empty() && times.back() > time.end) {
    throw InvalidSetting("times", "must lie within [0, end = " + format_number(time.end) +
                                      "] of [time] (got " + format_number(times.back()) + ")");
  }
  if (every > time.end) {
    throw InvalidSetting("every", "must be <= end = " + format_number(time.end) +
                                      " of [time] (got " + format_number(every) + ")");
  }
}

const std::vector<std::string>& ProbeSettings::component_names() {
  static const std::vector<std::string> names{"x", "y", "z", "magnitude", "normal"};
  return names;
}

void ProbeSettings::validate() const {
  if (!is_plain_name(name)) {
    throw InvalidSetting("name", "must be letters, digits, '_', '.' or '-' (got \"" + name +
                                     "\"); it becomes a CSV column");
  }
  const bool at_point = kind == ProbeKind::point_displacement || kind == ProbeKind::stress_parts ||
                        kind == ProbeKind::surface_stability || kind == ProbeKind::element_layer;
  if (at_point && point.has_value() == xi.has_value()) {
    throw InvalidSetting("point", std::string("or 'xi' (one of them) is needed by kind = \"") +
                                      to_string(kind) + "\"");
  }
  if (!at_point && (point || xi)) {
    throw InvalidSetting(point ? "point" : "xi",
                         std::string("is not used by kind = \"") + to_string(kind) + "\"");
  }
  if (point)
    check_vector("point", *point, false);
  if (xi) {
    for (int i = 0; i < 3; ++i) {
      const std::string d = range_violation((*xi)[i], Range::closed(0.0, 1.0));
      if (!d.empty())
        throw InvalidSetting("xi", "element " + std::to_string(i + 1) + " " + d);
    }
  }
  if ((kind == ProbeKind::face_reaction) != face.has_value()) {
    throw InvalidSetting("face",
                         kind == ProbeKind::face_reaction
                             ? "is needed by kind = \"face_reaction\""
                             : std::string("is not used by kind = \"") + to_string(kind) + "\"");
  }
  if (face)
    validate_in("face", *face);
  check_choice("component", component, component_names());
  if (component == "normal" && kind != ProbeKind::point_displacement) {
    throw InvalidSetting("component", std::string("\"normal\" applies to kind = "
                                                  "\"point_displacement\" only (here \"") +
                                          to_string(kind) + "\")");
  }
}

void Scene::validate() const {
  if (discretisation == Discretisation::tet)
    validate_in("tetrahedra", tetrahedra);
  validate_in("geometry", geometry);
  validate_in("material", material);
  validate_in("fibres", fibres);
  for (std::size_t i = 0; i < boundaries.size(); ++i) {
    validate_in("boundary[" + std::to_string(i) + "]", boundaries[i]);
  }
  for (std::size_t i = 0; i < loads.size(); ++i) {
    validate_in("load[" + std::to_string(i) + "]", loads[i]);
  }
  validate_in("time", time);
  validate_in("solver", solver);
  validate_in("output", output);
  try {
    output.check_within(time);
  } catch (const InvalidSetting& e) {
    throw InvalidSetting("output." + e.key(), e.detail());
  }
  for (std::size_t i = 0; i < probes.size(); ++i) {
    validate_in("probe[" + std::to_string(i) + "]", probes[i]);
    for (std::size_t j = 0; j < i; ++j) {
      if (probes[j].name == probes[i].name) {
        throw InvalidSetting(
            "probe[" + std::to_string(i) + "].name",
            "repeats the name of probe[" + std::to_string(j) + "] (\"" + probes[i].name + "\")");
      }
    }
  }
}

}  // namespace isomuscle::io
