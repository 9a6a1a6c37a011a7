#!/usr/bin/env bash
# On the lent GPU machine's CPUs: the mesh fuzz campaign, several formats at once, each with its own
# workers (FUZZ="obj:14 off:1" = format:jobs), until 1 M executions or MAX_SECONDS. The fuzz targets
# are built here with clang (scripts/fuzz-campaign.sh) and carried (build-fuzz-mesh/fuzz/fuzz_mesh_*);
# the replays through the guard (replay_mesh_<format>) are built there. Tables and logs go to $OUT.
set -uo pipefail
source .device/enter .devdeps
out=${OUT:-/tmp/depthtrack-gpu-fuzz}
mkdir -p "$out"
generator=$(command -v ninja >/dev/null && echo Ninja || echo "Unix Makefiles")
cmake -S . -B build-gpu -G "$generator" -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_SANITIZE_SUITE=OFF \
  -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF >"$out/configure.log" 2>&1 || { tail -30 "$out/configure.log"; exit 1; }
targets=()
for spec in ${FUZZ:-obj:14}; do targets+=("replay_mesh_${spec%%:*}"); done
cmake --build build-gpu -j"$(nproc)" --target "${targets[@]}" >"$out/build.log" 2>&1 ||
  { grep -E "error|Error" "$out/build.log" | head -30; exit 1; }
lscpu | grep -E "Model name|^CPU\(s\)" | tee "$out/cpu.txt"
pids=()
for spec in ${FUZZ:-obj:14}; do
  f=${spec%%:*} jobs=${spec##*:}
  scripts/fuzz-campaign.sh --formats "$f" --jobs "$jobs" --no-build --fuzz-build build-fuzz-mesh \
    --replay-build build-gpu --nice 0 --max-seconds "${MAX_SECONDS:-420}" --out /tmp/fz >"$out/table-$f.txt" 2>&1 &
  pids+=($!)
done
for p in "${pids[@]}"; do wait "$p"; done
cat "$out"/table-*.txt
tar czf "$out/logs.tgz" -C /tmp/fz --exclude=corpus . 2>/dev/null
