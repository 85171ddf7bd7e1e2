# Sourced by the ParaView tests: skips (exit 77) where ParaView or Xvfb is absent, makes $work (removed at exit) and
# defines pvbatch_headless SCRIPT ARGS...: pvbatch under Xvfb with GLX and software GL, its output in
# $work/pvbatch.log; a display that is not up yet ("bad X server connection") is tried again.
if ! command -v pvbatch > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "skipped: ParaView is not installed (apt-get install paraview python3-paraview xvfb)"
  exit 77
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

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
