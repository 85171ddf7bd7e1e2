#!/usr/bin/env bash
# The run stage's packages less what only builds software (docker/Dockerfile, run stage, in the layer that installs
# them). Debian 12's python3-fonttools, which python3-matplotlib needs, depends on python3-scipy and python3-sympy,
# and python3-scipy on python3-pythran, which brings g++, the Boost and OpenBLAS headers and python3-dev: about
# 700 MB of a 1.5 GB image. matplotlib uses none of them (fontTools only subsets fonts for PDF/PS output, without
# scipy or sympy), so they are removed with --force-depends. dpkg then records those dependencies as unmet: an
# `apt-get install` in the image first puts them back (`apt-get -f install`).
set -euo pipefail
TRIM=(
  python3-pythran python3-beniget python3-gast python3-scipy python3-sympy python3-mpmath unicode-data
  g++ g++-12 gcc gcc-12 cpp cpp-12 binutils binutils-common binutils-x86-64-linux-gnu
  libasan8 libtsan2 liblsan0 libubsan1 libitm1 libcc1-0 libisl23 libmpc3 libctf0 libctf-nobfd0 libgprofng0 libjansson4
  libgcc-12-dev libstdc++-12-dev libc6-dev linux-libc-dev libcrypt-dev libnsl-dev libtirpc-dev libexpat1-dev zlib1g-dev
  libboost1.74-dev libboost-dev libopenblas-dev libopenblas-pthread-dev libxsimd-dev
  python3-dev python3.11-dev libpython3.11-dev libpython3-dev python3-all-dev libpython3-all-dev
)
installed=()
for p in "${TRIM[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed" && installed+=("$p")
done
if [ ${#installed[@]} -gt 0 ]; then
  dpkg --purge --force-depends "${installed[@]}" > /tmp/trim.log 2>&1 || { cat /tmp/trim.log; exit 1; }
  rm -f /tmp/trim.log
fi
# What the image runs must still work: no compiler, and the Python packages cosim's scripts import.
! command -v g++ > /dev/null && ! command -v gcc > /dev/null
/usr/bin/python3 -c "import numpy, h5py, yaml, zmq, google.protobuf, matplotlib; matplotlib.use('Agg'); \
import matplotlib.pyplot as plt; plt.plot([0, 1]); plt.savefig('/tmp/trim_check.png')"
rm -f /tmp/trim_check.png
echo "trimmed: ${#installed[@]} packages"
