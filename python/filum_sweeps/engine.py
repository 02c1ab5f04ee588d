"""Where the tasks run: a Dask client on a LocalCluster or a remote scheduler, or none (serial)."""
import contextlib
import os


@contextlib.contextmanager
def open_client(scheduler=None, workers=None):
    """with open_client(...) as client: a dask.distributed Client, closed (with its LocalCluster) on exit.

    scheduler: address of a running scheduler ("tcp://host:8786"): the cluster's workers run the
    tasks; they need filum built at the same path as here (or --bench-dir pointing at theirs).
    Otherwise a LocalCluster of `workers` workers (default: one per core) of one thread each: a
    task is a C++ program in its own process, so a worker thread only waits for it, and one task
    per core keeps the wall times that accuracy_pareto measures free of contention. The workers
    are threads of this process (processes=False): nothing to start or pickle beyond the tasks
    themselves, and no network port opened.
    """
    from dask.distributed import Client, LocalCluster

    if scheduler:
        with Client(scheduler) as client:
            yield client
        return
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        yield client


def map_tasks(function, items, client=None, key_prefix="filum-task"):
    """[function(item) for item in items], through the client's workers when given.

    Results come back in the order of `items`, whatever order the workers finish in; the first
    task that raised raises here with its own exception.
    """
    items = list(items)
    if client is None:
        return [function(item) for item in items]
    futures = client.map(function, items, key=[f"{key_prefix}-{i}" for i in range(len(items))])
    return client.gather(futures)
