#!/usr/bin/env bash
# On the lent GPU machine, one call (about 5 minutes): the occlusion state window (TrackerConfig::
# occlusion_window) against the whole image, at issue 12's throughput bars: handset 80x60 at 2,000 to
# 1,500,000 particles (window WINDOW, default 32x24) and 640x480 at 10,000 and 30,000 (WINDOW_VGA,
# default 256x192), per backend; then the [device] equivalence tests (the window's included) on each.
# Carry .devdeps, .device and .devdata. Logs into $OUT; TESTS=0 leaves out the tests.
set -uo pipefail
source .device/enter .devdeps
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
build=${BUILD_DIR:-build-gpu}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_BUILD_TESTS=ON -DDEPTHTRACK_PYTHON=OFF >"$out/configure.log" 2>&1 &&
  cmake --build "$build" -j"$(nproc)" --target depthtrack_cli depthtrack_bench depthtrack_tests >"$out/build.log" 2>&1 ||
  { grep -E "error" "$out/build.log" | head -30; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
window=${WINDOW:-32x24} vga=${WINDOW_VGA:-256x192}
rows=',(weigh_ms|refine_ms|total_ms|status),'
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  "$build/depthtrack_bench" --backend "$b" --particles 2000,100000,1000000,1500000 --frames 10 --no-global \
    --occlusion-window "$window" | tee "$out/window-${b//:/-}.csv" | grep -E "$rows" | cut -d, -f1,5-
  "$build/depthtrack_bench" --backend "$b" --particles 1000000 --frames 10 --no-global |
    grep -E "$rows" | cut -d, -f1,5-
  "$build/depthtrack_bench" --backend "$b" --particles 10000,30000 --resolution 640x480 --frames 6 --no-global \
    --occlusion-window "$vga" | tee "$out/window-vga-${b//:/-}.csv" | grep -E "$rows" | cut -d, -f1,5-
  "$build/depthtrack_bench" --backend "$b" --particles 10000 --resolution 640x480 --frames 6 --no-global |
    grep -E "$rows" | cut -d, -f1,5-
done 2>&1 | tee "$out/window.txt"
[[ ${TESTS:-1} == 1 ]] || exit 0
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  echo "== $b"
  DEPTHTRACK_TEST_DEVICE=$b "$build/tests/depthtrack_tests" "[device],[window]" 2>&1 |
    grep -E "state window|test cases|FAILED|failed" | sed 's/pthread.*hand-off[^:]*//' | cut -c1-300 | head -30
done 2>&1 | tee "$out/equivalence.txt" | grep -E "test cases|FAILED|failed|All tests|moved"
