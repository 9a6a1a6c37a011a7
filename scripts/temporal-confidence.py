#!/usr/bin/env python3
"""Evaluates temporal confidences on tracked frames: two-state forward filters over "the pose is right".

Reads files of depthtrack_confidence_samples --track (each run's frames in order) and, for each file held
out in turn, picks the filter's parameters on the others (least log-loss over a small grid) and prints the
held-out calibration before (the evidence model alone) and after. The filter, per frame:

    prior_t = (1 - h_t) p_{t-1} + h_t b      h_t = 1 - (1 - h)^(elapsed frames): a gap forgets more
    logit p_t = logit prior_t + w_t (logit q_t - logit b)

q_t is the evidence model's probability (coefficients as src/tracker/confidence_model.cpp lists them), b the
base rate its evidence is weighed against, w_t = min(1, visible pixels / n0) so a frame that sees little of
the object says little. The gap runs jump before frame index 6 (depthtrack_confidence_samples --track).

With --gate a frame whose own confidence (q times the support) is below 0.5 reports it (the status's
rule), and a supported one the larger of it and the filter's; --reset lost,gap starts the filter afresh
after such a frame and at a gap; --cap reads the filter up to a ceiling; --fixed HAZARD BASE picks
nothing. The tracker's run confidence (src/tracker/run_confidence.hpp) is

    scripts/temporal-confidence.py samples-*-track.csv --n0 16 --gate --reset lost,gap --cap 0.99 --fixed 0.1 0.5
"""
import argparse
import csv
import importlib.util
import math
import os
import sys

import numpy as np

_spec = importlib.util.spec_from_file_location(
    "calibrate", os.path.join(os.path.dirname(os.path.abspath(__file__)), "calibrate-confidence.py"))
calibrate = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(calibrate)

COEFFICIENTS = [-3.1930, 1.7135, -11.6344, -1.9042, 5.6930, 2.1661]
GAP_FRAMES = {"track-gap0.5": 15, "track-gap2": 60}  # frames of 1/30 s the clock jumps by
GAP_INDEX = 6


def logit(p):
    p = min(max(p, 1e-9), 1 - 1e-9)
    return math.log(p / (1 - p))


def load_runs(path):
    """Each run: its kind and its frames as (q, seen pixels, within tolerance, ADD-S mm, the frame's confidence)."""
    runs, last = [], None
    with open(path) as f:
        for row in csv.DictReader(f):
            key, frame = (row["object"], row["kind"]), int(row["frame"])
            if last is None or key != last[0] or frame <= last[1]:
                runs.append((row["kind"], []))
            last = (key, frame)
            pixels = int(row["pixels"])
            q = 1 / (1 + math.exp(-float(np.dot(COEFFICIENTS, calibrate.features(row))))) if pixels > 0 else 0.0
            seen = pixels * (1 - float(row["missing"])) * float(row["visible"])
            tolerance = min(calibrate.TOLERANCE_MM, 0.1 * float(row["diameter_mm"]))
            adds = float(row["adds_mm"])
            frame = q * min(1.0, seen / 16)  # the frame's own confidence (the model's support)
            runs[-1][1].append((q, seen, adds <= tolerance, adds, frame))
    return runs


def forward(kind, frames, h, base, n0, gate=False, reset="", cap=1.0):
    out, p = [], None
    b = 1 / (1 + math.exp(-base))
    for i, (q, seen, _, _, reported) in enumerate(frames):
        if q <= 0:
            p = 0.0
            out.append(0.0)
            continue
        w = min(1.0, seen / n0) if n0 > 0 else 1.0
        gap = kind in GAP_FRAMES and i == GAP_INDEX
        if p is None or ("gap" in reset and gap):
            prior = base
        else:
            elapsed = GAP_FRAMES.get(kind, 1) if i == GAP_INDEX else 1
            hazard = 1 - (1 - h) ** elapsed
            prior = logit((1 - hazard) * p + hazard * b)
        p = 1 / (1 + math.exp(-max(-20.0, min(20.0, prior + w * (logit(q) - base)))))
        out.append((reported if reported < 0.5 else max(reported, min(p, cap))) if gate else min(p, cap))
        if "lost" in reset and reported < 0.5:
            p = None
    return out


def score(runs, params, gate=False, reset="", cap=1.0):
    p, y, adds = [], [], []
    for kind, frames in runs:
        p += forward(kind, frames, *params, gate=gate, reset=reset, cap=cap) if params else [f[4] for f in frames]
        y += [f[2] for f in frames]
        adds += [f[3] for f in frames]
    p, y, adds = np.array(p), np.array(y, float), np.array(adds)
    loss = -np.mean(y * np.log(np.clip(p, 1e-6, 1)) + (1 - y) * np.log(np.clip(1 - p, 1e-6, 1)))
    bins = np.minimum((p * 10).astype(int), 9)
    ece = worst = 0.0
    for b in range(10):
        m = bins == b
        if m.any():
            gap = abs(y[m].mean() - p[m].mean())
            ece += m.mean() * gap
            if m.mean() >= 0.05:
                worst = max(worst, gap)
    wrong = int(((adds > calibrate.WRONG_MM) & (p >= 0.5)).sum())
    return loss, ece, worst, wrong


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+")
    parser.add_argument("--n0", type=float, help="fix the pixel weight's n0 (e.g. 16, the support's pixels)")
    parser.add_argument("--all", action="store_true", help="fit on every file, none held out")
    parser.add_argument("--gate", action="store_true",
                        help="report the evidence alone below 0.5 (the status's rule), else the larger of it and the filter's")
    parser.add_argument("--reset", default="", help="lost, gap or both: the filter starts afresh after a lost frame, a gap")
    parser.add_argument("--cap", type=float, default=1.0, help="the filter's probability is read up to this")
    parser.add_argument("--fixed", nargs=2, type=float, metavar=("HAZARD", "BASE"), help="these parameters, none picked")
    args = parser.parse_args()
    data = {f: load_runs(f) for f in args.files}
    hazards, bases = (0.003, 0.01, 0.03, 0.1, 0.3), (0.1, 0.2, 0.3, 0.5, 0.6, 0.7, 0.8)
    if args.fixed:
        hazards, bases = (args.fixed[0],), (args.fixed[1],)
    grid = [(h, logit(b), n0) for h in hazards for b in bases
            for n0 in ((args.n0,) if args.n0 is not None else (0, 16, 30, 100))]
    print("before (ECE, worst bin of >= 5 %, confidently wrong) -> after, with "
          + ("the parameters fitted on all" if args.all else "the others' parameters (each held out)"))
    for f in args.files:
        others = args.files if args.all else [g for g in args.files if g != f]
        best = min(grid, key=lambda g: sum(score(data[o], g, args.gate, args.reset, args.cap)[0] for o in others))
        _, e0, w0, c0 = score(data[f], None)
        _, e1, w1, c1 = score(data[f], best, args.gate, args.reset, args.cap)
        print(f"{os.path.basename(f)}: {e0:.3f} {w0:.3f} {c0} -> {e1:.3f} {w1:.3f} {c1}"
              f"  (h {best[0]}, b {1 / (1 + math.exp(-best[1])):.1f}, n0 {best[2]})")


if __name__ == "__main__":
    sys.exit(main())
