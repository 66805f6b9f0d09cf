#!/usr/bin/env python3
"""The demo's closing summary (deploy/demo.sh): what kewd saw and raised, from its alert
log, and how those alerts score in hindsight, from `kew-eval --json --alerts` on the same
recording.

  demo_summary.py ALERT_LOG EVAL_JSON
"""

import json
import sys

SEVERITIES = ("caution", "warning", "loss")


def main(alert_log, eval_json):
    highest = {}  # alert id → its most severe event's severity
    with open(alert_log) as f:
        for line in f:
            event = json.loads(line)
            if event.get("class") != "ALERT":
                continue
            rank = SEVERITIES.index(event["severity"])
            highest[event["id"]] = max(highest.get(event["id"], rank), rank)
    with open(eval_json) as f:
        scored = json.load(f)
    truth = scored["truth"]
    run = scored["runs"][0]
    by_severity = ", ".join(f"{sum(1 for r in highest.values() if r == i)} {name}"
                            for i, name in reversed(list(enumerate(SEVERITIES))))
    p50 = run["warning_s"]["p50"] if run.get("warning_s") else None
    print()
    print("Summary")
    print(f"  records {truth['records']}, tracks {truth['tracks']} ({truth['aircraft']} aircraft, "
          f"{truth['flight_hours']:.1f} flight hours)")
    print(f"  alerts raised: {len(highest)} ({by_severity}, by the most severe each reached)")
    print(f"  scored in hindsight against what the aircraft did (kew-eval): {run['hit']} hits, "
          f"{run['close_call']} close calls, {run['nuisance']} nuisances, {run['ineligible']} ineligible")
    print(f"  losses of separation: {run['loss_events']}; {run['detected']} detected, {run['missed']} missed, "
          f"{run['unwarnable']} unwarnable (began as a track appeared); median warning "
          + (f"{p50:.0f} s" if p50 is not None else "n/a"))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(64)
    main(sys.argv[1], sys.argv[2])
