#pragma once
// Checks of one setting's value, shared by the scene reader (which knows file and line) and the
// validate() methods of the scene structs (which know only the key). Both produce the same text,
// e.g. "'dt' must be > 0 (got -0.001)", so an error reads the same whether a scene file or a
// program built the settings.
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace isomuscle::io {

// A closed, half-open or open interval of allowed values; the default allows every finite number.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  bool allow_infinity = false;  // +-inf pass when within the bounds (e.g. t1 = inf: never)

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static Range at_least(double a) { return {a, std::numeric_limits<double>::infinity()}; }
  static Range closed(double a, double b) { return {a, b}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  // Every number including +-inf (checked elsewhere, e.g. by the material factory).
  static Range any_or_infinite() {
    Range r;
    r.allow_infinity = true;
    return r;
  }

  bool contains(double x) const;
  // "> 0", ">= 1", "<= 5", "in [0, 1]", "in (0, 1]"; empty for the unbounded range.
  std::string describe() const;
};

// A setting with a bad value, found by a validate() method. key is relative to the struct's table
// ("dt", "refine.degree_elevation"); detail is the rest of the sentence ("must be > 0 (got -1)").
// The scene loader turns it into a SceneError at the key's line.
class InvalidSetting : public std::invalid_argument {
 public:
  InvalidSetting(std::string key, std::string detail);
  const std::string& key() const { return key_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string key_;
  std::string detail_;
};

// Shortest text that reads back to the same double (std::to_chars, general format), e.g.
// "-0.001", "700000", "1e-06".
std::string format_number(double x);
// "u, v, w"
std::string join(const std::vector<std::string>& items, std::string_view separator = ", ");

// Throw InvalidSetting when x is not finite or outside range: "'dt' must be > 0 (got -0.001)".
void check_range(std::string_view key, double x, const Range& range);
// Throw InvalidSetting when value is not one of choices: "'centreline' must be one of u, v (got
// "x")".
void check_choice(std::string_view key, std::string_view value,
                  const std::vector<std::string>& choices);
// The detail text of a failed check_range (without the key), empty when x is allowed.
std::string range_violation(double x, const Range& range);

// True for a non-empty name of letters, digits, '_', '.' and '-' (field names, CSV columns,
// HDF5 dataset names: nothing that needs quoting or escaping anywhere).
bool is_plain_name(std::string_view name);

// Levenshtein distance of two short strings (key suggestions, "did you mean").
std::size_t edit_distance(std::string_view a, std::string_view b);
// The candidate nearest to word when its edit distance is at most max_distance, else empty.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates,
                          std::size_t max_distance = 2);

}  // namespace isomuscle::io
