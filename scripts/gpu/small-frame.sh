#!/usr/bin/env bash
# On the lent GPU machine, one call (about 8 minutes): the 2,000-particle frame (target 0.25 ms) and
# three objects against one (target 1.5x), then the kernels' and the filter's equivalence tests on each
# backend (TESTS=0 leaves them out), after where a single frame's enqueue goes (scripts/gpu/enqueue-profile.sh;
# PROFILE=0 leaves it out). OLD=<commit> also builds that commit and alternates it with this tree, so both
# see the same host (its tree from .devvariants/old where carried, prepared with `mkdir -p .devvariants/old
# && git archive <commit> | tar -x -C .devvariants/old`, as the device's copy may hold no git history; else
# from git there). 2,000 particles, 80x60, untimed steps as a tracker runs: the handset and the YCB mug at
# the 0.5 mm default, REPS (default 2) repetitions; the several-object ratios at the 0.5 mm default, also
# with every fit in one launch and, on CUDA, with the streams at one priority. Carry .devdeps, .device,
# .devdata (and .devvariants with OLD).
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
flags=(-G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF
  -DDEPTHTRACK_PYTHON=OFF)
trees=(build-gpu)
if [[ -n ${OLD:-} ]]; then
  mkdir -p /tmp/old-tree
  if [[ -d .devvariants/old ]]; then cp -r .devvariants/old/. /tmp/old-tree/
  else git archive "$OLD" | tar -x -C /tmp/old-tree || exit 1; fi
  cmake -S /tmp/old-tree -B /tmp/old-tree/build "${flags[@]}" -DDEPTHTRACK_BUILD_TESTS=OFF >/tmp/old-configure.log 2>&1 &&
    cmake --build /tmp/old-tree/build -j"$(nproc)" --target depthtrack_bench >/tmp/old-build.log 2>&1 ||
    { tail -20 /tmp/old-build.log; exit 1; }
  trees=(/tmp/old-tree/build build-gpu)
fi
cmake -S . -B build-gpu "${flags[@]}" -DDEPTHTRACK_BUILD_TESTS=ON >/tmp/new-configure.log 2>&1 &&
  cmake --build build-gpu -j"$(nproc)" --target depthtrack_bench depthtrack_tests >/tmp/new-build.log 2>&1 ||
  { tail -20 /tmp/new-build.log; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
echo "${OLD:+old $OLD, }new $(git log --oneline -1 2>/dev/null | cut -c1-7)"
rows=',(total_ms|upload_ms|enqueue_ms|wait_ms),'
for rep in $(seq "${REPS:-2}"); do
  for b in cuda opencl:nvidia; do
    for mesh in "" "--mesh .devdata/meshes/ycb/025_mug.obj --simplify-error 0.0005"; do
      for tree in "${trees[@]}"; do
        echo "$b ${tree%%/build*} ${mesh:+mug}: $("$tree/depthtrack_bench" --backend "$b" --particles 2000 --frames 60 \
          --no-global --untimed-steps $mesh | grep -E "$rows" | cut -d, -f6,8 | tr '\n' ' ')"
      done
    done
  done
done
# The handset's frames handed over 5 ms apart, as a sensor stream leaves the device idle between frames
# (back to back, each frame's calls meet the last one's work, as the enqueue profile found).
for b in cuda opencl:nvidia; do
  echo "$b handset paced 5 ms: $(build-gpu/depthtrack_bench --backend "$b" --particles 2000 --frames 60 --no-global \
    --untimed-steps --pace 5 | grep -E "$rows" | cut -d, -f6,8 | tr '\n' ' ')"
done
for b in cuda opencl:nvidia; do
  for tree in "${trees[@]}"; do
    echo "$b ${tree%%/build*} three ycbv objects:"
    "$tree/depthtrack_bench" --multi-objects --backend "$b" --particles 2000 --untimed-steps --simplify-error 0.0005 \
      --frames 40 | grep -E "multi_object_ratio|occlusion_off.*(one_object|three_objects)_(enqueue|collect|upload_sum|steps_sum)_ms" |
      cut -d, -f5-
  done
done
# CUDA's streams at one priority (the earlier default) against the queues' ranked priorities.
for priorities in off on; do
  echo "cuda three ycbv objects, stream priorities $priorities:"
  DEPTHTRACK_CUDA_STREAM_PRIORITIES=$priorities build-gpu/depthtrack_bench --multi-objects --backend cuda \
    --particles 2000 --untimed-steps --simplify-error 0.0005 --frames 40 |
    grep -E "multi_object_ratio|occlusion_off.*three_objects_(enqueue|collect)_ms" | cut -d, -f5-
done
# The new tree's device time per step (timed steps: each kernel's event), the handset.
for b in cuda opencl:nvidia; do
  echo "$b timed steps: $(build-gpu/depthtrack_bench --backend "$b" --particles 2000 --frames 60 --no-global |
    grep -E ',(propagate|weigh|resample|refine|upload|enqueue|wait|total)_ms,' | cut -d, -f6,8 | tr '\n' ' ')"
done
# The mug at 0.5 mm has 3,196 triangles, so auto spreads its fit (19 launches on OpenCL) where the other
# two fit in one launch: its one-launch frame alone and the three objects with every fit in one launch.
for rep in 1 2; do
  for layout in spread one-launch; do
    echo "cuda handset $layout: $(build-gpu/depthtrack_bench --backend cuda --particles 2000 --frames 60 \
      --no-global --untimed-steps --refine-layout "$layout" | grep -E ',total_ms,' | cut -d, -f8)"
    echo "opencl:nvidia mug $layout: $(build-gpu/depthtrack_bench --backend opencl:nvidia --particles 2000 --frames 60 \
      --no-global --untimed-steps --mesh .devdata/meshes/ycb/025_mug.obj --simplify-error 0.0005 \
      --refine-layout "$layout" | grep -E ',total_ms,' | cut -d, -f8)"
  done
done
for b in cuda opencl:nvidia; do
  echo "$b three ycbv objects, every fit one-launch:"
  build-gpu/depthtrack_bench --multi-objects --backend "$b" --particles 2000 --untimed-steps \
    --simplify-error 0.0005 --frames 40 --refine-layout one-launch | grep -E "multi_object_ratio" | cut -d, -f5-
done
if [[ ${PROFILE:-1} == 1 ]]; then bash scripts/gpu-run.sh enqueue-profile; fi
[[ ${TESTS:-1} == 1 ]] || exit 0
source scripts/lib/device-tests.sh
device_tests build-gpu/tests/depthtrack_tests "[kernels],[refine],[device],[multi]"
