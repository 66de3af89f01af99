// Record-level IGES check (IGES 5.3 §2, fixed ASCII form); see iges_structure.hpp.
#include "geometry/iges_structure.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace isomuscle::geometry {

namespace {

constexpr std::string_view kSections = "SGDPT";

// Text from the file for a message, in quotes, with control and non-ASCII bytes as \xHH: a
// damaged file can hold anything, NUL included.
std::string shown(std::string_view text) {
  static const char digits[] = "0123456789ABCDEF";
  std::string out = "'";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7F) {
      out += ch;
    } else {
      out += "\\x";
      out += digits[c >> 4];
      out += digits[c & 0xF];
    }
  }
  return out + "'";
}

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

// A directory-entry field that may be negative (a negated pointer); blank is 0.
std::optional<long> signed_field(const std::string& record, std::size_t first) {
  if (record.size() < first - 1 + 8)
    return std::nullopt;
  const std::string text = record.substr(first - 1, 8);
  if (text.find_first_not_of(' ') == std::string::npos)
    return 0;
  const auto minus = text.find_first_not_of(' ');
  if (text[minus] != '-')
    return field(record, first, 8);
  const auto magnitude = field(std::string(minus + 1, ' ') + text.substr(minus + 1), 1, 8);
  return magnitude ? std::optional<long>(-*magnitude) : std::nullopt;
}

// The pointers of a directory entry (IGES 5.3 §2.2.4.4) and the entity types they may name.
// Negated fields hold a plain number when >= 0 and a pointer when < 0; the others 0 or a pointer.
struct DirectoryPointer {
  int record;  // 0: first D record of the entry, 1: second
  std::size_t column;
  bool negated;
  std::vector<int> types;  // empty: any
  const char* what;
};
const std::vector<DirectoryPointer>& directory_pointers() {
  static const std::vector<DirectoryPointer> pointers = {
      {0, 17, true, {}, "structure"},
      {0, 25, true, {304}, "line font pattern"},
      {0, 33, true, {406}, "level"},
      {0, 41, false, {410, 402}, "view"},
      {0, 49, false, {124}, "transformation matrix"},
      {0, 57, false, {402}, "label display associativity"},
      {1, 17, true, {314}, "colour"}};
  return pointers;
}

// OpenCASCADE 7.6 follows these pointers without checking their targets' types: a view pointer
// to a B-rep face made a reference cycle that it never frees (a leak found by
// fuzz/iges_reader_fuzzer). So each pointer must name an entity of a type its field allows.
void check_directory_pointers(const std::vector<std::string>& records, std::size_t first_d,
                              const std::vector<long>& types, const std::string& name) {
  const long entries = static_cast<long>(types.size());
  for (long e = 0; e < entries; ++e) {
    const std::string where = name + ": directory entry " + std::to_string(2 * e + 1) + " (type " +
                              std::to_string(types[static_cast<std::size_t>(e)]) + ")";
    for (const DirectoryPointer& p : directory_pointers()) {
      const std::string& record =
          records[first_d + 2 * static_cast<std::size_t>(e) + static_cast<std::size_t>(p.record)];
      const auto value = signed_field(record, p.column);
      if (!value) {
        throw std::runtime_error(where + ": " + p.what + " field " +
                                 shown(record.substr(p.column - 1, 8)) +
                                 " is not an integer (damaged)");
      }
      if (p.negated ? *value >= 0 : *value == 0)
        continue;
      const long target = p.negated ? -*value : *value;
      if (target < 1 || target % 2 == 0 || target > 2 * entries - 1) {
        throw std::runtime_error(where + ": " + p.what + " pointer " + std::to_string(*value) +
                                 " names no directory entry (damaged file)");
      }
      const long type = types[static_cast<std::size_t>(target / 2)];
      if (!p.types.empty() && std::find(p.types.begin(), p.types.end(), type) == p.types.end()) {
        std::string allowed;
        for (const int t : p.types)
          allowed += (allowed.empty() ? "" : " or ") + std::to_string(t);
        throw std::runtime_error(where + ": " + p.what + " pointer names directory entry " +
                                 std::to_string(target) + " of type " + std::to_string(type) +
                                 ", which is not " + allowed + " (damaged file)");
      }
    }
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

std::string with_e_exponent(std::string text) {
  for (char& ch : text) {
    if (ch == 'D' || ch == 'd')
      ch = 'E';
  }
  return text;
}

// Fields [0, names.size()) must be integers that std::stol can read; names[k] names field k in
// the message.
void require_integers(const std::vector<std::string>& p, const std::vector<const char*>& names,
                      const std::string& where) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    bool fits = false;
    if (k < p.size() && is_integer(p[k])) {
      try {
        (void)std::stol(p[k]);
        fits = true;
      } catch (const std::out_of_range&) {
        // beyond long: reported below like any other non-integer
      }
    }
    if (!fits) {
      throw std::runtime_error(where + ": parameter " + std::to_string(k + 1) + ", " + names[k] +
                               ", is " + shown(k < p.size() ? p[k] : std::string()) +
                               ", not an integer (damaged parameter data)");
    }
  }
}

// Fields [first, first + count) must be reals.
void require_reals(const std::vector<std::string>& p, long first, long count,
                   const std::string& where) {
  if (static_cast<long>(p.size()) < first + count) {
    throw std::runtime_error(where + ": " + std::to_string(static_cast<long>(p.size()) - first) +
                             " real parameters where the sizes need " + std::to_string(count) +
                             " (damaged or truncated parameter data)");
  }
  for (long k = first; k < first + count; ++k) {
    if (!is_real(p[static_cast<std::size_t>(k)])) {
      throw std::runtime_error(where + ": parameter " + std::to_string(k + 1) + " is " +
                               shown(p[static_cast<std::size_t>(k)]) +
                               ", not a real number (damaged parameter data)");
    }
  }
}

// Upper index K and degree M of a B-spline direction: 1 <= M <= K (at least M + 1 poles); the
// bound keeps the sizes below far from overflow and from an allocation OpenCASCADE cannot make.
bool plausible_sizes(long k, long m) {
  return m >= 1 && k >= m && k <= 100000;
}

// IGES 5.3 §4.23 parameter layout of entity 128: type, K1, K2, M1, M2, PROP1..5, then
// K1 + M1 + 2 and K2 + M2 + 2 knots, (K1 + 1)(K2 + 1) weights, 3 (K1 + 1)(K2 + 1) pole
// coordinates and U(0), U(1), V(0), V(1). OpenCASCADE 7.6 crashes on a malformed header instead
// of reporting it, so the syntax is checked here first.
void check_bspline_surface_parameters(const std::vector<std::string>& p, const std::string& where) {
  require_integers(
      p,
      {"entity type", "K1 (upper index in u)", "K2 (upper index in v)", "M1 (degree in u)",
       "M2 (degree in v)", "PROP1", "PROP2", "PROP3", "PROP4", "PROP5"},
      where);
  const long k1 = std::stol(p[1]), k2 = std::stol(p[2]), m1 = std::stol(p[3]), m2 = std::stol(p[4]);
  if (!plausible_sizes(k1, m1) || !plausible_sizes(k2, m2)) {
    throw std::runtime_error(where + ": impossible sizes K1 = " + p[1] + ", K2 = " + p[2] +
                             ", M1 = " + p[3] + ", M2 = " + p[4] + " (need 1 <= M <= K <= 100000)");
  }
  require_reals(p, 10, (k1 + m1 + 2) + (k2 + m2 + 2) + 4 * (k1 + 1) * (k2 + 1) + 4, where);
  // The weights must be positive (IGES 5.3 §4.23). Checked on the text: OpenCASCADE 7.6 reads a
  // zero or negative weight silently and then reports the surface as polynomial, so the bad
  // weight would vanish (all weights taken as 1) instead of being reported.
  const long first_weight = 10 + (k1 + m1 + 2) + (k2 + m2 + 2);
  for (long k = 0; k < (k1 + 1) * (k2 + 1); ++k) {
    const std::size_t at = static_cast<std::size_t>(first_weight + k);
    if (!(std::stod(with_e_exponent(p[at])) > 0.0)) {
      throw std::runtime_error(where + ": parameter " + std::to_string(at + 1) + ", weight W(" +
                               std::to_string(k % (k1 + 1)) + ", " + std::to_string(k / (k1 + 1)) +
                               "), is " + p[at] + "; weights must be positive");
    }
  }
}

// IGES 5.3 §4.22 parameter layout of entity 126 (B-spline curve, the trimming curves of CAD
// files): type, K, M, PROP1..4, then K + M + 2 knots, K + 1 weights, 3 (K + 1) pole coordinates,
// V(0), V(1) (the unit normal after them is optional). OpenCASCADE 7.6 dereferences a null array
// when a list is short or a size impossible (segmentation fault, found by fuzz/: regression
// fuzz/regressions/iges_reader/occt-126-degree-beyond-poles.igs).
void check_bspline_curve_parameters(const std::vector<std::string>& p, const std::string& where) {
  require_integers(
      p, {"entity type", "K (upper index)", "M (degree)", "PROP1", "PROP2", "PROP3", "PROP4"},
      where);
  const long k = std::stol(p[1]), m = std::stol(p[2]);
  if (!plausible_sizes(k, m)) {
    throw std::runtime_error(where + ": impossible sizes K = " + p[1] + ", M = " + p[2] +
                             " (need 1 <= M <= K <= 100000)");
  }
  require_reals(p, 7, (k + m + 2) + 4 * (k + 1) + 2, where);
}

// Parameter layouts of the entities CAD files put around their B-spline surfaces (IGES 5.3 §4:
// trimmed and bounded surfaces, curves on surfaces, composite curves, transformations and the
// B-rep entities), after the entity type: i an integer, r a real (both may be left empty, the
// default), p a pointer to an entity of the file, q such a pointer or 0, c an integer count and
// <...> as many repetitions of a group as the last count not yet used says. OpenCASCADE 7.6
// dereferences the null entity it makes of a pointer that names no entity (a segmentation fault in
// its 508 loop reader, found by fuzz/iges_reader_fuzzer) and of a list cut short, so these layouts
// are checked first. Parameters after the layout (back pointers to associativities and properties)
// are not.
const std::map<long, std::string_view>& entity_layouts() {
  static const std::map<long, std::string_view> layouts = {
      {102, "c<p>"},          // composite curve: its curves
      {124, "rrrrrrrrrrrr"},  // transformation matrix R | T
      {141, "iipc<pic<p>>"},  // boundary: type, preference, surface, curves
      {142, "ipqqi"},         // curve on surface
      {143, "ipc<p>"},        // bounded surface: type, surface, boundaries
      {144, "picq<p>"},       // trimmed surface: surface, outer flag, N2, outer, N2 inner
      {186, "pic<pi>"},       // manifold solid B-rep object: shell, voids
      {502, "c<rrr>"},        // vertex list
      {504, "c<ppipi>"},      // edge list: curve, start and end vertex
      {508, "c<ipiic<ip>>"},  // loop: edges and their parameter-space curves
      {510, "pci<p>"},        // face: surface, N, outer-loop flag, N loops
      {514, "c<pi>"}};        // shell: faces
  return layouts;
}

class LayoutCheck {
 public:
  LayoutCheck(const std::vector<std::string>& fields, long directory_records,
              const std::string& where)
      : fields_(fields), directory_records_(directory_records), where_(where) {}

  void read(std::string_view layout) {
    for (std::size_t k = 0; k < layout.size(); ++k) {
      if (layout[k] == 'c') {
        const long count = integer(next_field(), "a count");
        // Each repetition takes at least one field: a larger count is damage, not a long list.
        if (count < 0 || count > static_cast<long>(fields_.size())) {
          fail("count " + std::to_string(count) + " is impossible for " +
               std::to_string(fields_.size()) + " parameters");
        }
        counts_.push_back(count);
      } else if (layout[k] == '<') {
        const std::size_t end = group_end(layout, k);
        const long count = counts_.back();
        counts_.pop_back();
        for (long c = 0; c < count; ++c)
          read(layout.substr(k + 1, end - k - 1));
        k = end;
      } else {
        next(layout[k]);
      }
    }
  }

 private:
  static std::size_t group_end(std::string_view layout, std::size_t open) {
    int depth = 0;
    for (std::size_t k = open; k < layout.size(); ++k) {
      depth += layout[k] == '<' ? 1 : layout[k] == '>' ? -1 : 0;
      if (depth == 0)
        return k;
    }
    throw std::logic_error("entity layout without closing '>'");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(where_ + ": parameter " + std::to_string(at_) + ": " + what +
                             " (damaged or truncated parameter data)");
  }

  const std::string& next_field() {
    if (at_ >= fields_.size())
      fail("missing; the list ends after " + std::to_string(fields_.size()) + " parameters");
    return fields_[at_++];
  }

  long integer(const std::string& text, const char* what) const {
    if (!is_integer(text))
      fail(shown(text) + " is not " + what);
    try {
      return std::stol(text);
    } catch (const std::exception&) {
      fail(shown(text) + " is out of range");
    }
  }

  void next(char code) {
    const std::string& text = next_field();
    if (code == 'r') {
      if (!text.empty() && !is_real(text))
        fail(shown(text) + " is not a real number");
    } else if (code == 'i') {
      if (!text.empty())
        (void)integer(text, "an integer");
    } else if (!(code == 'q' && (text.empty() || text == "0"))) {
      if (text.empty())
        fail("empty where a pointer to an entity must stand");
      const long target = integer(text, "a pointer to an entity");
      if (target < 1 || target % 2 == 0 || target > directory_records_ - 1)
        fail("pointer " + shown(text) + " names no directory entry");
    }
  }

  const std::vector<std::string>& fields_;
  long directory_records_;
  const std::string& where_;
  std::size_t at_ = 1;  // field 0 is the entity type
  std::vector<long> counts_;
};

// Parameters of one entity: columns 1-64 of its P records up to the record delimiter, split at
// the parameter delimiter, blanks trimmed.
std::vector<std::string> parameter_fields(const std::string& text, char parameter, char record,
                                          const std::string& where) {
  const auto end = text.find(record);
  if (end == std::string::npos) {
    throw std::runtime_error(where + ": parameter data do not end with '" + std::string(1, record) +
                             "' (damaged)");
  }
  std::vector<std::string> fields;
  std::string field;
  for (std::size_t k = 0; k <= end; ++k) {
    if (k == end || text[k] == parameter) {
      const auto b = field.find_first_not_of(' ');
      fields.push_back(b == std::string::npos
                           ? std::string()
                           : field.substr(b, field.find_last_not_of(' ') - b + 1));
      field.clear();
    } else {
      field += text[k];
    }
  }
  return fields;
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
      throw std::runtime_error(where + ": column 73 holds " + shown(std::string(1, letter)) +
                               ", not a section letter S, G, D, P or T");
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
      throw std::runtime_error(where + ": sequence number (columns 74-80) " +
                               shown(record.size() > 73 ? record.substr(73, 7) : std::string()) +
                               " should be " + std::to_string(count[s]) + " (damaged file)");
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
                               shown(terminate.substr(0, 32)) + " but the file has S " +
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
  std::vector<long> types;
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
    types.push_back(*type1);
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
    // The entity types whose parameter lists OpenCASCADE reads without surviving a damaged one.
    const auto layout = entity_layouts().find(*type1);
    if (*type1 != 126 && *type1 != 128 && layout == entity_layouts().end())
      continue;
    std::string text;
    for (long l = 0; l < *lines; ++l) {
      text += records[first_p + static_cast<std::size_t>(*pointer - 1 + l)].substr(0, 64);
    }
    const std::string entity = where + " (type " + std::to_string(*type1) + ")";
    const std::vector<std::string> fields =
        parameter_fields(text, separators.first, separators.second, entity);
    if (*type1 == 128)
      check_bspline_surface_parameters(fields, entity);
    else if (*type1 == 126)
      check_bspline_curve_parameters(fields, entity);
    else
      LayoutCheck(fields, count[2], entity).read(layout->second);
  }
  check_directory_pointers(records, first_d, types, name);
}

}  // namespace isomuscle::geometry
