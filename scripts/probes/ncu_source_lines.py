#!/usr/bin/env python3
"""Where a kernel's instructions and stalls lie, by source line and by function, from Nsight Compute's
source page of an NVRTC-built kernel (the CUDA backend's programs carry line information when the build
sets DEPTHTRACK_CUDA_EXTRA_OPTIONS=-lineinfo).

On the GPU machine:
  ncu -k regex:render_weigh --launch-skip 30 --launch-count 1 --set full --import-source yes -o /tmp/k <command>
  ncu -i /tmp/k.ncu-rep --page source --csv --print-source cuda,sass > k.csv
Here: ncu_source_lines.py k.csv render_weigh.cl [--top N]
NVRTC's line numbers are those of the program's text with its includes inlined (compute::kernel_source,
which this script repeats), so --cl must be the cl/ folder the profiled build embedded (a checkout of its
commit), or the lines are named wrongly."""
import argparse
import csv
import pathlib
import re


def inlined(cl: pathlib.Path, name: str, done=None) -> list:
    """cl/<name> with every #include "x.h" replaced by cl/x.h's lines, once per file."""
    done = set() if done is None else done
    if name in done:
        return []
    done.add(name)
    lines = []
    for line in (cl / name).read_text().splitlines():
        if line.startswith('#include "'):
            lines += inlined(cl, line.split('"')[1], done)
        else:
            lines.append(line)
    return lines


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("report", help="the source page as CSV (--print-source cuda,sass)")
    parser.add_argument("kernel_file", help="the program's file in cl/, e.g. render_weigh.cl")
    parser.add_argument("--cl", default=str(pathlib.Path(__file__).resolve().parents[2] / "cl"))
    parser.add_argument("--top", type=int, default=30)
    a = parser.parse_args()
    source = inlined(pathlib.Path(a.cl), a.kernel_file)
    starts = [(i + 1, re.findall(r"([A-Za-z_0-9]+)\(", l)[0]) for i, l in enumerate(source)
              if re.match(r"^(DT_DEVICE_FN|DT_FN|__kernel)", l) and "(" in l]
    header, rows = None, []
    for row in csv.reader(open(a.report)):
        if row and row[0] == "Line No":
            header = row
        elif header and row and row[0].isdigit():
            rows.append(row)
    if not header:
        raise SystemExit("no 'Line No' table in the report: was it exported with --print-source cuda,sass?")
    instructions = header.index("Instructions Executed")
    samples = header.index("Warp Stall Sampling (All Samples)")
    value = lambda row, c: float(row[c]) if row[c] not in ("-", "") else 0.0
    total_i = sum(value(r, instructions) for r in rows) or 1.0
    total_s = sum(value(r, samples) for r in rows) or 1.0

    def function(line):
        name = "?"
        for start, fn in starts:
            if start <= line:
                name = fn
        return name

    by_function = {}
    for r in rows:
        f = by_function.setdefault(function(int(r[0])), [0.0, 0.0])
        f[0] += value(r, instructions)
        f[1] += value(r, samples)
    print(f"{total_i:.3g} warp instructions, {total_s:.0f} stall samples")
    print("by function (the line's own; inlined callers are not summed):")
    for name, (i, s) in sorted(by_function.items(), key=lambda x: -x[1][1])[: a.top]:
        print(f"  {100 * i / total_i:5.1f} % instructions {100 * s / total_s:5.1f} % samples  {name}")
    print("by line:")
    for r in sorted(rows, key=lambda r: -value(r, samples))[: a.top]:
        n = int(r[0])
        text = source[n - 1].strip() if n <= len(source) else "?"
        print(f"  {n:5d} {100 * value(r, instructions) / total_i:5.1f} % {100 * value(r, samples) / total_s:5.1f} %  {text[:90]}")


if __name__ == "__main__":
    main()
