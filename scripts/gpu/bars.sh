#!/usr/bin/env bash
# On the lent GPU machine, one call (about 4 minutes): the GPU targets at the current commit.
#   refinement:  refine_share at 2,000 particles, 80x60, handset, auto layout (bar <= 30 %), per backend;
#   frame:       the 2,000-particle frame (bar 0.25 ms), 100,000 particles (CUDA / OpenCL throughput >= 1.0),
#                1,000,000 particles, and the bars' 1,500,000 at 80x60 and 30,000 at 640x480 (<= 33 ms each),
#                with the default (automatic) occlusion state window and over the whole image (`full`);
#   objects:     three ycbv objects against one (bar <= 1.5x), per backend;
#   and the [device] equivalence tests on each backend.
# Carry .devdeps, .device and .devdata (as scripts/gpu/tests.sh). Logs into $OUT; SKIP_TESTS=1 leaves out the tests.
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
git log --oneline -1 2>/dev/null || true
rows=',(refine_ms|refine_share|total_ms|status),'
for b in cuda opencl:nvidia; do
  "$build/depthtrack_bench" --backend "$b" --particles 2000,100000,1000000,1500000 --frames 10 --no-global |
    tee "$out/bench-${b//:/-}.csv" | grep -E "$rows" | cut -d, -f1,5-
  # The same over the whole image's occlusion state (the model as MODEL.md writes it).
  "$build/depthtrack_bench" --backend "$b" --particles 2000,100000,1000000 --frames 10 --no-global \
    --occlusion-window full | tee "$out/bench-full-${b//:/-}.csv" | grep -E "$rows" | cut -d, -f1,5-
  "$build/depthtrack_bench" --backend "$b" --particles 10000,30000 --resolution 640x480 --frames 6 --no-global |
    grep -E ',(total_ms|status),' | cut -d, -f1,5-
  "$build/depthtrack_bench" --backend "$b" --particles 10000 --resolution 640x480 --frames 6 --no-global \
    --occlusion-window full | grep -E ',(total_ms|status),' | cut -d, -f1,5-
  "$build/depthtrack_bench" --multi-objects --backend "$b" --particles 2000 | grep -E "multi_object_ratio|_objects?_ms," |
    grep -v one_host | cut -d, -f1,5-
done 2>&1 | tee "$out/bars.txt"
[[ ${SKIP_TESTS:-0} == 1 ]] && exit 0
for b in cuda opencl:nvidia; do
  echo "== $b"
  DEPTHTRACK_TEST_DEVICE=$b "$build/tests/depthtrack_tests" "[device]" 2>&1 |
    grep -E "worst relative|test cases|FAILED|failed" | sed 's/pthread.*hand-off[^:]*//' | cut -c1-260 | head -30
done 2>&1 | tee "$out/equivalence.txt" | grep -E "test cases|FAILED|failed|All tests"
