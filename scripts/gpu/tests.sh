#!/usr/bin/env bash
# On the lent GPU machine (see ../shared/device), suite "tests": build with the CUDA backend, run the whole test
# suite once on CUDA and once on NVIDIA OpenCL, and benchmark both. Logs go to $OUT when set.
# Carry .devdeps, .device and .devdata (a copy of the ../shared/data files the tests read).
set -uo pipefail
source .device/enter .devdeps
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
generator=$(command -v ninja >/dev/null && echo Ninja || echo "Unix Makefiles")
# No -Werror here: the GPU machine's newer GCC warns where CI's does not; CI keeps warnings fatal.
# The sanitizer subset is CI's (a second full build); the GPU run covers the device paths.
cmake -S . -B build-gpu -G "$generator" -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_BUILD_TESTS=ON >"$out/configure.log" 2>&1 ||
  { tail -30 "$out/configure.log"; exit 1; }
cmake --build build-gpu -j"$(nproc)" >"$out/build.log" 2>&1 || { grep -E "error|Error" "$out/build.log" | head -30; exit 1; }
./build-gpu/depthtrack info | tee "$out/info.txt"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee -a "$out/info.txt"
for device in ${DEVICES-cuda opencl:nvidia}; do
  echo "== ctest with DEPTHTRACK_TEST_DEVICE=$device"
  DEPTHTRACK_TEST_DEVICE=$device ctest --test-dir build-gpu -j"${CTEST_JOBS:-4}" --timeout "${CTEST_TIMEOUT:-180}" --output-on-failure -V >"$out/ctest-${device//:/-}.log" 2>&1
  grep -E "tests passed|tests failed|Failed|\*\*\*|SKIPPED" "$out/ctest-${device//:/-}.log" | grep -v "^[0-9]*: SKIPPED" | tail -15
  grep -E "worst relative|^[0-9]+: +(occlusion|refine)|mean rotation error over|ADD-S|lost|found" "$out/ctest-${device//:/-}.log" |
    sed 's/^[0-9]*: //' | head -${CTEST_SUMMARY_LINES:-40}
done
for backend in ${BENCH_BACKENDS-cuda opencl:nvidia}; do
  for renderer in ${BENCH_RENDERERS:-kernel gl}; do
    ./build-gpu/depthtrack_bench --backend "$backend" --renderer "$renderer" \
      --particles "${BENCH_PARTICLES:-200,2000,10000,100000}" --frames "${BENCH_FRAMES:-6}" |
      tee "$out/bench-${backend//:/-}-$renderer.csv" | grep -E "_ms,|Hz" | cut -d, -f1,5-
  done
done
# The refinement's cost against the filter alone, and start-up at a million particles.
for backend in ${BENCH_BACKENDS-cuda opencl:nvidia}; do
  ./build-gpu/depthtrack_bench --backend "$backend" --particles "${REFINE_PARTICLES:-2000}" --frames 8 --refine off \
    --no-global | tee "$out/bench-${backend//:/-}-refine-off.csv" | grep -E "total_ms|Hz" | cut -d, -f1,5-
  ./build-gpu/depthtrack_bench --backend "$backend" --particles "${STARTUP_PARTICLES:-1000000}" --frames 4 \
    --no-global | tee "$out/bench-${backend//:/-}-1M.csv" | grep -E "total_ms|startup|Hz" | cut -d, -f1,5-
done
# ycbv-0000 started from each object's box and from no hint (the global initialization's table).
# The ycbv-0000 global initialization table (box hint and no hint); GLOBAL_TABLE=0 skips it.
for backend in $([[ ${GLOBAL_TABLE:-1} == 1 ]] && echo "${BENCH_BACKENDS-cuda opencl:nvidia}"); do
  DEPTHTRACK_TEST_GLOBAL_NO_HINT=1 DEPTHTRACK_TEST_GLOBAL_BACKEND=$backend \
    ./build-gpu/tests/depthtrack_tests "[global][accuracy]" 2>&1 | tee "$out/global-${backend//:/-}.log" |
    grep -E "ycbv-0000|  0[0-9][0-9]_|test cases"
done
