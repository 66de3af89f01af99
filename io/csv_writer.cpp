#include "io/csv_writer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/setting_check.hpp"

namespace isomuscle::io {

CsvWriter::CsvWriter(std::filesystem::path path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty())
    throw std::invalid_argument("CSV file " + path_.string() + ": no columns");
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    const std::string& name = columns_[i];
    if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos) {
      throw std::invalid_argument("CSV file " + path_.string() + ": column name \"" + name +
                                  "\" must be non-empty and hold no comma, quote or line break");
    }
    if (std::find(columns_.begin(), columns_.begin() + static_cast<long>(i), name) !=
        columns_.begin() + static_cast<long>(i)) {
      throw std::invalid_argument("CSV file " + path_.string() + ": column \"" + name +
                                  "\" appears twice");
    }
  }
  out_.open(path_, std::ios::out | std::ios::trunc);
  if (!out_)
    throw std::runtime_error("cannot create CSV file " + path_.string());
  out_ << join(columns_, ",") << '\n';
  out_.flush();
  if (!out_)
    throw std::runtime_error("cannot write CSV file " + path_.string());
}

void CsvWriter::write_row(std::span<const double> values) {
  const std::size_t row = rows_ + 1;
  if (values.size() != columns_.size()) {
    throw std::invalid_argument("CSV file " + path_.string() + ", row " + std::to_string(row) +
                                ": " + std::to_string(values.size()) + " values for " +
                                std::to_string(columns_.size()) + " columns (" + join(columns_) +
                                ")");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument("CSV file " + path_.string() + ", row " + std::to_string(row) +
                                  ": column '" + columns_[i] + "' is " + format_number(values[i]) +
                                  "; refusing to write a non-finite value as a result");
    }
  }
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0)
      line += ',';
    line += format_number(values[i]);
  }
  line += '\n';
  out_ << line;
  out_.flush();
  if (!out_)
    throw std::runtime_error("cannot write CSV file " + path_.string());
  rows_ = row;
}

}  // namespace isomuscle::io
