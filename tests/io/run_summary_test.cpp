// summary.json: every required key is written and parses back, failed runs say why, unknown or
// non-finite numbers become null, and the file is replaced atomically.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "io/run_summary.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

using testing_util::fresh_directory;
using testing_util::write_text;

RunSummary example() {
  RunSummary s;
  s.converged = true;
  s.scene = "examples/barrel/contract.toml";
  s.discretisation = "iga";
  s.degrees = {2, 2, 3};
  s.elements = 384;
  s.dofs = 5211;
  s.steps = 40;
  s.newton_iterations = 173;
  s.step_cuts = {{0.105, 0.005, 0.0025, "Newton did not converge in 25 iterations"},
                 {0.2, 0.01, 0.005, "J <= 0 at element 17"}};
  s.linear_solver = "cholmod";
  s.wall_seconds = {0.5, 3.25, 1.125, 0.0625, 0.25, 5.1875};
  s.volume_initial_m3 = 8.5e-6;
  s.volume_final_m3 = 8.4999e-6;
  s.max_displacement_m = 0.0123;
  s.probes = {{"tip_z", -0.0042}, {"volume", 8.4999e-6}};
  s.extra["mixed_pressure_dofs"] = 1536;
  return s;
}

nlohmann::json parse_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(RunSummary, EveryRequiredKeyIsWrittenAndReadsBack) {
  const auto dir = fresh_directory("summary");
  const RunSummary s = example();
  write_summary(s, dir / "summary.json");
  const nlohmann::json j = parse_file(dir / "summary.json");
  for (const std::string& key : summary_required_keys())
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key :
       {"status", "reason", "discretisation", "degrees", "elements", "dofs", "steps",
        "newton_iterations", "step_cuts", "linear_solver", "wall_seconds", "volume_initial_m3",
        "volume_final_m3", "max_displacement_m", "probes"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["status"], "converged");
  EXPECT_TRUE(j["reason"].is_null());
  EXPECT_EQ(j["degrees"], nlohmann::json({2, 2, 3}));
  EXPECT_EQ(j["dofs"], 5211);
  EXPECT_EQ(j["step_cuts"].size(), 2u);
  EXPECT_EQ(j["step_cuts"][1]["reason"], "J <= 0 at element 17");
  EXPECT_EQ(j["step_cuts"][0]["dt_retry"], 0.0025);
  for (const char* phase : {"setup", "assembly", "factorisation", "solve", "output", "total"}) {
    EXPECT_TRUE(j["wall_seconds"][phase].is_number()) << phase;
  }
  EXPECT_EQ(j["wall_seconds"]["factorisation"], 1.125);
  EXPECT_EQ(j["volume_final_m3"], 8.4999e-6);
  EXPECT_EQ(j["probes"]["tip_z"], -0.0042);
  EXPECT_EQ(j["mixed_pressure_dofs"], 1536);

  const RunSummary back = read_summary(dir / "summary.json");
  EXPECT_TRUE(back.converged);
  EXPECT_EQ(back.scene, s.scene);
  EXPECT_EQ(back.discretisation, "iga");
  EXPECT_EQ(back.degrees, s.degrees);
  EXPECT_EQ(back.elements, s.elements);
  EXPECT_EQ(back.dofs, s.dofs);
  EXPECT_EQ(back.steps, s.steps);
  EXPECT_EQ(back.newton_iterations, s.newton_iterations);
  ASSERT_EQ(back.step_cuts.size(), 2u);
  EXPECT_EQ(back.step_cuts[0].time, 0.105);
  EXPECT_EQ(back.step_cuts[0].dt_failed, 0.005);
  EXPECT_EQ(back.step_cuts[0].reason, s.step_cuts[0].reason);
  EXPECT_EQ(back.linear_solver, "cholmod");
  EXPECT_EQ(back.wall_seconds.total, 5.1875);
  EXPECT_EQ(back.wall_seconds.assembly, 3.25);
  EXPECT_EQ(back.volume_initial_m3, s.volume_initial_m3);
  EXPECT_EQ(back.max_displacement_m, s.max_displacement_m);
  EXPECT_EQ(back.probes, s.probes);
  EXPECT_EQ(back.extra["mixed_pressure_dofs"], 1536);
}

TEST(RunSummary, FailedRunsGiveTheReasonAndUnknownNumbersAreNull) {
  const auto dir = fresh_directory("summary");
  RunSummary s = example();
  s.converged = false;
  s.failure_reason = "time step below dt_min = 1e-6 s at t = 0.1234 s";
  s.volume_final_m3.reset();
  s.max_displacement_m = std::numeric_limits<double>::quiet_NaN();
  s.probes["tip_z"] = std::numeric_limits<double>::infinity();
  write_summary(s, dir / "summary.json");
  const nlohmann::json j = parse_file(dir / "summary.json");
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["reason"], s.failure_reason);
  EXPECT_TRUE(j["volume_final_m3"].is_null());
  EXPECT_TRUE(j["max_displacement_m"].is_null());
  EXPECT_TRUE(j["probes"]["tip_z"].is_null());
  const RunSummary back = read_summary(dir / "summary.json");
  EXPECT_FALSE(back.converged);
  EXPECT_EQ(back.failure_reason, s.failure_reason);
  EXPECT_FALSE(back.volume_final_m3.has_value());
  EXPECT_FALSE(back.max_displacement_m.has_value());
  EXPECT_FALSE(back.probes.at("tip_z").has_value());
}

TEST(RunSummary, AtomicReplacementLeavesNoTemporaryFiles) {
  const auto dir = fresh_directory("summary");
  write_text(dir / "summary.json", "{ half a file");
  write_summary(example(), dir / "summary.json");
  RunSummary second = example();
  second.steps = 41;
  write_summary(second, dir / "summary.json");
  EXPECT_EQ(read_summary(dir / "summary.json").steps, 41u);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "summary.json");
  }
  EXPECT_EQ(files, 1);
  EXPECT_THROW(write_summary(example(), dir / "missing" / "summary.json"), std::runtime_error);
}

TEST(RunSummary, ReadingReportsMissingKeysAndExtraMustNotShadowThem) {
  const auto dir = fresh_directory("summary");
  nlohmann::ordered_json j = summary_to_json(example());
  j.erase("dofs");
  write_text(dir / "summary.json", j.dump());
  try {
    read_summary(dir / "summary.json");
    ADD_FAILURE() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing key 'dofs'"), std::string::npos) << e.what();
  }
  j = summary_to_json(example());
  j["wall_seconds"]["solve"] = "fast";
  write_text(dir / "summary.json", j.dump());
  EXPECT_THROW(read_summary(dir / "summary.json"), std::runtime_error);
  write_text(dir / "summary.json", "not json");
  EXPECT_THROW(read_summary(dir / "summary.json"), std::runtime_error);
  RunSummary s = example();
  s.extra["dofs"] = 3;
  EXPECT_THROW(summary_to_json(s), std::invalid_argument);
  s.extra = nlohmann::ordered_json::array();
  EXPECT_THROW(summary_to_json(s), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::io
