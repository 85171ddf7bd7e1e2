#!/usr/bin/env bash
# ParaView (Debian's paraview + python3-paraview, headless under xvfb-run) opens a coupled run's fluid, solid and
# interface series with their arrays and time steps and renders the fluid. Skipped (exit 77) where ParaView is
# absent. Usage: paraview_opens_a_run.sh BUILD_DIR
set -euo pipefail
build="$1"
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v pvbatch > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "skipped: ParaView is not installed (apt-get install paraview python3-paraview xvfb)"
  exit 77
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$build/bin/cosim" run "$here/../../configs/piston_2d.yaml" --out "$work/run" --quiet --set coupling.time.end=0.03
# Xvfb with GLX and software GL; a display that is not up yet ("bad X server connection") is tried again.
for attempt in 1 2 3 4 5; do
  rc=0
  LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 1024x768x24 +extension GLX" \
    pvbatch "$here/open_run.py" "$work/run" "$work/fluid.png" > "$work/pvbatch.log" 2>&1 || rc=$?
  grep -q "bad X server connection" "$work/pvbatch.log" || break
  sleep 1
done
grep -E "cells|picture|FAILED" "$work/pvbatch.log" || tail -20 "$work/pvbatch.log"
exit "$rc"
