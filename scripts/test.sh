#!/usr/bin/env bash
# The README's test command: installs dependencies, builds, runs every test (release), then the unit
# tests again under AddressSanitizer + UndefinedBehaviorSanitizer, then a short fuzzing run
# (ISOMUSCLE_FUZZ_SECONDS per target, default 20; 0 only replays the seeds and regressions).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" release
(cd "$root/build/release" && ctest --output-on-failure -j "$(nproc)")
if [ "${ISOMUSCLE_SKIP_ASAN:-0}" != "1" ]; then
  bash "$root/scripts/build.sh" asan
  # The sanitizer run covers the unit tests; whole-run (slow) tests carry the label "slow".
  # print_suppressions=0: LeakSanitizer would otherwise append its suppression statistics to the
  # stderr of every isomuscle process, which the CLI tests read as the program's messages.
  (cd "$root/build/asan" && LSAN_OPTIONS=suppressions="$root/scripts/lsan.supp":print_suppressions=0 ctest --output-on-failure -j "$(nproc)" -LE "slow|tet")
  # The tetrahedral tests call gmsh, whose allocations at exit have not been audited for
  # LeakSanitizer yet: they run with address and UB checks but without leak detection.
  (cd "$root/build/asan" && ASAN_OPTIONS=detect_leaks=0 ctest --output-on-failure -j "$(nproc)" -L tet -LE slow)
fi
# A short libFuzzer run of the IGES reader and the scene parser (clang, ASan, UBSan;
# validation/fuzz/README.md): fails when it finds a crash, a sanitizer report, a leak or a hang.
bash "$root/scripts/fuzz.sh" "${ISOMUSCLE_FUZZ_SECONDS:-20}"
