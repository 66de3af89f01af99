#!/usr/bin/env bash
# Configures and builds one build tree. Usage: scripts/build.sh [release|asan] [targets...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
kind=${1:-release}; shift || true
bash "$root/scripts/install-deps.sh"
case "$kind" in
  release) flags=(-DCMAKE_BUILD_TYPE=Release) ;;
  asan) flags=(-DCMAKE_BUILD_TYPE=Debug -DISOMUSCLE_SANITIZE=ON -DISOMUSCLE_BUILD_BENCH=OFF) ;;
  *) echo "build.sh: unknown build kind '$kind' (valid: release, asan)" >&2; exit 2 ;;
esac
build="$root/build/$kind"
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja "${flags[@]}" >/dev/null
fi
jobs=${ISOMUSCLE_JOBS:-$(nproc)}
if [ $# -gt 0 ]; then
  cmake --build "$build" -j "$jobs" --target "$@"
else
  cmake --build "$build" -j "$jobs"
fi
