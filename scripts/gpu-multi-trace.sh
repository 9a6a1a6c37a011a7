#!/usr/bin/env bash
# On the lent GPU machine (under a minute with a carried binary): a CUDA timeline of three ycbv-0000
# objects' frames (issue 10's 1.5x), to see whether the objects' kernels overlap on the device: Nsight
# Systems' kernel and copy trace as CSV in $OUT/multi-trace_cuda_gpu_trace.csv (start, duration, stream,
# name). BIN=<folder> with depthtrack_bench and libdepthtrack.so.0 (else build-gpu). Carry .devdeps,
# .device, .devdata.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
bin=${BIN:+$PWD/$BIN}
bin=${bin:-$PWD/build-gpu}
[[ -n ${BIN:-} ]] && export LD_LIBRARY_PATH=$bin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
nsys=$(command -v nsys || ls /usr/local/cuda/bin/nsys /opt/nvidia/nsight-systems/*/bin/nsys 2>/dev/null | head -1)
[[ -x $nsys ]] || { echo "no nsys on this machine"; exit 0; }
"$nsys" profile --trace=cuda --sample=none --cpuctxsw=none -o /tmp/multi-trace -f true \
  "$bin/depthtrack_bench" --multi-objects --backend cuda --particles 2000 --untimed-steps --simplify-error 0.0005 \
  --frames 6 >/tmp/nsys.log 2>&1 || { tail -20 /tmp/nsys.log; exit 1; }
"$nsys" stats --report cuda_gpu_trace --format csv --output "$out/multi-trace" /tmp/multi-trace.nsys-rep >/dev/null 2>&1
ls -la "$out"/multi-trace* 2>/dev/null
# Within the bench's three-object frames: how much of the busy time had kernels of two streams at once.
python3 - "$out/multi-trace_cuda_gpu_trace.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(len(rows), "records;", "columns:", ", ".join(list(rows[0].keys())[:12]) if rows else "-")
EOF
