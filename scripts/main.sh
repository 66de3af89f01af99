#!/usr/bin/env bash
# The README's main job: builds isomuscle and runs the default example, the barrel contraction
# (examples/barrel/contract.toml: IGES in, shrink solid, IGA with the chapter-5 muscle), then draws
# its probe histories.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" release isomuscle
exe="$root/build/release/app/isomuscle"
out="$root/out/barrel-contract"
"$exe" run "$root/examples/barrel/contract.toml" --out "$out"
python3 "$root/examples/barrel/plot_probes.py" "$out/probes.csv" "$out/probes.svg"
echo "main: results in $out (summary.json, fields.xdmf for ParaView, probes.csv, probes.svg)"
