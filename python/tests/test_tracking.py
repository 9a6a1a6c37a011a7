"""The bindings give the C++ API's poses (`depthtrack track`'s CSV, same seed) for uint16 and float32
numpy frames, contiguous or not."""
import csv
import math
import subprocess

import numpy as np
import pytest

import depthtrack
from conftest import PARTICLES, SEED, SPREAD_DEGREES, SPREAD_METRES, cli, csv_pose, make_tracker


def track(scene, to_input):
    """Estimates of every frame, each frame given as to_input(units) -> (depth, metres_per_unit)."""
    tracker = make_tracker(scene)
    estimates = []
    for timestamp, units in scene["frames"]:
        depth, scale = to_input(units)
        estimates.append(tracker.update(depth, timestamp, metres_per_unit=scale))
    return estimates


def metres_of(units, scale):
    """float32 metres as the library computes them from units (double product, rounded once), NaN = missing."""
    metres = (units.astype(np.float64) * scale).astype(np.float32)
    metres[units == 0] = np.nan
    return metres


def assert_same_as_cli(scene, estimates):
    assert len(estimates) == len(scene["rows"]) == 10
    for estimate, row in zip(estimates, scene["rows"]):
        expected = csv_pose(row)  # printed with 9 significant digits
        np.testing.assert_allclose(estimate.pose[:3, 3], expected[:3, 3], rtol=0, atol=2e-8)
        np.testing.assert_allclose(estimate.pose[:3, :3], expected[:3, :3], rtol=0, atol=2e-8)
        assert estimate.ess == pytest.approx(float(row["ess"]), rel=1e-8)
        assert estimate.status == row["status"]
        assert estimate.confidence == pytest.approx(float(row["confidence"]), rel=1e-8)


def test_uint16_frames_give_the_cli_poses(scene):
    scale = scene["manifest"]["metres_per_unit"]
    estimates = track(scene, lambda units: (units, scale))
    assert_same_as_cli(scene, estimates)
    # And they follow the object: the CSV's ground-truth errors are small.
    assert max(float(r["err_t_mm"]) for r in scene["rows"]) < 15


def test_float32_frames_give_the_cli_poses(scene):
    scale = scene["manifest"]["metres_per_unit"]
    assert_same_as_cli(scene, track(scene, lambda units: (metres_of(units, scale), None)))


def test_a_slice_of_a_larger_array_is_read_through_its_strides(scene):
    scale = scene["manifest"]["metres_per_unit"]

    def window(units):
        h, w = units.shape
        big = np.full((h + 7, w + 11), 65535, np.uint16)  # far readings around the window
        big[4 : 4 + h, 6 : 6 + w] = units
        view = big[4 : 4 + h, 6 : 6 + w]
        assert not view.flags.c_contiguous
        return view, scale

    assert_same_as_cli(scene, track(scene, window))


def test_column_strided_and_fortran_arrays_are_copied_and_give_the_same_poses(scene):
    scale = scene["manifest"]["metres_per_unit"]

    def every_other_column(units):
        h, w = units.shape
        wide = np.zeros((h, 2 * w), np.float32)
        wide[:, ::2] = metres_of(units, scale)
        return wide[:, ::2], None

    assert_same_as_cli(scene, track(scene, every_other_column))
    assert_same_as_cli(scene, track(scene, lambda units: (np.asfortranarray(metres_of(units, scale)), None)))


def test_estimate_carries_every_field_of_the_cpp_estimate(scene):
    scale = scene["manifest"]["metres_per_unit"]
    tracker = make_tracker(scene)
    timestamp, units = scene["frames"][0]
    e = tracker.update(units, timestamp, metres_per_unit=scale)
    assert e.pose.shape == (4, 4) and e.pose.dtype == np.float64
    np.testing.assert_allclose(e.pose[3], [0, 0, 0, 1])
    np.testing.assert_allclose(e.pose[:3, :3] @ e.pose[:3, :3].T, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(e.pose[:3, 3], e.translation)
    assert e.quaternion.shape == (4,) and np.linalg.norm(e.quaternion) == pytest.approx(1.0)
    assert e.covariance.shape == (6, 6)
    np.testing.assert_allclose(e.covariance, e.covariance.T, rtol=1e-9, atol=1e-18)
    assert np.all(np.diag(e.covariance) > 0)  # refinement is on: a real covariance
    assert e.linear_velocity.shape == (3,) and e.angular_velocity.shape == (3,)
    assert 1 <= e.effective_sample_size <= PARTICLES and e.ess == e.effective_sample_size
    assert e.max_log_likelihood >= e.mean_log_likelihood
    assert isinstance(e.resampled, bool) and isinstance(e.recovered, bool) and e.search_poses == 0
    assert e.particles == PARTICLES  # no budget: the configured count
    assert 0.5 <= e.confidence <= 1 and e.status == "tracking"  # tracking means a supported pose
    ev = e.evidence  # what the confidence rests on: shares of the silhouette's measured pixels
    assert ev.pixels > 0 and ev.visible + ev.occluded + ev.contradicted == pytest.approx(1.0)
    assert 0 <= ev.separated <= 1 and 0 <= ev.missing <= 1 and ev.visible_rms >= 0 and ev.plane_rms >= 0
    t = e.timings
    assert t.total_ms > 0 and t.weigh_ms > 0 and t.refine_ms > 0 and t.search_ms == 0
    assert t.propagate_ms >= 0 and t.render_ms >= 0 and t.handoff_ms == 0 and t.resample_ms >= 0


def test_a_budgeted_run_is_replayed_by_its_particle_counts(scene):
    """budget_ms chooses each frame's count; the reference given the same counts by hand gives the same poses."""
    scale = scene["manifest"]["metres_per_unit"]
    cam = scene["manifest"]["camera"]
    camera = depthtrack.Camera(cam["width"], cam["height"], cam["fx"], cam["fy"], cam["cx"], cam["cy"])
    mesh = depthtrack.Mesh.load(str(scene["mesh"]))

    def tracker(budget_ms, backend):
        config = depthtrack.TrackerConfig()
        config.particles, config.width, config.height, config.seed = PARTICLES, 80, 60, SEED
        config.budget_ms, config.min_particles, config.backend = budget_ms, 5, backend
        return depthtrack.Tracker(mesh, camera, config)

    budgeted = tracker(1e4, "cpu:2")  # ample: the counts follow the estimate alone
    first_pose = scene["first_pose"]
    spread = dict(spread_metres=SPREAD_METRES, spread_radians=math.radians(SPREAD_DEGREES))
    budgeted.initialize(first_pose, **spread)
    chosen = [budgeted.update(units, t, metres_per_unit=scale) for t, units in scene["frames"]]
    counts = [e.particles for e in chosen]
    # Primed before the first frame, the ample budget affords the most at once; fewer once confident.
    assert counts[0] == PARTICLES and counts[1] == PARTICLES and len(set(counts)) >= 2
    with pytest.raises(depthtrack.InputError, match="budget"):
        budgeted.set_particle_count(7)
    replay = tracker(0, "reference")
    replay.set_particle_count(counts[0])
    replay.initialize(first_pose, **spread)
    for i, (t, units) in enumerate(scene["frames"]):
        if i > 0:
            replay.set_particle_count(counts[i])
        e = replay.update(units, t, metres_per_unit=scale)
        assert e.particles == counts[i]
        np.testing.assert_array_equal(e.pose, chosen[i].pose)
        assert e.confidence == chosen[i].confidence


def test_initialize_global_with_a_box_gives_the_cli_pose(scene, tmp_path):
    cam = scene["manifest"]["camera"]
    camera = depthtrack.Camera(cam["width"], cam["height"], cam["fx"], cam["fy"], cam["cx"], cam["cy"])
    mesh = depthtrack.Mesh.load(str(scene["mesh"]))
    # The box a detector would give: the object's vertices at the true pose, projected.
    points = scene["first_pose"][:3, :3] @ mesh.vertices.T.astype(float) + scene["first_pose"][:3, 3:]
    u = camera.fx * points[0] / points[2] + camera.cx
    v = camera.fy * points[1] / points[2] + camera.cy
    box = (int(u.min()), int(v.min()), int(math.ceil(u.max())), int(math.ceil(v.max())))
    out = tmp_path / "global.csv"
    subprocess.run([cli(), "track", "--mesh", str(scene["mesh"]), "--sequence", str(scene["sequence"]), "--out",
                    str(out), "--init-box", " ".join(map(str, box)), "--particles", str(PARTICLES), "--seed",
                    str(SEED)], check=True, capture_output=True)
    with open(out) as f:
        first = next(csv.DictReader(f))

    config = depthtrack.TrackerConfig()
    config.particles, config.seed = PARTICLES, SEED
    tracker = depthtrack.Tracker(mesh, camera, config)
    timestamp, units = scene["frames"][0]
    e = tracker.initialize_global(units, timestamp, metres_per_unit=scene["manifest"]["metres_per_unit"], box=box)
    assert e.search_poses > 0 and e.timings.search_ms > 0
    # The box search scores poses, checks their agreement with the box and fits the best ones, within its time.
    t = e.timings
    assert t.search_scoring_ms > 0 and t.search_box_ms > 0 and t.search_fit_ms > 0
    assert t.search_scoring_ms + t.search_box_ms + t.search_fit_ms <= t.search_ms
    expected = csv_pose(first)
    np.testing.assert_allclose(e.pose[:3, 3], expected[:3, 3], rtol=0, atol=2e-8)
    np.testing.assert_allclose(e.pose[:3, :3], expected[:3, :3], rtol=0, atol=2e-8)
    with pytest.raises(depthtrack.InputError, match="a box or a point, not both"):
        tracker.initialize_global(units, timestamp + 1, metres_per_unit=1e-4, box=box, point=(0, 0, 1))


def test_version_and_devices():
    assert depthtrack.__version__.count(".") == 2
    devices = depthtrack.devices()
    assert isinstance(devices, list)
    for d in devices:
        assert d["backend"] in ("opencl", "cuda") and d["selector"].startswith(d["backend"])
        assert d["global_memory_bytes"] > 0 and isinstance(d["extensions"], list)


def write_sphere(path, radius=0.05, rings=24, segments=48):
    """A closed UV sphere (poles fanned) as OBJ: finely tessellated, so simplification has work to do."""
    lines = [f"v 0 0 {radius}"]
    for r in range(1, rings):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            lines.append(f"v {radius * math.sin(theta) * math.cos(phi)} {radius * math.sin(theta) * math.sin(phi)} "
                         f"{radius * math.cos(theta)}")
    lines.append(f"v 0 0 {-radius}")
    at = lambda r, s: 2 + (r - 1) * segments + s % segments  # OBJ indices start at 1
    south = 1 + 1 + (rings - 1) * segments
    for s in range(segments):
        lines.append(f"f 1 {at(1, s)} {at(1, s + 1)}")
        lines.append(f"f {south} {at(rings - 1, s + 1)} {at(rings - 1, s)}")
        for r in range(1, rings - 1):
            lines.append(f"f {at(r, s)} {at(r + 1, s)} {at(r + 1, s + 1)}")
            lines.append(f"f {at(r, s)} {at(r + 1, s + 1)} {at(r, s + 1)}")
    path.write_text("\n".join(lines) + "\n")
    return 2 * segments * (rings - 1)


def test_simplify_error_draws_fewer_triangles_of_a_fine_mesh(tmp_path):
    triangles = write_sphere(tmp_path / "sphere.obj")
    camera = depthtrack.Camera(640, 480, 525, 525, 319.5, 239.5)
    mesh = depthtrack.Mesh.load(str(tmp_path / "sphere.obj"))
    config = depthtrack.TrackerConfig()
    assert config.simplify_error == 0.0005
    config.simplify_error = 0
    as_given = depthtrack.Tracker(mesh, camera, config)
    assert as_given.mesh_triangles == as_given.drawn_triangles == triangles
    config.simplify_error = 0.002
    simplified = depthtrack.Tracker(mesh, camera, config)
    assert simplified.mesh_triangles == triangles
    assert 0 < simplified.drawn_triangles < triangles // 4
    config.simplify_error = -1.0
    with pytest.raises(depthtrack.InputError, match="simplification error"):
        depthtrack.Tracker(mesh, camera, config)
