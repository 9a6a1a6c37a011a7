#!/usr/bin/env bash
# Peer comparison: depthtrack against the trackers users pick instead, on the same frames from
# the same starts, printed as one Markdown table: PCL's KLD-adaptive particle filter tracker (pcl::tracking,
# bench/peers/pcl_tracking.cpp), ViSP's model-based tracker on its dense depth features
# (vpMbGenericTracker, bench/peers/visp_tracking.cpp) and ICG (Iterative Corresponding Geometry,
# bench/peers/icg_tracking.cpp: its depth modality alone, and depth + region where the clip has colour).
# Needs libpcl-dev and libvisp-dev (for pcl and visp), ICG's library built outside this repository (for
# icg: ICG_DIR and ICG_LIBRARY, xvfb-run) and ../shared/data (meshes, the YCB-Video clips).
#
#   bash scripts/compare-peers.sh            # builds build-peers/, writes into $WORK, prints the table
#   PEERS=icg ICG_DIR=<3DObjectTracking>/ICG ICG_LIBRARY=<its build>/libicg.a SEEDS="1 2 3" \
#     ONLY=ycbv-0000 bash scripts/compare-peers.sh   # depthtrack and ICG on ycbv-0000, three starts
#
# Environment: BUILD (build folder, default build-peers), CMAKE_ARGS (extra configure options), WORK
# (sequences and CSVs, default /tmp/depthtrack-peers), DEPTHTRACK_DATA_DIR (default ../shared/data),
# PEERS (which peers beside depthtrack, default "pcl visp", with icg added when ICG_DIR is set),
# SEEDS (the seeds of the start perturbation; each tracker runs once per seed and its row is the mean,
# with the range in brackets; default 1), ONLY (run only the sequences whose label matches this
# extended regular expression), DT_VARIANTS (all, the default: depthtrack's variant rows as well;
# default: its default row only), DT_ARGS (extra `depthtrack track` options, e.g. "--backend opencl"), PCL_ARGS,
# VISP_ARGS, ICG_ARGS (extra options of each runner), VISP_RESOLUTION (the depth ViSP fits, default
# 320x240: its faces need pixels, and at 80x60 a fine mesh's triangles hold none), ICG_RESOLUTION
# (default 640x480, the sensor's: ICG probes the image along normals in metres), ICG_CACHE (ICG's
# generated models, default $WORK/icg-models: they take minutes per object, so keep the folder),
# JOBS (build parallelism for the library, default 2; the PCL file always builds with -j1), PCL_RUNS
# (PCL cannot be seeded: it runs this many times per seed, default 3).
# The sequences are written once and reused; delete $WORK to make them again. Each row is also written
# to ROWS_FILE (default $WORK/rows.md, emptied first) as soon as it is scored, so an interrupted run keeps
# what it measured.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${BUILD:-$ROOT/build-peers}
WORK=${WORK:-/tmp/depthtrack-peers}
DATA=${DEPTHTRACK_DATA_DIR:-$ROOT/../shared/data}
JOBS=${JOBS:-2}
PCL_RUNS=${PCL_RUNS:-3}
ICG_DIR=${ICG_DIR:-}
ICG_LIBRARY=${ICG_LIBRARY:-}
PEERS=${PEERS:-pcl visp${ICG_DIR:+ icg}}
SEEDS=${SEEDS:-1}
ONLY=${ONLY:-}
DT_VARIANTS=${DT_VARIANTS:-all}
read -r -a DT_EXTRA <<<"${DT_ARGS:-}"
read -r -a PCL_EXTRA <<<"${PCL_ARGS:-}"
read -r -a VISP_EXTRA <<<"${VISP_ARGS:-}"
read -r -a ICG_EXTRA <<<"${ICG_ARGS:-}"
read -r -a CMAKE_EXTRA <<<"${CMAKE_ARGS:-}"
read -r -a SEED_LIST <<<"$SEEDS"
VISP_RESOLUTION=${VISP_RESOLUTION:-320x240}
ICG_RESOLUTION=${ICG_RESOLUTION:-640x480}
ICG_CACHE=${ICG_CACHE:-$WORK/icg-models}
HANDSET=$DATA/meshes/dbot/handset.obj
YCBV=$DATA/sequences/ycbv-0000
YCBV49=$DATA/sequences/ycbv-0049
for f in "$HANDSET" "$YCBV/gt.json" "$YCBV49/gt.json"; do
  [[ -e $f ]] || { echo "compare-peers: missing $f (set DEPTHTRACK_DATA_DIR)" >&2; exit 1; }
done
uses() { [[ " $PEERS " == *" $1 "* ]]; }
for p in $PEERS; do
  [[ $p == pcl || $p == visp || $p == icg ]] || { echo "compare-peers: PEERS has '$p' (pcl, visp, icg)" >&2; exit 1; }
done
[[ ${#SEED_LIST[@]} -gt 0 ]] || { echo "compare-peers: SEEDS is empty" >&2; exit 1; }
if uses icg; then
  [[ -f $ICG_DIR/include/icg/tracker.h && -f $ICG_LIBRARY ]] ||
    { echo "compare-peers: icg needs ICG_DIR (ICG's source folder) and ICG_LIBRARY (its built libicg.a)" >&2; exit 1; }
  command -v xvfb-run >/dev/null || { echo "compare-peers: icg needs xvfb-run (ICG makes its models with OpenGL)" >&2; exit 1; }
fi

mkdir -p "$WORK"
echo "== building in $BUILD" >&2
CONFIGURE=(-DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_BUILD_BENCH=OFF)
TARGETS=()
if uses pcl || uses visp; then
  CONFIGURE+=(-DDEPTHTRACK_BUILD_PEERS=ON)
  uses pcl && TARGETS+=(depthtrack_pcl_tracking)
  uses visp && TARGETS+=(depthtrack_visp_tracking)
else
  CONFIGURE+=(-DDEPTHTRACK_BUILD_PEERS=OFF)
fi
if uses icg; then
  CONFIGURE+=("-DDEPTHTRACK_ICG_DIR=$ICG_DIR" "-DDEPTHTRACK_ICG_LIBRARY=$ICG_LIBRARY")
  TARGETS+=(depthtrack_icg_tracking)
fi
cmake -S "$ROOT" -B "$BUILD" -G Ninja "${CONFIGURE[@]}" "${CMAKE_EXTRA[@]}" >"$WORK/cmake.log" 2>&1 ||
  { cat "$WORK/cmake.log" >&2; exit 1; }
cmake --build "$BUILD" -j"$JOBS" --target depthtrack_cli depthtrack_peer_score >&2
cmake --build "$BUILD" -j1 --target "${TARGETS[@]}" depthtrack_import_visp_simulated >&2
DT=$BUILD/depthtrack
PCL=$BUILD/depthtrack_pcl_tracking
VISP=$BUILD/depthtrack_visp_tracking
ICG=$BUILD/depthtrack_icg_tracking
SCORE=$BUILD/depthtrack_peer_score

# Options that exist only after the precision work is merged are used when the binary has them.
has_option() { [[ $("$DT" "$1" --help 2>&1) == *"$2"* ]]; }

synth() {  # name, options...
  local name=$1
  shift
  [[ -f $WORK/$name/sequence.json ]] || "$DT" synth --mesh "$HANDSET" --out "$WORK/$name" "$@" >&2
}

ms_per_frame() {  # the mean over logs of the "N frames in S s" line every tracker prints
  sed -n 's/^\([0-9]*\) frames in \([0-9.]*\) s.*/\1 \2/p' "$@" |
    awk '{ if ($1 > 0) { s += 1000 * $2 / $1; n++ } } END { if (n) printf "%.1f", s / n; else printf "n/a" }'
}

ROWS=()
ROWS_FILE=${ROWS_FILE:-$WORK/rows.md}
: >"$ROWS_FILE"
row() {  # label, tracker, CSVs and logs of its runs (csv log csv log ...), scored as one row
  local label=$1 tracker=$2 csvs=() logs=()
  shift 2
  while [[ $# -gt 0 ]]; do
    csvs+=("$1")
    logs+=("$2")
    shift 2
  done
  local r
  r=$("$SCORE" "${SCORE_COMMON[@]}" --csv "${csvs[@]}" --label "$label" --tracker "$tracker" \
    --ms-per-frame "$(ms_per_frame "${logs[@]}")")
  ROWS+=("$r")
  echo "$r" | tee -a "$ROWS_FILE" >&2
}

runs_label() { [[ $1 == 1 ]] && echo "1 start" || echo "$1 starts"; }

# label, mesh, sequence, object ("" for none), resolution, extra ICG options
compare() {
  local label=$1 mesh=$2 seq=$3 object=$4 res=$5 icg_extra=() tag
  read -r -a icg_extra <<<"${6:-}"
  [[ -z $ONLY || $label =~ $ONLY ]] || return 0
  tag=$(echo "$label" | tr ' /' '__')
  local object_args=()
  [[ -n $object ]] && object_args=(--object "$object")
  local input=(--mesh "$mesh" --sequence "$seq" "${object_args[@]}")
  SCORE_COMMON=("${input[@]}")
  local starts
  starts=$(runs_label "${#SEED_LIST[@]}")
  # Each variant: "label|options" (the label names the row, the options go to `depthtrack track`).
  local variants=("|")
  if [[ $DT_VARIANTS == all ]]; then
    has_option track --refine && variants+=("--refine off|--refine off")
    # The fit at half the filter's depth noise (Refinement::noise_scale), where the binary has it.
    if "$DT" config --dump 2>/dev/null | grep -q noise_scale; then
      echo '{"refine": {"noise_scale": 0.5}}' >"$WORK/fit-noise-half.json"
      variants+=("fit noise 0.5|--config $WORK/fit-noise-half.json")
    fi
  fi
  for v in "${variants[@]}"; do
    local extra=() name="depthtrack, 200 particles, $res" variant_label=${v%%|*} runs=()
    read -r -a extra <<<"${v#*|}"
    [[ -n $variant_label ]] && name="$name, $variant_label"
    for seed in "${SEED_LIST[@]}"; do
      local out=$WORK/$tag-depthtrack-$(echo "${variant_label:-default}" | tr -d ' -.')-seed$seed
      echo "== $label: depthtrack ${extra[*]} seed $seed" >&2
      "$DT" track "${input[@]}" --resolution "$res" --out "$out.csv" --particles 200 --init-from-gt \
        --init-perturb "0.01 5" --seed "$seed" "${extra[@]}" "${DT_EXTRA[@]}" >"$out.log"
      runs+=("$out.csv" "$out.log")
    done
    row "$label" "$name, $starts" "${runs[@]}"
  done
  if uses pcl; then
    # PCL seeds its random numbers from std::random_device: every run differs, so it runs PCL_RUNS
    # times per start; its particle count is the mean over the frames of the first run.
    local runs=() particles=""
    for seed in "${SEED_LIST[@]}"; do
      for run in $(seq 1 "$PCL_RUNS"); do
        local out=$WORK/$tag-pcl-seed$seed-$run
        echo "== $label: PCL, seed $seed, run $run of $PCL_RUNS" >&2
        "$PCL" "${input[@]}" --resolution "$res" --out "$out.csv" --init-perturb "0.01 5" --seed "$seed" \
          "${PCL_EXTRA[@]}" >"$out.log"
        runs+=("$out.csv" "$out.log")
        [[ -n $particles ]] || particles=$(sed -n 's/^mean particles \([0-9]*\).*/\1/p' "$out.log")
      done
    done
    row "$label" "PCL KLD, $particles particles, $res, $starts x $PCL_RUNS runs" "${runs[@]}"
  fi
  if uses visp; then
    # ViSP's fitter has no randomness: one run per start. It fits its own resolution (VISP_RESOLUTION).
    local runs=() failed=0
    for seed in "${SEED_LIST[@]}"; do
      local out=$WORK/$tag-visp-seed$seed
      echo "== $label: ViSP seed $seed" >&2
      "$VISP" "${input[@]}" --resolution "$VISP_RESOLUTION" --out "$out.csv" --init-perturb "0.01 5" \
        --seed "$seed" "${VISP_EXTRA[@]}" >"$out.log" 2>"$out.err"
      runs+=("$out.csv" "$out.log")
      failed=$((failed + $(sed -n 's/.*, \([0-9]*\) frames failed/\1/p' "$out.log")))
    done
    row "$label" "ViSP dense depth, $VISP_RESOLUTION, $starts, $failed frames failed" "${runs[@]}"
  fi
  if uses icg; then
    # ICG: its depth modality alone (the like-for-like peer of a depth tracker), and with its region
    # modality too where the clip has colour images. Deterministic: one run per start.
    local modalities=(depth)
    compgen -G "$seq/*-color.png" >/dev/null && modalities+=(depth+region)
    for m in "${modalities[@]}"; do
      local runs=() failed=0
      for seed in "${SEED_LIST[@]}"; do
        local out=$WORK/$tag-icg-${m/+/-}-seed$seed
        echo "== $label: ICG $m seed $seed" >&2
        xvfb-run -a "$ICG" "${input[@]}" --resolution "$ICG_RESOLUTION" --out "$out.csv" --init-perturb "0.01 5" \
          --seed "$seed" --modalities "$m" --cache-dir "$ICG_CACHE" "${icg_extra[@]}" "${ICG_EXTRA[@]}" \
          >"$out.log" 2>"$out.err" || { cat "$out.err" >&2; exit 1; }
        runs+=("$out.csv" "$out.log")
        failed=$((failed + $(sed -n 's/.*, \([0-9]*\) frames failed/\1/p' "$out.log")))
      done
      row "$label" "ICG $m, $ICG_RESOLUTION, $starts, $failed frames failed" "${runs[@]}"
    done
  fi
}

# The real clips first, then ViSP's castle, then the synthetic handsets.
for o in 009_gelatin_box 025_mug 061_foam_brick; do
  compare "ycbv-0000 $o" "$DATA/meshes/ycb/$o.obj" "$YCBV" "$o" 160x120
done
for o in 004_sugar_box 007_tuna_fish_can 010_potted_meat_can 024_bowl; do
  compare "ycbv-0049 $o" "$DATA/meshes/ycb/$o.obj" "$YCBV49" "$o" 160x120
done
# ViSP's own simulated castle (noise-free, exact ground truth: where the fit's precision was first measured),
# converted once into depthtrack's layout. Its model is to be drawn without back-face culling.
CASTLE=$DATA/sequences/visp-castle-simu
if [[ -d $CASTLE && (-z $ONLY || visp-castle =~ $ONLY) ]]; then
  [[ -f $WORK/visp-castle/sequence.json ]] ||
    "$BUILD/depthtrack_import_visp_simulated" --in "$CASTLE" --out "$WORK/visp-castle" >&2
  compare "visp-castle" "$CASTLE/Models/DERIVED_chateau_plus_cube_triangulated.obj" "$WORK/visp-castle" "" 160x120 \
    "--culling false"
fi
HANDSETS=()
if [[ -z $ONLY || handset-sl-occ30 =~ $ONLY ]]; then
  synth handset-sl-occ30 --occluder 0.3
  HANDSETS+=("handset-sl-occ30")
fi
if has_option synth --sensor && [[ -z $ONLY || handset-ideal =~ $ONLY ]]; then
  synth handset-ideal --sensor ideal --occluder 0
  HANDSETS+=("handset-ideal")
fi
for s in "${HANDSETS[@]}"; do compare "$s" "$HANDSET" "$WORK/$s" "" 80x60; done

echo
echo "All from ground truth moved by exactly 1 cm / 5 deg (seeds: $SEEDS); errors over every frame; one CPU thread each;"
echo "several starts (or PCL's runs): the mean over the runs, with the range in brackets."
echo "ms/frame: wall-clock time of the tracking loop (depth loading included) over the frames, mean over the runs."
echo "ViSP rows: vpMbGenericTracker with depth dense features alone, at its own resolution; a failed frame keeps the last pose."
echo "ICG rows: ICG's own YCB-Video settings; its models are made once (not timed) and cached in $ICG_CACHE."
echo
echo "| sequence / object | tracker | mean translation mm | max mm | mean rotation deg | mean ADD-S mm | last-frame ADD-S mm | ADD-S AUC 0-100 mm % | ms/frame |"
echo "|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${ROWS[@]}"
