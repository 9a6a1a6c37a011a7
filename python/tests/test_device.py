"""depthtrack.Device: trackers sharing one device give their own runs' poses, and a compute device
compiles each kernel program once for all the trackers on it."""
import math
import os

import pytest

import depthtrack
from conftest import PARTICLES, SEED, SPREAD_DEGREES, SPREAD_METRES
from test_tracking import assert_same_as_cli


def tracker_on(scene, device, seed=SEED):
    cam = scene["manifest"]["camera"]
    camera = depthtrack.Camera(cam["width"], cam["height"], cam["fx"], cam["fy"], cam["cx"], cam["cy"])
    config = depthtrack.TrackerConfig()
    config.particles, config.width, config.height, config.seed = PARTICLES, 80, 60, seed
    tracker = depthtrack.Tracker(depthtrack.Mesh.load(str(scene["mesh"])), camera, config, device=device)
    tracker.initialize(scene["first_pose"], spread_metres=SPREAD_METRES, spread_radians=math.radians(SPREAD_DEGREES))
    return tracker


def test_two_trackers_on_one_host_device_each_give_the_cli_poses(scene):
    device = depthtrack.Device.open("cpu:2")  # the reference's results, bit for bit
    assert device.is_host and device.program_builds == 0
    a, b = tracker_on(scene, device), tracker_on(scene, device)
    assert a.config.backend == "cpu:2"
    scale = scene["manifest"]["metres_per_unit"]
    first, second = [], []
    for timestamp, units in scene["frames"]:  # interleaved, as a several-object loop runs them
        first.append(a.update(units, timestamp, metres_per_unit=scale))
        second.append(b.update(units, timestamp, metres_per_unit=scale))
    assert_same_as_cli(scene, first)
    assert_same_as_cli(scene, second)


def test_a_compute_device_builds_each_program_once(scene):
    selector = os.environ.get("DEPTHTRACK_TEST_DEVICE", "opencl")
    try:
        device = depthtrack.Device.open(selector)
    except depthtrack.InputError as e:
        pytest.skip(f"no compute device '{selector}': {e}")
    assert not device.is_host
    assert any(d["selector"] for d in depthtrack.Device.list())
    a = tracker_on(scene, device)
    builds = device.program_builds
    assert builds > 0
    b = tracker_on(scene, device, seed=SEED + 1)
    assert device.program_builds == builds
    again = tracker_on(scene, device)
    scale = scene["manifest"]["metres_per_unit"]
    for timestamp, units in scene["frames"][:3]:
        ea, eb, e_again = (t.update(units, timestamp, metres_per_unit=scale) for t in (a, b, again))
        assert (ea.pose == e_again.pose).all()  # same seed on one device: the same estimate
        assert not (ea.pose == eb.pose).all()  # another seed, another cloud: no state is shared


def test_device_open_names_a_bad_selector():
    with pytest.raises(depthtrack.InputError, match="unknown backend 'quantum'"):
        depthtrack.Device.open("quantum")
    with pytest.raises(depthtrack.InputError, match="thread count"):
        depthtrack.Device.open("cpu:0")


def multi_setup(scene):
    """The scene's camera, the CLI run's configuration and the scene's mesh, for the several-object tests."""
    cam = scene["manifest"]["camera"]
    camera = depthtrack.Camera(cam["width"], cam["height"], cam["fx"], cam["fy"], cam["cx"], cam["cy"])
    config = depthtrack.TrackerConfig()
    config.particles, config.width, config.height, config.seed = PARTICLES, 80, 60, SEED
    return camera, config, depthtrack.Mesh.load(str(scene["mesh"]))


def test_multi_tracker_gives_each_object_its_own_run(scene):
    """Two copies of the object at one pose, without mutual occlusion: each gets the CLI's poses."""
    camera, config, mesh = multi_setup(scene)
    multi = depthtrack.MultiTracker([mesh, mesh], camera, config, device=depthtrack.Device.open("cpu:2"),
                                    mutual_occlusion=False)
    assert len(multi) == 2 and multi.device == "cpu:2"
    for i in range(2):
        multi.initialize(i, scene["first_pose"], spread_metres=SPREAD_METRES,
                         spread_radians=math.radians(SPREAD_DEGREES))
    scale = scene["manifest"]["metres_per_unit"]
    per_object = [[], []]
    for timestamp, units in scene["frames"]:
        estimates = multi.update(units, timestamp, metres_per_unit=scale)
        assert len(estimates) == 2
        for i, e in enumerate(estimates):
            per_object[i].append(e)
    assert_same_as_cli(scene, per_object[0])
    assert_same_as_cli(scene, per_object[1])
    # Where the last frame's time went: each object's start, and no mutual occlusion stages without it.
    timings = multi.last_timings
    assert len(timings.object_enqueue_ms) == 2
    assert timings.enqueue_ms == pytest.approx(sum(timings.object_enqueue_ms))
    assert timings.occluders_ms == 0 and timings.masks_ms == 0
    assert timings.total_ms >= timings.enqueue_ms > 0
    with pytest.raises(depthtrack.InputError, match="object 5 does not exist"):
        multi.initialize(5, scene["first_pose"])


def test_multi_tracker_on_one_host_thread_gives_the_same_poses(scene):
    """host_threads only spreads the host's steps: one thread gives the pool's poses, bit for bit."""
    camera, config, mesh = multi_setup(scene)
    runs = []
    for threads in (0, 1):
        multi = depthtrack.MultiTracker([mesh, mesh], camera, config, host_threads=threads)
        for i in range(2):
            multi.initialize(i, scene["first_pose"], spread_metres=SPREAD_METRES,
                             spread_radians=math.radians(SPREAD_DEGREES))
        scale = scene["manifest"]["metres_per_unit"]
        runs.append([[e.pose for e in multi.update(units, timestamp, metres_per_unit=scale)]
                     for timestamp, units in scene["frames"]])
    for pool_frame, serial_frame in zip(runs[0], runs[1]):
        for a, b in zip(pool_frame, serial_frame):
            assert (a == b).all()
    with pytest.raises(depthtrack.InputError, match="host_threads"):
        depthtrack.MultiTracker([mesh], camera, config, host_threads=-1)
