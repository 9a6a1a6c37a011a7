#!/usr/bin/env python3
"""Fits the tracker's confidence: a logistic model of P(ADD-S within tolerance | evidence).

Reads the rows of depthtrack_confidence_samples (poses right and wrong, each fitted to its likelihood's
optimum, with the evidence the tracker computes for its estimate) from one or more CSV files, fits
the logistic regression by iteratively reweighted least squares with a small ridge, and prints the
coefficients in the order src/tracker/confidence_model.cpp lists its features, with the reliability
table and the confident-wrong count on every input file alone (so a fit on some clips can be checked
on the others: --fit names the files to fit on, the rest are held out). The tables scale each pose's
probability by its support, as the code does: poses seen by fewer than 16 pixels count in proportion.

    scripts/calibrate-confidence.py samples-*.csv [--fit FILE ...]
"""
import argparse
import csv
import math
import sys

import numpy as np

# Within tolerance: ADD-S at most 10 mm and at most a tenth of the object's diameter.
TOLERANCE_MM = 10.0
WRONG_MM = 20.0  # a frame this far off while confident is "confidently wrong"


def features(row):
    """The evidence as the model reads it (src/tracker/confidence_model.cpp: the same order).

    visible + occluded + contradicted = 1, so visible is left out: the other two say how far the
    measured pixels depart from it.
    """
    nearer = float(row["outline_nearer"])
    rms = min(float(row["visible_rms"]), 3.0)
    return [
        1.0,
        float(row["occluded"]),
        float(row["contradicted"]),
        rms,
        # The outline's share that sees past the edge, of the whole outline: the part hidden by nearer
        # surfaces says nothing.
        float(row["separated"]) * (1.0 - nearer),
        # The relief: how far the seen surface departs from a plane beyond the pose's own residual
        # (surface_relief in the code).
        max(0.0, min(float(row["plane_rms"]), 3.0) - rms),
    ]


# Fewer seen pixels than a plane needs: the confidence counts in proportion to those seen (pose_confidence).
PLANE_PIXELS = 16


def support(row):
    """The share of PLANE_PIXELS the pose's seen pixels reach, at most 1 (the code's support)."""
    seen = int(row["pixels"]) * (1.0 - float(row["missing"])) * float(row["visible"])
    return min(1.0, seen / PLANE_PIXELS)


NAMES = ["bias", "occluded", "contradicted", "visible_rms", "separated_free", "relief"]


def load(path):
    xs, ys, adds, supports = [], [], [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            if int(row["pixels"]) == 0:
                continue  # nothing drawn: the tracker reports confidence 0 without the model
            tol = min(TOLERANCE_MM, 0.1 * float(row["diameter_mm"]))
            a = float(row["adds_mm"])
            xs.append(features(row))
            ys.append(1.0 if a <= tol else 0.0)
            adds.append(a)
            supports.append(support(row))
    return np.array(xs), np.array(ys), np.array(adds), np.array(supports)


def fit(x, y, ridge=1e-2, weights=None):
    w = np.zeros(x.shape[1])
    sample_weight = np.ones(len(y)) if weights is None else weights
    for _ in range(100):
        p = 1.0 / (1.0 + np.exp(-x @ w))
        r = sample_weight * p * (1 - p)
        h = (x * r[:, None]).T @ x + ridge * np.eye(x.shape[1])
        g = x.T @ (sample_weight * (y - p)) - ridge * w
        step = np.linalg.solve(h, g)
        w += step
        if np.abs(step).max() < 1e-9:
            break
    return w


def report(name, x, y, adds, supports, w):
    p = supports / (1.0 + np.exp(-x @ w))
    bins = np.minimum((p * 10).astype(int), 9)
    print(f"\n{name}: {len(y)} poses, {int(y.sum())} within tolerance")
    print("  bin   poses  share  mean p  within")
    ece = 0.0
    for b in range(10):
        m = bins == b
        if not m.any():
            continue
        share = m.mean()
        ece += share * abs(p[m].mean() - y[m].mean())
        flag = "  <-" if share >= 0.05 and abs(p[m].mean() - y[m].mean()) > 0.1 else ""
        print(f"  {b / 10:.1f}  {m.sum():6d}  {share:5.2f}  {p[m].mean():6.3f}  {y[m].mean():6.3f}{flag}")
    wrong = (adds > WRONG_MM) & (p >= 0.5)
    right_low = (y == 1) & (p < 0.5)
    print(f"  ECE {ece:.3f}; wrong (> {WRONG_MM:.0f} mm) with p >= 0.5: {wrong.sum()} of {(adds > WRONG_MM).sum()};"
          f" right with p < 0.5: {right_low.sum()} of {int(y.sum())}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+")
    parser.add_argument("--fit", nargs="*", help="files to fit on (default: all)")
    args = parser.parse_args()
    data = {f: load(f) for f in args.files}
    fit_files = args.fit or args.files
    # Every file weighs the same in the fit, whatever its size: no clip dominates.
    xs, ys, ws = [], [], []
    for f in fit_files:
        x, y, _, _ = data[f]
        xs.append(x)
        ys.append(y)
        ws.append(np.full(len(y), 1.0 / len(y)))
    x, y, sw = np.vstack(xs), np.concatenate(ys), np.concatenate(ws)
    w = fit(x, y, weights=sw * len(y) / len(fit_files))
    print("coefficients (" + ", ".join(NAMES) + "):")
    print("  {" + ", ".join(f"{v:.4f}" for v in w) + "}")
    for f in args.files:
        report(f + ("" if f in fit_files else " (held out)"), *data[f], w)


if __name__ == "__main__":
    sys.exit(main())
