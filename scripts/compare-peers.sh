#!/usr/bin/env bash
# Peer comparison (issue 8): depthtrack against the trackers users pick instead, on the same frames from
# the same starts, printed as one Markdown table: PCL's KLD-adaptive particle filter tracker (pcl::tracking,
# bench/peers/pcl_tracking.cpp) and ViSP's model-based tracker on its dense depth features
# (vpMbGenericTracker, bench/peers/visp_tracking.cpp). Needs libpcl-dev, libvisp-dev and ../shared/data
# (meshes, the YCB-Video clip).
#
#   bash scripts/compare-peers.sh            # builds build-peers/, writes into $WORK, prints the table
#
# Environment: BUILD (build folder, default build-peers), WORK (sequences and CSVs, default
# /tmp/depthtrack-peers), DEPTHTRACK_DATA_DIR (default ../shared/data), DT_ARGS (extra
# `depthtrack track` options, e.g. "--backend opencl"), PCL_ARGS (extra options of the PCL runner),
# VISP_ARGS (extra options of the ViSP runner), VISP_RESOLUTION (the depth ViSP fits, default 320x240:
# its faces need pixels, and at 80x60 a fine mesh's triangles hold none),
# JOBS (build parallelism for the library, default 2; the PCL file always builds with -j1), PCL_RUNS
# (PCL cannot be seeded: its rows are the mean of this many runs, default 3, with the range in brackets).
# The sequences are written once and reused; delete $WORK to make them again.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${BUILD:-$ROOT/build-peers}
WORK=${WORK:-/tmp/depthtrack-peers}
DATA=${DEPTHTRACK_DATA_DIR:-$ROOT/../shared/data}
JOBS=${JOBS:-2}
PCL_RUNS=${PCL_RUNS:-3}
read -r -a DT_EXTRA <<<"${DT_ARGS:-}"
read -r -a PCL_EXTRA <<<"${PCL_ARGS:-}"
read -r -a VISP_EXTRA <<<"${VISP_ARGS:-}"
VISP_RESOLUTION=${VISP_RESOLUTION:-320x240}
HANDSET=$DATA/meshes/dbot/handset.obj
YCBV=$DATA/sequences/ycbv-0000
for f in "$HANDSET" "$YCBV/gt.json"; do
  [[ -e $f ]] || { echo "compare-peers: missing $f (set DEPTHTRACK_DATA_DIR)" >&2; exit 1; }
done

mkdir -p "$WORK"
echo "== building in $BUILD" >&2
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_PEERS=ON \
  -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_BUILD_BENCH=OFF >"$WORK/cmake.log" 2>&1 ||
  { cat "$WORK/cmake.log" >&2; exit 1; }
cmake --build "$BUILD" -j"$JOBS" --target depthtrack_cli depthtrack_peer_score >&2
cmake --build "$BUILD" -j1 --target depthtrack_pcl_tracking depthtrack_visp_tracking \
  depthtrack_import_visp_simulated >&2
DT=$BUILD/depthtrack
PCL=$BUILD/depthtrack_pcl_tracking
VISP=$BUILD/depthtrack_visp_tracking
SCORE=$BUILD/depthtrack_peer_score

# Options that exist only after the precision work is merged are used when the binary has them.
has_option() { [[ $("$DT" "$1" --help 2>&1) == *"$2"* ]]; }

synth() {  # name, options...
  local name=$1
  shift
  [[ -f $WORK/$name/sequence.json ]] || "$DT" synth --mesh "$HANDSET" --out "$WORK/$name" "$@" >&2
}
synth handset-sl-occ30 --occluder 0.3
SEQUENCES=("handset-sl-occ30")
if has_option synth --sensor; then
  synth handset-ideal --sensor ideal --occluder 0
  SEQUENCES+=("handset-ideal")
fi

ms_per_frame() {  # the "N frames in S s" line both trackers print
  sed -n 's/^\([0-9]*\) frames in \([0-9.]*\) s.*/\1 \2/p' "$1" | awk '{ if ($1 > 0) printf "%.1f", 1000 * $2 / $1 }'
}

ROWS=()
# label, mesh, sequence, object ("" for none), resolution
compare() {
  local label=$1 mesh=$2 seq=$3 object=$4 res=$5 tag
  tag=$(echo "$label" | tr ' /' '__')
  local object_args=()
  [[ -n $object ]] && object_args=(--object "$object")
  local common=(--mesh "$mesh" --sequence "$seq" "${object_args[@]}" --resolution "$res")
  # Each variant: "label|options" (the label names the row, the options go to `depthtrack track`).
  local variants=("|")
  has_option track --refine && variants+=("--refine off|--refine off")
  # The fit at half the filter's depth noise (Refinement::noise_scale), where the binary has it.
  if "$DT" config --dump 2>/dev/null | grep -q noise_scale; then
    echo '{"refine": {"noise_scale": 0.5}}' >"$WORK/fit-noise-half.json"
    variants+=("fit noise 0.5|--config $WORK/fit-noise-half.json")
  fi
  for v in "${variants[@]}"; do
    local extra=() name="depthtrack, 200 particles" variant_label=${v%%|*}
    read -r -a extra <<<"${v#*|}"
    [[ -n $variant_label ]] && name="$name, $variant_label"
    local out=$WORK/$tag-depthtrack-$(echo "${variant_label:-default}" | tr -d ' -.')
    echo "== $label: depthtrack ${extra[*]}" >&2
    "$DT" track "${common[@]}" --out "$out.csv" --particles 200 --init-from-gt --init-perturb "0.01 5" \
      "${extra[@]}" "${DT_EXTRA[@]}" >"$out.log"
    ROWS+=("$("$SCORE" --mesh "$mesh" --sequence "$seq" "${object_args[@]}" --csv "$out.csv" --label "$label" \
      --tracker "$name" --ms-per-frame "$(ms_per_frame "$out.log")")")
  done
  # PCL seeds its random numbers from std::random_device: every run differs, so run it PCL_RUNS times.
  local csvs=() ms=() particles=()
  for run in $(seq 1 "$PCL_RUNS"); do
    local out=$WORK/$tag-pcl-$run
    echo "== $label: PCL, run $run of $PCL_RUNS" >&2
    "$PCL" "${common[@]}" --out "$out.csv" --init-perturb "0.01 5" "${PCL_EXTRA[@]}" >"$out.log"
    csvs+=("$out.csv")
    ms+=("$(ms_per_frame "$out.log")")
    particles+=("$(sed -n 's/^mean particles \([0-9]*\).*/\1/p' "$out.log")")
  done
  local runs="$PCL_RUNS runs" ms_mean
  [[ $PCL_RUNS == 1 ]] && runs="1 run"
  ms_mean=$(printf '%s\n' "${ms[@]}" | awk '{ s += $1 } END { printf "%.1f", s / NR }')
  ROWS+=("$("$SCORE" --mesh "$mesh" --sequence "$seq" "${object_args[@]}" --csv "${csvs[@]}" --label "$label" \
    --tracker "PCL KLD, ${particles[0]} particles, $runs" --ms-per-frame "$ms_mean")")
  # ViSP's fitter has no randomness: one run. It fits its own resolution (VISP_RESOLUTION).
  local out=$WORK/$tag-visp
  echo "== $label: ViSP" >&2
  "$VISP" --mesh "$mesh" --sequence "$seq" "${object_args[@]}" --resolution "$VISP_RESOLUTION" --out "$out.csv" \
    --init-perturb "0.01 5" "${VISP_EXTRA[@]}" >"$out.log" 2>"$out.err"
  ROWS+=("$("$SCORE" --mesh "$mesh" --sequence "$seq" "${object_args[@]}" --csv "$out.csv" --label "$label" \
    --tracker "ViSP dense depth, $VISP_RESOLUTION, $(sed -n 's/.*, \([0-9]*\) frames failed/\1 frames failed/p' "$out.log")" \
    --ms-per-frame "$(ms_per_frame "$out.log")")")
}

for s in "${SEQUENCES[@]}"; do compare "$s" "$HANDSET" "$WORK/$s" "" 80x60; done
# ViSP's own simulated castle (noise-free, exact ground truth: where issue 8's precision was first measured),
# converted once into depthtrack's layout.
CASTLE=$DATA/sequences/visp-castle-simu
if [[ -d $CASTLE ]]; then
  [[ -f $WORK/visp-castle/sequence.json ]] ||
    "$BUILD/depthtrack_import_visp_simulated" --in "$CASTLE" --out "$WORK/visp-castle" >&2
  compare "visp-castle" "$CASTLE/Models/DERIVED_chateau_plus_cube_triangulated.obj" "$WORK/visp-castle" "" 160x120
fi
for o in 009_gelatin_box 025_mug 061_foam_brick; do
  compare "ycbv-0000 $o" "$DATA/meshes/ycb/$o.obj" "$YCBV" "$o" 160x120
done

echo
echo "All from ground truth moved by exactly 1 cm / 5 deg (seed 1); errors over every frame; one CPU thread each;"
echo "PCL rows: mean over its runs (range in brackets); PCL's particle count is its mean over the frames of run 1."
echo "ViSP rows: vpMbGenericTracker with depth dense features alone, at its own resolution; a failed frame keeps the last pose."
echo
echo "| sequence / object | tracker | mean translation mm | max mm | mean rotation deg | last-frame ADD-S mm | ms/frame |"
echo "|---|---|---|---|---|---|---|"
printf '%s\n' "${ROWS[@]}"
