"""Bad input from Python is an exception naming the problem, never a crash."""
import math
import threading

import numpy as np
import pytest

import depthtrack


@pytest.fixture
def tracker():
    config = depthtrack.TrackerConfig()
    config.particles = 20
    t = depthtrack.Tracker(depthtrack.Mesh.builtin(), depthtrack.Camera(80, 60, 66, 66, 39.5, 29.5), config)
    t.initialize(pose_at(0.8))
    return t


def pose_at(z):
    pose = np.eye(4)
    pose[2, 3] = z
    return pose


def frame(value=8000, dtype=np.uint16, shape=(60, 80)):
    return np.full(shape, value, dtype)


def test_error_classes():
    assert issubclass(depthtrack.InputError, ValueError) and issubclass(depthtrack.InputError, depthtrack.Error)
    assert issubclass(depthtrack.BackendError, RuntimeError) and issubclass(depthtrack.BackendError, depthtrack.Error)


@pytest.mark.parametrize("dtype", [np.float64, np.int32, np.uint8, np.int16, np.float16, np.dtype(">f4")])
def test_wrong_dtype(tracker, dtype):
    with pytest.raises(depthtrack.InputError, match="must be float32 .* or uint16 .* got dtype"):
        tracker.update(frame(1, dtype), 0.0, metres_per_unit=1e-3)


@pytest.mark.parametrize("shape", [(60,), (60, 80, 1), (1, 60, 80), ()])
def test_not_two_dimensional(tracker, shape):
    with pytest.raises(depthtrack.InputError, match="must be a 2-D array .* got shape"):
        tracker.update(np.zeros(shape, np.float32), 0.0)


@pytest.mark.parametrize("shape", [(80, 60), (60, 81), (120, 160), (0, 80)])
def test_wrong_size(tracker, shape):
    with pytest.raises(depthtrack.InputError, match="is 80x60|camera is 80x60|no pixels"):
        tracker.update(np.ones(shape, np.float32), 0.0)


def test_not_an_array(tracker):
    with pytest.raises(depthtrack.InputError, match="must be a numpy array .* got list"):
        tracker.update([[1.0] * 80] * 60, 0.0)


def test_metres_per_unit(tracker):
    with pytest.raises(depthtrack.InputError, match="uint16 depth needs metres_per_unit"):
        tracker.update(frame(), 0.0)
    with pytest.raises(depthtrack.InputError, match="float32 depth is in metres already"):
        tracker.update(frame(0.8, np.float32), 0.0, metres_per_unit=1e-3)
    for bad in (0.0, -1e-3, math.nan, math.inf):
        with pytest.raises(depthtrack.InputError, match="metres_per_unit must be finite and positive"):
            tracker.update(frame(), 0.0, metres_per_unit=bad)


def test_negative_depth_names_the_pixel(tracker):
    depth = frame(0.8, np.float32)
    depth[7, 3] = -0.5
    with pytest.raises(depthtrack.InputError, match=r"pixel \(3, 7\) has negative depth"):
        tracker.update(depth, 0.0)


def test_timestamps(tracker):
    with pytest.raises(depthtrack.InputError, match="timestamp is not finite"):
        tracker.update(frame(), math.nan, metres_per_unit=1e-4)
    tracker.update(frame(), 1.0, metres_per_unit=1e-4)
    with pytest.raises(depthtrack.InputError, match="timestamps must increase"):
        tracker.update(frame(), 1.0, metres_per_unit=1e-4)
    with pytest.raises(TypeError):
        tracker.update(frame(), "soon", metres_per_unit=1e-4)
    # Nanoseconds are a unit mistake, named as such.
    with pytest.raises(depthtrack.InputError, match="outside the sane range"):
        tracker.update(frame(), 1.7e18, metres_per_unit=1e-4)


def test_update_before_initialize():
    t = depthtrack.Tracker(depthtrack.Mesh.builtin(), depthtrack.Camera(80, 60, 66, 66, 39.5, 29.5))
    with pytest.raises(depthtrack.InputError, match="before initialize"):
        t.update(frame(), 0.0, metres_per_unit=1e-4)


def test_bad_poses(tracker):
    nan = pose_at(0.8)
    nan[1, 3] = math.nan
    with pytest.raises(depthtrack.InputError, match=r"non-finite entry nan at \[1\]\[3\]"):
        tracker.initialize(nan)
    scaled = pose_at(0.8)
    scaled[:3, :3] *= 2
    with pytest.raises(depthtrack.InputError, match="not a rigid transform.*not a rotation"):
        tracker.initialize(scaled)
    mirrored = pose_at(0.8)
    mirrored[0, 0] = -1
    with pytest.raises(depthtrack.InputError, match="not a rotation"):
        tracker.initialize(mirrored)
    projective = pose_at(0.8)
    projective[3, 2] = 0.1
    with pytest.raises(depthtrack.InputError, match="last row must be 0 0 0 1"):
        tracker.initialize(projective)
    with pytest.raises(depthtrack.InputError, match=r"must be a 4x4 matrix .* got shape \(3, 4\)"):
        tracker.initialize(np.eye(4)[:3])
    with pytest.raises(depthtrack.InputError, match="4x4 matrix of numbers"):
        tracker.initialize("identity")
    with pytest.raises(depthtrack.InputError, match="depth z = -0.8"):
        tracker.initialize(pose_at(-0.8))
    tracker.initialize([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.8], [0, 0, 0, 1]])  # nested lists are fine


def test_mesh_path_that_does_not_exist(tmp_path):
    with pytest.raises(depthtrack.InputError, match="does not exist"):
        depthtrack.Mesh.load(str(tmp_path / "missing.obj"))
    garbage = tmp_path / "garbage.obj"
    garbage.write_bytes(b"\x00\xff not a mesh")
    with pytest.raises(depthtrack.InputError):
        depthtrack.Mesh.load(str(garbage))


def test_bad_camera_and_config():
    with pytest.raises(depthtrack.InputError, match="fx = -1"):
        depthtrack.Camera(80, 60, -1, 66, 39.5, 29.5)
    with pytest.raises(depthtrack.InputError, match="skew"):
        depthtrack.Camera.from_matrix(80, 60, [[66, 1, 39.5], [0, 66, 29.5], [0, 0, 1]])
    camera = depthtrack.Camera.from_matrix(80, 60, [[66, 0, 39.5], [0, 67, 29.5], [0, 0, 1]])
    assert (camera.fx, camera.fy, camera.cx, camera.cy) == (66, 67, 39.5, 29.5)
    config = depthtrack.TrackerConfig()
    config.particles = 0
    with pytest.raises(depthtrack.InputError, match="particle count 0"):
        depthtrack.Tracker(depthtrack.Mesh.builtin(), camera, config)
    config = depthtrack.TrackerConfig()
    config.width = 30  # does not divide 80x60
    with pytest.raises(depthtrack.InputError, match="working resolution 30x60"):
        depthtrack.Tracker(depthtrack.Mesh.builtin(), camera, config)
    config = depthtrack.TrackerConfig()
    config.backend = "no-such-backend"
    with pytest.raises(depthtrack.Error):
        depthtrack.Tracker(depthtrack.Mesh.builtin(), camera, config)
    with pytest.raises(AttributeError):
        config.particle = 5  # a typo is no new attribute
    with pytest.raises(TypeError):
        config.particles = "many"
    with pytest.raises(depthtrack.InputError, match="unknown occlusion mode"):
        config.occlusion_storage = "sometimes"


def test_two_threads_on_one_tracker_take_turns(tracker):
    errors = []

    def run(start):
        try:
            for i in range(5):
                tracker.update(frame(), start + i, metres_per_unit=1e-4)
        except depthtrack.InputError as e:  # the other thread's timestamps may be later: a clear error
            errors.append(str(e))

    threads = [threading.Thread(target=run, args=(s,)) for s in (10.0, 20.0)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all("timestamps must increase" in e for e in errors)


def test_broadcast_depth_of_a_terabyte_is_refused_before_any_copy(tracker):
    huge = np.broadcast_to(np.float32(0.7), (1 << 20, 1 << 20))  # 4 TiB it does not hold
    with pytest.raises(depthtrack.InputError, match=r"shape \(1048576, 1048576\) does not fit the camera"):
        tracker.update(huge, 0.0)
    config = depthtrack.TrackerConfig()
    config.particles = 10
    multi = depthtrack.MultiTracker([depthtrack.Mesh.builtin()], depthtrack.Camera(80, 60, 66, 66, 39.5, 29.5), config)
    with pytest.raises(depthtrack.InputError, match="does not fit the camera, which is 80x60"):
        multi.update(huge, 0.0)
    # A broadcast array of the right size is read (copied once) like any other.
    assert tracker.update(np.broadcast_to(np.float32(0.8), (60, 80)), 0.0).status is not None


def test_config_nested_too_deep_is_an_error_not_a_crash():
    deep = '{"particles": ' + "[" * 200000 + "]" * 200000 + "}"
    with pytest.raises(depthtrack.InputError, match="nested deeper than 64 levels"):
        depthtrack.TrackerConfig.from_json(deep)
    with pytest.raises(depthtrack.InputError, match=r"must be an integer, got a string \"x+\.\.\.$"):
        depthtrack.TrackerConfig.from_json('{"particles": "' + "x" * 100000 + '"}')


def test_perturb_pose_refuses_nan():
    with pytest.raises(depthtrack.InputError, match="must be finite"):
        depthtrack.perturb_pose(pose_at(0.8), [0, 0, 0], math.nan, 5.0, 1)


def test_implausible_focal_length():
    for fx in (1e-300, 1e300):
        with pytest.raises(depthtrack.InputError, match="field of view"):
            depthtrack.Camera(640, 480, fx, 525, 319.5, 239.5)
