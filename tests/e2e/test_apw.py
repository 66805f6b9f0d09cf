"""End-to-end test of the area proximity warning (design §4.11) in a real kewd: three
[[volume]] tables, aircraft flown past them in NDJSON records written here, and the APW
alerts checked on the JSON-lines stream, against kew-replay's offline run, and in the
CAT004 datagrams as Wireshark's dissector (tshark) decodes them.

The volumes, each in its own local east/north frame (nautical miles):
  LKR1   restricted, a 20 NM square, 2,000–10,000 ft;
  WATCH1 watch, a circle of 5 NM, 0–60,000 ft;
  LKD2   danger, a 10 NM square, 1,000–15,000 ft, active "Mon 1415-2359": the records
         start on Monday 2024-04-29 at 14:13:20 UTC (T0), so it opens at T0 + 100 s.
The aircraft fly straight at constant speed and altitude (a record every 2 s), their
latitude and longitude linear in time, so each entry time is known exactly:
  P1 crosses LKR1 (enters at T0 + 180 s); P5 cuts its north-east corner (T0 + 203.6 s);
  P2 skims 0.5 NM outside its south edge; P3 passes under the band (1,700 ft), P4 over
  it (10,500 ft); W1 crosses WATCH1 (T0 + 241.2 s), W2 passes 3 NM outside it; D1 flies
  through LKD2 and out before it opens; D2 is inside it when it opens; D3 enters it
  after (T0 + 240 s).
Exactly five alerts, all "kind":"apw", every one ending: P1, P5, W1, D3 open as a
caution with the time to entry, become a warning 60 s before it and a loss inside; D2
opens as a loss at the opening. No aircraft comes near another (no STCA). A second test
reads the APW bit of CAT004 Alive (I004/060): 1 with volumes, 0 without.

Run by ctest with the e2e tests; by hand:
  KEWD=build/daemon/kewd KEW_REPLAY=build/replay/kew-replay \
  python3 -m unittest tests/e2e/test_apw.py -v
"""

import json
import math
import os
import shutil
import socket
import subprocess
import threading
import time
import unittest

from kewd_harness import Kewd, Subscriber, offline_alerts, temporary_directory, wait_until, write_pcap

T0 = 1714400000                 # Monday 2024-04-29 14:13:20 UTC
ACTIVATION = T0 + 100           # "Mon 1415-2359" opens at 14:15:00
PERIOD = 2.0                    # every aircraft is seen every 2 s
NM = 1852.0
KT = NM / 3600.0                # m/s per knot
LOOKAHEAD = 120.0               # the volumes' default lookahead_s
WARNING = 60.0                  # and warning_s

A_WGS84 = 6378137.0
F_WGS84 = 1 / 298.257223563
E2 = F_WGS84 * (2 - F_WGS84)


class Frame:
    """A local east/north plane (NM) about (lat0, lon0): latitude and longitude linear in
    east and north, with WGS84's radii of curvature at lat0 (exact to 1e-5 within 30 NM)."""

    def __init__(self, lat0, lon0):
        self.lat0, self.lon0 = lat0, lon0
        s = math.sin(math.radians(lat0))
        w = math.sqrt(1 - E2 * s * s)
        self.m = A_WGS84 * (1 - E2) / w ** 3       # meridional radius
        self.n = A_WGS84 / w                        # prime vertical radius

    def latlon(self, east_nm, north_nm):
        return (self.lat0 + math.degrees(north_nm * NM / self.m),
                self.lon0 + math.degrees(east_nm * NM / (self.n * math.cos(math.radians(self.lat0)))))


POLYGON = Frame(50.0, 15.0)
CIRCLE = Frame(50.0, 17.0)       # 77 NM east of POLYGON
DELAYED = Frame(50.0, 13.0)      # 77 NM west


class Aircraft:
    """A straight, level flight in `frame` from (x0, y0) NM at T0 with velocity (vx, vy)
    kt, seen every PERIOD s at `phase` from T0 to T0 + duration."""

    def __init__(self, ident, frame, x0, y0, vx, vy, alt_ft, phase, duration):
        self.ident, self.frame = ident, frame
        self.x0, self.y0, self.vx, self.vy, self.alt_ft = x0, y0, vx, vy, alt_ft
        self.times = [T0 + phase + PERIOD * k for k in range(int((duration - phase) / PERIOD) + 1)]

    def at(self, t):
        """(east, north) NM at data time t."""
        h = (t - T0) / 3600.0
        return self.x0 + self.vx * h, self.y0 + self.vy * h

    def time_at_x(self, x):
        return T0 + 3600.0 * (x - self.x0) / self.vx

    def records(self):
        for t in self.times:
            lat, lon = self.frame.latlon(*self.at(t))
            yield {"t": round(t, 3), "id": self.ident, "src": "apw", "lat": round(lat, 7), "lon": round(lon, 7),
                   "alt_ft": self.alt_ft, "gs_kt": round(math.hypot(self.vx, self.vy), 3),
                   "trk_deg": round(math.degrees(math.atan2(self.vx, self.vy)) % 360, 3), "vr_fpm": 0,
                   "cs": "T" + self.ident[-4:]}


def fleet():
    """The aircraft by name, and the expected alerts: name → (volume, volume_kind,
    entry time or None when inside at the volume's opening)."""
    s = 300.0 / math.sqrt(2)
    a = {
        # LKR1: the square (±10, ±10) NM.
        "P1": Aircraft("A00001", POLYGON, -25.0, 0.0, 300.0, 0.0, 6000, 0.1, 540),
        "P2": Aircraft("A00002", POLYGON, -25.0, -10.5, 300.0, 0.0, 6000, 0.5, 540),
        "P3": Aircraft("A00003", POLYGON, -25.0, 4.0, 300.0, 0.0, 1700, 0.9, 540),
        "P4": Aircraft("A00004", POLYGON, -25.0, -4.0, 300.0, 0.0, 10500, 1.3, 540),
        # Along x + y = 17, south-east: in through (7, 10), out through (10, 7).
        "P5": Aircraft("A00005", POLYGON, -5.0, 22.0, s, -s, 8000, 1.7, 480),
        # WATCH1: a circle of 5 NM about the frame's origin.
        "W1": Aircraft("A00011", CIRCLE, -25.0, 1.0, 300.0, 0.0, 25000, 0.3, 540),
        "W2": Aircraft("A00012", CIRCLE, -25.0, -8.0, 300.0, 0.0, 27000, 1.1, 540),
        # LKD2: the square (±5, ±5) NM, opening at T0 + 100 s.
        "D1": Aircraft("A00021", DELAYED, -6.0, 0.0, 480.0, 0.0, 5000, 0.7, 200),
        "D2": Aircraft("A00022", DELAYED, -12.0, 2.0, 300.0, 0.0, 9000, 1.5, 330),
        "D3": Aircraft("A00023", DELAYED, -25.0, -2.0, 300.0, 0.0, 13000, 1.9, 420),
    }
    expected = {
        "P1": ("LKR1", "restricted", a["P1"].time_at_x(-10.0)),
        "P5": ("LKR1", "restricted", T0 + 3600.0 * (12.0 * math.sqrt(2)) / 300.0),
        "W1": ("WATCH1", "watch", a["W1"].time_at_x(-math.sqrt(24.0))),
        "D2": ("LKD2", "danger", None),
        "D3": ("LKD2", "danger", a["D3"].time_at_x(-5.0)),
    }
    return a, expected


def square(frame, half_nm):
    corners = [(-half_nm, -half_nm), (half_nm, -half_nm), (half_nm, half_nm), (-half_nm, half_nm)]
    return "[" + ", ".join("[%.7f, %.7f]" % frame.latlon(x, y) for x, y in corners) + "]"


def volumes_toml():
    lat, lon = CIRCLE.latlon(0.0, 0.0)
    return f"""
[[volume]]
name = "LKR1"
kind = "restricted"
polygon = {square(POLYGON, 10.0)}
floor_ft = 2000
ceiling_ft = 10000

[[volume]]
name = "WATCH1"
kind = "watch"
circle = {{ lat = {lat:.7f}, lon = {lon:.7f}, radius_nm = 5.0 }}
floor_ft = 0
ceiling_ft = 60000

[[volume]]
name = "LKD2"
kind = "danger"
polygon = {square(DELAYED, 5.0)}
floor_ft = 1000
ceiling_ft = 15000
active = ["Mon 1415-2359"]
"""


# The live tick never fires during the test: the records are judged at their own times.
CONFIG = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 60

[[input]]
name = "feed"
format = "ndjson"
transport = "tcp-server"
address = "127.0.0.1:0"

[cat004]
enabled = true
destination = "127.0.0.1:{cat004_port}"
sac = 25
sic = 9
"""


def area_name(volume):
    """I004/100 AN as tshark shows it: 8 characters, space filled."""
    return volume.upper()[:8].ljust(8)


def tshark_records(pcap):
    """Every CAT004 record of the capture as {field: value} (tshark -T json, whose objects
    repeat a key per record: read as lists of pairs)."""
    out = subprocess.run(["tshark", "-n", "-r", pcap, "-T", "json"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True, check=True).stdout
    packets = json.loads(out, object_pairs_hook=lambda pairs: pairs)

    def members(pairs, key):
        return [v for k, v in pairs if k == key]

    def leaves(pairs, into):
        for k, v in pairs:
            if isinstance(v, list):
                leaves(v, into)
            else:
                into[k] = v
        return into

    records = []
    for packet in packets:
        layers = members(members(packet, "_source")[0], "layers")[0]
        for block in members(layers, "asterix"):
            category = members(block, "asterix.category")[0]
            for message in members(block, "asterix.message"):
                records.append(leaves(message, {"category": category}))
    return records


class Cat004Capture:
    """The datagrams sent to a loopback UDP port, received on a thread until stop()."""

    def __init__(self):
        self.socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.socket.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
        self.socket.bind(("127.0.0.1", 0))
        self.socket.settimeout(0.2)
        self.port = self.socket.getsockname()[1]
        self.datagrams = []
        self.receiving = True
        self.thread = threading.Thread(target=self._receive, daemon=True)
        self.thread.start()

    def _receive(self):
        while self.receiving:
            try:
                self.datagrams.append(self.socket.recv(65536))
            except socket.timeout:
                pass

    def stop(self):
        """The datagrams received; stops receiving (again: nothing more)."""
        if self.receiving:
            self.receiving = False
            self.thread.join()
            self.socket.close()
        return self.datagrams


class AreaProximityWarning(unittest.TestCase):
    def setUp(self):
        self._dir = temporary_directory()
        self.workdir = self._dir.name
        self.kewd = None

    def tearDown(self):
        if self.kewd:
            self.kewd.kill()
        while Subscriber.opened:
            Subscriber.opened.pop().close()
        self._dir.cleanup()

    def test_volumes_alert_on_the_stream_and_in_cat004(self):
        have_tshark = shutil.which("tshark") is not None
        aircraft, expected = fleet()
        self.check_fleet_apart(aircraft)

        capture = Cat004Capture()
        self.addCleanup(capture.stop)
        self.kewd = Kewd(CONFIG.format(cat004_port=capture.port) + volumes_toml(), self.workdir)
        subscriber = Subscriber(self.kewd.alert_port)

        records = sorted((r for a in aircraft.values() for r in a.records()), key=lambda r: r["t"])
        recording = os.path.join(self.workdir, "apw.ndjson")
        with open(recording, "w") as f:
            for r in records:
                f.write(json.dumps(r, separators=(",", ":")) + "\n")
        with socket.create_connection(("127.0.0.1", self.kewd.input_port("feed")), timeout=10) as feed, \
                open(recording, "rb") as f:
            feed.sendall(f.read())
        self.kewd.wait_records(len(records))
        stats = self.kewd.stats()
        self.assertEqual(stats["accepted"], len(records), stats["rejected"])

        def every_event_out():
            s = self.kewd.stats()
            sent = s["alerts_new"] + s["alerts_updated"] + s["alerts_ended"]
            return sent if sent and len(subscriber.alert_lines()) == sent else None
        events_sent = wait_until(every_event_out, 15, "every event kewd counts on the stream")
        time.sleep(1.5)  # CAT004 datagrams in flight, and an Alive or two
        self.assertEqual(self.kewd.terminate(), 0, self.kewd.log())
        datagrams = capture.stop()

        lines = subscriber.alert_lines()
        events = [json.loads(line) for line in lines]
        self.assertEqual(len(events), events_sent)
        self.check_stream(events, aircraft, expected)

        # kew-replay judges the same records under the same configuration alike.
        offline = [line for line in offline_alerts(self.kewd.config_path, recording)
                   if line.startswith('{"class":"ALERT",')]
        self.assertEqual(lines, offline, "kewd's stream equals kew-replay's offline run")

        if not have_tshark:
            self.skipTest("tshark is not installed (apt-get install tshark): the stream was checked, "
                          "CAT004 was NOT")
        self.check_cat004(datagrams, events)

    def check_fleet_apart(self, aircraft):
        """The scenario itself: no two aircraft ever within 5 NM and 2,000 ft of each other."""
        names = sorted(aircraft)
        for i, p in enumerate(names):
            for q in names[i + 1:]:
                a, b = aircraft[p], aircraft[q]
                if a.frame is not b.frame or abs(a.alt_ft - b.alt_ft) >= 2000:
                    continue
                for t in range(T0, T0 + 541):
                    if t > a.times[-1] or t > b.times[-1]:
                        break
                    (xa, ya), (xb, yb) = a.at(t), b.at(t)
                    self.assertGreater(math.hypot(xa - xb, ya - yb), 5.0, f"{p} and {q} at T0 + {t - T0} s")

    def check_stream(self, events, aircraft, expected):
        by_ident = {a.ident: name for name, a in aircraft.items()}
        self.assertEqual([e for e in events if e["kind"] != "apw"], [], "no alert but area warnings")
        by_alert = {}
        for e in events:
            self.assertNotIn("b", e)
            by_alert.setdefault(e["id"], []).append(e)
        opened = {by_ident[es[0]["a"]["id"]]: es for es in by_alert.values()}
        self.assertEqual(sorted(opened), sorted(expected), "which aircraft have an area warning")
        self.assertEqual(len(by_alert), len(expected), "one alert each")
        for name, (volume, kind, entry_t) in expected.items():
            es = opened[name]
            with self.subTest(aircraft=name, volume=volume):
                self.assertEqual({(e["volume"], e["volume_kind"]) for e in es}, {(volume, kind)})
                self.assertEqual(es[-1]["state"], "end", es)
                self.assertEqual(es[-1]["reason"], "cleared", es)
                self.assertTrue(all(e["state"] == "update" for e in es[1:-1]), es)
                steps = [e["severity"] for e in es[:-1]]
                if entry_t is None:
                    # Inside when the volume opens: a loss at once, from its first judgement.
                    self.assertEqual(steps, ["loss"])
                    self.assertGreaterEqual(es[0]["t"], ACTIVATION)
                    self.assertLessEqual(es[0]["t"], ACTIVATION + 2 * PERIOD + 0.5)
                    self.assertEqual(es[0]["t_los_s"], 0.0)
                    continue
                self.assertEqual(steps, ["caution", "warning", "loss"])
                new, warning, loss = es[0], es[1], es[2]
                # Opened once the entry is within the look-ahead (two looks to confirm).
                self.assertGreaterEqual(new["t"], entry_t - LOOKAHEAD)
                self.assertLessEqual(new["t"], entry_t - LOOKAHEAD + 2 * PERIOD + 0.5)
                self.assertAlmostEqual(new["t_los_s"], entry_t - new["t"], delta=1.0)
                self.assertGreaterEqual(warning["t"], entry_t - WARNING)
                self.assertLessEqual(warning["t"], entry_t - WARNING + PERIOD + 0.5)
                self.assertAlmostEqual(warning["t_los_s"], entry_t - warning["t"], delta=1.0)
                self.assertGreaterEqual(loss["t"], entry_t - 1.0)
                self.assertLessEqual(loss["t"], entry_t + PERIOD + 1.0)
                self.assertEqual(loss["t_los_s"], 0.0)
        # The volume that opens mid-run: nothing about it before its opening.
        self.assertTrue(all(e["t"] >= ACTIVATION for e in events if e["volume"] == "LKD2"))

    def check_cat004(self, datagrams, events):
        pcap = os.path.join(self.workdir, "cat004.pcap")
        write_pcap(pcap, datagrams)
        records = tshark_records(pcap)
        self.assertTrue(records, "tshark decoded no CAT004 record")
        self.assertEqual({r["category"] for r in records}, {"4"})
        self.assertEqual({int(r["asterix.004_010_SAC"], 0) for r in records}, {25})
        self.assertEqual({int(r["asterix.004_010_SIC"], 0) for r in records}, {9})
        self.assertGreaterEqual(sum(1 for r in records if r["asterix.004_000_VALUE"] == "1"), 1, "Alive messages")
        sent = [r for r in records if r["asterix.004_000_VALUE"] != "1"]

        def decoded(r):
            return (int(r["asterix.004_000_VALUE"]), int(r["asterix.004_040_VALUE"], 0),
                    int(r["asterix.004_045_STAT"]), int(r["asterix.004_030_VALUE"], 0),
                    r.get("asterix.004_100_AN_VALUE"), r.get("asterix.004_035_VALUE"))

        stat = {"caution": 1, "warning": 2, "loss": 3}

        def wanted(e):
            if e["state"] == "end":
                return (17, e["number"] & 0xFFFF, 0, e["a"]["tn"], None, None)
            return (5, e["number"] & 0xFFFF, stat[e["severity"]], e["a"]["tn"], area_name(e["volume"]), None)

        self.assertEqual([decoded(r) for r in sent], [wanted(e) for e in events],
                         "one CAT004 message per event, in order: APW (5) with the area's name, End Of Conflict (17)")
        self.assertEqual(sum(1 for r in sent if r["asterix.004_000_VALUE"] == "5"),
                         sum(1 for e in events if e["state"] != "end"))
        self.assertEqual(sum(1 for r in sent if r["asterix.004_000_VALUE"] == "17"), len({e["id"] for e in events}))
        self.assertEqual(sent[-1]["asterix.004_000_VALUE"], "17", "the last message ends an alert")
        # The names a reader of Wireshark's tree sees.
        tree = subprocess.run(["tshark", "-n", "-r", pcap, "-V"], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True, check=True).stdout
        self.assertIn("Message Type: Area Proximity Warning (APW) (5)", tree)
        self.assertIn("Message Type: End Of Conflict (EOC) (17)", tree)
        for volume in ("LKR1", "WATCH1", "LKD2"):
            self.assertIn(f"Area Name: {area_name(volume).rstrip()}", tree)
        self.assertNotIn("Malformed", tree)


    def test_alive_says_the_area_proximity_warning_runs(self):
        """I004/060 APW of the Alive messages (docs/protocol.md): 1 with volumes configured,
        0 without."""
        if shutil.which("tshark") is None:
            self.skipTest("tshark is not installed (apt-get install tshark): CAT004 NOT checked")
        for with_volumes in (True, False):
            capture = Cat004Capture()
            self.addCleanup(capture.stop)
            config = CONFIG.format(cat004_port=capture.port) + (volumes_toml() if with_volumes else "")
            self.kewd = Kewd(config, self.workdir)
            wait_until(lambda: len(capture.datagrams) >= 2, 10, "two Alive messages")
            self.assertEqual(self.kewd.terminate(), 0, self.kewd.log())
            self.kewd.kill()
            self.kewd = None
            pcap = os.path.join(self.workdir, "alive.pcap")
            write_pcap(pcap, capture.stop())
            alive = [r for r in tshark_records(pcap) if r["asterix.004_000_VALUE"] == "1"]
            self.assertGreaterEqual(len(alive), 2)
            with self.subTest(volumes=with_volumes):
                self.assertEqual({r.get("asterix.004_060_APW") for r in alive}, {"1" if with_volumes else "0"})
                self.assertEqual({r.get("asterix.004_060_STCA") for r in alive}, {"1"})


if __name__ == "__main__":
    unittest.main()
