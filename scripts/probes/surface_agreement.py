#!/usr/bin/env python3
"""How well each pose of an object explains its depth: the labelled pixels' points against the mesh.

A tracker judged against a YCB-Video ground truth is judged partly against that ground truth's own error.
This measures, independently of any tracker's likelihood, how far the observed surface lies from the mesh
placed at a pose: every pixel of the clip's label image that belongs to the object (shrunk by EROSION pixels
so that no mixed depth at an edge counts) is back-projected with the clip's intrinsics (OpenCV convention:
pixel (u, v) at image coordinate (u, v)) and its distance to the mesh's surface taken (exactly, to the
nearest of the 32 triangles whose centroids lie nearest). The label images come from the ground truth's
own poses, so the pixels chosen favour the ground truth, if anything.

Per pose source (the ground truth, then each CSV of `depthtrack track` / the peers' runners: frame, tx, ty,
tz, qw, qx, qy, qz) and frame: the median and mean distance (mm) and the mean signed distance along the
viewing ray (mm; positive: the observed surface lies behind the mesh's); then the means over the frames.

usage: surface_agreement.py SEQUENCE_FOLDER MESH.obj OBJECT_NAME [LABEL=CSV ...] [--erosion 2] [--frames]
"""
import argparse
import json
from pathlib import Path

import numpy as np
from PIL import Image
from scipy import ndimage
from scipy.spatial import cKDTree


def load_obj(path):
    vertices, faces = [], []
    for line in Path(path).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            ids = [int(p.split("/")[0]) for p in parts[1:]]
            ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
            faces.extend([ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1))
    return np.asarray(vertices), np.asarray(faces)


def closest_on_triangles(p, a, b, c):
    """Closest points on triangles (a, b, c) to points p, all (n, 3) (Ericson's regions, vectorized)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v, w = vb / denom, vc / denom
        out = a + v[:, None] * ab + w[:, None] * ac  # inside the face
        # edges
        t_ab = d1 / (d1 - d3)
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        out[m] = a[m] + t_ab[m, None] * ab[m]
        t_ac = d2 / (d2 - d6)
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        out[m] = a[m] + t_ac[m, None] * ac[m]
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
        out[m] = b[m] + t_bc[m, None] * (c[m] - b[m])
    # vertices
    m = (d1 <= 0) & (d2 <= 0)
    out[m] = a[m]
    m = (d3 >= 0) & (d4 <= d3)
    out[m] = b[m]
    m = (d6 >= 0) & (d5 <= d6)
    out[m] = c[m]
    return out


class Surface:
    def __init__(self, vertices, faces, candidates=32):
        self.a, self.b, self.c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
        self.tree = cKDTree((self.a + self.b + self.c) / 3)
        self.candidates = min(candidates, len(faces))

    def closest(self, points):
        _, nearest = self.tree.query(points, k=self.candidates)
        best = np.full(len(points), np.inf)
        closest = np.zeros_like(points)
        for k in range(self.candidates):
            ids = nearest[:, k]
            q = closest_on_triangles(points, self.a[ids], self.b[ids], self.c[ids])
            d = np.linalg.norm(points - q, axis=1)
            better = d < best
            best[better], closest[better] = d[better], q[better]
        return closest, best


def rotation(qw, qx, qy, qz):
    n = np.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def read_csv_poses(path):
    lines = Path(path).read_text().splitlines()
    head = lines[0].split(",")
    col = {name: i for i, name in enumerate(head)}
    poses = {}
    for line in lines[1:]:
        f = line.split(",")
        if len(f) < len(head):
            continue
        values = [float(f[col[k]]) for k in ("tx", "ty", "tz", "qw", "qx", "qy", "qz")]
        if not all(np.isfinite(values)):
            continue
        pose = np.eye(4)
        pose[:3, :3] = rotation(*values[3:])
        pose[:3, 3] = values[:3]
        poses[f[col["frame"]]] = pose
    return poses


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence")
    parser.add_argument("mesh")
    parser.add_argument("object")
    parser.add_argument("sources", nargs="*", metavar="LABEL=CSV")
    parser.add_argument("--erosion", type=int, default=2)
    parser.add_argument("--frames", action="store_true", help="print every frame's row too")
    args = parser.parse_args()

    seq = Path(args.sequence)
    gt = json.loads((seq / "gt.json").read_text())
    surface = Surface(*load_obj(args.mesh))
    sources = {"ground truth": {}}
    for spec in args.sources:
        label, _, csv = spec.partition("=")
        sources[label] = read_csv_poses(csv)
    observed = {}
    for frame in gt["frames"]:
        obj = next((o for o in frame["objects"] if o["name"] == args.object), None)
        if obj is None:
            continue
        sources["ground truth"][frame["frame"]] = np.asarray(obj["T_cam_obj"])
        depth = np.asarray(Image.open(seq / frame["depth"]), dtype=np.float64) / frame["factor_depth"]
        label = np.asarray(Image.open(seq / frame["depth"].replace("-depth", "-label")))
        mask = label == obj["cls_index"]
        if args.erosion > 0:
            mask = ndimage.binary_erosion(mask, iterations=args.erosion)
        mask &= depth > 0
        v, u = np.nonzero(mask)
        k = np.asarray(frame["K"])
        z = depth[v, u]
        points = np.stack([(u - k[0, 2]) / k[0, 0] * z, (v - k[1, 2]) / k[1, 1] * z, z], axis=1)
        observed[frame["frame"]] = points

    print("source, frames, median_mm, mean_mm, signed_along_ray_mm")
    for name, poses in sources.items():
        rows = []
        for frame, points in observed.items():
            if frame not in poses:
                continue
            pose = poses[frame]
            local = (points - pose[:3, 3]) @ pose[:3, :3]
            closest, distance = surface.closest(local)
            closest_cam = closest @ pose[:3, :3].T + pose[:3, 3]
            rays = points / np.linalg.norm(points, axis=1, keepdims=True)
            signed = np.einsum("ij,ij->i", points - closest_cam, rays)
            rows.append((np.median(distance) * 1e3, distance.mean() * 1e3, signed.mean() * 1e3))
            if args.frames:
                median, mean, signed = rows[-1]
                print(f"  {name} {frame}: {median:.2f} {mean:.2f} {signed:+.2f} ({len(points)} points)")
        if rows:
            r = np.asarray(rows)
            print(f"{name}, {len(rows)}, {r[:, 0].mean():.3f}, {r[:, 1].mean():.3f}, {r[:, 2].mean():+.3f}")


if __name__ == "__main__":
    main()
