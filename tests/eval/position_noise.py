#!/usr/bin/env python3
"""How far a report lands from where its track's previous report said it would be.

    python3 tests/eval/position_noise.py [--build DIR] [--recordings DIR]

The kinetic engine keeps a point where the model predicts it while a new report lies
within the tolerance τ of that prediction (design §2.3); further away, the point is
removed and reinserted. So the reinsertion rate follows from the distribution of
|p_k − (p_{k−1} + v_{k−1}·Δt)| over consecutive airborne reports of one track with a
velocity and Δt ≤ 12 s: measurement noise plus whatever the aircraft did meanwhile.
Distances are on a local east/north plane at the earlier report (exact to centimetres
over a few km). Prints one markdown row per recording: reports, Δt median, residual
p50 / p90 / p99 in metres, and the share of residuals above 50, 150 and 300 m.
"""

import argparse
import json
import math
import os
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from calibration import RECORDINGS, BARCELONA_RADAR, decoded_lines  # noqa: E402

EARTH_RADIUS_M = 6_371_008.8
KNOT_MPS = 1852.0 / 3600.0
MAX_GAP_S = 12.0
THRESHOLDS_M = (50, 150, 300)


def residuals(lines):
    last = {}
    out, gaps = [], []
    for line in lines:
        if not line.strip() or line.startswith("#"):
            continue
        r = json.loads(line)
        if r.get("gnd") or r.get("gs_kt") is None or r.get("trk_deg") is None:
            continue
        key = (r.get("src"), r["id"])
        previous = last.get(key)
        last[key] = r
        if previous is None:
            continue
        dt = r["t"] - previous["t"]
        if not 0 < dt <= MAX_GAP_S:
            continue
        lat0 = math.radians(previous["lat"])
        north = math.radians(r["lat"] - previous["lat"]) * EARTH_RADIUS_M
        east = math.radians((r["lon"] - previous["lon"] + 180) % 360 - 180) * EARTH_RADIUS_M * math.cos(lat0)
        speed = previous["gs_kt"] * KNOT_MPS
        track = math.radians(previous["trk_deg"])
        out.append(math.hypot(east - speed * math.sin(track) * dt, north - speed * math.cos(track) * dt))
        gaps.append(dt)
    return out, gaps


def percentile(sorted_values, p):
    return sorted_values[min(len(sorted_values) - 1, int(p * (len(sorted_values) - 1)))]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--recordings", default=os.path.join(os.path.dirname(ROOT), "shared", "data", "recordings"))
    options = parser.parse_args()
    radar_file = tempfile.NamedTemporaryFile("w", suffix=".toml", prefix="kew-radar-")
    radar_file.write(BARCELONA_RADAR)
    radar_file.flush()
    radar_config = radar_file.name
    print("| recording | pairs of reports | Δt median (s) | residual p50 / p90 / p99 (m) | "
          + " | ".join(f"> {t} m" for t in THRESHOLDS_M) + " |")
    print("|---|---:|---:|---|" + "---:|" * len(THRESHOLDS_M))
    for label, relative, radar, extra in RECORDINGS:
        path = os.path.join(options.recordings, relative)
        if not os.path.exists(path):
            print(f"*** {path} is absent: not measured ***", file=sys.stderr)
            continue
        lines = decoded_lines(os.path.join(options.build, "replay", "kew-decode"), path,
                              radar_config if radar else None, extra)
        values, gaps = residuals(lines)
        if not values:
            continue
        values.sort()
        shares = " | ".join(f"{100 * sum(v > t for v in values) / len(values):.0f} %" for t in THRESHOLDS_M)
        print(f"| {label} | {len(values)} | {statistics.median(gaps):.1f} | {percentile(values, 0.5):.0f} / "
              f"{percentile(values, 0.9):.0f} / {percentile(values, 0.99):.0f} | {shares} |", flush=True)


if __name__ == "__main__":
    main()
