#!/usr/bin/env bash
# On the lent GPU machine: the pose refinement's device layouts (their share of the frame and
# its latency): `depthtrack_bench` at 2,000 particles, 80x60, for the handset (842 triangles) and the YCB mug
# (16,384), each backend, refinement one-group / spread / one-launch / off, rows refine_ms, refine_share,
# refine_iterations, total_ms; then the equivalence tests with refinement on each backend (every layout:
# the "each refinement layout auto does not pick" test runs the ones auto leaves out). Carry .devdeps, .device
# and .devdata. FRAMES (default 20), BACKENDS (default cuda opencl:nvidia), TESTS=0 skips the tests.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
build=${BUILD_DIR:-build-gpu}
if [[ ! -x $build/depthtrack_bench || ! -x $build/tests/depthtrack_tests ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
    -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_BUILD_TESTS=ON -DDEPTHTRACK_PYTHON=OFF >/tmp/refine-configure.log 2>&1 &&
    cmake --build "$build" -j"$(nproc)" --target depthtrack_bench depthtrack_tests >/tmp/refine-build.log 2>&1 ||
    { tail -20 /tmp/refine-build.log; exit 1; }
fi
frames=${FRAMES:-20}
rows=',(refine_ms|refine_share|refine_iterations|total_ms),'
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  for mesh in "" .devdata/meshes/ycb/025_mug.obj; do
    for layout in one-group spread one-launch; do
      "$build/depthtrack_bench" --backend "$b" --particles 2000 --frames "$frames" --no-global \
        --refine-layout "$layout" ${mesh:+--mesh "$mesh"} | grep -E "$rows" | cut -d, -f1,5-
    done
    "$build/depthtrack_bench" --backend "$b" --particles 2000 --frames "$frames" --no-global --refine off \
      ${mesh:+--mesh "$mesh"} | grep -E ',total_ms,' | cut -d, -f1,5-
  done
done
[[ ${TESTS:-1} == 1 ]] || exit 0
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  echo "== $b"
  DEPTHTRACK_TEST_DEVICE=$b "$build/tests/depthtrack_tests" "[device]" 2>&1 |
    grep -E "worst relative|test cases|FAILED|failed" | sed 's/pthread.*hand-off[^:]*//' | head -20
done
