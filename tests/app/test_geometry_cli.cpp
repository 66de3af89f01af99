// `isomuscle geometry ...` end to end: examples written and measured, bad input rejected with a
// message and a non-zero exit code (never a crash).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_support.hpp"
#include "geometry/iges.hpp"
#include "geometry/shapes.hpp"
#include "geometry/shrink.hpp"
#include "geometry/volume_measures.hpp"

namespace isomuscle {
namespace {

namespace fs = std::filesystem;
using cli_test::CliResult;

class GeometryCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("isomuscle_test_geometry_cli_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    const CliResult r = run("geometry examples --out " + (dir_ / "examples").string());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static CliResult run(const std::string& arguments) {
    return cli_test::run_isomuscle(arguments, dir_ / "stderr.txt");
  }

  static nlohmann::json solid_json(const fs::path& file, const std::string& extra = "") {
    const CliResult r = run("geometry solid " + file.string() + " --centreline v --json " + extra);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }

  static fs::path example(const std::string& name) { return dir_ / "examples" / (name + ".igs"); }

  static fs::path dir_;
};

fs::path GeometryCli::dir_;

// Each example's shrink solid reports its closed-form volume (the DAO: the divergence theorem on
// its boundary), positive det J and the merged seam and axis points.
TEST_F(GeometryCli, SolidOfEachExampleHasTheExpectedVolume) {
  for (const geometry::ExampleShape& shape : geometry::example_shapes()) {
    const nlohmann::json j = solid_json(example(shape.name));
    const double expected = shape.exact_volume
                                ? *shape.exact_volume
                                : geometry::solid_volume_from_boundary(
                                      geometry::shrink_to_centreline(shape.surface, 0), 16);
    const double volume = j["volume_m3"].get<double>();
    std::printf("%-10s volume %.15e m^3, expected %.15e, rel. error %.2e (%d Gauss points)\n",
                shape.name.c_str(), volume, expected, std::abs(volume / expected - 1.0),
                j["volume_gauss_points_per_direction"].get<int>());
    EXPECT_LT(std::abs(volume / expected - 1.0), 1e-8) << shape.name;
    EXPECT_GT(j["min_jacobian"].get<double>(), 0.0) << shape.name;
    EXPECT_EQ(j["non_positive_jacobian_samples"].get<int>(), 0) << shape.name;
    EXPECT_EQ(j["degrees"][2].get<int>(), 1);
    EXPECT_LT(j["distinct_control_points"].get<int>(), j["control_points"].get<int>());
  }
  const nlohmann::json cone = solid_json(example("cone"));
  EXPECT_EQ(cone["control_points"].get<int>(), 9 * 3 * 2);
  EXPECT_EQ(cone["distinct_control_points"].get<int>(), 8 * 3 + 3);
  EXPECT_EQ(cone["closed_direction"], "u");
}

// The report names how far the parametric directions are from right angles: the DAO's flat
// section skews them (between around and radial, near the jaw), the barrel's circles do not.
TEST_F(GeometryCli, SolidReportsTheParametricSkew) {
  const nlohmann::json dao = solid_json(example("dao"));
  EXPECT_LT(dao["min_parametric_angle_deg"].get<double>(), 10.0);
  EXPECT_EQ(dao["min_parametric_angle_between"], "u-w");
  EXPECT_GT(dao["volume_share_parametric_angle_below_deg"]["15"].get<double>(), 0.1);
  const nlohmann::json barrel = solid_json(example("barrel"));
  EXPECT_GT(barrel["min_parametric_angle_deg"].get<double>(), 60.0);
  EXPECT_EQ(barrel["volume_share_parametric_angle_below_deg"]["45"].get<double>(), 0.0);
}

// A file closed in v (centreline along u) gives the same solid with --centreline u.
TEST_F(GeometryCli, CentrelineAlongUForASurfaceClosedInV) {
  const geometry::NurbsSurface barrel = geometry::barrel(0.05, 0.0045, 0.00875);
  const fs::path file = dir_ / "barrel_closed_in_v.igs";
  geometry::write_iges(file, {barrel.transposed()}, geometry::IgesUnit::kMetre);
  const CliResult r = run("geometry solid " + file.string() + " --centreline u --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const double volume = nlohmann::json::parse(r.out)["volume_m3"].get<double>();
  EXPECT_LT(std::abs(volume / geometry::barrel_volume(0.05, 0.0045, 0.00875) - 1.0), 1e-8);
  // Naming the closed direction as the centreline is an error that says what is wrong.
  const CliResult wrong = run("geometry solid " + file.string() + " --centreline v");
  EXPECT_NE(wrong.code, 0);
  EXPECT_NE(wrong.err.find("surface is not closed in u"), std::string::npos) << wrong.err;
}

TEST_F(GeometryCli, VtkHoldsHexahedraAndFibres) {
  const fs::path vtk = dir_ / "cone.vtk";
  const nlohmann::json j =
      solid_json(example("cone"), "--vtk " + vtk.string() + " --vtk-divisions 2");
  EXPECT_EQ(j["vtk"], vtk.string());
  std::ifstream in(vtk);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  // 4 knot spans around x 1 along x 1 towards, 2 cells each: 8 x 2 x 2 cells, 9 x 3 x 3 points.
  EXPECT_NE(s.find("# vtk DataFile Version 3.0"), std::string::npos);
  EXPECT_NE(s.find("POINTS 81 double"), std::string::npos);
  EXPECT_NE(s.find("CELLS 32 288"), std::string::npos);
  EXPECT_NE(s.find("CELL_TYPES 32"), std::string::npos);
  EXPECT_NE(s.find("VECTORS fibre double"), std::string::npos);
  EXPECT_NE(s.find("SCALARS jacobian double 1"), std::string::npos);
}

TEST_F(GeometryCli, InfoDescribesTheSurfaces) {
  const CliResult r = run("geometry info " + example("torus").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["unit"], "MM");
  ASSERT_EQ(j["surfaces"].size(), 1u);
  EXPECT_EQ(j["surfaces"][0]["control_points"][0], 9);
  EXPECT_TRUE(j["surfaces"][0]["closed_control_net"]["u"].get<bool>());
  EXPECT_TRUE(j["surfaces"][0]["closed_control_net"]["v"].get<bool>());
  EXPECT_TRUE(j["surfaces"][0]["rational"].get<bool>());
  const double outer = j["surfaces"][0]["bounding_box_m"]["max"][0].get<double>();
  EXPECT_NEAR(outer, 0.017, 1e-12);  // outer radius 1.7 cm: the control net touches it
  const CliResult text = run("geometry info " + example("cone").string());
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("degrees 2 x 2, control points 9 x 3, rational"), std::string::npos)
      << text.out;
  const fs::path hammer = "/usr/share/opencascade/data/iges/hammer.iges";
  if (fs::exists(hammer)) {
    const CliResult h = run("geometry info " + hammer.string() + " --json");
    ASSERT_EQ(h.code, 0) << h.err;
    EXPECT_EQ(nlohmann::json::parse(h.out)["surfaces"].size(), 45u);
  }
}

TEST_F(GeometryCli, BadInputGivesAMessageAndNonZeroExit) {
  const auto expect_error = [](const CliResult& r, const std::string& words) {
    EXPECT_EQ(r.code, 1) << r.err;  // 1 = handled error, not a signal
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  };
  const fs::path missing = dir_ / "missing.igs";
  expect_error(run("geometry solid " + missing.string() + " --centreline v"), "does not exist");
  expect_error(run("geometry info " + missing.string()), "missing.igs");

  // Truncated: the cone file cut in the middle of its parameter data.
  std::ifstream in(example("cone"), std::ios::binary);
  const std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path cut = dir_ / "truncated.igs";
  std::ofstream(cut, std::ios::binary) << full.substr(0, full.size() / 2);
  expect_error(run("geometry solid " + cut.string() + " --centreline v"), "truncated");

  const fs::path empty = dir_ / "empty.igs";
  std::ofstream(empty).close();
  expect_error(run("geometry info " + empty.string()), "is empty");
  const fs::path junk = dir_ / "junk.igs";
  std::ofstream(junk) << "this is not IGES\n";
  expect_error(run("geometry info " + junk.string()), "columns");

  expect_error(run("geometry solid " + example("cone").string() + " --centreline u"),
               "surface is not closed in v");
  expect_error(run("geometry solid " + example("cone").string() + " --centreline v --surface 3"),
               "--surface 3");
  expect_error(run("geometry solid " + example("cone").string() + " --centreline x"),
               "not one of u, v");
  expect_error(run("geometry examples --out " + (dir_ / "x").string() + " --unit cm"),
               "not one of m, mm");
}

TEST_F(GeometryCli, FileWithoutSurfacesIsNamed) {
  // Hand-made IGES file holding one point (entity 116) only.
  const auto record = [](const std::string& data, char section, int sequence) {
    std::ostringstream line;
    line << std::left << std::setw(72) << data << section << std::right << std::setw(7)
         << std::setfill('0') << sequence;
    return line.str() + "\n";
  };
  std::string text = record("point only", 'S', 1);
  text += record("1H,,1H;,,,,,32,38,6,308,15,,1.,2,2HMM,1,1.,,1E-07,1.,,,11,0,;", 'G', 1);
  text +=
      record("     116       1       0       0       0       0       0       000000000", 'D', 1);
  text += record("     116       0       0       1       0", 'D', 2);
  std::ostringstream parameters;
  parameters << std::left << std::setw(64) << "116,1.,2.,3.,0;" << std::right << std::setw(8) << 1;
  text += record(parameters.str(), 'P', 1);
  text += record("S      1G      1D      2P      1", 'T', 1);
  const fs::path file = dir_ / "point.igs";
  std::ofstream(file) << text;
  const CliResult r = run("geometry info " + file.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("holds no B-spline surface"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("116 point"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace isomuscle
