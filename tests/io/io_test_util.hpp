#pragma once
// Helpers shared by the io tests: fresh scratch folders, line numbers of snippets in texts and
// the clamped barrel scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace isomuscle::io::testing_util {

// An empty folder for one test, under GoogleTest's temporary directory.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "isomuscle_io" /
      (std::string(info->test_suite_name()) + "." + info->name() + "." + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// 1-based number of the first line of text containing snippet; 0 when absent.
inline int line_containing(std::string_view text, std::string_view snippet) {
  const std::size_t at = text.find(snippet);
  if (at == std::string_view::npos)
    return 0;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i)
    line += text[i] == '\n' ? 1 : 0;
  return line;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// The scene of the barrel (examples/geometry/barrel.igs, 5 cm along z) clamped at its v0 end,
// passive neo-Hookean, one 0.1 s step, on discretisation "iga" or "tet" (3 mm tetrahedra).
inline std::string clamped_barrel_scene(const std::string& discretisation) {
  return "discretisation = \"" + discretisation + "\"\n[geometry]\niges = \"" +
         std::string(ISOMUSCLE_SOURCE_DIR) +
         "/examples/geometry/barrel.igs\"\ncentreline = \"v\"\n[geometry.refine]\n"
         "degree_elevation = [0, 0, 1]\nknot_insertion = [1, 1, 0]\n" +
         (discretisation == "tet" ? "[tetrahedra]\nelement_size = 0.003\n" : "") +
         "[material]\nmodel = \"neo_hookean\"\n[[boundary]]\nface = \"v0\"\ntype = \"fixed\"\n"
         "[time]\nend = 0.1\ndt = 0.1\n";
}

}  // namespace isomuscle::io::testing_util
