// The thesis example suite (SPEC section 5, thesis 5.6) in examples/<shape>/: every committed
// scene loads, validates and builds its model (ExampleScenes: fast), the [geometry] extract option
// cuts the 1/8 torus exactly and rejects bad ranges at their line, and a small version of every
// example (coarse refinement, 0.02 s instead of 0.2 s: a modified copy of the committed scene in a
// temporary folder) runs through the CLI and shows the effect it is there for (SlowExamples):
// the free ends of the cone and the barrel move towards the fixed ones by about the committed
// examples' amounts, the 1/8 torus keeps its symmetry planes and its volume and shrinks its ring,
// the half torus and the depressor anguli oris converge with both fibre fields, their free ends
// move and their volume is kept.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "geometry/volume_measures.hpp"
#include "io/iga_run_probes.hpp"
#include "io/iga_run_setup.hpp"
#include "io/scene_loader.hpp"
#include "io/scene_reader.hpp"

namespace isomuscle {
namespace {

namespace fs = std::filesystem;
using cli_test::CliResult;
using cli_test::read_csv;
using cli_test::read_text;
using Table = cli_test::CsvTable;

const fs::path kExamples = fs::path(ISOMUSCLE_SOURCE_DIR) / "examples";

// The committed scenes, examples/*/*.toml, sorted.
std::vector<fs::path> committed_scenes() {
  std::vector<fs::path> scenes;
  for (const auto& dir : fs::directory_iterator(kExamples)) {
    if (!dir.is_directory())
      continue;
    for (const auto& f : fs::directory_iterator(dir.path()))
      if (f.path().extension() == ".toml")
        scenes.push_back(f.path());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// ---- ExampleScenes: fast checks without running ----

// Every committed scene is valid: it loads (schema, ranges, file:line errors otherwise), its model
// builds (IGES file, shrink, extract, refinement, fibres, boundary nodes) and its probes resolve
// (points inside the solid, faces not empty).
TEST(ExampleScenes, EveryCommittedSceneLoadsBuildsAndResolvesItsProbes) {
  const std::vector<fs::path> scenes = committed_scenes();
  // barrel (3), cone (2), torus (1), half torus (2), DAO (2), and any scene added later.
  EXPECT_GE(scenes.size(), 10u);
  for (const fs::path& path : scenes) {
    SCOPED_TRACE(path.string());
    try {
      const io::Scene scene = io::load_scene(path);
      EXPECT_FALSE(scene.description.empty());
      const io::IgaModel model = io::build_iga_model(scene, 1);
      const io::IgaProbes probes(scene.probes, model);
      EXPECT_FALSE(probes.columns().empty());
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

// The torus scene's extract = { u = [0, 1/2], v = [0, 1/4] } is exactly the 1/8 torus x, y,
// z >= 0: its volume is 2 pi^2 R r^2 / 8 (Gauss quadrature of the exact NURBS piece refined until
// converged to 1e-13, so to round-off, not to a tessellation error), no control point lies below a
// symmetry plane, and its faces u0, u1 lie in z = 0, v0 in y = 0 and v1 in x = 0 (evaluated at
// interior face points).
TEST(ExampleScenes, TorusExtractIsExactlyOneEighth) {
  const io::Scene scene = io::load_scene(kExamples / "torus" / "contract.toml");
  const io::IgaModel model = io::build_iga_model(scene, 1);
  const double ring = 0.013, tube = 0.004;
  const double eighth = 2.0 * std::numbers::pi * std::numbers::pi * ring * tube * tube / 8.0;
  EXPECT_NEAR(geometry::converged_solid_volume(model.unrefined).volume, eighth, 1e-12 * eighth);
  EXPECT_NEAR(geometry::converged_solid_volume(model.space->volume()).volume, eighth,
              1e-12 * eighth);
  for (const Eigen::Vector3d& p : model.space->volume().points())
    EXPECT_GE(p.minCoeff(), -1e-15) << p.transpose();

  const geometry::NurbsVolume& v = model.space->volume();
  for (double s : {0.2, 0.5, 0.9}) {
    for (double t : {0.1, 0.6}) {
      // Scene naming (u, v, w), mapped by the frame to the solid's parameters.
      EXPECT_NEAR(v.evaluate(model.frame.solid_xi({0.0, s, t})).z(), 0.0, 1e-15);  // u0
      EXPECT_NEAR(v.evaluate(model.frame.solid_xi({1.0, s, t})).z(), 0.0, 1e-15);  // u1
      EXPECT_NEAR(v.evaluate(model.frame.solid_xi({s, 0.0, t})).y(), 0.0, 1e-15);  // v0
      EXPECT_NEAR(v.evaluate(model.frame.solid_xi({s, 1.0, t})).x(), 0.0, 1e-15);  // v1
    }
  }
  // u = 0 is the outer equator, u = 1 the inner one, u = 1/2 the top of the tube.
  const Eigen::Vector3d outer = v.evaluate(model.frame.solid_xi({0.0, 0.0, 0.0}));
  const Eigen::Vector3d inner = v.evaluate(model.frame.solid_xi({1.0, 0.0, 0.0}));
  const Eigen::Vector3d top = v.evaluate(model.frame.solid_xi({0.5, 0.0, 0.0}));
  EXPECT_NEAR((outer - Eigen::Vector3d(ring + tube, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((inner - Eigen::Vector3d(ring - tube, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((top - Eigen::Vector3d(ring, 0.0, tube)).norm(), 0.0, 1e-15);
}

// A point_displacement probe with component = "normal" reads u . n with n the outward normal of
// the lateral surface: under the radial field u = eps (x, y, 0) (committed directly, the barrel's
// fixed end v0 does not reach mid-length: its functions vanish there) the mid-length points of the
// barrel, where the profile is parallel to the axis, give eps r_middle; a point inside is refused.
TEST(ExampleScenes, NormalDisplacementProbeIsOutward) {
  io::Scene scene = io::load_scene(kExamples / "barrel" / "contract.toml");
  io::ProbeSettings normal;
  normal.name = "n";
  normal.kind = io::ProbeKind::point_displacement;
  normal.xi = Eigen::Vector3d(0.3, 0.5, 0.0);
  normal.component = "normal";
  scene.probes = {normal};
  io::IgaModel model = io::build_iga_model(scene, 1);
  const io::IgaProbes probes(scene.probes, model);
  ASSERT_EQ(probes.points().size(), 1u);
  const Eigen::Vector3d X = probes.points()[0].second;
  const double r_middle = 0.0175 / 2.0;
  EXPECT_NEAR(std::hypot(X.x(), X.y()), r_middle, 1e-12);
  EXPECT_NEAR(X.z(), 0.025, 1e-12);
  iga::Problem& problem = *model.problem;
  const double eps = 1e-3;
  Eigen::VectorXd full(model.dofs->num_dofs());
  for (int n = 0; n < model.dofs->num_nodes(); ++n) {
    const Eigen::Vector3d& P = model.dofs->position(n);
    full.segment<3>(3 * n) = eps * Eigen::Vector3d(P.x(), P.y(), 0.0);
  }
  Eigen::VectorXd free;
  problem.constraints().restrict_to_free(full, free);
  problem.begin_step(1e-3, 1e-3);
  problem.commit_step(free);
  std::vector<double> values;
  probes.values(problem, values);
  ASSERT_EQ(values.size(), 1u);
  EXPECT_NEAR(values[0], eps * r_middle, 1e-12 * r_middle);

  scene.probes[0].xi = Eigen::Vector3d(0.3, 0.5, 0.5);
  try {
    const io::IgaProbes inside(scene.probes, model);
    ADD_FAILURE() << "a point inside the solid has no surface normal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("boundary surface"), std::string::npos) << e.what();
  }
}

// Bad extract ranges end in a SceneError at the line of the key, naming it and the valid range.
TEST(ExampleScenes, ExtractRangeErrorsNameTheKeyAndLine) {
  const std::string iges = (kExamples / "geometry" / "torus.igs").string();
  const auto scene_with = [&](const std::string& extract) {
    return "[geometry]\niges = \"" + iges + "\"\n" + extract +
           "\n[material]\nmodel = \"tang2009\"\n[[boundary]]\nface = \"v0\"\ntype = \"fixed\"\n"
           "[time]\nend = 0.01\ndt = 0.01\n";
  };
  const auto error_of = [&](const std::string& extract) -> std::string {
    try {
      io::parse_scene(scene_with(extract), "t.toml");
    } catch (const io::SceneError& e) {
      EXPECT_EQ(e.line(), 3) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no error for " << extract;
    return "";
  };
  std::string m = error_of("extract = { u = [0.5, 0.25] }");
  EXPECT_NE(m.find("'u'"), std::string::npos) << m;
  EXPECT_NE(m.find("0 <= a < b <= 1"), std::string::npos) << m;
  m = error_of("extract = { v = [0.0, 1.5] }");
  EXPECT_NE(m.find("'v'"), std::string::npos) << m;
  m = error_of("extract = { v = [0.0] }");
  EXPECT_NE(m.find("'v'"), std::string::npos) << m;
  m = error_of("extract = { x = [0.0, 0.5] }");
  EXPECT_NE(m.find("'x'"), std::string::npos) << m;
  m = error_of("extract = [0.0, 0.5]");
  EXPECT_NE(m.find("extract"), std::string::npos) << m;
  // A full range is the default and accepted.
  EXPECT_NO_THROW(io::parse_scene(scene_with("extract = { w = [0.0, 1.0] }"), "t.toml"));
}

// ---- SlowExamples: small versions of the committed examples through the CLI ----

// Replaces the first line that starts with `start` by `line`; a failure when there is none.
std::string replace_line(std::string text, const std::string& start, const std::string& line) {
  std::size_t at = text.rfind(start, 0) == 0 ? 0 : text.find("\n" + start);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no line starting with '" << start << "'";
    return text;
  }
  if (at > 0 || text[0] == '\n')
    ++at;
  const std::size_t end = text.find('\n', at);
  text.replace(at, end - at, line);
  return text;
}

class SlowExamples : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("isomuscle_test_examples_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // A small copy of a committed scene: refinement knot_insertion, end = 0.02 s, one output at the
  // end with the displacement only, the IGES path made absolute; extra text appended (probes).
  static fs::path small_copy(const std::string& scene, const std::string& knot_insertion,
                             const std::string& extra = "") {
    std::string text = read_text(kExamples / scene);
    EXPECT_FALSE(text.empty()) << scene;
    const std::string relative = "\"../geometry/";
    const std::size_t at = text.find(relative);
    EXPECT_NE(at, std::string::npos) << scene;
    if (at != std::string::npos)
      text.replace(at, relative.size(), "\"" + (kExamples / "geometry").string() + "/");
    text = replace_line(text, "knot_insertion", "knot_insertion = " + knot_insertion);
    text = replace_line(text, "end = ", "end = " + std::to_string(kEnd));
    text = replace_line(text, "times = ", "times = [" + std::to_string(kEnd) + "]");
    text = replace_line(text, "fields = ", "fields = [\"displacement\"]");
    text += extra;
    std::string name = scene;
    std::replace(name.begin(), name.end(), '/', '_');
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }

  static CliResult run(const fs::path& scene, const fs::path& out) {
    return cli_test::run_isomuscle("run " + scene.string() + " --out " + out.string(),
                                   dir_ / "stderr.txt");
  }

  // Runs a small copy; checks that it converged to the end time; returns its probes.
  static Table run_small(const std::string& scene, const std::string& knot_insertion,
                         const std::string& extra = "") {
    const fs::path path = small_copy(scene, knot_insertion, extra);
    const fs::path out = dir_ / (path.stem().string() + "_out");
    const CliResult r = run(path, out);
    EXPECT_EQ(r.code, 0) << r.err << r.out;
    std::ifstream in(out / "summary.json");
    const nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
    EXPECT_FALSE(s.is_discarded()) << "no summary.json for " << scene;
    if (!s.is_discarded()) {
      EXPECT_EQ(s["status"], "converged") << scene;
      max_displacement_ = s["max_displacement_m"].get<double>();
    }
    Table t = read_csv(out / "probes.csv");
    EXPECT_FALSE(t.rows.empty()) << scene;
    if (t.rows.empty())
      t.rows.emplace_back(t.header.size(), std::nan(""));
    else
      EXPECT_NEAR(t.last("time"), kEnd, 1e-12);
    return t;
  }

  static constexpr double kEnd = 0.02;  // s: activation full from 0.005 s, then 15 ms of shortening
  static fs::path dir_;
  static double max_displacement_;  // m, max |u| at the control points of the last run
};

fs::path SlowExamples::dir_;
double SlowExamples::max_displacement_ = 0.0;

// The volume bound of every small run: the volume term U_J = (J - 1)^2 / D gives the pressure
// p = 2 (J - 1) / D, and nothing in a free contraction pushes harder than the fibres that drive
// it, whose stress is at most sigma0 = 2.2e5 Pa (Table 5.1), so |J - 1| <= sigma0 D / 2 =
// 1.1e-4 with D = 1e-9 m^2/N, and so is |dV / V|. (Measured at 0.02 s: 1e-10 to 5e-9.)
constexpr double kVolumeBound = 2.2e5 * 1e-9 / 2.0;

// No external load but the support: at equilibrium the support force is minus the sum of the
// free residual, at most sqrt(DOFs) |r| ~ 1e-9 N after Newton, against fibre forces sigma0 A of
// newtons. (Measured: 1e-12 to 6e-10 N.)
constexpr double kSupportForceBound = 1e-6;  // N

// Cone (thesis 5.6.1): bottom fixed, the top's centre moves towards the base. The committed
// example (128 elements, graded towards the base) measured tip u_z(0.02 s) = -0.7526 mm
// (examples/cone/README.md); this copy with 2 uniform spans along (6 with the grading) and one
// radial span, 24 elements, measured -0.7536 mm, so within 5 %. NURBS (generatrix) and constant z
// fibres: 7 % apart at 0.02 s in the committed example, 1.4 % in this copy; within 10 %. (The top
// rim's radial motion, a tenth of a millimetre by then, is left to the refinement study: on coarse
// meshes it even has the wrong sign, validation/suite/README.md.)
TEST_F(SlowExamples, ConeTopMovesTowardsTheFixedBase) {
  const double reference = -7.526e-4;  // m, committed example at 0.02 s
  const Table nurbs = run_small("cone/contract.toml", "[0, 1, 0]");
  const Table z = run_small("cone/contract-zfibres.toml", "[0, 1, 0]");
  const double tip = nurbs.last("tip_z");
  std::printf("cone tip at 0.02 s: NURBS fibres %.4f mm, z fibres %.4f mm\n", 1e3 * tip,
              1e3 * z.last("tip_z"));
  EXPECT_LT(tip, 0.0);
  EXPECT_NEAR(tip, reference, 0.05 * std::abs(reference));
  EXPECT_NEAR(z.last("tip_z"), tip, 0.10 * std::abs(tip));
  for (const Table* t : {&nurbs, &z}) {
    EXPECT_LT(std::abs(t->last("volume") / t->first("volume") - 1.0), kVolumeBound);
    EXPECT_LT(std::abs(t->last("base_force_z")), kSupportForceBound);
  }
}

// Barrel (thesis 5.6.2, examples/barrel): as the cone. The committed contract.toml (128 elements,
// graded towards the fixed end) measured tip u_z(0.02 s) = -0.7455 mm (-13.93 mm at 0.2 s,
// examples/barrel/README.md); this copy with 2 uniform spans along (6 with the grading) and one
// radial span, 24 elements, measured -0.7509 mm (0.7 % more), so within 5 % as for the cone.
TEST_F(SlowExamples, BarrelFreeEndMovesTowardsTheFixedEnd) {
  const double reference = -7.455e-4;  // m, committed example at 0.02 s
  const Table t = run_small("barrel/contract.toml", "[0, 1, 0]");
  EXPECT_LT(t.last("tip_z"), 0.0);
  EXPECT_NEAR(t.last("tip_z"), reference, 0.05 * std::abs(reference));
  EXPECT_LT(std::abs(t.last("volume") / t.first("volume") - 1.0), kVolumeBound);
  EXPECT_LT(std::abs(t.last("fixed_end_force_z")), kSupportForceBound);
}

// Whole torus (thesis 5.6.3) as the extracted 1/8 model: the symmetry planes hold (the normal
// displacement of points ON the planes, given parametrically so that they lie exactly on the
// faces, is zero to 1e-12 of the largest displacement: only the face control points, whose normal
// component is constrained, act there), the ring shrinks (radial displacement of the centreline
// < 0, the same at both ends of the quarter ring since the piece is mirror-symmetric about the
// 45-degree plane), the tube thickens in z (incompressible) and the volume is kept. The committed
// example (64 elements) measured ring_x(0.02 s) = -0.1945 mm; this 8-element copy within 10 %.
TEST_F(SlowExamples, TorusEighthKeepsItsSymmetryPlanesAndShrinksItsRing) {
  std::string extra;
  const auto probe = [&](const std::string& name, const std::string& xi, const char* c) {
    extra += "\n[[probe]]\nname = \"" + name + "\"\nkind = \"point_displacement\"\nxi = " + xi +
             "\ncomponent = \"" + c + "\"\n";
  };
  probe("v0_a_y", "[0.3, 0.0, 0.4]", "y");  // face v0 lies in y = 0
  probe("v0_b_y", "[0.8, 0.0, 0.1]", "y");
  probe("v1_a_x", "[0.3, 1.0, 0.4]", "x");  // v1 in x = 0
  probe("v1_b_x", "[0.6, 1.0, 0.9]", "x");
  probe("u0_a_z", "[0.0, 0.4, 0.3]", "z");  // u0 and u1 in z = 0
  probe("u1_a_z", "[1.0, 0.7, 0.6]", "z");
  probe("axis_z", "[0.5, 0.5, 1.0]", "z");  // the ring centreline (w = 1) lies in z = 0 too
  const Table t = run_small("torus/contract.toml", "[1, 1, 0]", extra);
  const double max_u = max_displacement_;
  EXPECT_GT(max_u, 1e-4);  // measured 0.22 mm
  for (const char* name : {"v0_a_y", "v0_b_y", "v1_a_x", "v1_b_x", "u0_a_z", "u1_a_z", "axis_z"}) {
    EXPECT_LE(std::abs(t.last(name)), 1e-12 * max_u) << name;
  }
  const double ring = t.last("ring_x");
  EXPECT_LT(ring, 0.0);
  EXPECT_NEAR(ring, -1.945e-4, 0.10 * 1.945e-4);
  EXPECT_NEAR(t.last("ring_y"), ring, 1e-6 * std::abs(ring));
  EXPECT_LT(t.last("outer_x"), 0.0);
  EXPECT_LT(t.last("inner_x"), 0.0);
  EXPECT_GT(t.last("top_z"), 0.0);
  EXPECT_LT(std::abs(t.last("volume") / t.first("volume") - 1.0), kVolumeBound);
}

// Half torus (thesis 5.6.4) and depressor anguli oris (5.6.5), one end fixed, with NURBS fibres
// ("method 2") and two straight segments ("method 1"): both converge, the free end moves by a
// physical amount (more than 0.1 mm in 0.02 s; measured 0.43-0.68 mm), the volume is kept and the
// support carries no net force.
void check_free_end(const Table& t, const std::vector<std::string>& components) {
  double moved = 0.0;
  for (const std::string& c : components)
    moved += t.last(c) * t.last(c);
  EXPECT_GT(std::sqrt(moved), 1e-4);
  EXPECT_LT(std::abs(t.last("volume") / t.first("volume") - 1.0), kVolumeBound);
  EXPECT_LT(t.last("fixed_end_force"), kSupportForceBound);
}

TEST_F(SlowExamples, HalfTorusFreeEndMovesWithEitherFibreField) {
  for (const char* scene : {"half_torus/contract.toml", "half_torus/contract-segments.toml"}) {
    SCOPED_TRACE(scene);
    check_free_end(run_small(scene, "[0, 1, 0]"), {"free_end_x", "free_end_y"});
  }
}

TEST_F(SlowExamples, DaoFreeEndMovesWithEitherFibreField) {
  for (const char* scene : {"dao/contract.toml", "dao/contract-segments.toml"}) {
    SCOPED_TRACE(scene);
    const Table t = run_small(scene, "[0, 0, 0]");
    check_free_end(t, {"free_end_x", "free_end_y", "free_end_z"});
    EXPECT_LT(t.last("free_end_z"), 0.0);  // the mouth corner is pulled down towards the jaw
  }
}

// The 1/8 torus with three symmetry planes (contract.toml) and the whole torus held by six point
// constraints only (contract-whole.toml) at the same refinement per piece: the discrete problem
// of the whole torus is symmetric, so its solution restricted to the eighth is the eighth's
// solution up to the Newton tolerances. `isomuscle compare` evaluates both at the material points
// of the eighth. (Measured: 3e-14 of max |u|, volumes 8:1 to 1e-15.)
TEST_F(SlowExamples, EighthTorusAgreesWithTheWholeTorusWhereTheyOverlap) {
  run_small("torus/contract.toml", "[0, 1, 0]");
  run_small("torus/contract-whole.toml", "[0, 1, 0]");
  const CliResult r =
      cli_test::run_isomuscle(std::string("compare ") + (dir_ / "torus_contract_out").string() +
                                  " " + (dir_ / "torus_contract-whole_out").string() + " --json",
                              dir_ / "stderr.txt");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json c = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(c.is_discarded()) << r.out;
  EXPECT_EQ(c["outside_b"], 0);
  EXPECT_GT(c["samples"].get<int>(), 1000);
  EXPECT_GT(c["max_displacement_a_m"].get<double>(), 1e-4);  // the ring has moved
  EXPECT_LT(c["relative_max_difference"].get<double>(), 1e-9);
  EXPECT_LT(c["relative_l2_difference"].get<double>(), 1e-9);
  const double eighth = c["a"]["volume_final_m3"].get<double>();
  const double whole = c["b"]["volume_final_m3"].get<double>();
  EXPECT_NEAR(whole, 8.0 * eighth, 1e-9 * whole);
}

}  // namespace
}  // namespace isomuscle
