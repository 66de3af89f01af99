#include "solver/blas_threads.hpp"

#include <dlfcn.h>

namespace isomuscle::solver {

namespace {

// OpenBLAS's own entry points, looked up in the loaded libraries (CHOLMOD links libblas.so.3,
// which Debian's alternatives may point at OpenBLAS, BLIS or the reference BLAS): no link-time
// dependency on one BLAS.
using SetThreads = void (*)(int);
using GetThreads = int (*)();

SetThreads find_set() {
  return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
}
GetThreads find_get() {
  return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
}

}  // namespace

bool set_blas_threads(int threads) {
  const SetThreads set = find_set();
  if (set == nullptr || threads < 1)
    return false;
  set(threads);
  return true;
}

int blas_threads() {
  const GetThreads get = find_get();
  return get == nullptr ? 0 : get();
}

}  // namespace isomuscle::solver
