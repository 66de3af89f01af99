#pragma once
// A solver setting with a bad value, thrown by the validate() methods of the settings structs.
// key names the setting inside its struct ("min_dt"); detail is the rest of the sentence
// ("must be > 0 and <= initial_dt (got 0)"). what() reads "'min_dt' must be ...", the same text as
// io's checks, so the scene reader can attach the key's file line.
#include <stdexcept>
#include <string>

namespace isomuscle::solver {

class SettingError : public std::invalid_argument {
 public:
  SettingError(std::string key, std::string detail)
      : std::invalid_argument("'" + key + "' " + detail),
        key_(std::move(key)),
        detail_(std::move(detail)) {}
  const std::string& key() const { return key_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string key_;
  std::string detail_;
};

// Shortest round-trip text of a number for messages ("0.001", "1e-08").
std::string format_number(double x);

}  // namespace isomuscle::solver
