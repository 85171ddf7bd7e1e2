#!/usr/bin/env bash
# A source tree without git (a container build from a copy) records the commit given in $COSIM_GIT_COMMIT, and says
# "unknown" without it. Usage: version_without_git.sh SOURCE_DIR
set -euo pipefail
src="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
COSIM_GIT_COMMIT=0123456789ab cmake -DSOURCE_DIR="$tmp" -DVERSION=9.9.9 -DOUT="$tmp/given.h" \
  -P "$src/cmake/write_version.cmake"
grep -q '#define COSIM_GIT_COMMIT "0123456789ab"' "$tmp/given.h" || { cat "$tmp/given.h"; exit 1; }
env -u COSIM_GIT_COMMIT cmake -DSOURCE_DIR="$tmp" -DVERSION=9.9.9 -DOUT="$tmp/none.h" -P "$src/cmake/write_version.cmake"
grep -q '#define COSIM_GIT_COMMIT "unknown"' "$tmp/none.h" || { cat "$tmp/none.h"; exit 1; }
echo "the commit of a tree without git: given 0123456789ab, else unknown"
