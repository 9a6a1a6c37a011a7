"""python/examples/track_ycbv_objects.py against `depthtrack track` on ycbv-0000's three objects: the
same seeds and starts, so each object's last-frame ADD-S must be the CLI's (within 0.5 mm), with
mutual occlusion on and off; without it, also each object's own single-object run. Skips without the data."""
import csv
import os
import pathlib
import subprocess
import sys

import pytest

from conftest import cli

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = pathlib.Path(os.environ.get("DEPTHTRACK_DATA_DIR", ROOT.parent / "shared" / "data"))
PARTICLES = 40
sys.path.insert(0, str(ROOT / "python" / "examples"))

from track_ycbv_objects import OBJECTS, track  # noqa: E402


def have_data():
    return (DATA / "sequences" / "ycbv-0000" / "gt.json").exists() and all(
        (DATA / "meshes" / "ycb" / (name + ".obj")).exists() for name in OBJECTS)


def cli_last_adds(tmp_path, names, mutual_occlusion):
    """{name: last-frame adds_mm} of one `depthtrack track` run of the objects named."""
    out = tmp_path / ("cli-%s-%s.csv" % ("-".join(names), mutual_occlusion))
    command = [cli(), "track", "--sequence", str(DATA / "sequences" / "ycbv-0000"), "--init-from-gt",
               "--init-perturb", "0.01 5", "--particles", str(PARTICLES), "--resolution", "80x60",
               "--backend", "reference", "--out", str(out)]
    for name in names:  # one object: --object picks its ground truth in the clip
        command += ["--mesh", str(DATA / "meshes" / "ycb" / (name + ".obj")), "--object", name]
    if len(names) > 1:
        command += ["--mutual-occlusion", mutual_occlusion]
    subprocess.run(command, check=True, capture_output=True)
    with open(out) as f:
        rows = list(csv.DictReader(f))
    return {row.get("object", names[0]): float(row["adds_mm"]) for row in rows}  # the last row per object wins


@pytest.mark.skipif(not have_data(), reason="../shared/data lacks ycbv-0000 or its YCB meshes")
@pytest.mark.parametrize("mutual_occlusion", ["on", "off"])
def test_the_python_run_gives_each_object_the_cli_last_frame_adds(tmp_path, mutual_occlusion):
    python = track(str(DATA), particles=PARTICLES, backend="reference", mutual_occlusion=mutual_occlusion == "on")
    together = cli_last_adds(tmp_path, list(OBJECTS), mutual_occlusion)
    assert set(python) == set(together) == set(OBJECTS)
    for name in OBJECTS:
        assert abs(1000 * python[name] - together[name]) <= 0.5, name
        assert 1000 * python[name] == pytest.approx(together[name], abs=1e-3), name  # same seeds: equal
    if mutual_occlusion == "off":
        for name in OBJECTS:  # nothing is shared between the objects: each is its own single-object run
            assert abs(1000 * python[name] - cli_last_adds(tmp_path, [name], "off")[name]) <= 1e-3, name
