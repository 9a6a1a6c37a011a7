#!/usr/bin/env bash
# On the lent GPU machine, one call (about 6 minutes): the pose atlas drawn and weighed in turns
# (TrackerConfig::atlas_particles; by default as many tiles as one buffer holds, which on an H100's NVIDIA
# OpenCL, 19.8 GiB, refused 30,000 particles at 640x480 before), the throughput and latency bars again,
# and the equivalence tests on CUDA and NVIDIA OpenCL. Builds this tree in build-gpu.
# Carry .devdeps, .device, .devdata.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_PYTHON=OFF -DDEPTHTRACK_BUILD_TESTS=ON >/tmp/configure.log 2>&1 &&
  cmake --build build-gpu -j"$(nproc)" --target depthtrack_bench depthtrack_tests >/tmp/build.log 2>&1 ||
  { tail -20 /tmp/build.log; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
bench=build-gpu/depthtrack_bench
rows() { grep -E ",($1)," | cut -d, -f5,6,8 | tr '\n' ' '; }
for b in cuda opencl:nvidia; do
  echo "== $b"
  # 640x480: the atlas is a separate buffer (the tile does not fit in work-group memory).
  "$bench" --backend "$b" --particles 10000,30000,40000 --resolution 640x480 --frames 6 --no-global |
    grep -E ',(total_ms|render_ms|weigh_ms|status),' | cut -d, -f5- | tr '\n' ' '
  echo
  "$bench" --backend "$b" --particles 100000,1500000 --frames 10 --no-global | rows 'total_ms'
  echo
  for rep in 1 2 3; do
    for feed in "" "--pace 5"; do
      echo "2,000 ${feed:-back to back}: $("$bench" --backend "$b" --particles 2000 --frames 60 --no-global \
        --untimed-steps $feed | grep -E ',(total_ms|update_ms),' | cut -d, -f6,8 | tr '\n' ' ')"
    done
  done
done
source scripts/lib/device-tests.sh
device_tests build-gpu/tests/depthtrack_tests "[device],[atlas],[kernels],[refine]"
