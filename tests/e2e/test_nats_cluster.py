"""kewd on a NATS cluster (design §5.9): three real nats-server processes with JetStream,
routed on loopback; kewd lists them all (`[nats] servers`) with `replicas = 3`, and the
node that leads the alert stream is killed mid-run: no event is lost or repeated, the
other outputs never stop, publication resumes as soon as the cluster has a new leader. A
comma-separated `url` reaches the server a dead one is listed before; deploy/nats/'s
cluster files are valid nats-server configurations.

Run by ctest with Debian's `nats-server`; by hand:
KEWD=... KEW_REPLAY=... KEW_GEN=... KEW_WATCH=... python3 -m unittest test_nats_cluster -v
"""

import glob
import json
import os
import shutil
import subprocess
import threading
import time
import unittest
import urllib.request

from kewd_harness import (KEWD, NATS_SERVER, STARTUP_TIMEOUT_S, NatsServer, Subscriber, count_lines, free_port,
                          generate, nats_request, offline_alerts, replay_to, wait_until)
from test_kewd import E2eCase
from test_nats import SERVICE, UDP_INPUT, watch

DEPLOY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "deploy", "nats")

# What the test allows kewd once the cluster has a leader for the stream again (its
# retry period, a reconnection to a live node, the outbox's head acknowledged).
RESUME_AFTER_ELECTION_S = 5.0


class NatsCluster:
    """Three nats-server processes (Debian's) routed on loopback as one cluster with
    JetStream, each with its own store and monitoring port, on free ports."""

    SIZE = 3

    def __init__(self, workdir):
        self.ports = [free_port() for _ in range(self.SIZE)]
        self.route_ports = [free_port() for _ in range(self.SIZE)]
        self.http_ports = [free_port() for _ in range(self.SIZE)]
        self.processes = [None] * self.SIZE
        self.logs = []
        routes = ", ".join(f"nats-route://127.0.0.1:{port}" for port in self.route_ports)
        self.config_paths = []
        for i in range(self.SIZE):
            path = os.path.join(workdir, f"node{i}.conf")
            with open(path, "w") as f:
                f.write(f'server_name: node{i}\nlisten: 127.0.0.1:{self.ports[i]}\nhttp: 127.0.0.1:{self.http_ports[i]}\n'
                        f'jetstream {{ store_dir: "{os.path.join(workdir, f"store{i}")}" }}\n'
                        f'cluster {{ name: kew_e2e, listen: 127.0.0.1:{self.route_ports[i]}, routes: [{routes}] }}\n')
            self.config_paths.append(path)
            self.logs.append(open(os.path.join(workdir, f"node{i}.log"), "a"))
        for i in range(self.SIZE):
            self.processes[i] = subprocess.Popen([NATS_SERVER, "-c", self.config_paths[i]], stdout=self.logs[i],
                                                 stderr=subprocess.STDOUT)
        # Ready when every node knows the JetStream meta leader: streams can be made.
        wait_until(lambda: all(self.meta_leader(i) for i in range(self.SIZE)), STARTUP_TIMEOUT_S,
                   "the cluster's JetStream meta leader")

    def url(self, i):
        return f"nats://127.0.0.1:{self.ports[i]}"

    @property
    def urls(self):
        return [self.url(i) for i in range(self.SIZE)]

    def alive(self):
        return [i for i in range(self.SIZE) if self.processes[i] and self.processes[i].poll() is None]

    def meta_leader(self, i):
        """The meta leader node i knows (its monitoring endpoint /jsz), or None."""
        if self.processes[i].poll() is not None:
            raise AssertionError(f"nats-server node{i} exited")
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{self.http_ports[i]}/jsz", timeout=2) as reply:
                return json.load(reply).get("meta_cluster", {}).get("leader")
        except OSError:
            return None

    def stream_info(self, stream):
        """JetStream's answer to $JS.API.STREAM.INFO.<stream> from a live node, or None."""
        for i in self.alive():
            try:
                info = json.loads(nats_request(self.ports[i], f"$JS.API.STREAM.INFO.{stream}", timeout_s=0.5))
            except (OSError, AssertionError, ValueError):  # no answer, or no responder (an empty reply)
                continue
            if "error" not in info:
                return info
        return None

    def stream_leader(self, stream):
        """The node (its index) that leads `stream` now, or None."""
        info = self.stream_info(stream)
        leader = info and info.get("cluster", {}).get("leader")
        return int(leader[len("node"):]) if leader else None

    def kill(self, i):
        self.processes[i].kill()
        self.processes[i].wait()

    def stop(self):
        for p in self.processes:
            if p and p.poll() is None:
                p.terminate()
                p.wait(timeout=20)
        for log in self.logs:
            log.close()


class ClusterCase(E2eCase):
    def setUp(self):
        if shutil.which(NATS_SERVER) is None:
            self.skipTest(f"{NATS_SERVER} is not installed (Debian nats-server): the NATS cluster NOT checked")
        super().setUp()
        self.recording = self.path("tma.ndjson")
        generate(self.recording, "tma", aircraft=150, duration=120, seed=3)
        self.cluster = None

    def tearDown(self):
        if self.cluster:
            self.cluster.stop()
        super().tearDown()


class Cluster(ClusterCase):
    def test_killing_the_alert_stream_leader_loses_no_event_and_publication_resumes(self):
        self.cluster = cluster = NatsCluster(self.workdir)
        # An earlier run's stream with one replica: kewd scales it to [nats] replicas.
        created = json.loads(nats_request(cluster.ports[0], "$JS.API.STREAM.CREATE.KEW_ALERTS", json.dumps(
            {"name": "KEW_ALERTS", "subjects": ["kew.alerts.>", "kew.acks"], "num_replicas": 1,
             "storage": "file"}).encode()))
        self.assertNotIn("error", created, created)
        servers = ", ".join(f'"{url}"' for url in cluster.urls)
        kewd = self.start(SERVICE + f"\n[nats]\nservers = [{servers}]\nreplicas = 3\n" + UDP_INPUT)
        expected = offline_alerts(kewd.config_path, self.recording)
        self.assertGreater(len(expected), 100)
        kewd.wait_log("alerts kept in the JetStream stream KEW_ALERTS (kew.alerts.>, kew.acks; 3 replicas)")
        wait_until(lambda: (cluster.stream_info("KEW_ALERTS") or {}).get("config", {}).get("num_replicas") == 3, 20,
                   "the stream on three replicas")
        wait_until(lambda: len((cluster.stream_info("KEW_ALERTS") or {}).get("cluster", {}).get("replicas", [])) == 2
                   and cluster.stream_leader("KEW_ALERTS") is not None, 30, "the stream's leader and two replicas")
        reader = Subscriber(kewd.alert_port)
        feeder = threading.Thread(target=replay_to, args=(
            f"udp://127.0.0.1:{kewd.input_port('udp')}", self.recording, "--speed", "4"))
        feeder.start()
        wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected) // 4, 60, "a quarter of the events")

        leader = cluster.stream_leader("KEW_ALERTS")
        self.assertIsNotNone(leader)
        cluster.kill(leader)
        killed = time.monotonic()
        published_at_kill = kewd.stats()["nats"]["published"]
        # Watched every 0.1 s: when the survivors elect a leader, when kewd publishes again.
        elected = resumed = None
        while resumed is None or elected is None:
            now = time.monotonic()
            self.assertLess(now - killed, 60, "neither a new stream leader nor a publication within 60 s")
            if elected is None and cluster.stream_leader("KEW_ALERTS") not in (None, leader):
                elected = now
            if resumed is None and kewd.stats()["nats"]["published"] > published_at_kill + 1:
                resumed = now
            time.sleep(0.1)
        print(f"\nnode{leader} (the stream's leader) killed: a new leader elected after {elected - killed:.1f} s, "
              f"kewd publishing again after {resumed - killed:.1f} s")
        self.assertLess(resumed - elected, RESUME_AFTER_ELECTION_S, "publication resumes once a leader is elected")

        feeder.join()
        kewd.wait_records(count_lines(self.recording))
        # The other outputs never waited for the bus: the stream has every event.
        wait_until(lambda: len(reader.alert_lines()) >= len(expected), 30, "every alert on the stream")
        self.assertEqual(reader.alert_lines(), expected, "the alert stream goes on while the bus fails over")
        wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected) and kewd.stats()["nats"]["queued"] == 0,
                   60, "the outbox emptied")
        self.assertEqual(kewd.stats()["nats"]["dropped"], 0)
        self.assertTrue(kewd.running())

        # Read back through the two survivors, the dead node listed first.
        survivors = ",".join([cluster.url(leader)] + [cluster.url(i) for i in cluster.alive()])
        kept = watch(survivors, "--since", "0", "-n", str(len(expected)))
        self.assertEqual(kept, expected, "JetStream holds every alert event once, in order")
        with self.assertRaises(subprocess.TimeoutExpired):
            watch(survivors, "--since", str(json.loads(expected[-1])["seq"]), "-n", "1", timeout=3)
        self.assertEqual(kewd.terminate(), 0)


class CommaSeparatedUrl(ClusterCase):
    def test_a_comma_separated_url_reaches_the_server_listed_after_a_dead_one(self):
        server = NatsServer(self.workdir)
        try:
            dead = f"nats://127.0.0.1:{free_port()}"
            kewd = self.start(SERVICE + f'\n[nats]\nurl = "{dead}, {server.url}"\n' + UDP_INPUT)
            expected = offline_alerts(kewd.config_path, self.recording)
            wait_until(lambda: kewd.stats()["nats"]["connected"], 20, "kewd connected to the live server")
            replay_to(f"udp://127.0.0.1:{kewd.input_port('udp')}", self.recording, "--max-speed")
            kewd.wait_records(count_lines(self.recording))
            wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected), 30, "every event published")
            self.assertEqual(watch(f"{dead},{server.url}", "--since", "0", "-n", str(len(expected))), expected)
            self.assertEqual(kewd.terminate(), 0)
        finally:
            server.stop()

    def test_check_config_refuses_a_server_list_that_cannot_connect(self):
        for text, message in (
                ('url = "nats://127.0.0.1:4222,"', "names no NATS server between two commas or at an end"),
                ('url = "127.0.0.1:4222"', "no nats:// before the host"),
                ('servers = ["nats://127.0.0.1:4222", "nats://127.0.0.1:99999"]', "the port is above 65535"),
                ('url = "nats://a:4222"\nservers = ["nats://b:4222"]', "give servers or url, not both"),
                ('servers = ["nats://127.0.0.1:4222"]\nreplicas = 7', "replicas = 7 is outside [1, 5]")):
            path = self.path("check.toml")
            with open(path, "w") as f:
                f.write(f"[nats]\n{text}\n")
            result = subprocess.run([KEWD, "--check-config", "-c", path], stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True, timeout=20)
            self.assertEqual(result.returncode, 64, text)
            self.assertIn(f"{path}:", result.stderr)
            self.assertIn(message, result.stderr)


class DeployedConfiguration(unittest.TestCase):
    def test_the_shipped_nats_server_configurations_are_valid(self):
        if shutil.which(NATS_SERVER) is None:
            self.skipTest(f"{NATS_SERVER} is not installed (Debian nats-server): deploy/nats NOT checked")
        files = [os.path.join(DEPLOY, "nats-server.conf")] + sorted(glob.glob(os.path.join(DEPLOY, "cluster", "*.conf")))
        self.assertEqual(len(files), 4, files)
        for path in files:
            result = subprocess.run([NATS_SERVER, "-t", "-c", path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                    text=True, timeout=20)
            self.assertEqual(result.returncode, 0, result.stdout)
        for n in (1, 2, 3):
            with open(os.path.join(DEPLOY, "cluster", f"kew-bus-{n}.conf")) as f:
                text = f.read()
            self.assertIn(f"server_name: kew-bus-{n}\n", text)
            self.assertIn(f'store_dir: "/var/lib/nats/kew-bus-{n}"', text)
            for m in (1, 2, 3):
                self.assertIn(f"nats-route://bus-{m}.example:6222", text)


if __name__ == "__main__":
    unittest.main()
