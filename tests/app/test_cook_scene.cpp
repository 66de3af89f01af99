// Nearly incompressible Cook's membrane through the user's path (examples/cook/README.md): the
// committed scene examples/cook/cook.toml (an IGES sheet extruded into a plate, a dead shear
// traction [[load]], plane strain by two plane selectors) is loaded, its refinement and
// formulation changed, and run by io::run_scene. The corner displacement UY of the mixed u-p-J
// formulation must come within 1 % of the reference 4.7011 (B. Müller, thesis, Universität
// Duisburg-Essen 2015, as quoted by the Elmer test suite) at 16 x 16 elements and converge to it
// monotonically from above; the displacement formulation must visibly lock (below 85 % of it).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "io/scene_loader.hpp"
#include "io/scene_run.hpp"

namespace isomuscle {
namespace {

namespace fs = std::filesystem;

constexpr double kReference = 4.7011;
const fs::path kScene = fs::path(ISOMUSCLE_SOURCE_DIR) / "examples" / "cook" / "cook.toml";

struct CookRun {
  double uy = std::nan("");
  double clamp_force_y = std::nan("");
  int newton_iterations = 0;
  std::size_t cuts = 0;
};

CookRun run_cook(int n, io::Formulation formulation) {
  io::Scene scene = io::load_scene(kScene);
  scene.geometry.refine.knot_insertion = {n - 1, n - 1, 0};
  scene.solver.formulation = formulation;
  scene.output.fields.clear();
  const fs::path out =
      fs::temp_directory_path() / ("isomuscle_cook_" + std::to_string(getpid()) + "_" +
                                   std::to_string(n) + "_" + io::to_string(formulation));
  const io::RunResult r = io::run_scene(scene, {out, 1, {}, {}, {}});
  EXPECT_TRUE(r.converged) << r.failure_reason;
  CookRun c;
  if (r.summary.probes.at("corner_uy"))
    c.uy = *r.summary.probes.at("corner_uy");
  if (r.summary.probes.at("clamp_force_y"))
    c.clamp_force_y = *r.summary.probes.at("clamp_force_y");
  c.newton_iterations = static_cast<int>(r.summary.newton_iterations);
  c.cuts = r.summary.step_cuts.size();
  fs::remove_all(out);
  return c;
}

TEST(SlowCookScene, MixedFormulationConvergesToTheReferenceDisplacementFormulationLocks) {
  std::printf("Cook's membrane scene, p = 2, n x n x 1, corner UY (reference %.4f):\n", kReference);
  double previous_mixed = HUGE_VAL;
  CookRun mixed, displacement;
  for (int n : {4, 8, 16}) {
    mixed = run_cook(n, io::Formulation::mixed);
    displacement = run_cook(n, io::Formulation::displacement);
    std::printf(
        "  n = %2d: mixed %.4f (%+.2f %%, %d Newton iterations, %zu cuts), displacement %.4f "
        "(%+.2f %%)\n",
        n, mixed.uy, 100.0 * (mixed.uy / kReference - 1.0), mixed.newton_iterations, mixed.cuts,
        displacement.uy, 100.0 * (displacement.uy / kReference - 1.0));
    std::fflush(stdout);
    // From above, monotonically (the constant pressure per span converges at about O(h)).
    EXPECT_GT(mixed.uy, kReference) << "n = " << n;
    EXPECT_LT(mixed.uy, previous_mixed) << "n = " << n;
    previous_mixed = mixed.uy;
    // The clamp carries the applied shear: 0.05 per unit area on the 16 x 1 edge = 0.8.
    EXPECT_NEAR(mixed.clamp_force_y, -0.8, 1e-6) << "n = " << n;
  }
  EXPECT_NEAR(mixed.uy, kReference, 0.01 * kReference);
  EXPECT_LT(displacement.uy, 0.85 * kReference);
}

}  // namespace
}  // namespace isomuscle
