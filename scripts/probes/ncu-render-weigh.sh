#!/usr/bin/env bash
# On the GPU machine (a probe, issue 10): Nsight Compute's full report of render_weigh for ycbv-0000's
# gelatin box (its 11th launch in the several-object bench) and mug (31st), and the SM clock while the
# bench runs unprofiled. Carry .devdeps, .device, .devdata and build-carry-bin; reports go to $OUT.
set -uo pipefail
source .device/enter .devdeps >/dev/null 2>&1
export LD_LIBRARY_PATH=$PWD/build-carry-bin:$LD_LIBRARY_PATH DEPTHTRACK_DATA_DIR=$PWD/.devdata
bench=(build-carry-bin/depthtrack_bench --multi-objects --backend cuda --particles 2000 --frames 20 --untimed-steps
  --simplify-error 0.0005)
nvidia-smi --query-gpu=clocks.sm,clocks.max.sm,power.draw --format=csv,noheader -lms 20 >"$OUT/clocks.txt" &
sampler=$!
"${bench[@]}" | grep -E "ratio" | awk -F, '{ print $(NF-3), $(NF-2), $NF }'
kill $sampler
sort "$OUT/clocks.txt" | uniq -c | sort -rn | head -8
for skip in 10 30; do
  timeout 200 ncu -k regex:render_weigh --launch-skip $skip --launch-count 1 --set full --print-units base \
    --page details "${bench[@]}" >"$OUT/ncu-$skip.txt" 2>&1
  grep -E "Duration|Registers Per|Shared Memory Per Block|Achieved Occupancy|Theoretical Occupancy|Block Limit|Waves Per|SM Frequency|L2 Hit|Memory Throughput|Compute \(SM\) Throughput|One or More|No Eligible|Active Warps Per|Eligible Warps" \
    "$OUT/ncu-$skip.txt" | head -40
done
