#include "io/bloch_wave_text.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace isomuscle::io {

std::string spans_per_wave(double theta) {
  if (std::abs(theta) < 1e-3)
    return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", 2.0 * std::numbers::pi / std::abs(theta));
  return text;
}

std::string signed_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.3g", x);
  return text;
}

}  // namespace isomuscle::io
