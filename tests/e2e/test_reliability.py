"""kewd when a record, a client, a restart or the disk misbehaves (issue 18, README
"Reliability"). Run by ctest with test_kewd; by hand as test_kewd.py says.
"""
import errno
import json
import math
import os
import socket
import subprocess
import sys
import time
import unittest

from kewd_harness import Subscriber, wait_until
from test_kewd import E2eCase, MODBUS_CLIENT, pymodbus_python

KNOT = 1852.0 / 3600.0

# The live tick and ALIVE at their defaults (1 s): health is judged at each ALIVE.
FEED = """
[service]
alert_listen = "127.0.0.1:0"

[[input]]
name = "feed"
format = "ndjson"
transport = "tcp-server"
address = "127.0.0.1:0"
"""


def head_on(aircraft, t, t0):
    """Two aircraft head-on along 50° N at FL350, 20 NM apart at t0 and closing at 900 kt."""
    sign = 1.0 if aircraft == "A" else -1.0
    east_m = -sign * 10 * 1852.0 + sign * 450 * KNOT * (t - t0)
    lon = 8.0 + east_m / (111320.0 * math.cos(math.radians(50.0)))
    return {"t": round(t, 3), "id": aircraft, "src": "e2e", "lat": 50.0, "lon": round(lon, 7), "alt_ft": 35000,
            "gs_kt": 450, "trk_deg": 90.0 if sign > 0 else 270.0, "vr_fpm": 0}


def lines(records):
    return "".join(json.dumps(r, separators=(",", ":")) + "\n" for r in records).encode()


class FutureTime(E2eCase):
    """A record dated in the future neither silences kewd nor goes unreported."""

    def test_future_records_are_refused_and_a_later_conflict_still_alerts(self):
        kewd = self.start(FEED)
        watcher = Subscriber(kewd.alert_port)
        t0 = time.time() - 600  # data in the recent past, as a feed delayed by a few minutes
        before = [head_on(a, t0 + dt, t0) for dt in range(0, 20, 4) for a in "AB"]
        misdated = []
        for future in (4102444800.0, t0 + 3600, t0 + 60):  # 2100; an hour ahead; a minute ahead
            record = head_on("C", t0 + 16, t0)
            record["t"] = future
            misdated.append(record)
        after = [head_on(a, t0 + dt, t0) for dt in range(20, 80, 4) for a in "AB"]
        with socket.create_connection(("127.0.0.1", kewd.input_port("feed"))) as feed:
            feed.sendall(lines(before + misdated + after))
        kewd.wait_records(len(before) + len(misdated) + len(after))
        new = wait_until(lambda: [a for a in watcher.objects("ALERT") if a["state"] == "new"], 10,
                         "the conflict after the misdated records to alert")
        self.assertEqual({new[0]["a"]["id"], new[0]["b"]["id"]}, {"A", "B"})
        stats = kewd.stats()
        self.assertEqual(stats["rejected"].get("future_time"), 3, stats["rejected"])
        self.assertNotIn("too_late", stats["rejected"])
        self.assertEqual(stats["accepted"], len(before) + len(after))


class Health(E2eCase):
    """kewd says it is degraded, and why, when the records it receives are refused."""

    def test_refused_records_make_alive_and_modbus_say_degraded(self):
        python = pymodbus_python()
        if python is None:
            self.skipTest("python3-pymodbus is not installed: the Modbus map was NOT checked")
        kewd = self.start(FEED + '\n[modbus]\nenabled = true\nlisten = "127.0.0.1:0"\n')
        modbus_port = int(kewd.wait_log("Modbus TCP alarm map on port").split("on port ")[1].split()[0])
        watcher = Subscriber(kewd.alert_port)
        feed = socket.create_connection(("127.0.0.1", kewd.input_port("feed")))
        self.addCleanup(feed.close)

        def read_map():
            result = subprocess.run([python, MODBUS_CLIENT, "--port", str(modbus_port), "read-map"],
                                    stdout=subprocess.PIPE, text=True, timeout=20)
            decoded = json.loads(result.stdout)
            self.assertTrue(decoded["ok"], decoded)
            return decoded["map"]

        def last_alive():
            alive = watcher.objects("ALIVE")
            return alive[-1] if alive else None

        # Records of now: healthy.
        start = time.time()
        for i in range(12):
            feed.sendall(lines([head_on("A", time.time(), start)]))
            time.sleep(0.25)
        wait_until(lambda: (last_alive() or {}).get("health") == "healthy", 10, "ALIVE to say healthy")
        self.assertEqual(read_map()["discrete_inputs"]["feed_healthy"], 1)

        # Then only records dated 2100: every one refused, the feed is not healthy any more.
        misdated = head_on("A", time.time(), start)
        misdated["t"] = 4102444800.0
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and (last_alive() or {}).get("health") != "records_refused":
            feed.sendall(lines([misdated] * 5))
            time.sleep(0.2)
        alive = last_alive()
        self.assertEqual(alive["health"], "records_refused", alive)
        self.assertTrue(alive["degraded"])
        first = read_map()
        self.assertEqual(first["discrete_inputs"]["degraded"], 1)
        self.assertEqual(first["discrete_inputs"]["feed_healthy"], 0)
        # Register 4 counts the seconds since the last *accepted* record, not since bytes came.
        feed.sendall(lines([misdated] * 5))
        time.sleep(2.5)
        feed.sendall(lines([misdated] * 5))
        second = read_map()
        self.assertGreaterEqual(second["registers"]["seconds_since_last_record"],
                                first["registers"]["seconds_since_last_record"] + 2)
        self.assertGreater(kewd.stats()["rejected"]["future_time"], 10)


def pair_records(k, t, t0):
    """Pair k of head-on aircraft ("Ak", "Bk") along latitude 50° + k/2, as head_on."""
    out = []
    for aircraft in "AB":
        record = head_on(aircraft, t, t0)
        record["id"] = f"{aircraft}{k}"
        record["lat"] = 50.0 + 0.5 * k
        out.append(record)
    return out


def read_log(path):
    """The alert log's objects, failing on any line that is not a whole JSON object."""
    with open(path, "rb") as f:
        data = f.read()
    assert data.endswith(b"\n"), "the alert log ends mid-line: %r" % data[-200:]
    objects = []
    for number, line in enumerate(data.decode().splitlines(), 1):
        try:
            objects.append(json.loads(line))
        except ValueError as e:
            raise AssertionError(f"alert log line {number} is torn or joined: {line[:300]!r}") from e
    return objects


class Restarts(E2eCase):
    """A restart neither leaves alerts open in the alert log nor reuses seq or numbers;
    a full disk neither tears a line nor loses an event (issue 18 items 4 and 5)."""

    CONFIG = FEED.replace('alert_listen = "127.0.0.1:0"\n', 'alert_listen = "127.0.0.1:0"\nalert_log = "{log}"\n')

    def setUp(self):
        super().setUp()
        self.mounts = []

    def tearDown(self):
        for d in self.daemons:
            d.kill()
        for disk in self.mounts:  # before the temporary directory goes
            subprocess.run(["umount", "-l", disk], check=False)
        super().tearDown()

    def feed_pairs(self, kewd, pairs, t0, times):
        records = [r for dt in times for k in pairs for r in pair_records(k, t0 + dt, t0)]
        with socket.create_connection(("127.0.0.1", kewd.input_port("feed"))) as feed:
            feed.sendall(lines(records))
        kewd.wait_records(len(records))

    def new_ids(self, log, pairs):
        """Waits until every pair has an alert open in the log; their ids."""
        def opened():
            if not os.path.exists(log):
                return None
            alerts = [o for o in read_log(log) if o["class"] == "ALERT" and o["state"] == "new"]
            mine = {(a["a"]["id"], a["b"]["id"]): a["id"] for a in alerts}
            return mine if all((f"A{k}", f"B{k}") in mine for k in pairs) else None
        return wait_until(opened, 30, "an alert of every pair in the log")

    def check_restart(self, stop):
        log = self.path("alerts.jsonl")
        config = self.CONFIG.format(log=log)
        first = self.start(config)
        t0 = time.time() - 600
        self.feed_pairs(first, range(3), t0, range(0, 20, 4))
        open_at_stop = set(self.new_ids(log, range(3)).values())
        stop(first)

        second = self.start(config)
        watcher = Subscriber(second.alert_port)
        # The same pairs, still in conflict, and a new one.
        self.feed_pairs(second, range(4), t0, range(24, 44, 4))
        wait_until(lambda: len([o for o in read_log(log) if o["class"] == "ALERT" and o["state"] == "new"]) >= 7,
                   30, "the second run's alerts in the log")
        second.terminate()

        objects = read_log(log)
        # Each guarantee in its own subTest: every one that fails is reported.
        with self.subTest("every alert open at the stop ends with reason restart"):
            restarted = [o["id"] for o in objects if o["class"] == "ALERT" and o.get("reason") == "restart"]
            self.assertEqual(sorted(restarted), sorted(open_at_stop))
        with self.subTest("no alert of the first run dangles"):
            closed = {o["id"] for o in objects if o["class"] == "ALERT" and o["state"] == "end"}
            self.assertEqual(open_at_stop - closed, set())
        with self.subTest("seq strictly increases over the whole file"):
            seqs = [o["seq"] for o in objects if o["class"] == "ALERT"]
            self.assertEqual(seqs, sorted(set(seqs)), "ALERT seq values repeat or go back")
        with self.subTest("no alert number is given twice"):
            numbers = [o["number"] for o in objects if o["class"] == "ALERT" and o["state"] == "new"]
            self.assertEqual(len(numbers), len(set(numbers)), f"alert numbers reused: {numbers}")
        starts = [i for i, o in enumerate(objects) if o["class"] == "START"]
        self.assertEqual(len(starts), 2, "one START per run")
        self.assertNotEqual(objects[starts[0]]["run"], objects[starts[1]]["run"])
        self.assertRegex(objects[starts[1]]["run"], "^[0-9a-f]{32}$")
        self.assertEqual([o["run"] for o in watcher.objects("START")], [objects[starts[1]]["run"]],
                         "a subscriber is told the run it watches")
        first_run, second_run = objects[:starts[1]], objects[starts[1] + 1:]
        self.assertEqual(objects[starts[1]]["seq"], max(o["seq"] for o in first_run if o["class"] == "ALERT"))
        # The ends come right after the second START, before the second run's first alert.
        ended = []
        for o in second_run:
            if o["class"] != "ALERT":
                continue
            if o["state"] != "end" or o.get("reason") != "restart":
                break
            ended.append(o["id"])
        self.assertEqual(sorted(ended), sorted(open_at_stop))
        # Every New before the second START has an End; the same pairs open new alerts.
        opened = {o["id"] for o in first_run if o["class"] == "ALERT" and o["state"] == "new"}
        closed = {o["id"] for o in objects if o["class"] == "ALERT" and o["state"] == "end"}
        self.assertEqual(opened - closed, set())
        reopened = {o["id"] for o in second_run if o["class"] == "ALERT" and o["state"] == "new"}
        self.assertEqual(reopened & open_at_stop, set())

    def test_restart_after_sigkill_ends_open_alerts_and_continues_numbering(self):
        self.check_restart(lambda kewd: kewd.kill())

    def test_restart_after_sigterm_ends_open_alerts_and_continues_numbering(self):
        self.check_restart(lambda kewd: self.assertEqual(kewd.terminate(), 0))

    def test_full_disk_tears_no_line_says_degraded_and_loses_no_event(self):
        disk = self.path("disk")
        os.mkdir(disk)
        mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "kew-e2e", disk],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if mounted.returncode != 0:
            print("\n*** SKIPPED: cannot mount a tmpfs (%s): the full-disk test did NOT run ***" %
                  mounted.stdout.strip(), file=sys.stderr)
            self.skipTest("cannot mount a tmpfs: " + mounted.stdout.strip())
        self.mounts.append(disk)
        log = os.path.join(disk, "alerts.jsonl")
        kewd = self.start(self.CONFIG.format(log=log))
        watcher = Subscriber(kewd.alert_port)
        wait_until(lambda: watcher.objects("ALIVE"), 20, "the subscriber to watch")
        t0 = time.time() - 600
        # Alerts before the disk fills: the log's last page is partly used, as on a disk
        # that fills while kewd runs, so a later write can be cut short mid-line.
        self.feed_pairs(kewd, range(3), t0, range(0, 20, 4))
        self.new_ids(log, range(3))

        # Fill the file system to its last byte.
        filler = os.path.join(disk, "filler")
        with open(filler, "wb", buffering=0) as f:
            for size in (65536, 4096, 1):
                try:
                    while True:
                        f.write(b"x" * size)
                except OSError as e:
                    self.assertEqual(e.errno, errno.ENOSPC)

        def last_alive():
            alive = watcher.objects("ALIVE")
            return alive[-1] if alive else {}

        pairs = range(3, 15)
        self.feed_pairs(kewd, pairs, t0, range(0, 20, 4))
        wait_until(lambda: len([a for a in watcher.objects("ALERT") if a["state"] == "new"]) == 15, 30,
                   "an alert for every pair")
        # Each guarantee in its own subTest: every one that fails is reported.
        with self.subTest("no torn line while the disk is full"):
            logged = [o for o in read_log(log) if o["class"] == "ALERT"]
            self.assertLess(len(logged), len(watcher.alert_lines()), "the disk was full: events must be waiting")
        with self.subTest("ALIVE says degraded: alert_log_failing"):
            alive = wait_until(lambda: last_alive().get("health") == "alert_log_failing" and last_alive(), 20,
                               "ALIVE to say the alert log is failing")
            self.assertTrue(alive["degraded"])
            self.assertGreater(kewd.stats()["alert_log_queued_bytes"], 0)
            self.assertIn("cannot write to " + log, kewd.log())

        os.remove(filler)

        def logged_lines():
            with open(log) as f:
                return [line for line in f if line.startswith('{"class":"ALERT",')]
        with self.subTest("every event reaches the log once space returns"):
            # The queued events reach the log (the retry timer or the next event), complete.
            try:
                wait_until(lambda: logged_lines() == watcher.alert_lines(), 20, "the queued events in the log")
            except AssertionError:
                pass  # the comparison below says what differs
            self.assertEqual(logged_lines(), watcher.alert_lines(),
                             "the log holds every event the subscriber saw, once, in order")
            read_log(log)
        wait_until(lambda: last_alive().get("health") not in (None, "alert_log_failing"), 20,
                   "ALIVE to stop saying the alert log is failing")
        self.assertIn("alert_log_failing", [a["health"] for a in watcher.objects("ALIVE")])


if __name__ == "__main__":
    unittest.main()
