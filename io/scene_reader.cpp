#include "io/scene_reader.hpp"

#include <algorithm>
#include <climits>
#include <fstream>
#include <sstream>
#include <tuple>

namespace isomuscle::io {

namespace {

std::string location_prefix(const std::string& file, int line, int column) {
  std::string out = file;
  if (line > 0)
    out += ":" + std::to_string(line);
  if (line > 0 && column > 0)
    out += ":" + std::to_string(column);
  return out + ": ";
}

std::string in_quotes(std::string_view key) {
  std::string quoted;  // (appended: GCC 12 warns falsely about "'" + std::string&&)
  quoted.reserve(key.size() + 2);
  quoted.append(1, '\'').append(key).append(1, '\'');
  return quoted;
}

std::string ordinal_element(std::size_t index, std::string_view key) {
  return "element " + std::to_string(index + 1) + " of '" + std::string(key) + "'";
}

// toml++ 3.3.0 (Debian 12) reaches an unreachable point, i.e. undefined behaviour, when it asks
// whether a character in U+00A1..U+0499, U+2C5E..U+3057 or U+FB26..U+FEFE (é, µ, °, Greek,
// Cyrillic, ...) is whitespace (upstream marzer/tomlplusplus#190, #295). It asks that of every
// character outside strings and comments, also of a quote and what follows it where no string can
// begin ("a = 5'µ'"), and in a multi-line basic string of the characters after a backslash up to
// the first that is not whitespace, across line breaks after a line-ending backslash.
// fuzz/scene_parser_fuzzer found all but the last, which is #190 (fuzz/regressions/scene_parser/).
// Such input is rejected here, before toml++ reads it. All of it is a TOML syntax error anyway,
// except a non-ASCII character first after a line-ending backslash: valid, but rare.
void reject_input_tomlplusplus_mishandles(std::string_view text, const std::string& file_name) {
  enum class State { normal, comment, basic, literal, multi_basic, multi_literal };
  State state = State::normal;
  int line = 1;
  std::size_t line_begin = 0;
  char previous = '\n';  // last character outside strings and blanks: can a string start here?
  // toml++ reads a value that starts with neither a quote nor a bracket (a number, a date, true)
  // up to a value terminator, quotes included: no string starts inside it ("n = 0='x'").
  bool in_bare_value = false;
  std::string open;  // the '[' of arrays and '{' of inline tables open in values
  // Fails at the character at byte `where`; columns count characters, as toml++'s do.
  const auto fail = [&](std::size_t where, const std::string& message) {
    int column = 1;
    for (std::size_t b = line_begin; b < where; ++b)
      column += (static_cast<unsigned char>(text[b]) & 0xC0) != 0x80 ? 1 : 0;
    throw SceneError(file_name, line, column, "TOML syntax error: " + message);
  };
  const auto at = [&](std::size_t k, std::string_view token) {
    return text.compare(k, token.size(), token) == 0;
  };
  const auto blank = [&](std::size_t k) {
    return text[k] == ' ' || text[k] == '\t' || text[k] == '\r';
  };
  line_begin = at(0, "\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte-order mark is allowed
  for (std::size_t k = line_begin; k < text.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(text[k]);
    if (c == '\n') {
      ++line;
      line_begin = k + 1;
      previous = '\n';
      in_bare_value = false;
      if (state == State::comment || state == State::basic || state == State::literal)
        state = State::normal;  // an unterminated one-line string is toml++'s to report
      continue;
    }
    // Where a value starts: after the '=' of a key, or as an element of an array.
    const bool value_position =
        previous == '=' || (!open.empty() && open.back() == '[' &&
                            std::string_view("[,\n").find(previous) != std::string_view::npos);
    switch (state) {
      case State::normal:
        if (c >= 0x80)
          fail(k, "a non-ASCII character outside a string or comment");
        if (in_bare_value) {
          if (std::string_view(" \t\r]},#").find(static_cast<char>(c)) == std::string_view::npos) {
            previous = static_cast<char>(c);
            break;
          }
          in_bare_value = false;
        }
        if (c == '#') {
          state = State::comment;
        } else if ((c == '"' || c == '\'') &&
                   std::string_view("\n=[{,.").find(previous) != std::string_view::npos) {
          const bool multi = at(k, c == '"' ? "\"\"\"" : "\'\'\'");
          state = c == '"' ? (multi ? State::multi_basic : State::basic)
                           : (multi ? State::multi_literal : State::literal);
          k += multi ? 2 : 0;
        } else if ((c == '[' || c == '{') && value_position) {
          open += static_cast<char>(c);
        } else if ((c == ']' && !open.empty() && open.back() == '[') ||
                   (c == '}' && !open.empty() && open.back() == '{')) {
          open.pop_back();
        } else if (value_position && !blank(k) && c != ']' && c != '}' && c != ',') {
          in_bare_value = true;
        }
        if (!blank(k) && state == State::normal)
          previous = static_cast<char>(c);
        break;
      case State::comment:
        break;
      case State::basic:
        if (c == '\\' && k + 1 < text.size() && text[k + 1] != '\n') {
          ++k;  // an escape: \" does not end the string
        } else if (c == '"') {
          state = State::normal;
          previous = '"';
        }
        break;
      case State::literal:
        if (c == '\'') {
          state = State::normal;
          previous = '\'';
        }
        break;
      case State::multi_basic:
        if (c == '\\') {
          // toml++ asks of each character after a backslash whether it is whitespace, up to the
          // first that is not, across line breaks when the backslash ends its line.
          std::size_t n = k + 1;
          while (n < text.size() && blank(n))
            ++n;
          const bool line_ending = n < text.size() && text[n] == '\n';
          for (; line_ending && n < text.size() && (blank(n) || text[n] == '\n'); ++n) {
            if (text[n] == '\n') {
              ++line;
              line_begin = n + 1;
            }
          }
          if (n < text.size() && static_cast<unsigned char>(text[n]) >= 0x80) {
            fail(n, line_ending ? "a non-ASCII character right after a line-ending backslash in a "
                                  "multi-line string, which toml++ 3.3.0 cannot read; begin the "
                                  "line with an ASCII character"
                                : "a non-ASCII character after '\\' in a multi-line string is no "
                                  "escape sequence");
          }
          k = n == k + 1 ? n : n - 1;  // an escape: \" does not end the string
        } else if (at(k, "\"\"\"")) {
          for (k += 2; k + 1 < text.size() && text[k + 1] == '"';)
            ++k;  // up to two quotes of the content stand before the closing ones
          state = State::normal;
          previous = '"';
        }
        break;
      case State::multi_literal:
        if (at(k, "'''")) {
          for (k += 2; k + 1 < text.size() && text[k + 1] == '\'';)
            ++k;
          state = State::normal;
          previous = '\'';
        }
        break;
    }
  }
}

}  // namespace

SceneError::SceneError(std::string file, int line, int column, const std::string& message)
    : std::runtime_error(location_prefix(file, line, column) + message),
      file_(std::move(file)),
      line_(line),
      column_(column),
      message_(message) {}

toml::table parse_toml_text(std::string_view text, const std::string& file_name) {
  reject_input_tomlplusplus_mishandles(text, file_name);
  try {
    return toml::parse(text, std::string_view(file_name));
  } catch (const toml::parse_error& e) {
    throw SceneError(file_name, static_cast<int>(e.source().begin.line),
                     static_cast<int>(e.source().begin.column),
                     "TOML syntax error: " + std::string(e.description()));
  }
}

toml::table parse_toml_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw SceneError(
        path.string(), 0, 0,
        std::filesystem::exists(path, ec) ? "not a regular file" : "no such scene file");
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in)
    throw SceneError(path.string(), 0, 0, "cannot read the scene file");
  return parse_toml_text(text.str(), path.string());
}

std::string describe_value(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string (\"" + std::string(*node.value<std::string_view>()) + "\")";
    case toml::node_type::integer:
      return "an integer (" + std::to_string(*node.value<std::int64_t>()) + ")";
    case toml::node_type::floating_point:
      return "a floating-point number (" + format_number(*node.value<double>()) + ")";
    case toml::node_type::boolean:
      return std::string("a boolean (") + (*node.value<bool>() ? "true" : "false") + ")";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

SceneTable::SceneTable(const toml::table& root, std::string file)
    : SceneTable(root, std::move(file), "top level", std::string{}, true) {}

SceneTable::SceneTable(const toml::table& table, std::string file, std::string display,
                       std::optional<std::string> dotted_path, bool is_root)
    : table_(&table),
      file_(std::move(file)),
      display_(std::move(display)),
      dotted_path_(std::move(dotted_path)),
      is_root_(is_root) {}

int SceneTable::line() const {
  return is_root_ ? 0 : static_cast<int>(table_->source().begin.line);
}

int SceneTable::line_of(std::string_view key) const {
  for (auto&& [k, v] : *table_) {
    if (k.str() == key)
      return static_cast<int>(k.source().begin.line);
  }
  return line();
}

const toml::node* SceneTable::find(std::string_view key) {
  allow(key);
  return table_->get(key);
}

const toml::node* SceneTable::find_const(std::string_view key) const {
  return table_->get(key);
}

bool SceneTable::contains(std::string_view key) {
  return find(key) != nullptr;
}

toml::node_type SceneTable::type_of(std::string_view key) {
  const toml::node* node = find(key);
  return node ? node->type() : toml::node_type::none;
}

std::vector<std::string> SceneTable::keys() const {
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::string>> ordered;
  for (auto&& [k, v] : *table_) {
    ordered.emplace_back(k.source().begin.line, k.source().begin.column, std::string(k.str()));
  }
  std::sort(ordered.begin(), ordered.end());
  std::vector<std::string> out;
  for (auto& entry : ordered)
    out.push_back(std::get<2>(entry));
  return out;
}

void SceneTable::allow(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end())
    known_.emplace_back(key);
}

void SceneTable::forbid(std::string_view key, const std::string& reason) {
  if (contains(key))
    fail(key, reason);
}

std::string SceneTable::where() const {
  return is_root_ ? std::string{} : " in " + display_;
}

void SceneTable::fail(std::string_view key, const std::string& detail) const {
  throw SceneError(file_, line_of(key), 0, in_quotes(key) + where() + " " + detail);
}

void SceneTable::fail_table(const std::string& message) const {
  throw SceneError(file_, line(), 0, (is_root_ ? std::string{} : display_ + " ") + message);
}

void SceneTable::fail(const InvalidSetting& error) const {
  // Walk down a dotted key ("refine.degree_elevation") as far as the file has tables.
  const std::string& key = error.key();
  std::size_t start = 0;
  SceneTable current = *this;
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
    const std::string segment = key.substr(start, dot - start);
    const toml::node* node = current.find_const(segment);
    if (node == nullptr || !node->is_table())
      break;
    current = current.child(*node->as_table(), segment);
    start = dot + 1;
  }
  current.fail(key.substr(start), error.detail());
}

void SceneTable::fail_type(std::string_view key, const toml::node& node,
                           std::string_view expected) const {
  fail(key, "must be " + std::string(expected) + ", got " + describe_value(node));
}

void SceneTable::fail_missing(std::string_view key, bool is_table) const {
  const std::string path =
      dotted_path_ && !is_root_ ? *dotted_path_ + "." + std::string(key) : std::string(key);
  std::string message =
      "missing required " + (is_table ? "table [" + path + "]" : "key " + in_quotes(key)) + where();
  // A near miss among the keys nobody read is most likely the intended one, misspelt.
  for (auto&& [k, v] : *table_) {
    if (std::find(known_.begin(), known_.end(), k.str()) != known_.end())
      continue;
    const std::size_t d = edit_distance(k.str(), key);
    if (d <= 2 && d < k.str().size()) {
      message += "; found " + in_quotes(k.str()) + " on line " +
                 std::to_string(k.source().begin.line) + ": a misspelling?";
      break;
    }
  }
  throw SceneError(file_, line(), 0, message);
}

SceneTable SceneTable::child(const toml::table& table, std::string_view key) const {
  if (dotted_path_) {
    std::string path = is_root_ ? std::string(key) : *dotted_path_ + "." + std::string(key);
    return SceneTable(table, file_, "[" + path + "]", path, false);
  }
  return SceneTable(table, file_, in_quotes(key) + " of " + display_, std::nullopt, false);
}

// ---- numbers -------------------------------------------------------------------------------

std::optional<double> SceneTable::optional_number(std::string_view key, const Range& range) {
  const toml::node* node = find(key);
  if (node == nullptr)
    return std::nullopt;
  double x = 0.0;
  if (node->is_integer()) {
    x = static_cast<double>(*node->value<std::int64_t>());
  } else if (node->is_floating_point()) {
    x = *node->value<double>();
  } else {
    fail_type(key, *node, "a number");
  }
  const std::string detail = range_violation(x, range);
  if (!detail.empty())
    fail(key, detail);
  return x;
}

double SceneTable::number(std::string_view key, double default_value, const Range& range) {
  return optional_number(key, range).value_or(default_value);
}

double SceneTable::number(std::string_view key, Required, const Range& range) {
  const auto value = optional_number(key, range);
  if (!value)
    fail_missing(key, false);
  return *value;
}

std::optional<int> SceneTable::optional_integer(std::string_view key, const Range& range) {
  const toml::node* node = find(key);
  if (node == nullptr)
    return std::nullopt;
  if (!node->is_integer())
    fail_type(key, *node, "an integer");
  const std::int64_t x = *node->value<std::int64_t>();
  if (x < INT_MIN || x > INT_MAX)
    fail(key, "is too large (got " + std::to_string(x) + ")");
  const std::string detail = range_violation(static_cast<double>(x), range);
  if (!detail.empty())
    fail(key, detail);
  return static_cast<int>(x);
}

int SceneTable::integer(std::string_view key, int default_value, const Range& range) {
  return optional_integer(key, range).value_or(default_value);
}

int SceneTable::integer(std::string_view key, Required, const Range& range) {
  const auto value = optional_integer(key, range);
  if (!value)
    fail_missing(key, false);
  return *value;
}

// ---- booleans and strings ------------------------------------------------------------------

std::optional<bool> SceneTable::optional_boolean(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr)
    return std::nullopt;
  if (!node->is_boolean())
    fail_type(key, *node, "a boolean (true or false)");
  return *node->value<bool>();
}

bool SceneTable::boolean(std::string_view key, bool default_value) {
  return optional_boolean(key).value_or(default_value);
}

bool SceneTable::boolean(std::string_view key, Required) {
  const auto value = optional_boolean(key);
  if (!value)
    fail_missing(key, false);
  return *value;
}

std::optional<std::string> SceneTable::optional_string(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr)
    return std::nullopt;
  if (!node->is_string())
    fail_type(key, *node, "a string");
  return std::string(*node->value<std::string_view>());
}

std::string SceneTable::string(std::string_view key, const std::string& default_value) {
  return optional_string(key).value_or(default_value);
}

std::string SceneTable::string(std::string_view key, Required) {
  auto value = optional_string(key);
  if (!value)
    fail_missing(key, false);
  return *value;
}

std::optional<std::string> SceneTable::optional_choice(std::string_view key,
                                                       const std::vector<std::string>& choices) {
  auto value = optional_string(key);
  if (value) {
    try {
      check_choice(key, *value, choices);
    } catch (const InvalidSetting& e) {
      fail(key, e.detail());
    }
  }
  return value;
}

std::string SceneTable::choice(std::string_view key, const std::string& default_value,
                               const std::vector<std::string>& choices) {
  return optional_choice(key, choices).value_or(default_value);
}

std::string SceneTable::choice(std::string_view key, Required,
                               const std::vector<std::string>& choices) {
  auto value = optional_choice(key, choices);
  if (!value)
    fail_missing(key, false);
  return *value;
}

// ---- arrays --------------------------------------------------------------------------------

namespace {

// The array under key with its length checked, or nullptr when absent.
const toml::array* checked_array(SceneTable& table, const toml::node* node, std::string_view key,
                                 std::size_t size, std::string_view element_words) {
  if (node == nullptr)
    return nullptr;
  const toml::array* array = node->as_array();
  if (array == nullptr) {
    table.fail(key, "must be an array of " + std::string(element_words) + ", got " +
                        describe_value(*node));
  }
  if (size != 0 && array->size() != size) {
    table.fail(key, "must hold " + std::to_string(size) + " " + std::string(element_words) +
                        " (got " + std::to_string(array->size()) + ")");
  }
  return array;
}

}  // namespace

std::optional<std::vector<double>> SceneTable::optional_numbers(std::string_view key,
                                                                std::size_t size,
                                                                const Range& range) {
  const toml::array* array = checked_array(*this, find(key), key, size, "numbers");
  if (array == nullptr)
    return std::nullopt;
  std::vector<double> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& e = *array->get(i);
    const int line = static_cast<int>(e.source().begin.line);
    if (!e.is_number()) {
      throw SceneError(
          file_, line, 0,
          ordinal_element(i, key) + where() + " must be a number, got " + describe_value(e));
    }
    const double x =
        e.is_integer() ? static_cast<double>(*e.value<std::int64_t>()) : *e.value<double>();
    const std::string detail = range_violation(x, range);
    if (!detail.empty())
      throw SceneError(file_, line, 0, ordinal_element(i, key) + where() + " " + detail);
    out.push_back(x);
  }
  return out;
}

std::vector<double> SceneTable::numbers(std::string_view key, Required, std::size_t size,
                                        const Range& range) {
  auto value = optional_numbers(key, size, range);
  if (!value)
    fail_missing(key, false);
  return *value;
}

std::optional<std::vector<int>> SceneTable::optional_integers(std::string_view key,
                                                              std::size_t size,
                                                              const Range& range) {
  const toml::array* array = checked_array(*this, find(key), key, size, "integers");
  if (array == nullptr)
    return std::nullopt;
  std::vector<int> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& e = *array->get(i);
    const int line = static_cast<int>(e.source().begin.line);
    if (!e.is_integer()) {
      throw SceneError(
          file_, line, 0,
          ordinal_element(i, key) + where() + " must be an integer, got " + describe_value(e));
    }
    const std::int64_t x = *e.value<std::int64_t>();
    std::string detail = (x < INT_MIN || x > INT_MAX)
                             ? "is too large (got " + std::to_string(x) + ")"
                             : range_violation(static_cast<double>(x), range);
    if (!detail.empty())
      throw SceneError(file_, line, 0, ordinal_element(i, key) + where() + " " + detail);
    out.push_back(static_cast<int>(x));
  }
  return out;
}

std::optional<std::vector<std::string>> SceneTable::optional_strings(
    std::string_view key, const std::vector<std::string>& choices) {
  const toml::array* array = checked_array(*this, find(key), key, 0, "strings");
  if (array == nullptr)
    return std::nullopt;
  std::vector<std::string> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& e = *array->get(i);
    const int line = static_cast<int>(e.source().begin.line);
    const std::string prefix = ordinal_element(i, key) + where();
    if (!e.is_string()) {
      throw SceneError(file_, line, 0, prefix + " must be a string, got " + describe_value(e));
    }
    std::string value(*e.value<std::string_view>());
    if (!choices.empty()) {
      try {
        check_choice(key, value, choices);
      } catch (const InvalidSetting& error) {
        throw SceneError(file_, line, 0, prefix + " " + error.detail());
      }
    }
    if (std::find(out.begin(), out.end(), value) != out.end()) {
      throw SceneError(file_, line, 0, prefix + " repeats \"" + value + "\"");
    }
    out.push_back(std::move(value));
  }
  return out;
}

std::optional<std::array<double, 3>> SceneTable::optional_vector3(std::string_view key,
                                                                  const Range& range) {
  const auto values = optional_numbers(key, 3, range);
  if (!values)
    return std::nullopt;
  return std::array<double, 3>{(*values)[0], (*values)[1], (*values)[2]};
}

std::array<double, 3> SceneTable::vector3(std::string_view key, Required, const Range& range) {
  const auto value = optional_vector3(key, range);
  if (!value)
    fail_missing(key, false);
  return *value;
}

// ---- tables --------------------------------------------------------------------------------

std::optional<SceneTable> SceneTable::optional_table(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr)
    return std::nullopt;
  if (!node->is_table())
    fail_type(key, *node, "a table");
  return child(*node->as_table(), key);
}

SceneTable SceneTable::table(std::string_view key, Required) {
  auto value = optional_table(key);
  if (!value)
    fail_missing(key, true);
  return *value;
}

std::vector<SceneTable> SceneTable::tables(std::string_view key) {
  const toml::node* node = find(key);
  std::vector<SceneTable> out;
  if (node == nullptr)
    return out;
  const std::string path =
      dotted_path_ && !is_root_ ? *dotted_path_ + "." + std::string(key) : std::string(key);
  const toml::array* array = node->as_array();
  if (array == nullptr || !array->is_array_of_tables()) {
    fail(key, "must be an array of tables (write each entry as [[" + path + "]]), got " +
                  describe_value(*node));
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string number = " #" + std::to_string(i + 1);
    std::string display =
        dotted_path_ ? "[[" + path + "]]" + number : in_quotes(key) + number + " of " + display_;
    out.push_back(
        SceneTable(*array->get(i)->as_table(), file_, std::move(display), std::nullopt, false));
  }
  return out;
}

// ---- unknown keys --------------------------------------------------------------------------

void SceneTable::finish() const {
  std::tuple<std::uint32_t, std::uint32_t, std::string> first{UINT32_MAX, UINT32_MAX, ""};
  const toml::node* first_node = nullptr;
  for (auto&& [k, v] : *table_) {
    if (std::find(known_.begin(), known_.end(), k.str()) != known_.end())
      continue;
    std::tuple<std::uint32_t, std::uint32_t, std::string> here{
        k.source().begin.line, k.source().begin.column, std::string(k.str())};
    if (here < first) {
      first = here;
      first_node = &v;
    }
  }
  if (first_node == nullptr)
    return;
  const std::string& key = std::get<2>(first);
  const int line = static_cast<int>(std::get<0>(first));
  const std::string prefix = dotted_path_ && !is_root_ ? *dotted_path_ + "." : "";
  const toml::array* array = first_node->as_array();
  std::string what;
  std::string suggestion = closest_match(key, known_);
  if (first_node->is_table() && dotted_path_) {
    what = "unknown table [" + prefix + key + "]";
    if (!suggestion.empty())
      suggestion = "[" + prefix + suggestion + "]";
  } else if (array != nullptr && array->is_array_of_tables() && !array->empty() && dotted_path_) {
    what = "unknown table [[" + prefix + key + "]]";
    if (!suggestion.empty())
      suggestion = "[[" + prefix + suggestion + "]]";
  } else {
    what = "unknown key " + in_quotes(key) + where();
    if (!suggestion.empty())
      suggestion = in_quotes(suggestion);
  }
  std::string message = what;
  if (!suggestion.empty())
    message += "; did you mean " + suggestion + "?";
  message += !suggestion.empty() ? " " : "; ";
  message += known_.empty() ? "this table takes no keys" : "valid keys: " + join(known_);
  throw SceneError(file_, line, 0, message);
}

}  // namespace isomuscle::io
