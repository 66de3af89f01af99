#include "io/setting_check.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numeric>

namespace isomuscle::io {

// Membership in the interval; NaN never belongs, infinities only with allow_infinity.
bool Range::contains(double x) const {
  if (std::isnan(x) || (std::isinf(x) && !allow_infinity))
    return false;
  if (min_exclusive ? !(x > min) : !(x >= min))
    return false;
  if (max_exclusive ? !(x < max) : !(x <= max))
    return false;
  return true;
}

std::string Range::describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return std::string("in ") + (min_exclusive ? "(" : "[") + format_number(min) + ", " +
           format_number(max) + (max_exclusive ? ")" : "]");
  }
  if (has_min)
    return std::string(min_exclusive ? "> " : ">= ") + format_number(min);
  if (has_max)
    return std::string(max_exclusive ? "< " : "<= ") + format_number(max);
  return {};
}

InvalidSetting::InvalidSetting(std::string key, std::string detail)
    : std::invalid_argument("'" + key + "' " + detail),
      key_(std::move(key)),
      detail_(std::move(detail)) {}

std::string format_number(double x) {
  if (std::isnan(x))
    return "nan";
  if (std::isinf(x))
    return x > 0 ? "inf" : "-inf";
  std::array<char, 64> buffer{};
  // Shortest round-trip digits in %g style: 700000 rather than 7e+05, 1e-06 rather than 0.000001.
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), x, std::chars_format::general);
  return std::string(buffer.data(), result.ptr);
}

std::string join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0)
      out += separator;
    out += items[i];
  }
  return out;
}

std::string range_violation(double x, const Range& range) {
  if (std::isnan(x) && range.allow_infinity)
    return "must be a number (got nan)";
  if (std::isnan(x) || (std::isinf(x) && !range.allow_infinity)) {
    return "must be a finite number (got " + format_number(x) + ")";
  }
  if (range.contains(x))
    return {};
  return "must be " + range.describe() + " (got " + format_number(x) + ")";
}

void check_range(std::string_view key, double x, const Range& range) {
  const std::string detail = range_violation(x, range);
  if (!detail.empty())
    throw InvalidSetting(std::string(key), detail);
}

void check_choice(std::string_view key, std::string_view value,
                  const std::vector<std::string>& choices) {
  if (std::find(choices.begin(), choices.end(), value) != choices.end())
    return;
  std::string detail = "must be one of " + join(choices) + " (got \"" + std::string(value) + "\")";
  const std::string near = closest_match(value, choices);
  if (!near.empty())
    detail += "; did you mean \"" + near + "\"?";
  throw InvalidSetting(std::string(key), detail);
}

bool is_plain_name(std::string_view name) {
  if (name.empty())
    return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.' || c == '-';
    if (!ok)
      return false;
  }
  return true;
}

// Levenshtein distance by the two-row dynamic programme (Wagner & Fischer 1974).
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates,
                          std::size_t max_distance) {
  std::string best;
  std::size_t best_distance = max_distance + 1;
  for (const std::string& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    // A suggestion must keep part of what was typed: "x" is not a near miss of "u".
    if (d < best_distance && d < word.size()) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

}  // namespace isomuscle::io
