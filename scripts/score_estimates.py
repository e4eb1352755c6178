#!/usr/bin/env python3
"""Scores `drillwave estimate` (issue 34) on the synthetic recordings of ../shared and on the UFRJ rig.

Runs the estimator on each recording from its surface channels only and collects the error figures estimate.json
holds (the tool reads the downhole channels only to score). Prints a Markdown table and the medians.

  python3 scripts/score_estimates.py [--binary build/bin/drillwave] [--shared ../shared] [--jobs 2]
      [--rig-case CASE] [--sets synthetic,synthetic-train] [--fitted DIAGNOSE_OUTPUTS[,...]]

The rig is estimated with --rig-case (default json-cases/ufrj-rig.json; diagnose's fitted-case.json is the one to
use) from top_rpm only and scored on 2-20 s (where its settings were chosen) and on 20-30 s (the issue's target).
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(binary, args, out):
    cmd = [binary, "estimate"] + args + ["-o", out]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return {"error": p.stderr.strip() or p.stdout.strip()}
    with open(os.path.join(out, "estimate.json")) as f:
        return json.load(f)


def row(name, summary):
    if "error" in summary:
        return {"name": name, "error": summary["error"]}
    e = summary["errors"]
    # A downhole channel behind by telemetry (found by the tool as the shift that lowers the error) is scored there.
    late = e.get("bit_rpm_at_downhole_delay")
    return {
        "delay": late["delay_s"] if late else 0.0,
        "rpm_rms_aligned": late["rms"] if late else e["bit_rpm"]["rms"],
        "rpm_pct_aligned": late["rms_percent_of_mean"] if late else e["bit_rpm"]["rms_percent_of_mean"],
        "f1_aligned": late["stuck_f1"] if late else e["stuck"]["f1"],
        "name": name,
        "latency": summary["latency_s"],
        "rpm_rms": e["bit_rpm"]["rms"],
        "rpm_pct": e["bit_rpm"]["rms_percent_of_mean"],
        "bit_mean": e["bit_rpm"]["measured_mean"],
        "stuck_frac": e["stuck"]["measured_stuck_fraction"],
        "f1": e["stuck"]["f1"],
        "wob_rms_kN": e["wob_N"]["rms"] / 1000 if "wob_N" in e else float("nan"),
        "wob_pct": e["wob_N"]["rms_percent_of_mean"] if "wob_N" in e else float("nan"),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bin", "drillwave"))
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--rig-case", default=os.path.join(ROOT, "json-cases", "ufrj-rig.json"))
    ap.add_argument("--sets", default="synthetic,synthetic-train")
    ap.add_argument("--fitted", default="",
                    help="folders of diagnose outputs (comma-separated, as score_recordings.py writes them: "
                         "<set>-<rec>/fitted-case.json): each recording found there is estimated with its diagnosed case "
                         "(the others with the base case), and only those are listed")
    a = ap.parse_args()
    jobs = []
    tmp = tempfile.mkdtemp(prefix="score-estimates-")
    for s in a.sets.split(","):
        folder = os.path.join(a.shared, "recordings", s)
        if not os.path.isdir(folder):
            print(f"skipped {folder}: absent", file=sys.stderr)
            continue
        for f in sorted(os.listdir(folder)):
            if f.startswith("rec") and f.endswith(".csv"):
                stem = f[:-4]
                case = os.path.join(ROOT, "json-cases", "baseline-60rpm.json")
                if a.fitted:
                    found = [os.path.join(d, f"{s}-{stem}", "fitted-case.json") for d in a.fitted.split(",")]
                    found = [c for c in found if os.path.exists(c)]
                    if not found:
                        continue
                    case = found[0]
                jobs.append((f"{s}/{stem}", [case,
                                             os.path.join(folder, f), "--sidecar", os.path.join(folder, stem + ".json"),
                                             "--from", "top_rpm,top_torque_kNm,hookload_kN"]))
    rig = os.path.join(a.shared, "recordings", "ufrj-rig", "rig-0-30s.csv")
    if os.path.exists(rig) and not a.fitted:
        for window in ("2,20", "20,30"):
            jobs.append((f"ufrj-rig {window.replace(',', '-')} s", [a.rig_case, rig, "--from", "top_rpm", "--window", window]))
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        results = list(pool.map(lambda j: row(j[0], run(a.binary, j[1], os.path.join(tmp, j[0].replace("/", "_").replace(" ", "_")))), jobs))
    print("| recording | bit mean [rpm] | bit-speed RMS [rpm] | RMS % of mean | stuck fraction | stuck F1 | WOB RMS [kN] | "
          "WOB RMS % | latency [s] | downhole delay found [s] | RMS % / F1 at that delay |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        if "error" in r:
            print(f"| {r['name']} | error: {r['error']} |||||||")
            continue
        print(f"| {r['name']} | {r['bit_mean']:.1f} | {r['rpm_rms']:.2f} | {r['rpm_pct']:.1f} | {r['stuck_frac']:.3f} | "
              f"{r['f1']:.3f} | {r['wob_rms_kN']:.2f} | {r['wob_pct']:.1f} | {r['latency']:.2f} | "
              + (f"{r['delay']:.2f} | {r['rpm_pct_aligned']:.1f} / {r['f1_aligned']:.3f} |" if r["delay"] > 0 else "- | - |"))
    synth = [r for r in results if "error" not in r and not r["name"].startswith("ufrj")]
    if synth:
        pct = statistics.median(r["rpm_pct"] for r in synth)
        f1 = statistics.median(r["f1"] for r in synth)
        sticking = [r for r in synth if r["stuck_frac"] > 0.01]
        f1s = statistics.median(r["f1"] for r in sticking) if sticking else float("nan")
        wob = statistics.median(r["wob_pct"] for r in synth)
        pct_a = statistics.median(r["rpm_pct_aligned"] for r in synth)
        f1_a = statistics.median(r["f1_aligned"] for r in synth)
        f1s_a = statistics.median(r["f1_aligned"] for r in sticking) if sticking else float("nan")
        print(f"\nmedian over {len(synth)} synthetic recordings: bit-speed RMS {pct:.1f} % of mean (target <= 10), "
              f"stuck F1 {f1:.3f} (target >= 0.9; {f1s:.3f} over the {len(sticking)} that stick > 1 % of the time), "
              f"WOB RMS {wob:.1f} % of mean; "
              f"{sum(r['rpm_pct'] <= 10 for r in synth)} of {len(synth)} within 10 %")
        print(f"scored at the downhole delay where the tool finds one: RMS {pct_a:.1f} %, F1 {f1_a:.3f} "
              f"({f1s_a:.3f} over the sticking ones); {sum(r['rpm_pct_aligned'] <= 10 for r in synth)} of {len(synth)} "
              f"within 10 %")


if __name__ == "__main__":
    main()
