#!/usr/bin/env bash
# On the lent GPU machine (about 3 minutes with a carried binary): the depth in to pose out at
# 2,000 particles, 80x60, and where three objects spend their device time.
# - The handset's frame as the caller sees Tracker::update (update_ms) and as the filter times it
#   (total_ms): frames drawn before the timed loop (the bench's default),
#   drawn just before each update (--synthesize-inline, as before), and handed over 5 ms apart (--pace 5).
# - Each ycbv-0000 mesh's timed steps on the synthetic sequence, the fit's looser stop (2e-4 m) timed.
# - The three objects against one.
# BIN=<folder> runs a depthtrack_bench built elsewhere (with libdepthtrack.so.0 beside it: see the design
# notes, "A short device budget"); without it, this tree is built in build-gpu. Carry .devdeps, .device,
# .devdata (and BIN's folder).
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
if [[ -n ${BIN:-} ]]; then
  export LD_LIBRARY_PATH=$PWD/$BIN${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  bench=$PWD/$BIN/depthtrack_bench
else
  cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_PYTHON=OFF \
    >/tmp/configure.log 2>&1 && cmake --build build-gpu -j"$(nproc)" --target depthtrack_bench >/tmp/build.log 2>&1 ||
    { tail -20 /tmp/build.log; exit 1; }
  bench=$PWD/build-gpu/depthtrack_bench
fi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
# metric,median pairs of the rows named (fields 6 and 8 of the CSV).
rows() { grep -E ",($1)," | cut -d, -f6,8 | tr '\n' ' '; }
latency='upload_ms|enqueue_ms|wait_ms|total_ms|update_ms'
for rep in 1 2 3; do
  for b in cuda opencl:nvidia; do
    for feed in "" "--synthesize-inline" "--pace 5"; do
      echo "$b handset ${feed:-prepared}: $("$bench" --backend "$b" --particles 2000 --frames 60 --no-global \
        --untimed-steps $feed | rows "$latency")"
    done
  done
done
steps='weigh_ms|refine_ms|resample_ms|refine_iterations|total_ms'
for b in cuda opencl:nvidia; do
  for mesh in handset 009_gelatin_box 025_mug 061_foam_brick; do
    args=()
    [[ $mesh == handset ]] || args=(--mesh ".devdata/meshes/ycb/$mesh.obj" --simplify-error 0.0005)
    echo "$b $mesh timed: $("$bench" --backend "$b" --particles 2000 --frames 40 --no-global "${args[@]}" |
      rows "$steps")"
  done
  for converged in 0.00005 0.0002; do
    echo "$b handset untimed, fit stops below $converged m: $("$bench" --backend "$b" --particles 2000 --frames 60 \
      --no-global --untimed-steps --refine-converged $converged | rows 'refine_iterations|total_ms|update_ms')"
  done
done
for b in cuda opencl:nvidia; do
  echo "$b three ycbv objects:"
  "$bench" --multi-objects --backend "$b" --particles 2000 --untimed-steps --simplify-error 0.0005 --frames 40 |
    grep -E "multi_object_ratio|occlusion_off.*(one_object|three_objects)_(enqueue|collect)_ms" | cut -d, -f5-
done
