"""depthtrack: 6-DoF tracking of a known rigid object in depth images (occlusion-aware particle filter).

    import depthtrack, numpy as np
    tracker = depthtrack.Tracker(depthtrack.Mesh.load("object.obj"),
                                 depthtrack.Camera(640, 480, 525.0, 525.0, 319.5, 239.5),
                                 depthtrack.TrackerConfig())
    tracker.initialize(pose_4x4)                      # camera-from-object, metres
    estimate = tracker.update(depth, timestamp, metres_per_unit=0.001)   # uint16 mm, or float32 metres
    estimate.pose                                     # 4x4 numpy array

Errors from the library arrive as depthtrack.InputError (a ValueError) and depthtrack.BackendError
(a RuntimeError), both depthtrack.Error, with the C++ message.
"""
from ._depthtrack import *  # noqa: F401,F403
from ._depthtrack import __version__  # noqa: F401

# Tracebacks name depthtrack.InputError, not depthtrack._depthtrack.InputError.
for _value in list(globals().values()):
    if isinstance(_value, type) and _value.__module__ == __name__ + "._depthtrack":
        _value.__module__ = __name__
del _value
