#!/usr/bin/env bash
# Fuzzes the mesh importer N executions per format and prints a table:
#   format, executions, seconds (wall), cpu_seconds, crashes, timeouts, ooms, guarded
# The libFuzzer targets fuzz_mesh_<format> run assimp in this process (fuzz/fuzz_mesh.cpp), in
# libFuzzer's fork mode (-fork=1: one worker at a time, one core) so that a crash or hang of assimp
# is counted, its input kept, and the campaign goes on. Every input that crashed, hung or ran out of
# memory is then replayed through the product's guard (replay_mesh_<format>: Mesh::load's child process)
# and must come back as an InputError in bounded time: "guarded" says how many did (of how many).
#
# Usage: scripts/fuzz-campaign.sh [--runs N] [--formats "obj ply stl off"] [--out DIR]
#                                 [--fuzz-build DIR] [--replay-build DIR] [--nice N] [--max-seconds S]
#                                 [--jobs N] [--timeout S] [--no-build]
#   --runs N          executions per format (default 1000000)
#   --max-seconds S   stop a format after S seconds even if N executions are not done (default: none)
#   --formats LIST    formats with a fuzz_mesh_<format> target (default: obj ply stl off)
#   --out DIR         corpora, artifacts and logs (default /tmp/depthtrack-fuzz-campaign)
#   --fuzz-build DIR  a clang build with -DDEPTHTRACK_FUZZ=ON (default build-fuzz-mesh; configured and
#                     built here if absent, with -DDEPTHTRACK_FUZZ_ASAN=OFF: see cmake/Sanitizers.cmake)
#   --replay-build DIR  an ordinary build with the replay_mesh_<format> programs (default build)
#   --nice N          niceness of the fuzzer (default 19: a shared machine)
#   --jobs N          fork-mode workers per format (default 1: one core)
#   --timeout S       an input running longer than S seconds counts as a hang (default 10; PLY's
#                     looping reader makes each hang cost S seconds of a worker)
#   --no-build        use the fuzz targets already in --fuzz-build (e.g. copied to another machine)
# Seeds: fuzz/corpus/mesh_<format>/ less the known crashers (crash_*, hang_*, oom_*), which the
# regression tests replay; dictionary: fuzz/dict/<format>.dict. Exit status 1 if any input escaped
# the guard (a signal or a hang reached Mesh::load's caller).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
runs=1000000
formats="obj ply stl off"
out=/tmp/depthtrack-fuzz-campaign
fuzz_build=$root/build-fuzz-mesh
replay_build=$root/build
niceness=19
max_seconds=0
jobs=1
timeout=10
build=1
while [[ $# -gt 0 ]]; do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --formats) formats=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --fuzz-build) fuzz_build=$2; shift 2 ;;
    --replay-build) replay_build=$2; shift 2 ;;
    --nice) niceness=$2; shift 2 ;;
    --max-seconds) max_seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    -h|--help) sed -n '2,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fuzz-campaign: unknown option '$1'" >&2; exit 2 ;;
  esac
done
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "fuzz-campaign: --runs takes a positive integer, not '$runs'" >&2; exit 2; }
[[ $jobs =~ ^[1-9][0-9]*$ ]] || { echo "fuzz-campaign: --jobs takes a positive integer, not '$jobs'" >&2; exit 2; }
[[ $timeout =~ ^[1-9][0-9]*$ ]] || { echo "fuzz-campaign: --timeout takes a positive integer, not '$timeout'" >&2; exit 2; }
[[ $max_seconds =~ ^[0-9]+$ ]] || { echo "fuzz-campaign: --max-seconds takes an integer, not '$max_seconds'" >&2; exit 2; }

targets=()
for f in $formats; do targets+=("fuzz_mesh_$f"); done
if [[ $build == 1 && ! -f $fuzz_build/CMakeCache.txt ]]; then
  cmake -S "$root" -B "$fuzz_build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DDEPTHTRACK_FUZZ=ON \
    -DDEPTHTRACK_FUZZ_ASAN=OFF -DDEPTHTRACK_BUILD_TESTS=OFF -DDEPTHTRACK_BUILD_BENCH=OFF \
    -DDEPTHTRACK_WITH_CUDA=OFF >/dev/null
fi
[[ $build == 0 ]] || nice -n "$niceness" cmake --build "$fuzz_build" -j2 --target "${targets[@]}" >/dev/null
for f in $formats; do
  [[ -x $replay_build/fuzz/replay_mesh_$f ]] ||
    { echo "fuzz-campaign: $replay_build/fuzz/replay_mesh_$f is missing: build the project first" >&2; exit 2; }
done

# The last progress line of fork mode: "#N: cov: ... oom/timeout/crash: O/T/C time: Ss ..."
last_progress() { grep -E '^#[0-9]+: cov:' "$1" | tail -1; }

status=0
printf '%-6s %12s %9s %11s %8s %9s %5s %9s\n' format executions seconds cpu_seconds crashes timeouts ooms guarded
for f in $formats; do
  work=$out/$f
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  for seed in "$root"/fuzz/corpus/mesh_"$f"/*; do
    case $(basename "$seed") in crash_* | hang_* | oom_*) ;; *) cp "$seed" "$work/corpus/" ;; esac
  done
  dict=()
  [[ -f $root/fuzz/dict/$f.dict ]] && dict=(-dict="$root/fuzz/dict/$f.dict")
  start=$(date +%s.%N)
  # Leaks are not findings: Mesh::load's import runs in a child process that exits.
  timer=()
  [[ -x /usr/bin/time ]] && timer=(/usr/bin/time -f '%U %S' -o "$work/cpu.txt")
  "${timer[@]}" nice -n "$niceness" "$fuzz_build/fuzz/fuzz_mesh_$f" "$work/corpus" \
    -fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 -runs="$runs" -max_total_time="$max_seconds" -timeout="$timeout" \
    -rss_limit_mb=2048 -detect_leaks=0 "${dict[@]}" -artifact_prefix="$work/artifacts/" >"$work/log.txt" 2>&1 &
  campaign=$!
  # A fork-mode worker runs at most 300 s (libFuzzer caps -max_total_time per job), yet some PLY
  # workers were seen asleep on a futex for 25 minutes (a deadlock inside the fuzzer's own timeout or
  # crash handler, 2 % CPU), which stalls the whole campaign: such a worker is killed after 400 s,
  # and the parent goes on with the next job.
  while kill -0 "$campaign" 2>/dev/null; do
    for worker in $(pgrep -f "fuzz_mesh_$f -ignore_crashes" || true); do
      age=$(ps -o etimes= -p "$worker" 2>/dev/null | tr -d ' ')
      if [[ -n $age && $age -gt 400 ]]; then
        kill -9 "$worker" 2>/dev/null && echo "fuzz-campaign: killed worker $worker, stalled ${age} s" >>"$work/stalled.txt"
      fi
    done
    sleep 10
  done
  wait "$campaign" || true
  seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
  cpu=$([[ -f $work/cpu.txt ]] && tail -1 "$work/cpu.txt" | awk '{print $1 + $2}' || echo 0)
  line=$(last_progress "$work/log.txt")
  executions=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$line")
  read -r ooms timeouts crashes < <(sed -E 's#.*oom/timeout/crash: ([0-9]+)/([0-9]+)/([0-9]+).*#\1 \2 \3#' <<<"$line")
  # Each kept input through the guard: replay must exit 0 (an InputError inside) well within its limits.
  # The replays run --jobs at a time (a campaign keeps hundreds: one at a time they outlast the fuzzing).
  found=0
  guarded=0
  shopt -s nullglob
  artifacts=("$work"/artifacts/*)
  shopt -u nullglob
  found=${#artifacts[@]}
  if ((found > 0)); then
    printf '%s\0' "${artifacts[@]}" | xargs -0 -P "$jobs" -I{} sh -c \
      'if timeout 60 "$1" "$2" >/dev/null 2>&1; then echo ok; else echo "$2" >&2; fi' _ \
      "$replay_build/fuzz/replay_mesh_$f" {} >"$work/replayed.txt" 2>"$work/escaped.txt" || true
    guarded=$(grep -c '^ok$' "$work/replayed.txt" || true)
    while read -r escaped; do
      echo "fuzz-campaign: $escaped escaped Mesh::load's guard" >&2
      status=1
    done <"$work/escaped.txt"
  fi
  printf '%-6s %12s %9.0f %11.0f %8s %9s %5s %9s\n' "$f" "${executions:-0}" "$seconds" "$cpu" "${crashes:-?}" \
    "${timeouts:-?}" "${ooms:-?}" "$guarded/$found"
done
exit $status
