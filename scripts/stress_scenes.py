#!/usr/bin/env python3
"""Stress suite: every reference scene pushed past what it was made for.

Variants of each scene in apps/scenes/:
  dt10       the time step ×10
  dt100      the time step ×100
  stiff1000  every stiffness ×1000 (youngs_modulus, stiffness, stretch_stiffness, bend_stiffness)
  yank10     the two end control points of every DynamicSpline start at 10 m/s outwards along
             the thread (a trainee yanking both ends), through the "velocities" parameter
each run by `filum run` for --steps steps (default 100,000) with about 100 frames written.

A run passes when it ends with the scene intact (exit 0, every step done) or rolled back and
reported (exit 3 with "rolled back" in its message), and no output file holds a non-finite
value (nan or inf in any CSV, JSON or VTP). Anything else (a crash, a timeout, exit 2 or 4, a
non-finite value) fails. The table of outcomes, with steps done and wall time, goes to stdout
and, with --report, to a JSON file.

Usage: scripts/stress_scenes.py --filum build/apps/filum [--steps 100000] [--jobs 2]
                                [--variants dt10,dt100,stiff1000,yank10] [--timeout 3600]
                                [--report FILE] [SCENE.json ...]
Exit status 0 when every run passed, 1 otherwise. Python 3 standard library only.
"""
import argparse
import concurrent.futures
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from mutate_scenes import strip_comments  # noqa: E402  (one JSON-with-comments reader)

VARIANTS = ("dt10", "dt100", "stiff1000", "yank10")
STIFFNESS_KEYS = ("youngs_modulus", "stiffness", "stretch_stiffness", "bend_stiffness")
END_SPEED = 10.0  # m/s
NONFINITE = re.compile(r"(^|[,\s\"\[>:])[-+]?(nan|inf)", re.I | re.M)


def scale_stiffness(value, factor):
    if isinstance(value, dict):
        for key, item in value.items():
            if key in STIFFNESS_KEYS and isinstance(item, (int, float)):
                value[key] = item * factor
            else:
                scale_stiffness(item, factor)
    elif isinstance(value, list):
        for item in value:
            scale_stiffness(item, factor)


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v] if n > 0 else [1.0, 0.0, 0.0]


def end_directions(points):
    """Outward unit vectors at the first and last control points, from (from, to) or a list."""
    if isinstance(points, dict):
        a, b = points["from"], points["to"]
        return unit([a[i] - b[i] for i in range(3)]), unit([b[i] - a[i] for i in range(3)]), int(points["count"])
    first = unit([points[0][i] - points[1][i] for i in range(3)])
    last = unit([points[-1][i] - points[-2][i] for i in range(3)])
    return first, last, len(points)


def yank_ends(value):
    if isinstance(value, dict):
        if value.get("type") == "DynamicSpline" and "control_points" in value:
            first, last, count = end_directions(value["control_points"])
            velocities = [[0.0, 0.0, 0.0] for _ in range(count)]
            velocities[0] = [END_SPEED * c for c in first]
            velocities[-1] = [END_SPEED * c for c in last]
            value["velocities"] = velocities
        for item in value.values():
            yank_ends(item)
    elif isinstance(value, list):
        for item in value:
            yank_ends(item)


def variant(document, name, steps):
    scene = json.loads(json.dumps(document))
    if name == "dt10":
        scene["dt"] *= 10
    elif name == "dt100":
        scene["dt"] *= 100
    elif name == "stiff1000":
        scale_stiffness(scene, 1000.0)
    elif name == "yank10":
        yank_ends(scene)
    else:
        raise ValueError(name)
    scene["duration"] = steps * scene["dt"]
    output = scene.setdefault("output", {})
    output["interval"] = scene["duration"] / 100
    output["curve_samples"] = min(output.get("curve_samples", 16), 16)
    return scene


def nonfinite_file(out_dir):
    for folder, _, files in os.walk(out_dir):
        for name in files:
            if name.endswith((".csv", ".json", ".vtp", ".pvd")):
                with open(os.path.join(folder, name), encoding="utf-8", errors="replace") as f:
                    if NONFINITE.search(f.read()):
                        return os.path.relpath(os.path.join(folder, name), out_dir)
    return None


def run_one(job):
    scene_path, variant_name, steps, filum, timeout, workdir = job
    name = os.path.splitext(os.path.basename(scene_path))[0]
    with open(scene_path, encoding="utf-8") as f:
        document = json.loads(strip_comments(f.read()))
    folder = os.path.join(workdir, name + "." + variant_name)
    os.makedirs(folder, exist_ok=True)
    # Beside a link to the original's data/, so that files it names (data/organ.off) resolve.
    data = os.path.join(os.path.dirname(scene_path), "data")
    if os.path.isdir(data):
        os.symlink(data, os.path.join(folder, "data"))
    path = os.path.join(folder, "scene.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(variant(document, variant_name, steps), f)
    out_dir = os.path.join(folder, "out")
    start = time.monotonic()
    try:
        proc = subprocess.run([filum, "run", path, "--out", out_dir, "--quiet"], capture_output=True, text=True,
                              timeout=timeout, stdin=subprocess.DEVNULL)
        code, text = proc.returncode, proc.stdout + proc.stderr
    except subprocess.TimeoutExpired:
        code, text = None, "timeout after %d s" % timeout
    wall = time.monotonic() - start
    done = None
    timing = os.path.join(out_dir, "timing.json")
    if os.path.exists(timing):
        with open(timing, encoding="utf-8") as f:
            done = json.load(f).get("steps")
    errors = [l for l in text.splitlines() if l.startswith("error:")]
    bad_file = nonfinite_file(out_dir) if os.path.isdir(out_dir) else None
    if code is None:
        verdict = "FAIL hang"
    elif code < 0 or code not in (0, 3):
        verdict = "FAIL exit %d" % code
    elif code == 3 and not any("rolled back" in l for l in errors):
        verdict = "FAIL diverged without roll-back"
    elif bad_file:
        verdict = "FAIL non-finite in " + bad_file
    elif code == 0 and done is not None and done < steps:
        verdict = "FAIL %d of %d steps" % (done, steps)
    else:
        verdict = "intact" if code == 0 else "rolled back"
    shutil.rmtree(out_dir, ignore_errors=True)
    return {"scene": name, "variant": variant_name, "exit": code, "steps": done, "wall_s": round(wall, 1),
            "verdict": verdict, "message": errors[0][:300] if errors else ""}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--filum", default=os.path.join(ROOT, "build", "apps", "filum"))
    parser.add_argument("--steps", type=int, default=100000)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--timeout", type=int, default=3600, help="seconds per run")
    parser.add_argument("--report")
    parser.add_argument("scenes", nargs="*")
    args = parser.parse_args()
    scenes = args.scenes or sorted(glob.glob(os.path.join(ROOT, "apps", "scenes", "*.json")))
    variants = args.variants.split(",")
    for v in variants:
        if v not in VARIANTS:
            parser.error("unknown variant %r (expected one of %s)" % (v, ", ".join(VARIANTS)))
    workdir = tempfile.mkdtemp(prefix="filum_stress_")
    jobs = [(os.path.abspath(s), v, args.steps, args.filum, args.timeout, workdir) for s in scenes for v in variants]
    results = []
    print("%-24s %-10s %5s %8s %8s  %s" % ("scene", "variant", "exit", "steps", "wall s", "verdict"), flush=True)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for r in pool.map(run_one, jobs):
            results.append(r)
            print("%-24s %-10s %5s %8s %8s  %s" % (r["scene"], r["variant"], r["exit"], r["steps"], r["wall_s"],
                                                  r["verdict"]), flush=True)
    shutil.rmtree(workdir, ignore_errors=True)
    failed = [r for r in results if r["verdict"].startswith("FAIL")]
    print("%d runs: %d intact, %d rolled back and reported, %d failed" % (
        len(results), sum(r["verdict"] == "intact" for r in results),
        sum(r["verdict"] == "rolled back" for r in results), len(failed)))
    if args.report:
        with open(args.report, "w", encoding="utf-8") as f:
            json.dump({"steps": args.steps, "runs": results}, f, indent=1)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
