#include "io/process_memory.hpp"

#include <sys/resource.h>

#include <limits>

namespace isomuscle::io {

double peak_resident_mebibytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0)
    return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: ru_maxrss in KiB
}

}  // namespace isomuscle::io
