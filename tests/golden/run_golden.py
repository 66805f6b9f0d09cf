#!/usr/bin/env python3
"""Golden replay tests in the style of gpsd's regression tests.

Every case in CASES is replayed offline with kew-replay; its ALERT lines and the stable
part of its statistics must equal the files checked in under tests/golden/expected/
byte for byte, and a second run must give the same bytes (determinism, design §2.5).

After an intended change of behaviour, rebuild the goldens with ONE flag and review the
diff before committing:

    python3 tests/golden/run_golden.py --regen        (or: cmake --build build --target golden-regen)

Binaries come from KEW_REPLAY and KEW_GEN (ctest sets them), else from build/.
--shared additionally replays every real recording of ../shared/data/recordings that a
decoder supports, with --audit: exit 0, statistics printed, no unrepaired violation.

Every recording (bundled or shared, not the generated ones, which are NDJSON already) is
also converted by kew-decode (KEW_DECODE) and the conversion replayed: its alerts must be
byte-identical to the original's, and kew-eval (KEW_EVAL) must score both alike.
"""

import argparse
import difflib
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DATA = os.path.join(ROOT, "tests", "data")
EXPECTED = os.path.join(HERE, "expected")
SHARED = os.path.join(os.path.dirname(ROOT), "shared", "data", "recordings")
KEW_REPLAY = os.environ.get("KEW_REPLAY", os.path.join(ROOT, "build", "replay", "kew-replay"))
KEW_GEN = os.environ.get("KEW_GEN", os.path.join(ROOT, "build", "replay", "kew-gen"))
KEW_DECODE = os.environ.get("KEW_DECODE", os.path.join(ROOT, "build", "replay", "kew-decode"))
KEW_EVAL = os.environ.get("KEW_EVAL", os.path.join(ROOT, "build", "replay", "kew-eval"))

# name → recording: a bundled file (relative to tests/data), or "gen:" and kew-gen flags.
CASES = {
    "jade-cat062-ff": "asterix/jade/final_frame_062_first3min.ff",
    "croatia-cat062-pcap": "asterix/croatiacontrol/asterix.pcap",
    "croatia-cat048-pcap": "asterix/croatiacontrol/cat_034_048.pcap",
    "sbs-japan": "text/sbs_japan_13501-16500.csv",
    "opensky-switzerland": "text/opensky_switzerland_first2000.json.gz",
    "readsb-20min": "text/readsb_20minutes.json",
    "canonical-sample": "text/canonical_sample.ndjson",
    "gen-random": "gen:--scenario random --aircraft 80 --duration 120 --seed 21",
    "gen-airways": "gen:--scenario airways --aircraft 80 --duration 120 --seed 22",
    "gen-stacks": "gen:--scenario stacks --aircraft 80 --duration 120 --seed 23",
    "gen-tma": "gen:--scenario tma --aircraft 40 --duration 120 --seed 24",
    "gen-mixed": "gen:--scenario mixed --aircraft 80 --duration 120 --seed 25",
}

# Each case also runs in these configurations, with goldens of their own: one plane
# (today's figures for a site that keeps a single zone; design §4.9).
VARIANTS = {
    "single": os.path.join(HERE, "single-zone.toml"),
}

# Statistics that describe the input and the alerts, not the engine's internals (which
# change with every optimisation and are checked by the property tests instead).
STABLE_STATS = ("records", "rejected", "tracks_max", "updates", "alerts_new", "audit_violations_unrepaired")

# Real recordings a decoder supports, with the configuration or flag they need.
with open(os.path.join(HERE, "upc-bcn-radar.toml"), encoding="utf-8") as radar_file:
    BARCELONA_RADAR = "\n" + radar_file.read()
SHARED_CASES = [
    ("jade-cat062-ff/final_frame_062_30min.ff", ""),
    ("upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast", BARCELONA_RADAR),
    ("croatiacontrol-samples/asterix.pcap", ""),
    ("croatiacontrol-samples/cat_034_048.pcap", ""),
    ("croatiacontrol-samples/cat_062_065.pcap", ""),
    ("croatiacontrol-samples/cat21_re.ast", ""),
    ("jasterix-vectors/asterix4py_cat062.ast", ""),
    ("sbs-japan/adsb202201082242.csv", ""),
    ("traffic-opensky/switzerland.json.gz", "--sort"),  # grouped by flight, not by time
    ("adsb_actions-readsb/1hr.json", ""),
    ("adsb_actions-readsb/20minutes.json", ""),
    ("adsb_actions-readsb/grid_20250601_36_-122.jsonl.gz", ""),
    ("adsb_actions-readsb/grid_20250602_36_-122.jsonl.gz", ""),
]


def recording_for(spec, workdir):
    if not spec.startswith("gen:"):
        return os.path.join(DATA, spec)
    path = os.path.join(workdir, "generated.ndjson")
    subprocess.run([KEW_GEN, *spec[4:].split(), "-o", path], check=True)
    return path


def replay(recording, workdir, *extra):
    """(alert bytes, statistics object) of one offline run."""
    stats_path = os.path.join(workdir, "stats.json")
    result = subprocess.run([KEW_REPLAY, "--stats-json", stats_path, *extra, recording],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if result.returncode != 0:
        raise RuntimeError(f"kew-replay {recording} exited {result.returncode}:\n{result.stderr.decode()}")
    with open(stats_path) as f:
        return result.stdout, json.load(f), result.stderr.decode()


def decoded_alerts_differ(name, recording, workdir, alerts, extra):
    """kew-decode RECORDING, replay the NDJSON with the same flags: a failure message when
    its alerts are not the original's byte for byte, else None."""
    decoded = os.path.join(workdir, "decoded.ndjson")
    config = [extra[i + 1] for i, flag in enumerate(extra) if flag == "--config"]
    with open(decoded, "wb") as out:
        result = subprocess.run([KEW_DECODE, "--quiet", *(["--config", config[0]] if config else []), recording],
                                stdout=out, stderr=subprocess.PIPE)
    if result.returncode != 0 or b"kew-decode: " not in result.stderr:
        return f"kew-decode exited {result.returncode}: {result.stderr.decode()[-400:]}"
    again, _, _ = replay(decoded, workdir, *extra)
    if again != alerts:
        show_difference(f"{name} via kew-decode", alerts, again)
        return "alerts replayed from kew-decode's NDJSON differ from the original's"
    scores = [evaluation(path, [flag for flag in extra if flag != "--audit"]) for path in (recording, decoded)]
    if scores[0] != scores[1]:
        return f"kew-eval scores kew-decode's NDJSON otherwise than the original: {scores[0]} != {scores[1]}"
    return None


def evaluation(recording, extra):
    """kew-eval --json of one recording without what names the input: the file names, and
    the decoder's refusals (kew-decode's output holds only what was decoded)."""
    result = subprocess.run([KEW_EVAL, "--json", *extra, recording], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, check=True)
    scores = json.loads(result.stdout)
    scores["truth"].pop("files", None)
    return scores


def stable(stats):
    return json.dumps({k: stats[k] for k in STABLE_STATS}, indent=1, sort_keys=True) + "\n"


def show_difference(name, expected, actual):
    diff = difflib.unified_diff(expected.decode().splitlines(), actual.decode().splitlines(),
                                f"expected/{name}", f"actual/{name}", lineterm="", n=1)
    lines = list(diff)
    print("\n".join(lines[:40] + ([f"... {len(lines) - 40} more lines"] if len(lines) > 40 else [])))


def compare_or_write(regen, name, outputs):
    """Writes each output as its golden (regen), or counts those that differ from it."""
    failures = 0
    for filename, actual in outputs.items():
        path = os.path.join(EXPECTED, filename)
        if regen:
            with open(path, "wb") as f:
                f.write(actual)
            continue
        if not os.path.exists(path):
            print(f"FAIL {name}: {path} is missing (run with --regen)")
            failures += 1
            continue
        with open(path, "rb") as f:
            expected = f.read()
        if expected != actual:
            print(f"FAIL {name}: {filename} differs from the golden")
            show_difference(filename, expected, actual)
            failures += 1
    return failures


def run_goldens(regen):
    failures = 0
    os.makedirs(EXPECTED, exist_ok=True)
    for name, spec in CASES.items():
        with tempfile.TemporaryDirectory(prefix="kew-golden-") as workdir:
            recording = recording_for(spec, workdir)
            alerts, stats, _ = replay(recording, workdir)
            again, _, _ = replay(recording, workdir)
            outputs = {f"{name}.alerts.jsonl": alerts, f"{name}.stats.json": stable(stats).encode()}
            if again != alerts:
                print(f"FAIL {name}: two runs of the same input differ")
                failures += 1
                continue
            failures += compare_or_write(regen, name, outputs)
            for variant, config in VARIANTS.items():
                v_alerts, v_stats, _ = replay(recording, workdir, "-c", config)
                failures += compare_or_write(regen, name, {
                    f"{name}.{variant}.alerts.jsonl": v_alerts,
                    f"{name}.{variant}.stats.json": stable(v_stats).encode()})
            if not spec.startswith("gen:"):
                problem = decoded_alerts_differ(name, recording, workdir, alerts, [])
                if problem:
                    print(f"FAIL {name}: {problem}")
                    failures += 1
                    continue
            lines = alerts.count(b"\n")
            print(f"{'REGEN' if regen else 'ok  '} {name}: {stats['records']} records, {lines} alert lines"
                  f"{'' if spec.startswith('gen:') else ', the same through kew-decode'}")
    return failures


def run_shared():
    if not os.path.isdir(SHARED):
        print(f"*** {SHARED} is absent: the real recordings were NOT replayed ***")
        return 0
    failures = 0
    for relative, config_text in SHARED_CASES:
        path = os.path.join(SHARED, relative)
        if not os.path.exists(path):
            print(f"FAIL {relative}: missing from the shared recordings")
            failures += 1
            continue
        with tempfile.TemporaryDirectory(prefix="kew-shared-") as workdir:
            extra = ["--audit"]
            if config_text.startswith("--"):
                extra.append(config_text)
            elif config_text:
                config = os.path.join(workdir, "kew.toml")
                with open(config, "w") as f:
                    f.write(config_text)
                extra += ["--config", config]
            try:
                alerts, stats, summary = replay(path, workdir, *extra)
            except RuntimeError as e:
                print(f"FAIL {relative}: {e}")
                failures += 1
                continue
            problems = []
            if stats["audit_violations_unrepaired"] != 0:
                problems.append(f"{stats['audit_violations_unrepaired']} unrepaired audit violations")
            if stats["records"] == 0 and not stats["rejected"]:
                problems.append("no record decoded and no rejection counted")
            if "kew-replay: " not in summary:
                problems.append("no statistics printed")
            problem = decoded_alerts_differ(relative, path, workdir, alerts, extra)
            if problem:
                problems.append(problem)
            if problems:
                print(f"FAIL {relative}: " + "; ".join(problems))
                failures += 1
            else:
                print(f"ok   {relative}: {stats['records']} records, {stats['tracks_max']} tracks at most, "
                      f"{stats['alerts_new']} alerts, audit clean, the same through kew-decode; "
                      f"rejected {stats['rejected']}")
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--regen", action="store_true", help="rewrite the goldens from the current build")
    parser.add_argument("--shared", action="store_true", help="also replay the real shared recordings with --audit")
    args = parser.parse_args()
    failures = run_goldens(args.regen)
    if args.shared:
        failures += run_shared()
    if failures:
        print(f"{failures} failures")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
