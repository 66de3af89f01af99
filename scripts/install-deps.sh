#!/usr/bin/env bash
# Installs every build and run dependency of isomuscle from Debian 12 packages.
# Idempotent: when everything is present it only checks (dpkg-query) and returns in well under a second.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev                     # dense per-point tensors, sparse matrices
  libspectra-dev                    # Lanczos eigenpairs of the tangent (the unstable mode)
  libsuitesparse-dev libopenblas0-pthread  # CHOLMOD (sparse Cholesky), UMFPACK fallback; fast BLAS for them
  libocct-data-exchange-dev libocct-modeling-algorithms-dev
  libocct-foundation-dev libocct-modeling-data-dev libtbb-dev  # OpenCASCADE: IGES read/write
  libhdf5-dev                       # field output read by ParaView through XDMF
  libgmsh-dev gmsh                  # tetrahedral meshing of the same shapes
  libtomlplusplus-dev               # scene files
  libcli11-dev                      # command line
  nlohmann-json3-dev                # summary.json, --json output
  libgtest-dev libgmock-dev         # unit tests
  occt-misc                         # real IGES files written by other tools (hammer.iges) for reader tests
  libbenchmark-dev                  # bench/
  clang-14 libclang-rt-14-dev       # scripts/fuzz.sh: clang with libFuzzer and the sanitizer runtimes
  libomp-14-dev llvm-14             # clang's OpenMP (the project requires OpenMP); llvm-symbolizer
                                    # for readable fuzzer stack traces
  python3 python3-numpy python3-matplotlib python3-h5py  # validation figures (h5py reads fields.h5)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
