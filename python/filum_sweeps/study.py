"""The studies: accuracy_pareto and stability_map (apps/bench/), one configuration per task."""
import dataclasses
import os
import pathlib
import subprocess
import tempfile

from .engine import map_tasks


def default_bench_dir():
    """build/apps/bench of this tree, or $FILUM_BINARY_DIR/apps/bench."""
    build = os.environ.get("FILUM_BINARY_DIR") or pathlib.Path(__file__).resolve().parents[2] / "build"
    return pathlib.Path(build) / "apps" / "bench"


def run_program(command):
    """Runs a study program; its stdout, or RuntimeError with the command and what it printed."""
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed ({done.returncode}):\n{done.stdout}{done.stderr}")
    return done.stdout


@dataclasses.dataclass(frozen=True)
class Study:
    """A study program and the options that select its grid (the same for every task)."""
    name: str          # the program in apps/bench/
    options: tuple     # e.g. ("--quick", "--problem", "catenary")
    bench_dir: str = None

    @property
    def program(self):
        return pathlib.Path(self.bench_dir) / self.name if self.bench_dir else default_bench_dir() / self.name

    def configurations(self):
        """The configurations, one line each ("K,..."), in the order of the serial run."""
        return run_program([self.program, *self.options, "--list"]).splitlines()

    def run_configuration(self, index):
        """Runs configuration `index` alone: its result row (a task; picklable, runs on any worker)."""
        return run_program([self.program, *self.options, "--configuration", str(index)]).strip()

    def sweep(self, out, client=None, plot=True):
        """Runs every configuration through the client (serially without one) and writes the
        study's CSV (and plot) into `out` with the program itself, as a serial run would.
        Returns the program's report (stdout)."""
        count = len(self.configurations())
        rows = map_tasks(self.run_configuration, range(count), client, key_prefix=self.name)
        with tempfile.TemporaryDirectory() as scratch:
            rows_file = pathlib.Path(scratch) / "rows.csv"
            rows_file.write_text("\n".join(rows) + "\n")
            command = [self.program, *self.options, "--rows", rows_file, "--out", out]
            return run_program(command + ([] if plot else ["--no-plot"]))


def accuracy_pareto(quick=False, problem=None, bench_dir=None):
    """Run time against error of every integrator on the reference problems (apps/bench/accuracy_pareto.cpp)."""
    options = (("--quick",) if quick else ()) + (("--problem", problem) if problem else ())
    return Study("accuracy_pareto", options, bench_dir)


def stability_map(quick=False, bench_dir=None):
    """Largest stable step of every integrator against stiffness (apps/bench/stability_map.cpp)."""
    return Study("stability_map", ("--quick",) if quick else (), bench_dir)
