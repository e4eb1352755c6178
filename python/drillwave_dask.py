"""drillwave's work on Dask.distributed (issue 37): many runs, a sweep over a parameter's values, a stability map's
points, each point a task, by default on a LocalCluster of worker processes on this machine started for the call,
or on a given `client=` (a distributed.Client) or `scheduler=` address ("tcp://HOST:PORT").

    import drillwave_dask
    s = drillwave_dask.sweep("json-cases/two-mass-stickslip.json", "/model/top/speed_rad_s/knots/1/1", "3:12:40")

Each task is a pure function of (the case as JSON text, its settings) and returns a small result (summaries, no
channels unless asked), so the scheduler may run it again after a worker is lost, and a task's result is that of
the same call in-process: a sweep's point is drillwave.sweep on that one value, a map's point drillwave.stability
on that one value, a run drillwave.run. The case travels as its document, so workers on other machines need no case
file (they need drillwave and drillwave_dask importable: `cmake --install` puts both in dist-packages). Needs
Dask.distributed (Debian: apt-get install python3-distributed); importing this module does not. The local
cluster's worker processes are spawned and import the main script again: in a script, start it under
`if __name__ == "__main__":` (without the guard every worker would start a cluster in turn), and not from a program
read on standard input (refused).
"""
import contextlib
import json
import os
import sys
import time

import drillwave

__all__ = ["run_many", "sweep", "stability_map", "local_client", "SchedulerUnreachable"]


class SchedulerUnreachable(ConnectionError):
    """No Dask scheduler answered at the address given within the timeout."""


def _distributed():
    try:
        import distributed
    except ImportError as e:
        raise ImportError("drillwave_dask needs Dask.distributed (Debian: apt-get install python3-distributed): "
                          f"{e}") from e
    return distributed


def _cpus():
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


@contextlib.contextmanager
def local_client(workers=None):
    """A distributed.Client on a new LocalCluster of `workers` worker processes (default: the CPUs this process may
    run on), one thread each, without dashboard; leaving the `with` stops the cluster. To keep one cluster over
    several calls: `with drillwave_dask.local_client(2) as c: drillwave_dask.sweep(..., client=c)`."""
    distributed = _distributed()
    n = _cpus() if workers is None else workers
    if not isinstance(n, int) or n < 1:
        raise ValueError(f"workers: expected a whole number >= 1, got {workers!r}")
    main = getattr(sys.modules.get("__main__"), "__file__", None)
    if main is not None and not os.path.isfile(main):  # "<stdin>": each worker would fail to start, again and again
        raise RuntimeError(f"drillwave_dask: a LocalCluster's worker processes import the main program, and {main} "
                           "is not a file: run it from a script, or give client= or scheduler=")
    with distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            yield client


@contextlib.contextmanager
def _client(client, scheduler, workers, timeout):
    if client is not None and scheduler is not None:
        raise ValueError("give client= or scheduler=, not both")
    if client is not None:
        yield client
        return
    if scheduler is None:
        with local_client(workers) as c:
            yield c
        return
    distributed = _distributed()
    try:
        c = distributed.Client(scheduler, timeout=timeout)
    except (OSError, TimeoutError) as e:  # distributed raises OSError("Timed out trying to connect ...")
        raise SchedulerUnreachable(f"no Dask scheduler answered at {scheduler} within {timeout} s ({e})") from e
    with c:
        yield c


def _map(function, args, client, scheduler, workers, timeout):
    """function(*a) for each a in args as pure tasks, their results in order."""
    with _client(client, scheduler, workers, timeout) as c:
        futures = c.map(function, *zip(*args), pure=True) if args else []
        try:
            return c.gather(futures)
        except BaseException:  # the first error (raised as the task raised it): the rest is not needed
            c.cancel(futures)
            raise


# The tasks: module-level functions (workers import them by name) of JSON text and plain values.

def _run_task(case_text, max_samples, channels):
    r = drillwave.run(json.loads(case_text), max_samples=max_samples)
    if not channels:
        del r["channels"]
    return r


def _sweep_task(case_text, param, value, max_samples):
    return drillwave.sweep(json.loads(case_text), param, [value], jobs=1, max_samples=max_samples)["points"][0]


def _stability_task(case_text, param, value, max_samples):
    return drillwave.stability(json.loads(case_text), param, [value], jobs=1, max_samples=max_samples)["rows"]


def _text(case, overrides=None):
    # The document as drillwave reads it (file, dict or None: the default case), overrides applied, as JSON text.
    return json.dumps(drillwave.case_document(case, overrides), sort_keys=True)


def run_many(cases, sets=None, *, channels=False, max_samples=None, client=None, scheduler=None, workers=None,
             timeout=10):
    """drillwave.run for each case (a file name, dict or None), or for one case with each of `sets` (overrides, as
    drillwave.run's set=), or for each (case, set) pair when both are lists of one length. Returns the results in
    order, without "channels" unless channels=True. A run's error (drillwave.InputError, NumericalError) is raised."""
    if sets is None:
        pairs = [(c, None) for c in cases]
    elif isinstance(cases, (list, tuple)):
        if len(cases) != len(sets):
            raise ValueError(f"{len(cases)} cases and {len(sets)} sets: expected as many of each")
        pairs = list(zip(cases, sets))
    else:
        pairs = [(cases, s) for s in sets]
    args = [(_text(c, s), max_samples, channels) for c, s in pairs]
    return _map(_run_task, args, client, scheduler, workers, timeout)


def sweep(case, param, values, set=None, *, max_samples=None, client=None, scheduler=None, workers=None,
          timeout=10):
    """As drillwave.sweep, one task per value: {"param", "points": [{"value", "ok", "summary", "error"}],
    "wall_time_s"} (the whole map's wall time)."""
    start = time.perf_counter()
    text = _text(case, set)
    args = [(text, param, v, max_samples) for v in drillwave.sweep_values(values)]
    points = _map(_sweep_task, args, client, scheduler, workers, timeout)
    return {"param": param, "points": points, "wall_time_s": time.perf_counter() - start}


def stability_map(case, param, values, set=None, *, max_samples=None, client=None, scheduler=None, workers=None,
                  timeout=10):
    """As drillwave.stability(case, param, values), one task per value: {"param", "rows": [{"value", "branch",
    "speed_rad_s", "spectral_abscissa", "frequency_rad_s", "essential_abscissa", "stable"}]}."""
    text = _text(case, set)
    args = [(text, param, v, max_samples) for v in drillwave.sweep_values(values)]
    return {"param": param, "rows": [r for rows in _map(_stability_task, args, client, scheduler, workers, timeout)
                                     for r in rows]}
