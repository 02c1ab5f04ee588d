#!/usr/bin/env python3
"""Writes the vessel trees the navigation scenes use (apps/scenes/data/), as centrelines with radii
in the format of geometry/vessel_tree.hpp (docs/vessels.md). Coordinates in mm, patient axes:
x to the patient's left, y posterior, z cranial (head up).

aortic_arch.json - an adult aortic arch with its three branches, from the descending aorta (open
  at its lower end: the femoral route comes up it) over the arch to the aortic root (closed at the
  valve). Radii from the anatomy (adult means, e.g. Hager et al. 2002; Erbel & Eggebrecht 2006):
  root 15 mm, ascending 14, arch 13, isthmus 11, descending thoracic 10; brachiocephalic trunk 6,
  left common carotid 4, left subclavian 5. The arch bends over a 30 mm radius in a plane turned
  27 degrees towards the left and back; the branches leave its top, right to left, and are open
  at their upper ends (they go on to the head and the arms).
cerebral_aneurysm.json - a curved cerebral artery (radius 2 mm, a C-bend like the carotid siphon,
  open at both ends) with a saccular aneurysm on the outside of its bend: a neck 4 mm wide and a
  dome 8 mm across.

Run from anywhere: python3 apps/tools/make_vessel_trees.py
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "scenes", "data")


def lerp(a, b, t):
    return a + (b - a) * t


def rounded(p):
    return [round(v, 3) for v in p]


def aortic_arch(tilt=27.0, lsa=(122, (12.0, 3.0, 20.0), (45.0, 8.0, 40.0)), lcca=(92, (1.0, 0.0, 30.0), (4.0, 2.0, 90.0))):
    centre = (20.0, 15.0, 55.0)  # mm, centre of the arch's bend
    bend = 30.0  # mm, radius of the bend
    e1 = (math.cos(math.radians(tilt)), math.sin(math.radians(tilt)), 0.0)  # ascending -> descending

    def arch_point(theta):
        # theta = 0 at the top of the ascending aorta, pi/2 at the apex, pi at the descending aorta
        return tuple(centre[i] - bend * math.cos(theta) * e1[i] + (bend * math.sin(theta) if i == 2 else 0.0)
                     for i in range(3))

    aorta = []
    top_descending = arch_point(math.pi)
    # Descending aorta, from 20 cm below the arch upwards (open start: the femoral route).
    for k in range(0, 21):
        t = k / 20.0
        z = lerp(top_descending[2] - 200.0, top_descending[2], t)
        aorta.append([top_descending[0], top_descending[1], z, lerp(10.0, 11.0, t)])
    # The arch, from the descending side (theta = pi) back to the ascending side, every 5 degrees.
    for k in range(1, 37):
        theta = math.pi * (1.0 - k / 36.0)
        p = arch_point(theta)
        # isthmus 11 -> arch 13 at the apex -> 14 at the top of the ascending aorta
        s = k / 36.0
        r = lerp(11.0, 13.0, s / 0.5) if s <= 0.5 else lerp(13.0, 14.0, (s - 0.5) / 0.5)
        aorta.append([p[0], p[1], p[2], r])
    # Ascending aorta down to the root, bending forward and to the right.
    top = arch_point(0.0)
    root = (top[0] + 4.0, top[1] - 10.0, top[2] - 50.0)
    for k in range(1, 11):
        t = k / 10.0
        aorta.append([lerp(top[0], root[0], t), lerp(top[1], root[1], t), lerp(top[2], root[2], t), lerp(14.0, 15.0, t)])

    def branch(name, theta_degrees, radius, waypoints):
        start = arch_point(math.radians(theta_degrees))
        points = [list(start) + [radius]]
        previous = start
        for w in waypoints:
            target = tuple(start[i] + w[i] for i in range(3))
            steps = max(1, int(math.dist(previous, target) / 5.0))  # about every 5 mm
            for k in range(1, steps + 1):
                t = k / steps
                points.append([lerp(previous[i], target[i], t) for i in range(3)] + [radius])
            previous = target
        return {"name": name, "open": ["end"], "points": [rounded(p) for p in points]}

    # theta from the ascending side: brachiocephalic first (right), then left carotid, left subclavian.
    brachiocephalic = branch("brachiocephalic", 62, 6.0, [(-6.0, -3.0, 30.0), (-14.0, -5.0, 55.0)])
    carotid = branch("left_common_carotid", lcca[0], 4.0, list(lcca[1:]))
    subclavian = branch("left_subclavian", lsa[0], 5.0, list(lsa[1:]))
    return {
        "units": "mm",
        "blend": 3.0,
        "branches": [
            {"name": "aorta", "open": ["start"], "points": [rounded(p) for p in aorta]},
            brachiocephalic,
            carotid,
            subclavian,
        ],
    }


def cerebral_aneurysm():
    # The parent artery: a C-bend of radius 8 mm between two straight pieces, in the x-z plane.
    points = []
    for k in range(0, 5):  # straight, 10 mm, coming up
        points.append([8.0, 0.0, -10.0 + 2.5 * k, 2.0])
    for k in range(1, 37):  # half turn of radius 8 mm about (0, 0, 0), every 5 degrees
        a = math.pi * k / 36.0
        points.append([8.0 * math.cos(a), 0.0, 8.0 * math.sin(a), 2.0])
    for k in range(1, 5):  # straight, 10 mm, going down
        points.append([-8.0, 0.0, -2.5 * k, 2.0])
    # The sac on the outside of the bend's apex (0, 0, 8): a neck 4 mm wide (radius 2) from the
    # parent's axis out through its wall, and a dome of radius 4 mm whose centre is 5 mm beyond the
    # wall, so that it meets the neck across its width.
    neck = [[0.0, 0.0, 8.0, 2.0], [0.0, 0.0, 10.5, 2.0]]
    dome = [[0.0, 0.0, 14.8, 4.0], [0.0, 0.0, 15.2, 4.0]]
    return {
        "units": "mm",
        "blend": 1.0,
        "branches": [
            {"name": "parent", "open": ["start", "end"], "points": [rounded(p) for p in points]},
            {"name": "neck", "points": neck},
            {"name": "sac", "points": dome},
        ],
    }


def write(name, tree, comment):
    path = os.path.join(DATA, name)
    with open(path, "w") as out:
        out.write("// " + comment + "\n// Written by apps/tools/make_vessel_trees.py; format: docs/vessels.md.\n")
        out.write("{\n")
        out.write('  "units": "%s",\n  "blend": %s,\n  "branches": [\n' % (tree["units"], tree["blend"]))
        for b, branch in enumerate(tree["branches"]):
            out.write('    {"name": "%s"' % branch["name"])
            if "open" in branch:
                out.write(', "open": %s' % json.dumps(branch["open"]))
            out.write(', "points": [\n')
            lines = ["      " + json.dumps(p) for p in branch["points"]]
            out.write(",\n".join(lines))
            out.write("\n    ]}" + ("," if b + 1 < len(tree["branches"]) else "") + "\n")
        out.write("  ]\n}\n")
    print("wrote", path)


if __name__ == "__main__":
    write("aortic_arch.json", aortic_arch(),
          "An adult aortic arch with the brachiocephalic trunk, left common carotid and left subclavian arteries (mm).")
    write("cerebral_aneurysm.json", cerebral_aneurysm(),
          "A cerebral artery bend with a saccular aneurysm: neck 4 mm, dome 8 mm (mm).")
