"""Sweeps through Dask (filum_sweeps): a LocalCluster of two workers gives the serial result."""
import os
import subprocess

import numpy as np
import pytest

from conftest import BINARY_DIR
from filum_sweeps import accuracy_pareto, calibrate, map_tasks, open_client, stability_map
from filum_sweeps.calibration import rest_curve

BENCH_DIR = BINARY_DIR / "apps" / "bench"
needs_bench = pytest.mark.skipif(os.environ.get("FILUM_BUILD_BENCHMARKS") == "OFF",
                                 reason="the study programs are benchmarks (FILUM_BUILD_BENCHMARKS=OFF)")


@pytest.fixture(scope="module")
def two_workers():
    with open_client(workers=2) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        yield client


def serial_csv(program, options, out, name):
    subprocess.run([str(BENCH_DIR / program), *options, "--no-plot", "--out", str(out)], check=True,
                   capture_output=True)
    return (out / name).read_text()


@needs_bench
def test_stability_map_on_two_workers_equals_the_serial_run(two_workers, tmp_path):
    study = stability_map(quick=True, bench_dir=BENCH_DIR)
    assert len(study.configurations()) == 15           # 3 moduli × 5 integrators
    study.sweep(tmp_path / "dask", two_workers, plot=False)
    # Bisection on stability is deterministic (no timing in it): the same file, byte for byte.
    assert (tmp_path / "dask" / "stability_map.csv").read_text() == \
        serial_csv("stability_map", ["--quick"], tmp_path / "serial", "stability_map.csv")


@needs_bench
def test_accuracy_pareto_on_two_workers_equals_the_serial_run(two_workers, tmp_path):
    study = accuracy_pareto(quick=True, problem="cantilever", bench_dir=BENCH_DIR)
    study.sweep(tmp_path / "dask", two_workers, plot=False)
    swept = (tmp_path / "dask" / "pareto_cantilever.csv").read_text().splitlines()
    serial = serial_csv("accuracy_pareto", ["--quick", "--problem", "cantilever"], tmp_path / "serial",
                        "pareto_cantilever.csv").splitlines()
    # The comment line and header, then one row per configuration in the same order. Every column
    # but the measured wall times (wall_s, wall_per_sim_s) and what follows from them (pareto) is
    # computed, hence equal to the last digit; the wall times are each run's own measurement.
    assert swept[:2] == serial[:2]
    header = serial[1].split(",")
    measured = {header.index(c) for c in ("wall_s", "wall_per_sim_s", "pareto")}
    assert len(swept) == len(serial) > 2
    for a, b in zip(swept[2:], serial[2:]):
        a, b = a.split(","), b.split(",")
        assert [x for i, x in enumerate(a) if i not in measured] == [x for i, x in enumerate(b) if i not in measured]
        assert float(a[header.index("wall_s")]) > 0.0


@needs_bench
def test_a_failing_task_names_the_program_and_its_message():
    study = stability_map(quick=True, bench_dir=BENCH_DIR)
    with pytest.raises(RuntimeError, match=r"(?s)stability_map --quick --configuration 99 failed \(2\).*expected an index below 15"):
        map_tasks(study.run_configuration, [99])


def test_calibration_finds_the_modulus_of_a_measured_curve(two_workers):
    # "Measured": the model's own rest curve at E = 5 MPa, then a grid around it. The misfit is
    # zero at 5 MPa (the same deterministic run) and grows away from it: the sag goes as 1/E, 3.5 mm
    # at 10 MPa, so a factor of 2 moves the tip by millimetres.
    s = np.linspace(0.0, 1.0, 11)
    measured = rest_curve(5e6, s)
    moduli = [1e6, 2e6, 5e6, 1e7, 2e7]
    best, table = calibrate(s, measured, moduli, two_workers)
    assert best == 5e6
    misfits = dict(table)
    assert misfits[5e6] == 0.0
    assert misfits[2e6] > misfits[1e7] > 1e-4 and misfits[1e6] > misfits[2e6] and misfits[2e7] > misfits[1e7]
    # Two workers (threads running the module, GIL released in the steps) give the serial table.
    assert table == calibrate(s, measured, moduli)[1]
