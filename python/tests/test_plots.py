"""depthtrack.plots.reliability_diagram on a hand-made frames CSV: the bins and calibration error it
reports (worked out by hand) and the PNG it writes."""
import importlib.util
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
