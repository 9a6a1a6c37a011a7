"""Pictures of depthtrack's output, drawn with matplotlib.

    python3 -m depthtrack.plots reliability FRAMES.csv OUT.png
    python3 -m depthtrack.plots run TRACK.csv OUT.png
    python3 -m depthtrack.plots timeline TRACK.csv OUT.png
    python3 -m depthtrack.plots bench CASES.csv SWEEP=OUT.png [SWEEP=OUT.png ...]

FRAMES.csv is what `depthtrack eval --frames-out` writes: a row per frame with (among others) the
columns confidence and within_tolerance (1, 0, or empty where the frame has no ground truth).
TRACK.csv is what `depthtrack track --out` writes (an `object` column first when several objects were
tracked). CASES.csv is what `depthtrack bench` writes beside results.json: a row per case run.

This module needs only matplotlib (Debian: python3-matplotlib), not the compiled bindings: `depthtrack
eval --reliability`, `depthtrack plot` and `depthtrack bench` run this file directly.
"""
import csv
import math
import os
import sys

BINS = 10
MISSING_MATPLOTLIB = "matplotlib is not installed (Debian: apt install python3-matplotlib)"


def _pyplot():
    """matplotlib.pyplot on the Agg backend (no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _save(fig, png_path):
    """Writes the figure whole or not at all (through PATH.partial and a rename), then closes it."""
    plt = _pyplot()
    partial = png_path + ".partial"
    try:
        fig.savefig(partial, format="png")
        os.replace(partial, png_path)
    finally:
        plt.close(fig)
        if os.path.exists(partial):
            os.remove(partial)


def _plain_numbers(axis):
    """Tick labels of a log axis as plain numbers in the axis' unit (0.1, 1, 10, 100), not powers of ten;
    on an axis spanning under about a decade and a half, 2 and 5 of each decade labelled too, and under a
    factor of 3 every tick."""
    from matplotlib.ticker import FuncFormatter

    def minor(value, _):
        low, high = sorted(axis.get_view_interval())
        if value <= 0 or low <= 0 or high / low > 30:
            return ""
        if high / low <= 3:
            return "%g" % float("%.3g" % value)
        leading = value / 10 ** math.floor(math.log10(value) + 1e-9)
        return "%g" % value if round(leading) in (2, 5) and abs(leading - round(leading)) < 1e-6 else ""

    axis.set_major_formatter(FuncFormatter(lambda v, _: "%g" % v))
    axis.set_minor_formatter(FuncFormatter(minor))


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
    plt = _pyplot()
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
    _save(fig, png_path)
    return bins, ece


# The panels of a track run's figure: (axis label with its unit, [(column, what the line shows)]).
RUN_PANELS = [
    ("translation error (mm)", [("err_t_mm", "centre"), ("adds_mm", "ADD-S")]),
    ("rotation error (deg)", [("err_r_deg", "rotation")]),
    ("confidence (0 to 1)", [("confidence", "confidence")]),
    ("effective sample size (particles)", [("ess", "ESS")]),
    ("latency, depth in to pose out (ms)", [("latency_ms", "latency")]),
]
STYLES = [("-", "o"), ("--", "s"), (":", "^")]  # line and marker per quantity of a panel


class RunTable:
    """A track CSV: its header and rows (cells as text), checked to be a rectangular table."""

    def __init__(self, path):
        self.path = path
        try:
            with open(path, newline="") as f:
                lines = [row for row in csv.reader(f)]
        except OSError as e:
            raise ValueError("cannot open the run CSV '%s': %s" % (path, e.strerror or e))
        if not lines or not lines[0]:
            raise ValueError("'%s' is empty: expected a header line" % path)
        self.header = lines[0]
        self.rows, self.lines = [], []
        for number, cells in enumerate(lines[1:], start=2):
            if not cells:
                continue
            if len(cells) != len(self.header):
                raise ValueError("'%s' line %d has %d cells; the header has %d"
                                 % (path, number, len(cells), len(self.header)))
            self.rows.append(cells)
            self.lines.append(number)
        if not self.rows:
            raise ValueError("'%s' has a header but no rows" % path)

    def has(self, column):
        return column in self.header

    def numbers(self, column):
        """The column as floats: empty and nan cells are NaN, anything else must be a number."""
        i = self.header.index(column)
        values = []
        for cells, line in zip(self.rows, self.lines):
            cell = cells[i].strip()
            if cell in ("", "nan", "NaN"):
                values.append(math.nan)
                continue
            try:
                values.append(float(cell))
            except ValueError:
                raise ValueError("'%s' line %d: column '%s' holds '%s', not a number" % (self.path, line, column, cell))
        return values

    def text(self, column):
        i = self.header.index(column)
        return [cells[i] for cells in self.rows]

    def objects(self):
        """[(object name, row indices)] in order of first appearance; one unnamed object without an
        `object` column."""
        if not self.has("object"):
            return [("", list(range(len(self.rows))))]
        order = {}
        for r, name in enumerate(self.text("object")):
            order.setdefault(name, []).append(r)
        return list(order.items())

    def times(self, rows):
        """The x values of rows and their label: seconds since the run's first frame when there are
        timestamps, else the frame's place in the run."""
        if self.has("timestamp"):
            stamps = self.numbers("timestamp")
            first = min((s for s in stamps if math.isfinite(s)), default=0.0)
            return [stamps[r] - first for r in rows], "time since the first frame (s)"
        return list(range(len(rows))), "frame"


def _spread_wide(values):
    """Whether positive values span over two decades: a log axis then shows them better than a linear one."""
    positive = [v for v in values if math.isfinite(v) and v > 0]
    return len(positive) > 1 and max(positive) / min(positive) > 100 and len(positive) == sum(
        1 for v in values if math.isfinite(v))


def _colours(count):
    plt = _pyplot()
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return [cycle[i % len(cycle)] for i in range(count)]


def run_figure(csv_path, png_path):
    """Draws a track run's CSV over time as a PNG (see draw_run). Returns (the panels' labels, frames of
    the longest object, object names)."""
    fig, panels, frames, names = draw_run(csv_path)
    _save(fig, png_path)
    return panels, frames, names


def draw_run(csv_path):
    """A track run's CSV over time: a panel per quantity present (translation error and ADD-S in mm,
    rotation error in degrees, confidence, ESS, latency in ms), each object of a several-object run as
    its own line, markers on the lines, a legend where a panel has several. Returns (the figure, the
    panels' labels, frames of the longest object, object names)."""
    table = RunTable(csv_path)
    panels = [(label, [(c, what) for c, what in series if table.has(c)]) for label, series in RUN_PANELS]
    panels = [(label, series) for label, series in panels if series]
    if not panels:
        raise ValueError("'%s' has none of the columns plot shows (err_t_mm, adds_mm, err_r_deg, confidence, ess, "
                         "latency_ms): is it a track CSV?" % csv_path)
    values = {c: table.numbers(c) for _, series in panels for c, _ in series}
    objects = table.objects()
    plt = _pyplot()
    fig, axes = plt.subplots(len(panels), 1, sharex=True, squeeze=False, figsize=(9.6, 0.8 + 2.2 * len(panels)),
                             dpi=100)
    colours = _colours(max(len(objects), 2))
    x_label = "frame"
    for ax, (label, series) in zip(axes[:, 0], panels):
        drawn = []
        for o, (name, rows) in enumerate(objects):
            x, x_label = table.times(rows)
            for q, (column, what) in enumerate(series):
                y = [values[column][r] for r in rows]
                line, marker = STYLES[q % len(STYLES)]
                colour = colours[o] if len(objects) > 1 else colours[q]
                legend = " ".join(part for part in (name, what if len(series) > 1 or not name else "") if part)
                ax.plot(x, y, linestyle=line, marker=marker, markersize=4, markevery=max(1, len(x) // 30),
                        color=colour, linewidth=1.2, label=legend)
                drawn.extend(y)
        if label.startswith("confidence"):
            ax.set_ylim(-0.02, 1.02)
        elif _spread_wide(drawn):
            ax.set_yscale("log")
            _plain_numbers(ax.yaxis)
        ax.set_ylabel(label, fontsize=9)
        ax.grid(alpha=0.3, which="both")
        if len(ax.get_lines()) > 1:
            ax.legend(fontsize=8, loc="best")
    axes[-1, 0].set_xlabel(x_label)
    names = [name for name, _ in objects]
    fig.suptitle("%s: %s" % (os.path.basename(csv_path), ", ".join(names) if names[0] else "one object"),
                 fontsize=10)
    fig.tight_layout()
    return fig, [label for label, _ in panels], max(len(rows) for _, rows in objects), names


def _status_spans(x, status, wanted):
    """[(start, end)] of the runs of frames whose status is wanted, each frame reaching halfway to its
    neighbours."""
    spans, n = [], len(x)
    for i in range(n):
        if status[i] != wanted:
            continue
        left = x[i] - (x[i] - x[i - 1]) / 2 if i > 0 else x[i] - ((x[1] - x[0]) / 2 if n > 1 else 0.5)
        right = x[i] + (x[i + 1] - x[i]) / 2 if i + 1 < n else x[i] + ((x[i] - x[i - 1]) / 2 if n > 1 else 0.5)
        if spans and i > 0 and status[i - 1] == wanted:
            spans[-1] = (spans[-1][0], right)
        else:
            spans.append((left, right))
    return spans


def timeline_figure(csv_path, png_path):
    """Draws error and confidence over a run as a PNG (see draw_timeline). Returns (object names, frames
    of the longest object, lost frames over all objects)."""
    fig, names, frames, lost = draw_timeline(csv_path)
    _save(fig, png_path)
    return names, frames, lost


def draw_timeline(csv_path):
    """Error and confidence over a run: per object the ADD-S (or the centre error; in mm, left axis) and
    the confidence (right axis, 0 to 1), the frames it was lost shaded red and those without depth grey.
    Returns (the figure, object names, frames of the longest object, lost frames over all objects)."""
    table = RunTable(csv_path)
    if not table.has("confidence"):
        raise ValueError("'%s' has no confidence column: is it a `depthtrack track --out` CSV?" % csv_path)
    error = next((c for c in ("adds_mm", "err_t_mm") if table.has(c)), None)
    confidence = table.numbers("confidence")
    errors = table.numbers(error) if error else None
    status = table.text("status") if table.has("status") else [""] * len(table.rows)
    objects = table.objects()
    plt = _pyplot()
    fig, axes = plt.subplots(len(objects), 1, sharex=True, squeeze=False, figsize=(9.6, 0.9 + 2.6 * len(objects)),
                             dpi=100)
    lost, x_label = 0, "frame"
    for ax, (name, rows) in zip(axes[:, 0], objects):
        x, x_label = table.times(rows)
        states = [status[r] for r in rows]
        lost += states.count("lost")
        for state, colour, label in (("lost", "tab:red", "lost"), ("no-data", "grey", "no depth")):
            for s, (left, right) in enumerate(_status_spans(x, states, state)):
                ax.axvspan(left, right, color=colour, alpha=0.15, linewidth=0, label=label if s == 0 else None)
        right_ax = ax.twinx()
        every = max(1, len(x) // 30)
        right_ax.plot(x, [confidence[r] for r in rows], color="tab:green", marker="^", markersize=4, markevery=every,
                      linewidth=1.2, label="confidence (right axis)")
        right_ax.set_ylim(-0.02, 1.02)
        right_ax.set_ylabel("confidence (0 to 1)", fontsize=9, color="tab:green")
        if errors is not None:
            y = [errors[r] for r in rows]
            ax.plot(x, y, color="tab:blue", marker="o", markersize=4, markevery=every, linewidth=1.2,
                    label=("ADD-S" if error == "adds_mm" else "centre error") + " (left axis)")
            if _spread_wide(y):
                ax.set_yscale("log")
                _plain_numbers(ax.yaxis)
            ax.set_ylabel(("ADD-S" if error == "adds_mm" else "translation error") + " (mm)", fontsize=9,
                          color="tab:blue")
        else:
            ax.set_yticks([])
            ax.set_ylabel("no ground truth: no error", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.set_title(name or os.path.basename(csv_path), fontsize=10)
        handles, labels = ax.get_legend_handles_labels()
        more_handles, more_labels = right_ax.get_legend_handles_labels()
        ax.legend(handles + more_handles, labels + more_labels, fontsize=8, loc="best", framealpha=0.9)
    axes[-1, 0].set_xlabel(x_label)
    fig.tight_layout()
    return fig, [name for name, _ in objects], max(len(rows) for _, rows in objects), lost


BENCH_COLUMNS = ["sweep", "backend", "mesh", "triangles", "width", "height", "particles", "occlusion", "frame_ms",
                 "memory_mib"]
BENCH_SWEEPS = ("particles", "resolution", "triangles", "occlusion")


def read_cases(csv_path):
    """The rows of a bench CASES.csv as dicts, numbers as floats (NaN where empty)."""
    with open(csv_path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in BENCH_COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            raise ValueError("%s lacks the column(s) %s: is it the cases.csv `depthtrack bench` writes?"
                             % (csv_path, ", ".join(missing)))
        cases = []
        for line, row in enumerate(reader, start=2):
            case = dict(row)
            for column in ("triangles", "width", "height", "particles", "frame_ms", "memory_mib"):
                cell = row[column].strip()
                try:
                    case[column] = float(cell) if cell else math.nan
                except ValueError:
                    raise ValueError("%s line %d: %s '%s' is not a number" % (csv_path, line, column, cell))
            cases.append(case)
    return cases


def _by_backend(cases):
    order = {}
    for c in cases:
        order.setdefault(c["backend"], []).append(c)
    return list(order.items())


def _log_lines(ax, cases, x_of, y_of, colours):
    """A line per backend of y_of(case) over x_of(case), both axes logarithmic with plain-number ticks."""
    for b, (backend, rows) in enumerate(_by_backend(cases)):
        points = sorted((x_of(c), y_of(c)) for c in rows)
        points = [(x, y) for x, y in points if math.isfinite(y) and y > 0]
        if points:
            ax.plot([x for x, _ in points], [y for _, y in points], marker="os^Dv"[b % 5], color=colours[b],
                    linewidth=1.2, label=backend)
    ax.set_xscale("log")
    ax.set_yscale("log")
    _plain_numbers(ax.xaxis)
    _plain_numbers(ax.yaxis)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)


def bench_figure(cases, sweep, png_path):
    """Draws one sweep of `depthtrack bench` as a PNG (see draw_bench)."""
    _save(draw_bench(cases, sweep), png_path)


def draw_bench(cases, sweep):
    """One sweep of `depthtrack bench`, a line (or bar) per backend, times on log axes in ms or
    microseconds: particles (frame time and time per particle against the particle count),
    resolution (frame time against pixels), triangles (frame time against the mesh's triangles),
    occlusion (frame time and device memory per occlusion mode)."""
    from matplotlib.ticker import NullFormatter
    rows = [c for c in cases if c["sweep"] == sweep]
    if not rows:
        raise ValueError("the cases have no '%s' sweep to draw" % sweep)
    plt = _pyplot()
    colours = _colours(max(len(_by_backend(rows)), 2))
    first = rows[0]
    if sweep == "particles":
        fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.4), dpi=100)
        _log_lines(left, rows, lambda c: c["particles"], lambda c: c["frame_ms"], colours)
        left.set_ylabel("frame time (ms)")
        _log_lines(right, rows, lambda c: c["particles"], lambda c: 1000 * c["frame_ms"] / c["particles"], colours)
        right.set_ylabel("time per particle (µs)")
        for ax in (left, right):
            ax.set_xlabel("particles")
        fig.suptitle("Frame time against particles (%s, %dx%d)" % (first["mesh"], first["width"], first["height"]))
    elif sweep == "resolution":
        fig, ax = plt.subplots(figsize=(7.2, 4.8), dpi=100)
        _log_lines(ax, rows, lambda c: c["width"] * c["height"], lambda c: c["frame_ms"], colours)
        sizes = sorted({(c["width"] * c["height"], "%dx%d" % (c["width"], c["height"])) for c in rows})
        ax.set_xticks([p for p, _ in sizes])
        ax.set_xticklabels([name for _, name in sizes], fontsize=8)
        ax.xaxis.set_minor_formatter(NullFormatter())  # the cases' own ticks only
        ax.set_xlabel("image size (pixels, log scale)")
        ax.set_ylabel("frame time (ms)")
        ax.set_title("Frame time against resolution (%s, %d particles)" % (first["mesh"], first["particles"]))
    elif sweep == "triangles":
        fig, ax = plt.subplots(figsize=(7.2, 4.8), dpi=100)
        _log_lines(ax, rows, lambda c: c["triangles"], lambda c: c["frame_ms"], colours)
        meshes = sorted({(c["triangles"], c["mesh"]) for c in rows})
        ax.set_xticks([t for t, _ in meshes])
        ax.set_xticklabels(["%s\n%d" % (name, t) for t, name in meshes], fontsize=8)
        ax.xaxis.set_minor_formatter(NullFormatter())  # the cases' own ticks only
        ax.set_xlabel("mesh triangles (log scale)")
        ax.set_ylabel("frame time (ms)")
        ax.set_title("Frame time against triangles (%dx%d, %d particles)"
                     % (first["width"], first["height"], first["particles"]))
    elif sweep == "occlusion":
        modes = list(dict.fromkeys(c["occlusion"] for c in rows))
        backends = _by_backend(rows)
        memory = [(b, backend, cs) for b, (backend, cs) in enumerate(backends)
                  if any(math.isfinite(c["memory_mib"]) for c in cs)]
        fig, axes = plt.subplots(1, 2 if memory else 1, figsize=(11 if memory else 7.2, 4.6), dpi=100, squeeze=False)
        width = 0.8 / len(backends)

        def bars(ax, series, value):
            for b, backend, cs in series:
                heights = [next((value(c) for c in cs if c["occlusion"] == m), math.nan) for m in modes]
                ax.bar([i - 0.4 + width * (b + 0.5) for i in range(len(modes))], heights, width=width * 0.9,
                       color=colours[b], label=backend)
            ax.set_xticks(range(len(modes)))
            ax.set_xticklabels(modes)
            ax.set_xlabel("occlusion storage")
            ax.grid(alpha=0.3, axis="y", which="both")
            ax.legend(fontsize=8)

        # Times as markers on a log axis (a bar there would start at an arbitrary floor), memory as bars from 0.
        time = axes[0, 0]
        for b, (backend, cs) in enumerate(backends):
            times = [next((c["frame_ms"] for c in cs if c["occlusion"] == m), math.nan) for m in modes]
            time.plot(range(len(modes)), times, marker="os^Dv"[b % 5], markersize=8, linestyle=":", color=colours[b],
                      label=backend)
        time.set_xticks(range(len(modes)))
        time.set_xticklabels(modes)
        time.set_xlim(-0.5, len(modes) - 0.5)
        time.set_xlabel("occlusion storage")
        time.grid(alpha=0.3, axis="y", which="both")
        time.legend(fontsize=8)
        axes[0, 0].set_yscale("log")
        _plain_numbers(axes[0, 0].yaxis)
        axes[0, 0].set_ylabel("frame time (ms)")
        if memory:
            bars(axes[0, 1], memory, lambda c: c["memory_mib"])
            axes[0, 1].set_ylabel("device memory (MiB)")
        fig.suptitle("Occlusion storage modes (%s, %dx%d, %d particles)"
                     % (first["mesh"], first["width"], first["height"], first["particles"]))
    else:
        raise ValueError("unknown bench sweep '%s' (choose %s)" % (sweep, ", ".join(BENCH_SWEEPS)))
    fig.tight_layout()
    return fig


def bench_figures(csv_path, wanted):
    """Draws each (sweep, png path) of wanted from a bench CASES.csv."""
    cases = read_cases(csv_path)
    for sweep, png_path in wanted:
        bench_figure(cases, sweep, png_path)


USAGE = """usage: python3 -m depthtrack.plots reliability FRAMES.csv OUT.png
       python3 -m depthtrack.plots run TRACK.csv OUT.png
       python3 -m depthtrack.plots timeline TRACK.csv OUT.png
       python3 -m depthtrack.plots bench CASES.csv SWEEP=OUT.png [SWEEP=OUT.png ...]"""


def _draw(argv):
    """Runs one command; returns the line it prints."""
    what = argv[0]
    if what == "reliability":
        bins, ece = reliability_diagram(argv[1], argv[2])
        return "reliability diagram: %d frames, ECE %.3f" % (sum(n for n, _, _ in bins), ece)
    if what == "run":
        panels, frames, objects = run_figure(argv[1], argv[2])
        line = "%d panel%s, %d frames" % (len(panels), "" if len(panels) == 1 else "s", frames)
        return line + (", %d objects" % len(objects) if len(objects) > 1 else "")
    if what == "timeline":
        objects, frames, lost = timeline_figure(argv[1], argv[2])
        line = "error and confidence timeline, %d frames, %d lost" % (frames, lost)
        return line + (", %d objects" % len(objects) if len(objects) > 1 else "")
    wanted = []
    for pair in argv[2:]:
        sweep, _, png = pair.partition("=")
        if sweep not in BENCH_SWEEPS or not png:
            raise ValueError("'%s' is not SWEEP=OUT.png with SWEEP one of %s" % (pair, ", ".join(BENCH_SWEEPS)))
        wanted.append((sweep, png))
    bench_figures(argv[1], wanted)
    return "%d figure%s" % (len(wanted), "" if len(wanted) == 1 else "s")


def main(argv):
    known = {"reliability": 3, "run": 3, "timeline": 3}
    if not argv or not (known.get(argv[0]) == len(argv) or (argv[0] == "bench" and len(argv) >= 3)):
        print(USAGE, file=sys.stderr)
        return 2
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("depthtrack.plots: error: " + MISSING_MATPLOTLIB, file=sys.stderr)
        return 1
    try:
        print(_draw(argv))
    except (OSError, ValueError) as e:
        print("depthtrack.plots: error: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
