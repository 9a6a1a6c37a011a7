"""Pictures of depthtrack's evaluation output, drawn with matplotlib.

    python3 -m depthtrack.plots reliability FRAMES.csv OUT.png

FRAMES.csv is what `depthtrack eval --frames-out` writes: a row per frame with (among others) the
columns confidence and within_tolerance (1, 0, or empty where the frame has no ground truth).

This module needs only matplotlib (Debian: python3-matplotlib), not the compiled bindings: `depthtrack
eval --reliability` runs this file directly.
"""
import csv
import math
import os
import sys

BINS = 10


def read_outcomes(csv_path):
    """(confidence, within tolerance) of every row with ground truth and a finite confidence."""
    with open(csv_path, newline="") as f:
        reader = csv.DictReader(f)
        missing = {"confidence", "within_tolerance"} - set(reader.fieldnames or [])
        if missing:
            raise ValueError("%s lacks the column(s) %s: is it a `depthtrack eval --frames-out` CSV?"
                             % (csv_path, ", ".join(sorted(missing))))
        outcomes = []
        for line, row in enumerate(reader, start=2):
            within = row["within_tolerance"].strip()
            if within == "":
                continue
            if within not in ("0", "1"):
                raise ValueError("%s line %d: within_tolerance is '%s', not 0, 1 or empty" % (csv_path, line, within))
            try:
                confidence = float(row["confidence"])
            except ValueError:
                raise ValueError("%s line %d: confidence '%s' is not a number" % (csv_path, line, row["confidence"]))
            if math.isfinite(confidence):
                outcomes.append((confidence, within == "1"))
    return outcomes


def reliability_bins(outcomes):
    """Ten equal confidence bins over [0, 1] (1 falls in the last): per bin (frames, mean confidence,
    share within tolerance), the last two None for an empty bin; and the expected calibration error
    (frame-weighted mean of |share within - mean confidence|), None without frames."""
    counts, confidence, within = [0] * BINS, [0.0] * BINS, [0] * BINS
    for c, w in outcomes:
        b = min(BINS - 1, max(0, int(math.floor(c * BINS))))
        counts[b] += 1
        confidence[b] += c
        within[b] += 1 if w else 0
    bins, total, ece = [], sum(counts), 0.0
    for n, c, w in zip(counts, confidence, within):
        if n == 0:
            bins.append((0, None, None))
            continue
        bins.append((n, c / n, w / n))
        ece += n / total * abs(w / n - c / n)
    return bins, (ece if total else None)


def reliability_diagram(csv_path, png_path):
    """Draws the reliability diagram of a frames CSV as a PNG: per confidence bin a bar up to the share of
    its frames truly within tolerance, its frame count written above it, a marker at the bin's mean
    confidence, the diagonal of perfect calibration, and the expected calibration error in the title.
    Returns (bins, ece) as reliability_bins does. The PNG is written whole or not at all."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    outcomes = read_outcomes(csv_path)
    if not outcomes:
        raise ValueError("%s has no frame with ground truth (within_tolerance 0 or 1) to draw" % csv_path)
    bins, ece = reliability_bins(outcomes)
    width = 1.0 / BINS
    fig, ax = plt.subplots(figsize=(6.4, 5.6), dpi=100)
    ax.plot([0, 1], [0, 1], linestyle="--", color="grey", linewidth=1, label="perfect calibration")
    most = max(n for n, _, _ in bins)
    first = min(b for b, (n, _, _) in enumerate(bins) if n)  # the bin that labels the legend
    for b, (n, mean_confidence, share) in enumerate(bins):
        if n == 0:
            continue
        left = b * width
        # Darker bars hold more frames; the count is written above each.
        ax.bar(left + width / 2, share, width=width * 0.9, color="tab:blue", alpha=0.25 + 0.65 * n / most,
               edgecolor="tab:blue", label="share within tolerance" if b == first else None)
        ax.annotate("n=%d" % n, (left + width / 2, share), textcoords="offset points", xytext=(0, 3), ha="center",
                    fontsize=8)
        ax.plot(mean_confidence, share, marker="o", color="tab:red", markersize=4 + 8 * math.sqrt(n / most),
                label="bin's mean confidence" if b == first else None)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.08)
    ax.set_xticks([i * width for i in range(BINS + 1)])
    ax.set_xlabel("confidence")
    ax.set_ylabel("share of frames within tolerance")
    ax.set_title("Reliability: ECE %.3f over %d frames" % (ece, len(outcomes)))
    ax.legend(loc="upper left", fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    partial = png_path + ".partial"
    try:
        fig.savefig(partial, format="png")
        os.replace(partial, png_path)
    finally:
        plt.close(fig)
        if os.path.exists(partial):
            os.remove(partial)
    return bins, ece


def main(argv):
    usage = "usage: python3 -m depthtrack.plots reliability FRAMES.csv OUT.png"
    if len(argv) != 3 or argv[0] != "reliability":
        print(usage, file=sys.stderr)
        return 2
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("depthtrack.plots: error: matplotlib is not installed (Debian: apt install python3-matplotlib)",
              file=sys.stderr)
        return 1
    try:
        bins, ece = reliability_diagram(argv[1], argv[2])
    except (OSError, ValueError) as e:
        print("depthtrack.plots: error: %s" % e, file=sys.stderr)
        return 1
    print("reliability diagram: %d frames, ECE %.3f" % (sum(n for n, _, _ in bins), ece))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
