#!/usr/bin/env bash
# On the lent GPU machine (about 3 minutes with the build): how long the global search in an object's 2D box
# takes on each backend (target: <= 100 ms at 640x480 sensor, 80x60 working), with where each box start ends.
# `depthtrack eval --cases box` on ycbv-0000 and ycbv-0049, every object with a mesh, per backend in BACKENDS
# (default: cuda opencl:nvidia cpu). Prints each case row (search_ms, ADD-S) and the per-backend wall time.
# Carry .devdeps, .device and .devdata (the clips with their label images, the YCB meshes).
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
build=${BUILD_DIR:-build-gpu}
source scripts/lib/release-build.sh
release_build "$build" "$out" depthtrack depthtrack_cli || exit 1
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
lscpu | grep -E '^Model name|^CPU\(s\)'
for b in ${BACKENDS:-cuda opencl:nvidia cpu}; do
  for clip in ycbv-0000 ycbv-0049; do
    start=$(date +%s%N)
    "$build/depthtrack" eval --sequence ".devdata/sequences/$clip" --mesh-dir .devdata/meshes/ycb --cases box \
      --backend "$b" >"$out/box-$b-$clip.log" 2>&1
    rc=$?
    echo "== $b $clip (rc $rc, $((($(date +%s%N) - start) / 1000000)) ms wall)"
    grep -E 'search_ms|error' "$out/box-$b-$clip.log"
  done
done
