// A scene's explicit knots ([geometry.refine] knots) on a real example solid: they add element
// faces where the solid has none, and a value that is already a knot of the refined solid is not
// inserted again (which would lower the continuity there, not refine).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "iga/space.hpp"
#include "io/iga_run_setup.hpp"
#include "io/scene_loader.hpp"

namespace isomuscle::io {
namespace {

Scene dao_scene() {
  return load_scene(std::filesystem::path(ISOMUSCLE_SOURCE_DIR) / "examples" / "dao" /
                    "contract.toml");
}

TEST(SceneKnots, KnotsAlreadyInTheSolidAreLeftAsTheyAre) {
  Scene plain = dao_scene();
  plain.geometry.refine.knots = {};
  const IgaModel base = build_iga_model(plain, 1);
  const int along = base.frame.solid(Direction::v);
  const geometry::KnotVector& base_knots = base.space->volume().knots(along);

  // Knots at 1/3 and 2/3 (the centreline's own) and 1/2 (from the uniform insertion, computed as
  // 1/3 + (1/3) / 2, not exactly 1/2), and one new one.
  Scene listed = dao_scene();
  listed.geometry.refine.knots = {std::vector<double>{}, {1.0 / 3.0, 0.4, 0.5, 2.0 / 3.0}, {}};
  const IgaModel model = build_iga_model(listed, 1);
  const geometry::KnotVector& knots = model.space->volume().knots(along);
  const auto [lo, hi] = model.space->volume().domain(along);

  ASSERT_EQ(knots.breakpoints().size(), base_knots.breakpoints().size() + 1);
  for (double k : base_knots.breakpoints())
    EXPECT_EQ(knots.multiplicity(k), base_knots.multiplicity(k)) << "knot " << k;
  const double added = lo + 0.4 * (hi - lo);  // the scene direction runs as the solid's or reversed
  const double added_reversed = lo + 0.6 * (hi - lo);
  EXPECT_EQ(knots.multiplicity(added) + knots.multiplicity(added_reversed), 1);
  EXPECT_EQ(model.space->num_elements(), base.space->num_elements() / 6 * 7);  // 6 -> 7 along
}

}  // namespace
}  // namespace isomuscle::io
