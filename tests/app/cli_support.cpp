#include "cli_support.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace isomuscle::cli_test {

CliResult run_isomuscle(const std::string& arguments, const std::filesystem::path& stderr_file,
                        const std::string& launcher) {
  const std::string command = (launcher.empty() ? "" : launcher + " ") + ISOMUSCLE_EXE + " " +
                              arguments + " 2> " + stderr_file.string();
  CliResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr)
    return r;
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0)
    r.out.append(buffer, n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = read_text(stderr_file);
  return r;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name)
      return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

double CsvTable::first(const std::string& name) const {
  if (rows.empty()) {
    ADD_FAILURE() << "no rows for column " << name;
    return std::nan("");
  }
  return rows.front()[column(name)];
}

double CsvTable::last(const std::string& name) const {
  if (rows.empty()) {
    ADD_FAILURE() << "no rows for column " << name;
    return std::nan("");
  }
  return rows.back()[column(name)];
}

CsvTable read_csv(const std::filesystem::path& path) {
  CsvTable t;
  std::ifstream in(path);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(ss, cell, ',')) {
      if (first)
        t.header.push_back(cell);
      else
        row.push_back(std::stod(cell));
    }
    if (!first)
      t.rows.push_back(row);
    first = false;
  }
  return t;
}

}  // namespace isomuscle::cli_test
