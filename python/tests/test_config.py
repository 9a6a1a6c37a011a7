"""TrackerConfig from Python: every field an attribute (the C++ field list), nested models by
reference, JSON in and out equal to `depthtrack config --dump`."""
import json
import subprocess

import depthtrack
from conftest import cli


def attributes(obj):
    return {name for name in dir(obj) if not name.startswith("_") and not callable(getattr(obj, name))}


def test_every_dumped_key_is_an_attribute_and_back():
    dumped = json.loads(subprocess.run([cli(), "config", "--dump"], check=True, capture_output=True, text=True).stdout)
    config = depthtrack.TrackerConfig()

    def check(obj, tree, path):
        assert attributes(obj) == set(tree), path
        for key, value in tree.items():
            if isinstance(value, dict):
                check(getattr(obj, key), value, path + key + ".")
            else:
                assert getattr(obj, key) == value, path + key

    check(config, dumped, "")


def test_nested_fields_are_set_in_place_and_round_trip_through_json():
    config = depthtrack.TrackerConfig()
    config.observation.sigma_constant = 0.004
    config.refine.iterations = 3
    config.loss.search_after = 5
    config.occlusion_storage = "global-time"
    config.seed = 2**40
    config.backend = "opencl:pocl"
    assert config.observation.sigma_constant == 0.004 and config.refine.iterations == 3
    text = config.to_json()
    assert json.loads(text)["observation"]["sigma_constant"] == 0.004
    again = depthtrack.TrackerConfig.from_json(text)
    assert again == config and again != depthtrack.TrackerConfig()
    assert again.occlusion_storage == "global-time" and again.seed == 2**40


def test_config_file_errors_name_the_key(tmp_path):
    path = tmp_path / "c.json"
    path.write_text('{"motion": {"dampng": 0.5}}')
    try:
        depthtrack.TrackerConfig.load(str(path))
        raise AssertionError("no error")
    except depthtrack.InputError as e:
        assert "unknown key 'motion.dampng'" in str(e) and "c.json" in str(e)


def test_initialize_spread_defaults_are_track_s():
    """Tracker.initialize and MultiTracker.initialize start the cloud as `track --init-spread`'s default does."""
    import math
    import re
    helptext = subprocess.run([cli(), "track", "--help"], check=True, capture_output=True, text=True).stdout
    metres, degrees = map(float, re.search(r"--init-spread TEXT=([0-9.]+) ([0-9.]+) ", helptext).groups())
    assert (metres, degrees) == (0.01, 5.0)
    for method in (depthtrack.Tracker.initialize, depthtrack.MultiTracker.initialize):
        doc = method.__doc__
        assert float(re.search(r"spread_metres: float = ([0-9.e-]+)", doc).group(1)) == metres
        assert float(re.search(r"spread_radians: float = ([0-9.e-]+)", doc).group(1)) == math.radians(degrees)
