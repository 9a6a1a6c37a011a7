"""depthtrack: 6-DoF tracking of a known rigid object in depth images (occlusion-aware particle filter).

    import depthtrack, numpy as np
    tracker = depthtrack.Tracker(depthtrack.Mesh.load("object.obj"),
                                 depthtrack.Camera(640, 480, 525.0, 525.0, 319.5, 239.5),
                                 depthtrack.TrackerConfig())
    tracker.initialize(pose_4x4)                      # camera-from-object, metres
    estimate = tracker.update(depth, timestamp, metres_per_unit=0.001)   # uint16 mm, or float32 metres
    estimate.pose                                     # 4x4 numpy array

Frames from a folder or a stream (a raw depth stream on stdin or a named pipe) come from
depthtrack.open_source; any iterable of frames or (depth, timestamp) pairs runs through track_frames.

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


def track_frames(tracker, frames, metres_per_unit=None):
    """Runs tracker.update over frames, yielding each frame's estimate as it comes.

    frames: any iterable of depthtrack.Frame (depthtrack.open_source("raw:-"), a folder) or of (depth,
    timestamp) pairs from a generator of your own (depth: float32 metres, or uint16 units with
    metres_per_unit). The tracker must be initialized first (Tracker.initialize)."""
    for frame in frames:
        if isinstance(frame, Frame):  # noqa: F405 (from the extension)
            depth, timestamp = frame.depth, frame.timestamp
        else:
            depth, timestamp = frame
        yield tracker.update(depth, timestamp, metres_per_unit=metres_per_unit)
