"""Command-line behaviour of the tools: `--version` of every tool with the
source revision, the VERSION and ALIVE objects carrying it, and kew-decode's input,
output and refusal reporting, kew-watch's lines for a conflict and an area warning. That kew-decode's NDJSON replays to the same alerts as
every bundled and shared recording is checked by the golden test (run_golden.py).

Run by ctest with the e2e tests; by hand as test_kewd.py says (KEW_DECODE, KEW_EVAL too).
"""

import gzip
import json
import os
import re
import socket
import subprocess
import tempfile
import threading
import unittest

from kewd_harness import KEW_GEN, KEW_REPLAY, KEW_WATCH, KEWD, Kewd

KEW_DECODE = os.environ.get("KEW_DECODE", "kew-decode")
KEW_EVAL = os.environ.get("KEW_EVAL", "kew-eval")
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SAMPLE = os.path.join(ROOT, "tests", "data", "text", "canonical_sample.ndjson")
JADE = os.path.join(ROOT, "tests", "data", "asterix", "jade", "final_frame_062_first3min.ff")
VERSION_LINE = re.compile(r"^(kew[a-z-]*) (\d+\.\d+\.\d+) \(([0-9a-f]{12}(-dirty)?|unknown)\)$")


def source_revision():
    """The clone's commit (12 hex digits), or None outside git."""
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short=12", "HEAD"], check=True,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


class VersionTest(unittest.TestCase):
    def test_every_tool_prints_its_name_release_and_the_revision_it_was_built_from(self):
        revision = source_revision()
        for name, binary in (("kewd", KEWD), ("kew-replay", KEW_REPLAY), ("kew-gen", KEW_GEN),
                             ("kew-watch", KEW_WATCH), ("kew-eval", KEW_EVAL), ("kew-decode", KEW_DECODE)):
            with self.subTest(tool=name):
                out = subprocess.run([binary, "--version"], check=True, stdout=subprocess.PIPE, text=True).stdout
                match = VERSION_LINE.match(out.strip())
                self.assertIsNotNone(match, out)
                self.assertEqual(match.group(1), name)
                if revision:
                    self.assertEqual(match.group(3).removesuffix("-dirty"), revision)

    def test_version_and_alive_objects_carry_release_and_revision(self):
        tool = subprocess.run([KEWD, "--version"], check=True, stdout=subprocess.PIPE, text=True).stdout.split()
        release, revision = tool[1], tool[2].strip("()")
        with tempfile.TemporaryDirectory(prefix="kew-tools-") as workdir:
            kewd = Kewd('[service]\nalert_listen = "127.0.0.1:0"\ntick_interval_s = 0.2\n', workdir)
            try:
                with socket.create_connection(("127.0.0.1", kewd.alert_port), timeout=10) as s:
                    reader = s.makefile("r")
                    version = json.loads(reader.readline())
                    s.sendall(b'?WATCH={"enable":true}\n')
                    alive = next(o for o in map(json.loads, reader) if o["class"] == "ALIVE")
            finally:
                kewd.kill()
        self.assertEqual(version["class"], "VERSION")
        for obj in (version, alive):
            self.assertEqual((obj["release"], obj["revision"]), (release, revision), obj)


class KewDecodeTest(unittest.TestCase):
    def decode(self, *args, stdin=None):
        return subprocess.run([KEW_DECODE, *args], input=stdin, stdout=subprocess.PIPE, stderr=subprocess.PIPE)

    def test_standard_input_gzip_and_a_file_give_the_same_records(self):
        from_file = self.decode(SAMPLE)
        self.assertEqual(from_file.returncode, 0, from_file.stderr)
        with open(SAMPLE, "rb") as f:
            raw = f.read()
        for args, data in (((), raw), (("-",), raw), (("--format", "ndjson", "-"), raw), ((), gzip.compress(raw))):
            with self.subTest(args=args, gzip=data is not raw):
                piped = self.decode(*args, stdin=data)
                self.assertEqual(piped.returncode, 0, piped.stderr)
                self.assertEqual(piped.stdout, from_file.stdout)
        lines = from_file.stdout.decode().splitlines()
        self.assertEqual(len(lines), 16)
        self.assertIn(b"kew-decode: 16 records written, 0 refused\n", from_file.stderr)

    def test_refusals_are_counted_by_reason_and_reported_unless_quiet(self):
        with open(SAMPLE, "rb") as f:
            good = [line for line in f if line.startswith(b"{")][:2]
        data = good[0] + b"not json\n" + b'{"t":1,"id":"X","lat":91,"lon":0,"alt_ft":1000}\n' + b"{\n" + good[1]
        loud = self.decode("--format", "ndjson", stdin=data)
        self.assertEqual(loud.returncode, 0, loud.stderr)
        self.assertEqual(loud.stdout.count(b"\n"), 2)
        summary = loud.stderr.decode().splitlines()[-1]
        self.assertRegex(summary, r"^kew-decode: 2 records written, 3 refused \(.*bad_json 2.*\)$")
        self.assertEqual(sum(1 for line in loud.stderr.decode().splitlines() if ": refused (" in line), 3)
        quiet = self.decode("--quiet", "--format", "ndjson", stdin=data)
        self.assertEqual(quiet.stdout, loud.stdout)
        self.assertEqual(quiet.stderr.decode().splitlines(), [summary])

    def test_binary_asterix_becomes_canonical_ndjson_that_replays_to_the_same_alerts(self):
        decoded = self.decode("--quiet", JADE)
        self.assertEqual(decoded.returncode, 0, decoded.stderr)
        records = [json.loads(line) for line in decoded.stdout.decode().splitlines()]
        self.assertGreater(len(records), 3000)
        self.assertTrue(all({"t", "id", "lat", "lon", "alt_ft"} <= r.keys() for r in records))
        # The excerpt's one alert is on a tracker's duplicate seen in one record, which the
        # defaults hold back (min_records, design §4.5): let it alert, so that there is an
        # alert to compare.
        with tempfile.NamedTemporaryFile("w", suffix=".toml") as config:
            config.write("[eligibility]\nmin_records = 1\n")
            config.flush()
            original = subprocess.run([KEW_REPLAY, "-c", config.name, JADE], check=True, stdout=subprocess.PIPE,
                                      stderr=subprocess.DEVNULL).stdout
            again = subprocess.run([KEW_REPLAY, "-c", config.name, "-"], input=decoded.stdout, check=True,
                                   stdout=subprocess.PIPE, stderr=subprocess.DEVNULL).stdout
        self.assertEqual(again, original)
        self.assertGreater(original.count(b"\n"), 0)

    def test_exit_status_for_a_missing_file_and_an_unwritable_output(self):
        self.assertEqual(self.decode("/nonexistent/recording.ff").returncode, 64)
        with open("/dev/full", "wb") as full:
            result = subprocess.run([KEW_DECODE, JADE], stdout=full, stderr=subprocess.PIPE)
        self.assertEqual(result.returncode, 1)
        self.assertIn(b"cannot write standard output", result.stderr)


def serve_stream(lines):
    """A one-connection alert stream on loopback: after the client's first line (its
    ?WATCH), `lines`, then closed. Returns its port."""
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(10)

    def serve():
        with listener:
            conn, _ = listener.accept()
            with conn, conn.makefile("rb") as reader:
                reader.readline()
                conn.sendall("".join(json.dumps(line) + "\n" for line in lines).encode())

    threading.Thread(target=serve, daemon=True).start()
    return listener.getsockname()[1]


class KewWatchTest(unittest.TestCase):
    def test_an_area_warning_names_the_volume_and_when_the_aircraft_enters_it(self):
        def party(track_id, callsign, alt_ft):
            return {"id": track_id, "src": "adsb", "cs": callsign, "tn": 1, "lat": 48.1, "lon": 11.5,
                    "alt_ft": alt_ft, "gs_kt": 250.0, "trk_deg": 90.0, "vr_fpm": 0.0}

        t = 1_700_000_001.0  # 22:13:21Z
        conflict = {"class": "ALERT", "kind": "stca", "id": "c1", "number": 1, "seq": 1, "state": "new",
                    "severity": "warning", "t": t, "t_open": t, "a": party("3c6444", "DLH4AB", 5000.0),
                    "b": party("a1b2c3", "", 5300.0), "t_los_s": 45.0, "t_cpa_s": 60.0, "cpa_h_m": 740.8,
                    "cpa_v_ft": 100.0, "sep_h_m": 5556.0, "sep_v_ft": 300.0, "hypothesis": "linear", "ack": False}
        area = {"class": "ALERT", "kind": "apw", "id": "v1", "number": 2, "seq": 2, "state": "new",
                "severity": "warning", "t": t, "t_open": t, "a": party("3c6444", "DLH4AB", 5000.0),
                "volume": "EDR-114", "volume_kind": "restricted", "t_los_s": 40.0, "hypothesis": "linear",
                "ack": False}
        inside = dict(area, seq=3, state="update", severity="loss", t=t + 40, t_los_s=0.0)
        ended = dict(area, seq=4, state="end", reason="cleared", severity="loss", t=t + 100, t_los_s=0.0)
        port = serve_stream([conflict, area, inside, ended])
        out = subprocess.run([KEW_WATCH, f"127.0.0.1:{port}"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             encoding="utf-8", timeout=20, check=False)
        self.assertEqual(out.returncode, 0, out.stderr)
        lines = out.stdout.splitlines()
        self.assertEqual(len(lines), 4, out.stdout)
        self.assertRegex(lines[0], r" x a1b2c3 -        FL053  t_los  45 s  cpa 0\.4 NM 100 ft in 60 s  by linear  \[c1\]$")
        self.assertEqual(lines[1:], [
            "22:13:21Z NEW    warning 3c6444 DLH4AB   FL050 → EDR-114 (restricted)  entry in 40 s  [v1]",
            "22:14:01Z UPDATE loss    3c6444 DLH4AB   FL050 → EDR-114 (restricted)  inside now  [v1]",
            "22:15:01Z END    loss    3c6444 DLH4AB   FL050 → EDR-114 (restricted)  [v1]",
        ])


if __name__ == "__main__":
    unittest.main()


def without_stream_numbers(line):
    """An ALERT line as every instance of a share writes it: seq and alert numbers are
    each stream's own."""
    event = json.loads(line)
    event.pop("seq")
    event.pop("number")
    return json.dumps(event, sort_keys=True)


class ZoneShareTest(unittest.TestCase):
    """[projection] serve_west_deg/serve_east_deg (design §4.9): instances whose bands
    partition the longitudes report, together, exactly one pipeline's alerts."""

    def test_three_bands_give_the_whole_worlds_alerts_each_once(self):
        with tempfile.TemporaryDirectory(prefix="kew-share-") as workdir:
            recording = os.path.join(workdir, "global.ndjson")
            subprocess.run([KEW_GEN, "--scenario", "global", "--aircraft", "3000", "--duration", "300", "--seed", "4",
                            "-o", recording], check=True)

            def alerts(config_text):
                path = os.path.join(workdir, "kew.toml")
                with open(path, "w") as f:
                    f.write(config_text)
                stats = os.path.join(workdir, "stats.json")
                out = subprocess.run([KEW_REPLAY, "--config", path, "--stats-json", stats, recording], check=True,
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
                with open(stats) as f:
                    return out.splitlines(), json.load(f)

            whole, whole_stats = alerts("")
            self.assertGreater(len(whole), 100)
            union = []
            for west, east in ((-180, -60), (-60, 60), (60, 180)):
                lines, stats = alerts(f"[projection]\nserve_west_deg = {west}\nserve_east_deg = {east}\n")
                self.assertTrue(lines, f"band [{west}, {east}) has alerts")
                # Only the zones near its band: less work than the whole world's.
                self.assertLess(stats["zones"]["created"], whole_stats["zones"]["created"])
                union += lines
            self.assertEqual(sorted(map(without_stream_numbers, union)), sorted(map(without_stream_numbers, whole)),
                             "every event once, ids and all")
