#!/usr/bin/env bash
# Quick start 1: install what is missing, build, run the default scene and plot it.
# Usage: scripts/run_default.sh [SCENE.yaml] [--set key=value ...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
SCENE=configs/particle_blast_2d.yaml
if [ $# -gt 0 ] && [[ "$1" != --* ]]; then SCENE=$1; shift; fi
NAME=$(basename "$SCENE" .yaml)
OUT=runs/$NAME
./build/bin/fluid_solver "$SCENE" --out "$OUT" "$@"
/usr/bin/python3 scripts/plot_fluid.py "$OUT"
echo "results: $OUT (open $OUT/fluid.xmf in ParaView; pictures: $OUT/*.png)"
