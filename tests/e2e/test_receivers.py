"""kewd reading what ADS-B receivers write (design §5.7): a receiver's aircraft.json,
replaced once a second by its writer (readsb renames a new file over the old one),
read each time it is, each position once however many versions show it.

Run by ctest; by hand: KEWD=... KEW_REPLAY=... python3 -m unittest test_receivers -v
"""

import json
import os
import subprocess
import time

from kewd_harness import KEW_REPLAY, wait_until
from test_kewd import SERVICE, E2eCase

HISTORY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "text",
                       "aircraft_json_history.json")

WATCHED = """
[[input]]
name = "receiver"
format = "{format}"
transport = "watched-file"
address = "{path}"
"""


class WatchedFile(E2eCase):
    def test_a_replaced_aircraft_json_is_read_each_time_and_each_position_once(self):
        """120 versions of aircraft.json (real readsb positions, tests/data/text), each
        written to a temporary file and renamed over the watched one as readsb does: kewd
        reads every version and takes each position once, as kew-replay reads the same
        snapshots from a directory."""
        snapshots = [line for line in open(HISTORY, encoding="utf-8") if line.strip()]
        history = self.path("history")
        os.mkdir(history)
        for i, snapshot in enumerate(snapshots):
            with open(os.path.join(history, f"history_{i}.json"), "w", encoding="utf-8") as f:
                f.write(snapshot)
        replayed = subprocess.run([KEW_REPLAY, "--stats-json", self.path("replay.json"), history],
                                  capture_output=True, text=True, check=True)
        with open(self.path("replay.json"), encoding="utf-8") as f:
            expected = json.load(f)["records"]
        self.assertGreater(expected, 90, replayed.stderr)

        run = self.path("run")
        os.mkdir(run)
        watched = os.path.join(run, "aircraft.json")
        for fmt in ("aircraft-json", "auto"):
            with self.subTest(format=fmt):
                if os.path.exists(watched):
                    os.remove(watched)
                kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir) +
                                  WATCHED.format(format=fmt, path=watched))
                kewd.wait_log(f"input receiver: {fmt} watched-file {watched}")
                written = 0
                for snapshot in snapshots:
                    temporary = os.path.join(run, "aircraft.json.tmp")
                    with open(temporary, "w", encoding="utf-8") as f:
                        f.write(snapshot)
                    os.replace(temporary, watched)
                    written += len(snapshot.encode())
                    # Each version read before the next replaces it (readsb writes once a
                    # second; a version never read would lose the positions it alone shows).
                    wait_until(lambda: kewd.stats()["inputs"][0]["bytes"] >= written, 10, "the version read")
                stats = kewd.stats()
                self.assertEqual(stats["records"], expected, "each position once, as kew-replay reads the snapshots")
                self.assertEqual(stats["inputs"][0]["rejected_total"] if "rejected_total" in stats["inputs"][0]
                                 else sum(stats["inputs"][0]["rejected"].values()), 0)
                self.assertEqual(stats["rejected_total"], 0, stats["rejected"])
                kewd.terminate()
