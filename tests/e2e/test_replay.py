"""End-to-end tests of `kewd --replay FILE` (design §5.6): a recording
replayed by kewd with a built-in configuration, on loopback, writing nothing.

Run by ctest with the e2e tests; by hand as test_kewd.py says.
"""

import json
import os
import shutil
import stat
import subprocess
import time
import urllib.request
import unittest

from kewd_harness import (KEWD, KEW_GEN, KEW_REPLAY, E2eCase, Kewd, Subscriber, active_at_end, count_lines, free_port,
                          offline_alerts, wait_until)

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")

# A production-like file: its inputs, CAT004, Modbus and alert log must all be left out
# of a replay; its shared tables and [service] limits apply.
PRODUCTION = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 60
subscriber_queue = 100000
alert_log = "{workdir}/production-alerts.jsonl"

[alerts]
confirm = 2

[cat004]
enabled = true
destination = "127.0.0.1:0"

[modbus]
enabled = true
listen = "127.0.0.1:0"

[[input]]
name = "radar"
transport = "tcp-server"
address = "127.0.0.1:0"
"""


def kew_gen(path, scenario, aircraft, duration, seed, *extra):
    subprocess.run([KEW_GEN, "--scenario", scenario, "--aircraft", str(aircraft), "--duration", str(duration),
                    "--seed", str(seed), "-o", path, *extra], check=True)


class Replay(E2eCase):
    def tearDown(self):
        # The read-only directory of one test: writable again so that it can be removed.
        for root, dirs, _ in os.walk(self.workdir):
            for d in dirs:
                os.chmod(os.path.join(root, d), 0o755)
        super().tearDown()

    def start(self, config, *args, cwd=None):
        daemon = Kewd(config, self.workdir, args, cwd=cwd)
        self.daemons.append(daemon)
        return daemon

    def test_as_fast_as_possible_gives_kew_replays_alerts_under_the_files_shared_tables(self):
        """Same ids, order and figures as kew-replay with the same file, a recording dated
        in 2100 included (no wall-clock ceiling in a replay); the file's inputs, CAT004,
        Modbus and alert log are left out; the last state is served after the end."""
        recording = self.path("mixed.ndjson")
        kew_gen(recording, "mixed", 300, 120, 3, "--start", "4102444800")
        kewd = self.start(PRODUCTION.format(workdir=self.workdir), "--replay", recording, "--max-speed",
                          "--alert-log", self.path("replay-alerts.jsonl"))
        kewd.wait_log(f"replay of {recording} ended", 60)
        expected = offline_alerts(kewd.config_path, recording)
        self.assertGreater(len(expected), 10, "the scenario must have conflicts")

        with open(self.path("replay-alerts.jsonl")) as f:
            start, _, logged = f.read().partition("\n")
        self.assertTrue(start.startswith('{"class":"START",'), start)
        self.assertEqual(logged.splitlines(keepends=True), expected, "kewd --replay gives kew-replay's alerts")

        stats = kewd.stats()
        self.assertEqual(stats["accepted"], count_lines(recording), "nothing refused: " + json.dumps(stats["rejected"]))
        self.assertEqual([i["name"] for i in stats["inputs"]], ["replay"], "the file's [[input]] tables are replaced")
        self.assertNotIn("cat004", stats)
        self.assertNotIn("modbus", stats)
        self.assertFalse(os.path.exists(self.path("production-alerts.jsonl")), "the file's alert log is not written")
        self.assertFalse(os.path.exists(self.path("kewd.state")), "no state file")

        # Still serving after the end: a late subscriber gets the last state.
        self.assertTrue(kewd.running())
        late = Subscriber(kewd.alert_port)
        wait_until(lambda: late.objects("ALERTS"), 10, "the snapshot")
        self.assertEqual({a["id"]: a for a in late.objects("ALERTS")[0]["alerts"]}, active_at_end(expected))
        self.assertEqual(kewd.terminate(), 0)

    def test_paced_at_ten_times_and_serving_the_last_state(self):
        """A 60 s recording at --speed 10 takes about 6 s; the stream has alerts while it
        plays; after the end the tracks stay (the data clock stops) until SIGTERM."""
        recording = self.path("tma.ndjson")
        kew_gen(recording, "tma", 150, 60, 3)
        offline = subprocess.run([KEW_REPLAY, recording], check=True, stdout=subprocess.PIPE,
                                 stderr=subprocess.DEVNULL, text=True).stdout.splitlines()
        self.assertGreater(len(offline), 0, "the scenario must have conflicts")
        port, http_port = free_port(), free_port()
        began = time.monotonic()
        kewd = self.start(None, "--replay", recording, "--speed", "10", "--alert-listen", f"127.0.0.1:{port}",
                          "--http-listen", f"127.0.0.1:{http_port}")
        self.assertEqual(kewd.alert_port, port)
        reader = Subscriber(kewd.alert_port)
        kewd.wait_log(f"replay of {recording} ended", 40)
        elapsed = time.monotonic() - began
        self.assertGreater(elapsed, 3.0, "paced, not as fast as possible")
        self.assertLess(elapsed, 20.0)
        wait_until(lambda: reader.alert_lines(), 5, "alerts on the stream")

        before = kewd.stats()
        self.assertGreater(before["tracks"], 0)
        time.sleep(3.0)  # three ticks, 30 s of data at speed 10 were the clock still running
        after = kewd.stats()
        self.assertEqual((after["tracks"], after["alerts_active"], after["data_time_last"]),
                         (before["tracks"], before["alerts_active"], before["data_time_last"]),
                         "the last state stays on show")
        self.assertIn("serving the last state until SIGINT or SIGTERM", kewd.log())
        # The map and its API are how a replay is watched.
        http = f"http://127.0.0.1:{http_port}"
        with urllib.request.urlopen(http + "/api/tracks", timeout=10) as reply:
            self.assertEqual(len(json.loads(reply.read())["tracks"]), after["tracks"])
        with urllib.request.urlopen(http + "/", timeout=10) as reply:
            self.assertIn(b"<html", reply.read())
        self.assertEqual(kewd.terminate(), 0)

    def test_refuses_listen_any_and_remote_addresses(self):
        recording = os.path.join(DATA, "text", "canonical_sample.ndjson")
        for args, why in ((["--listen-any"], "--listen-any"),
                          (["--alert-listen", f"0.0.0.0:{free_port()}"], "loopback"),
                          (["--http-listen", f"0.0.0.0:{free_port()}"], "loopback")):
            result = subprocess.run([KEWD, "--replay", recording, *args], stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True, timeout=20)
            self.assertEqual(result.returncode, 64, result.stderr)
            self.assertIn(why, result.stderr)
        # The replay options need --replay.
        result = subprocess.run([KEWD, "--speed", "4", "--check-config"], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, timeout=20)
        self.assertEqual(result.returncode, 64, result.stderr)
        self.assertIn("--replay", result.stdout + result.stderr)

    def test_runs_in_a_read_only_directory_and_writes_nothing(self):
        """An unprivileged engineer's replay: a relative path, a read-only working
        directory, --exit-at-end; no file appears anywhere under it."""
        directory = self.path("incident")
        os.mkdir(directory)
        shutil.copy(os.path.join(DATA, "text", "canonical_sample.ndjson"), os.path.join(directory, "recording.ndjson"))
        os.chmod(directory, stat.S_IRUSR | stat.S_IXUSR | stat.S_IRGRP | stat.S_IXGRP | stat.S_IROTH | stat.S_IXOTH)
        before = sorted(os.listdir(directory))
        kewd = os.path.abspath(KEWD) if os.sep in KEWD else KEWD  # run from another directory
        result = subprocess.run([kewd, "--replay", "recording.ndjson", "--max-speed", "--exit-at-end",
                                 "--alert-listen", f"127.0.0.1:{free_port()}",
                                 "--http-listen", f"127.0.0.1:{free_port()}"],
                                cwd=directory, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("replay of " + os.path.join(directory, "recording.ndjson") + " ended", result.stderr)
        self.assertIn("exiting (--exit-at-end)", result.stderr)
        self.assertNotIn("state file", result.stderr)
        self.assertNotIn("alert log", result.stderr)
        self.assertEqual(sorted(os.listdir(directory)), before)


if __name__ == "__main__":
    unittest.main()
