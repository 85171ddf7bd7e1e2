#!/usr/bin/env bash
# `cmake --install BUILD --prefix P` gives a working product: P/bin/cosim runs an example scene from
# P/share/cosim/examples whose solid is the installed Python piston ({python}), and the installed package reads the
# run; the Docker image's run-time package list covers the installed programs' libraries. Usage: install_and_run.sh BUILD_DIR
set -euo pipefail
build="$1"
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" > "$prefix/install.log"
# The package where Debian's python3 looks under /usr/local and /usr: PREFIX/lib/python3.X/dist-packages.
site="lib/$(/usr/bin/python3 -c 'import sys; print("python%d.%d" % sys.version_info[:2])')/dist-packages"
/usr/bin/python3 - "$site" <<'PY'
import sys
site = sys.argv[1]
for prefix in ("/usr/local", "/usr"):
    assert f"{prefix}/{site}" in sys.path, f"{prefix}/{site} is not on the path of /usr/bin/python3: {sys.path}"
PY
for f in bin/cosim bin/coupler bin/fluid_solver bin/solid_solver "$site/cosim/coupling_pb2.py" \
  share/cosim/python/rigid_piston.py share/cosim/examples/piston_2d.yaml share/doc/cosim/README.md share/doc/cosim/docs/methods.md; do
  [ -e "$prefix/$f" ] || { echo "missing in the install: $f"; exit 1; }
done
# The Docker run stage's packages cover what the installed programs load (and the check sees one left out).
here="$(cd "$(dirname "$0")" && pwd)"
bash "$here/runtime_packages_cover.sh" "$prefix" "$here/../.."
if bash "$here/runtime_packages_cover.sh" "$prefix" "$here/../.." libyaml-cpp0.7 > /dev/null; then
  echo "the runtime-package check did not see libyaml-cpp0.7 left out"
  exit 1
fi
cd "$prefix"  # nothing of the build tree's working directory is used
"$prefix/bin/cosim" run "$prefix/share/cosim/examples/piston_1d.yaml" --out "$prefix/run" --quiet \
  --set coupling.time.end=0.02
PYTHONPATH="$prefix/$site" /usr/bin/python3 - "$prefix" <<'PY'
import sys
from pathlib import Path
import cosim
prefix = Path(sys.argv[1])
run = cosim.read_run(prefix / "run")
assert len(run.fluid) >= 2, f"{len(run.fluid)} fluid snapshots"
assert abs(run.fluid.times[-1] - 0.02) < 1e-9, run.fluid.times
assert Path(cosim.find_executable()) == prefix / "bin" / "cosim", cosim.find_executable()
print(f"installed run: {len(run.fluid)} fluid snapshots to t = {run.fluid.times[-1]:g} s, launcher {cosim.find_executable()}")
PY
