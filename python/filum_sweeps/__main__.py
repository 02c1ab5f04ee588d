"""python3 -m filum_sweeps STUDY [options]: a study through Dask (see the package's docstring)."""
import argparse
import sys
import time

from .engine import open_client
from .study import accuracy_pareto, stability_map


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m filum_sweeps",
                                     description="filum's parameter studies, one configuration per Dask task")
    parser.add_argument("study", choices=["accuracy_pareto", "stability_map"])
    parser.add_argument("--quick", action="store_true", help="the study's short grid")
    parser.add_argument("--problem", help="accuracy_pareto: one problem (catenary, taut_string, cantilever)")
    parser.add_argument("--out", default=".", help="folder of the CSV and PNG files (default: .)")
    parser.add_argument("--no-plot", action="store_true", help="CSV only")
    parser.add_argument("--bench-dir", help="folder of the study programs (default: build/apps/bench)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="address of a Dask scheduler (tcp://host:8786); default: a LocalCluster")
    where.add_argument("--workers", type=int, help="LocalCluster workers (default: one per core)")
    where.add_argument("--serial", action="store_true", help="no Dask: every configuration here, one after the other")
    args = parser.parse_args(argv)
    if args.problem and args.study != "accuracy_pareto":
        parser.error("--problem is an option of accuracy_pareto")

    study = (accuracy_pareto(args.quick, args.problem, args.bench_dir) if args.study == "accuracy_pareto"
             else stability_map(args.quick, args.bench_dir))
    start = time.perf_counter()
    if args.serial:
        report = study.sweep(args.out, None, plot=not args.no_plot)
        where_text = "serially"
    else:
        with open_client(args.scheduler, args.workers) as client:
            workers = len(client.scheduler_info()["workers"])
            report = study.sweep(args.out, client, plot=not args.no_plot)
        where_text = f"on {workers} Dask worker{'s' if workers != 1 else ''}"
    print(report, end="")
    print(f"{args.study}: {len(study.configurations())} configurations {where_text} in "
          f"{time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
