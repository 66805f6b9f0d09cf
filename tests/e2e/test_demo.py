"""The demo of the README's run command (deploy/demo.sh): on a short bundled recording,
the map answers while it runs, alerts open and end as the recording unfolds, the clock
of the status lines moves, and the closing summary is kew-eval's scoring of the very
alerts kewd raised.

Run by ctest with KEW_BUILD_DIR set; by hand:
  KEW_BUILD_DIR=build python3 -m unittest tests/e2e/test_demo.py -v
"""

import json
import os
import re
import subprocess
import tempfile
import threading
import unittest
import urllib.request

from kewd_harness import free_port, wait_until

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
BUILD = os.environ.get("KEW_BUILD_DIR", os.path.join(ROOT, "build"))
RECORDING = os.path.join(ROOT, "tests", "data", "text", "readsb_20minutes.json")
WATCH_LINE = re.compile(r"^(\d\d:\d\d:\d\dZ) (NEW|UPDATE|END) .*\[([0-9a-f]{16})\]$")
ALIVE_LINE = re.compile(r"^(\S+) ALIVE ")


class Demo(unittest.TestCase):
    def test_the_demo_shows_alerts_unfold_and_scores_them(self):
        with tempfile.TemporaryDirectory(prefix="kew-demo-") as workdir:
            http_port = free_port()
            alert_port = free_port()
            while alert_port == http_port:
                alert_port = free_port()
            env = dict(os.environ, KEW_DEMO_RECORDING=RECORDING, KEW_DEMO_SPEED="40", KEW_DEMO_SECONDS="120",
                       KEW_DEMO_ALERT_PORT=str(alert_port), KEW_DEMO_HTTP_PORT=str(http_port),
                       KEW_DEMO_DIR=workdir, KEW_DEMO_SCREENSHOT="0")
            demo = subprocess.Popen(["bash", os.path.join(ROOT, "deploy", "demo.sh"), BUILD], env=env,
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            lines = []
            reader = threading.Thread(target=lambda: lines.extend(line.rstrip("\n") for line in demo.stdout))
            reader.start()
            try:
                url = wait_until(lambda: next((l.split("Live map: ")[1].split()[0] for l in list(lines)
                                               if l.startswith("Live map: ")), None), 30, "the map's URL")
                self.assertEqual(url, f"http://127.0.0.1:{http_port}/")
                # The map answers while the recording plays.
                wait_until(lambda: any(WATCH_LINE.match(l) for l in list(lines)), 60, "the first alert")
                with urllib.request.urlopen(url, timeout=10) as reply:
                    self.assertEqual(reply.status, 200)
                    self.assertIn(b"<html", reply.read().lower())
                self.assertEqual(demo.wait(timeout=180), 0, "\n".join(lines))
            finally:
                if demo.poll() is None:
                    demo.kill()
                reader.join(timeout=10)
            output = "\n".join(lines)
            self.assertNotIn("stopped after", output, "the demo ends with the recording")

            opened, ended = {}, {}
            for line in lines:
                m = WATCH_LINE.match(line)
                if m and m.group(2) == "NEW":
                    opened.setdefault(m.group(3), m.group(1))
                elif m and m.group(2) == "END":
                    ended[m.group(3)] = m.group(1)
            self.assertTrue(any(i in ended and ended[i] != t for i, t in opened.items()),
                            "an alert opens and later ends at another time:\n" + output)
            alive_times = [m.group(1) for m in map(ALIVE_LINE.match, lines) if m]
            self.assertGreaterEqual(len(alive_times), 2, output)
            repeats = [(a, b) for a, b in zip(alive_times, alive_times[1:]) if a == b]
            self.assertEqual(repeats, [], "the status clock moves from one ALIVE to the next")

            # The summary is kew-eval's scoring of the alerts this run raised.
            log = os.path.join(workdir, "demo-alerts.jsonl")
            scored = json.loads(subprocess.run(
                [os.path.join(BUILD, "replay", "kew-eval"), "--json", "--alerts", log, RECORDING],
                check=True, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout)
            run, truth = scored["runs"][0], scored["truth"]
            summary = output[output.index("Summary"):]
            self.assertIn(f"records {truth['records']}, tracks {truth['tracks']}", summary)
            self.assertIn(f"{run['hit']} hits, {run['close_call']} close calls, {run['nuisance']} nuisances, "
                          f"{run['ineligible']} ineligible", summary)
            self.assertIn(f"losses of separation: {run['loss_events']}; {run['detected']} detected, "
                          f"{run['missed']} missed", summary)
            alerts = {json.loads(l)["id"] for l in open(log) if '"class":"ALERT"' in l}
            self.assertIn(f"alerts raised: {len(alerts)} (", summary)
            self.assertEqual(len(alerts), run["alerts"])
            self.assertIn(log, output, "the summary says where the alert log is")


if __name__ == "__main__":
    unittest.main()
