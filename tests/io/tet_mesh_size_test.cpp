// [[tetrahedra.refine]] as gmsh's local size (io/tet_mesh_size.hpp) on the barrel's solid
// (examples/barrel/contract-tet.toml: face v0 is the end z = 0, v1 the end z = 5 cm): the refined
// size on the face, element_size beyond the distance, in between never above the asked linear
// growth and below it by no more than the sampling error (0.61 size of the distance).
#include <gtest/gtest.h>

#include <filesystem>

#include "io/scene_loader.hpp"
#include "io/tet_mesh_size.hpp"

namespace isomuscle::io {
namespace {

TEST(FaceRefinementSize, RefinedOnTheFaceGrowingLinearlyToElementSize) {
  const Scene scene = load_scene(std::filesystem::path(ISOMUSCLE_SOURCE_DIR) / "examples" /
                                 "barrel" / "contract-tet.toml");
  const SceneSolid solid = build_scene_solid(scene.geometry);
  const double coarse = 0.002, size = 0.0005, distance = 0.004;
  tet::MeshingOptions options;
  options.element_size = coarse;
  set_face_refinement(options, solid, {{Face::v0, size, distance}});
  ASSERT_TRUE(options.local_size);
  EXPECT_EQ(options.finest_size, size);
  const double sampling_error = 0.61 * size;
  auto asked = [&](double d) {
    return size + (coarse - size) * std::clamp(d / distance, 0.0, 1.0);
  };

  // Points of the face v0 (solid parameters: v is the barrel's axis direction in this scene).
  const int v = solid.frame.solid(Direction::v);
  const auto [v0, v1] = solid.volume.domain(v);
  int checked = 0;
  for (double a : {0.0, 0.1, 0.37, 0.5, 0.93})
    for (double b : {0.0, 0.25, 0.6, 1.0}) {
      Eigen::Vector3d xi;
      xi[v] = v0;
      const int p = (v + 1) % 3, q = (v + 2) % 3;
      xi[p] =
          solid.volume.domain(p)[0] + a * (solid.volume.domain(p)[1] - solid.volume.domain(p)[0]);
      xi[q] =
          solid.volume.domain(q)[0] + b * (solid.volume.domain(q)[1] - solid.volume.domain(q)[0]);
      const Eigen::Vector3d on_face = solid.volume.evaluate(xi);
      ASSERT_NEAR(on_face.z(), 0.0, 1e-12) << "face v0 is the end z = 0";
      EXPECT_EQ(options.local_size(on_face), size) << on_face.transpose();
      // Into the barrel along the face's normal, the distance to the face is the depth.
      for (double depth : {0.0003, 0.001, 0.002, 0.0035}) {
        const double h = options.local_size(on_face + depth * Eigen::Vector3d::UnitZ());
        EXPECT_LE(h, asked(depth) + 1e-15) << depth;
        EXPECT_GE(h, asked(depth - sampling_error) - 1e-15) << depth;
        ++checked;
      }
      EXPECT_EQ(
          options.local_size(on_face + (distance + sampling_error) * Eigen::Vector3d::UnitZ()),
          coarse);
      // Outside the body (below the face) the distance counts the same way.
      EXPECT_LE(options.local_size(on_face - 0.001 * Eigen::Vector3d::UnitZ()), asked(0.001));
    }
  EXPECT_EQ(checked, 80);
  EXPECT_EQ(options.local_size(Eigen::Vector3d(0, 0, 0.025)), coarse);

  // Two faces: the smaller size wins where both reach, each face keeps its own size.
  tet::MeshingOptions both;
  both.element_size = coarse;
  set_face_refinement(both, solid, {{Face::v0, size, distance}, {Face::v1, 0.001, 0.03}});
  EXPECT_EQ(both.finest_size, size);
  EXPECT_EQ(both.local_size(Eigen::Vector3d(0, 0, 0)), size);
  EXPECT_EQ(both.local_size(Eigen::Vector3d(0, 0, 0.05)), 0.001);
  const double middle = both.local_size(Eigen::Vector3d(0, 0, 0.025));
  EXPECT_LT(middle, coarse);  // 25 mm from v1: 0.001 + 0.001 * 25 / 30 (less the sampling error)
  EXPECT_GT(middle, 0.001 + 0.001 * (0.025 - 0.61 * 0.001) / 0.03 - 1e-15);
}

}  // namespace
}  // namespace isomuscle::io
