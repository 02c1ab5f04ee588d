#!/usr/bin/env python3
"""Mutation experiment on the reference scenes.

Every field of every scene in apps/scenes/ is mutated in turn: numbers pushed to 0, negative,
1e308, 5e-324 and huge counts; values replaced by the wrong type; arrays emptied, shortened and
blown up; keys removed, duplicated and added; values replaced by deeply nested arrays; file names
replaced by a FIFO, a directory and /dev/zero. A deterministic sample of N mutants goes through
`filum check` and M through a short `filum run`, each in a child process with a timeout and a
memory limit. Reported:
  crash     the child died of a signal (segmentation fault, abort, ...) or an exit status that
            filum does not use (only 0, 2, 3 and 4 are documented);
  hang      the timeout was reached (or stdin/FIFO blocked);
  no place  the error message does not name the scene file and a place in it (a JSON pointer
            '/...' or line:column; for a fault of the whole file, its type or size, the file
            alone), or for an output error (4) the file it concerns;
  nonfinite a run wrote 'nan' or 'inf' into one of its CSV files.

Checks go 50 to a `filum check` process (it prints one flushed line per file; starting the
process costs about 0.5 s of dynamic loading); a batch that crashes or times out is resolved by
running each of its unfinished files alone. Runs are `filum run -t 0.01` each in its own process.
Every field of every scene is mutated before any field twice (the first 3,422 mutants cover all
fields once).

Usage: scripts/mutate_scenes.py --filum build/apps/filum [--checks 30000] [--runs 3000]
                                [--jobs 1] [--seed 14] [--timeout 20] [--batch 50]
                                [--report out/mutations.json]
Python 3 standard library only. Exit status 0 when nothing was found, 1 otherwise.
"""
import argparse
import collections
import concurrent.futures
import copy
import functools
import json
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "apps", "scenes")
DEEP = 100000  # nesting depth of the "deep" mutation (nlohmann's parser recursed on it)


# ---------------------------------------------------------------------------------------------
# Reading scenes: JSON with // and /* */ comments, keys kept in order (pairs), so that the
# writer can also emit duplicated keys.

def strip_comments(text):
    out, i, n, in_string = [], 0, len(text), False
    while i < n:
        c = text[i]
        if in_string:
            out.append(c)
            if c == "\\" and i + 1 < n:
                out.append(text[i + 1])
                i += 1
            elif c == '"':
                in_string = False
        elif c == '"':
            in_string = True
            out.append(c)
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            i = n if end < 0 else end + 2
            continue
        else:
            out.append(c)
        i += 1
    return "".join(out)


class Obj(list):
    """A JSON object as a list of [key, value] pairs (duplicates allowed)."""


class Raw(str):
    """Text written verbatim (deep nesting)."""


@functools.lru_cache(maxsize=None)
def load(path):
    with open(path, encoding="utf-8") as f:
        return json.loads(strip_comments(f.read()), object_pairs_hook=lambda pairs: Obj([list(p) for p in pairs]))


def dump(value):
    if isinstance(value, Raw):
        return str(value)
    if isinstance(value, Obj):
        return "{" + ", ".join(json.dumps(k) + ": " + dump(v) for k, v in value) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(dump(v) for v in value) + "]"
    if isinstance(value, float):
        return repr(value) if value == value and abs(value) != float("inf") else "1e999"
    return json.dumps(value)


# ---------------------------------------------------------------------------------------------
# Mutations: (pointer, kind) pairs, applied to a copy of the document.

def walk(value, pointer=""):
    """Every value of the document with its JSON pointer (the root excluded)."""
    if isinstance(value, Obj):
        for k, v in value:
            p = pointer + "/" + k.replace("~", "~0").replace("/", "~1")
            yield p, v
            yield from walk(v, p)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            p = pointer + "/" + str(i)
            yield p, v
            yield from walk(v, p)


NUMBER_KINDS = ["zero", "negative", "big", "-big", "tiny", "huge_count", "int_max", "minus_one", "half",
                "string", "null", "bool", "array", "object", "deep", "remove", "duplicate", "nan_string"]
STRING_KINDS = ["empty", "number", "null", "long", "slash", "fifo", "directory", "dev_zero", "missing_file",
                "array", "deep", "remove", "duplicate"]
ARRAY_KINDS = ["empty", "drop_last", "repeat", "huge", "number", "string", "deep", "remove", "duplicate",
               "nested"]
OBJECT_KINDS = ["empty", "unknown_key", "number", "array", "deep", "remove", "duplicate"]
BOOL_KINDS = ["number", "string", "null", "remove", "duplicate"]


def kinds_for(value):
    if isinstance(value, bool):
        return BOOL_KINDS
    if isinstance(value, (int, float)):
        return NUMBER_KINDS
    if isinstance(value, str):
        return STRING_KINDS
    if isinstance(value, Obj):
        return OBJECT_KINDS
    if isinstance(value, list):
        return ARRAY_KINDS
    return ["number", "remove"]


def replacement(value, kind, workdir):
    if kind == "zero":
        return 0
    if kind == "negative":
        return -value if value != 0 else -1.0
    if kind == "big":
        return 1e308
    if kind == "-big":
        return -1e308
    if kind == "tiny":
        return 5e-324
    if kind == "huge_count":
        return 100000000
    if kind == "int_max":
        return 9223372036854775807
    if kind == "minus_one":
        return -1
    if kind == "half":
        return 0.5
    if kind in ("string", "nan_string"):
        return "NaN" if kind == "nan_string" else "abc"
    if kind == "null":
        return None
    if kind == "bool":
        return True
    if kind == "array":
        return [1, 2]
    if kind == "object":
        return Obj([["a", 1]])
    if kind == "deep":
        return Raw("[" * DEEP + "]" * DEEP)
    if kind == "empty":
        return "" if isinstance(value, str) else (Obj() if isinstance(value, Obj) else [])
    if kind == "number":
        return 3
    if kind == "long":
        return "x" * 100000
    if kind == "slash":
        return "a/b"
    if kind == "fifo":
        return os.path.join(workdir, "fifo")
    if kind == "directory":
        return workdir
    if kind == "dev_zero":
        return "/dev/zero"
    if kind == "missing_file":
        return "no_such_file.obj"
    if kind == "drop_last":
        return value[:-1]
    if kind == "repeat":
        return value + value
    if kind == "huge":  # 200,000 entries, or as many as fit in 8 MB of text (below the 16 MiB limit)
        return value * max(2, min(200000 // max(1, len(value)), 8000000 // max(1, len(dump(value)))))
    if kind == "nested":
        return [value]
    if kind == "unknown_key":
        return Obj(list(value) + [["unknown_key", 1]])
    raise ValueError(kind)


def parent_and_key(document, pointer):
    tokens = [t.replace("~1", "/").replace("~0", "~") for t in pointer.split("/")[1:]]
    node = document
    for t in tokens[:-1]:
        node = dict_get(node, t)
    return node, tokens[-1]


def dict_get(node, token):
    if isinstance(node, Obj):
        for k, v in node:
            if k == token:
                return v
        raise KeyError(token)
    return node[int(token)]


def mutate(document, pointer, kind, workdir):
    doc = copy.deepcopy(document)
    parent, key = parent_and_key(doc, pointer)
    if isinstance(parent, Obj):
        index = next(i for i, (k, _) in enumerate(parent) if k == key)
        value = parent[index][1]
        if kind == "remove":
            del parent[index]
        elif kind == "duplicate":
            parent.insert(index + 1, [key, value])
        else:
            parent[index][1] = replacement(value, kind, workdir)
    else:
        index = int(key)
        if kind == "remove":
            del parent[index]
        elif kind == "duplicate":
            parent.insert(index + 1, parent[index])
        else:
            parent[index] = replacement(parent[index], kind, workdir)
    return doc


def all_mutations():
    """Every (scene, pointer, kind) of every reference scene, in a fixed order."""
    out = []
    for name in sorted(os.listdir(SCENES)):
        if not name.endswith(".json"):
            continue
        document = load(os.path.join(SCENES, name))
        for pointer, value in walk(document):
            for kind in kinds_for(value):
                out.append((name, pointer, kind))
    return out


# ---------------------------------------------------------------------------------------------
# Running filum on one mutant.

PLACE = re.compile(r"(: /|:\d+:\d+)")
WHOLE_FILE = re.compile(r": expected a regular scene file")


def limit_child(memory_bytes):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        os.setsid()
    return apply


def classify(mode, path, out_dir, returncode, stdout, stderr, timed_out):
    text = stdout + stderr
    if timed_out:
        return "hang", ""
    if returncode < 0 or returncode not in (0, 2, 3, 4) or "terminate called" in text:
        return "crash", ("signal %d" % -returncode) if returncode < 0 else "exit %d" % returncode
    if returncode in (2, 3):
        errors = [l for l in text.splitlines() if l.startswith("error:")]
        if not errors or not any(path in l and (PLACE.search(l.split(path, 1)[1]) or returncode == 3 or
                                                WHOLE_FILE.match(l.split(path, 1)[1])) for l in errors):
            return "no place", errors[0] if errors else text.strip()[:200]
    if returncode == 4:
        errors = [l for l in text.splitlines() if l.startswith("error:")]
        if not errors or "/" not in errors[0]:
            return "no place", errors[0] if errors else text.strip()[:200]
    if mode == "run" and out_dir and os.path.isdir(out_dir):
        for name in os.listdir(out_dir):
            if name.endswith(".csv"):
                with open(os.path.join(out_dir, name), encoding="utf-8", errors="replace") as f:
                    content = f.read().lower()
                if re.search(r"(^|,)-?(nan|inf)", content, re.M):
                    return "nonfinite", name
    return "ok", ""


def prepare(job):
    """Writes the mutant of a job into a fresh folder (with the FIFO and the data/ link it may
    name); returns (folder, scene path)."""
    index, mode, scene, pointer, kind = job[:5]
    workdir = tempfile.mkdtemp(prefix="filum_mut_")
    os.mkfifo(os.path.join(workdir, "fifo"))
    os.symlink(os.path.join(SCENES, "data"), os.path.join(workdir, "data"))
    path = os.path.join(workdir, "scene.json")
    with open(path, "w", encoding="utf-8") as f:
        f.write(dump(mutate(load(os.path.join(SCENES, scene)), pointer, kind, workdir)))
    return workdir, path


def execute(argv, cwd, timeout, memory):
    """(status, stdout, stderr, timed out) of a child with its own process group and limits."""
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                            preexec_fn=limit_child(memory), cwd=cwd)
    timed_out = False
    try:
        stdout, stderr = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        os.killpg(proc.pid, signal.SIGKILL)
        stdout, stderr = proc.communicate()
    return proc.returncode, stdout.decode("utf-8", "replace"), stderr.decode("utf-8", "replace"), timed_out


def result(job, status, verdict, detail, text):
    index, mode, scene, pointer, kind = job[:5]
    lines = text.strip().splitlines()
    return {"index": index, "mode": mode, "scene": scene, "pointer": pointer, "kind": kind, "status": status,
            "verdict": verdict, "detail": detail, "message": lines[-1][:300] if lines else ""}


def run_one(job):
    """One mutant through its own `filum check` or `filum run` process."""
    index, mode, scene, pointer, kind, filum, timeout, memory = job
    workdir, path = prepare(job)
    try:
        out_dir = os.path.join(workdir, "out")
        argv = [filum, "check", path] if mode == "check" else [filum, "run", path, "-t", "0.01", "-q", "--out", out_dir]
        status, stdout, stderr, timed_out = execute(argv, workdir, timeout, memory)
        verdict, detail = classify(mode, path, out_dir, status, stdout, stderr, timed_out)
        return result(job, status, verdict, detail, stdout + stderr)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def check_batch(jobs):
    """Mutants through one `filum check` process (it prints one line per file, flushed, so a
    process start — 0.5 s of dynamic loading — is paid once per batch). A batch that crashed or
    timed out is resolved file by file: each file without its line runs alone."""
    filum, timeout, memory = jobs[0][5:8]
    prepared = [prepare(job) for job in jobs]
    try:
        argv = [filum, "check"] + [path for _, path in prepared]
        # A check takes well under a second: a batch slower than that per file holds a hang,
        # found below by running its unfinished files alone, each with the full timeout.
        status, stdout, stderr, timed_out = execute(argv, "/", timeout + len(jobs), memory)
        lines = [l for l in stdout.splitlines() if l.startswith("error: ") or ": ok (" in l]
        complete = not timed_out and status in (0, 2) and len(lines) == len(jobs)
        results = []
        for k, (job, (workdir, path)) in enumerate(zip(jobs, prepared)):
            if complete or k < len(lines):  # a line is printed only once its file is done
                line = lines[k]
                one_status = 2 if line.startswith("error: ") else 0
                verdict, detail = classify("check", path, "", one_status, line, "", False)
                results.append(result(job, one_status, verdict, detail, line))
            else:
                results.append(run_one(job))
        return results
    finally:
        for workdir, _ in prepared:
            shutil.rmtree(workdir, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--filum", default=os.path.join(ROOT, "build", "apps", "filum"))
    parser.add_argument("--checks", type=int, default=30000, help="mutants through `filum check`")
    parser.add_argument("--runs", type=int, default=3000, help="mutants through `filum run -t 0.01`")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--seed", type=int, default=14)
    parser.add_argument("--timeout", type=float, default=20.0, help="seconds per check (runs get 3x)")
    parser.add_argument("--memory", type=int, default=4 << 30, help="address-space limit of a child (bytes)")
    parser.add_argument("--report", default="", help="write every non-ok result (and the counts) as JSON")
    parser.add_argument("--only", default="", help="only scenes whose name contains this")
    parser.add_argument("--batch", type=int, default=50, help="mutants per `filum check` process")
    args = parser.parse_args()
    filum = os.path.abspath(args.filum)

    mutations = [m for m in all_mutations() if args.only in m[0]]
    rng = random.Random(args.seed)
    # Every field first: round r takes the r-th (shuffled) kind of every (scene, pointer), so that
    # any sample larger than the number of fields mutates every field of every scene; whole
    # passes over all mutations before any repeats.
    by_field = collections.OrderedDict()
    for m in mutations:
        by_field.setdefault(m[:2], []).append(m)
    rounds = []
    for kinds in by_field.values():
        rng.shuffle(kinds)
    for r in range(max(len(k) for k in by_field.values())):
        layer = [kinds[r] for kinds in by_field.values() if r < len(kinds)]
        rng.shuffle(layer)
        rounds.extend(layer)

    def sample(count, offset):
        return [rounds[(offset + i) % len(rounds)] for i in range(count)]
    jobs = [(i, "check", s, p, k, filum, args.timeout, args.memory) for i, (s, p, k) in enumerate(sample(args.checks, 0))]
    jobs += [(args.checks + i, "run", s, p, k, filum, 3 * args.timeout, args.memory)
             for i, (s, p, k) in enumerate(sample(args.runs, args.checks))]
    print("%d distinct mutations of %d fields of %d scenes; %d checks, %d runs" %
          (len(mutations), len(by_field), len({m[0] for m in mutations}), args.checks, args.runs), flush=True)

    counts = collections.Counter()
    findings = []
    checks = [j for j in jobs if j[1] == "check"]
    batches = [checks[i:i + args.batch] for i in range(0, len(checks), args.batch)]

    def outcomes(pool):
        for batch in pool.map(check_batch, batches):
            yield from batch
        yield from pool.map(run_one, [j for j in jobs if j[1] == "run"])

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for done, result in enumerate(outcomes(pool), 1):
            counts[(result["mode"], result["verdict"])] += 1
            counts[(result["mode"], "exit %s" % result["status"])] += 1
            if result["verdict"] != "ok":
                findings.append(result)
                print("%-9s %-5s %s %s [%s] -> %s %s" % (result["verdict"], result["mode"], result["scene"],
                      result["pointer"], result["kind"], result["detail"], result["message"][:160]), flush=True)
            if done % 500 == 0:
                print("... %d / %d done" % (done, len(jobs)), flush=True)

    summary = {mode: {v: counts[(mode, v)] for v in ("ok", "crash", "hang", "no place", "nonfinite")}
               for mode in ("check", "run")}
    statuses = {mode: {k[1]: n for k, n in counts.items() if k[0] == mode and k[1].startswith("exit")}
                for mode in ("check", "run")}
    print(json.dumps({"summary": summary, "exit statuses": statuses}, indent=1))
    if args.report:
        os.makedirs(os.path.dirname(os.path.abspath(args.report)), exist_ok=True)
        with open(args.report, "w", encoding="utf-8") as f:
            json.dump({"summary": summary, "exit statuses": statuses, "findings": findings}, f, indent=1)
    bad = sum(summary[m][v] for m in summary for v in ("crash", "hang", "no place", "nonfinite"))
    return 0 if bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
