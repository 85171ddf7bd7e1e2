#!/usr/bin/env bash
# Sedov (LULESH 2.0 setup, configs/solid_sedov_lulesh.yaml) throughput of solid_solver: N^3 hexahedra,
# strength off and on, 1 and 2 threads. Writes bench/solid/results/sedov_bench.csv, prints a markdown table
# (zone-cycles/s, steps, wall, energy error, bytes/element) and plots bench/solid/results/sedov_bench.png.
# Usage: bench/solid/run_sedov_bench.sh [BUILD_DIR] [SIZES...]     (default: build, sizes 30 45)
# Needs /usr/bin/python3 with matplotlib (Debian: python3-matplotlib).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
shift || true
sizes=${*:-30 45}
exe=$build/bin/solid_solver
[ -x "$exe" ] || { echo "no solid_solver in $build/bin (build it first)" >&2; exit 2; }
scene=$root/configs/solid_sedov_lulesh.yaml
results=$root/bench/solid/results
mkdir -p "$results"
csv=$results/sedov_bench.csv
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "n,strength,threads,steps,wall_s,zone_cycles_per_s,bytes_per_element,max_rss_mb,load1,rel_energy_error,host_cpu" > "$csv"
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//; s/,/ /g')
for n in $sizes; do
  for strength in off on; do
    extra=()
    if [ "$strength" = on ]; then
      # The same gas with a (tiny) shear modulus and yield stress: the full deviatoric path (Jaumann rate,
      # radial return, midpoint velocity gradient) runs in every element while the flow stays the same.
      extra=(--set "solid.blocks=[{name: gas, eos: {type: ideal_gas, gamma: 1.6666666666666667}, density: 1.0,
              strength: {shear_modulus: 1.0e-3, yield_stress: 1.0e-3}}]")
    fi
    for threads in 1 2; do
      load1=$(cut -d' ' -f1 /proc/loadavg)  # other users of the machine make the 2-thread runs noisy
      /usr/bin/time -f "%M" -o "$out/rss" "$exe" "$scene" --out "$out/run" --quiet --threads "$threads" \
        --set "solid.mesh.cells=[$n,$n,$n]" --set solid.output.snapshots=false "${extra[@]}"
      /usr/bin/python3 - "$out/run/summary.json" "$n" "$strength" "$threads" "$cpu" "$(tail -1 "$out/rss")" "$load1" \
        >> "$csv" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{j['steps']},{j['wall_time_s']:.3f},{j['zone_cycles_per_s']:.4e},"
      f"{j['bytes_per_element']:.0f},{int(sys.argv[6]) / 1024:.1f},{sys.argv[7]},"
      f"{j['energy']['relative_balance_error']:.2e},{sys.argv[5]}")
PY
    done
  done
done
/usr/bin/python3 "$root/bench/solid/plot_sedov_bench.py" "$csv" "$results/sedov_bench.png"
