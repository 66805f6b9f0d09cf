"""kewd when a record, a client, a restart or the disk misbehaves (docs/reliability.md).
Run by ctest with test_kewd; by hand as test_kewd.py says.
"""
import errno
import json
import math
import os
import resource
import socket
import subprocess
import sys
import threading
import time
import unittest
import urllib.request
import zlib

from kewd_harness import (MODBUS_CLIENT, E2eCase, Subscriber, count_lines, generate, offline_alerts, pymodbus_python,
                          replay_to, wait_until)

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


def address_of(name):
    """A 24-bit address for a synthetic aircraft: aircraft reports with addresses open an
    alert at the second look (a track without one waits for its second record first,
    design §4.5)."""
    return f"{zlib.crc32(name.encode()) & 0xFFFFFF:06X}"


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

    def test_targets_on_the_ground_do_not_make_kewd_degraded(self):
        # A receiver beside an airport: most records are aircraft on the ground, left out
        # by configuration. That is not a fault.
        kewd = self.start(FEED)
        watcher = Subscriber(kewd.alert_port)
        feed = socket.create_connection(("127.0.0.1", kewd.input_port("feed")))
        self.addCleanup(feed.close)
        start = time.time()
        for i in range(16):
            taxiing = [dict(head_on("A", time.time(), start), id=f"G{k}", gnd=True, gs_kt=10) for k in range(6)]
            feed.sendall(lines([head_on("A", time.time(), start)] + taxiing))
            time.sleep(0.25)
        wait_until(lambda: len(watcher.objects("ALIVE")) >= 3, 10, "three ALIVE objects")
        self.assertGreater(kewd.stats()["rejected"]["on_ground"], 50)
        self.assertEqual(watcher.objects("ALIVE")[-1]["health"], "healthy")

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

    def test_datagrams_the_kernel_drops_are_counted_and_make_kewd_degraded(self):
        # The I/O thread held in a batch by the test hook stands for a kewd slower than its
        # feed: the socket's receive buffer fills and the kernel drops the rest.
        stall = self.path("stall")
        kewd = self.start(UDP_FEED, env={"KEWD_TEST_STALL_FILE": stall})
        watcher = Subscriber(kewd.alert_port)
        target = ("127.0.0.1", kewd.input_port("feed"))
        sender = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.addCleanup(sender.close)
        start = time.time()

        def feed_until(predicate, timeout_s, what):
            """Sends a record of now every 0.25 s until `predicate` holds."""
            deadline = time.monotonic() + timeout_s
            while not predicate():
                self.assertLess(time.monotonic(), deadline, f"timed out after {timeout_s} s waiting for {what}")
                sender.sendto(lines([head_on("A", time.time(), start)]), target)
                time.sleep(0.25)

        def health():
            alive = watcher.objects("ALIVE")
            return alive[-1]["health"] if alive else None

        def dropped():
            return kewd.stats()["inputs"][0].get("datagrams_dropped", 0)

        feed_until(lambda: health() == "healthy", 15, "ALIVE to say healthy")
        self.assertEqual(dropped(), 0)
        open(stall, "w").close()
        sender.sendto(lines([head_on("A", time.time(), start)]), target)
        kewd.wait_log("test hook: the pipeline is stalled")
        # 20,000 datagrams of 1.4 kB (comment lines, skipped by the decoder): several times
        # what a receive buffer of the kernel's largest default holds.
        padding = b"# " + b"x" * 1400 + b"\n"
        for _ in range(20000):
            sender.sendto(padding, target)
        os.unlink(stall)
        kewd.wait_log("test hook: the pipeline runs again")
        # The kernel tells its count with the first datagram it queues after the drops.
        feed_until(lambda: dropped() > 0, 20, "?STATS to count the datagrams the kernel dropped")
        feed_until(lambda: health() == "input_dropping", 10, "ALIVE to say input_dropping")
        self.assertTrue(watcher.objects("ALIVE")[-1]["degraded"])
        self.assertLess(dropped(), 20000)
        with urllib.request.urlopen(f"http://127.0.0.1:{kewd.http_port}/metrics", timeout=5) as response:
            metrics = response.read().decode()
        self.assertRegex(metrics, r'kew_input_datagrams_dropped_total{input="feed"} [1-9][0-9]*\n')
        # No more drops for 10 ALIVE intervals: healthy again.
        feed_until(lambda: health() == "healthy", 30, "ALIVE to say healthy again")


UDP_FEED = """
[service]
alert_listen = "127.0.0.1:0"

[[input]]
name = "feed"
format = "ndjson"
transport = "udp"
address = "127.0.0.1:0"
"""


def feed_with(service="", feed="", rest=""):
    """FEED with extra [service] keys, extra keys of its input, then more tables."""
    head, table = FEED.split("[[input]]")
    return head + service + "\n[[input]]" + table + feed + rest


def cpu_seconds(pid):
    """User plus system CPU time of process `pid` so far, s (from /proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def memory_kib(pid, key):
    """A figure of /proc/PID/status (VmRSS, VmHWM), KiB."""
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    raise AssertionError(f"no {key} in /proc/{pid}/status")


def parked_pairs(count, t):
    """`count` head-on pairs, each far from the others, 6 NM apart and closing: every pair
    alerts at once and stays in conflict while no later record comes."""
    records = []
    for i in range(count):
        lat = 40.0 + (i // 40) * 0.5
        lon = 0.0 + (i % 40) * 0.5
        for side in (-1, 1):
            name = f"P{i}{'AB'[side > 0]}"
            records.append({"t": t, "id": name, "addr": address_of(name), "src": "e2e", "lat": lat,
                            "lon": round(lon + side * 3 * 1852.0 / (111320.0 * math.cos(math.radians(lat))), 7),
                            "alt_ft": 30000 + 10 * (i % 50), "gs_kt": 450, "trk_deg": 270.0 if side > 0 else 90.0,
                            "vr_fpm": 0})
    return records


class Connections(E2eCase):
    """Silent, slow and greedy clients neither lock others out nor exhaust kewd (docs/reliability.md
    "Connections")."""

    def try_watch(self, port):
        """A subscriber that got its snapshot, or None when kewd refused it."""
        try:
            s = Subscriber(port)
        except (OSError, ValueError):
            return None
        wait_until(lambda: s.objects("ALERTS") or s.closed, 10, "a snapshot or a refusal")
        return s if s.objects("ALERTS") else None

    def test_silent_subscribers_neither_lock_out_watchers_nor_stats(self):
        kewd = self.start(feed_with("max_subscribers = 4\nrequest_timeout_s = 1\n"))
        # Connected before the attack, reading: never timed out.
        early = Subscriber(kewd.alert_port)
        wait_until(lambda: early.objects("ALERTS"), 10, "the early subscriber's snapshot")
        self.silent(kewd.alert_port, 2)
        slow = self.silent(kewd.alert_port, 1)[0]
        slow.sendall(b"?WAT")  # a request line begun, never finished
        wait_until(lambda: kewd.stats()["subscribers"]["now"] >= 4, 10, "every slot taken")
        # Every slot is taken: ?STATS is still answered (the reserved slot) ...
        stats = kewd.stats()
        self.assertEqual(stats["subscribers"]["refused"], 0)
        # ... and the silent ones leave, so a watcher gets in.
        watcher = wait_until(lambda: self.try_watch(kewd.alert_port), 30, "a watcher to get a slot")
        self.assertTrue(watcher.objects("ALERTS"))
        stats = kewd.stats()
        self.assertEqual(stats["subscribers"]["timed_out"], 3, stats["subscribers"])
        self.assertFalse(early.closed, "a watching subscriber is never idle")
        self.assertIn("no complete request line in time", kewd.log())

    def timed_stats(self, port, source="127.0.0.1"):
        """(seconds, STATS object) of one ?STATS on a fresh connection from `source`."""
        start = time.monotonic()
        with socket.create_connection(("127.0.0.1", port), timeout=5, source_address=(source, 0)) as s:
            s.sendall(b"?STATS\n")
            for line in s.makefile("r"):
                obj = json.loads(line)
                if obj["class"] == "STATS":
                    return time.monotonic() - start, obj
        raise AssertionError("no STATS object")

    def timed_status(self, port):
        """(seconds, status line) of one GET /api/status on a fresh connection."""
        start = time.monotonic()
        with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
            s.sendall(b"GET /api/status HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n")
            reply = b""
            while b"\r\n" not in reply:
                chunk = s.recv(4096)
                if not chunk:
                    break
                reply += chunk
        return time.monotonic() - start, reply.split(b"\r\n")[0].decode()

    def test_health_answers_at_once_under_a_flood_of_silent_connections(self):
        # The request time-out stays at its 10 s: the flood is not waited out.
        kewd = self.start(feed_with("max_subscribers = 4\n",
                                    rest='\n[http]\nlisten = "127.0.0.1:0"\nmax_connections = 4\n'))
        watcher = Subscriber(kewd.alert_port)
        wait_until(lambda: watcher.objects("ALERTS"), 10, "the watcher's snapshot")
        reserved = 2
        # Twice every slot, reserved ones included, from one address: silent, or a request
        # begun and never finished.
        subscribers = self.silent(kewd.alert_port, 2 * (4 + reserved))
        for s in subscribers[::2]:
            s.sendall(b"?WAT")
        http = self.silent(kewd.http_port, 2 * (4 + reserved))
        for s in http[::2]:
            s.sendall(b"GET /api/sta")
        time.sleep(0.5)  # every one of them accepted
        seconds, stats = self.timed_stats(kewd.alert_port)
        self.assertLess(seconds, 1.0)
        self.assertGreaterEqual(stats["subscribers"]["evicted"], 2 * (4 + reserved) - 4, stats["subscribers"])
        self.assertEqual(stats["subscribers"]["timed_out"], 0, stats["subscribers"])
        seconds, status = self.timed_status(kewd.http_port)
        self.assertLess(seconds, 1.0)
        self.assertEqual(status, "HTTP/1.1 200 OK")
        # A silent connection from another address was not closed for this address's flood.
        other = socket.create_connection(("127.0.0.1", kewd.alert_port), source_address=("127.0.0.2", 0))
        self.addCleanup(other.close)
        self.silent(kewd.alert_port, 2 * (4 + reserved))
        seconds, _ = self.timed_stats(kewd.alert_port)
        self.assertLess(seconds, 1.0)
        other.settimeout(0.3)
        received = b""
        with self.assertRaises(socket.timeout):  # not closed: it keeps its slot
            while True:
                chunk = other.recv(4096)
                if not chunk:
                    break
                received += chunk
        self.assertNotIn(b"ERROR", received)
        # The watcher that reads keeps its slot and its stream.
        alive = len(watcher.objects("ALIVE"))
        wait_until(lambda: len(watcher.objects("ALIVE")) > alive, 5, "another ALIVE for the watcher")
        self.assertFalse(watcher.closed)
        with urllib.request.urlopen(f"http://127.0.0.1:{kewd.http_port}/metrics", timeout=5) as response:
            metrics = response.read().decode()
        self.assertRegex(metrics, r'kew_http_connections_refused_total{reason="evicted"} ([89]|[1-9][0-9])')
        self.assertRegex(metrics, r"kew_subscribers_evicted_total ([89]|[1-9][0-9])")
        self.assertIn("disconnecting it for a newcomer", kewd.log())

    def test_reserved_slot_answers_stats_and_refuses_watch(self):
        kewd = self.start(feed_with("max_subscribers = 1\n"))
        first = Subscriber(kewd.alert_port)
        wait_until(lambda: first.objects("ALERTS"), 10, "the first subscriber's snapshot")
        second = Subscriber(kewd.alert_port)  # over max_subscribers: ?WATCH refused
        second.wait_closed()
        self.assertEqual(second.objects()[-1]["class"], "ERROR")
        stats = kewd.stats()
        self.assertEqual(stats["subscribers"]["refused"], 1, kewd.log())
        self.assertGreaterEqual(stats["subscribers"]["admin"], 2)
        self.assertFalse(first.closed)

    def test_silent_feed_connections_do_not_lock_out_a_feed(self):
        kewd = self.start(FEED + "max_connections = 4\nidle_timeout_s = 1\n")
        port = kewd.input_port("feed")
        self.silent(port, 4)
        wait_until(lambda: kewd.stats()["inputs"][0].get("connections_idle", 0) >= 4, 30,
                   "the silent feed connections to be closed")
        t0 = time.time() - 600
        records = [head_on(a, t0 + dt, t0) for dt in range(0, 40, 4) for a in "AB"]
        with socket.create_connection(("127.0.0.1", port)) as feed:
            feed.sendall(lines(records))
        kewd.wait_records(len(records))
        stats = kewd.stats()["inputs"][0]
        self.assertEqual(stats["connections"], 5)
        self.assertEqual(stats["connections_refused"], 0)
        self.assertIn("no byte for 1 s", kewd.log())

    def silent(self, port, count):
        """`count` connections to `port` that send nothing (closed at the end of the test)."""
        sockets = [socket.create_connection(("127.0.0.1", port)) for _ in range(count)]
        for s in sockets:
            self.addCleanup(s.close)
        return sockets

    def start_with_modbus(self, modbus_keys=""):
        """kewd with the Modbus map, and the map's port."""
        kewd = self.start(FEED + '\n[modbus]\nenabled = true\nlisten = "127.0.0.1:0"\n' + modbus_keys)
        return kewd, int(kewd.wait_log("Modbus TCP alarm map on port").split("on port ")[1].split()[0])

    def modbus(self, python, port, *command):
        result = subprocess.run([python, MODBUS_CLIENT, "--port", str(port), "--timeout", "2", *command],
                                stdout=subprocess.PIPE, text=True, timeout=30)
        return json.loads(result.stdout)

    def test_silent_modbus_clients_do_not_lock_out_the_panel(self):
        python = pymodbus_python()
        if python is None:
            self.skipTest("python3-pymodbus is not installed: the Modbus connections were NOT checked")
        # One address may hold every slot here, so that the 8 silent clients fill them.
        kewd, port = self.start_with_modbus("silent_per_address = 8\n")
        self.silent(port, 8)
        wait_until(lambda: kewd.stats()["modbus"]["connections_open"] == 8, 10, "every Modbus slot taken")
        # The panel replaces the longest-silent client.
        wait_until(lambda: self.modbus(python, port, "read-input-registers", "0", "1")["ok"], 30,
                   "the panel to be served")
        stats = kewd.stats()["modbus"]
        self.assertGreaterEqual(stats["rejected"].get("modbus_evicted", 0), 1, stats)

    def test_a_polling_panel_is_answered_under_a_flood_of_reconnecting_silent_connections(self):
        python = pymodbus_python()
        if python is None:
            self.skipTest("python3-pymodbus is not installed: the Modbus connections were NOT checked")
        kewd, port = self.start_with_modbus()  # max_connections 8, silent_per_address 4
        # A scanner on another address: 24 connections that say nothing, each closed after
        # 0.1-0.5 s and opened again at once, three times the slots.
        stop = threading.Event()

        def flood(seed):
            pause = 0.1 + (seed % 5) * 0.1
            while not stop.is_set():
                try:
                    with socket.create_connection(("127.0.0.1", port), timeout=2, source_address=("127.0.0.2", 0)):
                        stop.wait(pause)
                except OSError:
                    stop.wait(0.05)

        threads = [threading.Thread(target=flood, args=(i,), daemon=True) for i in range(24)]
        for t in threads:
            t.start()
        self.addCleanup(lambda: [t.join(5) for t in threads])
        self.addCleanup(stop.set)
        wait_until(lambda: kewd.stats()["modbus"]["accepted"] >= 24, 10, "the flood to be under way")
        # The panel polls once a second, each poll on a new connection as mbpoll does.
        answered = 0
        for _ in range(10):
            began = time.monotonic()
            answered += bool(self.modbus(python, port, "read-input-registers", "0", "1")["ok"])
            time.sleep(max(0.0, 1.0 - (time.monotonic() - began)))
        stats = kewd.stats()["modbus"]
        self.assertGreaterEqual(answered, 9, stats)
        self.assertGreater(stats["rejected"].get("modbus_evicted", 0), 0, stats)

    def test_idle_modbus_clients_are_closed(self):
        kewd, port = self.start_with_modbus("idle_timeout_s = 1\n")
        self.silent(port, 3)
        wait_until(lambda: kewd.stats()["modbus"]["rejected"].get("modbus_idle_timeout", 0) == 3, 30,
                   "the silent Modbus clients to be closed")
        self.assertEqual(kewd.stats()["modbus"]["connections_open"], 0)

    def test_memory_stays_bounded_while_clients_repeat_watch_without_reading(self):
        kewd = self.start(feed_with("tick_interval_s = 60\n"))
        pairs = parked_pairs(640, time.time() - 600)
        with socket.create_connection(("127.0.0.1", kewd.input_port("feed"))) as feed:
            feed.sendall(lines(pairs))
        kewd.wait_records(len(pairs))
        # A second pass of records confirms every conflict (alerts open after two).
        for r in pairs:
            r["t"] += 4
        with socket.create_connection(("127.0.0.1", kewd.input_port("feed"))) as feed:
            feed.sendall(lines(pairs))
        kewd.wait_records(2 * len(pairs))
        active = wait_until(lambda: kewd.stats()["alerts_active"] >= 600 and kewd.stats()["alerts_active"], 20,
                            "the alerts to open")
        pid = kewd.process.pid
        before_kib = memory_kib(pid, "VmRSS")
        attackers = []
        for _ in range(31):
            s = socket.socket()
            s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
            s.connect(("127.0.0.1", kewd.alert_port))
            s.setblocking(False)
            attackers.append(s)
        # Each asks for the snapshot (~530 bytes an alert) 60 times and never reads: ~650 MB
        # of snapshots if kewd queued every answer.
        request = b'?WATCH={"enable":true}\n'
        for _ in range(60):
            for s in attackers:
                try:
                    s.send(request)
                except (BlockingIOError, ConnectionError):
                    pass
        # Until kewd has dealt with them: it answered a ?STATS after all of them.
        stats = kewd.stats()
        peak_mib = memory_kib(pid, "VmHWM") / 1024
        bound_mib = before_kib / 1024 + 160
        self.assertLess(peak_mib, bound_mib, f"{active} alerts, {stats['subscribers']}")
        for s in attackers:
            s.close()
        wait_until(lambda: kewd.stats()["subscribers"]["now"] <= 1, 30, "the attackers to be gone")
        self.assertLess(memory_kib(pid, "VmRSS") / 1024, before_kib / 1024 + 64, "memory returned after they left")

    def test_reading_subscriber_receives_every_event_at_max_speed(self):
        recording = self.path("tma.ndjson")
        generate(recording, "tma", aircraft=1000, duration=100, seed=11)
        # The defaults of kewd's subscriber limits; only the live tick is held back, so
        # that the stream equals the offline run.
        kewd = self.start(feed_with("tick_interval_s = 60\n"))
        expected = offline_alerts(kewd.config_path, recording)
        self.assertGreater(len(expected), 20000, "the burst must be long")
        reader = Subscriber(kewd.alert_port)
        wait_until(lambda: reader.objects("ALERTS"), 10, "the snapshot")
        replay_to(f"127.0.0.1:{kewd.input_port('feed')}", recording, "--max-speed")
        kewd.wait_records(count_lines(recording), timeout_s=300)
        wait_until(lambda: len(reader.alert_lines()) >= len(expected) or reader.closed, 120,
                   "the reader to receive every alert")
        stats = kewd.stats()["subscribers"]
        self.assertEqual(stats["cut_off"], 0, stats)
        self.assertFalse(reader.closed)
        self.assertEqual(reader.alert_lines(), expected)

    def test_full_descriptor_table_backs_off_and_recovers(self):
        kewd = self.start(FEED)
        pid = kewd.process.pid
        open_fds = len(os.listdir(f"/proc/{pid}/fd"))
        resource.prlimit(pid, resource.RLIMIT_NOFILE, (open_fds + 4, open_fds + 4))
        clients = []
        for _ in range(12):  # more than the table holds: the rest wait in the backlog
            clients.append(socket.create_connection(("127.0.0.1", kewd.alert_port)))
        wait_until(lambda: "cannot accept connections" in kewd.log(), 10, "kewd to say it is out of descriptors")
        # A resource check, not a timing one: kewd uses little CPU while it cannot accept.
        used = cpu_seconds(pid)
        time.sleep(2)
        used = cpu_seconds(pid) - used
        self.assertLess(used, 0.5, "kewd spins while out of descriptors")
        self.assertEqual(kewd.log().count("cannot accept connections"), 1, "logged once per episode")
        for c in clients:
            c.close()
        t0 = time.time() - 600
        records = [head_on(a, t0 + dt, t0) for dt in range(0, 40, 4) for a in "AB"]
        with socket.create_connection(("127.0.0.1", kewd.input_port("feed"))) as feed:
            feed.sendall(lines(records))
        kewd.wait_records(len(records))
        self.assertGreater(kewd.stats()["subscribers"]["accept_failures"], 0)
        kewd.wait_log("accepting connections again")
def pair_records(k, t, t0):
    """Pair k of head-on aircraft ("Ak", "Bk") along latitude 50° + k/2, as head_on."""
    out = []
    for aircraft in "AB":
        record = head_on(aircraft, t, t0)
        record["id"] = f"{aircraft}{k}"
        record["addr"] = address_of(record["id"])
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


class Watchdog(E2eCase):
    """systemd's watchdog restarts a kewd whose pipeline is stuck, not only a dead one: the
    pings come from the thread that runs the pipeline. The test plays systemd's part of the
    protocol (sd_notify(3)): NOTIFY_SOCKET and WATCHDOG_USEC, as the unit's WatchdogSec sets
    them, and every message read as it arrives (a full socket would block kewd's sender);
    systemd restarts a service that sends no WATCHDOG=1 for WatchdogSec."""

    WATCHDOG_S = 2.0

    def listen_for_pings(self):
        """The notify socket's path, and the list of arrival times of WATCHDOG=1 that a
        thread fills until the test ends."""
        notify = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
        notify.bind(self.path("notify"))
        notify.settimeout(0.2)
        pings, done = [], threading.Event()

        def read():
            while not done.is_set():
                try:
                    message = notify.recv(4096).decode()
                except socket.timeout:
                    continue
                if "WATCHDOG=1" in message.split("\n"):
                    pings.append(time.monotonic())

        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        self.addCleanup(notify.close)
        self.addCleanup(reader.join)
        self.addCleanup(done.set)
        return self.path("notify"), pings

    def test_a_stuck_pipeline_stops_the_watchdog_pings(self):
        notify_path, pings = self.listen_for_pings()
        stall = self.path("stall")
        kewd = self.start(FEED, env={"NOTIFY_SOCKET": notify_path, "WATCHDOG_USEC": str(int(self.WATCHDOG_S * 1e6)),
                                     "KEWD_TEST_STALL_FILE": stall})
        feed = socket.create_connection(("127.0.0.1", kewd.input_port("feed")))
        self.addCleanup(feed.close)
        t0 = time.time() - 600
        feed.sendall(lines([head_on(a, t0, t0) for a in "AB"]))
        kewd.wait_records(2)
        # Serving: pings at least once per WatchdogSec.
        start = time.monotonic()
        time.sleep(3 * self.WATCHDOG_S)
        healthy = [t for t in pings if t >= start]
        self.assertGreaterEqual(len(healthy), 4, healthy)
        self.assertLess(max(b - a for a, b in zip([start] + healthy, healthy)), self.WATCHDOG_S)
        # The pipeline stuck in a batch: no ping for 3 WatchdogSec (systemd would have
        # restarted kewd after the first).
        open(stall, "w").close()
        feed.sendall(lines([head_on(a, t0 + 4, t0) for a in "AB"]))
        kewd.wait_log("test hook: the pipeline is stalled")
        stalled = time.monotonic()
        time.sleep(3 * self.WATCHDOG_S)
        self.assertEqual([t for t in pings if t > stalled], [])
        self.assertTrue(kewd.running(), "stuck, not dead: only the watchdog notices")
        # Unstuck, it pings again and has lost nothing.
        os.unlink(stall)
        kewd.wait_log("test hook: the pipeline runs again")
        wait_until(lambda: len([t for t in pings if t > stalled]) >= 2, 3 * self.WATCHDOG_S, "pings again")
        kewd.wait_records(4)
        self.assertIn("KEWD_TEST_STALL_FILE is set", kewd.log())


class Restarts(E2eCase):
    """A restart neither leaves alerts open in the alert log nor reuses seq or numbers;
    a full disk neither tears a line nor loses an event."""

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
