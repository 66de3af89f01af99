#pragma once
// Numbers of the Bloch checks (element_layer_check.hpp, element_column_check.hpp) as the log
// writes them.
#include <string>

namespace isomuscle::io {

// Spans per wavelength along a surface direction, 2 pi / |theta| ("inf" for a constant phase).
std::string spans_per_wave(double theta);

// Three significant digits with the sign always written ("+1.78e+09"): the sign is the verdict.
std::string signed_number(double x);

}  // namespace isomuscle::io
