// Scene files into Scene structs: a full scene round trip, the defaults, and the errors a user
// meets, each at its exact line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "io/scene_loader.hpp"
#include "io/scene_reader.hpp"
#include "io/setting_check.hpp"
#include "io_test_util.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::io {
namespace {

using testing_util::fresh_directory;
using testing_util::line_containing;
using testing_util::write_text;

// A folder with an (empty) IGES file, so that [geometry] iges = "shape.igs" exists.
class SceneLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_directory("scene");
    write_text(dir_ / "shape.igs", "");
    const auto& specs = materials::material_parameters("lu2010");
    ASSERT_FALSE(specs.empty());
    parameter_ = specs.front();
  }

  Scene parse(const std::string& text) { return parse_scene(text, dir_ / "scene.toml"); }

  // Parses text, which must fail; returns the error.
  SceneError error(const std::string& text) {
    try {
      parse(text);
    } catch (const SceneError& e) {
      return e;
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return SceneError("", 0, 0, "");
  }

  // The smallest valid scene, with extra text inserted before [time].
  std::string minimal(const std::string& extra = "") const {
    return "[geometry]\n"
           "iges = \"shape.igs\"\n"
           "[material]\n"
           "model = \"lu2010\"\n"
           "[[boundary]]\n"
           "face = \"v0\"\n"
           "type = \"fixed\"\n" +
           extra +
           "[time]\n"
           "end = 0.2\n"
           "dt = 0.005\n";
  }

  std::filesystem::path dir_;
  materials::ParameterSpec parameter_;
};

TEST_F(SceneLoader, EveryFieldRoundTrips) {
  // A parameter value inside its range and different from the default.
  const double value = std::isfinite(parameter_.max)
                           ? 0.5 * (parameter_.default_value + parameter_.max)
                           : 2.0 * parameter_.default_value + 1.0;
  const std::string text =
      "description = \"barrel, pulled\"\n"
      "[geometry]\n"
      "iges = \"shape.igs\"\n"
      "surface = 2\n"
      "centreline = \"u\"\n"
      "[geometry.refine]\n"
      "degree_elevation = [1, 0, 2]\n"
      "knot_insertion = [3, 4, 5]\n"
      "[material]\n"
      "model = \"lu2010\"\n"
      "[material.parameters]\n" +
      parameter_.name + " = " + format_number(value) +
      "\n"
      "[fibres]\n"
      "mode = \"segments\"\n"
      "direction = \"w\"\n"
      "segments = 3\n"
      "[[boundary]]\n"
      "face = \"u1\"\n"
      "type = \"fixed\"\n"
      "components = [\"z\", \"x\"]\n"
      "[[boundary]]\n"
      "face = { point = [0, 0, 0.05], normal = [0, 0, 2], tolerance = 1e-5 }\n"
      "type = \"displacement\"\n"
      "components = [\"z\"]\n"
      "velocity = [0, 0, 0.005]\n"
      "value = [0, 0, 0.001]\n"
      "start = 0.5\n"
      "stop = 2.4\n"
      "[[boundary]]\n"
      "face = \"w1\"\n"
      "type = \"symmetry\"\n"
      "[time]\n"
      "end = 3.0\n"
      "dt = 0.01\n"
      "dt_min = 1e-5\n"
      "dt_max = 0.05\n"
      "adaptive = false\n"
      "[solver]\n"
      "formulation = \"displacement\"\n"
      "newton_max_iterations = 40\n"
      "tolerance_residual = 1e-9\n"
      "tolerance_energy = 1e-14\n"
      "line_search = false\n"
      "linear_solver = \"umfpack\"\n"
      "tangent = \"frozen_ce\"\n"
      "indefinite_tangent = \"shift\"\n"
      "stall_iterations = 0\n"
      "threads = 2\n"
      "[output]\n"
      "times = [0.5, 1, 3.0]\n"
      "fields = [\"J\", \"fibre\", \"activation\"]\n"
      "samples_per_element = 3\n"
      "[[probe]]\n"
      "name = \"tip_z\"\n"
      "kind = \"point_displacement\"\n"
      "point = [0, 0, 0.05]\n"
      "component = \"z\"\n"
      "[[probe]]\n"
      "name = \"centre\"\n"
      "kind = \"stress_parts\"\n"
      "xi = [0.5, 0.5, 1]\n"
      "[[probe]]\n"
      "name = \"reaction\"\n"
      "kind = \"face_reaction\"\n"
      "face = \"u1\"\n"
      "component = \"magnitude\"\n"
      "[[probe]]\n"
      "name = \"volume\"\n"
      "kind = \"volume\"\n";
  const Scene s = parse(text);
  EXPECT_EQ(s.file, dir_ / "scene.toml");
  EXPECT_EQ(s.description, "barrel, pulled");
  EXPECT_EQ(s.geometry.iges, dir_ / "shape.igs");
  EXPECT_EQ(s.geometry.surface, 2);
  EXPECT_EQ(s.geometry.centreline, Direction::u);
  EXPECT_EQ(s.geometry.refine.degree_elevation, (std::array<int, 3>{1, 0, 2}));
  EXPECT_EQ(s.geometry.refine.knot_insertion, (std::array<int, 3>{3, 4, 5}));
  EXPECT_EQ(s.material.model, "lu2010");
  ASSERT_EQ(s.material.parameters.size(), 1u);
  EXPECT_EQ(s.material.parameters.at(parameter_.name), value);
  EXPECT_EQ(s.fibres.mode, FibreMode::segments);
  EXPECT_EQ(s.fibres.direction, Direction::w);
  EXPECT_EQ(s.fibres.segments, 3);

  ASSERT_EQ(s.boundaries.size(), 3u);
  const BoundarySettings& fixed = s.boundaries[0];
  EXPECT_EQ(fixed.where.face, Face::u1);
  EXPECT_FALSE(fixed.where.plane.has_value());
  EXPECT_EQ(fixed.type, BoundaryType::fixed);
  EXPECT_EQ(fixed.components, (std::array<bool, 3>{true, false, true}));
  const BoundarySettings& pulled = s.boundaries[1];
  ASSERT_TRUE(pulled.where.plane.has_value());
  EXPECT_FALSE(pulled.where.face.has_value());
  EXPECT_EQ(pulled.where.plane->point, Eigen::Vector3d(0, 0, 0.05));
  EXPECT_EQ(pulled.where.plane->normal, Eigen::Vector3d(0, 0, 1));  // normalised
  EXPECT_EQ(pulled.where.plane->tolerance, 1e-5);
  EXPECT_EQ(pulled.type, BoundaryType::displacement);
  EXPECT_EQ(pulled.components, (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(pulled.velocity, Eigen::Vector3d(0, 0, 0.005));
  EXPECT_EQ(pulled.value, Eigen::Vector3d(0, 0, 0.001));
  EXPECT_EQ(pulled.start, 0.5);
  EXPECT_EQ(pulled.stop, 2.4);
  // u(t) = value + velocity (min(t, stop) - start) from start on.
  EXPECT_EQ(pulled.prescribed_displacement(0.4), Eigen::Vector3d::Zero());
  EXPECT_NEAR(pulled.prescribed_displacement(1.5).z(), 0.001 + 0.005 * 1.0, 1e-15);
  EXPECT_NEAR(pulled.prescribed_displacement(3.0).z(), 0.001 + 0.005 * 1.9, 1e-15);
  EXPECT_EQ(s.boundaries[2].type, BoundaryType::symmetry);
  EXPECT_EQ(s.boundaries[2].where.face, Face::w1);

  EXPECT_EQ(s.time.end, 3.0);
  EXPECT_EQ(s.time.dt, 0.01);
  EXPECT_EQ(s.time.dt_min, 1e-5);
  EXPECT_EQ(s.time.dt_max, 0.05);
  EXPECT_FALSE(s.time.adaptive);

  EXPECT_EQ(s.solver.formulation, Formulation::displacement);
  EXPECT_EQ(s.solver.newton_max_iterations, 40);
  EXPECT_EQ(s.solver.tolerance_residual, 1e-9);
  EXPECT_EQ(s.solver.tolerance_energy, 1e-14);
  EXPECT_FALSE(s.solver.line_search);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::umfpack);
  EXPECT_EQ(s.solver.tangent, TangentKind::frozen_ce);
  EXPECT_EQ(s.solver.indefinite_tangent, IndefiniteTangent::shift);
  EXPECT_EQ(s.solver.stall_iterations, 0);
  EXPECT_EQ(s.solver.threads, 2);

  EXPECT_EQ(s.output.times, (std::vector<double>{0.5, 1.0, 3.0}));
  EXPECT_EQ(s.output.every, 0.0);
  EXPECT_EQ(s.output.fields, (std::vector<std::string>{"J", "fibre", "activation"}));
  EXPECT_EQ(s.output.samples_per_element, 3);

  ASSERT_EQ(s.probes.size(), 4u);
  EXPECT_EQ(s.probes[0].name, "tip_z");
  EXPECT_EQ(s.probes[0].kind, ProbeKind::point_displacement);
  EXPECT_EQ(s.probes[0].point, Eigen::Vector3d(0, 0, 0.05));
  EXPECT_FALSE(s.probes[0].xi.has_value());
  EXPECT_EQ(s.probes[0].component, "z");
  EXPECT_EQ(s.probes[1].kind, ProbeKind::stress_parts);
  EXPECT_EQ(s.probes[1].xi, Eigen::Vector3d(0.5, 0.5, 1.0));
  EXPECT_EQ(s.probes[2].kind, ProbeKind::face_reaction);
  ASSERT_TRUE(s.probes[2].face.has_value());
  EXPECT_EQ(s.probes[2].face->face, Face::u1);
  EXPECT_EQ(s.probes[2].component, "magnitude");
  EXPECT_EQ(s.probes[3].kind, ProbeKind::volume);
  EXPECT_NO_THROW(s.validate());
}

TEST_F(SceneLoader, DefaultsOfAMinimalScene) {
  const Scene s = parse(minimal());
  EXPECT_EQ(s.geometry.surface, 0);
  EXPECT_EQ(s.geometry.centreline, Direction::v);
  EXPECT_EQ(s.geometry.refine.degree_elevation, (std::array<int, 3>{0, 0, 0}));
  EXPECT_TRUE(s.material.parameters.empty());
  EXPECT_EQ(s.fibres.mode, FibreMode::isocurve);
  EXPECT_EQ(s.fibres.direction, Direction::v);  // the centreline
  EXPECT_EQ(s.boundaries[0].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(s.time.dt_min, 0.005 / 1024);
  EXPECT_EQ(s.time.dt_max, 0.005);
  EXPECT_TRUE(s.time.adaptive);
  EXPECT_EQ(s.solver.formulation, Formulation::mixed);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::cholmod);
  EXPECT_EQ(s.solver.indefinite_tangent, IndefiniteTangent::lu);
  EXPECT_EQ(s.solver.stall_iterations, 4);
  EXPECT_TRUE(s.output.times.empty());
  EXPECT_EQ(s.output.every, 0.0);
  EXPECT_TRUE(s.probes.empty());
  // Fibres follow the centreline when it is u.
  std::string u_scene = minimal("[fibres]\nmode = \"isocurve\"\n");
  u_scene.replace(u_scene.find("iges = \"shape.igs\"\n"), 19,
                  "iges = \"shape.igs\"\ncentreline = \"u\"\n");
  EXPECT_EQ(parse(u_scene).fibres.direction, Direction::u);
  // Constant fibres are normalised.
  EXPECT_EQ(parse(minimal("[fibres]\nmode = \"constant\"\nvector = [0, 3, 4]\n")).fibres.vector,
            Eigen::Vector3d(0, 0.6, 0.8));
}

TEST_F(SceneLoader, LoadsFromAFileAndResolvesTheIgesPathAgainstIt) {
  std::filesystem::create_directories(dir_ / "sub");
  write_text(dir_ / "sub" / "scene.toml",
             "[geometry]\niges = \"../shape.igs\"\n[material]\nmodel = \"lu2010\"\n"
             "[[boundary]]\nface = \"v0\"\ntype = \"fixed\"\n[time]\nend = 1\ndt = 0.1\n");
  const Scene s = load_scene(dir_ / "sub" / "scene.toml");
  EXPECT_EQ(s.geometry.iges, dir_ / "shape.igs");
  const std::string text = minimal();
  std::string missing = text;
  missing.replace(missing.find("shape.igs"), 9, "nothere.igs");
  const SceneError e = error(missing);
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.message(), "'iges' in [geometry] names no readable file (looked for " +
                             (dir_ / "nothere.igs").string() + ")");
}

TEST_F(SceneLoader, TypoInATableIsReportedBeforeTheKeyItHides) {
  std::string text = minimal();
  text.replace(text.find("model = "), 8, "modle = ");
  const SceneError e = error(text);
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.message(),
            "missing required key 'model' in [material]; found 'modle' on line 4: a "
            "misspelling?");
  const SceneError top = error("[materal]\nmodel = \"lu2010\"\n" + minimal());
  EXPECT_EQ(top.line(), 1);
  EXPECT_EQ(top.message().rfind("unknown table [materal]; did you mean [material]?", 0), 0u)
      << top.message();
  const std::string extra = minimal("[solver]\nlinear_solvr = \"umfpack\"\n");
  const SceneError key = error(extra);
  EXPECT_EQ(key.line(), line_containing(extra, "linear_solvr"));
  EXPECT_EQ(key.message(),
            "unknown key 'linear_solvr' in [solver]; did you mean 'linear_solver'? valid keys: "
            "formulation, newton_max_iterations, tolerance_residual, tolerance_energy, "
            "line_search, linear_solver, tangent, indefinite_tangent, stall_iterations, threads, "
            "blas_threads");
}

TEST_F(SceneLoader, MaterialModelAndParametersAreCheckedByTheFactory) {
  std::string text = minimal();
  text.replace(text.find("\"lu2010\""), 8, "\"lu2011\"");
  const SceneError model = error(text);
  EXPECT_EQ(model.line(), 4);
  EXPECT_EQ(model.message().rfind("'model' in [material] must be one of ", 0), 0u)
      << model.message();
  EXPECT_NE(model.message().find("(got \"lu2011\"); did you mean \"lu2010\"?"), std::string::npos)
      << model.message();

  std::string unknown = minimal();
  unknown.replace(unknown.find("[[boundary]]"), 0,
                  "[material.parameters]\n" + parameter_.name + "x = 1.0\n");
  const SceneError name = error(unknown);
  EXPECT_EQ(name.line(), line_containing(unknown, parameter_.name + "x = "));
  EXPECT_EQ(name.message().rfind("'" + parameter_.name +
                                     "x' in [material.parameters] is not a "
                                     "parameter of model \"lu2010\"; did you mean '" +
                                     parameter_.name + "'?",
                                 0),
            0u)
      << name.message();

  // Just outside the valid range of the first parameter.
  const double bad = std::isfinite(parameter_.min) ? parameter_.min - 1.0 : parameter_.max + 1.0;
  std::string range = minimal();
  range.replace(range.find("[[boundary]]"), 0,
                "[material.parameters]\n\n" + parameter_.name + " = " + format_number(bad) + "\n");
  const SceneError out = error(range);
  EXPECT_EQ(out.line(), line_containing(range, parameter_.name + " = "));
  EXPECT_EQ(out.message().rfind("'" + parameter_.name + "' in [material.parameters] must be in " +
                                    materials::describe_range(parameter_) + " (got " +
                                    format_number(bad) + ")",
                                0),
            0u)
      << out.message();
}

TEST_F(SceneLoader, InfiniteParametersPassWhereTheModelAllowsThem) {
  // e.g. lu2010's t1 = inf: activation never ends (thesis 3.26).
  for (const auto& spec : materials::material_parameters("lu2010")) {
    const double inf = std::numeric_limits<double>::infinity();
    std::string text = minimal();
    text.replace(text.find("[[boundary]]"), 0, "[material.parameters]\n" + spec.name + " = inf\n");
    if (materials::in_range(spec, inf)) {
      EXPECT_EQ(parse(text).material.parameters.at(spec.name), inf) << spec.name;
    } else {
      EXPECT_THROW(parse(text), SceneError) << spec.name;
    }
  }
  std::string nan = minimal();
  nan.replace(nan.find("[[boundary]]"), 0,
              "[material.parameters]\n" + parameter_.name + " = nan\n");
  EXPECT_EQ(error(nan).message(),
            "'" + parameter_.name + "' in [material.parameters] must be a number (got nan)");
}

TEST_F(SceneLoader, ModeAndTypeSpecificKeysAreRejectedElsewhere) {
  const std::string fibres = minimal("[fibres]\nmode = \"isocurve\"\nvector = [0, 0, 1]\n");
  const SceneError f = error(fibres);
  EXPECT_EQ(f.line(), line_containing(fibres, "vector ="));
  EXPECT_EQ(f.message(),
            "'vector' in [fibres] is used only with mode = \"constant\" (here mode = "
            "\"isocurve\")");
  const std::string needs = minimal("[fibres]\nmode = \"line\"\norigin = [0, 0, 0]\n");
  EXPECT_EQ(error(needs).message(), "missing required key 'insertion' in [fibres]");
  const std::string same =
      minimal("[fibres]\nmode = \"line\"\norigin = [0, 0, 1]\ninsertion = [0, 0, 1]\n");
  EXPECT_EQ(error(same).line(), line_containing(same, "insertion ="));

  std::string fixed = minimal();
  fixed.replace(fixed.find("type = \"fixed\"\n") + 15, 0, "velocity = [0, 0, 1]\n");
  const SceneError b = error(fixed);
  EXPECT_EQ(b.line(), line_containing(fixed, "velocity ="));
  EXPECT_EQ(b.message(),
            "'velocity' in [[boundary]] #1 is used only with type = \"displacement\" (here type "
            "= \"fixed\")");
}

TEST_F(SceneLoader, BoundaryConditionsAreChecked) {
  const std::string plane = minimal(
      "[[boundary]]\nface = { point = [0, 0, 0], normal = [0, 0, 0] }\ntype = \"symmetry\"\n");
  const SceneError zero = error(plane);
  EXPECT_EQ(zero.line(), line_containing(plane, "normal = [0, 0, 0]"));
  EXPECT_EQ(zero.message(), "'normal' in 'face' of [[boundary]] #2 must not be the zero vector");

  const std::string mask = minimal(
      "[[boundary]]\nface = \"v1\"\ntype = \"displacement\"\ncomponents = [\"z\"]\n"
      "velocity = [0.001, 0, 0.005]\n");
  const SceneError m = error(mask);
  EXPECT_EQ(m.line(), line_containing(mask, "components = [\"z\"]"));
  EXPECT_EQ(m.message(),
            "'components' in [[boundary]] #2 leaves x free, but the prescribed motion moves "
            "along x");

  const std::string face = minimal("[[boundary]]\nface = \"v2\"\ntype = \"fixed\"\n");
  EXPECT_EQ(error(face).message(),
            "'face' in [[boundary]] #2 must be one of u0, u1, v0, v1, w0, w1 (got \"v2\"); did "
            "you mean \"v0\"?");
  const std::string motion = minimal("[[boundary]]\nface = \"v1\"\ntype = \"displacement\"\n");
  const SceneError none = error(motion);
  EXPECT_EQ(none.line(), line_containing(motion, "face = \"v1\"") - 1);
  EXPECT_EQ(none.message(),
            "[[boundary]] #2 with type = \"displacement\" needs 'velocity' (m/s) or 'value' (m)");
  const std::string stop = minimal(
      "[[boundary]]\nface = \"v1\"\ntype = \"displacement\"\nvelocity = [0, 0, 1]\nstart = 1\n"
      "stop = 0.5\n");
  EXPECT_EQ(error(stop).message(), "'stop' in [[boundary]] #2 must be > start (1) (got 0.5)");

  // Elastic supports: springs on a named face, a stiffness in Pa/m, components as for "fixed".
  const Scene sprung = parse(minimal(
      "[[boundary]]\nface = \"v1\"\ntype = \"elastic\"\nstiffness = 2e6\ncomponents = [\"z\"]\n"));
  ASSERT_EQ(sprung.boundaries.size(), 2u);
  EXPECT_EQ(sprung.boundaries[1].type, BoundaryType::elastic);
  EXPECT_EQ(sprung.boundaries[1].stiffness, 2e6);
  EXPECT_EQ(sprung.boundaries[1].components, (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(parse(minimal("[[boundary]]\nface = \"v1\"\ntype = \"elastic\"\nstiffness = 1\n"))
                .boundaries[1]
                .components,
            (std::array<bool, 3>{true, true, true}));
  const std::string soft =
      minimal("[[boundary]]\nface = \"v1\"\ntype = \"elastic\"\nstiffness = 0\n");
  EXPECT_EQ(error(soft).line(), line_containing(soft, "stiffness = 0"));
  EXPECT_EQ(error(soft).message(), "'stiffness' in [[boundary]] #2 must be > 0 (got 0)");
  const std::string missing = minimal("[[boundary]]\nface = \"v1\"\ntype = \"elastic\"\n");
  EXPECT_NE(error(missing).message().find("'stiffness'"), std::string::npos)
      << error(missing).message();
  const std::string stray =
      minimal("[[boundary]]\nface = \"v1\"\ntype = \"fixed\"\nstiffness = 1e6\n");
  EXPECT_EQ(error(stray).line(), line_containing(stray, "stiffness = 1e6"));
  EXPECT_NE(error(stray).message().find("elastic"), std::string::npos) << error(stray).message();
  const std::string on_plane = minimal(
      "[[boundary]]\nface = { point = [0, 0, 0], normal = [0, 0, 1] }\ntype = \"elastic\"\n"
      "stiffness = 1e6\n");
  EXPECT_EQ(error(on_plane).message(),
            "'face' in [[boundary]] #2 of an elastic support must be a face name (u0, u1, v0, v1, "
            "w0, w1): the springs are spread over the face's area");
  const std::string typo = minimal("[[boundary]]\nface = \"v1\"\ntype = \"elastik\"\n");
  EXPECT_NE(error(typo).message().find("\"elastic\""), std::string::npos) << error(typo).message();

  std::string no_boundary = minimal();
  const std::string entry = "[[boundary]]\nface = \"v0\"\ntype = \"fixed\"\n";
  no_boundary.erase(no_boundary.find(entry), entry.size());
  EXPECT_STREQ(error(no_boundary).what(),
               ((dir_ / "scene.toml").string() +
                ": the scene needs at least one [[boundary]] entry (a body without supports has "
                "no unique equilibrium)")
                   .c_str());
}

// [geometry] construction = "extrude" and [[load]] tables: values, defaults, the load factor, and
// the errors at their lines.
TEST_F(SceneLoader, ExtrusionAndLoads) {
  std::string text = minimal(
      "[[load]]\nface = \"u1\"\ntype = \"traction\"\ntraction = [0, 0.05, 0]\nramp_time = 2\n"
      "start = 1\n");
  text.replace(text.find("iges = \"shape.igs\"\n") + 19, 0,
               "construction = \"extrude\"\nextrusion = [0, 0, 0.5]\n");
  const Scene scene = parse(text);
  EXPECT_EQ(scene.geometry.construction, Construction::extrude);
  EXPECT_EQ(scene.geometry.extrusion, Eigen::Vector3d(0, 0, 0.5));
  ASSERT_EQ(scene.loads.size(), 1u);
  const LoadSettings& load = scene.loads[0];
  EXPECT_EQ(load.face, Face::u1);
  EXPECT_EQ(load.traction, Eigen::Vector3d(0, 0.05, 0));
  EXPECT_EQ(load.factor(0.5), 0.0);
  EXPECT_DOUBLE_EQ(load.factor(2.0), 0.5);
  EXPECT_EQ(load.factor(7.0), 1.0);
  EXPECT_EQ(parse(minimal()).geometry.construction, Construction::shrink);
  EXPECT_TRUE(parse(minimal()).loads.empty());

  std::string centreline = text;
  centreline.replace(centreline.find("extrusion ="), 0, "centreline = \"v\"\n");
  const SceneError c = error(centreline);
  EXPECT_EQ(c.line(), line_containing(centreline, "centreline ="));
  EXPECT_EQ(c.message(),
            "'centreline' in [geometry] is used only with construction = \"shrink\" (here "
            "construction = \"extrude\")");
  std::string no_vector = text;
  no_vector.erase(no_vector.find("extrusion = [0, 0, 0.5]\n"), 24);
  EXPECT_EQ(error(no_vector).message(), "missing required key 'extrusion' in [geometry]");
  std::string zero = text;
  zero.replace(zero.find("[0, 0, 0.5]"), 11, "[0, 0, 0]");
  const SceneError z = error(zero);
  EXPECT_EQ(z.line(), line_containing(zero, "extrusion ="));
  EXPECT_EQ(z.message(), "'extrusion' in [geometry] must not be the zero vector");

  const std::string plane = minimal(
      "[[load]]\nface = { point = [0, 0, 0], normal = [1, 0, 0] }\ntype = \"traction\"\n"
      "traction = [1, 0, 0]\n");
  const SceneError p = error(plane);
  EXPECT_EQ(p.line(), line_containing(plane, "face = {"));
  EXPECT_NE(p.message().find("must be a face name"), std::string::npos) << p.message();
  const std::string kind =
      minimal("[[load]]\nface = \"u1\"\ntype = \"pressure\"\ntraction = [1, 0, 0]\n");
  EXPECT_EQ(error(kind).message(),
            "'type' in [[load]] #1 must be one of traction (got \"pressure\")");
  const std::string ramp = minimal(
      "[[load]]\nface = \"u1\"\ntype = \"traction\"\ntraction = [1, 0, 0]\nramp_time = -1\n");
  EXPECT_EQ(error(ramp).line(), line_containing(ramp, "ramp_time ="));
}

// Knots at chosen parameters (refinement concentrated next to the axis): read per direction,
// checked to be strictly increasing inside (0, 1), at the line of the key.
TEST_F(SceneLoader, ConcentratedKnotsAreReadAndChecked) {
  const auto with_knots = [this](const std::string& knots) {
    std::string text = minimal();
    text.insert(text.find("[material]"), "[geometry.refine]\nknots = { " + knots + " }\n");
    return text;
  };
  const Scene s = parse(with_knots("w = [0.9, 0.97], u = [0.5]"));
  EXPECT_EQ(s.geometry.refine.knots[2], (std::vector<double>{0.9, 0.97}));
  EXPECT_EQ(s.geometry.refine.knots[0], (std::vector<double>{0.5}));
  EXPECT_TRUE(s.geometry.refine.knots[1].empty());

  const std::string outside = with_knots("w = [0.9, 1.0]");
  const SceneError e1 = error(outside);
  EXPECT_EQ(e1.line(), line_containing(outside, "knots ="));
  EXPECT_NE(e1.message().find("must be in (0, 1)"), std::string::npos) << e1.message();
  const std::string unordered = with_knots("w = [0.97, 0.9]");
  const SceneError e2 = error(unordered);
  EXPECT_EQ(e2.line(), line_containing(unordered, "knots ="));
  EXPECT_NE(e2.message().find("strictly increasing"), std::string::npos) << e2.message();
  const SceneError e3 = error(with_knots("r = [0.5]"));
  EXPECT_NE(e3.message().find("unknown key"), std::string::npos) << e3.message();
}

TEST_F(SceneLoader, ContinuityIsReadAndChecked) {
  const auto with_continuity = [this](const std::string& value) {
    std::string text = minimal();
    text.insert(text.find("[material]"), "[geometry.refine]\ncontinuity = " + value + "\n");
    return text;
  };
  EXPECT_FALSE(parse(minimal()).geometry.refine.continuity.has_value());
  EXPECT_EQ(parse(with_continuity("0")).geometry.refine.continuity, 0);
  const std::string negative = with_continuity("-1");
  const SceneError e = error(negative);
  EXPECT_EQ(e.line(), line_containing(negative, "continuity ="));
  EXPECT_NE(e.message().find("'continuity'"), std::string::npos) << e.message();
  EXPECT_NE(error(with_continuity("0.5")).message().find("integer"), std::string::npos);
}

TEST_F(SceneLoader, TimeAndOutputConsistency) {
  std::string dt = minimal();
  dt.replace(dt.find("dt = 0.005"), 10, "dt = 0.5");
  const SceneError big = error(dt);
  EXPECT_EQ(big.line(), line_containing(dt, "dt = 0.5"));
  EXPECT_EQ(big.message(), "'dt' in [time] must be in (0, 0.2] (got 0.5)");

  const std::string dt_min = minimal() + "dt_min = 0.01\n";
  EXPECT_EQ(error(dt_min).message(), "'dt_min' in [time] must be in (0, 0.005] (got 0.01)");
  EXPECT_EQ(error(dt_min).line(), line_containing(dt_min, "dt_min"));

  const std::string late = minimal() + "[output]\ntimes = [0.1, 0.3]\n";
  const SceneError t = error(late);
  EXPECT_EQ(t.line(), line_containing(late, "times ="));
  EXPECT_EQ(t.message(), "'times' in [output] must lie within [0, end = 0.2] of [time] (got 0.3)");
  const std::string order = minimal() + "[output]\ntimes = [0.1, 0.1]\n";
  EXPECT_EQ(error(order).message(),
            "'times' in [output] element 2 must be > 0.1 (got 0.1); times must increase");
  const std::string both = minimal() + "[output]\ntimes = [0.1]\nevery = 0.05\n";
  EXPECT_EQ(error(both).line(), line_containing(both, "every ="));
  const std::string fields = minimal() + "[output]\nfields = [\"stress\"]\n";
  EXPECT_EQ(error(fields).message(),
            "element 1 of 'fields' in [output] must be one of displacement, cauchy_stress, J, "
            "fibre, activation (got \"stress\")");
}

TEST_F(SceneLoader, ProbesAreChecked) {
  const std::string twice = minimal() +
                            "[[probe]]\nname = \"v\"\nkind = \"volume\"\n"
                            "[[probe]]\nname = \"v\"\nkind = \"volume\"\n";
  const SceneError e = error(twice);
  const std::string second = twice.substr(0, twice.rfind("name = \"v\""));
  EXPECT_EQ(e.line(), 1 + static_cast<int>(std::count(second.begin(), second.end(), '\n')));
  EXPECT_EQ(e.message(),
            "'name' in [[probe]] #2 repeats the name of an earlier [[probe]] (\"v\"); names "
            "become CSV columns");
  const std::string point =
      minimal() + "[[probe]]\nname = \"tip\"\nkind = \"point_displacement\"\n";
  EXPECT_EQ(error(point).message(),
            "'point' in [[probe]] #1 or 'xi' (one of them) is needed by kind = "
            "\"point_displacement\"");
  const std::string xi =
      minimal() + "[[probe]]\nname = \"tip\"\nkind = \"stress_parts\"\nxi = [0.5, 1.5, 0]\n";
  EXPECT_EQ(error(xi).message(), "'xi' in [[probe]] #1 element 2 must be in [0, 1] (got 1.5)");
  const std::string name = minimal() + "[[probe]]\nname = \"a b\"\nkind = \"volume\"\n";
  EXPECT_EQ(error(name).line(), line_containing(name, "a b"));
  // The surface check and the element's layer are placed by a point (or xi), never by a face or a
  // component.
  for (const ProbeKind kind : {ProbeKind::surface_stability, ProbeKind::element_layer}) {
    const std::string head =
        minimal() + "[[probe]]\nname = \"deep\"\nkind = \"" + to_string(kind) + "\"\n";
    const Scene placed = parse(head + "point = [0.001, 0.002, 0.01]\n");
    ASSERT_EQ(placed.probes.size(), 1u);
    EXPECT_EQ(placed.probes[0].kind, kind);
    EXPECT_EQ(placed.probes[0].point, Eigen::Vector3d(0.001, 0.002, 0.01));
    EXPECT_EQ(parse(head + "xi = [0.5, 0.5, 0]\n").probes[0].xi, Eigen::Vector3d(0.5, 0.5, 0.0));
    EXPECT_EQ(error(head).message(),
              std::string("'point' in [[probe]] #1 or 'xi' (one of them) is needed by kind = \"") +
                  to_string(kind) + "\"");
    const std::string component = head + "point = [0, 0, 0]\ncomponent = \"x\"\n";
    EXPECT_EQ(error(component).line(), line_containing(component, "component"));
  }
  // The material's ellipticity is scanned over the whole body: no point, face or component.
  const std::string body = minimal() + "[[probe]]\nname = \"e\"\nkind = \"material_ellipticity\"\n";
  ASSERT_EQ(parse(body).probes.size(), 1u);
  EXPECT_EQ(parse(body).probes[0].kind, ProbeKind::material_ellipticity);
  EXPECT_STREQ(to_string(ProbeKind::material_ellipticity), "material_ellipticity");
  for (const char* key :
       {"point = [0, 0, 0]\n", "xi = [0, 0, 0]\n", "face = \"v0\"\n", "component = \"x\"\n"}) {
    const std::string placed = body + key;
    const SceneError misplaced = error(placed);
    EXPECT_EQ(misplaced.line(), 1 + static_cast<int>(std::count(body.begin(), body.end(), '\n')))
        << key;
    EXPECT_NE(misplaced.message().find("material_ellipticity"), std::string::npos)
        << misplaced.message();
  }
  const std::string typo = minimal() + "[[probe]]\nname = \"deep\"\nkind = \"surface\"\n";
  for (const char* choice : {"surface_stability", "element_layer", "material_ellipticity"})
    EXPECT_NE(error(typo).message().find(choice), std::string::npos) << error(typo).message();
}

TEST_F(SceneLoader, ProgrammaticScenesValidateWithQualifiedKeys) {
  Scene s = parse(minimal());
  s.time.dt = -1.0;
  try {
    s.validate();
    ADD_FAILURE() << "no throw";
  } catch (const InvalidSetting& e) {
    EXPECT_EQ(e.key(), "time.dt");
    EXPECT_STREQ(e.what(), "'time.dt' must be in (0, 0.2] (got -1)");
  }
  s = parse(minimal());
  s.probes.resize(2);
  s.probes[0].name = s.probes[1].name = "same";
  try {
    s.validate();
    ADD_FAILURE() << "no throw";
  } catch (const InvalidSetting& e) {
    EXPECT_EQ(e.key(), "probe[1].name");
  }
}

// [tetrahedra] with local refinement next to a face ([[tetrahedra.refine]]): values, and the
// errors a user meets, each at its line.
TEST_F(SceneLoader, TetrahedraAndTheirLocalRefinement) {
  const std::string head = "discretisation = \"tet\"\n[tetrahedra]\nelement_size = 0.001\n";
  const std::string refine =
      "[[tetrahedra.refine]]\nface = \"v0\"\nsize = 0.0003\n"
      "distance = 0.002\n";
  const Scene s = parse(head + refine + minimal());
  EXPECT_EQ(s.discretisation, Discretisation::tet);
  EXPECT_EQ(s.tetrahedra.element_size, 0.001);
  ASSERT_EQ(s.tetrahedra.refine.size(), 1u);
  EXPECT_EQ(s.tetrahedra.refine[0].face, Face::v0);
  EXPECT_EQ(s.tetrahedra.refine[0].size, 0.0003);
  EXPECT_EQ(s.tetrahedra.refine[0].distance, 0.002);
  EXPECT_TRUE(parse(head + minimal()).tetrahedra.refine.empty());

  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = head + refine + minimal();
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string coarse = with("size = 0.0003", "size = 0.0015");
  const SceneError c = error(coarse);
  EXPECT_EQ(c.line(), line_containing(coarse, "size = 0.0015"));
  EXPECT_EQ(c.message(),
            "'size' in [[tetrahedra.refine]] #1 must be smaller than [tetrahedra] element_size "
            "(0.001 m), got 0.0015");
  const std::string face = with("face = \"v0\"", "face = \"v9\"");
  EXPECT_EQ(error(face).message(),
            "'face' in [[tetrahedra.refine]] #1 must be one of u0, u1, v0, v1, w0, w1 (got "
            "\"v9\"); did you mean \"v0\"?");
  const std::string typo = with("distance", "distanse");
  EXPECT_EQ(
      error(typo).message(),
      "missing required key 'distance' in [[tetrahedra.refine]] #1; found 'distanse' on line " +
          std::to_string(line_containing(typo, "distanse")) + ": a misspelling?");
  const std::string negative = with("distance = 0.002", "distance = -0.002");
  EXPECT_EQ(error(negative).line(), line_containing(negative, "distance = -0.002"));
  // A given mesh is not meshed, so it cannot be refined.
  const std::string given = with("element_size = 0.001", "mesh = \"shape.igs\"");
  const SceneError g = error(given);
  EXPECT_EQ(g.line(), line_containing(given, "[[tetrahedra.refine]]"));
  EXPECT_EQ(g.message(),
            "[[tetrahedra.refine]] #1 refines the meshing, and [tetrahedra] gives a mesh ('mesh')");

  // Programmatic scenes are checked by validate() with the qualified key.
  Scene programmatic = s;
  programmatic.tetrahedra.refine[0].size = 0.002;
  try {
    programmatic.validate();
    ADD_FAILURE() << "no throw";
  } catch (const InvalidSetting& e) {
    EXPECT_EQ(e.key(), "tetrahedra.refine.size");
  }
}

// [tetrahedra] quadrature_degree: absent means the order's default (0 here, tet::default_tet_rule
// in the run); the rules that would make a wrong or indefinite discretisation are refused at
// their line with the reason and the choices.
TEST_F(SceneLoader, TetrahedraQuadratureDegree) {
  const std::string head = "discretisation = \"tet\"\n[tetrahedra]\nelement_size = 0.001\n";
  EXPECT_EQ(parse(head + minimal()).tetrahedra.quadrature_degree, 0);
  EXPECT_EQ(parse(head + "quadrature_degree = 4\n" + minimal()).tetrahedra.quadrature_degree, 4);
  EXPECT_EQ(
      parse(head + "order = 1\nquadrature_degree = 1\n" + minimal()).tetrahedra.quadrature_degree,
      1);
  const auto refused = [&](const std::string& lines, const std::string& why) {
    const std::string text = head + lines + minimal();
    const SceneError e = error(text);
    EXPECT_EQ(e.line(), line_containing(text, "quadrature_degree")) << lines;
    EXPECT_NE(e.message().find(why), std::string::npos) << e.message();
  };
  refused("quadrature_degree = 3\n", "negative weight");
  refused("quadrature_degree = 1\n", "zero-energy modes");
  refused("quadrature_degree = 16\n", "'quadrature_degree' in [tetrahedra]");
  refused("quadrature_degree = 0\n", "'quadrature_degree' in [tetrahedra]");
}

TEST_F(SceneLoader, SyntaxErrorsInAFile) {
  write_text(dir_ / "bad.toml", "[time]\nend = 1\ndt = \n");
  try {
    load_scene(dir_ / "bad.toml");
    ADD_FAILURE() << "no throw";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.file(), (dir_ / "bad.toml").string());
    EXPECT_EQ(e.message().rfind("TOML syntax error: ", 0), 0u) << e.message();
  }
}

}  // namespace
}  // namespace isomuscle::io
