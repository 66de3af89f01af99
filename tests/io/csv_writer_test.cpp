// Probe time series: header and rows read back exactly, each row is on disk as soon as it is
// written, and non-finite values or wrong counts are refused without touching the file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <sstream>

#include "io/csv_writer.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

using testing_util::fresh_directory;
using testing_util::read_text;

std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(read_text(path));
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream cells_in(line);
    std::string cell;
    while (std::getline(cells_in, cell, ','))
      cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(CsvWriter, RowsReadBackExactlyAndAreFlushedOneByOne) {
  const auto dir = fresh_directory("csv");
  CsvWriter csv(dir / "probes.csv", {"time", "tip_z", "volume"});
  EXPECT_EQ(read_text(dir / "probes.csv"), "time,tip_z,volume\n");
  const std::vector<std::vector<double>> rows{{0.0, 0.0, 1.2345678901234567e-5},
                                              {0.1, -1.0 / 3.0, 1.2345678901234e-5},
                                              {0.30000000000000004, 2.5e-300, 1e22}};
  for (std::size_t r = 0; r < rows.size(); ++r) {
    csv.write_row(rows[r]);
    // On disk already, while the writer is alive.
    EXPECT_EQ(read_csv(dir / "probes.csv").size(), r + 2);
  }
  EXPECT_EQ(csv.rows(), 3u);
  const auto back = read_csv(dir / "probes.csv");
  ASSERT_EQ(back.size(), 4u);
  EXPECT_EQ(back[0], (std::vector<std::string>{"time", "tip_z", "volume"}));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    ASSERT_EQ(back[r + 1].size(), 3u);
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(std::strtod(back[r + 1][c].c_str(), nullptr), rows[r][c]) << back[r + 1][c];
    }
  }
  EXPECT_EQ(back[2][0], "0.1");
}

TEST(CsvWriter, RefusesNonFiniteValuesAndWrongCountsKeepingEarlierRows) {
  const auto dir = fresh_directory("csv");
  CsvWriter csv(dir / "probes.csv", {"time", "tip_z"});
  csv.write_row({0.0, 1.0});
  try {
    csv.write_row({0.1, std::numeric_limits<double>::quiet_NaN()});
    ADD_FAILURE() << "NaN written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 2: column 'tip_z' is nan"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(csv.write_row({std::numeric_limits<double>::infinity(), 0.0}),
               std::invalid_argument);
  EXPECT_THROW(csv.write_row({0.1}), std::invalid_argument);
  EXPECT_EQ(read_text(dir / "probes.csv"), "time,tip_z\n0,1\n");
  EXPECT_EQ(csv.rows(), 1u);
  csv.write_row({0.1, 2.0});
  EXPECT_EQ(read_text(dir / "probes.csv"), "time,tip_z\n0,1\n0.1,2\n");
}

TEST(CsvWriter, RejectsBadColumnsAndUnwritablePaths) {
  const auto dir = fresh_directory("csv");
  EXPECT_THROW(CsvWriter(dir / "a.csv", {}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir / "a.csv", {"time", "a,b"}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir / "a.csv", {"time", "time"}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir / "a.csv", {"time", ""}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir / "missing" / "a.csv", {"time"}), std::runtime_error);
}

}  // namespace
}  // namespace isomuscle::io
