#!/usr/bin/env python3
"""Scores `drillwave estimate --fuse` (issue 34 item 2) on the synthetic recordings of ../shared whose downhole
channels arrive late: the estimate from the surface channels against the same with bit_rpm and wob_kN fused, both
scored at the telemetry's delay, with the baseline case at each recording's operating point (its sidecar) and as given.

  python3 scripts/score_fusion.py [--binary build/bin/drillwave] [--shared ../shared]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The recordings whose bit_rpm `estimate` finds late (docs/results.md, the estimate's table).
DELAYED = [("synthetic", "rec04"), ("synthetic", "rec08"), ("synthetic-train", "rec06"), ("synthetic-train", "rec17"),
           ("synthetic-train", "rec20"), ("synthetic-train", "rec21"), ("synthetic-train", "rec35")]


def errors(binary, csv, sidecar, fuse, out):
    cmd = [binary, "estimate", os.path.join(ROOT, "json-cases", "baseline-60rpm.json"), csv,
           "--from", "top_rpm,top_torque_kNm,hookload_kN", "-o", out]
    if sidecar:
        cmd += ["--sidecar", sidecar]
    if fuse:
        cmd += ["--fuse", "bit_rpm,wob_kN"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return p.stderr.strip()
    with open(os.path.join(out, "estimate.json")) as f:
        e = json.load(f)["errors"]
    if "wob_N_at_downhole_delay" not in e:
        return "no telemetry delay found"
    return (e["bit_rpm_at_downhole_delay"]["rms_percent_of_mean"], e["wob_N_at_downhole_delay"]["bias"] / 1e3,
            e["wob_N_at_downhole_delay"]["rms"] / 1e3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bin", "drillwave"))
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    a = ap.parse_args()
    out = tempfile.mkdtemp(prefix="score-fusion-")
    print("| recording | case | bit-speed RMS % of mean, surface -> fused | WOB bias [kN] | WOB RMS [kN] |")
    print("|---|---|---|---|---|")
    for folder, rec in DELAYED:
        csv = os.path.join(a.shared, "recordings", folder, rec + ".csv")
        if not os.path.exists(csv):
            print(f"skipped {csv}: absent", file=sys.stderr)
            continue
        for sidecar in (csv[:-4] + ".json", None):
            before, after = (errors(a.binary, csv, sidecar, fuse, out) for fuse in (False, True))
            label = f"| {folder}/{rec} | {'sidecar' if sidecar else 'as given'} |"
            if isinstance(before, str) or isinstance(after, str):
                print(f"{label} {before if isinstance(before, str) else after} |||")
                continue
            print(f"{label} {before[0]:.1f} -> {after[0]:.1f} | {before[1]:.1f} -> {after[1]:.1f} | "
                  f"{before[2]:.1f} -> {after[2]:.1f} |")


if __name__ == "__main__":
    main()
