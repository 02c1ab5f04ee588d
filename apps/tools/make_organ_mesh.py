#!/usr/bin/env python3
"""Writes apps/scenes/data/organ.off: the triangle-mesh organ of apps/scenes/organ.json.

A smooth, kidney-like closed surface of about 10 x 6 x 4 cm (metres in the file), made by the
project itself so that the scene ships with no third-party data. It is a star-shaped radial
deformation of a subdivided icosahedron (icosphere), so it is a closed, consistently oriented
(counter-clockwise seen from outside), self-intersection-free triangle mesh, as the collision
library's inside test requires:

    x = r(u) u,   u on the unit sphere,
    r(u) = ellipsoid radius along u  x  (1 + 0.10 sin(3 phi) cos(theta)^2 - 0.15 bean(u)),

with the ellipsoid semi-axes (5, 3, 2) cm, phi the azimuth, theta the latitude and bean(u) a
smooth dent on the -y side (the hilum of a kidney). Pure Python, no dependencies:

    python3 apps/tools/make_organ_mesh.py [--subdivisions 3] [--out apps/scenes/data/organ.off]
"""
import argparse
import math
import os


def icosphere(subdivisions):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [normalize(v) for v in vertices]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        midpoint = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                va, vb = vertices[a], vertices[b]
                vertices.append(normalize(tuple((x + y) / 2 for x, y in zip(va, vb))))
                midpoint[key] = len(vertices) - 1
            return midpoint[key]

        refined = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            refined += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = refined
    return vertices, faces


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def radius(u, axes=(0.05, 0.03, 0.02)):
    x, y, z = u
    # Radius of the ellipsoid x²/a² + y²/b² + z²/c² = 1 along the unit direction u.
    a, b, c = axes
    ellipsoid = 1.0 / math.sqrt((x / a) ** 2 + (y / b) ** 2 + (z / c) ** 2)
    phi = math.atan2(y, x)
    cos_theta_sq = x * x + y * y  # cos(latitude)^2
    lobes = 0.10 * math.sin(3.0 * phi) * cos_theta_sq
    bean = math.exp(-((x / 0.35) ** 2) - ((y + 1.0) / 0.6) ** 2 - (z / 0.5) ** 2)  # dent around u = -y
    return ellipsoid * (1.0 + lobes - 0.15 * bean)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument("--subdivisions", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(root, "apps", "scenes", "data", "organ.off"))
    args = parser.parse_args()
    units, faces = icosphere(args.subdivisions)
    points = [tuple(radius(u) * c for c in u) for u in units]
    with open(args.out, "w") as f:
        f.write("OFF\n# kidney-like organ for apps/scenes/organ.json, metres; written by apps/tools/make_organ_mesh.py\n")
        f.write(f"{len(points)} {len(faces)} 0\n")
        for p in points:
            f.write("{:.7f} {:.7f} {:.7f}\n".format(*p))
        for a, b, c in faces:
            f.write(f"3 {a} {b} {c}\n")
    print(f"wrote {args.out}: {len(points)} vertices, {len(faces)} triangles")


if __name__ == "__main__":
    main()
