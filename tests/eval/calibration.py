#!/usr/bin/env python3
"""docs/performance.md's calibration table: what real traffic looks like against kew-gen's scenarios.

    python3 tests/eval/calibration.py [--build DIR] [--recordings DIR] [--aircraft N] [--duration S]

For each controlled-airspace recording (and, for contrast, the ADS-B ones) and for each
kew-gen scenario at the benchmarks' density (one aircraft per 126 km², as
kew_peers_bench generates it), one row of: the share of airborne records per flight-level
band, the share climbing or descending (|altitude change| >= 500 ft/min over >= 30 s of a
track: the same rule for every source, whether or not it reports a vertical rate), the
median ground speed, and kew-eval's hindsight figures: flight hours, losses of
separation per 100 flight hours, and kew's alerts per 100 flight hours with the default
configuration. The recordings are decoded with kew-decode (UPC with its [[radar]] table),
the scenarios written by kew-gen; both are scored by kew-eval the same way.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests", "golden"))
from run_golden import BARCELONA_RADAR  # noqa: E402

RECORDINGS = [
    ("jade-cat062-ff (CAT062, 30 min)", "jade-cat062-ff/final_frame_062_30min.ff", False, []),
    ("upc-bcn-cat048 (Barcelona TMA, 60 min)", "upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast", True, []),
    ("opensky switzerland (17 h)", "traffic-opensky/switzerland.json.gz", False, ["--sort"]),
    ("readsb grid 2025-06-01 (GA, 28.6 h)", "adsb_actions-readsb/grid_20250601_36_-122.jsonl.gz", False, []),
]

BANDS = [(-math.inf, 10_000, "< FL100"), (10_000, 20_000, "FL100–195"), (20_000, 30_000, "FL200–295"),
         (30_000, math.inf, ">= FL300")]
LEVEL_CHANGE_FPM = 500.0
RATE_SPAN_S = 30.0
# kew_peers_bench: region radius 2,000 km · sqrt(N / 100,000), one aircraft per 126 km².
BENCH_RADIUS_KM_PER_SQRT_AIRCRAFT = 2000.0 / math.sqrt(100_000)


def traffic_shape(ndjson_lines):
    """Band shares, level-change share and median ground speed of the airborne records."""
    bands = [0] * len(BANDS)
    speeds = []
    anchors = {}  # track -> (t, alt) of the start of the current rate span
    changing = steady = 0
    for line in ndjson_lines:
        if not line.strip() or line.startswith("#"):
            continue
        r = json.loads(line)
        alt = r.get("alt_ft")
        if r.get("gnd") or alt is None:
            continue
        for i, (lo, hi, _) in enumerate(BANDS):
            if lo <= alt < hi:
                bands[i] += 1
        if r.get("gs_kt") is not None:
            speeds.append(r["gs_kt"])
        key = (r.get("src"), r["id"])
        t = r["t"]
        anchor = anchors.get(key)
        if anchor is None or t - anchor[0] > 10 * RATE_SPAN_S:  # a gap starts a new span
            anchors[key] = (t, alt)
        elif t - anchor[0] >= RATE_SPAN_S:
            rate = (alt - anchor[1]) / (t - anchor[0]) * 60.0
            if abs(rate) >= LEVEL_CHANGE_FPM:
                changing += 1
            else:
                steady += 1
            anchors[key] = (t, alt)
    total = sum(bands)
    return {
        "bands": [b / total if total else 0.0 for b in bands],
        "changing": changing / (changing + steady) if changing + steady else 0.0,
        "gs_median_kt": statistics.median(speeds) if speeds else None,
        "records": total,
    }


def decoded_lines(kew_decode, path, radar_config, extra):
    """A recording as kew-decode's NDJSON lines, in time order when `extra` asks --sort
    (recordings grouped by flight: per-track spans need each track in time order)."""
    decode = [kew_decode, "-q"] + (["-c", radar_config] if radar_config else []) + [path]
    lines = subprocess.run(decode, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True,
                           text=True).stdout.splitlines()
    if "--sort" in extra:
        lines.sort(key=lambda l: json.loads(l)["t"] if l.strip() and not l.startswith("#") else -1)
    return lines


def scored(kew_eval, path, extra, config):
    args = [kew_eval, "--json", *extra]
    if config:
        args += ["-c", config]
    out = subprocess.run(args + [path], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True)
    result = json.loads(out.stdout)
    truth, run = result["truth"], result["runs"][0]
    hours = truth["flight_hours"]
    return {"flight_hours": hours,
            "losses_per_100h": 100.0 * truth["loss_events"] / hours if hours else 0.0,
            "alerts_per_100h": 100.0 * run["alerts"] / hours if hours else 0.0}


def row(label, shape, score):
    bands = " | ".join(f"{100 * b:.0f} %" for b in shape["bands"])
    gs = "n/a" if shape["gs_median_kt"] is None else f"{shape['gs_median_kt']:.0f}"
    return (f"| {label} | {bands} | {100 * shape['changing']:.0f} % | {gs} | {score['flight_hours']:.1f} | "
            f"{score['losses_per_100h']:.1f} | {score['alerts_per_100h']:.1f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--recordings", default=os.path.join(os.path.dirname(ROOT), "shared", "data", "recordings"))
    parser.add_argument("--aircraft", type=int, default=2000, help="generated aircraft per scenario")
    parser.add_argument("--duration", type=float, default=600, help="generated seconds per scenario")
    parser.add_argument("--scenarios", default="calibrated,mixed,random")
    parser.add_argument("--area", type=float, default=None,
                        help="km² per generated aircraft (default: the benchmarks' 126)")
    parser.add_argument("--generated-only", action="store_true", help="skip the recordings")
    options = parser.parse_args()
    tool = lambda name: os.path.join(options.build, "replay", name)  # noqa: E731
    print("| traffic | " + " | ".join(label for _, _, label in BANDS) +
          " | climbing or descending | median GS (kt) | flight h | losses / 100 flight h | alerts / 100 flight h |")
    print("|---|" + "---:|" * (len(BANDS) + 5))
    with tempfile.TemporaryDirectory(prefix="kew-calibration-") as workdir:
        radar_config = os.path.join(workdir, "radar.toml")
        with open(radar_config, "w") as f:
            f.write(BARCELONA_RADAR)
        for label, relative, radar, extra in (RECORDINGS if not options.generated_only else []):
            path = os.path.join(options.recordings, relative)
            if not os.path.exists(path):
                print(f"*** {path} is absent: not measured ***", file=sys.stderr)
                continue
            config = radar_config if radar else None
            lines = decoded_lines(tool("kew-decode"), path, config, extra)
            print(row(label, traffic_shape(lines), scored(tool("kew-eval"), path, extra, config)), flush=True)
        radius = BENCH_RADIUS_KM_PER_SQRT_AIRCRAFT * math.sqrt(options.aircraft)
        if options.area:
            radius = math.sqrt(options.area * options.aircraft / math.pi)
        for scenario in options.scenarios.split(","):
            out = os.path.join(workdir, f"{scenario}.ndjson")
            subprocess.run([tool("kew-gen"), "--scenario", scenario, "--aircraft", str(options.aircraft),
                            "--duration", str(options.duration), "--radius", f"{radius:.1f}", "-o", out],
                           check=True, stdout=subprocess.DEVNULL)
            with open(out) as f:
                shape = traffic_shape(f)
            label = f"kew-gen {scenario}, {options.aircraft} aircraft in {radius:.0f} km"
            print(row(label, shape, scored(tool("kew-eval"), out, [], None)), flush=True)


if __name__ == "__main__":
    main()
