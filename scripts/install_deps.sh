#!/usr/bin/env bash
# Installs the Debian 12 packages this project needs, only those that are missing. With --runtime, only what an
# installed build needs to run (the shared libraries and the Python packages: docker/Dockerfile's run stage). With
# --tests, also what only the tests use (a one-node SLURM cluster: slurm-wlm and munge).
set -euo pipefail
RUNTIME_PACKAGES=(
  libstdc++6 libgomp1 libyaml-cpp0.7 libspdlog1.10 libfmt9 libhdf5-openmpi-103-1 libzmq5 libprotobuf32 libopenmpi3 openmpi-bin libmetis5
  python3 python3-numpy python3-matplotlib python3-h5py python3-zmq python3-protobuf python3-yaml
)
PACKAGES=(
  g++ gfortran cmake ninja-build pkg-config
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev libhdf5-openmpi-dev libeigen3-dev nlohmann-json3-dev
  libgtest-dev libzmq3-dev libprotobuf-dev protobuf-compiler libopenmpi-dev openmpi-bin libmetis-dev
  python3 python3-numpy python3-matplotlib python3-h5py python3-zmq python3-protobuf python3-yaml python3-pytest
)
TEST_PACKAGES=(slurm-wlm munge)
[ "${1:-}" = "--runtime" ] && PACKAGES=("${RUNTIME_PACKAGES[@]}")
[ "${1:-}" = "--tests" ] && PACKAGES+=("${TEST_PACKAGES[@]}")
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
