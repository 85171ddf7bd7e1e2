#!/usr/bin/env bash
# Every run writes a ParaView state, RUN/view.py: loaded by pvbatch under Xvfb (software GL) for short coupled runs,
# 2D and 3D pistons and a 2D panel that the blast deforms (its von Mises stress varies), it shows the fluid's
# pressure, the solid's von Mises stress and the interface at the last time with the colour ranges fitted to it, in
# a picture that holds the fields' colours (render_view.py). Skipped (exit 77) where ParaView is absent.
# Usage: paraview_shows_a_run.sh BUILD_DIR
set -euo pipefail
build="$1"
here="$(cd "$(dirname "$0")" && pwd)"
source "$here/headless.sh"  # the skip where ParaView is absent, $work and pvbatch_headless
configs="$here/../../configs"

rc=0
while read -r scene end; do
  "$build/bin/cosim" run "$configs/$scene.yaml" --out "$work/$scene" --quiet --set "coupling.time.end=$end"
  [ -f "$work/$scene/view.py" ] || { echo "FAILED: $scene: the run wrote no view.py"; rc=1; continue; }
  echo "== $scene to t = $end s"
  pvbatch_headless "$here/render_view.py" "$work/$scene" "$work/$scene.png" || rc=1
  grep -E "view time|colour range|picture|FAILED" "$work/pvbatch.log" || tail -20 "$work/pvbatch.log"
done <<SCENES
piston_2d 0.03
piston_3d 0.03
shock_panel_2d 3e-4
SCENES
exit "$rc"
