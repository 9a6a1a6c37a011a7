#!/usr/bin/env python3
"""Tracks ycbv-0000's three objects in one run through depthtrack.MultiTracker, each started 1 cm / 5 deg
off its ground truth as `depthtrack track --init-from-gt --init-perturb "0.01 5"` starts it, and prints
each object's last-frame ADD-S (mm), the number the CLI's CSV ends with.

    PYTHONPATH=build/python python3 python/examples/track_ycbv_objects.py --data ../shared/data
"""
import argparse
import math
import os
import sys

import depthtrack

OBJECTS = ("009_gelatin_box", "025_mug", "061_foam_brick")


def track(data, particles=200, backend="reference", mutual_occlusion=True, seed=None):
    """{object name: last-frame ADD-S in metres} for ycbv-0000 tracked in one MultiTracker; seed None:
    TrackerConfig's, as the CLI's."""
    clip = os.path.join(data, "sequences", "ycbv-0000")
    sequences = [depthtrack.Sequence.load(clip, name) for name in OBJECTS]
    meshes = [depthtrack.Mesh.load(os.path.join(data, "meshes", "ycb", name + ".obj")) for name in OBJECTS]
    config = depthtrack.TrackerConfig()
    config.particles, config.backend = particles, backend
    if seed is not None:
        config.seed = seed
    seed = config.seed  # the CLI perturbs each start with the tracker's seed
    config.width, config.height = 80, 60
    tracker = depthtrack.MultiTracker(meshes, sequences[0].camera, config, mutual_occlusion=mutual_occlusion)
    for j, (sequence, mesh) in enumerate(zip(sequences, meshes)):
        start = depthtrack.perturb_pose(sequence.frames[0].ground_truth, mesh.centre, 0.01, 5.0, seed)
        tracker.initialize(j, start, spread_metres=0.01, spread_radians=math.radians(5.0))  # --init-spread "0.01 5"
    clip_frames = sequences[0].frames
    for i, frame in enumerate(clip_frames):
        estimates = tracker.update(sequences[0].load_depth(i), frame.timestamp)
    last = len(clip_frames) - 1
    return {name: depthtrack.AddsMetric(mesh)(e.pose, sequence.frames[last].ground_truth)
            for name, mesh, sequence, e in zip(OBJECTS, meshes, sequences, estimates)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.environ.get("DEPTHTRACK_DATA_DIR", "../shared/data"),
                        help="the third-party data folder (meshes/ycb, sequences/ycbv-0000)")
    parser.add_argument("--particles", type=int, default=200)
    parser.add_argument("--backend", default="reference")
    parser.add_argument("--seed", type=int, default=None, help="default: TrackerConfig's, as the CLI's")
    parser.add_argument("--mutual-occlusion", choices=("on", "off"), default="on")
    args = parser.parse_args()
    try:
        adds = track(args.data, args.particles, args.backend, args.mutual_occlusion == "on", args.seed)
    except depthtrack.Error as e:
        sys.exit("track_ycbv_objects: %s" % e)
    for name, value in adds.items():
        print("%s %.4f" % (name, 1000 * value))


if __name__ == "__main__":
    main()
