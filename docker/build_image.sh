#!/usr/bin/env bash
# Builds docker/Dockerfile without Docker and without a registry: a Debian 12 base made here by debootstrap from
# Debian's package mirror, imported into buildah (chroot isolation, vfs storage when overlay does not work), the
# image built with the commit as a build argument, then checked by running it as the user cosim: `cosim --version`
# names the commit, `/usr/bin/python3 -c "import cosim"` works, and a short coupled run (configs/piston_2d.yaml)
# finishes. Prints the build time and the image size. docker/README.md describes it.
#
#   bash docker/build_image.sh [--tag cosim] [--run-tests] [--keep-base] [--base-only]
#
# --keep-base reuses the base image of an earlier call; --base-only stops after making it; --run-tests runs the
# test suite in the build stage (slow: most of an hour on two cores).
#
# Environment: COSIM_IMAGE_WORK (default /var/tmp/cosim-image: the debootstrap tree and logs), DEBIAN_MIRROR
# (default http://deb.debian.org/debian), BUILDAH_STORAGE (overlay or vfs; default: overlay when it works).
# Needs root, debootstrap and buildah (Debian packages). Exit 0 when the image was built and every check passed.
set -euo pipefail
cd "$(dirname "$0")/.."

TAG=cosim
RUN_TESTS=0
KEEP_BASE=0
BASE_ONLY=0
while [ $# -gt 0 ]; do
  case "$1" in
    --tag) TAG=$2; shift 2 ;;
    --run-tests) RUN_TESTS=1; shift ;;
    --keep-base) KEEP_BASE=1; shift ;;
    --base-only) BASE_ONLY=1; shift ;;
    *) echo "build_image.sh: unknown argument '$1' (expected --tag NAME, --run-tests, --keep-base, --base-only)" >&2; exit 2 ;;
  esac
done

WORK=${COSIM_IMAGE_WORK:-/var/tmp/cosim-image}
MIRROR=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
BASE=localhost/cosim-debian:12
mkdir -p "$WORK"
for tool in debootstrap buildah; do
  command -v "$tool" > /dev/null || { echo "build_image.sh: $tool is not installed (apt-get install $tool)" >&2; exit 2; }
done
[ "$(id -u)" -eq 0 ] || { echo "build_image.sh: run as root (debootstrap and buildah's chroot isolation)" >&2; exit 2; }

# Storage: overlay where the kernel allows it here, else vfs (every layer a full copy: slower, more disk).
if [ -z "${BUILDAH_STORAGE:-}" ]; then
  BUILDAH_STORAGE=vfs
  if buildah --storage-driver overlay images > "$WORK/storage-probe.log" 2>&1; then BUILDAH_STORAGE=overlay; fi
fi
B=(buildah --storage-driver "$BUILDAH_STORAGE")
echo "buildah storage: $BUILDAH_STORAGE"

# 1. The base: Debian 12 (minbase, as small as debian:12-slim) from the mirror, imported as $BASE.
if [ "$KEEP_BASE" = 1 ] && "${B[@]}" inspect --type image "$BASE" > /dev/null 2>&1; then
  echo "base: $BASE (kept)"
else
  rootfs="$WORK/rootfs"
  rm -rf "$rootfs"
  echo "debootstrap bookworm from $MIRROR (log: $WORK/debootstrap.log)"
  nice -n 10 debootstrap --variant=minbase bookworm "$rootfs" "$MIRROR" > "$WORK/debootstrap.log" 2>&1 ||
    { tail -20 "$WORK/debootstrap.log"; exit 1; }
  # The image's apt: the mirror with its updates and security suites, no caches or lists kept.
  cat > "$rootfs/etc/apt/sources.list" << EOF
deb $MIRROR bookworm main
deb $MIRROR bookworm-updates main
deb ${MIRROR%/debian}/debian-security bookworm-security main
EOF
  rm -rf "$rootfs"/var/cache/apt/archives/*.deb "$rootfs"/var/lib/apt/lists/*
  tar -C "$rootfs" -cf "$WORK/rootfs.tar" .
  rm -rf "$rootfs"
  "${B[@]}" rmi -f "$BASE" > /dev/null 2>&1 || true
  ctr=$("${B[@]}" from scratch)
  "${B[@]}" add "$ctr" "$WORK/rootfs.tar" /
  "${B[@]}" config --env PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin --cmd bash "$ctr"
  "${B[@]}" commit --quiet "$ctr" "$BASE" > /dev/null
  "${B[@]}" rm "$ctr" > /dev/null
  rm -f "$WORK/rootfs.tar"
  echo "base: $BASE ($("${B[@]}" images --format '{{.Size}}' "$BASE"))"
fi

[ "$BASE_ONLY" = 1 ] && exit 0

# 2. The image, from the checkout's commit (git archive HEAD: uncommitted changes are not in it), with the commit as
# a build argument.
commit=$(git rev-parse --short=12 HEAD 2> /dev/null) ||
  { echo "build_image.sh: not a git checkout (the image is built from its commit)" >&2; exit 2; }
git diff --quiet HEAD || echo "note: uncommitted changes are not in the image (it is built from $commit)"
ctx="$WORK/context"
rm -rf "$ctx"
mkdir -p "$ctx"
git archive HEAD | tar -x -C "$ctx"
echo "building $TAG at commit $commit (log: $WORK/build.log)"
start=$(date +%s)
nice -n 10 "${B[@]}" bud --isolation chroot --layers -f "$ctx/docker/Dockerfile" -t "$TAG" \
  --build-arg BASE_IMAGE="$BASE" --build-arg RUN_BASE_IMAGE="$BASE" \
  --build-arg COSIM_GIT_COMMIT="$commit" --build-arg RUN_TESTS="$RUN_TESTS" \
  --ignorefile "$ctx/docker/Dockerfile.dockerignore" "$ctx" > "$WORK/build.log" 2>&1 ||
  { tail -40 "$WORK/build.log"; echo "build_image.sh: the image build failed (log: $WORK/build.log)" >&2; exit 1; }
build_s=$(($(date +%s) - start))

# 3. The checks, in a container of the image as its user (cosim).
ctr=$("${B[@]}" from "$TAG")
trap '"${B[@]}" rm "$ctr" > /dev/null 2>&1 || true' EXIT
run() { "${B[@]}" run --isolation chroot --user cosim --workingdir /home/cosim "$ctr" -- "$@"; }
fail=0
user=$(run id -un)
[ "$user" = cosim ] || { echo "FAIL: runs as '$user', expected cosim" >&2; fail=1; }
version=$(run cosim --version)
echo "cosim --version: $version"
if ! grep -q "$commit" <<< "$version" || grep -q "unknown" <<< "$version"; then
  echo "FAIL: cosim --version does not name the commit $commit" >&2
  fail=1
fi
run /usr/bin/python3 -c "import cosim; print('import cosim:', cosim.__file__)" || fail=1
# A coupled scene, shortened: coupler, fluid_solver and solid_solver as three processes.
if run cosim run configs/piston_2d.yaml --out /tmp/piston --quiet --set coupling.time.end=0.01 \
  --set coupling.output.interval=0.005 > "$WORK/run.log" 2>&1 &&
  run test -s /tmp/piston/coupler/interface_history.csv; then
  echo "coupled run: configs/piston_2d.yaml to 10 ms: finished"
else
  cat "$WORK/run.log"
  echo "FAIL: the coupled run did not finish" >&2
  fail=1
fi
size=$("${B[@]}" images --format '{{.Size}}' "$TAG")
echo "image $TAG: $size, built in ${build_s} s (nice -n 10, $(nproc) cores)"
exit $fail
