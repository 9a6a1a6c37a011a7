#!/usr/bin/env bash
# On the lent GPU machine (a few minutes): where DeviceFilter::enqueue_update's host time goes in the
# single-object bench, whose enqueue took 0.17-0.22 ms on an H100 against 0.035-0.05 ms for the same
# filter inside `--multi-objects`. A copy of this tree gets
# scripts/probes/enqueue-profile.patch (a stopwatch lap after each part of enqueue_update, their
# medians and means printed per filter at exit when DT_ENQUEUE_PROFILE is set; not for the tree itself),
# then the handset and the gelatin box run on both backends, and the several-object bench (ycbv-0000's
# three objects: which object's enqueue costs what). Carry .devdeps, .device and .devdata.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
copy=/tmp/enqueue-profile
rm -rf "$copy" && mkdir -p "$copy" && cp -r cl cmake include src bench tests shaders python fuzz CMakeLists.txt "$copy"/ &&
  (cd "$copy" && patch -p1 <"$OLDPWD/scripts/probes/enqueue-profile.patch") || exit 1
cmake -S "$copy" -B "$copy/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_PYTHON=OFF >/tmp/profile-configure.log 2>&1 &&
  cmake --build "$copy/build" -j"$(nproc)" --target depthtrack_bench >/tmp/profile-build.log 2>&1 ||
  { tail -20 /tmp/profile-build.log; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for b in cuda opencl:nvidia; do
  for mesh in "" "--mesh .devdata/meshes/ycb/009_gelatin_box.obj --simplify-error 0.0005"; do
    echo "== $b ${mesh:+gelatin box}"
    # The profile line goes to stderr at exit; the bench's rows are CSV (metric in field 6, median in 8).
    DT_ENQUEUE_PROFILE=1 "$copy/build/depthtrack_bench" --backend "$b" --particles 2000 --frames 100 --no-global \
      --untimed-steps $mesh 2>&1 | grep -E 'enqueue profile|,(upload|enqueue|wait|total)_ms,' |
      sed -E 's/^[^"]*"[^"]*",-,[^,]*,([a-z_]+),ms,([0-9.]+)$/\1 \2/'
  done
done
# The several-object bench: its filters in the order they first enqueue (each object alone, then the three
# objects with mutual occlusion off and on, then on one host thread): 0-2, 3-5 (off), 6-8 (on), ...
for b in cuda opencl:nvidia; do
  echo "== $b, ycbv-0000's three objects (gelatin box, mug, foam brick)"
  DT_ENQUEUE_PROFILE=1 "$copy/build/depthtrack_bench" --multi-objects --backend "$b" --particles 2000 --frames 40 \
    --untimed-steps --simplify-error 0.0005 2>&1 | grep -E 'enqueue profile|occlusion_off_untimed,(multi_object_ratio_to_mean|three_objects_enqueue_ms)'
done
