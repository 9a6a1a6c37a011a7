#!/usr/bin/env bash
# On the lent GPU machine's host CPU (about 3 minutes with the build): the `cpu` backend's frame against
# the reference's on 1 to all cores (targets: >= 10x on 16 cores, >= 1.8x on 2), `depthtrack_bench
# --backend cpu:N` (which times the reference on each case and prints speedup_over_reference) for
# THREADS (default "1 2 4 8 16"), the handset and the YCB mug, PARTICLES (default "200 2000") at 80x60.
# Carry .devdeps, .device and .devdata.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
build=${BUILD_DIR:-build-gpu}
source scripts/lib/release-build.sh
release_build "$build" "$out" depthtrack_bench depthtrack_bench || exit 1
lscpu | grep -E '^Model name|^CPU\(s\)|^Thread|^Core'
source scripts/lib/cpu-cores.sh
echo "cpu:core/socket $(cpu_topology)"
for mesh in handset 025_mug; do
  args=()
  [[ $mesh == handset ]] || args=(--mesh ".devdata/meshes/ycb/$mesh.obj" --simplify-error 0.0005)
  for p in ${PARTICLES:-200 2000}; do
    for t in ${THREADS:-1 2 4 8 16}; do
      echo "$mesh $p particles cpu:$t: $("$build/depthtrack_bench" --backend "cpu:$t" --particles "$p" --frames 20 \
        --no-global --no-offscreen "${args[@]}" 2>&1 |
        grep -E ',(total_ms|busy_threads|speedup_over_reference|cpu_time_over_reference),' | cut -d, -f1,6,8 |
        tr '\n' ' ')"
    done
  done
done
