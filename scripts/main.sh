#!/usr/bin/env bash
# The README's main job: builds isomuscle and runs the default example.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" release isomuscle
exe="$root/build/release/app/isomuscle"
"$exe" geometry solid "$root/examples/geometry/barrel.igs" --centreline v \
  --vtk "$root/out/barrel-solid.vtk"
echo "main: solid written to out/barrel-solid.vtk (open in ParaView)"
