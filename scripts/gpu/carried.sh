#!/usr/bin/env bash
# On the lent GPU machine, with binaries built on the CPU machine (no build here: the whole call goes to
# measuring). Pack them first with scripts/pack-carried-build.sh and carry .devdeps, .device, .devdata and
# build-carry. Parts (PARTS, default "bars box cpu tests"), each bounded so the call stays within LIMIT
# seconds (default 570):
#   bars   the frame rows of scripts/gpu/bars.sh (2,000 to 1,500,000 particles at 80x60, 30,000 at 640x480,
#          three objects against one), per backend; with build-base/ carried too (an earlier build packed
#          the same way), the same rows of that build, alternating with this one's, for a before/after;
#   box    the box search on ycbv-0000 and ycbv-0049 (`depthtrack eval --cases box`), per backend;
#   cpu    the cpu backend against the reference on THREADS cores of their own (default "1 2 8 16"),
#          CPU_PARTICLES (default 2,000);
#   budget depthtrack_bench_budget on the GPU (BUDGET_ARGS: a 5 ms budget of up to 100,000 particles against
#          200), then the reference's 5 ms budget on one idle core per seed (CPU_BUDGET_SEEDS, default 1 2 3);
#   tests  the test binary's TEST_SPEC (default: all but the host-only [cli], [io], [viz] and [bench] cases) on
#          CUDA and on NVIDIA OpenCL side by side, SHARDS processes each (default 8), each backend with its own
#          temporary folder, in the time left; the failing cases are listed, the logs go to $OUT gzipped.
set -uo pipefail
source .device/enter .devdeps >/dev/null 2>&1
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
started=$SECONDS
limit=${LIMIT:-570}
left() { echo $((limit - (SECONDS - started))); }
# The binaries name the CPU machine's build folder (their run path, the CLI and temporary folder the tests
# use): make that folder this carried one.
build=/work/main/build
if [[ $(realpath -m "$build") != $(realpath -m build-carry) ]]; then
  mkdir -p /work/main
  [[ -e $build && ! -L $build ]] && mv "$build" "$build.away"
  ln -sfn "$PWD/build-carry" "$build"
fi
mkdir -p "$build/tests/tmp"
# A library the carried ones need but this machine lacks (a stand-in libOSMesa) lies beside them.
export LD_LIBRARY_PATH=$PWD/build-carry/src:${LD_LIBRARY_PATH:-}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
lscpu | grep -E '^Model name|^CPU\(s\)'
cat build-carry/commit.txt 2>/dev/null
parts=" ${PARTS:-bars box cpu tests} "
bars() { # BUILD_FOLDER TAG
  local rows=',(refine_ms|refine_share|total_ms|status),' b
  for b in cuda opencl:nvidia; do
    timeout 60 "$1/depthtrack_bench" --backend "$b" --particles 2000,100000,1500000 --frames 10 --no-global |
      grep -E "$rows" | cut -d, -f1,5- | sed "s/^/$2 /"
    timeout 40 "$1/depthtrack_bench" --backend "$b" --particles 30000 --resolution 640x480 --frames 6 --no-global |
      grep -E ',(total_ms|status),' | cut -d, -f1,5- | sed "s/^/$2 /"
  done
}
if [[ $parts == *" bars "* ]]; then
  for rep in 1 2; do
    [[ -d build-base ]] && LD_LIBRARY_PATH=$PWD/build-base/src:$LD_LIBRARY_PATH bars "$PWD/build-base" "base$rep"
    bars "$build" "new$rep"
  done 2>&1 | tee "$out/bars.txt"
  multi() { # BUILD_FOLDER TAG
    for b in cuda opencl:nvidia; do
      timeout 40 "$1/depthtrack_bench" --multi-objects --backend "$b" --particles 2000 |
        grep -E "multi_object_ratio,|_objects?_ms," | grep -v one_host | cut -d, -f1,5- | sed "s/^/$2 /"
    done
  }
  { [[ -d build-base ]] && LD_LIBRARY_PATH=$PWD/build-base/src:$LD_LIBRARY_PATH multi "$PWD/build-base" base
    multi "$build" new; } 2>&1 | tee -a "$out/bars.txt"
fi
if [[ $parts == *" box "* ]]; then
  for b in ${BOX_BACKENDS:-cuda opencl:nvidia}; do
    for clip in ycbv-0000 ycbv-0049; do
      t0=$SECONDS
      timeout 90 "$build/depthtrack" eval --sequence ".devdata/sequences/$clip" --mesh-dir .devdata/meshes/ycb \
        --cases box --backend "$b" >"/tmp/box-$b-$clip.log" 2>&1
      echo "== box $b $clip (rc $?, $((SECONDS - t0)) s)"
      grep -E 'search_ms|error' "/tmp/box-$b-$clip.log" | head -12
    done
  done 2>&1 | tee "$out/box.txt"
fi
if [[ $parts == *" cpu "* ]]; then
  source scripts/lib/cpu-cores.sh
  echo "cpu:core/socket $(cpu_topology)" | tee "$out/cpu.txt"
  for mesh in handset 025_mug; do
    args=()
    [[ $mesh == handset ]] || args=(--mesh ".devdata/meshes/ycb/$mesh.obj" --simplify-error 0.0005)
    for t in ${THREADS:-1 2 8 16}; do
      # On the first t CPUs, and (where those share a physical core) on t CPUs of t cores of their own, as
      # on CI's machine. busy_threads and cpu_time_over_reference tell idle threads from slowed ones.
      for cpus in "0-$((t - 1))" $(own_cores "$t"); do
        [[ $cpus == "0-$((t - 1))" || $cpus != $(seq -s, 0 $((t - 1))) ]] || continue
        echo "$mesh ${CPU_PARTICLES:-2000} particles cpu:$t on $cpus: $(taskset -c "$cpus" timeout 60 \
          "$build/depthtrack_bench" --backend "cpu:$t" --particles "${CPU_PARTICLES:-2000}" --frames 10 --no-global \
          --no-offscreen "${args[@]}" 2>&1 |
          grep -E ',(total_ms|busy_threads|speedup_over_reference|cpu_time_over_reference),' | cut -d, -f1,6,8 |
          tr '\n' ' ')"
      done
    done
  done 2>&1 | tee -a "$out/cpu.txt"
fi
if [[ $parts == *" budget "* ]]; then
  # The GPU's budget against its fixed count; then one idle core's reference, a seed per core side by side.
  timeout 150 "$build/depthtrack_bench_budget" ${BUDGET_ARGS:---backend cuda --particles 200 --budget-ms 5 --max-particles 100000} \
    2>&1 | grep -E 'adds_mean|frame_p95,|particles_mean' | cut -d, -f1,5- | tee "$out/budget.txt"
  for seed in ${CPU_BUDGET_SEEDS:-1 2 3}; do
    taskset -c $((seed + 1)) timeout 200 "$build/depthtrack_bench_budget" --backend reference --particles 200 \
      --budget-ms 5 --seed "$seed" 2>&1 | grep -E 'adds_mean|frame_p95,|update_cpu_p95|particles_mean' |
      cut -d, -f1,5- | sed "s/^/seed$seed /" >"/tmp/budget-cpu-$seed.txt" &
  done
  wait
  cat /tmp/budget-cpu-*.txt | tee -a "$out/budget.txt"
fi
if [[ $parts == *" tests "* ]]; then
  shards=${SHARDS:-8}
  # Test names as patterns: a comma, bracket, star or backslash in a name is escaped.
  "$build/tests/depthtrack_tests" --list-test-names-only "${TEST_SPEC:-~[cli]~[io]~[viz]~[bench]}" | grep -v '^$' |
    sed 's/[],[*\\]/\\&/g' >/tmp/names.txt
  split -n "r/$shards" -d /tmp/names.txt /tmp/shard-
  budget=$(($(left) - 15))
  echo "== tests: $(wc -l </tmp/names.txt) cases, $shards shards per backend, ${budget} s"
  for b in cuda opencl:nvidia; do
    mkdir -p "/tmp/tmp-${b//:/-}"
    for f in /tmp/shard-*; do
      (DEPTHTRACK_TEST_DEVICE=$b DEPTHTRACK_TEST_TMP=/tmp/tmp-${b//:/-} timeout "$budget" \
        "$build/tests/depthtrack_tests" -f "$f" >"/tmp/log-${b//:/-}-${f##*-}.txt" 2>&1
        echo "rc $?" >>"/tmp/log-${b//:/-}-${f##*-}.txt") &
    done
  done
  wait
  for b in cuda opencl:nvidia; do
    echo "== tests on $b"
    for log in /tmp/log-"${b//:/-}"-*.txt; do
      echo "$(basename "$log"): $(grep -a -E '^test cases|^All tests' "$log" | tail -1) $(tail -1 "$log")"
    done
    # Each failing case's name (between the two dashed lines above its FAILED block).
    cat /tmp/log-"${b//:/-}"-*.txt | awk '/^-+$/ && length($0) > 70 { if (!inside) { inside = 1; name = "" } else inside = 0; next }
      inside { name = name (name == "" ? "" : " ") $0 } /FAILED:|due to unexpected/ { print "  FAILED " name }' | sort -u | head -40
    cat /tmp/log-"${b//:/-}"-*.txt | gzip >"$out/tests-${b//:/-}.log.gz"
  done 2>&1 | tee "$out/tests.txt"
fi
echo "== $((SECONDS - started)) s"
