"""kewd when the disk under its alert log and record file fails under heavy traffic
(docs/reliability.md "Restarts and the alert log"): the files' queues fill and drop their
oldest lines, and ingestion, health and shutdown go on as if the disk were well.
Run by ctest with test_kewd; by hand as test_kewd.py says.

The disk fails through RLIMIT_FSIZE, which any user may lower: kewd's writes beyond it
fail with EFBIG (SIGXFSZ ignored), as on a full disk, without mounting anything.
"""
import json
import math
import resource
import signal
import subprocess
import threading
import time
import unittest
import urllib.request

from kewd_harness import KEW_REPLAY, E2eCase, count_lines, generate
from test_reliability import Connections, feed_with

# Bytes kewd may write to any one file; then every write fails.
FILE_LIMIT = 256 * 1024
# Queues large enough that a copy of one per line (what a queue must never cost) would
# take the I/O thread tens of minutes over this traffic.
ALERT_QUEUE_BYTES = 32 << 20
RECORD_QUEUE_BYTES = 4 << 20


def files_fail_beyond(limit):
    """A preexec_fn: writes past `limit` bytes of a file fail (EFBIG), as on a full disk."""
    def limit_writes():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return limit_writes


class FailingDisk(E2eCase):
    timed_stats = Connections.timed_stats
    timed_status = Connections.timed_status

    def test_full_queues_never_slow_ingestion_health_or_shutdown(self):
        recording = self.path("tma.ndjson")
        generate(recording, "tma", aircraft=1000, duration=300, seed=11)
        records = count_lines(recording)
        kewd = self.start(feed_with(
            f'alert_log = "{self.path("alerts.jsonl")}"\nrecord_file = "{self.path("records.ndjson")}"\n'
            f"alert_log_queue_bytes = {ALERT_QUEUE_BYTES}\nrecord_file_queue_bytes = {RECORD_QUEUE_BYTES}\n"),
            preexec_fn=files_fail_beyond(FILE_LIMIT))

        # Health is asked throughout the feed, each answer timed.
        answers = []  # (seconds for ?STATS, seconds for GET /api/status, its status line, STATS)
        feeding = threading.Event()
        feeding.set()

        def ask_health():
            while feeding.is_set():
                try:
                    stats_s, stats = self.timed_stats(kewd.alert_port)
                    status_s, status = self.timed_status(kewd.http_port)
                except OSError as e:  # a time-out (5 s) is an answer too late
                    answers.append((math.inf, math.inf, str(e), {}))
                    continue
                answers.append((stats_s, status_s, status, stats))
                time.sleep(0.2)
        asker = threading.Thread(target=ask_health, daemon=True)
        asker.start()
        feeder = subprocess.Popen([KEW_REPLAY, "--to", f"127.0.0.1:{kewd.input_port('feed')}", "--max-speed",
                                   recording], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.addCleanup(feeder.kill)
        try:
            # A generous bound: a few seconds of work for a kewd that a full queue never
            # slows, tens of minutes at the cost of a queue's copy per line.
            kewd.wait_records(records, timeout_s=120)
        finally:
            feeding.clear()
            asker.join(timeout=10)
        feeder.wait(timeout=30)
        stats = kewd.stats()

        with self.subTest("both queues overflowed, bounded, and the overflow is counted"):
            self.assertGreater(stats["alert_log_dropped"], 0, stats)
            self.assertGreater(stats["record_file_dropped"], 0, stats)
            self.assertLessEqual(stats["alert_log_queued_bytes"], ALERT_QUEUE_BYTES)
            self.assertLessEqual(stats["record_file_queued_bytes"], RECORD_QUEUE_BYTES)
            self.assertGreater(stats["alert_log_errors"], 0)
            self.assertIn("the oldest queued lines are dropped", kewd.log())
        with self.subTest("health answered within 1 s while the queues were full"):
            overflowing = [a for a in answers if a[3].get("record_file_dropped", 0) > 0]
            self.assertTrue(overflowing, "no health answer during the overflow")
            self.assertEqual({a[2] for a in answers}, {"HTTP/1.1 200 OK"})
            # Health answers at once through one door or the other (?STATS, /api/status).
            slow = [a[:2] for a in answers if min(a[0], a[1]) >= 1.0]
            self.assertEqual(slow, [], "seconds to answer ?STATS and GET /api/status")
        with self.subTest("health says degraded: alert_log_failing"):
            with urllib.request.urlopen(f"http://127.0.0.1:{kewd.http_port}/api/status", timeout=10) as reply:
                status = json.load(reply)
            self.assertEqual(status["health"], "alert_log_failing")
            self.assertTrue(status["degraded"])

        # SIGTERM in the middle of the same traffic again (its records are refused as too
        # late, and recorded all the same).
        again = subprocess.Popen([KEW_REPLAY, "--to", f"127.0.0.1:{kewd.input_port('feed')}", "--max-speed",
                                  recording], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.addCleanup(again.kill)
        kewd.wait_records(records + records // 4, timeout_s=60)
        signalled = time.monotonic()
        self.assertEqual(kewd.terminate(timeout_s=30), 0)
        self.assertLess(time.monotonic() - signalled, 5.0, "SIGTERM handled at once")
        self.assertIn("kewd stopped", kewd.log())


if __name__ == "__main__":
    unittest.main()
