#!/usr/bin/env python3
"""Issue 37's bench: a map of short runs (the two-mass case, 300 s each, the top speed varied) through drillwave_dask
on a LocalCluster of 1 and of 2 worker processes, against the same runs in-process, one after the other and on two
Python threads (the module releases the GIL). Prints wall times, the speed-up of 2 workers against 1, and the
overhead per task: (1 worker's wall time - the in-process serial one) / runs, and a map of as many almost empty
runs (0.1 simulated s) on 1 worker. The clusters are started and warmed up
(drillwave imported in every worker) before the clock starts.

    PYTHONPATH=build/python /usr/bin/python3 scripts/bench_dask.py [--runs 300] [--duration 300]
"""
import argparse
import os
import threading
import time

import drillwave
import drillwave_dask

CASE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "json-cases", "two-mass-stickslip.json")
SPEED = "/model/top/speed_rad_s/knots/1/1"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=300)
    parser.add_argument("--duration", type=float, default=300, help="simulated seconds per run")
    args = parser.parse_args()
    d = args.duration
    sets = [{"/simulation/duration_s": d, "/statistics/window_s": [d / 2, d], SPEED: 3 + 11 * i / (args.runs - 1)}
            for i in range(args.runs)]
    cpus = len(os.sched_getaffinity(0))
    print(f"{args.runs} runs of {CASE.rsplit('/', 1)[-1]} ({d:g} simulated s each); {cpus} CPUs, "
          f"load average {os.getloadavg()[0]:.1f} at the start")

    drillwave.run(CASE, set=sets[0])  # the first call's one-time set-up, out of the clock
    start = time.perf_counter()
    serial = [drillwave.run(CASE, set=s)["summary"] for s in sets]
    t_serial = time.perf_counter() - start

    halves, results = [sets[0::2], sets[1::2]], [None, None]
    start = time.perf_counter()
    threads = [threading.Thread(target=lambda k=k: results.__setitem__(
        k, [drillwave.run(CASE, set=s)["summary"] for s in halves[k]])) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    t_threads = time.perf_counter() - start

    t_workers = {}
    for workers in (1, 2):
        with drillwave_dask.local_client(workers) as client:
            client.wait_for_workers(workers)
            drillwave_dask.run_many(CASE, sets[:2 * workers], client=client)  # drillwave imported in every worker
            start = time.perf_counter()
            runs = drillwave_dask.run_many(CASE, sets, client=client)
            t_workers[workers] = time.perf_counter() - start
            if workers == 1:  # a task with almost no work: the per-task cost of Dask and of the layer alone
                tiny = [{"/simulation/duration_s": 0.1, "/statistics/window_s": [0, 0.1], SPEED: s[SPEED]} for s in sets]
                start = time.perf_counter()
                drillwave_dask.run_many(CASE, tiny, client=client)
                t_tiny = time.perf_counter() - start
        for a, b in zip(runs, serial):
            same = {k: v for k, v in a["summary"].items() if not k.endswith("wall_time_s")} == \
                   {k: v for k, v in b.items() if not k.endswith("wall_time_s")}
            assert same, "a run on Dask differs from the in-process one"

    n = args.runs
    print(f"in-process, one after the other: {t_serial:7.2f} s ({1e3 * t_serial / n:.1f} ms a run)")
    print(f"in-process, two Python threads:  {t_threads:7.2f} s (speed-up {t_serial / t_threads:.2f}x)")
    print(f"Dask, 1 worker process:          {t_workers[1]:7.2f} s "
          f"(overhead {1e3 * (t_workers[1] - t_serial) / n:.1f} ms a task; {1e3 * t_tiny / n:.1f} ms a task of "
          f"0.1 simulated s)")
    print(f"Dask, 2 worker processes:        {t_workers[2]:7.2f} s "
          f"(speed-up {t_workers[1] / t_workers[2]:.2f}x against 1 worker)")
    print(f"every Dask result equal to the in-process run's; load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":  # the worker processes are spawned: they import this file without running it
    main()
