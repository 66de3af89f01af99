#!/usr/bin/env bash
# Bounded libFuzzer campaign on the IGES reader and the scene parser (validation/fuzz/README.md).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
#   SECONDS per target, default 60; 0 runs only the corpus once (a check of the build and seeds).
#   TARGET: iges_reader, scene_parser (default both).
# Builds build/fuzz with clang (libFuzzer, ASan, UBSan; only the fuzz targets), runs each fuzzer on
# a scratch copy of its seed corpus and regression inputs (the committed corpus never grows) and
# writes crash/timeout/leak/oom artefacts to $ISOMUSCLE_FUZZ_FINDINGS (default
# build/fuzz/findings). Exits 1 naming the artefacts when a fuzzer found something.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(iges_reader scene_parser)
case "$seconds" in
  '' | *[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number (got '$seconds')" >&2; exit 2 ;;
esac

bash "$root/scripts/install-deps.sh"
build="$root/build/fuzz"
findings=${ISOMUSCLE_FUZZ_FINDINGS:-$build/findings}
# -O1 without NDEBUG: fast enough to fuzz, and Eigen's and the project's assertions stay on (an
# assertion that fires is a finding).
if [ ! -f "$build/build.ninja" ]; then
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DISOMUSCLE_FUZZ=ON \
    -DISOMUSCLE_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
    -DCMAKE_C_FLAGS_DEBUG="-g -O1" >/dev/null
fi
executables=()
for t in "${targets[@]}"; do executables+=("${t}_fuzzer"); done
cmake --build "$build" -j "${ISOMUSCLE_JOBS:-$(nproc)}" --target "${executables[@]}"

scratch=$(mktemp -d "${TMPDIR:-/tmp}/isomuscle-fuzz.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
touch "$scratch/start"  # artefacts newer than this are this run's
# Leaks are findings, except OpenCASCADE's one-time static tables (scripts/lsan.supp).
# UBSan reports abort (the build uses -fno-sanitize-recover), with a stack trace.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:symbolize=1}
export LSAN_OPTIONS=suppressions="$root/scripts/lsan.supp":print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The corpus inputs are 2-15 kB; -max_len leaves room to grow without slowing every mutation.
declare -A max_len=([iges_reader]=24000 [scene_parser]=8192)
status=0
for t in "${targets[@]}"; do
  corpus="$scratch/$t"
  mkdir -p "$corpus" "$findings/$t"
  cp "$root/fuzz/corpus/$t"/* "$corpus"/
  if compgen -G "$root/fuzz/regressions/$t/*" >/dev/null; then
    cp "$root/fuzz/regressions/$t"/* "$corpus"/
  fi
  echo "fuzz.sh: $t for ${seconds} s (corpus $corpus, findings $findings/$t)"
  # -timeout: one input running 10 s is a hang (a normal one takes milliseconds);
  # -rss_limit_mb: 2 GB, far above what a parse of a 24 kB input needs.
  set +e
  if [ "$seconds" -eq 0 ]; then limit=(-runs=0); else limit=(-max_total_time="$seconds"); fi
  "$build/fuzz/${t}_fuzzer" "${limit[@]}" -max_len="${max_len[$t]}" -timeout=10 \
    -rss_limit_mb=2048 -dict="$root/fuzz/$t.dict" -artifact_prefix="$findings/$t/" \
    -print_final_stats=1 "$corpus" 2>"$scratch/$t.log"
  rc=$?
  set -e
  # The totals (runs, coverage, corpus) and any report; the whole log is kept on a finding.
  grep -E '^(#[0-9]+[[:space:]]+DONE|Done [0-9]+ runs|stat::|==[0-9]+==ERROR|SUMMARY|ALARM)' \
    "$scratch/$t.log" | head -40 || true
  if [ $rc -ne 0 ]; then
    cp "$scratch/$t.log" "$findings/$t/fuzzer.log"
    echo "fuzz.sh: $t exited with $rc; log $findings/$t/fuzzer.log" >&2
    status=1
  fi
done
artefacts=$(find "$findings" -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'leak-*' \
  -o -name 'oom-*' \) -newer "$scratch/start" 2>/dev/null | sort || true)
if [ -n "$artefacts" ]; then
  echo "fuzz.sh: findings (replay one with $build/fuzz/<target>_fuzzer FILE):" >&2
  echo "$artefacts" >&2
  status=1
fi
exit $status
