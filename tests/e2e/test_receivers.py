"""kewd reading what ADS-B receivers write (design §5.7): a receiver's aircraft.json,
replaced once a second by its writer (readsb renames a new file over the old one),
read each time it is, each position once however many versions show it.

Run by ctest; by hand: KEWD=... KEW_REPLAY=... python3 -m unittest test_receivers -v
"""

import json
import os
import subprocess
import sys
import time

from kewd_harness import KEW_REPLAY, SERVICE, E2eCase, wait_until

TEXT_DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "text")
HISTORY = os.path.join(TEXT_DATA, "aircraft_json_history.json")
KEW_EVAL = os.environ.get("KEW_EVAL", "kew-eval")

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


class ReceiverHistory(E2eCase):
    def test_a_history_directory_scores_as_the_positions_it_shows(self):
        """A receiver's history: twenty minutes of real readsb positions (tests/data/text,
        19 aircraft) written as 1,200 history_N.json snapshots, one a second, as readsb's
        history is kept. kew-replay reads the directory with no refusal, one record per
        position (the same second's second position of an aircraft is the one readsb
        shows); kew-eval scores it as it scores the positions themselves (readsb lines):
        the same losses, each detected or missed alike."""
        lines = os.path.join(TEXT_DATA, "readsb_20minutes.json")
        history = self.path("history")
        subprocess.run([sys.executable, os.path.join(TEXT_DATA, "make_aircraft_json_history.py"), lines, history],
                       check=True, capture_output=True)
        self.assertEqual(len(os.listdir(history)), 1200)
        replayed = subprocess.run([KEW_REPLAY, "--stats-json", self.path("replay.json"), history],
                                  capture_output=True, text=True, check=True)
        with open(self.path("replay.json"), encoding="utf-8") as f:
            stats = json.load(f)
        seconds = {}
        for line in open(lines, encoding="utf-8"):
            record = json.loads(line)
            if "lat" in record:
                seconds.setdefault(record["hex"], set()).add(record["now"])
        self.assertEqual(stats["rejected_total"], 0, replayed.stderr)
        self.assertEqual(stats["records"], sum(len(s) for s in seconds.values()), "one record per position")

        def score(recording):
            out = subprocess.run([KEW_EVAL, "--json", recording], capture_output=True, text=True, check=True)
            column = json.loads(out.stdout)["runs"][0]
            return {k: column[k] for k in ("loss_events", "detected", "missed", "unwarnable")}

        from_history, from_lines = score(history), score(lines)
        self.assertGreater(from_lines["loss_events"], 0, "the recording has losses to score")
        self.assertEqual(from_history, from_lines)
