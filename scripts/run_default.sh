#!/usr/bin/env bash
# Quick start 1: install what is missing, build, run the default scene through the launcher and plot it.
# Default: the coupled piston (paper 9.3: fluid_solver + solid_solver + coupler), with the conforming
# all-Lagrangian run of the same piston as the reference curve.
# Usage: scripts/run_default.sh [SCENE.yaml] [--set key=value ...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
SCENE=configs/piston_2d.yaml
if [ $# -gt 0 ] && [[ "$1" != --* ]]; then SCENE=$1; shift; fi
NAME=$(basename "$SCENE" .yaml)
OUT=runs/$NAME
./build/bin/cosim run "$SCENE" --out "$OUT" "$@"
REFERENCE=()
if [[ "$NAME" == piston* ]]; then  # the same piston on a conforming Lagrangian mesh (solid_solver alone)
  ./build/bin/solid_solver configs/solid_piston_1d.yaml --out runs/solid_piston_1d --quiet \
    --set solid.output.interval=0.0005  # fine enough that the reference curve is not interpolation-limited
  REFERENCE=(--reference runs/solid_piston_1d)
fi
/usr/bin/python3 python/plot_run.py "$OUT" "${REFERENCE[@]}"
echo "results: $OUT (ParaView: $OUT/fluid/fluid.xmf, $OUT/solid/solid.xmf; pictures: $OUT/plots/*.png)"
