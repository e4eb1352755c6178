"""The module releases Python's GIL while the library works (issue 37): other Python threads, and other drillwave
calls, run meanwhile. Shown by what happens inside a call's span, not by how long it takes: with the GIL held, no
other thread could run a line in it, so the longest gap between what they did there would be the whole span."""
import os
import threading
import time

import pytest

import drillwave

SOURCE = os.environ.get("DRILLWAVE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CASE = os.path.join(SOURCE, "json-cases", "two-mass-stickslip.json")
# Half a second or so, and a millisecond.
LONG = {"/simulation/duration_s": 8000, "/simulation/output_interval_s": 1, "/statistics/window_s": [20, 8000]}
SHORT = {"/simulation/duration_s": 8, "/statistics/window_s": [2, 8]}


def call_in_thread(function):
    """Starts function() in a thread; returns the thread and a dict that gets "start" and "end" around the call."""
    span = {}

    def work():
        span["start"] = time.perf_counter()
        try:
            function()
        finally:
            span["end"] = time.perf_counter()

    thread = threading.Thread(target=work)
    thread.start()
    return thread, span


def longest_gap(span, times):
    """The longest stretch of the span without one of `times` (those outside the span ignored)."""
    inside = sorted(t for t in times if span["start"] < t < span["end"])
    edges = [span["start"], *inside, span["end"]]
    return max(b - a for a, b in zip(edges, edges[1:])), len(inside)


def test_python_threads_run_while_a_call_works():
    thread, span = call_in_thread(lambda: drillwave.run(CASE, set=LONG))
    ticks = []
    while thread.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    thread.join()
    gap, inside = longest_gap(span, ticks)
    assert inside >= 10 and gap < 0.5 * (span["end"] - span["start"]), (inside, gap, span)


def test_two_calls_run_side_by_side():
    # Short runs, one after the other in this thread, end inside the long run's span in the other thread.
    thread, span = call_in_thread(lambda: drillwave.run(CASE, set=LONG))
    ends = []
    while thread.is_alive():
        drillwave.run(CASE, set=SHORT)
        ends.append(time.perf_counter())
    thread.join()
    gap, inside = longest_gap(span, ends)
    assert inside >= 3 and gap < 0.5 * (span["end"] - span["start"]), (inside, gap, span)


def test_sweep_and_stability_release_the_gil_too():
    for call in (lambda: drillwave.sweep(CASE, "/model/top/speed_rad_s/knots/1/1", "3:12:2", set=LONG, jobs=1),
                 lambda: drillwave.stability(CASE, "/model/top/speed_rad_s/knots/1/1", "3:12:5000", jobs=1)):
        thread, span = call_in_thread(call)
        ticks = []
        while thread.is_alive():
            ticks.append(time.perf_counter())
            time.sleep(0.001)
        thread.join()
        gap, inside = longest_gap(span, ticks)
        assert inside >= 10 and gap < 0.5 * (span["end"] - span["start"]), (inside, gap, span)


def test_a_calls_own_sample_limit_does_not_reach_a_concurrent_call():
    # The library's limit is process-wide: a call with max_samples holds it alone for its length, so a call without
    # one, at the same time, is judged by the default limit (1e7), never by the other call's (1e6).
    stop = threading.Event()
    ran = []

    def own_limit():
        while not stop.is_set():
            drillwave.run(CASE, set=LONG, max_samples=1e6)
            ran.append(1)

    too_many = {"/simulation/duration_s": 100, "/simulation/output_interval_s": 1e-6}  # 1e8 samples: refused
    thread = threading.Thread(target=own_limit)
    thread.start()
    messages = set()
    try:
        while len(ran) < 3 and thread.is_alive():
            with pytest.raises(drillwave.InputError) as e:
                drillwave.run(CASE, set=too_many)
            messages.add(str(e.value).split("above the limit of ")[1].split(";")[0])
    finally:
        stop.set()
        thread.join()
    assert len(ran) >= 3 and messages == {"10000000"}, (len(ran), messages)
