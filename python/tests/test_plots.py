"""depthtrack.plots on hand-made CSVs: the reliability bins and calibration error (worked out by hand),
the track run's panels and timeline (a line per object, its own rows), the bench figures' log axes, the
PNGs written, and the refusals."""
import importlib.util
import os
import pathlib
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib", reason="python3-matplotlib is not installed")


def load_plots():
    """The module from the source tree: it is pure Python, so the compiled bindings need not be built."""
    path = pathlib.Path(__file__).resolve().parents[1] / "depthtrack" / "plots.py"
    spec = importlib.util.spec_from_file_location("depthtrack_plots", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


plots = load_plots()

HEADER = "object,case,frame,timestamp,adds_mm,confidence,status,within_tolerance\n"
ROWS = [  # confidence, within tolerance ('' = no ground truth, left out)
    (0.05, "1"), (0.05, "0"), (0.95, "1"), (1.0, "1"), (0.92, "0"), (0.5, "1"), (0.7, ""),
]


def write_csv(path):
    lines = [HEADER]
    for i, (confidence, within) in enumerate(ROWS):
        adds = "" if within == "" else ("3.5" if within == "1" else "25")
        lines.append("box,perturbed-1,%06d,%g,%s,%g,tracking,%s\n" % (i, i / 30, adds, confidence, within))
    path.write_text("".join(lines))


def test_reliability_diagram_bins_and_png(tmp_path):
    csv_path, png_path = tmp_path / "frames.csv", tmp_path / "reliability.png"
    write_csv(csv_path)
    bins, ece = plots.reliability_diagram(str(csv_path), str(png_path))
    assert len(bins) == 10
    assert bins[0] == (2, pytest.approx(0.05), pytest.approx(0.5))
    assert bins[5] == (1, pytest.approx(0.5), pytest.approx(1.0))
    assert bins[7] == (0, None, None)  # 0.7 had no ground truth
    assert bins[9] == (3, pytest.approx(2.87 / 3), pytest.approx(2 / 3))
    # 2/6 * |0.5 - 0.05| + 3/6 * |2/3 - 2.87/3| + 1/6 * |1 - 0.5|
    assert ece == pytest.approx(0.15 + 0.145 + 0.5 / 6)
    data = png_path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 10000  # a drawn figure, not an empty canvas
    assert not (tmp_path / "reliability.png.partial").exists()


def test_module_entry_point(tmp_path):
    csv_path, png_path = tmp_path / "frames.csv", tmp_path / "out.png"
    write_csv(csv_path)
    done = subprocess.run([sys.executable, plots.__file__, "reliability", str(csv_path), str(png_path)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "6 frames, ECE 0.378" in done.stdout
    assert png_path.read_bytes()[:4] == b"\x89PNG"
    # A CSV without the columns is refused with a reason.
    (tmp_path / "bad.csv").write_text("frame,adds_mm\n1,2\n")
    bad = subprocess.run([sys.executable, plots.__file__, "reliability", str(tmp_path / "bad.csv"),
                          str(tmp_path / "bad.png")], capture_output=True, text=True)
    assert bad.returncode == 1
    assert "lacks the column(s) confidence, within_tolerance" in bad.stderr
    assert not (tmp_path / "bad.png").exists()


RUN_HEADER = "object,frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess,err_t_mm,err_r_deg,adds_mm,latency_ms,confidence,status\n"


def write_two_objects(path):
    """Two objects over four frames at 10 Hz starting at a Unix time: the mug lost in frames 1-2."""
    lines = [RUN_HEADER]
    for i in range(4):
        lost = i in (1, 2)
        lines.append("mug,%06d,%.1f,0,0,1,1,0,0,0,40,%g,1,%g,5,%g,%s\n"
                     % (i, 1.7e9 + i / 10, 300 if lost else 2 + i, 250 if lost else 1 + i, 0.1 if lost else 0.9,
                        "lost" if lost else "tracking"))
        lines.append("box,%06d,%.1f,0,0,1,1,0,0,0,50,%g,2,%g,6,0.8,tracking\n" % (i, 1.7e9 + i / 10, 10 + i, 8 + i))
    path.write_text("".join(lines))


def test_run_figure_draws_each_object_as_its_own_line(tmp_path):
    csv_path = tmp_path / "run.csv"
    write_two_objects(csv_path)
    fig, panels, frames, names = plots.draw_run(str(csv_path))
    assert names == ["mug", "box"]
    assert frames == 4
    assert panels == ["translation error (mm)", "rotation error (deg)", "confidence (0 to 1)",
                      "effective sample size (particles)", "latency, depth in to pose out (ms)"]
    translation = fig.axes[0]
    lines = {line.get_label(): line for line in translation.get_lines()}
    assert set(lines) == {"mug centre", "mug ADD-S", "box centre", "box ADD-S"}
    # Each object's own rows, against seconds since the first frame (not one saw-tooth over all rows).
    assert list(lines["mug centre"].get_xdata()) == pytest.approx([0, 0.1, 0.2, 0.3])
    assert list(lines["mug centre"].get_ydata()) == [2, 300, 300, 5]
    assert list(lines["box ADD-S"].get_ydata()) == [8, 9, 10, 11]
    assert all(line.get_marker() not in (None, "None", "") for line in translation.get_lines())
    assert translation.get_legend() is not None
    # 1 to 300 mm spans over two decades: a log axis labelled in millimetres, not powers of ten.
    assert translation.get_yscale() == "log"
    assert translation.yaxis.get_major_formatter()(100, 0) == "100"
    assert fig.axes[1].get_yscale() == "linear"
    assert [line.get_label() for line in fig.axes[2].get_lines()] == ["mug", "box"]
    assert fig.axes[-1].get_xlabel() == "time since the first frame (s)"
    plots._pyplot().close(fig)


def test_run_figure_png_size_and_entry_point(tmp_path):
    csv_path, png_path = tmp_path / "run.csv", tmp_path / "run.png"
    write_two_objects(csv_path)
    done = subprocess.run([sys.executable, plots.__file__, "run", str(csv_path), str(png_path)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "5 panels, 4 frames, 2 objects"
    data = png_path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(data[16:20], "big") == 960  # 9.6 inches at 100 dpi
    assert int.from_bytes(data[20:24], "big") == 80 + 5 * 220  # 0.8 inches and 2.2 per panel


def test_timeline_marks_lost_frames_and_plots_both_quantities(tmp_path):
    csv_path = tmp_path / "run.csv"
    write_two_objects(csv_path)
    fig, names, frames, lost = plots.draw_timeline(str(csv_path))
    assert (names, frames, lost) == (["mug", "box"], 4, 2)
    mug = fig.axes[0]
    error = [line for line in mug.get_lines() if line.get_label().startswith("ADD-S")]
    assert len(error) == 1 and list(error[0].get_ydata()) == [1, 250, 250, 4]
    # The lost frames 1 and 2 (0.1 s and 0.2 s) shaded as one span reaching halfway to their neighbours.
    spans = [p for p in mug.patches if p.get_label() == "lost"]
    assert len(spans) == 1
    xs = [x for x, _ in spans[0].get_xy()]
    left, right = min(xs), max(xs)
    assert (left, right) == (pytest.approx(0.05), pytest.approx(0.25))
    confidence = [ax for ax in fig.axes if ax.get_ylabel() == "confidence (0 to 1)"]
    assert len(confidence) == 2
    assert list(confidence[0].get_lines()[0].get_ydata()) == [0.9, 0.1, 0.1, 0.9]
    plots._pyplot().close(fig)


def test_status_spans_by_hand():
    x = [0, 1, 2, 3, 4]
    assert plots._status_spans(x, ["lost", "tracking", "lost", "lost", "tracking"], "lost") == [(-0.5, 0.5), (1.5, 3.5)]
    assert plots._status_spans(x, ["tracking"] * 5, "lost") == []


CASES = """sweep,backend,mesh,triangles,width,height,particles,occlusion,frame_ms,memory_mib
particles,reference,handset,1200,80,60,10,per-pixel-time,2,
particles,reference,handset,1200,80,60,100,per-pixel-time,20,
particles,opencl:0,handset,1200,80,60,100,per-pixel-time,0.5,1.5
particles,opencl:0,handset,1200,80,60,10,per-pixel-time,0.2,0.25
occlusion,reference,handset,1200,80,60,200,per-pixel-time,40,
occlusion,reference,handset,1200,80,60,200,off,30,
occlusion,opencl:0,handset,1200,80,60,200,per-pixel-time,1,3
occlusion,opencl:0,handset,1200,80,60,200,off,0.8,2
"""


def test_bench_figures_log_axes_in_real_units(tmp_path):
    csv_path = tmp_path / "cases.csv"
    csv_path.write_text(CASES)
    cases = plots.read_cases(str(csv_path))
    fig = plots.draw_bench(cases, "particles")
    frame, per_particle = fig.axes
    lines = {line.get_label(): line for line in frame.get_lines()}
    assert list(lines["reference"].get_xdata()) == [10, 100]
    assert list(lines["opencl:0"].get_ydata()) == [0.2, 0.5]  # sorted by particles
    assert list({l.get_label(): l for l in per_particle.get_lines()}["reference"].get_ydata()) == [200, 200]  # us
    assert frame.get_xscale() == frame.get_yscale() == "log"
    assert frame.get_ylabel() == "frame time (ms)"
    assert frame.yaxis.get_major_formatter()(0.1, 0) == "0.1"
    plots._pyplot().close(fig)
    fig = plots.draw_bench(cases, "occlusion")
    time, memory = fig.axes
    assert [t.get_text() for t in time.get_xticklabels()] == ["per-pixel-time", "off"]
    times = {line.get_label(): list(line.get_ydata()) for line in time.get_lines()}
    assert times == {"reference": [40, 30], "opencl:0": [1, 0.8]}
    assert time.get_yscale() == "log"
    assert [p.get_height() for p in memory.patches] == [3, 2]  # only the device reports memory
    plots._pyplot().close(fig)
    with pytest.raises(ValueError, match="no 'resolution' sweep"):
        plots.draw_bench(cases, "resolution")
    written = subprocess.run([sys.executable, plots.__file__, "bench", str(csv_path),
                              "particles=" + str(tmp_path / "p.png"), "occlusion=" + str(tmp_path / "o.png")],
                             capture_output=True, text=True)
    assert written.returncode == 0, written.stderr
    assert (tmp_path / "p.png").read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "o.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("text, message", [
    ("", "is empty: expected a header line"),
    ("frame,ess\n", "has a header but no rows"),
    ("frame,ess\n0,1\n1\n", "line 3 has 1 cells; the header has 2"),
    ("frame,ess\n0,1\n1,lots\n", "line 3: column 'ess' holds 'lots', not a number"),
    ("a,b\n1,2\n", "has none of the columns plot shows"),
])
def test_run_figure_refuses_bad_csv(tmp_path, text, message):
    (tmp_path / "bad.csv").write_text(text)
    done = subprocess.run([sys.executable, plots.__file__, "run", str(tmp_path / "bad.csv"), str(tmp_path / "x.png")],
                          capture_output=True, text=True)
    assert done.returncode == 1
    assert message in done.stderr
    assert not (tmp_path / "x.png").exists()


def test_missing_matplotlib_is_named(tmp_path):
    """With a matplotlib that cannot be imported first on the path, the module says what to install."""
    fake = tmp_path / "fake" / "matplotlib"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text("raise ImportError('no matplotlib here')\n")
    (tmp_path / "run.csv").write_text("frame,ess\n0,1\n")
    done = subprocess.run([sys.executable, plots.__file__, "run", str(tmp_path / "run.csv"), str(tmp_path / "x.png")],
                          capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(tmp_path / "fake")})
    assert done.returncode == 1
    assert "matplotlib is not installed (Debian: apt install python3-matplotlib)" in done.stderr


def test_log_axis_labels_plain_numbers_and_narrow_spans():
    plt = plots._pyplot()
    fig, ax = plt.subplots()
    ax.set_yscale("log")
    plots._plain_numbers(ax.yaxis)
    major, minor = ax.yaxis.get_major_formatter(), ax.yaxis.get_minor_formatter()
    assert [major(v, 0) for v in (0.01, 1, 1000)] == ["0.01", "1", "1000"]
    ax.set_ylim(2, 7)  # under a decade: 2 and 5 labelled as well
    assert [minor(v, 0) for v in (2, 3, 5, 6)] == ["2", "", "5", ""]
    ax.set_ylim(0.65, 0.9)  # under a factor of 3: every tick
    assert [minor(v, 0) for v in (0.7, 0.8)] == ["0.7", "0.8"]
    ax.set_ylim(0.1, 100)  # three decades: the powers of ten are enough
    assert minor(5, 0) == ""
    plt.close(fig)
