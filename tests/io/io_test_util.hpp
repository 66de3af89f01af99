#pragma once
// Helpers shared by the io tests: fresh scratch folders and line numbers of snippets in texts.
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

}  // namespace isomuscle::io::testing_util
