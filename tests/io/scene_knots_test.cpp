// A scene's explicit knots ([geometry.refine] knots) on a real example solid: they add element
// faces where the solid has none, and a value that is already a knot of the refined solid is not
// inserted again (which would lower the continuity there, not refine). [geometry.refine]
// continuity lowers the continuity on purpose: the same elements and geometry, a C^c basis.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

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

  // Knots at 1/3 and 2/3 (the centreline's own) and 1/2 (from the uniform insertion, computed
  // from 1/3 and the span's fraction, not exactly 1/2), and one new one.
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
  const int along_before = static_cast<int>(base_knots.breakpoints().size()) - 1;
  EXPECT_EQ(model.space->num_elements(),
            base.space->num_elements() / along_before * (along_before + 1));  // one span more
}

// continuity = 0 raises every interior knot to multiplicity p in every direction: the elements and
// the geometry (knot insertion is exact) stay, and the unknowns become those of a Lagrange mesh of
// degree p on those elements (a node at every multiple of 1/p of each span, shared across faces).
TEST(SceneKnots, ContinuityZeroGivesC0ElementFacesOnTheSameElementsAndGeometry) {
  const IgaModel smooth = build_iga_model(dao_scene(), 1);
  Scene c0_scene = dao_scene();
  c0_scene.geometry.refine.continuity = 0;
  const IgaModel c0 = build_iga_model(c0_scene, 1);

  const geometry::NurbsVolume& a = smooth.space->volume();
  const geometry::NurbsVolume& b = c0.space->volume();
  EXPECT_EQ(c0.space->num_elements(), smooth.space->num_elements());
  int lagrange_points = 1;
  for (int d = 0; d < 3; ++d) {
    ASSERT_EQ(b.degree(d), a.degree(d));
    const std::vector<double> breaks = b.knots(d).breakpoints();
    EXPECT_EQ(breaks, a.knots(d).breakpoints()) << "direction " << d;
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
      EXPECT_EQ(b.knots(d).multiplicity(breaks[i]), b.degree(d)) << "knot " << breaks[i];
    lagrange_points *= b.degree(d) * static_cast<int>(breaks.size() - 1) + 1;
  }
  EXPECT_EQ(b.num_control_points(), lagrange_points);
  double largest = 0.0;
  for (double s : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    for (double t : {0.0, 0.31, 0.62, 1.0}) {
      for (double r : {0.05, 0.5, 0.93}) {
        const Eigen::Vector3d xi(s, t, r);
        largest = std::max(largest, (b.evaluate(xi) - a.evaluate(xi)).norm());
      }
    }
  }
  EXPECT_LT(largest, 1e-15);  // m; the DAO is 35 mm long
}

TEST(SceneKnots, ContinuityNotBelowTheDegreeIsRefusedNamingTheDegrees) {
  Scene scene = dao_scene();
  scene.geometry.refine.continuity = 2;  // the DAO's solid is of degree (2, 3, 2)
  try {
    build_iga_model(scene, 1);
    FAIL() << "continuity = 2 accepted on a solid of degree 2";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "[geometry.refine] continuity = 2 must be below the degree in every direction; the "
              "refined solid has degree (2, 3, 2) in u, v, w");
  }
}

}  // namespace
}  // namespace isomuscle::io
