#!/usr/bin/env python3
"""Prints one readable line per alert event of kewd's alert stream.

    python3 print_alerts.py --host 127.0.0.1 --port 4747 --http-port 8747

An alert line: data time (UTC), state, severity, the pair (callsign, track id, flight
level), time to loss of separation, the closest approach (NM, ft, in s), the current
separation, the hypothesis and the alert id. The active alerts of the snapshot kewd sends
on every (re)connection are printed as events too; other lines start with '#'.
"""

import argparse
import math
import os
import sys
from datetime import datetime, timezone

# The examples run from a checkout, next to the module, without installing it.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from kew_client import SEVERITIES, Ack, Alert, Alerts, Error, KewClient, Start  # noqa: E402

METRES_PER_NM = 1852.0


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="127.0.0.1", help="kewd's host (default 127.0.0.1)")
    parser.add_argument("--port", type=int, default=4747, help="the alert stream's port (default 4747)")
    parser.add_argument("--http-port", type=int, default=8747,
                        help="kewd's HTTP port, for acknowledgements (default 8747)")
    parser.add_argument("--min-severity", choices=SEVERITIES, default="caution")
    parser.add_argument("--count", type=int, default=0, help="stop after this many alert events (0: never)")
    parser.add_argument("--timeout", type=float, default=0, help="stop after this many seconds (0: never)")
    parser.add_argument("--no-reconnect", action="store_true", help="stop when the connection is lost")
    return parser.parse_args()


def clock(t):
    if t is None or math.isnan(t):
        return "--:--:--.---"
    return datetime.fromtimestamp(t, timezone.utc).strftime("%H:%M:%S.%f")[:-3]


def aircraft(party):
    name = f"{party.cs} ({party.id})" if party.cs else party.id
    level = "FL---" if math.isnan(party.alt_ft) else f"FL{round(party.alt_ft / 100):03d}"
    return f"{name} {level}"


def describe(alert):
    state = f"end ({alert.reason})" if alert.state == "end" else alert.state
    if alert.kind == "apw":  # an aircraft and a volume
        text = (f"{clock(alert.t)}  {state:<19} {alert.severity:<8} {aircraft(alert.a)} -> {alert.volume}"
                f" ({alert.volume_kind})  entry in {alert.t_los_s:.0f} s")
    else:
        text = (f"{clock(alert.t)}  {state:<19} {alert.severity:<8} {aircraft(alert.a)} - {aircraft(alert.b)}"
                f"  LoS in {alert.t_los_s:.0f} s"
                f"  CPA {alert.cpa_h_m / METRES_PER_NM:.2f} NM / {alert.cpa_v_ft:.0f} ft in {alert.t_cpa_s:.0f} s"
                f"  now {alert.sep_h_m / METRES_PER_NM:.2f} NM / {alert.sep_v_ft:.0f} ft")
    if alert.state != "end":
        text += f"  by {alert.hypothesis}"
    if alert.region:
        text += f"  region {alert.region}"
    if alert.ack:
        text += "  ack"
    return text + f"  [{alert.id}]"


def main():
    args = arguments()
    client = KewClient(args.host, args.port, min_severity=args.min_severity, http_port=args.http_port,
                       reconnect=not args.no_reconnect)
    if args.timeout > 0:
        client.close_after(args.timeout)
    printed = 0
    try:
        with client:
            for obj in client:
                alerts = []
                if isinstance(obj, Alert):
                    alerts = [obj]
                elif isinstance(obj, Alerts):
                    print(f"# {len(obj.alerts)} active alerts", flush=True)
                    alerts = obj.alerts
                elif isinstance(obj, Start):
                    print(f"# kewd {obj.release} run {obj.run} started at {clock(obj.t)}", flush=True)
                elif isinstance(obj, Ack):
                    print(f"# {len(obj.ids)} acknowledged by {obj.by} {obj.client}", flush=True)
                elif isinstance(obj, Error):
                    print(f"# kewd: {obj.message}", flush=True)
                for alert in alerts:
                    print(describe(alert), flush=True)
                    printed += 1
                    if printed == args.count:
                        return 0
    except KeyboardInterrupt:
        return 130
    except OSError as e:
        print(f"print_alerts: {args.host}:{args.port}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
