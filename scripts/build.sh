#!/usr/bin/env bash
# Configures (Release, -O3) and builds everything into build/. Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j "$JOBS" >> build.log 2>&1 || { tail -60 build.log; exit 1; }
echo "built: $(ls build/bin | tr '\n' ' ')"
