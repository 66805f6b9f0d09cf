"""kewd when a record, a client, a restart or the disk misbehaves (issue 18, README
"Reliability"). Run by ctest with test_kewd; by hand as test_kewd.py says.
"""
import json
import math
import socket
import subprocess
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


if __name__ == "__main__":
    unittest.main()
