// The tetrahedral discretisation through the user's path (discretisation = "tet" in a scene,
// io::run_scene) against the isogeometric one on the same scene: the barrel contraction
// (examples/barrel/contract.toml and contract-tet.toml, tang2009, NURBS fibres; the first 20 ms at
// fixed steps of 1 ms so that both share the time integration). The two agree within the
// discretisation error that refinement shows: the IGA fine run (32 elements) and the finer
// tetrahedral run (10-node, 5 mm) differ by no more than 1.5 times the larger of the two
// refinement changes (IGA 8 -> 32 elements, tetrahedra 6 -> 5 mm), in the L2 norm of the field
// (io::compare_runs), and their tip displacements agree to 1 %. Measured: tip -0.7512 mm (IGA
// fine), -0.7487 (tet 5 mm), -0.7497 (tet 6 mm), -0.7829 (IGA coarse); L2 IGA fine vs tet 5 mm
// 4.8 %, tet 6 vs 5 mm 4.7 %, IGA coarse vs fine 3.2 % (the unstructured meshes twist the free end
// slightly, a soft mode: 0.4 degrees at 5 mm).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "io/run_comparison.hpp"
#include "io/scene_loader.hpp"
#include "io/scene_run.hpp"
#include "materials/material_factory.hpp"
#include "materials/strong_ellipticity.hpp"

namespace isomuscle {
namespace {

namespace fs = std::filesystem;

const fs::path kBarrel = fs::path(ISOMUSCLE_SOURCE_DIR) / "examples" / "barrel";

class SlowTetScenes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("isomuscle_test_tet_scenes_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // The scene file shortened to `end` at fixed 1 ms steps, without field output.
  static io::Scene shortened(const fs::path& scene_file, double end) {
    io::Scene scene = io::load_scene(scene_file);
    scene.time.end = end;
    scene.time.dt = 0.001;
    scene.time.dt_max = 0.001;
    scene.time.adaptive = false;
    scene.output.times = {end};
    scene.output.fields.clear();
    return scene;
  }

  // The scene shortened to 20 ms; returns the tip z (m).
  static double run(const fs::path& scene_file, const std::string& name,
                    const std::array<int, 3>& knot_insertion, double element_size) {
    io::Scene scene = shortened(scene_file, 0.02);
    scene.geometry.refine.knot_insertion = knot_insertion;
    // Uniform spans: the IGA numbers above were measured without contract.toml's grading.
    scene.geometry.refine.knots = {};
    if (scene.discretisation == io::Discretisation::tet)
      scene.tetrahedra.element_size = element_size;
    const io::RunResult r = io::run_scene(scene, {dir_ / name, 1, {}, {}, {}});
    EXPECT_TRUE(r.converged) << name << ": " << r.failure_reason;
    EXPECT_EQ(r.summary.discretisation,
              scene.discretisation == io::Discretisation::tet ? "tet" : "iga");
    return r.summary.probes.at("tip_z").value_or(std::nan(""));
  }
  static double l2(const std::string& a, const std::string& b) {
    const io::RunComparison c = io::compare_runs(dir_ / a, dir_ / b);
    EXPECT_EQ(c.outside_b + c.outside_a, 0) << a << " " << b;
    return c.relative_l2();
  }

  static fs::path dir_;
};

fs::path SlowTetScenes::dir_;

TEST_F(SlowTetScenes, BarrelContractionOnTetrahedraAgreesWithIgaWithinTheRefinementChange) {
  const double iga_coarse = run(kBarrel / "contract.toml", "iga_coarse", {0, 1, 0}, 0.0);
  const double iga_fine = run(kBarrel / "contract.toml", "iga_fine", {0, 3, 1}, 0.0);
  const double tet_coarse = run(kBarrel / "contract-tet.toml", "tet_coarse", {0, 0, 0}, 0.006);
  const double tet_fine = run(kBarrel / "contract-tet.toml", "tet_fine", {0, 0, 0}, 0.005);
  const double between = l2("iga_fine", "tet_fine");
  const double iga_change = l2("iga_fine", "iga_coarse");
  const double tet_change = l2("tet_fine", "tet_coarse");
  std::printf(
      "[ measured ] tip z (mm): IGA %.4f -> %.4f, tet %.4f -> %.4f; L2: IGA fine vs tet fine "
      "%.4f, IGA change %.4f, tet change %.4f\n",
      1e3 * iga_coarse, 1e3 * iga_fine, 1e3 * tet_coarse, 1e3 * tet_fine, between, iga_change,
      tet_change);
  EXPECT_LT(iga_fine, -5e-4);  // the free end moves towards the fixed one
  EXPECT_NEAR(tet_fine, iga_fine, 0.01 * std::abs(iga_fine));
  EXPECT_LE(between, 1.5 * std::max(iga_change, tet_change));
}

// The flat depressor anguli oris (2 mm thick, 30 mm wide at its clamped root) on 10-node
// tetrahedra through the user's path: it meshes (gmsh could not mesh its filled end caps at any
// size from 0.5 to 1.2 mm, and at 1.5 mm some curved elements folded over; tet_meshing.cpp,
// curved_tet_repair.hpp), the run says how many elements it made straight-sided, and the first
// 5 ms of the contraction converge with the mouth corner moving down and the volume kept.
TEST_F(SlowTetScenes, FlatDaoRunsOnTetrahedraAndNamesItsStraightenedElements) {
  io::Scene scene =
      io::load_scene(fs::path(ISOMUSCLE_SOURCE_DIR) / "examples" / "dao" / "contract-tet.toml");
  scene.tetrahedra.element_size = 0.0015;
  scene.time.end = 0.005;
  scene.time.dt = 0.001;
  scene.time.dt_max = 0.001;
  scene.time.adaptive = false;
  scene.output.times = {0.005};
  scene.output.fields.clear();
  const io::RunResult r = io::run_scene(scene, {dir_ / "dao_tet", 1, {}, {}, {}});
  ASSERT_TRUE(r.converged) << r.failure_reason;
  EXPECT_EQ(r.summary.discretisation, "tet");
  bool named = false;
  for (const auto& note : r.summary.extra.at("notes"))
    named = named || note.get<std::string>().find("made straight-sided") != std::string::npos;
  EXPECT_TRUE(named) << r.summary.extra.at("notes").dump();
  const double z = r.summary.probes.at("free_end_z").value_or(std::nan(""));
  EXPECT_LT(z, 0.0);
  EXPECT_NEAR(*r.summary.volume_final_m3, *r.summary.volume_initial_m3,
              1e-5 * *r.summary.volume_initial_m3);
}

// [[tetrahedra.refine]] through the user's path: the barrel on 6 mm 10-node tetrahedra with 2 mm
// elements asked at its clamped end (face v0), growing back over 10 mm. The mesh has more
// elements (measured 687 against 283), the run says what was refined, and the first millisecond
// converges with the free end moving towards the clamped one.
TEST_F(SlowTetScenes, RefinementNextToTheClampedFaceReachesTheMeshAndTheRun) {
  io::Scene scene = shortened(kBarrel / "contract-tet.toml", 0.001);
  scene.tetrahedra.element_size = 0.006;
  io::ProbeSettings ellipticity;
  ellipticity.name = "e";
  ellipticity.kind = io::ProbeKind::material_ellipticity;
  scene.probes.push_back(ellipticity);
  const io::RunResult uniform = io::run_scene(scene, {dir_ / "barrel_uniform", 1, {}, {}, {}});
  scene.tetrahedra.refine = {{io::Face::v0, 0.002, 0.01}};
  scene.validate();
  const io::RunResult refined = io::run_scene(scene, {dir_ / "barrel_refined", 1, {}, {}, {}});
  ASSERT_TRUE(uniform.converged) << uniform.failure_reason;
  ASSERT_TRUE(refined.converged) << refined.failure_reason;
  std::printf("barrel 6 mm: %zu elements; refined to 2 mm at v0: %zu\n", uniform.summary.elements,
              refined.summary.elements);
  EXPECT_GT(refined.summary.elements, 2 * uniform.summary.elements);
  bool said = false;
  for (const auto& note : refined.summary.extra.at("notes"))
    said =
        said || note.get<std::string>().find("elements refined near face v0") != std::string::npos;
  EXPECT_TRUE(said) << refined.summary.extra.at("notes").dump();
  EXPECT_LT(refined.summary.probes.at("tip_z").value_or(std::nan("")), 0.0);

  // The material_ellipticity probe on tetrahedra: after 1 ms (activation 0.2, strains about 1 %)
  // the law is strongly elliptic everywhere, and its smallest isochoric wave stiffness is the law's
  // own at rest (F = I, the same time and step) to 0.1 % (measured 2939.17 and 2939.14 Pa against
  // 2939.18).
  const auto law = materials::make_material("tang2009");
  materials::PointInput in;
  in.fibre = Eigen::Vector3d::UnitZ();
  in.time = in.dt = 0.001;
  std::vector<double> history(static_cast<std::size_t>(law->history_size()));
  law->initial_history(history);
  in.history = history;
  std::vector<double> trial(history.size());
  materials::PointResult at_rest;
  at_rest.history = trial;
  ASSERT_EQ(law->evaluate_isochoric(in, at_rest, true), materials::PointStatus::ok);
  const double e_rest = materials::refined_isochoric_ellipticity(Eigen::Matrix3d::Identity(),
                                                                 at_rest.S, at_rest.tangent)
                            .smallest;
  for (const io::RunResult* r : {&uniform, &refined}) {
    const double e = r->summary.probes.at("e").value_or(std::nan(""));
    std::printf("smallest e after 1 ms: %.6g Pa (%zu elements); the law at rest %.6g Pa\n", e,
                r->summary.elements, e_rest);
    EXPECT_EQ(r->summary.probes.at("e.not_elliptic").value_or(-1.0), 0.0);
    EXPECT_NEAR(e, e_rest, 1e-3 * e_rest);
    const double z = r->summary.probes.at("e.z").value_or(std::nan(""));
    EXPECT_GE(z, 0.0);  // a point of the barrel: its ends are at z = 0 and 0.05 m
    EXPECT_LE(z, 0.05);
  }
}

// [tetrahedra] quadrature_degree through the user's path: the barrel's first millisecond on 6 mm
// 10-node tetrahedra with the 14-point rule (degree 4) instead of the default 4 points. The run
// integrates at 14 points per element and says so in its summary, and the rule moves the tip by
// less than the step from 6 to 5 mm elements does: the quadrature error of the default rule is
// below the mesh's discretisation error, as it must be for the default to be sound. Measured tip
// z (mm): -5.4631e-4 (4 points), -5.4649e-4 (14 points), -5.4748e-4 (5 mm): 0.03 % against 0.2 %.
TEST_F(SlowTetScenes, QuadratureDegreeReachesTheRunAndMovesTheTipLessThanTheMesh) {
  io::Scene scene = shortened(kBarrel / "contract-tet.toml", 0.001);
  scene.tetrahedra.element_size = 0.006;
  const io::RunResult four = io::run_scene(scene, {dir_ / "barrel_q2", 1, {}, {}, {}});
  scene.tetrahedra.quadrature_degree = 4;
  scene.validate();
  const io::RunResult fourteen = io::run_scene(scene, {dir_ / "barrel_q4", 1, {}, {}, {}});
  scene.tetrahedra.quadrature_degree = 0;
  scene.tetrahedra.element_size = 0.005;
  const io::RunResult finer = io::run_scene(scene, {dir_ / "barrel_5mm", 1, {}, {}, {}});
  for (const io::RunResult* r : {&four, &fourteen, &finer})
    ASSERT_TRUE(r->converged) << r->failure_reason;
  EXPECT_EQ(four.summary.extra.at("quadrature_degree"), 2);
  EXPECT_EQ(four.summary.extra.at("quadrature_points"), 4 * four.summary.elements);
  EXPECT_EQ(fourteen.summary.extra.at("quadrature_degree"), 4);
  EXPECT_EQ(fourteen.summary.extra.at("quadrature_points"), 14 * fourteen.summary.elements);
  const auto tip = [](const io::RunResult& r) {
    return r.summary.probes.at("tip_z").value_or(std::nan(""));
  };
  std::printf(
      "[ measured ] barrel tip z at 1 ms (mm): 6 mm 4 points %.6e, 14 points %.6e; 5 mm "
      "%.6e\n",
      1e3 * tip(four), 1e3 * tip(fourteen), 1e3 * tip(finer));
  EXPECT_LT(tip(fourteen), 0.0);
  EXPECT_LT(std::abs(tip(fourteen) - tip(four)), std::abs(tip(finer) - tip(four)));
}

}  // namespace
}  // namespace isomuscle
