#pragma once
// A strict, typed reader over one TOML table of a scene file. Every value is read through it, so
// every mistake a user can make in a scene — a misspelt key, a wrong type, a value out of range, a
// choice that does not exist, a missing key, a TOML syntax error — becomes a SceneError whose
// message names the file, the line, what is wrong and what would be right:
//   scene.toml:12: unknown key 'materal' in [muscle]; did you mean 'material'? valid keys: ...
//   scene.toml:7: 'dt' in [time] must be > 0 (got -0.001)
//   scene.toml:3: 'centreline' in [geometry] must be one of u, v (got "x")
// Usage: read every key the table may hold, then call finish(), which rejects the keys nobody
// read (with a "did you mean" for near misses).
#include <toml++/toml.h>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/setting_check.hpp"

namespace isomuscle::io {

// An error in a scene file. what() reads "file:line:column: message" (column and line are left
// out when unknown, i.e. 0).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, int line, int column, const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  int column_;
  std::string message_;
};

// Tag for "this key must be present".
struct Required {};
inline constexpr Required required{};

// Parses TOML; syntax errors become SceneError at the parser's line and column. file_name is the
// name used in messages.
toml::table parse_toml_text(std::string_view text, const std::string& file_name);
// Reads and parses a file; a missing or unreadable file is a SceneError naming the path.
toml::table parse_toml_file(const std::filesystem::path& path);

// The words used in messages for a TOML value: "a string (\"x\")", "an integer (3)", "a table".
std::string describe_value(const toml::node& node);

class SceneTable {
 public:
  // The root table of a parsed file.
  SceneTable(const toml::table& root, std::string file);

  const std::string& file() const { return file_; }
  // "[time]", "[geometry.refine]", "[[boundary]] #2", "'face' of [[boundary]] #2", "top level".
  const std::string& name() const { return display_; }
  // Line of the table's header (of its first key for implicit tables); 0 for the root.
  int line() const;
  // Line of key when present, else the table's line.
  int line_of(std::string_view key) const;
  // Whether the key is present; marks it as known.
  bool contains(std::string_view key);
  // Type of the value under key (toml::node_type::none when absent); marks it as known.
  toml::node_type type_of(std::string_view key);
  // Every key present, in the order of the file.
  std::vector<std::string> keys() const;

  // Numbers: TOML integers and floats both read as double. Non-finite values (nan, inf) are
  // rejected, as are values outside range.
  std::optional<double> optional_number(std::string_view key, const Range& range = {});
  double number(std::string_view key, double default_value, const Range& range = {});
  double number(std::string_view key, Required, const Range& range = {});

  // Integers: TOML integers only ("2.0" is rejected), checked against range and the int limits.
  std::optional<int> optional_integer(std::string_view key, const Range& range = {});
  int integer(std::string_view key, int default_value, const Range& range = {});
  int integer(std::string_view key, Required, const Range& range = {});

  std::optional<bool> optional_boolean(std::string_view key);
  bool boolean(std::string_view key, bool default_value);
  bool boolean(std::string_view key, Required);

  std::optional<std::string> optional_string(std::string_view key);
  std::string string(std::string_view key, const std::string& default_value);
  std::string string(std::string_view key, Required);

  // A string that must be one of choices; near misses get a "did you mean".
  std::optional<std::string> optional_choice(std::string_view key,
                                             const std::vector<std::string>& choices);
  std::string choice(std::string_view key, const std::string& default_value,
                     const std::vector<std::string>& choices);
  std::string choice(std::string_view key, Required, const std::vector<std::string>& choices);

  // Arrays. size 0 accepts any length (including empty); otherwise the length must equal size.
  std::optional<std::vector<double>> optional_numbers(std::string_view key, std::size_t size = 0,
                                                      const Range& range = {});
  std::vector<double> numbers(std::string_view key, Required, std::size_t size = 0,
                              const Range& range = {});
  std::optional<std::vector<int>> optional_integers(std::string_view key, std::size_t size = 0,
                                                    const Range& range = {});
  // Strings each one of choices (choices empty: any string); duplicates are rejected.
  std::optional<std::vector<std::string>> optional_strings(
      std::string_view key, const std::vector<std::string>& choices = {});
  std::optional<std::array<double, 3>> optional_vector3(std::string_view key,
                                                        const Range& range = {});
  std::array<double, 3> vector3(std::string_view key, Required, const Range& range = {});

  // Sub-tables (a [section], an inline { ... } table). The child must be finished by the caller.
  std::optional<SceneTable> optional_table(std::string_view key);
  SceneTable table(std::string_view key, Required);
  // An array of tables ([[boundary]] entries); empty when absent.
  std::vector<SceneTable> tables(std::string_view key);

  // Marks keys as valid without reading them (e.g. read through another SceneTable).
  void allow(std::string_view key);
  // Marks key as valid for this table but wrong here: a SceneError with reason when present.
  void forbid(std::string_view key, const std::string& reason);

  // Errors at a key's line: "'key' in [table] detail".
  [[noreturn]] void fail(std::string_view key, const std::string& detail) const;
  // Error at the table's header line: "[table] message".
  [[noreturn]] void fail_table(const std::string& message) const;
  // An InvalidSetting from a validate() method at the line of its (possibly dotted) key.
  [[noreturn]] void fail(const InvalidSetting& error) const;

  // Rejects every key that was neither read nor allowed: the first such key in file order.
  void finish() const;

 private:
  SceneTable(const toml::table& table, std::string file, std::string display,
             std::optional<std::string> dotted_path, bool is_root);
  SceneTable child(const toml::table& table, std::string_view key) const;
  const toml::node* find(std::string_view key);
  const toml::node* find_const(std::string_view key) const;
  [[noreturn]] void fail_type(std::string_view key, const toml::node& node,
                              std::string_view expected) const;
  [[noreturn]] void fail_missing(std::string_view key, bool is_table) const;
  std::string where() const;

  const toml::table* table_;
  std::string file_;
  std::string display_;
  std::optional<std::string> dotted_path_;  // "geometry.refine"; empty inside array elements
  bool is_root_;
  std::vector<std::string> known_;  // keys read or allowed, in the order first asked for
};

}  // namespace isomuscle::io
