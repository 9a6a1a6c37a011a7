"""Frame sources from Python: a raw depth stream written here and the synthesized folder give the same frames,
and tracking them (or a generator's frames) through track_frames gives `depthtrack track`'s poses."""

import numpy as np
import pytest

import depthtrack
from conftest import csv_pose, make_tracker


def metres_of(units, scale):
    metres = (units.astype(np.float64) * scale).astype(np.float32)
    metres[units == 0] = np.nan
    return metres


def write_raw_stream(path, scene):
    """Even frames as float32 metres, odd ones as uint16 units: the format's two pixel types."""
    cam = scene["manifest"]["camera"]
    scale = scene["manifest"]["metres_per_unit"]
    with open(path, "wb") as out:
        out.write(("depthtrack-raw-depth 1 %d %d %r %r %r %r\n" % (
            cam["width"], cam["height"], cam["fx"], cam["fy"], cam["cx"], cam["cy"])).encode())
        for i, (timestamp, units) in enumerate(scene["frames"]):
            if i % 2 == 0:
                out.write(("%r f32\n" % timestamp).encode())
                out.write(np.nan_to_num(metres_of(units, scale), nan=0.0).astype("<f4").tobytes())
            else:
                out.write(("%r u16 %r\n" % (timestamp, scale)).encode())
                out.write(units.astype("<u2").tobytes())


def assert_cli_poses(scene, estimates):
    assert len(estimates) == len(scene["rows"]) == 10
    for estimate, row in zip(estimates, scene["rows"]):
        expected = csv_pose(row)  # printed with 9 significant digits
        np.testing.assert_allclose(estimate.pose[:3, 3], expected[:3, 3], rtol=0, atol=2e-8)
        np.testing.assert_allclose(estimate.pose[:3, :3], expected[:3, :3], rtol=0, atol=2e-8)


def test_raw_stream_and_folder_give_the_same_frames(scene, tmp_path):
    stream = tmp_path / "frames.raw"
    write_raw_stream(stream, scene)
    raw = depthtrack.open_source("raw:" + str(stream))
    folder = depthtrack.open_source(str(scene["sequence"]))
    assert raw.size is None
    assert folder.size == 10
    assert (raw.camera.width, raw.camera.height, raw.camera.fx) == (160, 120, scene["manifest"]["camera"]["fx"])
    count = 0
    for a, b, (timestamp, units) in zip(raw, folder, scene["frames"]):
        assert a.timestamp == b.timestamp == timestamp
        expected = metres_of(units, scene["manifest"]["metres_per_unit"])
        np.testing.assert_array_equal(a.depth, expected)  # NaN where missing, in both
        np.testing.assert_array_equal(b.depth, expected)
        assert a.ground_truth is None
        np.testing.assert_allclose(b.ground_truth, np.array(scene["manifest"]["frames"][count]["T_cam_obj"],
                                                            float).reshape(4, 4), rtol=0, atol=1e-12)
        count += 1
    assert count == 10
    with pytest.raises(StopIteration):
        next(raw)


def test_track_frames_gives_the_cli_poses_from_a_stream_and_from_a_generator(scene, tmp_path):
    stream = tmp_path / "frames.raw"
    write_raw_stream(stream, scene)
    assert_cli_poses(scene, list(depthtrack.track_frames(make_tracker(scene),
                                                         depthtrack.open_source("raw:" + str(stream)))))
    scale = scene["manifest"]["metres_per_unit"]
    generator = ((units, timestamp) for timestamp, units in scene["frames"])
    assert_cli_poses(scene, list(depthtrack.track_frames(make_tracker(scene), generator, metres_per_unit=scale)))


def test_open_source_refuses_bad_specs_and_ranges(scene, tmp_path):
    with pytest.raises(depthtrack.InputError, match="unknown kind 'camera'"):
        depthtrack.open_source("camera:0")
    with pytest.raises(depthtrack.InputError, match="the range is empty"):
        depthtrack.open_source(str(scene["sequence"]), frames="5:2")
    bad = tmp_path / "bad.raw"
    bad.write_bytes(b"P5 2 2\n")
    with pytest.raises(depthtrack.InputError, match="is not a raw depth stream"):
        depthtrack.open_source("raw:" + str(bad))
    cut = depthtrack.open_source(str(scene["sequence"]), frames="7:")
    assert [f.name for f in cut] == [f["name"] for f in scene["manifest"]["frames"][7:]]
