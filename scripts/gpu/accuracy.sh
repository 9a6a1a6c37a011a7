#!/usr/bin/env bash
# On the lent GPU machine: the accuracy tests ([accuracy]: the synthetic handsets, the YCB-Video clip, ViSP's
# simulated castle; each on the reference and on the test device) and the castle's import tests, on CUDA and
# on NVIDIA OpenCL. BIN=<folder> holds depthtrack_tests and libdepthtrack.so.0 built elsewhere (the design
# notes, "A short device budget"); without it this tree is built in build-gpu. Carry .devdeps, .device,
# .devdata (with sequences/visp-castle-simu for the castle).
set -uo pipefail
source .device/enter .devdeps
source scripts/lib/device-tests.sh
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
if [[ -n ${BIN:-} ]]; then
  export LD_LIBRARY_PATH=$PWD/$BIN${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  tests=$PWD/$BIN/depthtrack_tests
else
  cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_TESTS=ON -DDEPTHTRACK_PYTHON=OFF \
    -DDEPTHTRACK_SANITIZE_SUITE=OFF -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF >/tmp/accuracy-configure.log 2>&1 &&
    cmake --build build-gpu -j"$(nproc)" --target depthtrack_tests >/tmp/accuracy-build.log 2>&1 ||
    { tail -20 /tmp/accuracy-build.log; exit 1; }
  tests=$PWD/build-gpu/tests/depthtrack_tests
fi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for b in cuda opencl:nvidia; do
  echo "== [accuracy] on $b (each test prints the reference's row, then the device's)"
  DEPTHTRACK_TEST_DEVICE=$b "$tests" "[accuracy]" 2>&1 | grep -vE "^(Filters:|$)" | head -120
done
device_tests "$tests" "[visp]"
