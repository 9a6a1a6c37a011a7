#!/usr/bin/env bash
# On the GPU machine (the three-object target, 1.5x one): builds and kernel variants of the several-object frame, timed on
# ycbv-0000's three objects. Carry .devdeps, .device, .devdata and build-carry-bin with one folder per
# build (depthtrack_bench and libdepthtrack.so.0 each, built on the CPU machine) and probe/libtimeline.so
# (scripts/probes/cuda_timeline.cpp). VARIANTS names them: a build's folder ("new"), or a build and one
# of scripts/probes/kernel_variants.py's kernel variants ("new:no_draw", through DEPTHTRACK_KERNEL_DIR;
# "new:tree": the carried cl/ as it is).
# REPS repetitions of the timing (default 2), then each variant once under the CUDA timeline probe
# (bench.txt and the timelines in $OUT; summarize them with timeline_summary.py). TESTS=BUILD runs that build's TEST_TAGS (default [render],[device])
# on both backends, each within TEST_LIMIT seconds (TEST_TREE=1: with the carried cl/). NCU=1: Nsight Compute's report of render_weigh (the
# first object's frame 10 and the second's) for the first variant, and its source page as CSV. Timelines and reports go to $OUT.
set -uo pipefail
source .device/enter .devdeps >/dev/null 2>&1
export DEPTHTRACK_DATA_DIR=$PWD/.devdata
out=${OUT:-/tmp/variants}
mkdir -p "$out"
ablations=$(mktemp -d)
python3 scripts/probes/kernel_variants.py "$ablations" >/dev/null || exit 1
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
args=(--multi-objects --particles 2000 --untimed-steps)
# A variant: BUILD[:KERNELS][@SIMPLIFY_ERROR] (the mesh simplified to that error in metres; default 0.0005).
build_of() { local v=${1%%@*}; echo "${v%%:*}"; }
variant_env() { # variant: its build's library path and, for a kernel variant, its kernel folder
  local v=${1%%@*} kernels=
  [[ $v == *:* ]] && kernels=$ablations/${v#*:}
  [[ $v == *:tree ]] && kernels=$PWD/cl # the carried working tree's kernels
  echo "LD_LIBRARY_PATH=$PWD/build-carry-bin/$(build_of "$1"):${LD_LIBRARY_PATH:-} DEPTHTRACK_KERNEL_DIR=$kernels"
}
bench() { # variant backend frames [more environment]
  local simplify=0.0005
  [[ $1 == *@* ]] && simplify=${1#*@}
  env $(variant_env "$1") "${@:4}" "build-carry-bin/$(build_of "$1")/depthtrack_bench" "${args[@]}" \
    --simplify-error "$simplify" --backend "$2" --frames "$3"
}
rows() { grep -E "occlusion_off_untimed,(multi_object_ratio_to_mean|object[012]_alone_ms|three_objects_ms)," |
  awk -F, -v tag="$1" '{ printf "%s %s %s\n", tag, $(NF-2), $NF }'; }
variants=${VARIANTS:-base new}
for rep in $(seq "${REPS:-2}"); do
  for v in $variants; do
    for b in cuda opencl:nvidia; do bench "$v" "$b" 40 | rows "$v $b rep$rep" >>"$out/bench.txt"; done
  done
done
for v in $variants; do
  csv=$out/timeline-$(tr ':@' '-_' <<<"$v").csv
  bench "$v" cuda 20 CUDA_INJECTION64_PATH="$PWD/build-carry-bin/probe/libtimeline.so" DT_TIMELINE_OUT="$csv" |
    rows "$v cuda probed" >>"$out/bench.txt"
  gzip -f "$csv"
done
grep ratio_to_mean "$out/bench.txt" # the rest there, and the timelines: timeline_summary.py on the CPU machine
if [[ -n ${TESTS:-} ]]; then # each backend's run within TEST_LIMIT seconds (scripts/lib/device-tests.sh)
  source scripts/lib/device-tests.sh
  (export LD_LIBRARY_PATH=$PWD/build-carry-bin/$TESTS:$LD_LIBRARY_PATH TEST_LIMIT=${TEST_LIMIT:-150}
    [[ ${TEST_TREE:-0} == 1 ]] && export DEPTHTRACK_KERNEL_DIR=$PWD/cl
    device_tests "build-carry-bin/$TESTS/depthtrack_tests" "${TEST_TAGS:-[render],[device]}")
fi
if [[ ${NCU:-0} == 1 ]] && command -v ncu >/dev/null; then
  v=${variants%% *}
  for skip in 10 30; do
    report=$out/ncu-$(tr ':@' '-_' <<<"$v")-$skip.txt
    env $(variant_env "$v") timeout 150 ncu --clock-control none -k regex:render_weigh --launch-skip $skip \
      --launch-count 1 --set full --import-source yes -f -o /tmp/ncu-$skip "build-carry-bin/$(build_of "$v")/depthtrack_bench" \
      "${args[@]}" --simplify-error 0.0005 --backend cuda --frames 20 >/dev/null 2>&1
    ncu -i /tmp/ncu-$skip.ncu-rep --page details >"$report" 2>&1
    # Per source line (a build with DEPTHTRACK_CUDA_EXTRA_OPTIONS=-lineinfo): scripts/probes/ncu_source_lines.py.
    ncu -i /tmp/ncu-$skip.ncu-rep --page source --csv --print-source cuda,sass 2>/dev/null | gzip >"${report%.txt}-source.csv.gz"
    grep -E "^    (Duration|Registers Per|Achieved Occupancy|Theoretical Occupancy|Block Limit|Waves Per|SM Frequency|Memory Throughput|Compute \(SM\) Throughput|No Eligible|Active Warps Per|Eligible Warps|Warp Cycles Per Issued)" \
      "$report" | head -24
  done
fi
ls "$out"
