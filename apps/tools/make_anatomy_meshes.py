#!/usr/bin/env python3
"""Writes the organs of apps/scenes/salpingectomy.json and apps/scenes/intestine.json into
apps/scenes/data/: uterus.off, ovary.off, bowel.off and abdomen.off (metres), made by the project
itself so that the scenes ship with no third-party data.

Sizes are those of an adult pelvis (Gray's Anatomy, 42nd ed.): a uterus about 7.5 x 5 x 3.5 cm,
pear-shaped (the body wider than the cervix below it); an ovary about 3.5 x 2 x 1.5 cm; and a
loop of small bowel (diameter about 2.5 cm) lying below the adnexa; and the peritoneal cavity of
the abdomen below the liver as a flattened ellipsoid of 44 x 36 x 18 cm, its lower (posterior)
side a little flatter, in which the small bowel of intestine.json lies (a cavity: the bowel is
inside it).

Every mesh is closed, consistently oriented (counter-clockwise seen from outside) and free of
self-intersections, as the collision library's inside test requires: the uterus and the ovary
are star-shaped radial deformations of a subdivided icosahedron (make_organ_mesh.icosphere), the
bowel a torus. Pure Python, no dependencies:

    python3 apps/tools/make_anatomy_meshes.py [--out apps/scenes/data]
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_organ_mesh import icosphere  # noqa: E402


def ellipsoid_radius(u, axes):
    x, y, z = u
    a, b, c = axes
    return 1.0 / math.sqrt((x / a) ** 2 + (y / b) ** 2 + (z / c) ** 2)


def star_mesh(centre, axes, shape, subdivisions=3):
    vertices, faces = icosphere(subdivisions)
    out = []
    for u in vertices:
        r = ellipsoid_radius(u, axes) * shape(u)
        out.append(tuple(c + r * x for c, x in zip(centre, u)))
    return out, faces


def pear(u):
    """The uterus: full at the fundus (top), narrowing smoothly towards the cervix (bottom)."""
    z = u[2]
    return 1.0 - 0.28 * max(0.0, -z) ** 1.5


def flat_back(u):
    """The abdomen: its posterior side (z < 0) flattened, as the abdominal wall lies on the spine."""
    z = u[2]
    return 1.0 - 0.15 * max(0.0, -z) ** 2


def torus(centre, major, minor, rings=48, sides=16):
    vertices, faces = [], []
    for i in range(rings):
        phi = 2.0 * math.pi * i / rings
        for j in range(sides):
            theta = 2.0 * math.pi * j / sides
            r = major + minor * math.cos(theta)
            vertices.append((centre[0] + r * math.cos(phi), centre[1] + r * math.sin(phi),
                             centre[2] + minor * math.sin(theta)))
    for i in range(rings):
        for j in range(sides):
            a = i * sides + j
            b = ((i + 1) % rings) * sides + j
            c = ((i + 1) % rings) * sides + (j + 1) % sides
            d = i * sides + (j + 1) % sides
            # Counter-clockwise seen from outside: the outward normal is (dP/dphi) x (dP/dtheta).
            faces += [(a, b, c), (a, c, d)]
    return vertices, faces


def write_off(path, vertices, faces):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(vertices), len(faces)))
        for v in vertices:
            f.write("%.7f %.7f %.7f\n" % v)
        for a, b, c in faces:
            f.write("3 %d %d %d\n" % (a, b, c))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "scenes", "data"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    # The uterus: its left horn (cornu), where the tube starts, near the origin.
    write_off(os.path.join(args.out, "uterus.off"), *star_mesh((-0.023, 0.0, -0.021), (0.025, 0.017, 0.036), pear))
    # The ovary, below the tube's distal half.
    write_off(os.path.join(args.out, "ovary.off"), *star_mesh((0.072, 0.018, -0.0205), (0.017, 0.010, 0.0075),
                                                             lambda u: 1.0))
    # A loop of small bowel under the adnexa (tube radius 12.5 mm on a loop of radius 35 mm).
    write_off(os.path.join(args.out, "bowel.off"), *torus((0.045, 0.01, -0.046), 0.035, 0.0125))
    # The peritoneal cavity of intestine.json, centred at the origin, z towards the front (the
    # patient lies on the back: gravity -z).
    write_off(os.path.join(args.out, "abdomen.off"), *star_mesh((0.0, 0.0, 0.0), (0.22, 0.18, 0.09), flat_back,
                                                              subdivisions=4))


if __name__ == "__main__":
    main()
