#!/usr/bin/env bash
# Every run writes a ParaView state, RUN/view.py: loaded by pvbatch under Xvfb (software GL) for short coupled runs,
# 2D and 3D pistons and a 2D panel that the blast deforms (its von Mises stress varies), it shows the fluid's
# pressure, the solid's von Mises stress and the interface at the last time with the colour ranges fitted to it, in
# a picture that holds the fields' colours (render_view.py). Skipped (exit 77) where ParaView is absent.
# Usage: paraview_shows_a_run.sh BUILD_DIR
set -euo pipefail
build="$1"
if ! command -v pvbatch > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "skipped: ParaView is not installed (apt-get install paraview python3-paraview xvfb)"
  exit 77
fi
here="$(cd "$(dirname "$0")" && pwd)"
configs="$here/../../configs"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# pvbatch SCRIPT ARGS... under Xvfb with GLX and software GL, its output in $work/pvbatch.log; a display that is not
# up yet ("bad X server connection") is tried again.
pvbatch_headless() {
  local rc=0
  for attempt in 1 2 3 4 5; do
    rc=0
    LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 1024x768x24 +extension GLX" \
      pvbatch "$@" > "$work/pvbatch.log" 2>&1 || rc=$?
    grep -q "bad X server connection" "$work/pvbatch.log" || break
    sleep 1
  done
  return "$rc"
}

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
