#!/usr/bin/env python3
"""The docs/alert-quality.md tables: kew-eval on every shared recording kew reads.

    python3 tests/eval/alert_quality.py [--kew-eval BIN] [--recordings DIR] [--zones]

Prints four markdown tables: each recording with every filter off (filters-off.toml, kew
without its eligibility rules) and with the default configuration; then, summed over the recordings,
what switching off each rule alone gives back; the turn hypothesis (off by default)
switched on, recording by recording; and UPC with the Barcelona terminal-area example
(deploy/examples/barcelona-tma.toml) beside the defaults. UPC is read with its [[radar]]
table, switzerland with --sort, as tests/golden/run_golden.py replays them.

--census prints the missed, late and unwarnable losses of each recording by the stage
that kept kew from alerting earlier (kew-eval --explain), then each missed and late one.

--peers prints kew beside the baselines of kew-eval --baseline (statebased: all pairs,
linear, 5 NM / 1,000 ft / 300 s, no filters; raw: kew with every eligibility rule off),
then kew's warning time on the losses the statebased baseline warned of 60 s ahead.

--zones prints one table instead: each recording with one plane ([projection] zones =
"single", kew's only projection before zones) beside the default worldwide zones.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests", "golden"))
from run_golden import BARCELONA_RADAR  # noqa: E402

CASES = [
    ("jade-cat062-ff (30 min)", "jade-cat062-ff/final_frame_062_30min.ff", False, []),
    ("upc-bcn-cat048 (60 min)", "upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast", True, []),
    ("opensky switzerland (17 h)", "traffic-opensky/switzerland.json.gz", False, ["--sort"]),
    ("readsb 1hr", "adsb_actions-readsb/1hr.json", False, []),
    ("readsb 20minutes", "adsb_actions-readsb/20minutes.json", False, []),
    ("readsb grid 2025-06-01 (28.6 h)", "adsb_actions-readsb/grid_20250601_36_-122.jsonl.gz", False, []),
    ("readsb grid 2025-06-02 (24 h)", "adsb_actions-readsb/grid_20250602_36_-122.jsonl.gz", False, []),
    ("sbs-japan (2 h)", "sbs-japan/adsb202201082242.csv", False, []),
]

# One rule off at a time, on top of the default configuration.
RULES_OFF = [
    ("one aircraft by discrete code (the address rule cannot be switched off)", "[eligibility]\nsame_code_distance_nm = 0\nsame_code_altitude_ft = 0\n"),
    ("level pairs (and with them the adjacent level-off)", "[eligibility]\nlevel_rate_fpm = 0\n"),
    ("adjacent level-off", "[eligibility]\nadjacent_level_off = false\n"),
    ("speed floor 50 kt", "[eligibility]\nmin_ground_speed_kt = 0\n"),
    ("altitude band", "[eligibility]\nmin_altitude_ft = -5000\nmax_altitude_ft = 200000\n"),
    ("lower limit (1,500 ft, and 1,000 ft above the nearest aerodrome)",
     "[eligibility]\nlower_limit_ft = 0\naerodrome_height_ft = 0\n"),
    ("code 7777", "[eligibility]\nexcluded_mode3a = []\n"),
    ("coasting", "[eligibility]\nexclude_coasting = false\n"),
    ("stale position 20 s", "[eligibility]\nmax_position_age_s = 3600\n"),
    ("first record of a track without an address", "[eligibility]\nmin_records = 1\n"),
    ("vertical look-ahead 30 s + tolerance (T_v = T, tolerance 0)", "[probe]\nvertical_lookahead_s = 120\naltimetry_tolerance_ft = 0\n"),
    ("clear = 4 (2 instead)", "[alerts]\nclear = 2\n"),
    ("vertical intent (selected altitude)", "[probe]\nvertical_intent = false\n"),
]

# Off by default; measured switched on.
TURN_ON = "[probe]\nturn_hypothesis = true\n"
TERMINAL_AREA = os.path.join(ROOT, "deploy", "examples", "barcelona-tma.toml")


def evaluate(kew_eval, recording, radar, extra, configs, workdir, files=()):
    """kew-eval --json with one run per text of `configs` (the radar table appended when
    `radar`), then one per path of `files` (used as they are)."""
    args = [kew_eval, "--json", *extra]
    for index, text in enumerate(configs):
        path = os.path.join(workdir, f"c{index}.toml")
        with open(path, "w") as f:
            f.write(text + (BARCELONA_RADAR if radar else ""))
        args += ["-c", path]
    for path in files:
        args += ["-c", path]
    out = subprocess.run(args + [recording], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True)
    return json.loads(out.stdout)


def share(run):
    u = run["undesirable_share"]
    return "n/a" if u == "n/a" else f"{100 * u:.1f} %"


def cell(run):
    return f"{run['alerts']} ({run['hit']} / {run['close_call']} / {run['nuisance']} / {run['ineligible']})"


def warning(run):
    w = run["warning_s"]
    return "n/a" if w == "n/a" else f"{w['p10']:.0f} / {w['p50']:.0f}"


def outcome(run):
    return (f"{cell(run)} | {share(run)} | {run['detected']} / {run['missed']} / {run['unwarnable']} | "
            f"{warning(run)}")


def present_cases(options):
    """CASES whose recording is there, with its path; the others are said on stderr."""
    for label, relative, radar, extra in CASES:
        path = os.path.join(options.recordings, relative)
        if os.path.exists(path):
            yield label, path, radar, extra
        else:
            print(f"*** {path} is absent: not evaluated ***", file=sys.stderr)


def compare_zones(options):
    header = ("alerts (hit / close / nuisance / inelig.) | undesirable | detected / missed / unwarnable | "
              "warning p10 / p50 (s)")
    print(f"| recording | one plane: {header} | zones: {header} |")
    print("|---|---|---:|---|---|---|---:|---|---|")
    with tempfile.TemporaryDirectory(prefix="kew-quality-") as workdir:
        for label, path, radar, extra in present_cases(options):
            single, zones = evaluate(options.kew_eval, path, radar, extra,
                                     ['[projection]\nzones = "single"\n', ""], workdir)["runs"]
            print(f"| {label} | {outcome(single)} | {outcome(zones)} |", flush=True)


def peer_cells(run):
    per_100 = run["alerts_per_100_flight_hours"]
    return (f"{run['alerts']} | {'n/a' if per_100 == 'n/a' else f'{per_100:.0f}'} | {share(run)} | "
            f"{run['detected']} / {run['missed']} / {run['unwarnable']} | {warning(run)}")


def median(values):
    values = sorted(values)
    return values[(len(values) - 1) // 2] if values else None


def peers(options):
    """kew beside the two baselines of kew-eval --baseline, recording by recording; then
    the losses the state-based baseline warned of 60 s ahead or more (predictable from
    straight flight) and kew's warning on them."""
    header = "alerts | per 100 flight h | undesirable | detected / missed / unwarnable | warning p10 / p50 (s)"
    rows, predictable = [], []
    with tempfile.TemporaryDirectory(prefix="kew-quality-") as workdir:
        for label, path, radar, extra in present_cases(options):
            result = evaluate(options.kew_eval, path, radar,
                              extra + ["--list", "--baseline", "statebased", "--baseline", "raw"], [""], workdir)
            kew, statebased, raw = result["runs"]
            rows.append((label, kew, statebased, raw))
            early = [k for k, loss in enumerate(statebased["loss_list"])
                     if loss["warning_s"] is not None and loss["warning_s"] >= 60]
            kew_warnings = [kew["loss_list"][k]["warning_s"] for k in early]
            missed = sum(1 for k in early if kew["loss_list"][k]["outcome"] == "missed")
            warned = [w for w in kew_warnings if w is not None]
            predictable.append((label, len(early), missed, len(warned), median(warned),
                                median([statebased["loss_list"][k]["warning_s"] for k in early])))
    print(f"| recording | kew: {header} | statebased: {header} | raw: {header} |")
    print("|---|" + "---:|---:|---:|---|---|" * 3)
    for label, kew, statebased, raw in rows:
        print(f"| {label} | {peer_cells(kew)} | {peer_cells(statebased)} | {peer_cells(raw)} |")
    print()
    print("| recording | losses statebased warned ≥ 60 s ahead | kew missed of them | kew warned of them | "
          "kew's median warning (s) | statebased's median warning (s) |")
    print("|---|---:|---:|---:|---:|---:|")
    for label, count, missed, warned, kew_median, peer_median in predictable:
        fmt = lambda v: "n/a" if v is None else f"{v:.0f}"
        print(f"| {label} | {count} | {missed} | {warned} | {fmt(kew_median)} | {fmt(peer_median)} |")


STAGES = ["record_refused", "no_track", "awaiting_velocity", "not_candidate", "probe_clear",
          "one_aircraft_address", "one_aircraft_code", "level_pair", "adjacent_level_off", "inhibited", "excluded",
          "confirm_pending", "alerting"]


def census(options):
    """kew-eval --explain on every recording: its missed, late and unwarnable losses by
    the stage that kept kew from alerting earlier (missed / late / unwarnable per cell),
    then every missed and late loss with its reason."""
    runs = []
    with tempfile.TemporaryDirectory(prefix="kew-quality-") as workdir:
        for label, path, radar, extra in present_cases(options):
            runs.append((label, evaluate(options.kew_eval, path, radar, extra + ["--explain"], [""], workdir)["runs"][0]))
    used = [s for s in STAGES if any(s in run["census"] for _, run in runs)]
    print("| recording | missed / late / unwarnable | " + " | ".join(used) + " |")
    print("|---|---|" + "---|" * len(used))
    for label, run in runs:
        counts = [0, 0, 0]
        for c in run["census"].values():
            counts = [counts[0] + c["missed"], counts[1] + c["late"], counts[2] + c["unwarnable"]]
        cells = []
        for stage in used:
            c = run["census"].get(stage)
            cells.append(f"{c['missed']} / {c['late']} / {c['unwarnable']}" if c else "")
        print(f"| {label} | {counts[0]} / {counts[1]} / {counts[2]} | " + " | ".join(cells) + " |")
    print()
    for label, run in runs:
        for e in run["explain"]:
            if e["outcome"] == "unwarnable":
                continue
            warning = "" if e["warning_s"] is None else f", warning {e['warning_s']:.0f} s"
            print(f"- {label}, {e['start']} {e['a']['id']} x {e['b']['id']} ({e['outcome']}{warning}): "
                  f"**{e['stage']}**: {e['reason']}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--kew-eval", default=os.path.join(ROOT, "build", "replay", "kew-eval"))
    parser.add_argument("--recordings", default=os.path.join(os.path.dirname(ROOT), "shared", "data", "recordings"))
    parser.add_argument("--zones", action="store_true", help="one plane beside the worldwide zones")
    parser.add_argument("--peers", action="store_true",
                        help="kew beside the statebased and raw baselines (kew-eval --baseline)")
    parser.add_argument("--census", action="store_true",
                        help="missed, late and unwarnable losses by stage (kew-eval --explain)")
    options = parser.parse_args()
    if options.census:
        census(options)
        return
    if options.peers:
        peers(options)
        return
    if options.zones:
        compare_zones(options)
        return
    with open(os.path.join(HERE, "filters-off.toml")) as f:
        before = f.read()
    totals = {name: [0, 0, 0] for name, _ in RULES_OFF}  # alerts, undesirable, missed
    default_total = [0, 0, 0]
    turn_rows, terminal_rows = [], []
    print("| recording | flight h | loss events | alerts before (hit / close / nuisance / inelig.) | undesirable before | "
          "alerts now | undesirable now | per 100 flight h now | detected / missed / unwarnable now | warning p10 / p50 (s) |")
    print("|---|---:|---:|---|---:|---|---:|---:|---|---|")
    with tempfile.TemporaryDirectory(prefix="kew-quality-") as workdir:
        for label, path, radar, extra in present_cases(options):
            result = evaluate(options.kew_eval, path, radar, extra,
                              [before, ""] + [text for _, text in RULES_OFF] + [TURN_ON], workdir,
                              [TERMINAL_AREA] if radar else [])
            old, now, *off = result["runs"]
            turn_rows.append((label, now, off[len(RULES_OFF)]))
            if radar:
                terminal_rows.append((label, now, off[len(RULES_OFF) + 1]))
                # The truth at 3 NM: what the terminal area's own minimum calls a loss.
                at_3nm = evaluate(options.kew_eval, path, radar, extra + ["--h-nm", "3"], [""], workdir,
                                  [TERMINAL_AREA])["runs"]
                terminal_rows.append((label + ", truth at 3 NM", *at_3nm))
            off = off[:len(RULES_OFF)]
            print(f"| {label} | {result['truth']['flight_hours']:.1f} | {result['truth']['loss_events']} | {cell(old)} | "
                  f"{share(old)} | {cell(now)} | {share(now)} | {now['alerts_per_100_flight_hours']:.0f} | "
                  f"{now['detected']} / {now['missed']} / {now['unwarnable']} | {warning(now)} |")
            for total, run in [(default_total, now)] + list(zip(totals.values(), off)):
                total[0] += run["alerts"]
                total[1] += run["nuisance"] + run["ineligible"]
                total[2] += run["missed"]
    print()
    print("| rule switched off alone | alerts (all recordings) | undesirable | missed losses |")
    print("|---|---:|---:|---:|")
    print(f"| none (default) | {default_total[0]} | {default_total[1]} | {default_total[2]} |")
    for name, (alerts, undesirable, missed) in totals.items():
        print(f"| {name} | {alerts} ({alerts - default_total[0]:+d}) | {undesirable} ({undesirable - default_total[1]:+d}) | "
              f"{missed} |")
    header = ("alerts (hit / close / nuisance / inelig.) | undesirable | detected / missed / unwarnable | "
              "warning p10 / p50 (s)")
    for title, rows in (("turn hypothesis", turn_rows), ("terminal-area example", terminal_rows)):
        print()
        print(f"| recording | default: {header} | {title}: {header} |")
        print("|---|---|---:|---|---|---|---:|---|---|")
        for label, default, other in rows:
            print(f"| {label} | {outcome(default)} | {outcome(other)} |")


if __name__ == "__main__":
    main()
