#include "io/scene_loader.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "io/scene_reader.hpp"
#include "materials/material_factory.hpp"
#include "solver/setting_error.hpp"

namespace isomuscle::io {

namespace {

Eigen::Vector3d to_vector(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

// Runs a struct's validate() and reports its errors at the line of the offending key (io's own
// structs throw InvalidSetting, the solver's settings structs solver::SettingError).
template <class Settings>
void validate_at(const SceneTable& table, const Settings& settings) {
  try {
    settings.validate();
  } catch (const InvalidSetting& e) {
    table.fail(e);
  } catch (const solver::SettingError& e) {
    table.fail(InvalidSetting(e.key(), e.detail()));
  }
}

// Keys that only some values of a selector key use ("vector" only for mode = "constant"): the
// others are rejected with a message saying which value would use them.
void forbid_unused(SceneTable& table, const std::string& selector, const std::string& value,
                   const std::map<std::string, std::vector<std::string>>& used_by) {
  for (const auto& [key, values] : used_by) {
    if (std::find(values.begin(), values.end(), value) != values.end())
      continue;
    std::string which;
    for (const auto& v : values)
      which += (which.empty() ? "" : " or ") + selector + " = \"" + v + "\"";
    table.forbid(key,
                 "is used only with " + which + " (here " + selector + " = \"" + value + "\")");
  }
}

std::filesystem::path resolve(const std::filesystem::path& base, const std::string& file) {
  const std::filesystem::path p(file);
  return (p.is_absolute() ? p : base / p).lexically_normal();
}

GeometrySettings read_geometry(SceneTable t, const std::filesystem::path& base) {
  GeometrySettings g;
  g.iges = resolve(base, t.string("iges", required));
  g.surface = t.integer("surface", g.surface, Range::non_negative());
  const std::string construction = t.choice("construction", "shrink", {"shrink", "extrude"});
  forbid_unused(t, "construction", construction,
                {{"centreline", {"shrink"}}, {"extrusion", {"extrude"}}});
  if (construction == "shrink") {
    g.construction = Construction::shrink;
    g.centreline = parse_direction("centreline", t.choice("centreline", "v", {"u", "v"}));
  } else {
    g.construction = Construction::extrude;
    g.extrusion = to_vector(t.vector3("extrusion", required));
  }
  if (auto r = t.optional_table("refine")) {
    const Range allowed = Range::non_negative();
    if (auto d = r->optional_integers("degree_elevation", 3, allowed)) {
      g.refine.degree_elevation = {(*d)[0], (*d)[1], (*d)[2]};
    }
    if (auto k = r->optional_integers("knot_insertion", 3, allowed)) {
      g.refine.knot_insertion = {(*k)[0], (*k)[1], (*k)[2]};
    }
    g.refine.continuity = r->optional_integer("continuity", Range::non_negative());
    if (auto knots = r->optional_table("knots")) {
      for (Direction d : {Direction::u, Direction::v, Direction::w}) {
        if (auto t = knots->optional_numbers(to_string(d), 0, Range::open(0.0, 1.0)))
          g.refine.knots[static_cast<std::size_t>(d)] = *t;
      }
      knots->finish();
    }
    r->finish();
  }
  if (auto e = t.optional_table("extract")) {
    for (Direction d : {Direction::u, Direction::v, Direction::w}) {
      if (auto r = e->optional_numbers(to_string(d), 2, Range::closed(0.0, 1.0))) {
        g.extract[static_cast<std::size_t>(d)] = {(*r)[0], (*r)[1]};
        if (!((*r)[0] < (*r)[1])) {
          e->fail(to_string(d), "must be an increasing range [a, b] with 0 <= a < b <= 1 (got [" +
                                    format_number((*r)[0]) + ", " + format_number((*r)[1]) + "])");
        }
      }
    }
    e->finish();
  }
  t.finish();
  validate_at(t, g);
  return g;
}

MaterialSettings read_material(SceneTable t) {
  MaterialSettings m;
  m.model = t.choice("model", required, materials::material_models());
  if (auto p = t.optional_table("parameters")) {
    for (const std::string& name : p->keys()) {
      m.parameters[name] = p->number(name, required, Range::any_or_infinite());
    }
    p->finish();
  }
  t.finish();
  validate_at(t, m);
  return m;
}

FibreSettings read_fibres(std::optional<SceneTable> t, Direction centreline) {
  FibreSettings f;
  f.direction = centreline;
  if (!t)
    return f;
  const std::string mode =
      t->choice("mode", "isocurve", {"isocurve", "constant", "segments", "line"});
  forbid_unused(*t, "mode", mode,
                {{"direction", {"isocurve", "segments"}},
                 {"vector", {"constant"}},
                 {"segments", {"segments"}},
                 {"origin", {"line"}},
                 {"insertion", {"line"}}});
  if (mode == "isocurve" || mode == "segments") {
    f.direction = parse_direction("direction",
                                  t->choice("direction", to_string(centreline), {"u", "v", "w"}));
  }
  if (mode == "isocurve")
    f.mode = FibreMode::isocurve;
  if (mode == "constant") {
    f.mode = FibreMode::constant;
    f.vector = to_vector(t->vector3("vector", required));
  }
  if (mode == "segments") {
    f.mode = FibreMode::segments;
    f.segments = t->integer("segments", required, Range::closed(1, 1000));
  }
  if (mode == "line") {
    f.mode = FibreMode::line;
    f.origin = to_vector(t->vector3("origin", required));
    f.insertion = to_vector(t->vector3("insertion", required));
  }
  t->finish();
  validate_at(*t, f);
  if (f.mode == FibreMode::constant)
    f.vector.normalize();
  return f;
}

// The face a boundary condition or probe acts on: a name or an inline plane table.
FaceSelector read_face(SceneTable& t) {
  FaceSelector s;
  const toml::node_type type = t.type_of("face");
  if (type == toml::node_type::none) {
    t.fail_table("needs 'face': one of " + join(face_names()) +
                 ", or a plane { point = [x, y, z], normal = [x, y, z], tolerance = 1e-6 }");
  }
  if (type == toml::node_type::table) {
    SceneTable p = t.table("face", required);
    PlaneSelector plane;
    plane.point = to_vector(p.vector3("point", required));
    plane.normal = to_vector(p.vector3("normal", required));
    plane.tolerance = p.number("tolerance", plane.tolerance, Range::positive());
    p.finish();
    validate_at(p, plane);
    plane.normal.normalize();
    s.plane = plane;
  } else if (type == toml::node_type::string) {
    s.face = parse_face("face", t.choice("face", required, face_names()));
  } else {
    t.fail("face", "must be a face name (" + join(face_names()) +
                       ") or a plane table { point, normal, tolerance }, got another type");
  }
  return s;
}

std::array<bool, 3> read_components(SceneTable& t) {
  std::array<bool, 3> mask{true, true, true};
  if (auto names = t.optional_strings("components", {"x", "y", "z"})) {
    mask = {false, false, false};
    for (const auto& n : *names)
      mask[static_cast<std::size_t>(n[0] - 'x')] = true;
    if (names->empty())
      t.fail("components", "must name at least one of x, y, z");
  }
  return mask;
}

BoundarySettings read_boundary(SceneTable t) {
  BoundarySettings b;
  if (t.type_of("at") != toml::node_type::none) {
    if (t.type_of("face") != toml::node_type::none)
      t.fail("at", "and 'face' exclude each other: a condition acts on a face or at a point");
    PointSelector p;
    p.point = to_vector(t.vector3("at", required));
    p.tolerance = t.number("tolerance", p.tolerance, Range::positive());
    b.where.point = p;
  } else {
    b.where = read_face(t);
  }
  const std::string type =
      t.choice("type", required, {"fixed", "displacement", "symmetry", "elastic"});
  forbid_unused(t, "type", type,
                {{"components", {"fixed", "displacement", "elastic"}},
                 {"stiffness", {"elastic"}},
                 {"velocity", {"displacement"}},
                 {"value", {"displacement"}},
                 {"start", {"displacement"}},
                 {"stop", {"displacement"}}});
  if (type == "fixed") {
    b.type = BoundaryType::fixed;
    b.components = read_components(t);
  } else if (type == "displacement") {
    b.type = BoundaryType::displacement;
    b.components = read_components(t);
    const auto velocity = t.optional_vector3("velocity");
    const auto value = t.optional_vector3("value");
    if (!velocity && !value) {
      t.fail_table("with type = \"displacement\" needs 'velocity' (m/s) or 'value' (m)");
    }
    if (velocity)
      b.velocity = to_vector(*velocity);
    if (value)
      b.value = to_vector(*value);
    b.start = t.number("start", b.start, Range::non_negative());
    b.stop = t.number("stop", b.stop);
  } else if (type == "elastic") {
    b.type = BoundaryType::elastic;
    b.components = read_components(t);
    b.stiffness = t.number("stiffness", required, Range::positive());
  } else {
    b.type = BoundaryType::symmetry;
  }
  t.finish();
  validate_at(t, b);
  return b;
}

TetrahedraSettings read_tetrahedra(SceneTable t, const std::filesystem::path& base) {
  TetrahedraSettings s;
  if (t.type_of("mesh") != toml::node_type::none) {
    s.mesh = resolve(base, t.string("mesh", required));
    s.mesh_unit = t.number("mesh_unit", s.mesh_unit, Range::positive());
    if (t.type_of("element_size") != toml::node_type::none)
      t.fail("element_size", "and 'mesh' exclude each other: the mesh is given");
  } else {
    s.element_size = t.number("element_size", required, Range::positive());
  }
  for (SceneTable r : t.tables("refine")) {
    if (!s.mesh.empty())
      r.fail_table("refines the meshing, and [tetrahedra] gives a mesh ('mesh')");
    TetRefinement refinement;
    refinement.face = parse_face("face", r.choice("face", required, face_names()));
    refinement.size = r.number("size", required, Range::positive());
    refinement.distance = r.number("distance", required, Range::positive());
    r.finish();
    try {
      refinement.validate(s.element_size);
    } catch (const InvalidSetting& e) {
      r.fail(e);
    }
    s.refine.push_back(refinement);
  }
  s.order = t.integer("order", s.order, Range::closed(1, 2));
  s.quadrature_degree = t.integer("quadrature_degree", s.quadrature_degree, Range::closed(1, 15));
  t.finish();
  validate_at(t, s);
  return s;
}

LoadSettings read_load(SceneTable t) {
  LoadSettings l;
  const toml::node_type face_type = t.type_of("face");
  if (face_type == toml::node_type::none)
    t.fail_table("needs 'face': one of " + join(face_names()));
  if (face_type != toml::node_type::string) {
    t.fail("face", "must be a face name (" + join(face_names()) +
                       "): a load is integrated over the parameters of a face, which a plane "
                       "selection does not have");
  }
  l.face = parse_face("face", t.choice("face", required, face_names()));
  t.choice("type", required, {"traction"});
  l.type = LoadType::traction;
  l.traction = to_vector(t.vector3("traction", required));
  l.start = t.number("start", l.start, Range::non_negative());
  l.ramp_time = t.number("ramp_time", l.ramp_time, Range::non_negative());
  t.finish();
  validate_at(t, l);
  return l;
}

TimeSettings read_time(SceneTable t) {
  TimeSettings s;
  s.end = t.number("end", required, Range::positive());
  s.dt = t.number("dt", required, Range::positive());
  s.dt_min = t.number("dt_min", s.dt / 1024.0, Range::positive());
  s.dt_max = t.number("dt_max", s.dt, Range::positive());
  s.adaptive = t.boolean("adaptive", s.adaptive);
  t.finish();
  validate_at(t, s);
  return s;
}

SolverSettings read_solver(std::optional<SceneTable> t) {
  SolverSettings s;
  if (!t)
    return s;
  s.formulation = t->choice("formulation", "mixed", {"mixed", "displacement"}) == "mixed"
                      ? Formulation::mixed
                      : Formulation::displacement;
  s.newton_max_iterations = t->integer("newton_max_iterations", s.newton_max_iterations);
  s.tolerance_residual = t->number("tolerance_residual", s.tolerance_residual);
  s.tolerance_energy = t->number("tolerance_energy", s.tolerance_energy);
  s.line_search = t->boolean("line_search", s.line_search);
  s.linear_solver = t->choice("linear_solver", "cholmod", {"cholmod", "umfpack"}) == "cholmod"
                        ? LinearSolverKind::cholmod
                        : LinearSolverKind::umfpack;
  s.tangent = t->choice("tangent", "consistent", {"consistent", "frozen_ce"}) == "consistent"
                  ? TangentKind::consistent
                  : TangentKind::frozen_ce;
  const std::string indefinite = t->choice("indefinite_tangent", "lu", {"lu", "shift", "cut"});
  s.indefinite_tangent = indefinite == "lu"      ? IndefiniteTangent::lu
                         : indefinite == "shift" ? IndefiniteTangent::shift
                                                 : IndefiniteTangent::cut;
  s.stall_iterations = t->integer("stall_iterations", s.stall_iterations);
  s.threads = t->integer("threads", s.threads);
  s.blas_threads = t->integer("blas_threads", s.blas_threads);
  t->finish();
  validate_at(*t, s);
  return s;
}

OutputSettings read_output(std::optional<SceneTable> t, const TimeSettings& time) {
  OutputSettings s;
  if (!t)
    return s;
  s.times = t->optional_numbers("times").value_or(s.times);
  s.every = t->number("every", s.every);
  s.fields = t->optional_strings("fields", OutputSettings::field_names()).value_or(s.fields);
  s.samples_per_element = t->integer("samples_per_element", s.samples_per_element);
  t->finish();
  validate_at(*t, s);
  try {
    s.check_within(time);
  } catch (const InvalidSetting& e) {
    t->fail(e);
  }
  return s;
}

ProbeSettings read_probe(SceneTable t) {
  ProbeSettings p;
  p.name = t.string("name", required);
  const std::string kind =
      t.choice("kind", required,
               {"point_displacement", "face_reaction", "volume", "stress_parts",
                "surface_stability", "element_layer", "material_ellipticity"});
  forbid_unused(
      t, "kind", kind,
      {{"point", {"point_displacement", "stress_parts", "surface_stability", "element_layer"}},
       {"xi", {"point_displacement", "stress_parts", "surface_stability", "element_layer"}},
       {"face", {"face_reaction"}},
       {"component", {"point_displacement", "face_reaction"}}});
  p.kind = kind == "point_displacement"  ? ProbeKind::point_displacement
           : kind == "face_reaction"     ? ProbeKind::face_reaction
           : kind == "volume"            ? ProbeKind::volume
           : kind == "stress_parts"      ? ProbeKind::stress_parts
           : kind == "surface_stability" ? ProbeKind::surface_stability
           : kind == "element_layer"     ? ProbeKind::element_layer
                                         : ProbeKind::material_ellipticity;
  if (auto point = t.optional_vector3("point"))
    p.point = to_vector(*point);
  if (auto xi = t.optional_vector3("xi"))
    p.xi = to_vector(*xi);
  if (p.kind == ProbeKind::face_reaction)
    p.face = read_face(t);
  p.component = t.choice("component", p.component, ProbeSettings::component_names());
  t.finish();
  validate_at(t, p);
  return p;
}

Scene scene_from_document(const toml::table& document, const std::filesystem::path& path) {
  SceneTable root(document, path.string());
  // Unknown top-level tables first: a misspelt [materal] explains a "missing [material]".
  for (const char* key : {"description", "discretisation", "tetrahedra", "geometry", "material",
                          "fibres", "boundary", "load", "time", "solver", "output", "probe"}) {
    root.allow(key);
  }
  root.finish();

  Scene scene;
  scene.file = path;
  const std::filesystem::path base = path.parent_path();
  scene.description = root.string("description", "");
  const std::string discretisation = root.choice("discretisation", "iga", {"iga", "tet"});
  forbid_unused(root, "discretisation", discretisation, {{"tetrahedra", {"tet"}}});
  if (discretisation == "tet") {
    scene.discretisation = Discretisation::tet;
    scene.tetrahedra = read_tetrahedra(root.table("tetrahedra", required), base);
  }
  scene.geometry = read_geometry(root.table("geometry", required), base);
  scene.material = read_material(root.table("material", required));
  scene.fibres = read_fibres(root.optional_table("fibres"), scene.geometry.centreline);
  for (SceneTable& entry : root.tables("boundary")) {
    scene.boundaries.push_back(read_boundary(entry));
  }
  if (scene.boundaries.empty()) {
    root.fail_table(
        "the scene needs at least one [[boundary]] entry (a body without supports has no unique "
        "equilibrium)");
  }
  for (SceneTable& entry : root.tables("load")) {
    scene.loads.push_back(read_load(entry));
  }
  scene.time = read_time(root.table("time", required));
  scene.solver = read_solver(root.optional_table("solver"));
  scene.output = read_output(root.optional_table("output"), scene.time);
  std::set<std::string> names;
  for (SceneTable& entry : root.tables("probe")) {
    scene.probes.push_back(read_probe(entry));
    if (!names.insert(scene.probes.back().name).second) {
      entry.fail("name", "repeats the name of an earlier [[probe]] (\"" + scene.probes.back().name +
                             "\"); names become CSV columns");
    }
  }
  return scene;
}

}  // namespace

Scene parse_scene(std::string_view text, const std::filesystem::path& path) {
  return scene_from_document(parse_toml_text(text, path.string()), path);
}

Scene load_scene(const std::filesystem::path& path) {
  return scene_from_document(parse_toml_file(path), path);
}

}  // namespace isomuscle::io
