#pragma once
// Time series of probes as CSV: one header row of column names, then one row per call, each
// flushed at once so that a run that fails later keeps every row written so far. Numbers are
// written in their shortest exact form (they read back to the same double); NaN and infinity are
// refused, never written as if they were results.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace isomuscle::io {

class CsvWriter {
 public:
  // Creates (truncates) path and writes the header. Column names must be non-empty, unique and
  // free of commas, quotes and line breaks; std::invalid_argument otherwise, std::runtime_error
  // when the file cannot be written.
  CsvWriter(std::filesystem::path path, std::vector<std::string> columns);

  // Appends one row of columns().size() values and flushes it. Throws std::invalid_argument
  // (nothing written) for a wrong count or a non-finite value, naming the column and row.
  void write_row(std::span<const double> values);
  void write_row(std::initializer_list<double> values) {
    write_row(std::span<const double>(values.begin(), values.size()));
  }

  const std::filesystem::path& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::ofstream out_;
  std::size_t rows_ = 0;
};

}  // namespace isomuscle::io
