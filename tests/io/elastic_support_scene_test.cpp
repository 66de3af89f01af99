// [[boundary]] type = "elastic" in a scene: on a NURBS solid it becomes the problem's springs on
// the named face (iga/elastic_support.hpp), and that face no longer counts as traction-free
// surface (the surface checks look elsewhere); on tetrahedra (meshed by gmsh first: the test name
// says Gmsh, so the sanitizer pass runs it with the tetrahedral tests) the set-up says it is not
// offered.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "io/iga_run_setup.hpp"
#include "io/iga_surface_point.hpp"
#include "io/scene_loader.hpp"
#include "io/tet_run_setup.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

// The clamped barrel with its v0 end on springs along x, y and z instead.
std::string sprung_barrel_scene(const std::string& discretisation) {
  std::string text = testing_util::clamped_barrel_scene(discretisation);
  const std::string fixed = "type = \"fixed\"\n";
  text.replace(text.find(fixed), fixed.size(), "type = \"elastic\"\nstiffness = 5e5\n");
  return text;
}

TEST(ElasticSupportScene, NurbsSolidGetsTheSpringsAndTheFaceIsNotFreeSurface) {
  const std::filesystem::path dir = testing_util::fresh_directory("elastic_iga");
  const Scene scene = parse_scene(sprung_barrel_scene("iga"), dir / "scene.toml");
  const IgaModel model = build_iga_model(scene, 1);
  ASSERT_EQ(model.problem->elastic_supports().size(), 1u);
  const iga::ElasticSupport& s = model.problem->elastic_supports()[0];
  EXPECT_EQ(s.side, iga::Side::v0);
  EXPECT_EQ(s.stiffness, 5e5);
  EXPECT_EQ(s.components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(s.label, "[[boundary]] #1 (elastic, face v0)");
  EXPECT_EQ(model.problem->constraints().num_free(), 3 * model.dofs->num_nodes());
  // Without the springs' sides the v0 end would count as free surface.
  const iga::ConstrainedDofs& c = model.problem->constraints();
  EXPECT_EQ(traction_free_sides(*model.space, *model.dofs, c),
            (std::vector<iga::Side>{iga::Side::v0, iga::Side::v1, iga::Side::w0}));
  EXPECT_EQ(traction_free_sides(*model.space, *model.dofs, c, {iga::Side::v0}),
            (std::vector<iga::Side>{iga::Side::v1, iga::Side::w0}));
  const std::optional<SurfaceLocation> at_end =
      locate_surface_point(*model.problem, {0.0, 0.0, -0.001});
  ASSERT_TRUE(at_end);
  EXPECT_GT(at_end->surface_position.z(), 1e-4);  // not on the sprung end z = 0
}

TEST(ElasticSupportScene, TetrahedraMeshedByGmshRefuseItByName) {
  const std::filesystem::path dir = testing_util::fresh_directory("elastic_tet");
  const Scene scene = parse_scene(sprung_barrel_scene("tet"), dir / "scene.toml");
  try {
    build_tet_model(scene, 1);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "[[boundary]] #1 (elastic, face v0): elastic supports are not offered on tetrahedra "
              "yet (the springs are integrated over parametric faces of the NURBS solid; "
              "discretisation = \"iga\")");
  }
}

}  // namespace
}  // namespace isomuscle::io
