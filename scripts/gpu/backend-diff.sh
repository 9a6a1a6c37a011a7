#!/usr/bin/env bash
# On the lent GPU machine, one call: where CUDA and NVIDIA OpenCL differ on the same kernel source.
# Times CASES on both backends with every step's row, keeping each backend's compiled programs in a
# fresh program cache, then sets the two builds of every kernel side by side (registers, spills, shared
# memory: scripts/probes/kernel_resources.py) and packs the cache (PTX and cubins) into $OUT/programs.tar.gz.
#   CASES  semicolon-separated depthtrack_bench argument lists (default: 2,000 and 100,000 particles, handset,
#          80x60, the whole image).
# Carry .devdeps, .device and .devdata.
set -uo pipefail
source .device/enter .devdeps
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache XDG_CACHE_HOME=/tmp/backend-diff-cache
rm -rf "$XDG_CACHE_HOME"
build=${BUILD_DIR:-build-gpu}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_PYTHON=OFF >"$out/configure.log" 2>&1 &&
  cmake --build "$build" -j"$(nproc)" --target depthtrack_cli depthtrack_bench >"$out/build.log" 2>&1 ||
  { grep -E "error" "$out/build.log" | head -30; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
IFS=';' read -r -a cases <<<"${CASES:---particles 2000 --frames 30 --no-global;--particles 100000 --frames 10 --no-global}"
for c in "${cases[@]}"; do
  for b in cuda opencl:nvidia; do
    echo "== $b: $c"
    # shellcheck disable=SC2086
    "$build/depthtrack_bench" --backend "$b" $c | tee -a "$out/steps.csv" | grep -E "_ms,|_share," | cut -d, -f1,5-
  done
done 2>&1 | tee "$out/steps.txt"
python3 scripts/probes/kernel_resources.py "$XDG_CACHE_HOME" 2>&1 | tee "$out/resources.txt"
tar -czf "$out/programs.tar.gz" -C "$XDG_CACHE_HOME" .
