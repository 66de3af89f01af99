// Hand-made bad inputs through the real `isomuscle` command (issue #7): damaged IGES files given to
// `isomuscle geometry info|solid` and broken scenes given to `isomuscle run`. Each must end with a
// non-zero exit code (not a signal), one error line that names the file, line, key or entity and
// what is wrong, and no NaN; no run may report convergence. No scene reaches time stepping.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "geometry/iges.hpp"
#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_surface.hpp"

namespace isomuscle {
namespace {

namespace fs = std::filesystem;
using cli_test::CliResult;
using cli_test::read_text;

const std::string kBarrel = std::string(ISOMUSCLE_SOURCE_DIR) + "/examples/geometry/barrel.igs";

// Replaces the first occurrence of `from` (which must be there) by `to`.
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the text";
  if (at != std::string::npos)
    text.replace(at, from.size(), to);
  return text;
}

// 1-based number of the first line of `text` that starts with `prefix` (0 when none).
int line_of(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.rfind(prefix, 0) == 0)
      return n;
  }
  ADD_FAILURE() << "no line starts with '" << prefix << "'";
  return 0;
}

// The parameters of the P section of an IGES text (one entity 128 file), each as (line, first
// column, past-the-end column) of its text in columns 1-64.
struct Parameter {
  std::size_t line;
  std::size_t begin;
  std::size_t end;
};

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

std::vector<Parameter> parameters(const std::vector<std::string>& lines) {
  std::vector<Parameter> found;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (lines[l].size() < 73 || lines[l][72] != 'P')
      continue;
    const std::string body = lines[l].substr(0, 64);
    std::size_t k = 0;
    while (k < body.size()) {
      const std::size_t stop = body.find_first_of(",;", k);
      const std::size_t end = stop == std::string::npos ? body.size() : stop;
      const std::size_t first = body.find_first_not_of(' ', k);
      if (first < end) {
        const std::size_t last = body.find_last_not_of(' ', end - 1);
        found.push_back({l, first, last + 1});
      }
      k = end + 1;
    }
  }
  return found;
}

// The IGES text with parameter `index` (0-based; 0 is the entity type) replaced by `value`, right
// aligned in the same columns so that every record keeps its 80 columns.
std::string with_parameter(const std::string& text, std::size_t index, const std::string& value) {
  std::vector<std::string> lines = split_lines(text);
  const std::vector<Parameter> p = parameters(lines);
  EXPECT_LT(index, p.size());
  if (index >= p.size())
    return text;
  const Parameter& at = p[index];
  const std::size_t width = at.end - at.begin;
  EXPECT_LE(value.size(), width) << value;
  const std::string padded = std::string(width - std::min(width, value.size()), ' ') + value;
  lines[at.line].replace(at.begin, width, padded);
  std::string out;
  for (const std::string& l : lines)
    out += l + "\n";
  return out;
}

// Entity 128 layout (IGES 5.3 §4.23): 10 integers, then K1 + M1 + 2 u knots, K2 + M2 + 2 v
// knots, (K1 + 1)(K2 + 1) weights, then the control point coordinates.
struct Layout {
  std::size_t first_u_knot = 10;
  std::size_t first_weight = 0;
  std::size_t first_coordinate = 0;
};

Layout layout(const std::string& text) {
  const std::vector<std::string> lines = split_lines(text);
  const std::vector<Parameter> p = parameters(lines);
  const auto integer = [&](std::size_t k) {
    return std::stoul(lines[p[k].line].substr(p[k].begin, p[k].end - p[k].begin));
  };
  const std::size_t k1 = integer(1), k2 = integer(2), m1 = integer(3), m2 = integer(4);
  Layout l;
  l.first_weight = 10 + (k1 + m1 + 2) + (k2 + m2 + 2);
  l.first_coordinate = l.first_weight + (k1 + 1) * (k2 + 1);
  return l;
}

class BadInputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("isomuscle_test_bad_inputs_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  static CliResult run(const std::string& arguments) {
    return cli_test::run_isomuscle(arguments, dir_ / "stderr.txt");
  }

  // A clean rejection: exit code 1 or 2 (no signal, no abort), at most `max_lines` lines on
  // stderr, every word of `needles` in it, no NaN printed (unless `nan_allowed`: the file's own
  // text quoted back), nothing converged.
  static void expect_rejected(const CliResult& r, const std::vector<std::string>& needles,
                              std::size_t max_lines = 1, bool nan_allowed = false) {
    EXPECT_TRUE(r.code == 1 || r.code == 2) << "exit code " << r.code << ", stderr: " << r.err;
    std::vector<std::string> lines;
    for (const std::string& l : split_lines(r.err)) {
      if (l.find_first_not_of(" \t\r") != std::string::npos)
        lines.push_back(l);
    }
    EXPECT_GE(lines.size(), 1u);
    EXPECT_LE(lines.size(), max_lines) << r.err;
    for (const std::string& needle : needles)
      EXPECT_NE(r.err.find(needle), std::string::npos) << "'" << needle << "' not in: " << r.err;
    if (!nan_allowed) {
      EXPECT_FALSE(std::regex_search(r.err, std::regex("\\bnan\\b", std::regex::icase))) << r.err;
    }
    EXPECT_EQ(r.out.find("converged"), std::string::npos) << r.out;
  }

  // Scene runs: as above, and a summary, where one was written, says the run failed.
  static void expect_scene_rejected(const std::string& name, const std::string& text,
                                    const std::vector<std::string>& needles, int exit_code,
                                    std::size_t max_lines) {
    SCOPED_TRACE(name);
    const fs::path scene = write(name + ".toml", text);
    const fs::path out = dir_ / ("out_" + name);
    const CliResult r = run("run " + scene.string() + " --out " + out.string());
    EXPECT_EQ(r.code, exit_code) << r.err;
    expect_rejected(r, needles, max_lines);
    if (fs::exists(out / "summary.json")) {
      const nlohmann::json s = nlohmann::json::parse(read_text(out / "summary.json"));
      EXPECT_EQ(s["status"], "failed");
      EXPECT_EQ(s.value("steps", 0), 0);  // rejected before the first time step
    }
  }

  // examples/barrel/contract.toml with the IGES path absolute.
  static std::string contract_scene() {
    const std::string text =
        read_text(fs::path(ISOMUSCLE_SOURCE_DIR) / "examples/barrel/contract.toml");
    return replace_once(text, "\"../geometry/barrel.igs\"", "\"" + kBarrel + "\"");
  }

  static fs::path dir_;
};

fs::path BadInputs::dir_;

// Each damaged barrel file is rejected by both `geometry info` and `geometry solid`, with the
// message naming the file and the damage.
TEST_F(BadInputs, DamagedIgesFilesAreRejectedWithTheirFault) {
  const std::string barrel = read_text(kBarrel);
  const Layout l = layout(barrel);
  const std::size_t y_of_point_1 = l.first_coordinate + 4;
  struct Case {
    std::string name;
    std::string text;
    std::vector<std::string> needles;
  };
  const std::vector<Case> cases = {
      {"nan_coordinate",
       with_parameter(barrel, y_of_point_1, "NaN"),
       {"parameter " + std::to_string(y_of_point_1 + 1), "'NaN'", "not a real number"}},
      {"huge_coordinate",
       with_parameter(barrel, y_of_point_1, "1.0E+300"),
       {"entity 128", "control point (1, 0)", "beyond 1000 m"}},
      {"zero_weight",
       with_parameter(barrel, l.first_weight + 2, "0.0"),
       {"parameter " + std::to_string(l.first_weight + 3), "weight W(2, 0)", "must be positive"}},
      {"negative_weight",
       with_parameter(barrel, l.first_weight + 1, "-0.5"),
       {"weight W(1, 0)", "is -0.5", "must be positive"}},
      {"decreasing_knots",
       with_parameter(barrel, l.first_u_knot + 3, "0.9"),
       {"entity 128", "knots decrease", "non-decreasing"}},
      {"truncated", barrel.substr(0, barrel.size() / 2), {"is truncated", "terminate (T) record"}},
      {"cut_mid_record", barrel.substr(0, 1500), {"line 19 has 42 columns", "80"}},
      {"empty", "", {"is empty"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path file = write(c.name + ".igs", c.text);
    const bool quotes_nan = c.name == "nan_coordinate";
    for (const std::string& command : {"geometry info " + file.string(),
                                       "geometry solid " + file.string() + " --centreline v"}) {
      SCOPED_TRACE(command);
      const CliResult r = run(command);
      std::vector<std::string> needles = c.needles;
      needles.push_back("IGES file '" + file.string() + "'");
      expect_rejected(r, needles, 1, quotes_nan);
    }
  }
}

// Surfaces that are valid NURBS but not a muscle: all control points at one place, and an open
// patch asked for a solid around a centreline (the direction named must be the open one's
// partner, closed: it is not).
TEST_F(BadInputs, SurfacesThatCannotBeShrunkAreRejected) {
  const geometry::KnotVector k({0.0, 0.0, 0.0, 1.0, 1.0, 1.0}, 2);
  std::vector<Eigen::Vector3d> same(9, Eigen::Vector3d(0.01, 0.02, 0.03));
  std::vector<Eigen::Vector3d> patch;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i)
      patch.emplace_back(0.01 * i, 0.01 * j, 0.001 * i * j);
  }
  const fs::path degenerate = dir_ / "degenerate.igs";
  const fs::path open = dir_ / "open_patch.igs";
  geometry::write_iges(degenerate,
                       {geometry::NurbsSurface(k, k, same, std::vector<double>(9, 1.0))});
  geometry::write_iges(open, {geometry::NurbsSurface(k, k, patch, std::vector<double>(9, 1.0))});

  expect_rejected(run("geometry solid " + degenerate.string() + " --centreline v"),
                  {"degenerate", "all 9 control points coincide"});
  expect_rejected(run("geometry solid " + open.string() + " --centreline v"),
                  {"not closed in u", "--centreline"});
  expect_rejected(run("geometry solid " + open.string() + " --centreline u"),
                  {"not closed in v", "--centreline"});

  // The same open patch named by a scene: the scene's centreline direction is not closed.
  std::string scene = replace_once(contract_scene(), kBarrel, open.string());
  expect_scene_rejected("open_patch", scene, {"not closed in u"}, 1, 2);
}

// Scene mistakes found while reading the scene: exit code 2 and one line "scene.toml:LINE: ..."
// naming the key and what is wrong, with the valid choices where there are choices.
TEST_F(BadInputs, SceneMistakesNameTheLineAndTheKey) {
  const std::string base = contract_scene();
  struct Case {
    std::string name;
    std::string from;
    std::string to;
    std::string line_prefix;  // the line the message must name
    std::vector<std::string> needles;
  };
  const std::string params =
      "model = \"tang2009\"                # defaults: Table 5.1, "
      "ramp_time = 0.005 s, t0 = 0, t1 = inf\n";
  const std::vector<Case> cases = {
      {"negative_dt", "dt = 0.001 ", "dt = -0.001 ", "dt = ", {"'dt' in [time]", "must be > 0"}},
      {"zero_dt", "dt = 0.001 ", "dt = 0.0 ", "dt = ", {"'dt' in [time]", "must be > 0"}},
      {"end_before_start", "end = 0.2", "end = -0.1", "end = ", {"'end' in [time]", "must be > 0"}},
      {"unknown_model",
       "model = \"tang2009\"",
       "model = \"tang2010\"",
       "model = ",
       {"'model' in [material]", "must be one of lu2010, tang2009, neo_hookean, linear_elastic",
        "did you mean \"tang2009\""}},
      {"unknown_parameter",
       params,
       params + "[material.parameters]\nsigmaa = 1.0\n",
       "sigmaa",
       {"'sigmaa'", "not a parameter", "did you mean 'sigma0'", "valid parameters"}},
      {"parameter_out_of_range",
       params,
       params + "[material.parameters]\nD = -1.0\n",
       "D = ",
       {"'D' in [material.parameters]", "must be in (0, inf)", "got -1"}},
      {"missing_iges",
       kBarrel,
       (dir_ / "nothere.igs").string(),
       "iges = ",
       {"'iges' in [geometry]", "no readable file", "nothere.igs"}},
      {"face_that_does_not_exist",
       "face = \"v0\"                       # the end z = 0",
       "face = \"x7\"",
       "face = \"x7\"",
       {"'face' in [[boundary]] #1", "must be one of u0, u1, v0, v1, w0, w1", "\"x7\""}},
      {"typo", "dt_max = ", "dt_maxx = ", "dt_maxx", {"unknown key", "did you mean 'dt_max'"}},
      {"string_for_number",
       "end = 0.2",
       "end = \"0.2\"",
       "end = ",
       {"'end' in [time]", "must be a number", "string"}},
  };
  for (const Case& c : cases) {
    const std::string text = replace_once(base, c.from, c.to);
    const std::string scene = (dir_ / (c.name + ".toml")).string();
    std::vector<std::string> needles = c.needles;
    needles.push_back(scene + ":" + std::to_string(line_of(text, c.line_prefix)) + ":");
    expect_scene_rejected(c.name, text, needles, 2, 1);
  }
}

// Mistakes that need the geometry are found by the set-up, before any time step: exit code 1, the
// error names the scene entry ([[boundary]] #1, [[probe]] 'tip_z') and what is wrong. The command
// also says where the (failed) summary is: 2 lines on stderr.
TEST_F(BadInputs, SetupRejectsPlanesAndProbesThatMissTheBody) {
  const std::string base = contract_scene();
  expect_scene_rejected(
      "plane_selects_nothing",
      replace_once(base, "face = \"v0\"                       # the end z = 0",
                   "face = { point = [0.0, 0.0, 1.0], normal = [0.0, 0.0, 1.0], tolerance = 1e-9 "
                   "}"),
      {"[[boundary]] #1", "no control point lies within 1e-09 m of the plane", "tolerance"}, 1, 2);
  expect_scene_rejected("probe_outside",
                        replace_once(base, "point = [0.0, 0.0, 0.05]", "point = [1.0, 0.0, 0.05]"),
                        {"[[probe]] 'tip_z'", "lies outside the solid"}, 1, 2);
  // A damaged IGES file named by a scene: the reader's message, not a crash in the set-up.
  const std::string barrel = read_text(kBarrel);
  const fs::path zero_weight =
      write("scene_zero_weight.igs", with_parameter(barrel, layout(barrel).first_weight, "0.0"));
  expect_scene_rejected("scene_zero_weight", replace_once(base, kBarrel, zero_weight.string()),
                        {"scene_zero_weight.igs", "weight W(0, 0)", "must be positive"}, 1, 2);
}

}  // namespace
}  // namespace isomuscle
