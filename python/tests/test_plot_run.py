"""The plots the README lists come from `filum run` followed by apps/tools/plot_run.py, as the
demo does: both files exist, are PNG, and are drawn from the run's CSV files."""
import subprocess
import sys

from conftest import BINARY_DIR, SCENES, SOURCE_DIR


def test_plot_run_draws_the_energy_and_the_snapshots_of_a_filum_run(tmp_path):
    out = tmp_path / "hanging_thread"
    subprocess.run([str(BINARY_DIR / "apps" / "filum"), "run", str(SCENES / "hanging_thread.json"),
                    "--duration", "0.2", "--out", str(out), "-q"], check=True)
    subprocess.run([sys.executable, str(SOURCE_DIR / "apps" / "tools" / "plot_run.py"), str(out)], check=True)
    for name in ("energy.png", "snapshots.png"):
        data = (out / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n", name
        assert len(data) > 10_000, name     # a drawn figure, not an empty canvas (a few kB)
