#include "solver/setting_error.hpp"

#include <array>
#include <charconv>

namespace isomuscle::solver {

std::string format_number(double x) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return {buffer.data(), result.ptr};
}

}  // namespace isomuscle::solver
