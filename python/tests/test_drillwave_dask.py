"""drillwave_dask on a real Dask.distributed LocalCluster of two worker processes (issue 37): the results are the
in-process calls' to the last digit, a worker killed mid-map (SIGKILL) costs nothing but time, and a scheduler that
is not there is a clear error after the timeout rather than a hang. Skipped without Dask.distributed."""
import math
import os
import signal
import socket
import threading
import time

import pytest

distributed = pytest.importorskip(
    "distributed", reason="Dask.distributed is not importable (Debian: apt-get install python3-distributed)")

import drillwave  # noqa: E402
import drillwave_dask  # noqa: E402

SOURCE = os.environ.get("DRILLWAVE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CASE = os.path.join(SOURCE, "json-cases", "two-mass-stickslip.json")
SPEED = "/model/top/speed_rad_s/knots/1/1"
SHORT = {"/simulation/duration_s": 20, "/statistics/window_s": [10, 20]}  # a millisecond of work
# A tenth of a second (here; more on two busy cores): a map of them still runs when a worker is killed.
DEFAULT_SHORT = {"/simulation/duration_s": 5, "/statistics/window_s": [0, 5]}  # for the embedded default case
LONGER = {"/simulation/duration_s": 1500, "/simulation/output_interval_s": 1, "/statistics/window_s": [20, 1500]}


def same(a, b):
    """Equal to the last digit, wall times aside (NaN equal to NaN)."""
    if isinstance(a, dict) and isinstance(b, dict):
        keys = {k for k in set(a) | set(b) if not k.endswith("wall_time_s")}
        return all(k in a and k in b and same(a[k], b[k]) for k in keys)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


@pytest.fixture(scope="module")
def client():
    with drillwave_dask.local_client(2) as c:
        c.wait_for_workers(2)
        yield c


def test_a_sweep_on_two_worker_processes_is_the_in_process_sweep(client):
    assert len(client.scheduler_info()["workers"]) == 2
    values = "3:14:8"
    dask = drillwave_dask.sweep(CASE, SPEED, values, set=SHORT, client=client)
    local = drillwave.sweep(CASE, SPEED, values, set=SHORT)
    assert [p["value"] for p in dask["points"]] == drillwave.sweep_values(values)
    assert any(p["summary"]["stick_fraction"] > 0.4 for p in local["points"])  # runs that stick, and some that don't
    assert any(p["summary"]["stick_fraction"] == 0 for p in local["points"])
    assert same(dask, local)


def test_runs_and_a_stability_map_are_the_in_process_ones(client):
    sets = [{**SHORT, SPEED: v} for v in (3.0, 6.5, 11.0)]
    runs = drillwave_dask.run_many(CASE, sets, client=client)
    for r, s in zip(runs, sets):
        local = drillwave.run(CASE, set=s)
        del local["channels"]
        assert same(r, local)
    with_channels = drillwave_dask.run_many([CASE, None], channels=True, max_samples=1e7,
                                            sets=[SHORT, DEFAULT_SHORT], client=client)
    assert same(with_channels[1]["summary"], drillwave.run(None, set=DEFAULT_SHORT)["summary"])
    assert (with_channels[0]["channels"]["bit_rpm"] == drillwave.run(CASE, set=SHORT)["channels"]["bit_rpm"]).all()
    dask = drillwave_dask.stability_map(CASE, SPEED, "2:14:7", client=client)
    assert same(dask, drillwave.stability(CASE, SPEED, "2:14:7"))
    assert {r["stable"] for r in dask["rows"]} == {True, False}


def test_a_bad_case_is_the_in_process_error(client):
    # Found by a worker, raised here as drillwave.InputError with its path, as in-process.
    with pytest.raises(drillwave.InputError) as e:
        drillwave_dask.sweep(CASE, SPEED, "3:12:4", set={"/no/such": 1}, client=client)
    assert e.value.path == "/no" and "unknown field" in str(e.value) and "(sweep value " + SPEED in str(e.value)
    with pytest.raises(drillwave.InputError) as e:
        drillwave_dask.run_many(CASE, [{"/model/bit/inertia_kgm2": -1}], client=client)
    assert e.value.path == "/model/bit/inertia_kgm2"
    with pytest.raises(drillwave.InputError, match="cannot open case file no-such-case.json"):  # here, no task
        drillwave_dask.run_many(["no-such-case.json"], client=client)


def test_a_worker_killed_mid_map_costs_only_time(client):
    pids = client.run(os.getpid)  # {worker address: its process}
    assert len(pids) == 2
    values = [3 + 0.25 * i for i in range(40)]
    result = {}
    thread = threading.Thread(
        target=lambda: result.update(drillwave_dask.sweep(CASE, SPEED, values, set=LONGER, client=client)))
    thread.start()

    def done():
        return client.run_on_scheduler(lambda dask_scheduler: sum(
            ts.state == "memory" for key, ts in dask_scheduler.tasks.items() if "_sweep_task" in str(key)))

    while done() < 6 and thread.is_alive():
        time.sleep(0.05)
    assert thread.is_alive(), "the map ended before a worker could be killed; make it longer"
    victim = max(pids.values())
    os.kill(victim, signal.SIGKILL)
    thread.join(timeout=120)
    assert not thread.is_alive()
    assert [p["value"] for p in result["points"]] == values  # every point, once, in order
    assert same(result, drillwave.sweep(CASE, SPEED, values, set=LONGER))
    client.wait_for_workers(2, timeout=60)  # the nanny started a new worker process in the killed one's place
    assert victim not in client.run(os.getpid).values()


def test_a_scheduler_that_is_not_there_is_a_clear_error_not_a_hang():
    with socket.socket() as s:  # a port where nothing listens
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    start = time.perf_counter()
    address = f"tcp://127.0.0.1:{port}"
    with pytest.raises(drillwave_dask.SchedulerUnreachable, match=f"^no Dask scheduler answered at {address} within 2 s"):
        drillwave_dask.sweep(CASE, SPEED, "3:12:2", set=SHORT, scheduler=address, timeout=2)
    assert time.perf_counter() - start < 60  # a guard against a hang, far above the 2 s asked for
    with pytest.raises(ValueError, match="client= or scheduler="):
        drillwave_dask.run_many([None], client=object(), scheduler=address)
