#!/usr/bin/env bash
# On the lent GPU machine: one object against ycbv-0000's three in one process, 2,000 particles each at
# 80x60, per backend (target: three objects <= 1.5x one): `depthtrack_bench --multi-objects` prints
# multi_object_ratio rows (the median frame of one object and of three, and three / one) with mutual
# occlusion off and on, three over the mean of the three objects alone (multi_object_ratio_to_mean), the
# same without the host thread pool, and each stage's median: untimed, as a
# tracker runs by default (the bar), then with the steps timed (steps_sum, render_sum), both over FRAMES
# (default 40) frames of the ten-frame clip played forth and back. Then the same through `track` (mean
# per-frame latency after the first frame, the PNG decoding overlapped), as measured before the objects
# overlapped on the device. Carry .devdeps, .device and .devdata.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata
build=${BUILD_DIR:-build-gpu}
if [[ ! -x $build/depthtrack || ! -x $build/depthtrack_bench ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_BUILD_BENCH=ON \
    -DDEPTHTRACK_PYTHON=OFF >/tmp/multi-configure.log 2>&1 &&
    cmake --build "$build" -j"$(nproc)" --target depthtrack_cli depthtrack_bench >/tmp/multi-build.log 2>&1 ||
    { tail -20 /tmp/multi-build.log; exit 1; }
fi
particles=${PARTICLES:-2000}
# The meshes as given (the rows earlier sessions compare with) and at the tracker's default simplification
# (TrackerConfig::simplify_error, 0.5 mm), untimed; then as given with the steps timed.
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  for run in "--untimed-steps" "--untimed-steps --simplify-error 0.0005" ""; do
    "$build/depthtrack_bench" --multi-objects --backend "$b" --particles "$particles" --frames "${FRAMES:-40}" \
      $run | grep -v '^backend,' | awk -F, '{ print $1, $(NF-3), $(NF-2), $NF, $(NF-1) }'
  done
done
m=.devdata/meshes/ycb
q=.devdata/sequences/ycbv-0000
common=(--particles "$particles" --init-from-gt --init-perturb "0.01 5" --sequence "$q")
# Mean latency_ms over the frames after the first (its row carries the start-up); with several objects
# there is a row per object, each carrying the whole frame's latency.
mean_frame() { awk -F, -v objects="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "latency_ms") c = i; next }
  { f = (objects > 1) ? $2 : $1; if (f != first && first != "") { s += $c; n++ } if (first == "") first = f }
  END { printf "%.3f", (n ? s / n : 0) }' "$1"; }
for b in ${BACKENDS:-cuda opencl:nvidia}; do
  "$build/depthtrack" track --backend "$b" "${common[@]}" --mesh $m/025_mug.obj --object 025_mug --out /tmp/one.csv >/dev/null
  one=$(mean_frame /tmp/one.csv 1)
  for mo in off on; do
    "$build/depthtrack" track --backend "$b" "${common[@]}" --mesh $m/009_gelatin_box.obj --object 009_gelatin_box \
      --mesh $m/025_mug.obj --object 025_mug --mesh $m/061_foam_brick.obj --object 061_foam_brick \
      --mutual-occlusion "$mo" --out /tmp/three.csv >/dev/null
    three=$(mean_frame /tmp/three.csv 3)
    echo "track $b one object ${one} ms/frame, three objects (mutual occlusion $mo) ${three} ms/frame, ratio" \
      "$(awk -v a="$three" -v b="$one" 'BEGIN { printf "%.2f", a / b }')"
  done
done
