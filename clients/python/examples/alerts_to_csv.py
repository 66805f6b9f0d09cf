#!/usr/bin/env python3
"""Writes one CSV row per alert event of kewd's alert stream, every field flattened.

    python3 alerts_to_csv.py --host 127.0.0.1 --port 4747 --http-port 8747 -o alerts.csv

Columns: from_snapshot (true for the active alerts of the snapshot kewd sends on every
(re)connection, which a reader may have seen before), then every member of the ALERT
object in kew_client.Alert's order, the aircraft's as a_id, a_cs, ..., b_tn. Units are
the JSON's (seconds, metres, feet, feet per minute, knots, degrees); a member the server
left out is empty, a figure it wrote as null is nan.
"""

import argparse
import csv
import dataclasses
import os
import sys

# The examples run from a checkout, next to the module, without installing it.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from kew_client import SEVERITIES, Alert, Alerts, KewClient, Party  # noqa: E402


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="127.0.0.1", help="kewd's host (default 127.0.0.1)")
    parser.add_argument("--port", type=int, default=4747, help="the alert stream's port (default 4747)")
    parser.add_argument("--http-port", type=int, default=8747,
                        help="kewd's HTTP port, for acknowledgements (default 8747)")
    parser.add_argument("--min-severity", choices=SEVERITIES, default="caution")
    parser.add_argument("-o", "--output", help="the CSV file (default: standard output)")
    parser.add_argument("--count", type=int, default=0, help="stop after this many alert events (0: never)")
    parser.add_argument("--timeout", type=float, default=0, help="stop after this many seconds (0: never)")
    parser.add_argument("--no-reconnect", action="store_true", help="stop when the connection is lost")
    return parser.parse_args()


# Derived from the dataclasses, so that a member added to Alert or Party gets its column.
PARTY_FIELDS = [f.name for f in dataclasses.fields(Party)]
COLUMNS = ["from_snapshot"] + [
    name for f in dataclasses.fields(Alert)
    for name in ([f"{f.name}_{p}" for p in PARTY_FIELDS] if f.name in ("a", "b") else [f.name])]


def cell(value):
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)  # repr: every digit kewd sent


def row(alert, from_snapshot):
    out = {"from_snapshot": cell(from_snapshot)}
    for f in dataclasses.fields(Alert):
        value = getattr(alert, f.name)
        if f.name in ("a", "b"):  # an area warning has no b: its columns stay empty
            for p in PARTY_FIELDS:
                out[f"{f.name}_{p}"] = cell(getattr(value, p)) if isinstance(value, Party) else ""
        else:
            out[f.name] = cell(value)
    return out


def main():
    args = arguments()
    client = KewClient(args.host, args.port, min_severity=args.min_severity, http_port=args.http_port,
                       reconnect=not args.no_reconnect)
    if args.timeout > 0:
        client.close_after(args.timeout)
    output = open(args.output, "w", newline="") if args.output else sys.stdout
    written = 0
    try:
        writer = csv.DictWriter(output, fieldnames=COLUMNS)
        writer.writeheader()
        output.flush()
        with client:
            for obj in client:
                if isinstance(obj, Alert):
                    events = [(obj, False)]
                elif isinstance(obj, Alerts):
                    events = [(alert, True) for alert in obj.alerts]
                else:
                    continue
                for alert, from_snapshot in events:
                    writer.writerow(row(alert, from_snapshot))
                    written += 1
                    if written == args.count:
                        return 0
                output.flush()  # rows are visible while the stream runs (tail -f)
    except KeyboardInterrupt:
        return 130
    except OSError as e:
        print(f"alerts_to_csv: {args.host}:{args.port}: {e}", file=sys.stderr)
        return 1
    finally:
        if output is not sys.stdout:
            output.close()
        else:
            output.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
