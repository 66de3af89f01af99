// The fibre field a scene's [fibres] builds on the real example solids: "method 1" segments of
// the half torus and the depressor anguli oris (thesis 5.6.4-5.6.5) cut the body at v = 1/2.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "iga/fibre_directions.hpp"
#include "iga/space.hpp"
#include "io/iga_run_setup.hpp"
#include "io/scene_loader.hpp"
#include "io/scene_solid.hpp"

namespace isomuscle::io {
namespace {

// A scene's fibres at the quadrature points of its unrefined solid.
struct SceneFibreField {
  explicit SceneFibreField(const char* scene_file)
      : scene(load_scene(std::filesystem::path(ISOMUSCLE_SOURCE_DIR) / "examples" / scene_file)),
        solid(build_scene_solid(scene.geometry)),
        spec(fibre_spec(scene.fibres, solid.frame, solid.volume)),
        space(solid.volume),
        fibres(iga::fibre_directions(space, spec)) {}

  const Eigen::Vector3d& X(int i) const {
    return space.position(i / space.points_per_element(), i % space.points_per_element());
  }
  const Eigen::Vector3d& xi(int i) const {
    return space.parametric(i / space.points_per_element(), i % space.points_per_element());
  }

  Scene scene;
  SceneSolid solid;
  iga::FibreSpec spec;
  iga::Space space;
  std::vector<Eigen::Vector3d> fibres;
};

// Every point takes the chord of its own half of the body, decided by its parameter along the
// centreline.
void expect_halves(const SceneFibreField& f, const Eigen::Vector3d& chord0,
                   const Eigen::Vector3d& chord1) {
  const int along = f.solid.frame.solid(Direction::v);
  const auto [lo, hi] = f.solid.volume.domain(along);
  for (int i = 0; i < f.space.num_points(); ++i) {
    const Eigen::Vector3d& chord = f.xi(i)[along] < 0.5 * (lo + hi) ? chord0 : chord1;
    EXPECT_NEAR(std::abs(f.fibres[static_cast<std::size_t>(i)].dot(chord.normalized())), 1.0, 1e-9)
        << "point " << i << " at X = (" << f.X(i).transpose() << ")";
  }
}

TEST(SceneFibres, HalfTorusSegmentsAreTheTwoHalvesWithTheirChords) {
  // Ends at x = +-1 cm, the middle section centred on (0, 1 cm, 0): chords at +-45 degrees; the
  // cut v = 1/2 is the plane x = 0.
  const SceneFibreField f("half_torus/contract-segments.toml");
  expect_halves(f, {-1, 1, 0}, {-1, -1, 0});
  // Beyond the joint on its convex side (y - 1 cm > |x|) both segments are equally near, so a
  // nearest-segment rule would leave these points to round-off; the side of x = 0 decides.
  int outer_joint = 0;
  for (int i = 0; i < f.space.num_points(); ++i) {
    if (f.X(i).y() - 0.01 > std::abs(f.X(i).x())) {
      ++outer_joint;
      const Eigen::Vector3d chord = f.X(i).x() > 0 ? Eigen::Vector3d(-1, 1, 0).normalized()
                                                   : Eigen::Vector3d(-1, -1, 0).normalized();
      EXPECT_NEAR(std::abs(f.fibres[static_cast<std::size_t>(i)].dot(chord)), 1.0, 1e-9) << i;
    }
  }
  EXPECT_GT(outer_joint, 0);
}

TEST(SceneFibres, DaoSegmentsAreTheHalvesAlongTheCentreline) {
  const SceneFibreField f("dao/contract-segments.toml");
  ASSERT_EQ(f.spec.polyline.size(), 3u);
  EXPECT_EQ(f.spec.cut_direction, f.solid.frame.solid(Direction::v));
  expect_halves(f, f.spec.polyline[1] - f.spec.polyline[0],
                f.spec.polyline[2] - f.spec.polyline[1]);
}

// The analysis space makes each cut a C^0 element face (knot multiplicity = degree), so the kink
// of the displacement where the fibre direction jumps is in the basis; NURBS fibres add no knot.
TEST(SceneFibres, SegmentCutsAreC0FacesOfTheAnalysisSpace) {
  for (const char* file :
       {"dao/contract-segments.toml", "half_torus/contract-segments.toml", "dao/contract.toml"}) {
    SCOPED_TRACE(file);
    const Scene scene = load_scene(std::filesystem::path(ISOMUSCLE_SOURCE_DIR) / "examples" / file);
    const IgaModel model = build_iga_model(scene, 1);
    const int along = model.frame.solid(Direction::v);
    const geometry::KnotVector& knots = model.space->volume().knots(along);
    const auto [lo, hi] = model.space->volume().domain(along);
    double middle = knots.breakpoints().front();  // the knot nearest to the cut at 1/2
    for (double k : knots.breakpoints())
      if (std::abs(k - 0.5 * (lo + hi)) < std::abs(middle - 0.5 * (lo + hi)))
        middle = k;
    ASSERT_LT(std::abs(middle - 0.5 * (lo + hi)), 1e-12 * (hi - lo));
    const bool segments = model.fibre_spec.mode == iga::FibreSpec::Mode::polyline;
    // The DAO's cubic centreline has a simple knot at 1/2; the half torus's quadratic half
    // circle already a double one (C^0).
    const int expected = segments ? knots.degree() : 1;
    EXPECT_EQ(knots.multiplicity(middle), expected);
    EXPECT_EQ(knots.degree(), std::string(file).starts_with("dao") ? 3 : 2);
  }
}

}  // namespace
}  // namespace isomuscle::io
