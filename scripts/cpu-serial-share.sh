#!/usr/bin/env bash
# The reference filter's serial share of a frame, counted in instructions under callgrind (so other
# processes on a shared machine do not change it): the instructions of Tracker::update outside the thread
# pool's batches (the loops `--backend cpu` splits over its threads) against all of Tracker::update's, the
# speedup Amdahl's law predicts from it for 2, 8 and 16 threads, and the serial steps' own shares.
# Instructions are not time (a division costs more than an add, a copy waits on memory): a prediction for
# a CPU, to set against depthtrack_bench's measured speedup_over_reference and busy_threads there.
# Usage: scripts/cpu-serial-share.sh [BUILD_DIR] [depthtrack_bench options, default --particles 2000 --frames 20]
set -euo pipefail
build=${1:-build}
shift || true
args=("$@")
[[ ${#args[@]} -gt 0 ]] || args=(--particles 2000 --frames 20)
command -v valgrind >/dev/null || { echo "cpu-serial-share: valgrind is not installed" >&2; exit 1; }
[[ -x $build/depthtrack_bench ]] || { echo "cpu-serial-share: no $build/depthtrack_bench; build it first" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" \
  --toggle-collect='depthtrack::Tracker::update(depthtrack::DepthImage const&, double)' \
  "$build/depthtrack_bench" --backend reference --no-global --no-offscreen "${args[@]}" >"$out/bench.csv" 2>"$out/valgrind.log" ||
  { tail -n 20 "$out/valgrind.log" >&2; exit 1; }
callgrind_annotate --tree=calling --inclusive=yes --threshold=100 "$out/cg.out" >"$out/tree.txt"
python3 - "$out/tree.txt" "${args[*]}" <<'PY'
import re, sys
# Each function's block: "N (p%)  *  file:name" then its callees "N (p%)  >   file:name (calls)".
inclusive, pooled, current = {}, {}, None
for line in open(sys.argv[1]):
    m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+([*>])\s+\S*?:(.*)$", line)
    if not m:
        continue
    n, kind = int(m.group(1).replace(",", "")), m.group(2)
    name = re.sub(r"( \(\d[\d,]*x\))? \[[^]]*\]$", "", m.group(3).strip())
    if kind == "*":
        current = name
        inclusive[name] = max(inclusive.get(name, 0), n)
    elif current and re.search(r"ThreadPool::run\(|::for_chunks<|over_ranges<", name):
        pooled[current] = pooled.get(current, 0) + n
def find(pattern):
    return next((k for k in inclusive if re.search(pattern, k)), None)
update, pool = find(r"^depthtrack::Tracker::update\(depthtrack::DepthImage"), find(r"^depthtrack::ThreadPool::run\(")
if not update:
    sys.exit("cpu-serial-share: no Tracker::update counted")
total, parallel = inclusive[update], inclusive.get(pool, 0)
s = (total - parallel) / total
print(f"depthtrack_bench --backend reference {sys.argv[2]}: Tracker::update {total:,} instructions, "
      f"{parallel:,} in the thread pool's batches")
print(f"serial share {100 * s:.2f} %; Amdahl: {1 / (s + (1 - s) / 2):.2f}x on 2 threads, "
      f"{1 / (s + (1 - s) / 8):.2f}x on 8, {1 / (s + (1 - s) / 16):.2f}x on 16")
print("serial steps, outside the pool's batches (% of Tracker::update's instructions):")
for label, pattern in [("refinement (fit and cloud shift)", r"ReferenceFilter::refine\("),
                       ("weighted mean pose", r"weighted_mean_pose\("),
                       ("confidence and covariance", r"Tracker::Impl::assess_confidence\("),
                       ("weight summary", r"summarize_log_weights\("),
                       ("resampling draw", r"systematic_resample\(std::span<double const, \d+ul>, double\)$"),
                       ("resampling gather", r"ReferenceFilter::gather\("),
                       ("state window move", r"ReferenceFilter::move_state_window\("),
                       ("occlusion map for the fit", r"ReferenceFilter::occlusion_map\(")]:
    name = find(pattern)
    n = inclusive.get(name, 0) - pooled.get(name, 0) if name else 0
    print(f"  {label:34s} {100 * n / total:6.2f} %")
PY
