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

A second table measures the same pairs of reports for kinetic detection (design §2.7),
whose points are the look-ahead positions q = p + v·T: how far a report moves its q-point
from where the previous report put it, |Δp_residual + T·(v_k − v_{k−1})|, and the change
of velocity |v_k − v_{k−1}| itself, with the share of updates whose velocity change
exceeds τ_q / T (such an update would need the full query) for τ_q = 300 m and 1 km.
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
LOOKAHEAD_S = 120.0
Q_TOLERANCES_M = (300, 1000)


def residuals(lines):
    """Per consecutive pair of reports: position residual (m), Δt (s), velocity change
    (m/s) and look-ahead point residual (m)."""
    last = {}
    out, gaps, dvs, q_out = [], [], [], []
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
        ve0, vn0 = speed * math.sin(track), speed * math.cos(track)
        speed1, track1 = r["gs_kt"] * KNOT_MPS, math.radians(r["trk_deg"])
        dve, dvn = speed1 * math.sin(track1) - ve0, speed1 * math.cos(track1) - vn0
        re, rn = east - ve0 * dt, north - vn0 * dt
        out.append(math.hypot(re, rn))
        gaps.append(dt)
        dvs.append(math.hypot(dve, dvn))
        q_out.append(math.hypot(re + LOOKAHEAD_S * dve, rn + LOOKAHEAD_S * dvn))
    return out, gaps, dvs, q_out


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
    q_rows = []
    for label, relative, radar, extra in RECORDINGS:
        path = os.path.join(options.recordings, relative)
        if not os.path.exists(path):
            print(f"*** {path} is absent: not measured ***", file=sys.stderr)
            continue
        lines = decoded_lines(os.path.join(options.build, "replay", "kew-decode"), path,
                              radar_config if radar else None, extra)
        values, gaps, dvs, q_values = residuals(lines)
        if not values:
            continue
        values.sort()
        dvs.sort()
        q_values.sort()
        q_shares = " | ".join(f"{100 * sum(v > t / LOOKAHEAD_S for v in dvs) / len(dvs):.0f} %"
                              for t in Q_TOLERANCES_M)
        q_rows.append(f"| {label} | {percentile(dvs, 0.5):.1f} / {percentile(dvs, 0.9):.1f} / "
                      f"{percentile(dvs, 0.99):.1f} | {percentile(q_values, 0.5):.0f} / "
                      f"{percentile(q_values, 0.9):.0f} / {percentile(q_values, 0.99):.0f} | {q_shares} |")
        shares = " | ".join(f"{100 * sum(v > t for v in values) / len(values):.0f} %" for t in THRESHOLDS_M)
        print(f"| {label} | {len(values)} | {statistics.median(gaps):.1f} | {percentile(values, 0.5):.0f} / "
              f"{percentile(values, 0.9):.0f} / {percentile(values, 0.99):.0f} | {shares} |", flush=True)
    print(f"\n| recording | Δv p50 / p90 / p99 (m/s) | q-point residual at T = {LOOKAHEAD_S:.0f} s, "
          "p50 / p90 / p99 (m) | " + " | ".join(f"Δv > {t} m / T" for t in Q_TOLERANCES_M) + " |")
    print("|---|---|---|" + "---:|" * len(Q_TOLERANCES_M))
    for row in q_rows:
        print(row)


if __name__ == "__main__":
    main()
