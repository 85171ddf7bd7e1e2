#!/usr/bin/env bash
# ParaView (Debian's paraview + python3-paraview, headless under xvfb-run) opens a coupled run's fluid, solid and
# interface series with their arrays and time steps and renders the fluid, then a fluid run made by 2 MPI ranks as
# one grid. Skipped (exit 77) where ParaView is absent. Usage: paraview_opens_a_run.sh BUILD_DIR
set -euo pipefail
build="$1"
here="$(cd "$(dirname "$0")" && pwd)"
source "$here/headless.sh"  # the skip where ParaView is absent, $work and pvbatch_headless

"$build/bin/cosim" run "$here/../../configs/piston_2d.yaml" --out "$work/run" --quiet --set coupling.time.end=0.03
rc=0
pvbatch_headless "$here/open_run.py" "$work/run" "$work/fluid.png" || rc=$?
grep -E "cells|picture|FAILED" "$work/pvbatch.log" || tail -20 "$work/pvbatch.log"
[ "$rc" = 0 ] || exit "$rc"

mpirun --allow-run-as-root --oversubscribe -np 2 "$build/bin/fluid_solver" "$here/../../configs/particle_blast_2d.yaml" \
  --out "$work/ranks" --quiet --threads 1 --set 'fluid.mesh.cells=[40,30]' --set fluid.time.end=2.0e-4 \
  --set fluid.output.interval=1.0e-4 > "$work/ranks.log" 2>&1 || { cat "$work/ranks.log"; exit 1; }
pvbatch_headless "$here/open_ranks_run.py" "$work/ranks" 40 30 || rc=$?
grep -E "cells|air_pressure|FAILED" "$work/pvbatch.log" || tail -20 "$work/pvbatch.log"
exit "$rc"
