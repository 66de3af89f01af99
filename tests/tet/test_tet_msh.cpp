// Reading a user's .msh file: physical groups as regions and boundary tags, gmsh's 10-node
// ordering (edge nodes at the midpoints of the edges tet_mesh.hpp names), lengths scaled.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tet/tet_meshing.hpp"

namespace isomuscle::tet {
namespace {

// A 2 x 1 x 1 box (mm) with a physical volume "muscle" and physical surfaces "fixed" (x = 0) and
// "loaded" (x = 2), meshed by gmsh at the given order and written as .msh.
std::filesystem::path write_box_msh(int order) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("isomuscle_tet_box_" + std::to_string(order) + ".msh");
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("box");
  gmsh::model::occ::addBox(0, 0, 0, 2, 1, 1);
  gmsh::model::occ::synchronize();
  gmsh::vectorpair faces;
  gmsh::model::getEntities(faces, 2);
  std::vector<int> fixed, loaded;
  for (const auto& [dim, tag] : faces) {
    double x, y, z;
    gmsh::model::occ::getCenterOfMass(dim, tag, x, y, z);
    if (std::abs(x) < 1e-9) {
      fixed.push_back(tag);
    } else if (std::abs(x - 2.0) < 1e-9) {
      loaded.push_back(tag);
    }
  }
  gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {1}, 7), "muscle");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, fixed, 11), "fixed");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, loaded, 12), "loaded");
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
  gmsh::model::mesh::generate(3);
  gmsh::model::mesh::setOrder(order);
  gmsh::write(file.string());
  gmsh::finalize();
  return file;
}

TEST(ReadMsh, PhysicalGroupsOrderingAndUnits) {
  for (int order : {1, 2}) {
    const std::filesystem::path file = write_box_msh(order);
    const TetMesh mesh = read_msh(file, 1e-3);
    EXPECT_EQ(mesh.order, order);
    EXPECT_NEAR(mesh_volume(mesh), 2e-9, 1e-20);
    for (int region : mesh.element_region) {
      ASSERT_EQ(region, 7);
    }
    EXPECT_EQ(group_tag(mesh, "muscle"), 7);
    const auto fixed = boundary_nodes(mesh, group_tag(mesh, "fixed"));
    EXPECT_EQ(fixed, nodes_on_plane(mesh, 0, 0.0, 1e-12));
    const auto loaded = boundary_nodes(mesh, group_tag(mesh, "loaded"));
    EXPECT_EQ(loaded, nodes_on_plane(mesh, 0, 2e-3, 1e-12));
    if (order == 2) {
      constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
      double worst = 0.0;
      for (int e = 0; e < mesh.num_elements(); ++e) {
        const auto el = mesh.element(e);
        for (int k = 0; k < 6; ++k) {
          const Eigen::Vector3d mid =
              0.5 * (mesh.nodes[el[kEdges[k][0]]] + mesh.nodes[el[kEdges[k][1]]]);
          worst = std::max(worst, (mesh.nodes[el[4 + k]] - mid).norm());
        }
      }
      EXPECT_LT(worst, 1e-15);
    }
    std::filesystem::remove(file);
  }
}

TEST(ReadMsh, BadFilesAreNamed) {
  EXPECT_THROW(read_msh("no/such.msh"), std::runtime_error);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "isomuscle_bad.msh";
  std::ofstream(file) << "this is not a mesh\n";
  try {
    read_msh(file);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace isomuscle::tet
