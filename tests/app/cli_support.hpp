#pragma once
// What the command-line tests share: running the real `isomuscle` executable and reading back
// what it wrote (text, CSV).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace isomuscle::cli_test {

struct CliResult {
  int code = -1;  // exit status; 128 + signal when killed by one
  std::string out;
  std::string err;
};

// Runs ISOMUSCLE_EXE with `arguments` (a shell command line), stdout captured, stderr through
// `stderr_file` (overwritten); `launcher` goes before the executable (e.g. "timeout -s TERM 1").
CliResult run_isomuscle(const std::string& arguments, const std::filesystem::path& stderr_file,
                        const std::string& launcher = "");

// The whole file as bytes ("" if it cannot be read).
std::string read_text(const std::filesystem::path& path);

// A CSV file as columns of numbers (header row first).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  // Index of the named column (a test failure and 0 if there is none).
  std::size_t column(const std::string& name) const;
  double first(const std::string& name) const;  // first row's value (NaN and a failure if none)
  double last(const std::string& name) const;   // last row's value
};
CsvTable read_csv(const std::filesystem::path& path);

}  // namespace isomuscle::cli_test
