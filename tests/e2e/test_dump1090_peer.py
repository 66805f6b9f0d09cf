"""kewd reading both live outputs of a real ADS-B decoder (design §5.2): Debian's
dump1090-mutability, fed Mode S frames over its Beast input, writes aircraft.json
(replaced by rename once a second) and serves SBS (BaseStation) on a TCP port; kewd reads
the one through a watched-file input and the other through a tcp-client input, and both
give kew the same aircraft at the same positions.

The frames are of two kinds, interleaved in time:
- real ones: tests/data/modes/tutorial_0934-0938.jsonl.gz (four minutes of a real
  recording, one aircraft taking off; see its SOURCE.md);
- encoded ones (modes_encoder.py): 13 more aircraft flying the real positions of four
  minutes of tests/data/text/readsb_1hr.json.gz (traffic around 88NV, Nevada), each
  sending as a transponder does: airborne positions even and odd alternately twice a
  second, its velocity once a second, its identification every 5 s, at positions, altitudes
  and rates interpolated linearly between the recorded ones.
They are sent in the Beast binary format paced as timed but SPEED times faster. dump1090
dates what it decodes by the wall clock, so the time is compressed SPEED times in both
outputs; its global CPR decoding needs an even and an odd position within 10 s of its own
receive time, which the compression only helps.

A missing dump1090-mutability skips the end-to-end test (ctest reports it skipped);
deploy/bootstrap.sh installs it. The encoder's checks (ModesEncoder) need no dump1090.

Run by ctest; by hand: KEWD=... python3 -m unittest test_dump1090_peer -v
"""

import bisect
import gzip
import json
import math
import os
import random
import shutil
import socket
import subprocess
import time
import unittest
import urllib.request

import modes_encoder
from kewd_harness import E2eCase, free_port, wait_until

DUMP1090 = os.environ.get("DUMP1090_MUTABILITY", "dump1090-mutability")
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
EXCERPT = os.path.join(DATA, "modes", "tutorial_0934-0938.jsonl.gz")
RECORDING = os.path.join(DATA, "text", "readsb_1hr.json.gz")
# Four minutes of RECORDING with the most aircraft airborne (13 with two airborne positions
# or more, 11 at once; no window of 240 s on a 10 s grid has more): 2023-08-29 10:09:10 to
# 10:13:10 UTC, sent as the same minutes of the excerpt, from 2024-06-06 09:34:00 UTC.
WINDOW = (1693303750, 1693303990)
WINDOW_TO_EXCERPT_S = 1717666440 - WINDOW[0]
# A transponder's extended squitters: an airborne position every 0.4 to 0.6 s, even and
# odd alternately; the velocity about once a second; the identification every 4.8 to 5.2 s.
POSITION_PERIOD_S = (0.4, 0.6)
VELOCITY_PERIOD_S = (0.9, 1.1)
IDENTIFICATION_PERIOD_S = (4.8, 5.2)
# dump1090's default ports (raw, SBS and Beast in and out, HTTP), never the test's: a
# receiver may be running on this machine.
DEFAULT_PORTS = {30001, 30002, 30003, 30004, 30005, 30104, 8080}
SPEED = 8.0  # 240 s of frames in 30 s

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
    6-byte big-endian 12 MHz counter (here the frame's time), one signal-level byte and
    the frame, every 0x1a after the type byte doubled."""
    kind = {7: b"2", 14: b"3"}[len(frame)]
    body = (round(t * 12e6) % (1 << 48)).to_bytes(6, "big") + b"\x80" + frame
    return b"\x1a" + kind + body.replace(b"\x1a", b"\x1a\x1a")


def load_excerpt():
    with gzip.open(EXCERPT, "rt", encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def recorded_flights():
    """{address: (callsigns, points)} of every aircraft with two airborne positions or more
    in WINDOW of RECORDING: the set of its `flight` values (null and "N/A" left out) and
    its airborne positions (t, lat, lon, alt_ft, gs_kt, track_deg) in time order. A line
    with `alt_baro` 0 is an aircraft on the ground (the lines carry no "ground"), which
    sends no airborne position."""
    flights = {}
    with gzip.open(RECORDING, "rt", encoding="utf-8") as f:
        for line in f:
            r = json.loads(line)
            if "lat" not in r or not WINDOW[0] <= r["now"] < WINDOW[1]:
                continue
            callsigns, points = flights.setdefault(r["hex"], (set(), []))
            if r.get("flight") not in (None, "N/A"):
                callsigns.add(r["flight"])
            if r["alt_baro"] > 0:
                points.append((r["now"], r["lat"], r["lon"], r["alt_baro"], r["gscp"], r["track"]))
    return {address: (callsigns, sorted(points)) for address, (callsigns, points) in flights.items()
            if len(points) >= 2}


def transponder_frames(flights):
    """The DF17 frames the aircraft of `flights` send from their first airborne position to
    their last, as lines like the excerpt's (time moved to the excerpt's window): "frame",
    "timestamp", "df", "icao24", "bds" and what a decoder reads from the frame: a position's
    "parity", "altitude" and "latitude"/"longitude" (the CPR cell's position, what a
    decoder finds), with the position it encoded in "sent_lat"/"sent_lon"; a velocity's
    "groundspeed", "track" and "vertical_rate"; an identification's "callsign". Each
    aircraft's times come from its own seeded generator: the same frames on every run."""
    frames = []
    for address, (callsigns, points) in sorted(flights.items()):
        rng = random.Random(address)
        icao = int(address, 16)
        times = [p[0] for p in points]

        def at(t):
            """Position, altitude and vertical rate between the recorded points around t;
            ground speed and track of the latest point at or before it."""
            latest = bisect.bisect_right(times, t) - 1
            i = min(latest, len(points) - 2)
            (t0, lat0, lon0, alt0, _, _), (t1, lat1, lon1, alt1, _, _) = points[i], points[i + 1]
            f = (t - t0) / (t1 - t0) if t1 > t0 else 1.0
            rate = (alt1 - alt0) / (t1 - t0) * 60 if t1 > t0 else 0.0
            _, _, _, _, gs, track = points[latest]
            return (lat0 + f * (lat1 - lat0), lon0 + f * (lon1 - lon0), alt0 + f * (alt1 - alt0), rate,
                    gs, track)

        def add(t, frame, **decoded):
            frames.append({"timestamp": t + WINDOW_TO_EXCERPT_S, "frame": frame.hex(), "df": "17",
                           "icao24": address, **decoded})

        t, odd = times[0] + rng.uniform(0, POSITION_PERIOD_S[1]), rng.randrange(2)
        while t <= times[-1]:
            lat, lon, alt, _, _, _ = at(t)
            alt = round(alt / ALTITUDE_STEP_FT) * ALTITUDE_STEP_FT
            yz, xz = modes_encoder.encode_cpr(lat, lon, odd)
            cell_lat, cell_lon = modes_encoder.decode_cpr_local(lat, lon, yz, xz, odd)
            add(t, modes_encoder.airborne_position(icao, lat, lon, alt, odd), bds="05",
                parity=("even", "odd")[odd], altitude=alt, latitude=cell_lat, longitude=cell_lon,
                sent_lat=lat, sent_lon=lon)
            odd ^= 1
            t += rng.uniform(*POSITION_PERIOD_S)
        t = times[0] + rng.uniform(0, VELOCITY_PERIOD_S[1])
        while t <= times[-1]:
            _, _, _, rate, gs, track = at(t)
            east, north = round(gs * math.sin(math.radians(track))), round(gs * math.cos(math.radians(track)))
            vr = round(rate / 64) * 64
            add(t, modes_encoder.airborne_velocity(icao, east, north, vr), bds="09",
                groundspeed=math.hypot(east, north), track=math.degrees(math.atan2(east, north)) % 360,
                vertical_rate=vr)
            t += rng.uniform(*VELOCITY_PERIOD_S)
        t = times[0] + rng.uniform(0, IDENTIFICATION_PERIOD_S[1])
        for callsign in callsigns:  # none or one (the test checks it)
            while t <= times[-1]:
                add(t, modes_encoder.identification(icao, callsign), bds="08", callsign=callsign)
                t += rng.uniform(*IDENTIFICATION_PERIOD_S)
    return frames


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


class ModesEncoder(unittest.TestCase):
    """modes_encoder.py against real frames, the book's examples and its own decoder."""

    def test_parity_of_every_real_frame(self):
        """The parity of every frame of the excerpt: a DF17's remainder is 0, a DF20/21's
        (Comm-B replies, parity overlaid with the address) the address; with one bit
        flipped (another in each frame), another remainder."""
        frames = load_excerpt()
        for f in frames:
            frame = bytes.fromhex(f["frame"])
            expected = 0 if f["df"] == "17" else int(f["icao24"], 16)
            self.assertEqual(modes_encoder.crc24(frame), expected, f)
            bit = int(f["timestamp"] * 1000) % (len(frame) * 8)
            flipped = (int.from_bytes(frame, "big") ^ 1 << bit).to_bytes(len(frame), "big")
            self.assertNotEqual(modes_encoder.crc24(flipped), expected, f)
        self.assertEqual(sum(f["df"] in ("20", "21") for f in frames), 305)

    def test_reproduces_every_real_extended_squitter(self):
        """Every DF17 airborne position, velocity and identification frame of the excerpt,
        903 frames, rebuilt byte for byte, parity included, from what the traffic library
        decoded of it: the position from its latitude and longitude (so the CPR numbers are
        the library's lat_cpr/lon_cpr), the altitude, the velocity components from ground
        speed and track, the callsign. Only what the library does not report comes from the
        frame's own bits: CA, the identification's category and the velocity's intent
        change flag; the library reads a vertical rate of 0 sent with the sign "down" as 0
        and names the source bit 1 "GNSS" (the book names it barometric)."""
        counts = {"05": 0, "08": 0, "09": 0}
        for f in load_excerpt():
            if f["df"] != "17" or f.get("bds") not in counts:
                continue
            frame = bytes.fromhex(f["frame"])
            bits = modes_encoder.decode(frame)
            address = int(f["icao24"], 16)
            if f["bds"] == "05":
                odd = f["parity"] == "odd"
                self.assertEqual(modes_encoder.encode_cpr(f["latitude"], f["longitude"], odd),
                                 (f["lat_cpr"], f["lon_cpr"]), f)
                made = {modes_encoder.airborne_position(address, f["latitude"], f["longitude"], f["altitude"],
                                                        odd, tc=18 - f["NUCp"], saf=f["NICb"], ca=bits["ca"])}
            elif f["bds"] == "09":
                track = math.radians(f["track"])
                made = {modes_encoder.airborne_velocity(
                    address, round(f["groundspeed"] * math.sin(track)), round(f["groundspeed"] * math.cos(track)),
                    f["vertical_rate"], vr_baro=f["vrate_src"] == "GNSS", nacv=f["NACv"],
                    gnss_minus_baro_ft=f["geo_minus_baro"], ca=bits["ca"], zero_rate_down=down,
                    intent_change=bits["ic"]) for down in (False, True)}
            else:
                made = {modes_encoder.identification(address, f["callsign"], tc=bits["tc"],
                                                     category=bits["category"], ca=bits["ca"])}
            self.assertIn(frame, made, f)
            counts[f["bds"]] += 1
        self.assertEqual(counts, {"05": 431, "08": 51, "09": 421})

    def test_the_books_examples(self):
        """The examples of "The 1090 MHz Riddle": KLM1023's identification, and 40621D's even
        and odd positions at 38,000 ft, globally decoded to 52.2572 N 3.91937 E."""
        klm = bytes.fromhex("8D4840D6202CC371C32CE0576098")
        self.assertEqual(modes_encoder.decode(klm)["callsign"], "KLM1023")
        self.assertEqual(modes_encoder.identification(0x4840D6, "KLM1023"), klm)
        even = modes_encoder.decode(bytes.fromhex("8D40621D58C382D690C8AC2863A7"))
        odd = modes_encoder.decode(bytes.fromhex("8D40621D58C386435CC412692AD6"))
        self.assertEqual((even["alt_ft"], even["odd"], odd["odd"], even["crc"], odd["crc"]), (38000, 0, 1, 0, 0))
        lat, lon = modes_encoder.decode_cpr_global((even["lat_cpr"], even["lon_cpr"]),
                                                   (odd["lat_cpr"], odd["lon_cpr"]), latest_odd=False)
        self.assertAlmostEqual(lat, 52.2572, places=4)
        self.assertAlmostEqual(lon, 3.91937, places=5)
        self.assertEqual(modes_encoder.airborne_position(0x40621D, lat, lon, 38000, 0),
                         bytes.fromhex("8D40621D58C382D690C8AC2863A7"))

    def test_round_trip_of_random_messages(self):
        """5,000 random positions over the whole globe (poles and the antimeridian
        included; one in five within 3e-5 degrees, about a CPR cell, of a latitude where the
        number of longitude zones changes), altitudes, velocities and callsigns: the
        decoder gives back what was
        encoded; a position's CPR cell is within half a cell of it, decoded locally from
        any reference within 100 km and globally with a position of the other format 1 km
        away (when both lie in the same number of longitude zones)."""
        rng = random.Random(1090)
        # The latitudes where the number of longitude zones changes: a position within a
        # CPR cell of one takes its zones from its cell's latitude, not its own.
        transitions = []
        for k in range(8700):
            low, high = k / 100, (k + 1) / 100
            if modes_encoder.nl(low) != modes_encoder.nl(high):
                for _ in range(60):
                    middle = (low + high) / 2
                    low, high = (middle, high) if modes_encoder.nl(middle) == modes_encoder.nl(low) else (low, middle)
                transitions.append(low)
        self.assertEqual(len(transitions), 57)  # NL 59 at the equator to 2 below 87 degrees
        globally = 0
        for n in range(5000):
            address = rng.randrange(1 << 24)
            lat, lon = rng.uniform(-90, 90), rng.uniform(-180, 180)
            if n % 5 == 0:
                lat = rng.choice((-1, 1)) * (rng.choice(transitions) + rng.uniform(-3e-5, 3e-5))
            odd = rng.randrange(2)
            alt = rng.randrange(-1000, 50175, 25)
            frame = modes_encoder.airborne_position(address, lat, lon, alt, odd)
            d = modes_encoder.decode(frame)
            self.assertEqual((d["df"], d["ca"], d["address"], d["tc"], d["crc"], d["alt_ft"], d["odd"]),
                             (17, 5, address, 11, 0, alt, odd))
            cell = modes_encoder.decode_cpr_local(lat, lon, d["lat_cpr"], d["lon_cpr"], odd)
            half_lat, half_lon = modes_encoder.cpr_half_cell_deg(cell[0], odd)
            self.assertLessEqual(abs(cell[0] - lat), half_lat + 1e-12, (lat, lon, odd))
            # Longitude in degrees wraps; compare along the circle.
            self.assertLessEqual(abs((cell[1] - lon + 180) % 360 - 180), half_lon + 1e-12, (lat, lon, odd))
            ref_lat = max(-90.0, min(90.0, lat + rng.uniform(-0.9, 0.9)))
            ref_lon = lon + rng.uniform(-0.9, 0.9) / max(math.cos(math.radians(ref_lat)), 0.02)
            if abs(ref_lat) < 85:
                local = modes_encoder.decode_cpr_local(ref_lat, ref_lon, d["lat_cpr"], d["lon_cpr"], odd)
                self.assertAlmostEqual(local[0], cell[0], places=9)
                self.assertAlmostEqual((local[1] - cell[1] + 180) % 360 - 180, 0, places=9)
            other_lat = max(-90.0, min(90.0, lat + 0.009))
            other = modes_encoder.decode(modes_encoder.airborne_position(address, other_lat, lon, alt, 1 - odd))
            pair = {odd: (d["lat_cpr"], d["lon_cpr"]), 1 - odd: (other["lat_cpr"], other["lon_cpr"])}
            position = modes_encoder.decode_cpr_global(pair[0], pair[1], latest_odd=odd)
            if position is not None:
                globally += 1
                self.assertAlmostEqual(position[0], cell[0], places=9, msg=(lat, lon, odd))
                self.assertAlmostEqual((position[1] - cell[1] + 180) % 360 - 180, 0, places=9, msg=(lat, lon, odd))

            east, north = rng.randrange(-1021, 1022), rng.randrange(-1021, 1022)
            vr = rng.randrange(-510, 511) * 64
            dif = rng.choice([None, rng.randrange(-126, 127) * 25])
            d = modes_encoder.decode(modes_encoder.airborne_velocity(address, east, north, vr, vr_baro=odd,
                                                                     nacv=alt % 8, gnss_minus_baro_ft=dif))
            self.assertEqual((d["tc"], d["subtype"], d["crc"], d["east_kt"], d["north_kt"], d["vr_fpm"],
                              d["vr_baro"], d["nacv"], d["gnss_minus_baro_ft"]),
                             (19, 1, 0, east, north, vr, odd, alt % 8, dif))
            callsign = "".join(rng.choice("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789") for _ in range(rng.randrange(1, 9)))
            d = modes_encoder.decode(modes_encoder.identification(address, callsign, category=odd * 3))
            self.assertEqual((d["tc"], d["crc"], d["callsign"], d["category"]), (4, 0, callsign, odd * 3))
        self.assertGreater(globally, 4000)  # about half of those at a transition straddle it

    def test_the_encoded_traffic(self):
        """The frames the end-to-end test sends: each aircraft has one callsign at most; every
        frame decodes to what it was made of; every position's CPR cell lies within half a
        cell of the position encoded (about 2.6 m by 3.5 m there); each position after the
        first, decoded globally with the latest of the other format as dump1090 does, is its
        cell (but across a change of the number of longitude zones)."""
        flights = recorded_flights()
        self.assertEqual(len(flights), 13)
        self.assertTrue(all(len(callsigns) <= 1 for callsigns, _ in flights.values()), flights)
        frames = transponder_frames(flights)
        latest = {}  # (address, parity) -> (lat_cpr, lon_cpr)
        pairs = 0
        for f in frames:
            d = modes_encoder.decode(bytes.fromhex(f["frame"]))
            self.assertEqual((d["df"], d["ca"], d["address"], d["crc"]), (17, 5, int(f["icao24"], 16), 0), f)
            if f["bds"] == "05":
                odd = f["parity"] == "odd"
                self.assertEqual((d["tc"], d["alt_ft"], d["odd"]), (11, f["altitude"], odd), f)
                half_lat, half_lon = modes_encoder.cpr_half_cell_deg(f["latitude"], odd)
                self.assertLessEqual(abs(f["latitude"] - f["sent_lat"]), half_lat + 1e-12, f)
                self.assertLessEqual(abs(f["longitude"] - f["sent_lon"]), half_lon + 1e-12, f)
                self.assertLess(half_lat, 2.5e-5)
                self.assertLess(half_lon, 3.5e-5)
                latest[f["icao24"], odd] = (d["lat_cpr"], d["lon_cpr"])
                other = latest.get((f["icao24"], not odd))
                if other:
                    mine = latest[f["icao24"], odd]
                    position = modes_encoder.decode_cpr_global(*((other, mine) if odd else (mine, other)),
                                                               latest_odd=odd)
                    if position is not None:
                        pairs += 1
                        self.assertAlmostEqual(position[0], f["latitude"], places=9, msg=f)
                        self.assertAlmostEqual(position[1], f["longitude"], places=9, msg=f)
            elif f["bds"] == "09":
                self.assertEqual((d["tc"], d["subtype"], d["vr_fpm"]), (19, 1, f["vertical_rate"]), f)
                self.assertAlmostEqual(math.hypot(d["east_kt"], d["north_kt"]), f["groundspeed"], places=9)
            else:
                self.assertEqual((d["tc"], d["callsign"]), (4, f["callsign"]), f)
        self.assertGreater(pairs, 0.99 * sum(f["bds"] == "05" for f in frames))


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
        """Sends the frames (in time order) paced as timed, SPEED times faster; returns the
        wall time (s, Unix) just before each was sent."""
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
        """Four minutes of frames through dump1090-mutability into one kewd with two inputs:
        those of a real recording (a takeoff from Toulouse and the climb, every frame of
        those minutes: surface and airborne positions, velocities, identification, Comm-B
        replies) and those of 13 aircraft flying recorded positions, encoded by the test
        (14 aircraft, up to 11 of them airborne at once); every record kewd decodes, from its
        record file:
        - the aircraft with positions are the same from both inputs, and the same as those
          with airborne positions among the frames sent;
        - every aircraft.json position is an SBS position: the same aircraft, time within
          0.15 s, latitude and longitude within the precision of the two formats, altitude
          within 25 ft;
        - every position of both inputs is one decoded from a frame of that aircraft
          (within the format's precision, the altitude of that frame), dated when dump1090
          received that frame: the traffic library's decoding of a real frame, the CPR cell
          of an encoded one, which lies within half a cell (about 3 m) of the position the
          test encoded;
        - the callsigns of both inputs are those sent, for every aircraft that sent one, and
          SBS velocities are those sent (ground speed and track within 1 kt and 1.5 degrees,
          vertical rate exact);
        - kewd accepts every record of both inputs but the SBS positions that repeat the
          time of the one before (dump1090 without a radio reads its network inputs every
          100 ms, so the positions of one read share a time to the ms; the speed-up puts
          more in one read)."""
        if shutil.which(DUMP1090) is None:
            self.skipTest(f"{DUMP1090} is not installed (Debian package dump1090-mutability, which "
                          "deploy/bootstrap.sh installs)")
        real = load_excerpt()
        encoded = transponder_frames(recorded_flights())
        frames = sorted(real + encoded, key=lambda f: f["timestamp"])
        # The airborne positions sent: those the traffic library decoded from the real
        # frames (a surface position needs a reference position, and dump1090 run without a
        # receiver position places none) and the encoded ones.
        decoded = [f for f in frames if f.get("bds") == "05" and f.get("latitude") is not None]
        expected_aircraft = {f["icao24"].upper() for f in decoded}
        self.assertGreater(sum("sent_lat" not in f for f in decoded), 400)
        self.assertEqual(len(expected_aircraft), 14)
        callsigns = {}
        for f in frames:
            if f.get("callsign"):
                callsigns.setdefault(f["icao24"].upper(), set()).add(f["callsign"])
        self.assertEqual(len(callsigns), 14)

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

        # The same aircraft from both inputs, and those sent with airborne positions.
        self.assertEqual({r["id"] for r in snapshots}, expected_aircraft, context)
        self.assertEqual({r["id"] for r in sbs}, expected_aircraft, context)
        # Nearly every position sent arrives by SBS (dump1090 needs an even and an odd one
        # before its first); aircraft.json shows the latest of each aircraft once a second.
        self.assertGreaterEqual(len(sbs), 0.95 * len(decoded), context)
        for aircraft in expected_aircraft:
            times = [f["timestamp"] for f in decoded if f["icao24"].upper() == aircraft]
            shown = sum(r["id"] == aircraft for r in snapshots)
            self.assertGreaterEqual(shown, 0.6 * (times[-1] - times[0]) / SPEED - 1, f"{aircraft}{context}")
        self.assertEqual(inputs["aircraft-json"]["reports"], len(snapshots), context)
        self.assertEqual(inputs["sbs"]["reports"], len(sbs), context)

        # Every aircraft.json position is an SBS position of the same aircraft.
        sbs_of = {}  # id -> its SBS records in time order
        for s in sorted(sbs, key=lambda s: s["t"]):
            sbs_of.setdefault(s["id"], []).append(s)
        worst = {"t_s": 0.0, "lat_deg": 0.0, "lon_deg": 0.0, "alt_ft": 0}
        for r in snapshots:
            mine = sbs_of[r["id"]]
            near = mine[bisect.bisect_left([s["t"] for s in mine], r["t"] - 2):][:200]
            same = [s for s in near if abs(s["t"] - r["t"]) <= SAME_TIME_S
                    and abs(s["lat"] - r["lat"]) <= SBS_HALF_UNIT_DEG + JSON_HALF_UNIT_DEG + SLACK_DEG
                    and abs(s["lon"] - r["lon"]) <= SBS_HALF_UNIT_DEG + JSON_HALF_UNIT_DEG + SLACK_DEG
                    and abs(s["alt_ft"] - r["alt_ft"]) <= ALTITUDE_STEP_FT]
            nearest = sorted(mine, key=lambda s: abs(s["t"] - r["t"]))[:4]
            self.assertTrue(same, f"aircraft.json {r} is no SBS position; the SBS ones nearest in time: "
                                  f"{[(s['t'], s['lat'], s['lon'], s['alt_ft']) for s in nearest]}{context}")
            best = min(same, key=lambda s: (abs(s["lat"] - r["lat"]) + abs(s["lon"] - r["lon"]),
                                            abs(s["t"] - r["t"])))
            for key, field in (("t_s", "t"), ("lat_deg", "lat"), ("lon_deg", "lon"), ("alt_ft", "alt_ft")):
                worst[key] = max(worst[key], abs(best[field] - r[field]))
        print(f"{len(snapshots)} aircraft.json positions, each an SBS position ({len(sbs)} in all) of "
              f"{len(expected_aircraft)} aircraft {sorted(expected_aircraft)}; largest differences {worst}")

        # Every position of both inputs is one decoded from a frame of that aircraft, dated
        # when dump1090 received that frame (it reads every 100 ms); an encoded frame's is
        # within half a CPR cell of the position the test encoded.
        positions_of = {}  # id -> [(latitude, index in frames)] in latitude order
        for i, f in enumerate(frames):
            if f.get("latitude") is not None:
                positions_of.setdefault(f["icao24"].upper(), []).append((f["latitude"], i))
        for positions in positions_of.values():
            positions.sort()
        worst_cell = [0.0, 0.0]
        for name, half_unit, earliest_s in (("sbs", SBS_HALF_UNIT_DEG, -0.002),
                                            ("aircraft-json", JSON_HALF_UNIT_DEG, -SAME_TIME_S)):
            for r in by_source[name]:
                positions, within = positions_of[r["id"]], half_unit + SLACK_DEG
                band = positions[bisect.bisect_left(positions, (r["lat"] - within,)):
                                 bisect.bisect_right(positions, (r["lat"] + within, len(frames)))]
                frames_at = [i for _, i in band if abs(frames[i]["longitude"] - r["lon"]) <= within]
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
                for i in frames_at:
                    if "sent_lat" in frames[i]:
                        half_lat, half_lon = modes_encoder.cpr_half_cell_deg(frames[i]["latitude"],
                                                                             frames[i]["parity"] == "odd")
                        cell = (abs(r["lat"] - frames[i]["sent_lat"]), abs(r["lon"] - frames[i]["sent_lon"]))
                        self.assertLessEqual(cell[0], half_unit + half_lat + SLACK_DEG, f"{name} {r}{context}")
                        self.assertLessEqual(cell[1], half_unit + half_lon + SLACK_DEG, f"{name} {r}{context}")
                        worst_cell = [max(w, c) for w, c in zip(worst_cell, cell)]
        print(f"encoded positions: largest difference of a decoded one from the position encoded "
              f"{worst_cell[0]:.7f} deg latitude, {worst_cell[1]:.7f} deg longitude")

        # The callsigns sent, and (by SBS) the velocities sent: each SBS velocity is that of
        # a velocity frame of the aircraft sent at most 10 s (kewd's velocity_max_age_s)
        # before, in whole kt and degrees as dump1090 rounds them (the speed down; a track west
        # of north by adding 0.5 to a negative angle and dropping the fraction: up to 1.5
        # degrees more).
        for name in ("aircraft-json", "sbs"):
            received = {}
            for r in by_source[name]:
                if r.get("cs"):
                    received.setdefault(r["id"], set()).add(r["cs"])
            self.assertEqual(received, callsigns, f"{name}{context}")
        velocities_of = {}  # id -> [(sent, index in frames)] in time order
        for i, f in enumerate(frames):
            if f.get("groundspeed") is not None:
                velocities_of.setdefault(f["icao24"].upper(), []).append((sent[i], i))
        with_velocity = 0
        for r in sbs:
            if r.get("gs_kt") is None:
                continue
            with_velocity += 1
            velocities = velocities_of[r["id"]]
            candidates = [frames[i] for at, i in velocities[bisect.bisect_left(velocities, (r["t"] - 10.5,)):]
                          if at <= r["t"] + 0.01]
            self.assertTrue(any(abs(f["groundspeed"] - r["gs_kt"]) <= 1
                                and abs((f["track"] - r["trk_deg"] + 180) % 360 - 180) <= 1.5
                                and f["vertical_rate"] == r.get("vr_fpm") for f in candidates),
                            f"sbs {r}: no velocity sent is this one{context}")
        self.assertGreater(with_velocity, 0.9 * len(sbs), context)

        # kewd refuses nothing of aircraft.json, and of SBS only the message types that carry
        # no airborne position, the first positions of an aircraft (before dump1090 has an
        # even and an odd one) and the positions whose time repeats the one before.
        self.assertEqual({k: v for k, v in rejected.items() if k[0] == "aircraft-json"}, {}, context)
        sbs_reasons = {reason for (name, reason) in rejected if name == "sbs"}
        self.assertLessEqual(sbs_reasons, {"ignored_message_type", "no_position", "duplicate_time"}, context)
        self.assertLessEqual(rejected.get(("sbs", "no_position"), 0), 2 * len(expected_aircraft), context)
        repeated, seen = 0, set()
        for r in sbs:
            repeated += (r["id"], r["t"]) in seen
            seen.add((r["id"], r["t"]))
        self.assertEqual(rejected.get(("sbs", "duplicate_time"), 0), repeated, context)
