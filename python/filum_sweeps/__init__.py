"""filum_sweeps: parameter studies of filum run through Dask.

The benchmark studies (accuracy_pareto, stability_map) are lists of independent configurations; each task runs one of them by invoking the
study's C++ program (apps/bench/) with --configuration K, which prints one result row; the rows
are gathered in the order of the list and handed back to the same program (--rows FILE), which
writes exactly the CSV and the plot of a serial run. Tasks run on a Dask LocalCluster on this
machine by default, or on a cluster given by its scheduler address.

    python3 -m filum_sweeps stability_map --quick --out results/          # LocalCluster, one worker a core
    python3 -m filum_sweeps accuracy_pareto --workers 2 --out results/
    python3 -m filum_sweeps stability_map --scheduler tcp://10.0.0.5:8786  # an existing cluster

calibrate() fits a material parameter to a measured curve, one candidate per task, through the
`filum` module itself. See docs/sweeps.md.
"""
from .calibration import calibrate
from .engine import map_tasks, open_client
from .study import Study, accuracy_pareto, stability_map

__all__ = ["Study", "accuracy_pareto", "calibrate", "map_tasks", "open_client", "stability_map"]
