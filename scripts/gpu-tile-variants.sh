#!/usr/bin/env bash
# On the GPU machine (issue 10's 1.5x): render_weigh's tile, whole image against half its rows, timed on
# ycbv-0000's three objects. Carry .devdeps, .device, .devdata and build-carry-bin with one folder per
# variant (depthtrack_bench and libdepthtrack.so.0 each, built on the CPU machine; VARIANTS names them,
# the first also gets Nsight Compute's report of render_weigh when NCU=1) and probe/libtimeline.so
# (scripts/probes/cuda_timeline.cpp). REPS repetitions of the timing (default 2). TESTS=VARIANT runs that
# variant's TEST_TAGS (default [render],[device]) on both backends, each within TEST_LIMIT seconds.
# Timelines and reports go to $OUT.
set -uo pipefail
source .device/enter .devdeps >/dev/null 2>&1
export DEPTHTRACK_DATA_DIR=$PWD/.devdata
out=${OUT:-/tmp/variants}
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
args=(--multi-objects --particles 2000 --untimed-steps --simplify-error 0.0005)
bench() { # variant backend frames
  LD_LIBRARY_PATH=$PWD/build-carry-bin/$1:$LD_LIBRARY_PATH "build-carry-bin/$1/depthtrack_bench" "${args[@]}" \
    --backend "$2" --frames "$3"
}
rows() { grep -E "occlusion_off_untimed,(multi_object_ratio_to_mean|object[012]_alone_ms|three_objects_ms)," |
  awk -F, -v tag="$1" '{ printf "%s %s %s\n", tag, $(NF-2), $NF }'; }
for rep in $(seq "${REPS:-2}"); do
  for v in ${VARIANTS:-base new}; do
    for b in cuda opencl:nvidia; do bench "$v" "$b" 40 | rows "$v $b rep$rep"; done
  done
done
if [[ -n ${TESTS:-} ]]; then # each backend's run within TEST_LIMIT seconds (scripts/lib/device-tests.sh)
  source scripts/lib/device-tests.sh
  (export LD_LIBRARY_PATH=$PWD/build-carry-bin/$TESTS:$LD_LIBRARY_PATH TEST_LIMIT=${TEST_LIMIT:-150}
    device_tests "build-carry-bin/$TESTS/depthtrack_tests" "${TEST_TAGS:-[render],[device]}")
fi
for v in ${VARIANTS:-base new}; do
  LD_LIBRARY_PATH=$PWD/build-carry-bin/$v:$LD_LIBRARY_PATH CUDA_INJECTION64_PATH=$PWD/build-carry-bin/probe/libtimeline.so \
    DT_TIMELINE_OUT=$out/timeline-$v.csv "build-carry-bin/$v/depthtrack_bench" "${args[@]}" --backend cuda --frames 20 \
    | rows "$v cuda probed"
done
gzip -f "$out"/timeline-*.csv
if [[ ${NCU:-0} == 1 ]] && command -v ncu >/dev/null; then
  v=${VARIANTS%% *}; v=${v:-base}
  for skip in 10 30; do
    LD_LIBRARY_PATH=$PWD/build-carry-bin/$v:$LD_LIBRARY_PATH timeout 150 ncu -k regex:render_weigh --launch-skip $skip \
      --launch-count 1 --set full --page details "build-carry-bin/$v/depthtrack_bench" "${args[@]}" --backend cuda \
      --frames 20 >"$out/ncu-$v-$skip.txt" 2>&1
    grep -E "^    (Duration|Registers Per|Achieved Occupancy|Theoretical Occupancy|Block Limit|Waves Per|SM Frequency|Memory Throughput|Compute \(SM\) Throughput|No Eligible|Active Warps Per|Eligible Warps)" \
      "$out/ncu-$v-$skip.txt" | head -24
  done
fi
ls "$out"
