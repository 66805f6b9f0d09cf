#!/usr/bin/env python3
"""The largest generated scenario: kew-gen's 100,000 aircraft for 600 s through
kew-replay with audits, every aircraft inside the coverage.

Usage: run_long_100k.py KEW_GEN KEW_REPLAY STATS_JSON

Fails unless kew-replay exits 0, refuses no record, tracks at least 100,000 aircraft at
once, and its audits find nothing (repaired or not).
"""
import json
import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent


def main() -> int:
    kew_gen, kew_replay, stats_path = sys.argv[1:4]
    generator = subprocess.Popen(
        [kew_gen, "--scenario", "mixed", "--aircraft", "100000", "--duration", "600", "--radius", "2000", "--seed", "1"],
        stdout=subprocess.PIPE)
    replay = subprocess.run(
        [kew_replay, "--format", "ndjson", "--audit", "--config", str(HERE / "continental.toml"),
         "--alerts", "/dev/null", "--stats-json", stats_path, "/dev/stdin"],
        stdin=generator.stdout, check=False)
    generator.stdout.close()
    if generator.wait() != 0 or replay.returncode != 0:
        print(f"kew-gen exited {generator.returncode}, kew-replay {replay.returncode}")
        return 1
    stats = json.loads(pathlib.Path(stats_path).read_text())
    problems = []
    if stats["rejected_total"] != 0:
        problems.append(f"records refused: {stats['rejected']}")
    if stats["tracks_max"] < 100000:
        problems.append(f"only {stats['tracks_max']} tracks at once")
    if stats["audits"] == 0:
        problems.append("no audit ran")
    if stats["audit_violations_found"] != 0:
        problems.append(f"{stats['audit_violations_found']} audit violations "
                        f"({stats['audit_violations_unrepaired']} unrepaired)")
    for key in ("records", "accepted", "tracks_max", "audits", "audit_violations_found", "reinsertions", "repairs",
                "wall_s"):
        print(f"{key}: {stats[key]}")
    for problem in problems:
        print("FAIL:", problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
