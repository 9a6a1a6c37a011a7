#!/usr/bin/env bash
# On the lent GPU machine, one call (about 5 minutes with carried binaries): every GPU throughput and latency
# target at this commit, and `depthtrack bench`'s figures.
#   - `depthtrack bench` (full grid) on CUDA, NVIDIA OpenCL and the reference: results.json, the PNGs and
#     the table, packed into $OUT/bench.tar.gz;
#   - the 2,000-particle frame, depth in to pose out (update_ms), back to back and paced 5 ms apart, three times;
#   - 100,000 and 1,500,000 particles at 80x60, and 30,000 and 40,000 at 640x480 (timed steps, as the bars
#     were; NVIDIA OpenCL on an H100 draws 640x480's atlas in two and three turns);
#   - `track` with 1,000,000 particles at 80x60 on a synthesized handset sequence: wall time, peak resident
#     memory (/usr/bin/time -v), latency_ms against the bench's frame;
#   - three ycbv-0000 objects against one;
#   - with depthtrack_tests in BIN (or TESTS=1 when building), [device],[atlas],[kernels],[refine] on both.
# BIN=<folder> holds depthtrack, depthtrack_bench and libdepthtrack.so.0 built elsewhere (a short device
# budget); without it this tree is built in build-gpu. Carry .devdeps, .device, .devdata.
set -uo pipefail
source .device/enter .devdeps
export DEPTHTRACK_DATA_DIR=$PWD/.devdata POCL_CACHE_DIR=/tmp/pocl-cache
out=${OUT:-/tmp/depthtrack-gpu}
mkdir -p "$out"
if [[ -n ${BIN:-} ]]; then
  export LD_LIBRARY_PATH=$PWD/$BIN${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  bin=$PWD/$BIN
else
  tests=OFF
  [[ ${TESTS:-0} == 1 ]] && tests=ON
  cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEPTHTRACK_BUILD_TESTS=$tests -DDEPTHTRACK_PYTHON=OFF \
    -DDEPTHTRACK_SANITIZE_SUITE=OFF -DDEPTHTRACK_STATIC_PACKAGE_TEST=OFF >"$out/configure.log" 2>&1 &&
    cmake --build build-gpu -j"$(nproc)" --target depthtrack_cli depthtrack_bench \
      $([[ $tests == ON ]] && echo depthtrack_tests) >"$out/build.log" 2>&1 ||
    { tail -20 "$out/build.log"; exit 1; }
  bin=$PWD/build-gpu
  [[ -x $bin/tests/depthtrack_tests ]] && ln -sf "$bin/tests/depthtrack_tests" "$bin/depthtrack_tests"
fi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
rows() { grep -E ",($1)," | cut -d, -f6,8 | tr '\n' ' '; }
echo "== depthtrack bench"
mkdir -p "$out/bench"
"$bin/depthtrack" bench --backend cuda --backend opencl:nvidia --backend reference --max-seconds 240 \
  --out "$out/bench" >"$out/bench/table.txt" 2>"$out/bench/progress.log"
echo "status $?"
grep -E "latency_|particles_handset_80x60_(2000|100000|1500000)p" "$out/bench/table.txt" |
  grep -E "frame_ms|latency_ms|speedup" | head -40
grep -E "failed|skipped" "$out/bench/progress.log" | head -10
tar -C "$out" -czf "$out/bench.tar.gz" bench && rm -rf "$out/bench"
echo "== 2,000 particles, 80x60, depth in to pose out"
for rep in 1 2 3; do
  for b in cuda opencl:nvidia; do
    for feed in "" "--pace 5"; do
      echo "$b ${feed:-back to back}: $("$bin/depthtrack_bench" --backend "$b" --particles 2000 --frames 60 --no-global \
        --untimed-steps $feed | rows 'total_ms|update_ms')"
    done
  done
done
echo "== throughput"
for b in cuda opencl:nvidia; do
  "$bin/depthtrack_bench" --backend "$b" --particles 100000,1500000 --frames 10 --no-global | grep -E ',(total_ms|status),' |
    cut -d, -f1,5,6,8
  "$bin/depthtrack_bench" --backend "$b" --particles 30000,40000 --resolution 640x480 --frames 6 --no-global |
    grep -E ',(total_ms|status),' | cut -d, -f1,5,6,8
done
echo "== track, 1,000,000 particles"
seq=/tmp/handset-seq
"$bin/depthtrack" synth --out "$seq" --mesh .devdata/meshes/dbot/handset.obj --frames 40 --occluder 0.3 >/dev/null ||
  exit 1
for b in cuda opencl:nvidia; do
  # A small run first fills the program cache, as a user's second run finds it.
  "$bin/depthtrack" track --mesh .devdata/meshes/dbot/handset.obj --sequence "$seq" --out /tmp/warm.csv --backend "$b" \
    --particles 1000 --init-from-gt >/dev/null 2>&1
  /usr/bin/time -v "$bin/depthtrack" track --mesh .devdata/meshes/dbot/handset.obj --sequence "$seq" --out "/tmp/$b.csv" \
    --backend "$b" --particles 1000000 --init-from-gt >/tmp/track.log 2>&1
  echo "$b: status $?, $(grep -E 'Elapsed \(wall|Maximum resident' /tmp/track.log | sed 's/^\s*//' | tr '\n' ' ')"
  # latency_ms found by its header; frames 2-9 are the ones the bench times on the same trajectory.
  awk -F, 'NR==1 {for (i=1;i<=NF;i++) if ($i=="latency_ms") c=i} NR>1 {print $c}' "/tmp/$b.csv" | sed -n 3,10p |
    sort -g | awk '{a[NR]=$1} END {print "  latency_ms frames 2-9 median", (a[4]+a[5])/2}'
  "$bin/depthtrack_bench" --backend "$b" --particles 1000000 --frames 10 --no-global |
    grep -E ',(total_ms|startup_ms|startup_host_peak),' | cut -d, -f6,8 | tr '\n' ' '
  echo
done
echo "== three ycbv objects against one"
for b in cuda opencl:nvidia; do
  echo "$b: $("$bin/depthtrack_bench" --multi-objects --backend "$b" --particles 2000 --untimed-steps \
    --simplify-error 0.0005 --frames 40 | grep -oE 'occlusion_(off|on)_untimed,multi_object_ratio_to_mean,x,[0-9.]+' |
    tr '\n' ' ')"
done
source scripts/lib/device-tests.sh
[[ -x $bin/depthtrack_tests ]] && device_tests "$bin/depthtrack_tests" "[device],[atlas],[kernels],[refine]"
