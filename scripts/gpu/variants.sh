#!/usr/bin/env bash
# On the lent GPU machine, one call: the same build timed with several versions of the kernels, read at
# run time from DEPTHTRACK_KERNEL_DIR (files there replace the embedded cl/ files of the same name), so
# one build measures a kernel change against what it replaces on the same machine in the same minutes.
#   VARIANTS  space-separated name=source pairs: source a folder (its files replace cl/'s), a commit
#             (its whole cl/, by git archive), "embedded" (the build's own), or env:NAME=VALUE (the
#             build's own kernels with that variable set, e.g. env:DEPTHTRACK_CUDA_GRAPHS=off); default
#             "embedded".
#   CASES     semicolon-separated depthtrack_bench argument lists, each run for every variant and backend
#             (default: 100,000 / 1,000,000 / 1,500,000 particles, handset, 80x60, a 32x24 state window).
#   ROWS      the rows printed (an extended regex; all go to variants.csv).
#   BACKENDS  default "cuda opencl:nvidia". TESTS: a Catch test spec run per backend on the embedded
#             kernels afterwards (default: none). MULTI=1 adds `--multi-objects` per variant, every row.
# Carry .devdeps, .device and .devdata (as scripts/gpu/tests.sh), and any variant folders. Logs into $OUT.
set -uo pipefail
source .device/enter .devdeps
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache DEPTHTRACK_PROGRAM_CACHE=off
build=${BUILD_DIR:-build-gpu}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_BUILD_TESTS=ON -DDEPTHTRACK_PYTHON=OFF >"$out/configure.log" 2>&1 &&
  cmake --build "$build" -j"$(nproc)" --target depthtrack_cli depthtrack_bench ${TESTS:+depthtrack_tests} \
    >"$out/build.log" 2>&1 || { grep -E "error" "$out/build.log" | head -30; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
git log --oneline -1 2>/dev/null || true
variant_dir() { # name source -> folder to point DEPTHTRACK_KERNEL_DIR at ("" for the embedded kernels)
  local name=$1 source=$2
  if [[ $source == embedded || $source == env:* ]]; then echo ""
  elif [[ -d $source ]]; then realpath "$source"
  else mkdir -p "/tmp/variants/$name" && git archive "$source" cl | tar -x -C "/tmp/variants/$name" --strip-components=1 &&
    echo "/tmp/variants/$name"; fi
}
IFS=';' read -r -a cases <<<"${CASES:---particles 100000,1000000,1500000 --frames 10 --no-global --occlusion-window 32x24}"
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  for pair in ${VARIANTS:-embedded=embedded}; do
    name=${pair%%=*} source=${pair#*=} dir=$(variant_dir "${pair%%=*}" "${pair#*=}") || exit 1
    setting=()
    [[ $source == env:* ]] && setting=("${source#env:}")
    for c in "${cases[@]}"; do
      echo "== $b $name: $c"
      # shellcheck disable=SC2086
      env "${setting[@]}" DEPTHTRACK_KERNEL_DIR="$dir" "$build/depthtrack_bench" --backend "$b" $c |
        tee -a "$out/variants.csv" | grep -E "${ROWS:-,(total_ms|weigh_ms|refine_ms|refine_share|status),}" | cut -d, -f1,5-
    done
    if [[ ${MULTI:-0} == 1 ]]; then
      echo "== $b $name: multi-objects"
      env "${setting[@]}" DEPTHTRACK_KERNEL_DIR="$dir" "$build/depthtrack_bench" --multi-objects --backend "$b" \
        --particles 2000 | tee -a "$out/multi.csv" | grep -E "_ms,|ratio" | cut -d, -f1,5-
    fi
  done
done 2>&1 | tee "$out/variants.txt"
[[ -z ${TESTS:-} ]] && exit 0
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  echo "== tests $b"
  DEPTHTRACK_TEST_DEVICE=$b "$build/tests/depthtrack_tests" "$TESTS" 2>&1 |
    grep -E "worst relative|test cases|FAILED|failed" | cut -c1-260 | head -30
done 2>&1 | tee "$out/tests.txt"
