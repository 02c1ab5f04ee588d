#!/usr/bin/env python3
"""Print a scene "camera" block that frames a whole run.

    filum run SCENE.json --out RUN
    apps/tools/frame_camera.py RUN [--view 0.15 -1 0.25] [--fov 30] [--size 960 540] [--margin 0.9]

Reads RUN/curve.csv (time,body,sample,s,x,y,z: every curve at every written frame), takes the
box that holds all of them over the whole run, and places a pinhole camera looking at the box
centre from the direction --view (from the look-at point towards the camera; z is up), as close
as it can while every corner of the box projects inside --margin of the half field of view,
horizontally and vertically. For a corner at offset c from the centre, with the camera at
distance D along the view direction, forward f, right r and up u:
    depth = D + c·f,   |c·r| <= margin · tan(fov_h / 2) · depth,   |c·u| <= margin · tan(fov_v / 2) · depth,
so D = max over corners of max(|c·r| / (margin tan(fov_h/2)), |c·u| / (margin tan(fov_v/2))) − c·f.
Paste the printed block into the scene (it is what filum run --render and filum view use).
"""
import argparse
import csv
import math
import sys


def read_box(run):
    lower = [math.inf] * 3
    upper = [-math.inf] * 3
    with open(f"{run}/curve.csv", newline="") as f:
        for row in csv.DictReader(f):
            p = (float(row["x"]), float(row["y"]), float(row["z"]))
            for k in range(3):
                lower[k] = min(lower[k], p[k])
                upper[k] = max(upper[k], p[k])
    if not all(math.isfinite(v) for v in lower + upper):
        sys.exit(f"{run}/curve.csv: no finite points")
    return lower, upper


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalized(a):
    n = math.sqrt(dot(a, a))
    return [v / n for v in a]


def frame(lower, upper, view, fov, width, height, margin, pad):
    lower = [v - pad for v in lower]
    upper = [v + pad for v in upper]
    center = [0.5 * (lower[k] + upper[k]) for k in range(3)]
    back = normalized(view)  # from the look-at point towards the camera
    forward = [-v for v in back]
    right = normalized(cross(forward, [0.0, 0.0, 1.0]))
    up = cross(right, forward)
    tan_v = math.tan(math.radians(fov) / 2)
    tan_h = tan_v * width / height
    distance = 0.0
    for i in range(8):
        corner = [upper[k] if (i >> k) & 1 else lower[k] for k in range(3)]
        c = sub(corner, center)
        need = max(abs(dot(c, right)) / (margin * tan_h), abs(dot(c, up)) / (margin * tan_v)) - dot(c, forward)
        distance = max(distance, need)
    position = [center[k] + distance * back[k] for k in range(3)]
    return position, center


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run", help="output folder of `filum run` (holds curve.csv)")
    parser.add_argument("--view", type=float, nargs=3, default=[0.15, -1.0, 0.25],
                        help="direction from the scene towards the camera (default: front, a little right and above)")
    parser.add_argument("--fov", type=float, default=30.0, help="vertical field of view, degrees (default 30)")
    parser.add_argument("--size", type=int, nargs=2, default=[960, 540], help="image width and height in pixels")
    parser.add_argument("--margin", type=float, default=0.9, help="fraction of the half field of view to fill")
    parser.add_argument("--pad", type=float, default=0.0, help="grow the box by this much (m) on every side: "
                        "thick skins, spheres and meshes that curve.csv does not hold")
    args = parser.parse_args()
    lower, upper = read_box(args.run)
    position, center = frame(lower, upper, args.view, args.fov, args.size[0], args.size[1], args.margin, args.pad)
    fmt = lambda v: "[" + ", ".join(f"{x:.4g}" for x in v) + "]"
    print(f'"camera": {{"position": {fmt(position)}, "look_at": {fmt(center)}, "up": [0, 0, 1],\n'
          f'           "fov": {args.fov:g}, "size": [{args.size[0]}, {args.size[1]}], "background": [1, 1, 1]}},')


if __name__ == "__main__":
    main()
