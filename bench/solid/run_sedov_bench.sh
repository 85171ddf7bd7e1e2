#!/usr/bin/env bash
# Sedov (LULESH 2.0 setup) throughput of solid_solver: zone-cycles per second for N^3 meshes, strength off
# and on, 1 and 2 threads. Usage: bench/solid/run_sedov_bench.sh [BUILD_DIR] [SIZES...]
# Prints one line per run: N, strength, threads, steps, wall [s], zone-cycles/s, bytes/element, energy error.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
shift || true
sizes=${*:-30 45}
exe=$build/bin/solid_solver
scene=$root/configs/solid_sedov_lulesh.yaml
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf "%4s %8s %7s %6s %8s %12s %10s %10s\n" N strength threads steps wall_s zone_cyc/s B/elem rel_err
for n in $sizes; do
  for strength in off on; do
    extra=()
    if [ "$strength" = on ]; then
      # Same gas with a (tiny) shear modulus and yield stress: exercises the full deviatoric path.
      extra=(--set "solid.blocks=[{name: gas, eos: {type: ideal_gas, gamma: 1.6666666666666667}, density: 1.0,
              strength: {shear_modulus: 1.0e-3, yield_stress: 1.0e-3}}]")
    fi
    for threads in 1 2; do
      "$exe" "$scene" --out "$out/run" --quiet --threads "$threads" --set "solid.mesh.cells=[$n,$n,$n]" \
        --set solid.output.snapshots=false "${extra[@]}"
      python3 - "$out/run/summary.json" "$n" "$strength" "$threads" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]:>4} {sys.argv[3]:>8} {sys.argv[4]:>7} {j['steps']:>6} {j['wall_time_s']:>8.2f} "
      f"{j['zone_cycles_per_s']:>12.3e} {j['bytes_per_element']:>10.0f} {j['energy']['relative_balance_error']:>10.1e}")
PY
    done
  done
done
