#!/usr/bin/env bash
# On the lent GPU machine: build, run `depthtrack bench` (the full grid) on CUDA, NVIDIA OpenCL and the
# reference, print the frame times side by side, and pack results.json and the PNG figures into one tar
# in $OUT (the device tool brings back at most 8 files). Carry .devdeps, .device and .devdata as for
# scripts/gpu/tests.sh. BENCH_BACKENDS, BENCH_MAX_SECONDS and BENCH_FLAGS (e.g. --quick) adjust the run.
set -uo pipefail
source .device/enter .devdeps
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out/bench"
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
generator=$(command -v ninja >/dev/null && echo Ninja || echo "Unix Makefiles")
cmake -S . -B build-gpu -G "$generator" -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_BUILD_TESTS=OFF >"$out/configure.log" 2>&1 || { tail -30 "$out/configure.log"; exit 1; }
cmake --build build-gpu -j"$(nproc)" --target depthtrack_cli >"$out/build.log" 2>&1 ||
  { grep -E "error|Error" "$out/build.log" | head -30; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
backends=()
for b in ${BENCH_BACKENDS:-cuda opencl:nvidia reference}; do backends+=(--backend "$b"); done
# shellcheck disable=SC2086
./build-gpu/depthtrack bench "${backends[@]}" --max-seconds "${BENCH_MAX_SECONDS:-360}" ${BENCH_FLAGS:-} \
  --out "$out/bench" >"$out/bench/table.txt" 2>"$out/bench/progress.log"
status=$?
grep -E "frame_ms|speedup|device_memory|wrote" "$out/bench/table.txt" | head -80
grep -E "failed|skipped" "$out/bench/progress.log" | head -20
tar -C "$out" -czf "$out/bench.tar.gz" bench && rm -rf "$out/bench"
exit $status
