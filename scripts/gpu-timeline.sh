#!/usr/bin/env bash
# On the lent GPU machine: the CUDA timeline of the several-object bench (issue 10's 1.5x), recorded by
# the CUPTI injection library of scripts/probes/cuda_timeline.cpp (no Nsight Systems there). Carry
# .devdeps, .device, .devdata and BIN (default build-carry-bin: depthtrack_bench, libdepthtrack.so.0 and
# probe/libtimeline.so with its libcupti.so.13, built on the CPU machine). Writes $OUT/timeline-*.csv.gz
# and the bench's rows, with and without the probe (its own cost).
set -uo pipefail
source .device/enter .devdeps
bin=${BIN:-build-carry-bin}
export LD_LIBRARY_PATH=$PWD/$bin:$LD_LIBRARY_PATH DEPTHTRACK_DATA_DIR=$PWD/.devdata
out=${OUT:-/tmp/timeline}
mkdir -p "$out"
args=(--multi-objects --backend cuda --particles "${PARTICLES:-2000}" --frames "${FRAMES:-20}" --untimed-steps
  --simplify-error 0.0005 ${EXTRA:-})
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
"$bin/depthtrack_bench" "${args[@]}" | grep -E "ratio|_ms," | awk -F, '{ print "plain", $(NF-3), $(NF-2), $NF }'
CUDA_INJECTION64_PATH=$PWD/$bin/probe/libtimeline.so DT_TIMELINE_OUT=$out/timeline-${TAG:-cuda}.csv \
  "$bin/depthtrack_bench" "${args[@]}" | grep -E "ratio|_ms," | awk -F, '{ print "probed", $(NF-3), $(NF-2), $NF }'
gzip -f "$out"/timeline-*.csv
ls -la "$out"
