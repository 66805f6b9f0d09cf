"""End-to-end tests of the Python subscriber client (clients/python/kew_client.py) and its
examples against the real kewd on loopback: every alert of a replay as kew-replay writes
it, acknowledgements through HTTP seen on the stream, reconnection to a restarted kewd.

Run by ctest (tests/CMakeLists.txt, test client) with the binaries in the environment; by hand:
  cd tests/e2e && KEWD=../../build/daemon/kewd KEW_REPLAY=../../build/replay/kew-replay \
  KEW_GEN=../../build/replay/kew-gen KEW_WATCH=../../build/daemon/kew-watch python3 -m unittest -v test_client
"""

import csv
import json
import math
import os
import subprocess
import sys
import threading
import typing
import unittest

from kewd_harness import (E2eCase, active_at_end, count_lines, free_port, generate, offline_alerts, replay_to,
                          wait_until)

CLIENT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "clients", "python")
sys.path.insert(0, CLIENT_DIR)

import kew_client  # noqa: E402
from kew_client import Ack, Alert, Alerts, Alive, KewClient, Party, Start, Version  # noqa: E402

EXAMPLES = os.path.join(CLIENT_DIR, "examples")

# The live tick never fires during a test: a feed silent for a whole tick would move the
# clock on and make the stream differ from the offline run.
SERVICE = """
[service]
alert_listen = "{alert}"
tick_interval_s = 60
alert_log = "{workdir}/alerts.jsonl"
"""

TCP_INPUT = """
[[input]]
name = "feed"
format = "ndjson"
transport = "tcp-server"
address = "127.0.0.1:0"
"""


class Collector:
    """Iterates a KewClient in a thread of its own, keeping every object it yields."""

    def __init__(self, client):
        self.client = client
        self.objects = []
        self.failure = None
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        try:
            for obj in self.client:
                self.objects.append(obj)
        except Exception as e:  # reported by the test, not lost in the thread
            self.failure = e

    def of(self, cls):
        if self.failure:
            raise AssertionError(f"the client's iteration failed: {self.failure!r}")
        return [o for o in list(self.objects) if isinstance(o, cls)]

    def wait(self, cls, n=1, timeout_s=20.0):
        """The objects of class `cls` once there are at least `n`."""
        return wait_until(lambda: (lambda found: found if len(found) >= n else None)(self.of(cls)), timeout_s,
                          f"{n} {cls.__name__} object(s) from the client")

    @property
    def iterating(self):
        return self._thread.is_alive()

    def stop(self):
        self.client.close()
        self._thread.join(timeout=10)


def assert_typed(test, obj, where="object"):
    """Every field of a dataclass holds a value of its annotated type (Optional: or None)."""
    for name, hint in typing.get_type_hints(type(obj)).items():
        value = getattr(obj, name)
        allowed = typing.get_args(hint) if typing.get_origin(hint) is typing.Union else (hint,)
        allowed = tuple(typing.get_origin(a) or a for a in allowed)
        test.assertIsInstance(value, allowed, f"{where}.{name} = {value!r} is not {hint}")
        if int in allowed and float not in allowed:
            test.assertNotIsInstance(value, bool, f"{where}.{name}")
        if isinstance(value, Party):
            assert_typed(test, value, f"{where}.{name}")


def flatten(obj, prefix=""):
    """A JSON object's members with the nested objects' as PARENT_MEMBER."""
    out = {}
    for key, value in obj.items():
        if isinstance(value, dict):
            out.update(flatten(value, f"{prefix}{key}_"))
        else:
            out[prefix + key] = value
    return out


class ClientCase(E2eCase):
    """The harness's E2eCase (a work directory, kewd processes) with the clients' readers."""

    def setUp(self):
        super().setUp()
        self.collectors = []

    def tearDown(self):
        for c in self.collectors:
            c.stop()
        super().tearDown()

    def collect(self, client):
        collector = Collector(client)
        self.collectors.append(collector)
        return collector

    def client(self, kewd, **options):
        return KewClient("127.0.0.1", kewd.alert_port, http_port=kewd.http_port, **options)

    def replayed(self, watch_first):
        """kewd fed a scenario that leaves alerts active; kew-replay's alert lines for it;
        with `watch_first`, a collecting client watching from before the feed."""
        recording = self.path("airways.ndjson")
        generate(recording, "airways", aircraft=300, duration=150, seed=8)
        kewd = self.start(SERVICE.format(alert="127.0.0.1:0", workdir=self.workdir) + TCP_INPUT)
        expected = offline_alerts(kewd.config_path, recording)
        self.assertGreater(len(expected), 100, "the scenario must have conflicts")
        collector = None
        if watch_first:
            collector = self.collect(self.client(kewd))
            self.assertEqual(collector.wait(Alerts)[0].alerts, [], "a fresh kewd has no active alert")
        records = count_lines(recording)
        replay_to(f"127.0.0.1:{kewd.input_port('feed')}", recording, "--max-speed")
        kewd.wait_records(records)
        return kewd, expected, records, collector


class Stream(ClientCase):
    def test_every_alert_of_a_replay_arrives_as_kew_replay_writes_it(self):
        kewd, expected, records, collector = self.replayed(watch_first=True)
        alerts = collector.wait(Alert, len(expected))
        # Field by field: the parsed object, written back as JSON, is the offline line's object.
        self.assertEqual([a.to_dict() for a in alerts], [json.loads(line) for line in expected])
        for a in alerts:
            assert_typed(self, a, f"alert {a.id}")
        self.assertEqual({a.state for a in alerts}, {"new", "update", "end"})
        self.assertTrue(all((a.reason is None) == (a.state != "end") for a in alerts), "reason only on ends")

        head = collector.objects[:3]
        self.assertEqual([type(o) for o in head], [Version, Start, Alerts])
        self.assertEqual(head[0].proto, kew_client.PROTOCOL_VERSION)
        for o in head:
            assert_typed(self, o)

        # ALIVE, once the feed is over, counts the alerts it left active.
        active = active_at_end(expected)
        alive = wait_until(lambda: [o for o in collector.of(Alive) if o.alerts == len(active)], 10,
                           "an ALIVE counting the active alerts")[-1]
        assert_typed(self, alive)
        self.assertGreater(alive.tracks, 100)

        stats = collector.client.stats()
        self.assertEqual((stats["records"], stats["accepted"]), (records, records))
        self.assertEqual(stats["alerts_active"], len(active))
        self.assertEqual(collector.client.connections, 1)
        self.assertEqual(kewd.terminate(), 0)

    def test_parse_maps_every_class_and_refuses_what_is_not_the_protocol(self):
        self.assertEqual(kew_client.parse(b'{"class":"ERROR","seq":3,"message":"too slow"}\n'),
                         kew_client.Error(seq=3, message="too slow"))
        track = kew_client.parse('{"class":"TRACK","seq":1,"t":2.5,"id":"4CA123","src":"sbs","cs":"",'
                                 '"lat":51.5,"lon":-0.4,"alt_ft":3000,"gnd":true}')
        self.assertEqual((track.gs_kt, track.gnd, track.alt_ft), (None, True, 3000.0))
        stats = kew_client.parse('{"class":"STATS","seq":4,"records":7}')
        self.assertEqual((stats.seq, stats["records"]), (4, 7))
        self.assertEqual(kew_client.parse('{"class":"NEWS","seq":5,"x":1}'),
                         kew_client.Unknown(cls="NEWS", seq=5, data={"class": "NEWS", "seq": 5, "x": 1}))
        alive = kew_client.parse('{"class":"ALIVE","seq":0,"t":null,"tracks":0,"alerts":0,'
                                 '"rates":{"records_per_s":0.0,"updates_per_s":0.0},"degraded":true}')
        self.assertEqual((alive.t, alive.health), (None, "feed_stale"), "an older server's ALIVE")
        area = ('{"class":"ALERT","kind":"apw","id":"9f3c2a51d0e4b7c8","number":42,"seq":17,"state":"update",'
                '"severity":"warning","t":1714400000.250,"t_open":1714399990.000,"a":{"id":"4CA123","src":"sbs",'
                '"cs":"BAW123","lat":51.470000,"lon":-0.450000,"alt_ft":35000,"gs_kt":450.0,"trk_deg":270.0,'
                '"vr_fpm":0,"tn":12},"volume":"ED-R 138","volume_kind":"restricted","t_los_s":41.0,'
                '"hypothesis":"linear","ack":false}')
        warning = kew_client.parse(area)
        self.assertEqual((warning.kind, warning.volume, warning.volume_kind, warning.b, warning.region),
                         ("apw", "ED-R 138", "restricted", None, None))
        self.assertEqual(warning.to_dict(), json.loads(area))
        for bad in ('{"class":"ALERT","seq":1}', '{"seq":1}', '[1]', '{"class":"ACK","seq":1,"t":0,"by":"web",'
                    '"ids":[1]}', 'not json', '{"class":"VERSION","seq":"1","release":"x","proto":1}',
                    area.replace('"volume":"ED-R 138",', '')):
            with self.assertRaises(kew_client.ProtocolError, msg=bad):
                kew_client.parse(bad)


class Acknowledgement(ClientCase):
    def test_acknowledgements_appear_on_the_stream_as_ack_objects(self):
        kewd, expected, _, _ = self.replayed(watch_first=False)
        collector = self.collect(self.client(kewd))
        snapshot = collector.wait(Alerts)[0].alerts
        active = active_at_end(expected)
        self.assertGreater(len(active), 3, "the scenario must leave alerts active")
        self.assertEqual({a.id: a.to_dict() for a in snapshot}, active)
        self.assertFalse(any(a.ack for a in snapshot))

        first = snapshot[0].id
        self.assertEqual(collector.client.acknowledge(first), [first])
        ack = collector.wait(Ack)[0]
        assert_typed(self, ack)
        self.assertEqual((ack.ids, ack.by), ([first], "web"))
        self.assertTrue(ack.client.startswith("127.0.0.1:"), ack.client)

        rest = collector.client.acknowledge()
        self.assertEqual(sorted(rest), sorted(set(active) - {first}))
        self.assertEqual(sorted(collector.wait(Ack, 2)[1].ids), sorted(rest))
        self.assertEqual(collector.client.acknowledge(), [], "nothing is left to acknowledge")
        self.assertEqual(collector.client.acknowledge("0000000000000000"), [], "no such alert")

        # A subscriber connecting now sees every active alert acknowledged.
        late = self.collect(self.client(kewd))
        self.assertEqual({a.id: a.ack for a in late.wait(Alerts)[0].alerts}, {i: True for i in active})
        self.assertEqual(kewd.terminate(), 0)


class Reconnection(ClientCase):
    def test_the_client_comes_back_to_a_restarted_kewd(self):
        # Fixed ports, written into the configuration both runs read.
        alert_port, http_port = free_port(), free_port()
        config = (SERVICE.format(alert=f"127.0.0.1:{alert_port}", workdir=self.workdir)
                  + f'\n[http]\nlisten = "127.0.0.1:{http_port}"\n')
        first = self.start(config)
        self.assertEqual((first.alert_port, first.http_port), (alert_port, http_port))
        client = self.collect(KewClient("127.0.0.1", alert_port, http_port=http_port,
                                        backoff_min_s=0.1, backoff_max_s=0.4))
        once = self.collect(KewClient("127.0.0.1", alert_port, http_port=http_port, reconnect=False))
        client.wait(Alerts)
        once.wait(Alerts)

        first.kill()
        wait_until(lambda: not once.iterating, 10, "the client without reconnect to stop")
        self.assertIsNone(once.failure)
        second = self.start(config)
        starts = client.wait(Start, 2)
        second_start = client.objects.index(starts[1])
        # The new connection's VERSION, then its START; the snapshot after it shows that
        # ?WATCH was sent again.
        self.assertIsInstance(client.objects[second_start - 1], Version)
        self.assertEqual(len(client.of(Version)), 2)
        wait_until(lambda: any(isinstance(o, Alerts) for o in client.objects[second_start:]), 10,
                   "a snapshot after the second START")
        with open(self.path("alerts.jsonl")) as f:
            logged = [json.loads(line)["run"] for line in f if line.startswith('{"class":"START",')]
        self.assertEqual([s.run for s in starts], logged, "the client saw each run's START")
        self.assertNotEqual(starts[0].run, starts[1].run)
        self.assertEqual(client.client.connections, 2)
        self.assertEqual(len(once.of(Start)), 1)
        self.assertEqual(second.terminate(), 0)


class Examples(ClientCase):
    def run_example(self, kewd, script, count, *args):
        result = subprocess.run(
            [sys.executable, os.path.join(EXAMPLES, script), "--host", "127.0.0.1", "--port", str(kewd.alert_port),
             "--http-port", str(kewd.http_port), "--count", str(count), "--timeout", "30", *args],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result.stdout

    def test_print_alerts_and_alerts_to_csv_show_the_active_alerts(self):
        kewd, expected, _, _ = self.replayed(watch_first=False)
        active = active_at_end(expected)
        self.assertGreater(len(active), 3, "the scenario must leave alerts active")

        csv_path = self.path("alerts.csv")
        self.run_example(kewd, "alerts_to_csv.py", len(active), "-o", csv_path)
        with open(csv_path, newline="") as f:
            reader = csv.DictReader(f)
            header, rows = reader.fieldnames, list(reader)
        members = set(flatten(next(iter(active.values())))) - {"class", "reason"}
        self.assertLessEqual(members, set(header), "a column for every member")
        self.assertEqual(sorted(r["id"] for r in rows), sorted(active))
        for r in rows:
            self.assertEqual(r["from_snapshot"], "true")
            for key, value in flatten(active[r["id"]]).items():
                if key == "class":
                    continue
                cell = r[key]
                if isinstance(value, bool):
                    self.assertEqual(cell, "true" if value else "false", key)
                elif isinstance(value, (int, float)):
                    self.assertEqual(float(cell), value, key)
                elif value is None:
                    self.assertTrue(math.isnan(float(cell)), key)
                else:
                    self.assertEqual(cell, value, key)

        printed = self.run_example(kewd, "print_alerts.py", len(active)).splitlines()
        alert_lines = [line for line in printed if not line.startswith("#")]
        self.assertIn(f"# {len(active)} active alerts", printed)
        self.assertEqual(len(alert_lines), len(active))
        for i, alert in active.items():
            mine = [line for line in alert_lines if line.endswith(f"[{i}]")]
            self.assertEqual(len(mine), 1, i)
            self.assertIn(f" {alert['state']} ", mine[0])
            self.assertIn(f" {alert['severity']} ", mine[0])
            for party in (alert["a"], alert["b"]):
                self.assertIn(f"({party['id']})" if party["cs"] else party["id"], mine[0])
        self.assertEqual(kewd.terminate(), 0)


if __name__ == "__main__":
    unittest.main()
