"""The Python module against the library's command line: the same case gives the same summary, bad input raises
ValueError naming the JSON path, and results come back as NumPy arrays and dicts."""
import csv
import json
import math
import os
import subprocess

import numpy as np
import pytest

import drillwave

SOURCE = os.environ.get("DRILLWAVE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("DRILLWAVE_CLI", "")
CASE = os.path.join(SOURCE, "json-cases", "two-mass-stickslip.json")
# 60 s of the 300 s case: a second or so of work, still a few stick-slip periods (7.5 s) in the window.
SHORT = {"/simulation/duration_s": 60, "/statistics/window_s": [20, 60]}


def load_case():
    with open(CASE) as f:
        return json.load(f)


def test_run_from_file_gives_numpy_channels_and_a_summary():
    r = drillwave.run(CASE, set=SHORT)
    assert r["name"] == "two-mass-stickslip" and r["kind"] == "two_mass"
    time = r["channels"]["time_s"]
    assert isinstance(time, np.ndarray) and time.dtype == np.float64
    assert len(time) == 6001 and time[0] == 0 and time[-1] == pytest.approx(60)  # every 0.01 s
    for name, values in r["channels"].items():
        assert values.shape == time.shape, name
    assert "bit_rpm" in r["channels"]
    assert r["summary"]["stick_onsets"] >= 4
    assert r["case"]["simulation"]["duration_s"] == 60
    assert {e["key"] for e in r["expectations"]} >= {"stick_slip_period_s", "stick_fraction"}


def test_a_dict_with_an_override_is_the_same_case_changed():
    case = load_case()
    case["simulation"]["duration_s"] = 60
    case["statistics"]["window_s"] = [20, 60]
    slow = drillwave.run(case, set={"/model/top/speed_rad_s/knots/1/1": 3.0})
    assert slow["case"]["model"]["top"]["speed_rad_s"]["knots"][1][1] == 3.0
    fast = drillwave.run(case, set=["/model/top/speed_rad_s/knots/1/1=12"])  # the command line's form
    # Driven at 3 rad/s the bit sticks longer than at 12 rad/s, above the stick-slip threshold (10.79 rad/s).
    assert slow["summary"]["stick_fraction"] > 0.3
    assert fast["summary"]["stick_fraction"] < slow["summary"]["stick_fraction"]


@pytest.mark.skipif(not CLI, reason="the command-line tool is not built")
def test_summary_matches_the_command_lines_summary_json(tmp_path):
    out = tmp_path / "out"
    args = [f"--set={p}={json.dumps(v)}" for p, v in SHORT.items()]
    subprocess.run([CLI, "run", CASE, "--out", str(out), *args], check=True, capture_output=True)
    with open(out / "summary.json") as f:
        cli = json.load(f)
    py = drillwave.run(CASE, set=SHORT)["summary"]
    assert set(py) == set(cli)
    assert py["stick_fraction"] > 0.3  # the comparison below is about a run that sticks
    for key, value in cli.items():
        if key != "wall_time_s":
            assert py[key] == value, key  # the same library on the same case: the same numbers, to the last digit


def test_a_bad_field_raises_value_error_naming_path_value_and_range():
    with pytest.raises(ValueError) as e:
        drillwave.run(CASE, set={"/model/bit/inertia_kgm2": -1})
    message = str(e.value)
    assert message.startswith("/model/bit/inertia_kgm2: ")
    assert "-1" in message and "> 0" in message
    assert isinstance(e.value, drillwave.InputError) and e.value.path == "/model/bit/inertia_kgm2"


def test_an_unknown_field_in_a_dict_and_a_bad_file_are_value_errors():
    case = load_case()
    case["model"]["stiffnes_Nm_per_rad"] = 1
    with pytest.raises(ValueError, match=r"^/model/stiffnes_Nm_per_rad: unknown field"):
        drillwave.run(case)
    with pytest.raises(ValueError, match="no-such-case.json"):
        drillwave.run("no-such-case.json")
    with pytest.raises(ValueError, match=r"^/model/top/inertia_kgm2: a value of Python type object"):
        drillwave.run(case, set={"/model/top/inertia_kgm2": object()})
    with pytest.raises(ValueError, match=r"^set: 'top=3': expected /json/pointer=value"):
        drillwave.run(CASE, set=["top=3"])
    with pytest.raises(ValueError, match=r"^max_samples: expected a finite number >= 1, got 0"):
        drillwave.run(CASE, max_samples=0)


def test_max_samples_refuses_a_long_run_for_one_call_only():
    with pytest.raises(ValueError, match="max_samples"):
        drillwave.run(CASE, set=SHORT, max_samples=1000)
    assert len(drillwave.run(CASE, set=SHORT)["channels"]["time_s"]) == 6001  # the default limit again


def test_numerical_failure_is_a_runtime_error_with_time_and_state():
    # The default case (a torsional wave string) with an absurd top-drive damping: the outputs overflow (the command
    # line's exit 3).
    with pytest.raises(RuntimeError) as e:
        drillwave.run(None, set={"/model/top/beta_Nms_per_rad": 1e308, "/simulation/duration_s": 10,
                                 "/statistics/window_s": [5, 10]})
    assert isinstance(e.value, drillwave.NumericalError)
    assert "is not finite" in str(e.value) and " at t = " in str(e.value)
    assert math.isfinite(e.value.time) and isinstance(e.value.state, list)


def test_sweep_returns_one_summary_per_value():
    r = drillwave.sweep(CASE, "/model/top/speed_rad_s/knots/1/1", [3.0, 12.0], set=SHORT, jobs=2)
    assert [p["value"] for p in r["points"]] == [3.0, 12.0]
    assert all(p["ok"] for p in r["points"])
    assert r["points"][0]["summary"]["stick_fraction"] > r["points"][1]["summary"]["stick_fraction"]
    with pytest.raises(ValueError, match=r"^values/1: expected a finite number, got nan"):
        drillwave.sweep(CASE, "/model/top/speed_rad_s/knots/1/1", [3.0, float("nan")], set=SHORT)
    with pytest.raises(ValueError, match=r"^jobs: expected a whole number in \[1, 1024\], got 0"):
        drillwave.sweep(CASE, "/model/top/speed_rad_s/knots/1/1", [3.0], set=SHORT, jobs=0)
    with pytest.raises(ValueError, match=r"^/model/bit/inertia_kgm2: .*got -1"):  # refused before any run
        drillwave.sweep(CASE, "/model/bit/inertia_kgm2", [400, -1], set=SHORT)


def test_stability_of_the_case_and_a_map():
    r = drillwave.stability(CASE)
    assert r["kind"] == "two_mass" and len(r["operating_points"]) >= 1
    # At 5 rad/s smooth rotation is linearly stable (stable from 4.12 rad/s on; the case's notes).
    assert r["operating_points"][0]["stable"]
    m = drillwave.stability(CASE, param="/model/top/speed_rad_s/knots/1/1", values="3:6:2", jobs=1)
    rows = m["rows"]
    assert [row["value"] for row in rows] == [3.0, 6.0]
    assert not rows[0]["stable"] and rows[1]["stable"]
    with pytest.raises(ValueError, match="both param and values"):
        drillwave.stability(CASE, param="/model/top/speed_rad_s/knots/1/1")


def own_recording(tmp_path):
    """The case's own short run written as a recording (time_s, top_rpm, bit_rpm)."""
    r = drillwave.run(CASE, set=SHORT)
    recording = tmp_path / "recording.csv"
    names = ["time_s", "top_rpm", "bit_rpm"]
    with open(recording, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        writer.writerows(zip(*(r["channels"][n] for n in names)))
    return recording


def test_diagnose_a_recording_of_the_model_itself(tmp_path):
    # The model's own run written as a recording: nothing to explain.
    recording = own_recording(tmp_path)
    d = drillwave.diagnose(CASE, str(recording), set=SHORT, fit_window=(20, 40), held_out=(40, 60))
    assert d["hypotheses"] == [] and d["unexplained"] == []
    assert d["held_out"]["window_s"] == [40, 60] and d["held_out"]["error_after"] < 1
    assert d["fitted_case"]["model"]["kind"] == "two_mass"
    with pytest.raises(ValueError, match=r"^held_out: \(60, 20\) is empty or reversed"):
        drillwave.diagnose(CASE, str(recording), set=SHORT, held_out=(60, 20))
    with pytest.raises(ValueError, match=r"^maps: 'bit_rpm=no_such': the model has no channel no_such"):
        drillwave.diagnose(CASE, str(recording), set=SHORT, maps=["bit_rpm=no_such"])


def test_option_values_out_of_range_raise_input_error_naming_the_keyword(tmp_path):
    # The library's options check their own fields (IsValid) before any run; an options field is named by the keyword
    # that sets it (the fit window's end by fit_window, the held-out window's start by held_out).
    recording = own_recording(tmp_path)
    with pytest.raises(drillwave.InputError, match=r"^margin: expected a fraction in \[0, 1\), got 1$") as e:
        drillwave.diagnose(CASE, str(recording), set=SHORT, margin=1)
    assert e.value.path == "margin"
    with pytest.raises(drillwave.InputError, match=r"^held_out: the held-out window must not begin before the fit "
                                                   r"window ends \(fit_end_s 45, held_out_begin_s 40\)$") as e:
        drillwave.diagnose(CASE, str(recording), set=SHORT, fit_window=(20, 45), held_out=(40, 60))
    assert e.value.path == "held_out"
    with pytest.raises(drillwave.InputError, match=r"^burn_in: expected a whole number in \[0, steps - 1 = 11\]"):
        drillwave.calibrate(CASE, str(recording), ["/model/bit/friction/mu_s:0.5:1"], set=SHORT, steps=12, burn_in=12)


def test_estimate_sees_the_bit_of_the_models_own_recording_as_the_command_line_does(tmp_path):
    # The model's own run as a recording: its bit estimated from the top speed alone, scored against its bit speed.
    recording = own_recording(tmp_path)
    e = drillwave.estimate(CASE, str(recording), "top_rpm", set=SHORT, window=(20, 60))
    errors = e["errors"]
    assert errors["window_s"] == [20, 60]
    assert errors["bit_rpm"]["rms_percent_of_mean"] < 15 and errors["stuck"]["f1"] > 0.9
    channels = e["channels"]
    assert len(channels["time_s"]) == len(channels["bit_rpm"]) == len(channels["bit_stuck"]) > 1000
    assert set(np.unique(channels["bit_stuck"])) <= {0.0, 1.0}
    out = tmp_path / "out"
    args = [f"--set={p}={json.dumps(v)}" for p, v in SHORT.items()]
    subprocess.run([CLI, "estimate", CASE, str(recording), "--from", "top_rpm", "--window", "20,60", "--out",
                    str(out), *args], check=True, capture_output=True)
    with open(out / "estimate.json") as f:
        cli = json.load(f)
    assert cli["errors"] == errors and cli["method"] == e["method"]  # the same library: the same numbers
    with pytest.raises(ValueError, match="is a downhole channel"):
        drillwave.estimate(CASE, str(recording), "bit_rpm", set=SHORT)


TRAIN_REC06 = os.path.join(SOURCE, "..", "shared", "recordings", "synthetic-train", "rec06.csv")


@pytest.mark.skipif(not os.path.exists(TRAIN_REC06), reason="the workplace's recordings (../shared) are absent")
def test_estimate_fuses_delayed_telemetry_as_the_command_line_does(tmp_path):
    # train rec06's downhole channels arrive about 3.7 s late; the baseline case as given is off in weight on bit.
    base = os.path.join(SOURCE, "json-cases", "baseline-60rpm.json")
    surface = drillwave.estimate(base, TRAIN_REC06, "top_rpm,top_torque_kNm,hookload_kN")
    fused = drillwave.estimate(base, TRAIN_REC06, "top_rpm,top_torque_kNm,hookload_kN", fuse="bit_rpm,wob_kN")
    bias = [abs(e["errors"]["wob_N_at_downhole_delay"]["bias"]) for e in (surface, fused)]
    assert bias[1] < 0.5 * bias[0]
    assert any("telemetry fused at a delay of" in n for n in fused["notes"])
    out = tmp_path / "out"
    subprocess.run([CLI, "estimate", base, TRAIN_REC06, "--from", "top_rpm,top_torque_kNm,hookload_kN", "--fuse",
                    "bit_rpm,wob_kN", "--out", str(out)], check=True, capture_output=True)
    with open(out / "estimate.json") as f:
        assert json.load(f)["errors"] == fused["errors"]
    with pytest.raises(drillwave.InputError, match="^fuse_time_constant: expected a finite number > 0"):
        drillwave.estimate(base, TRAIN_REC06, "top_rpm,top_torque_kNm", fuse="bit_rpm", fuse_time_constant=0)


def test_calibrate_samples_the_posterior_of_a_recording_of_the_model_itself(tmp_path):
    # The model's own run as a recording: the posterior of its static friction holds the case's value.
    recording = own_recording(tmp_path)
    truth = drillwave.case_document(CASE)["model"]["bit"]["friction"]["mu_s"]
    p = drillwave.calibrate(CASE, str(recording), [f"/model/bit/friction/mu_s:{0.7 * truth}:{1.3 * truth}"],
                            set=SHORT, fit_window=(20, 40), held_out=(40, 60), walkers=6, steps=12, burn_in=4,
                            predictive_draws=4, jobs=2)
    (mu,) = p["parameters"]
    assert mu["q05"] <= truth <= mu["q95"]
    assert len(p["samples"]) == 6 * (12 - 4) and len(p["samples"][0]) == 4
    assert p["walkers"] == 6 and p["predictive_runs"] == 4
    assert p["map_case"]["model"]["kind"] == "two_mass"
    with pytest.raises(drillwave.InputError, match=r"^walkers: expected an even number") as e:
        drillwave.calibrate(CASE, str(recording), ["/model/bit/friction/mu_s:0.5:1"], set=SHORT, walkers=5)
    assert e.value.path == "walkers"


def test_a_file_name_with_a_nul_byte_is_refused_not_cut(tmp_path):
    # Issue 41: "case.json\0.bak" was cut at the NUL and case.json read instead.
    with pytest.raises(drillwave.InputError, match=r"^case: the file name .*holds a NUL byte \(at offset") as e:
        drillwave.run(CASE + "\0.bak")
    assert e.value.path == "case"
    recording = tmp_path / "recording.csv"
    recording.write_text("time_s,bit_rpm\n0,1\n")
    with pytest.raises(drillwave.InputError, match=r"holds a NUL byte") as e:
        drillwave.diagnose(CASE, str(recording) + "\0x", set=SHORT)
    assert e.value.path == "recording"
    with pytest.raises(drillwave.InputError, match=r"holds a NUL byte") as e:
        drillwave.diagnose(CASE, str(recording), sidecar=str(tmp_path / "s.json") + "\0", set=SHORT)
    assert e.value.path == "sidecar"


def test_a_huge_sweep_raises_input_error_before_allocating():
    # Issue 41: 1e6 values allocated GBs of parsed cases and killed the interpreter; the work is estimated first.
    with pytest.raises(drillwave.InputError, match=r"^values: 1000000 runs of about .* above a sweep's limit") as e:
        drillwave.sweep(CASE, "/model/top/speed_rad_s/knots/1/1", "1:12:1000000", set=SHORT)
    assert e.value.path == "values"


def test_kinds_lists_every_kind_with_its_fields():
    kinds = drillwave.kinds()
    assert {"two_mass", "two_disc", "torsional_wave"} <= set(kinds)
    assert "bit/inertia_kgm2" in json.dumps(kinds["two_mass"]["fields"])


def test_version_is_the_projects_and_the_command_lines():
    # The one version: project(drillwave VERSION ...) in CMakeLists.txt, which `drillwave --version` prints too.
    import re
    with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
        version = re.search(r"project\(drillwave VERSION ([0-9.]+)", f.read()).group(1)
    assert drillwave.__version__ == version
    if CLI:
        out = subprocess.run([CLI, "--version"], capture_output=True, text=True, check=True).stdout
        assert out == f"drillwave {version}\n"


def test_ctrl_c_stops_a_long_call_with_keyboard_interrupt():
    # Issue 41: a long call is interruptible. A sweep of 400 runs of the 300-s case (minutes of work) in a child
    # interpreter gets SIGINT after its first second: KeyboardInterrupt within two seconds, and the module works again.
    import signal
    import sys
    import time
    script = (
        "import sys, time, drillwave\n"
        "print('started', flush=True)\n"
        "t = time.monotonic()\n"
        "try:\n"
        f"    drillwave.sweep({CASE!r}, '/model/top/speed_rad_s/knots/1/1', '3:12:400', jobs=1)\n"
        "    print('finished', flush=True)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted after %.2f s' % (time.monotonic() - t), flush=True)\n"
        f"r = drillwave.run({CASE!r}, set={SHORT!r})\n"
        "print('again', r['summary']['stick_fraction'] > 0, flush=True)\n")
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=os.environ.copy())
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    line = child.stdout.readline().strip()
    assert line.startswith("interrupted after"), line
    assert time.monotonic() - sent < 2.0
    assert child.stdout.readline().strip() == "again True"
    assert child.wait(timeout=60) == 0
