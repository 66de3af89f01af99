// Record-level IGES check (IGES 5.3 §2, fixed ASCII form); see iges_structure.hpp.
#include "geometry/iges_structure.hpp"

#include <array>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace isomuscle::geometry {

namespace {

constexpr std::string_view kSections = "SGDPT";

// Integer in columns [first, first + width) (1-based), blanks allowed around it.
std::optional<long> field(const std::string& record, std::size_t first, std::size_t width) {
  if (record.size() < first - 1 + width)
    return std::nullopt;
  const std::string text = record.substr(first - 1, width);
  const auto begin = text.find_first_not_of(' ');
  if (begin == std::string::npos)
    return std::nullopt;
  const auto end = text.find_last_not_of(' ');
  const std::string digits = text.substr(begin, end - begin + 1);
  if (digits.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  try {
    return std::stol(digits);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Delimiters from the first two global parameters ("1H," style Hollerith or empty = default).
std::pair<char, char> delimiters(const std::string& global) {
  char parameter = ',';
  char record = ';';
  std::size_t pos = 0;
  if (global.size() >= 3 && global.compare(0, 2, "1H") == 0) {
    parameter = global[2];
    pos = 3;
  }
  if (pos < global.size() && global[pos] == parameter)
    ++pos;
  if (global.size() >= pos + 3 && global.compare(pos, 2, "1H") == 0)
    record = global[pos + 2];
  return {parameter, record};
}

bool is_integer(const std::string& t) {
  std::size_t k = (!t.empty() && (t[0] == '+' || t[0] == '-')) ? 1 : 0;
  return k < t.size() && t.find_first_not_of("0123456789", k) == std::string::npos;
}

bool is_real(const std::string& t) {
  if (t.empty() || t.find_first_of("0123456789") == std::string::npos)
    return false;
  std::string c = t;
  for (char& ch : c) {
    if (ch == 'D' || ch == 'd')
      ch = 'E';
  }
  std::size_t used = 0;
  try {
    (void)std::stod(c, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == c.size();
}

// IGES 5.3 §4.23 parameter layout of entity 128: type, K1, K2, M1, M2, PROP1..5, then
// K1 + M1 + 2 and K2 + M2 + 2 knots, (K1 + 1)(K2 + 1) weights, 3 (K1 + 1)(K2 + 1) pole
// coordinates and U(0), U(1), V(0), V(1). OpenCASCADE 7.6 crashes on a malformed header instead
// of reporting it, so the syntax is checked here first.
void check_bspline_surface_parameters(const std::vector<std::string>& p, const std::string& where) {
  static const char* const header[] = {"entity type",
                                       "K1 (upper index in u)",
                                       "K2 (upper index in v)",
                                       "M1 (degree in u)",
                                       "M2 (degree in v)",
                                       "PROP1",
                                       "PROP2",
                                       "PROP3",
                                       "PROP4",
                                       "PROP5"};
  for (std::size_t k = 0; k < 10; ++k) {
    if (k >= p.size() || !is_integer(p[k])) {
      throw std::runtime_error(where + ": parameter " + std::to_string(k + 1) + ", " + header[k] +
                               ", is '" + (k < p.size() ? p[k] : std::string()) +
                               "', not an integer (damaged parameter data)");
    }
  }
  const long k1 = std::stol(p[1]), k2 = std::stol(p[2]), m1 = std::stol(p[3]), m2 = std::stol(p[4]);
  if (m1 < 1 || m2 < 1 || k1 < m1 || k2 < m2 || k1 > 100000 || k2 > 100000) {
    throw std::runtime_error(where + ": impossible sizes K1 = " + p[1] + ", K2 = " + p[2] +
                             ", M1 = " + p[3] + ", M2 = " + p[4] + " (need 1 <= M <= K <= 100000)");
  }
  const long reals = (k1 + m1 + 2) + (k2 + m2 + 2) + 4 * (k1 + 1) * (k2 + 1) + 4;
  if (static_cast<long>(p.size()) < 10 + reals) {
    throw std::runtime_error(where + ": " + std::to_string(p.size() - 10) +
                             " real parameters where the sizes need " + std::to_string(reals) +
                             " (damaged or truncated parameter data)");
  }
  for (long k = 10; k < 10 + reals; ++k) {
    if (!is_real(p[static_cast<std::size_t>(k)])) {
      throw std::runtime_error(where + ": parameter " + std::to_string(k + 1) + " is '" +
                               p[static_cast<std::size_t>(k)] +
                               "', not a real number (damaged parameter data)");
    }
  }
  // The weights must be positive (IGES 5.3 §4.23). Checked on the text: OpenCASCADE 7.6 reads a
  // zero or negative weight silently and then reports the surface as polynomial, so the bad
  // weight would vanish (all weights taken as 1) instead of being reported.
  const long first_weight = 10 + (k1 + m1 + 2) + (k2 + m2 + 2);
  for (long k = 0; k < (k1 + 1) * (k2 + 1); ++k) {
    const std::size_t at = static_cast<std::size_t>(first_weight + k);
    std::string text = p[at];
    for (char& ch : text) {
      if (ch == 'D' || ch == 'd')
        ch = 'E';
    }
    if (!(std::stod(text) > 0.0)) {
      throw std::runtime_error(where + ": parameter " + std::to_string(at + 1) + ", weight W(" +
                               std::to_string(k % (k1 + 1)) + ", " + std::to_string(k / (k1 + 1)) +
                               "), is " + p[at] + "; weights must be positive");
    }
  }
}

}  // namespace

void check_iges_structure(const std::filesystem::path& path) {
  const std::string name = "IGES file '" + path.string() + "'";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw std::runtime_error(name + " does not exist");
  if (std::filesystem::is_directory(path, ec)) {
    throw std::runtime_error(name + " is a directory, not a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(name + " cannot be opened for reading");

  std::vector<std::string> records;
  std::string line;
  bool blank_seen = false;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.find_first_not_of(" \t\x1a") == std::string::npos) {
      blank_seen = true;  // allowed only after the last record
      continue;
    }
    if (blank_seen) {
      throw std::runtime_error(name + ": line " + std::to_string(line_no - 1) +
                               " is blank inside the file (records must be contiguous)");
    }
    records.push_back(line);
  }
  if (records.empty())
    throw std::runtime_error(name + " is empty");

  std::array<long, 5> count{};
  int section = 0;
  for (std::size_t r = 0; r < records.size(); ++r) {
    const std::string& record = records[r];
    const std::string where = name + ": line " + std::to_string(r + 1);
    if (record.size() < 73) {
      throw std::runtime_error(where + " has " + std::to_string(record.size()) +
                               " columns; fixed-format IGES records have 80 with the section "
                               "letter in column 73 (not an IGES file, or a damaged one)");
    }
    const char letter = record[72];
    if (r == 0 && (letter == 'B' || letter == 'C' || letter == 'F')) {
      throw std::runtime_error(name +
                               " is in binary or compressed IGES form; save it as "
                               "fixed-format ASCII IGES");
    }
    const auto s = kSections.find(letter);
    if (s == std::string_view::npos) {
      throw std::runtime_error(where + ": column 73 holds '" + std::string(1, letter) +
                               "', not a section letter S, G, D, P or T");
    }
    if (static_cast<int>(s) < section) {
      throw std::runtime_error(where + ": section " + std::string(1, letter) + " after section " +
                               std::string(1, kSections[section]) +
                               " (the order must be S, G, D, P, T)");
    }
    section = static_cast<int>(s);
    ++count[s];
    const auto sequence = field(record, 74, 7);
    if (!sequence || *sequence != count[s]) {
      throw std::runtime_error(where + ": sequence number (columns 74-80) '" +
                               (record.size() > 73 ? record.substr(73, 7) : std::string()) +
                               "' should be " + std::to_string(count[s]) + " (damaged file)");
    }
  }
  if (count[4] != 1 || records.back()[72] != 'T') {
    throw std::runtime_error(name +
                             " is truncated: it does not end with the terminate (T) "
                             "record");
  }
  const std::string& terminate = records.back();
  for (int s = 0; s < 4; ++s) {
    const std::size_t first = static_cast<std::size_t>(8 * s + 1);
    const auto written = field(terminate, first + 1, 7);
    if (terminate[first - 1] != kSections[s] || !written || *written != count[s]) {
      throw std::runtime_error(name + " is truncated or damaged: the terminate record announces " +
                               terminate.substr(0, 32) + " but the file has S " +
                               std::to_string(count[0]) + ", G " + std::to_string(count[1]) +
                               ", D " + std::to_string(count[2]) + ", P " +
                               std::to_string(count[3]) + " records");
    }
  }
  if (count[1] == 0)
    throw std::runtime_error(name + " has no global (G) section");
  if (count[2] == 0)
    throw std::runtime_error(name + " holds no entities (empty D section)");
  if (count[2] % 2 != 0) {
    throw std::runtime_error(name + " is damaged: odd number of directory (D) records, " +
                             std::to_string(count[2]));
  }
  std::string global;
  for (long g = 0; g < count[1]; ++g) {
    global += records[static_cast<std::size_t>(count[0] + g)].substr(0, 72);
  }
  const std::pair<char, char> separators = delimiters(global);
  const std::size_t first_d = static_cast<std::size_t>(count[0] + count[1]);
  for (long e = 0; e < count[2] / 2; ++e) {
    const std::string& d1 = records[first_d + 2 * static_cast<std::size_t>(e)];
    const std::string& d2 = records[first_d + 2 * static_cast<std::size_t>(e) + 1];
    const std::string where = name + ": directory entry " + std::to_string(2 * e + 1);
    const auto type1 = field(d1, 1, 8);
    const auto type2 = field(d2, 1, 8);
    const auto pointer = field(d1, 9, 8);
    const auto lines = field(d2, 25, 8);
    if (!type1 || !type2 || *type1 != *type2) {
      throw std::runtime_error(where + ": entity type fields are missing or differ");
    }
    if (!pointer || !lines || *pointer < 1 || *lines < 1 || *pointer + *lines - 1 > count[3]) {
      throw std::runtime_error(
          where + " (type " + std::to_string(*type1) + "): parameter data lines " +
          (pointer ? std::to_string(*pointer) : std::string("?")) + " + " +
          (lines ? std::to_string(*lines) : std::string("?")) + " lie outside the P section of " +
          std::to_string(count[3]) + " lines (file truncated or damaged)");
    }
    // Every P record of the entity points back to its directory entry in columns 65-72.
    const std::size_t first_p = first_d + static_cast<std::size_t>(count[2]);
    for (long l = 0; l < *lines; ++l) {
      const std::string& p = records[first_p + static_cast<std::size_t>(*pointer - 1 + l)];
      const auto back = field(p, 65, 8);
      if (!back || *back != 2 * e + 1) {
        throw std::runtime_error(where + ": parameter record " + std::to_string(*pointer + l) +
                                 " does not point back to it in columns 65-72 (damaged file)");
      }
    }
    if (*type1 != 128)
      continue;
    // Parameters: columns 1-64 of its P records, up to the record delimiter.
    std::string text;
    for (long l = 0; l < *lines; ++l) {
      text += records[first_p + static_cast<std::size_t>(*pointer - 1 + l)].substr(0, 64);
    }
    const auto [parameter, record] = separators;
    const auto end = text.find(record);
    if (end == std::string::npos) {
      throw std::runtime_error(where + " (type 128): parameter data do not end with '" +
                               std::string(1, record) + "' (damaged)");
    }
    std::vector<std::string> tokens;
    std::string token;
    for (std::size_t k = 0; k <= end; ++k) {
      if (k == end || text[k] == parameter) {
        const auto b = token.find_first_not_of(' ');
        tokens.push_back(b == std::string::npos
                             ? std::string()
                             : token.substr(b, token.find_last_not_of(' ') - b + 1));
        token.clear();
      } else {
        token += text[k];
      }
    }
    check_bspline_surface_parameters(tokens, where + " (type 128)");
  }
}

}  // namespace isomuscle::geometry
