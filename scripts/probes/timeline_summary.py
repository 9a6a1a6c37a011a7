#!/usr/bin/env python3
"""Summarize a CUDA timeline of the several-object bench (scripts/probes/cuda_timeline.cpp's CSV, gzipped).

Each tracker has its own stream; a frame starts with its depth upload (a host-to-device copy of
FRAME_BYTES, 80x60 floats by default). Prints, per stream, the median duration of each kernel and of the
frame (upload to the end of its last kernel), and, for each group of streams that ran together (the
three-object runs), the median span of a frame over all of them and how long render_weigh kept the device:
the union of the groups' render_weigh intervals against their sum (equal: the objects' weighs ran one
after another; the sum larger: they overlapped).

usage: timeline_summary.py TIMELINE.csv.gz [--frame-bytes N] [--frame K]  (--frame: print frame K of each
group, every kernel with its start and duration)
"""
import argparse
import collections
import csv
import gzip
import statistics


def load(path):
    with gzip.open(path, "rt") as f:
        rows = [r for r in csv.DictReader(f) if r["kind"] in ("kernel", "copy")]
    for r in rows:
        r["s"], r["e"] = int(r["start_ns"]), int(r["end_ns"])
    rows.sort(key=lambda r: r["s"])
    return rows


def frames_of(rows, frame_bytes):
    """Per stream: a list of frames, each the stream's records from one upload to the next."""
    frames = collections.defaultdict(list)
    for r in rows:
        if r["kind"] == "copy" and r["name"] == "HtoD" and r["detail"] == str(frame_bytes):
            frames[r["stream"]].append([])
        if frames[r["stream"]]:
            frames[r["stream"]][-1].append(r)
    return frames


def union_length(intervals):
    total, end = 0, None
    for s, e in sorted(intervals):
        if end is None or s > end:
            total += e - s
            end = e
        elif e > end:
            total += e - end
            end = e
    return total


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("timeline")
    parser.add_argument("--frame-bytes", type=int, default=80 * 60 * 4)
    parser.add_argument("--frame", type=int, default=-1)
    args = parser.parse_args()
    frames = frames_of(load(args.timeline), args.frame_bytes)
    streams = sorted(frames, key=lambda s: frames[s][0][0]["s"])
    for s in streams:
        kernels = collections.defaultdict(list)
        for f in frames[s][2:]:  # the bench's warm-up frames left out
            for r in f:
                if r["kind"] == "kernel":
                    kernels[r["name"]].append(r["e"] - r["s"])
        spans = [max(r["e"] for r in f) - f[0]["s"] for f in frames[s][2:]]
        text = ", ".join(f"{n} {statistics.median(d) / 1e3:.1f}" for n, d in kernels.items())
        print(f"stream {s}: {len(frames[s])} frames, frame {statistics.median(spans) / 1e3:.1f} us; median us: {text}")
    # Streams whose first upload came within 2 ms of each other ran together.
    groups, current = [], []
    for s in streams:
        if current and frames[s][0][0]["s"] - frames[current[0]][0][0]["s"] > 2_000_000:
            groups.append(current)
            current = []
        current.append(s)
    groups.append(current)
    for g in (g for g in groups if len(g) > 1):
        n = min(len(frames[s]) for s in g)
        spans, unions, sums = [], [], []
        for i in range(2, n):
            records = [r for s in g for r in frames[s][i]]
            spans.append(max(r["e"] for r in records) - min(r["s"] for r in records))
            weighs = [(r["s"], r["e"]) for r in records if r["name"] == "render_weigh"]
            unions.append(union_length(weighs))
            sums.append(sum(e - s for s, e in weighs))
        print(f"streams {','.join(g)} together: frame {statistics.median(spans) / 1e3:.1f} us, render_weigh on the "
              f"device {statistics.median(unions) / 1e3:.1f} us of {statistics.median(sums) / 1e3:.1f} us summed")
        if 0 <= args.frame < n:
            t0 = min(frames[s][args.frame][0]["s"] for s in g)
            for r in sorted((r for s in g for r in frames[s][args.frame]), key=lambda r: r["s"]):
                indent = "    " * g.index(r["stream"])
                print(f"  {(r['s'] - t0) / 1e3:8.1f} {(r['e'] - r['s']) / 1e3:6.1f} {indent}{r['name']} {r['detail']}")


if __name__ == "__main__":
    main()
