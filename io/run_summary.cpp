#include "io/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace isomuscle::io {

using Json = nlohmann::ordered_json;

namespace {

// A number, or null when unknown or not finite: JSON has no NaN, and a run never reports one.
Json number_or_null(std::optional<double> x) {
  if (!x || !std::isfinite(*x))
    return nullptr;
  return *x;
}

struct Reader {
  const Json& document;
  const std::filesystem::path& path;

  const Json& at(const Json& object, const std::string& key, const std::string& where) const {
    if (!object.is_object() || !object.contains(key)) {
      throw std::runtime_error(path.string() + ": missing key '" + where + key + "'");
    }
    return object.at(key);
  }
  [[noreturn]] void mistyped(const std::string& key, const char* expected) const {
    throw std::runtime_error(path.string() + ": key '" + key + "' must be " + expected);
  }
  double number(const Json& object, const std::string& key, const std::string& where = "") const {
    const Json& v = at(object, key, where);
    if (!v.is_number())
      mistyped(where + key, "a number");
    return v.get<double>();
  }
  std::optional<double> number_or_null(const Json& object, const std::string& key,
                                       const std::string& where = "") const {
    const Json& v = at(object, key, where);
    if (v.is_null())
      return std::nullopt;
    if (!v.is_number())
      mistyped(where + key, "a number or null");
    return v.get<double>();
  }
  std::size_t count(const std::string& key) const {
    const Json& v = at(document, key, "");
    if (!v.is_number_unsigned())
      mistyped(key, "a non-negative integer");
    return v.get<std::size_t>();
  }
  std::string string(const Json& object, const std::string& key,
                     const std::string& where = "") const {
    const Json& v = at(object, key, where);
    if (!v.is_string())
      mistyped(where + key, "a string");
    return v.get<std::string>();
  }
};

}  // namespace

const std::vector<std::string>& summary_required_keys() {
  static const std::vector<std::string> keys{"status",
                                             "reason",
                                             "scene",
                                             "discretisation",
                                             "degrees",
                                             "elements",
                                             "dofs",
                                             "steps",
                                             "newton_iterations",
                                             "step_cuts",
                                             "linear_solver",
                                             "wall_seconds",
                                             "volume_initial_m3",
                                             "volume_final_m3",
                                             "max_displacement_m",
                                             "probes"};
  return keys;
}

Json summary_to_json(const RunSummary& s) {
  Json j = Json::object();
  j["status"] = s.converged ? "converged" : "failed";
  j["reason"] = s.converged ? Json(nullptr) : Json(s.failure_reason);
  j["scene"] = s.scene;
  j["discretisation"] = s.discretisation;
  j["degrees"] = s.degrees;
  j["elements"] = s.elements;
  j["dofs"] = s.dofs;
  j["steps"] = s.steps;
  j["newton_iterations"] = s.newton_iterations;
  j["step_cuts"] = Json::array();
  for (const StepCut& cut : s.step_cuts) {
    j["step_cuts"].push_back(Json{{"time", number_or_null(cut.time)},
                                  {"dt_failed", number_or_null(cut.dt_failed)},
                                  {"dt_retry", number_or_null(cut.dt_retry)},
                                  {"reason", cut.reason}});
  }
  j["linear_solver"] = s.linear_solver;
  const WallSeconds& w = s.wall_seconds;
  j["wall_seconds"] = Json{{"setup", number_or_null(w.setup)},
                           {"assembly", number_or_null(w.assembly)},
                           {"factorisation", number_or_null(w.factorisation)},
                           {"solve", number_or_null(w.solve)},
                           {"output", number_or_null(w.output)},
                           {"total", number_or_null(w.total)}};
  j["volume_initial_m3"] = number_or_null(s.volume_initial_m3);
  j["volume_final_m3"] = number_or_null(s.volume_final_m3);
  j["max_displacement_m"] = number_or_null(s.max_displacement_m);
  j["probes"] = Json::object();
  for (const auto& [name, value] : s.probes)
    j["probes"][name] = number_or_null(value);
  if (!s.extra.is_object()) {
    throw std::invalid_argument("run summary: 'extra' must be a JSON object, got " +
                                std::string(s.extra.type_name()));
  }
  for (const auto& [key, value] : s.extra.items()) {
    if (j.contains(key)) {
      throw std::invalid_argument("run summary: extra key '" + key +
                                  "' would replace a required key");
    }
    j[key] = value;
  }
  return j;
}

void write_summary(const RunSummary& summary, const std::filesystem::path& path) {
  write_file_atomically(path, summary_to_json(summary).dump(2) + "\n");
}

RunSummary read_summary(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot open run summary " + path.string());
  Json document;
  try {
    document = Json::parse(in);
  } catch (const Json::parse_error& e) {
    throw std::runtime_error(path.string() + ": not valid JSON (" + e.what() + ")");
  }
  const Reader r{document, path};
  RunSummary s;
  const std::string status = r.string(document, "status");
  if (status != "converged" && status != "failed") {
    throw std::runtime_error(
        path.string() + ": 'status' must be \"converged\" or \"failed\" (got \"" + status + "\")");
  }
  s.converged = status == "converged";
  const Json& reason = r.at(document, "reason", "");
  if (!reason.is_null() && !reason.is_string())
    r.mistyped("reason", "a string or null");
  if (reason.is_string())
    s.failure_reason = reason.get<std::string>();
  s.scene = r.string(document, "scene");
  s.discretisation = r.string(document, "discretisation");
  const Json& degrees = r.at(document, "degrees", "");
  if (!degrees.is_array())
    r.mistyped("degrees", "an array of integers");
  for (const Json& d : degrees) {
    if (!d.is_number_integer())
      r.mistyped("degrees", "an array of integers");
    s.degrees.push_back(d.get<int>());
  }
  s.elements = r.count("elements");
  s.dofs = r.count("dofs");
  s.steps = r.count("steps");
  s.newton_iterations = r.count("newton_iterations");
  const Json& cuts = r.at(document, "step_cuts", "");
  if (!cuts.is_array())
    r.mistyped("step_cuts", "an array");
  for (const Json& c : cuts) {
    s.step_cuts.push_back(
        StepCut{r.number(c, "time", "step_cuts[]."), r.number(c, "dt_failed", "step_cuts[]."),
                r.number(c, "dt_retry", "step_cuts[]."), r.string(c, "reason", "step_cuts[].")});
  }
  s.linear_solver = r.string(document, "linear_solver");
  const Json& w = r.at(document, "wall_seconds", "");
  const std::string in_w = "wall_seconds.";
  s.wall_seconds = WallSeconds{r.number(w, "setup", in_w),         r.number(w, "assembly", in_w),
                               r.number(w, "factorisation", in_w), r.number(w, "solve", in_w),
                               r.number(w, "output", in_w),        r.number(w, "total", in_w)};
  s.volume_initial_m3 = r.number_or_null(document, "volume_initial_m3");
  s.volume_final_m3 = r.number_or_null(document, "volume_final_m3");
  s.max_displacement_m = r.number_or_null(document, "max_displacement_m");
  const Json& probes = r.at(document, "probes", "");
  if (!probes.is_object())
    r.mistyped("probes", "an object");
  for (const auto& [name, value] : probes.items()) {
    s.probes[name] = r.number_or_null(probes, name, "probes.");
  }
  const auto& required = summary_required_keys();
  for (const auto& [key, value] : document.items()) {
    if (std::find(required.begin(), required.end(), key) == required.end())
      s.extra[key] = value;
  }
  return s;
}

}  // namespace isomuscle::io
