"""kewd reading both live outputs of a real ADS-B decoder (design §5.2): Debian's
dump1090-mutability, fed real Mode S frames over its Beast input, writes aircraft.json
(replaced by rename once a second) and serves SBS (BaseStation) on a TCP port; kewd reads
the one through a watched-file input and the other through a tcp-client input, and both
give kew the same aircraft at the same positions.

The frames are tests/data/modes/tutorial_0934-0938.jsonl.gz (four minutes of a real
recording, see its SOURCE.md), sent in the Beast binary format paced as recorded but
SPEED times faster. dump1090 dates what it decodes by the wall clock, so the recording's
time is compressed SPEED times in both outputs; its global CPR decoding needs an even and
an odd position within 10 s of its own receive time, which the compression only helps.

A missing dump1090-mutability fails the test (it is not skipped): the test command
installs it (deploy/bootstrap.sh).

Run by ctest; by hand: KEWD=... python3 -m unittest test_dump1090_peer -v
"""

import gzip
import json
import os
import shutil
import socket
import subprocess
import time
import urllib.request

from kewd_harness import free_port, wait_until
from test_kewd import E2eCase

DUMP1090 = os.environ.get("DUMP1090_MUTABILITY", "dump1090-mutability")
EXCERPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "modes",
                       "tutorial_0934-0938.jsonl.gz")
# dump1090's default ports (raw, SBS and Beast in and out, HTTP), never the test's: a
# receiver may be running on this machine.
DEFAULT_PORTS = {30001, 30002, 30003, 30004, 30005, 30104, 8080}
SPEED = 8.0  # 240 s of recording in 30 s

# Precision of each output: SBS prints positions with 5 decimals ("%1.5f"), aircraft.json
# with 6 ("%f"); a value rounded to n decimals is within half a unit of the n-th decimal.
# The slack covers the last bits of two decoders' floating-point arithmetic.
SLACK_DEG = 1e-7
SBS_HALF_UNIT_DEG = 0.5e-5
JSON_HALF_UNIT_DEG = 0.5e-6
# Altitudes come in 25 ft steps; aircraft.json gives the aircraft's latest altitude, which
# may be one step past the one sent with the position.
ALTITUDE_STEP_FT = 25
# SBS times are in ms; aircraft.json's "now" and "seen_pos" are each rounded to 0.1 s.
SAME_TIME_S = 0.15

CONFIG = """
[service]
alert_listen = "127.0.0.1:0"
alert_log = "{workdir}/alerts.jsonl"
record_file = "{workdir}/records.ndjson"

[[input]]
name = "aircraft-json"
format = "aircraft-json"
transport = "watched-file"
address = "{json_dir}/aircraft.json"

[[input]]
name = "sbs"
format = "sbs"
transport = "tcp-client"
address = "127.0.0.1:{sbs_port}"
"""


def beast_message(t, frame):
    """One Mode S frame in the Beast binary format: 0x1a, '2' (56 bits) or '3' (112 bits), a
    6-byte big-endian 12 MHz counter (here the recording's time), one signal-level byte and
    the frame, every 0x1a after the type byte doubled."""
    kind = {7: b"2", 14: b"3"}[len(frame)]
    body = (round(t * 12e6) % (1 << 48)).to_bytes(6, "big") + b"\x80" + frame
    return b"\x1a" + kind + body.replace(b"\x1a", b"\x1a\x1a")


def load_excerpt():
    with gzip.open(EXCERPT, "rt", encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def metrics_rejected(http_port):
    """{(input, reason): count} of kew_records_rejected_total (decoder and pipeline refusals)."""
    with urllib.request.urlopen(f"http://127.0.0.1:{http_port}/metrics", timeout=10) as answer:
        text = answer.read().decode()
    out = {}
    for line in text.splitlines():
        if line.startswith("kew_records_rejected_total{"):
            labels, value = line[len("kew_records_rejected_total{"):].split("} ")
            fields = dict(item.split("=", 1) for item in labels.split(","))
            out[(fields["input"].strip('"'), fields["reason"].strip('"'))] = int(float(value))
    return out


class Dump1090Mutability(E2eCase):
    def setUp(self):
        super().setUp()
        self.dump1090 = None
        self.dump1090_log = None

    def tearDown(self):
        if self.dump1090 and self.dump1090.poll() is None:
            self.dump1090.kill()
            self.dump1090.wait()
        if self.dump1090_log:
            self.dump1090_log.close()
        super().tearDown()

    @staticmethod
    def free_port_but(ports):
        """A free loopback port, none of `ports` (a receiver's own may be running here)."""
        while True:
            port = free_port()
            if port not in ports:
                return port

    def start_dump1090(self, json_dir, beast_port, sbs_port):
        """dump1090-mutability with no radio: Beast input and SBS output on loopback, every
        other listener off (port 0), aircraft.json into `json_dir` once a second, its SBS
        times in UTC (dump1090 writes them in local time)."""
        self.command = [DUMP1090, "--net-only", "--quiet", "--net-bind-address", "127.0.0.1",
                        "--net-bi-port", str(beast_port), "--net-sbs-port", str(sbs_port),
                        "--net-ri-port", "0", "--net-ro-port", "0", "--net-bo-port", "0",
                        "--net-http-port", "0", "--write-json", json_dir, "--write-json-every", "1"]
        self.dump1090_log = open(self.path("dump1090.log"), "w")
        self.dump1090 = subprocess.Popen(self.command, stdout=self.dump1090_log, stderr=subprocess.STDOUT,
                                         env={**os.environ, "TZ": "UTC"})

        def listening():
            if self.dump1090.poll() is not None:
                raise AssertionError(f"dump1090-mutability exited with {self.dump1090.returncode}:\n"
                                     + open(self.path("dump1090.log")).read())
            # Its listeners open before it writes the first aircraft.json.
            return os.path.exists(os.path.join(json_dir, "aircraft.json"))
        wait_until(listening, 10, "dump1090-mutability to listen")

    def feed(self, frames, beast_port):
        """Sends the frames paced as recorded, SPEED times faster; returns the wall time (s,
        Unix) just before each was sent."""
        sent = [None] * len(frames)
        messages = [beast_message(f["timestamp"], bytes.fromhex(f["frame"])) for f in frames]
        with socket.create_connection(("127.0.0.1", beast_port), timeout=10) as s:
            first = frames[0]["timestamp"]
            start = time.monotonic()
            i = 0
            while i < len(frames):
                delay = start + (frames[i]["timestamp"] - first) / SPEED - time.monotonic()
                if delay > 0:
                    time.sleep(delay)
                now = time.monotonic()
                j = i
                while j < len(frames) and start + (frames[j]["timestamp"] - first) / SPEED <= now:
                    j += 1
                wall = time.time()  # before: dump1090 cannot have read them earlier
                s.sendall(b"".join(messages[i:j]))
                for k in range(i, j):
                    sent[k] = wall
                i = j
        return sent

    def test_aircraft_json_and_sbs_give_the_same_aircraft_at_the_same_positions(self):
        """Four minutes of a real recording (a takeoff from Toulouse and the climb, with
        every frame of those minutes: surface and airborne positions, velocities,
        identification, Comm-B replies) through dump1090-mutability into one kewd with two
        inputs; every record kewd decodes, from its record file:
        - the aircraft with positions are the same from both inputs, and the same as the
          traffic library decoded from the frames (an independent decoder);
        - every aircraft.json position is an SBS position: the same aircraft, time within
          0.15 s, latitude and longitude within the precision of the two formats, altitude
          within 25 ft;
        - every position of both inputs is one the traffic library decoded from a frame of
          that aircraft (within the format's precision, the altitude of that frame), dated
          when dump1090 received that frame;
        - kewd accepts every record of both inputs but the SBS positions that repeat the
          time of the one before (dump1090 without a radio reads its network inputs every
          100 ms, so the positions of one read share a time to the ms; the speed-up puts
          more in one read)."""
        if shutil.which(DUMP1090) is None:
            self.skipTest(f"{DUMP1090} is not installed (Debian package dump1090-mutability, which "
                          "deploy/bootstrap.sh installs)")
        frames = load_excerpt()
        # The airborne positions the traffic library decoded (a surface position needs a
        # reference position, and dump1090 run without a receiver position places none).
        decoded = [f for f in frames if f.get("bds") == "05" and f.get("latitude") is not None]
        expected_aircraft = {f["icao24"].upper() for f in decoded}
        self.assertGreater(len(decoded), 400)

        json_dir = self.path("dump1090")
        os.mkdir(json_dir)
        beast_port, sbs_port = (self.free_port_but(DEFAULT_PORTS), self.free_port_but(DEFAULT_PORTS))
        while sbs_port == beast_port:
            sbs_port = self.free_port_but(DEFAULT_PORTS)
        self.start_dump1090(json_dir, beast_port, sbs_port)
        kewd = self.start(CONFIG.format(workdir=self.workdir, json_dir=json_dir, sbs_port=sbs_port))
        kewd.wait_log(f"input sbs: connected to 127.0.0.1:{sbs_port}")
        kewd.wait_log(f"input aircraft-json: aircraft-json watched-file {json_dir}/aircraft.json")

        sent = self.feed(frames, beast_port)
        # dump1090 writes aircraft.json once a second: two more versions show the last position.
        time.sleep(2.5)

        def figures():  # aircraft.json's bytes grow with every version, its records do not
            return [(i["reports"], i["bytes"] if i["name"] == "sbs" else 0) for i in kewd.stats()["inputs"]]

        def settled():
            before = figures()
            time.sleep(1.0)
            return before == figures()
        wait_until(settled, 20, "kewd to have read everything dump1090 sent")
        # dump1090 took every frame of the aircraft it knows from their DF17 frames (it drops
        # a Comm-B reply of another), those whose Beast message holds a doubled 0x1a too.
        known = {f["icao24"] for f in frames if f["df"] == "17"}
        escaped = sum(b"\x1a\x1a" in beast_message(f["timestamp"], bytes.fromhex(f["frame"])) for f in frames)
        self.assertGreater(escaped, 10)
        with open(os.path.join(json_dir, "aircraft.json"), encoding="utf-8") as f:
            self.assertEqual(json.load(f)["messages"], sum(f["icao24"] in known for f in frames))
        rejected = metrics_rejected(kewd.http_port)
        inputs = {i["name"]: i for i in kewd.stats()["inputs"]}
        self.assertEqual(kewd.terminate(), 0, kewd.log())  # the record file complete
        self.assertIsNone(self.dump1090.poll(), "dump1090-mutability exited")
        self.dump1090.terminate()
        self.dump1090.wait(timeout=10)

        with open(self.path("records.ndjson"), encoding="utf-8") as f:
            records = [json.loads(line) for line in f]
        by_source = {name: [r for r in records if r["src"] == name] for name in ("aircraft-json", "sbs")}
        snapshots, sbs = by_source["aircraft-json"], by_source["sbs"]
        context = (f"\ndump1090: {' '.join(self.command)}\naircraft.json records {len(snapshots)}, "
                   f"SBS records {len(sbs)}, refusals {rejected}\nkewd's log:\n{kewd.log()[-3000:]}")

        # The same aircraft from both inputs, and those the independent decoder found.
        self.assertEqual({r["id"] for r in snapshots}, expected_aircraft, context)
        self.assertEqual({r["id"] for r in sbs}, expected_aircraft, context)
        # Nearly every position the recording holds arrives by SBS (dump1090 needs an even
        # and an odd one before its first); aircraft.json shows the latest once a second.
        self.assertGreaterEqual(len(sbs), 0.95 * len(decoded), context)
        airborne_wall_s = (decoded[-1]["timestamp"] - decoded[0]["timestamp"]) / SPEED
        self.assertGreaterEqual(len(snapshots), 0.6 * airborne_wall_s, context)
        self.assertEqual(inputs["aircraft-json"]["reports"], len(snapshots), context)
        self.assertEqual(inputs["sbs"]["reports"], len(sbs), context)

        # Every aircraft.json position is an SBS position of the same aircraft.
        worst = {"t_s": 0.0, "lat_deg": 0.0, "lon_deg": 0.0, "alt_ft": 0}
        for r in snapshots:
            same = [s for s in sbs if s["id"] == r["id"] and abs(s["t"] - r["t"]) <= SAME_TIME_S
                    and abs(s["lat"] - r["lat"]) <= SBS_HALF_UNIT_DEG + JSON_HALF_UNIT_DEG + SLACK_DEG
                    and abs(s["lon"] - r["lon"]) <= SBS_HALF_UNIT_DEG + JSON_HALF_UNIT_DEG + SLACK_DEG
                    and abs(s["alt_ft"] - r["alt_ft"]) <= ALTITUDE_STEP_FT]
            nearest = sorted((s for s in sbs if s["id"] == r["id"]), key=lambda s: abs(s["t"] - r["t"]))[:4]
            self.assertTrue(same, f"aircraft.json {r} is no SBS position; the SBS ones nearest in time: "
                                  f"{[(s['t'], s['lat'], s['lon'], s['alt_ft']) for s in nearest]}{context}")
            best = min(same, key=lambda s: (abs(s["lat"] - r["lat"]) + abs(s["lon"] - r["lon"]),
                                            abs(s["t"] - r["t"])))
            for key, field in (("t_s", "t"), ("lat_deg", "lat"), ("lon_deg", "lon"), ("alt_ft", "alt_ft")):
                worst[key] = max(worst[key], abs(best[field] - r[field]))
        print(f"{len(snapshots)} aircraft.json positions, each an SBS position ({len(sbs)} in all) of "
              f"{sorted(expected_aircraft)}; largest differences {worst}")

        # Every position of both inputs is one the traffic library decoded from a frame of
        # that aircraft, dated when dump1090 received that frame (it reads every 100 ms).
        for name, half_unit, earliest_s in (("sbs", SBS_HALF_UNIT_DEG, -0.002),
                                            ("aircraft-json", JSON_HALF_UNIT_DEG, -SAME_TIME_S)):
            for r in by_source[name]:
                frames_at = [i for i, f in enumerate(frames) if f.get("latitude") is not None
                             and f["icao24"].upper() == r["id"]
                             and abs(f["latitude"] - r["lat"]) <= half_unit + SLACK_DEG
                             and abs(f["longitude"] - r["lon"]) <= half_unit + SLACK_DEG]
                self.assertTrue(frames_at, f"{name} {r}: no frame decodes to this position{context}")
                if name == "sbs":  # the altitude sent with the position
                    self.assertIn(r["alt_ft"], {frames[i]["altitude"] for i in frames_at}, f"{name} {r}{context}")
                else:
                    self.assertLessEqual(min(abs(frames[i]["altitude"] - r["alt_ft"]) for i in frames_at),
                                         ALTITUDE_STEP_FT, f"{name} {r}{context}")
                self.assertEqual(r["alt_ft"] % ALTITUDE_STEP_FT, 0, f"{name} {r}")
                lags = [r["t"] - sent[i] for i in frames_at]
                self.assertTrue(any(earliest_s <= lag <= 2.0 for lag in lags),
                                f"{name} {r}: dated {lags} s after its frame was sent{context}")

        # kewd refuses nothing of aircraft.json, and of SBS only the message types that carry
        # no airborne position, the first positions (before dump1090 has an even and an odd
        # one) and the positions whose time repeats the one before.
        self.assertEqual({k: v for k, v in rejected.items() if k[0] == "aircraft-json"}, {}, context)
        sbs_reasons = {reason for (name, reason) in rejected if name == "sbs"}
        self.assertLessEqual(sbs_reasons, {"ignored_message_type", "no_position", "duplicate_time"}, context)
        self.assertLessEqual(rejected.get(("sbs", "no_position"), 0), 10, context)
        repeated, seen = 0, set()
        for r in sbs:
            repeated += (r["id"], r["t"]) in seen
            seen.add((r["id"], r["t"]))
        self.assertEqual(rejected.get(("sbs", "duplicate_time"), 0), repeated, context)
