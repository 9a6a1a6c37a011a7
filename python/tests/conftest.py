"""Shared fixtures: an object mesh, a sequence synthesized by `depthtrack synth` and the poses
`depthtrack track` (the C++ API behind the command line) estimates on it."""
import csv
import json
import math
import os
import subprocess

import numpy as np
import pytest

from png16 import read_png16

PARTICLES, SEED = 60, 5
SPREAD_METRES, SPREAD_DEGREES = 0.01, 5.0  # track's default --init-spread


def write_two_boxes(path):
    """An asymmetric object, 16 x 9 x 6 cm and a 6 cm cube beside it, as an OBJ file."""
    lines, faces = [], []
    for centre, size in (((0.0, 0.0, 0.0), (0.16, 0.09, 0.06)), ((0.06, 0.07, 0.0), (0.06, 0.06, 0.06))):
        base = len(lines)
        for i in range(8):
            corner = [centre[k] + (0.5 if (i >> k) & 1 else -0.5) * size[k] for k in range(3)]
            lines.append("v %.6f %.6f %.6f" % tuple(corner))
        for a, b, c, d in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)):
            faces.append("f %d %d %d" % (base + a + 1, base + b + 1, base + c + 1))
            faces.append("f %d %d %d" % (base + a + 1, base + c + 1, base + d + 1))
    path.write_text("\n".join(lines + faces) + "\n")


def cli():
    return os.environ.get("DEPTHTRACK_CLI", "depthtrack")


@pytest.fixture(scope="session")
def scene(tmp_path_factory):
    root = tmp_path_factory.mktemp("scene")
    mesh = root / "two_boxes.obj"
    write_two_boxes(mesh)
    sequence = root / "sequence"
    subprocess.run([cli(), "synth", "--mesh", str(mesh), "--out", str(sequence), "--frames", "10", "--resolution",
                    "160x120", "--occluder", "0.3", "--seed", "3"], check=True, capture_output=True)
    track_csv = root / "track.csv"
    subprocess.run([cli(), "track", "--mesh", str(mesh), "--sequence", str(sequence), "--out", str(track_csv),
                    "--init-from-gt", "--particles", str(PARTICLES), "--resolution", "80x60", "--seed", str(SEED),
                    "--init-spread", f"{SPREAD_METRES} {SPREAD_DEGREES}"], check=True, capture_output=True)
    manifest = json.loads((sequence / "sequence.json").read_text())
    frames = [(f["timestamp"], read_png16(sequence / f["depth"])) for f in manifest["frames"]]
    with open(track_csv) as f:
        rows = list(csv.DictReader(f))
    return {"mesh": mesh, "sequence": sequence, "manifest": manifest, "frames": frames, "rows": rows,
            "first_pose": np.array(manifest["frames"][0]["T_cam_obj"], float).reshape(4, 4)}


def make_tracker(scene):
    """A tracker on the scene's camera and mesh, started at its first pose as `depthtrack track` starts."""
    import depthtrack

    cam = scene["manifest"]["camera"]
    camera = depthtrack.Camera(cam["width"], cam["height"], cam["fx"], cam["fy"], cam["cx"], cam["cy"])
    config = depthtrack.TrackerConfig()
    config.particles, config.width, config.height, config.seed = PARTICLES, 80, 60, SEED
    tracker = depthtrack.Tracker(depthtrack.Mesh.load(str(scene["mesh"])), camera, config)
    tracker.initialize(scene["first_pose"], spread_metres=SPREAD_METRES, spread_radians=math.radians(SPREAD_DEGREES))
    return tracker


def csv_pose(row):
    """The 4x4 pose of a `depthtrack track` CSV row (quaternion qw qx qy qz)."""
    w, x, y, z = (float(row[k]) for k in ("qw", "qx", "qy", "qz"))
    n = np.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    pose = np.eye(4)
    pose[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    pose[:3, 3] = [float(row[k]) for k in ("tx", "ty", "tz")]
    return pose
