"""kewd on a NATS cluster (design §5.9): three real nats-server processes with JetStream,
routed on loopback; kewd lists them all (`[nats] servers`) with `replicas = 3`, and the
node that leads the alert stream is killed mid-run: no event is lost or repeated, the
other outputs never stop, publication resumes as soon as the cluster has a new leader. A
hot-standby pair on the cluster loses the alert stream's leader, then (that node back) the
lease's: one instance speaks, the stream is the run without failure. A comma-separated
`url` reaches the server a dead one is listed before; deploy/nats/'s cluster files are
valid nats-server configurations.

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

from kewd_harness import (KEWD, NATS_SERVER, STARTUP_TIMEOUT_S, E2eCase, NatsServer, Subscriber, _nats_client,
                          active_at_end, count_lines, free_port, generate, nats_request, offline_alerts, replay_to,
                          wait_until)
from test_hot_standby import pair_member
from test_nats import SERVICE, UDP_INPUT, check_alert_lifecycles, watch

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
            self.start(i)
        # Ready when every node knows the JetStream meta leader: streams can be made.
        wait_until(lambda: all(self.meta_leader(i) for i in range(self.SIZE)), STARTUP_TIMEOUT_S,
                   "the cluster's JetStream meta leader")

    def start(self, i):
        self.processes[i] = subprocess.Popen([NATS_SERVER, "-c", self.config_paths[i]], stdout=self.logs[i],
                                             stderr=subprocess.STDOUT)

    def restart(self, i):
        """Node i again after a kill, with its configuration and its store: it rejoins the
        cluster (it knows the meta leader again) and its replicas catch up."""
        self.start(i)
        wait_until(lambda: self.meta_leader(i), STARTUP_TIMEOUT_S, f"node{i} to rejoin the cluster")

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
        return self.info(f"$JS.API.STREAM.INFO.{stream}")

    def info(self, subject):
        """JetStream's answer to the request `subject` ($JS.API.…) from a live node, or None."""
        for i in self.alive():
            try:
                info = json.loads(nats_request(self.ports[i], subject, timeout_s=0.5))
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

    def current_replicas(self, group):
        """How many replicas of `group` (a stream, or (stream, consumer)) are current, its
        leader included (0 without one), as the leader tells JetStream's API."""
        if isinstance(group, tuple):
            info = self.info("$JS.API.CONSUMER.INFO.%s.%s" % group)
        else:
            info = self.stream_info(group)
        cluster = (info or {}).get("cluster", {})
        if not cluster.get("leader"):
            return 0
        return 1 + sum(1 for replica in cluster.get("replicas", []) if replica.get("current"))

    def leaders(self):
        """The leader (a node's index) of every stream and consumer, as the live nodes know
        it from their monitoring endpoint (/jsz): {stream: i, (stream, consumer): i}; a
        group none of them knows a live leader of is left out."""
        found = {}
        for i in self.alive():
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{self.http_ports[i]}/jsz?accounts=true&streams=true"
                                            f"&consumers=true", timeout=2) as reply:
                    details = json.load(reply).get("account_details", [])
            except OSError:
                continue
            for account in details:
                for stream in account.get("stream_detail", []):
                    groups = [(stream["name"], stream.get("cluster", {}))]
                    groups += [((stream["name"], consumer["name"]), consumer.get("cluster", {}))
                               for consumer in stream.get("consumer_detail", [])]
                    for group, cluster in groups:
                        leader = cluster.get("leader")
                        if leader and int(leader[len("node"):]) in self.alive():
                            found.setdefault(group, int(leader[len("node"):]))
        return found

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
        # Unanswered while it had no leader, the stream was never gone: not made again.
        self.assertNotIn("creating the stream again", kewd.log())

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


class AcknowledgedFeed(threading.Thread):
    """The recording published on the cluster as the producer of a durable feed publishes:
    20 lines a message at `speed` times their own pace, each message with a Nats-Msg-Id
    and sent again, through any live node, until JetStream acknowledges it (the stream
    keeps it once). kew-replay publishes without acknowledgement: what it publishes while
    the feed stream elects a leader is lost (42 of 118 messages over 12 s, measured), and
    the alerts would not be the recording's."""

    def __init__(self, cluster, subject, recording, speed):
        super().__init__(daemon=True)
        self.cluster = cluster
        self.subject = subject
        self.speed = speed
        with open(recording, "rb") as f:
            lines = [line for line in f if line.strip() and not line.startswith(b"#")]
        self.batches = [lines[i:i + 20] for i in range(0, len(lines), 20)]
        self.sent_again = 0
        self.error = None
        self._socket = self._reader = None

    def run(self):
        try:
            first = json.loads(self.batches[0][0])["t"]
            start = time.monotonic()
            for number, batch in enumerate(self.batches):
                time.sleep(max(0.0, start + (json.loads(batch[0])["t"] - first) / self.speed - time.monotonic()))
                self._publish(number, b"".join(batch))
        except Exception as e:  # seen by join()
            self.error = e
        finally:
            self._close()

    def join(self, timeout=None):
        super().join(timeout)
        if self.error:
            raise self.error

    def _publish(self, number, payload):
        headers = b"NATS/1.0\r\nNats-Msg-Id: kew-e2e-feed-%d\r\n\r\n" % number
        for attempt in range(600):
            inbox = f"_INBOX.kew_e2e_feed.{number}.{attempt}".encode()
            try:
                if self._socket is None:
                    self._connect()
                self._socket.sendall(b"HPUB %s %s %d %d\r\n%s%s\r\n" % (
                    self.subject.encode(), inbox, len(headers), len(headers) + len(payload), headers, payload))
                reply = self._reply(inbox)
                if reply.startswith(b"{") and "seq" in json.loads(reply):
                    return
            except OSError:  # the node died, or no answer in time: another try, maybe through another node
                self._close()
            self.sent_again += 1
            time.sleep(0.1)
        raise AssertionError(f"feed message {number} never acknowledged")

    def _connect(self):
        for i in self.cluster.alive():
            try:
                self._socket, self._reader = _nats_client(self.cluster.ports[i], 2)
            except OSError:
                continue
            self._socket.sendall(b"SUB _INBOX.kew_e2e_feed.> 1\r\n")
            return
        raise OSError("no live node")

    def _reply(self, inbox):
        """The payload of the reply to `inbox` (empty for a status such as 503, no stream
        leader to answer); earlier tries' late replies are passed over."""
        while True:
            line = self._reader.readline()
            if not line:
                raise OSError("the node closed the connection")
            if line.startswith(b"PING"):
                self._socket.sendall(b"PONG\r\n")
            elif line.startswith((b"MSG ", b"HMSG ")):
                words = line.split()
                header_size = int(words[-2]) if line.startswith(b"HMSG ") else 0
                size = int(words[-1])
                payload = self._reader.read(size + 2)[header_size:size]
                if words[1] == inbox:
                    return payload
            elif line.startswith(b"-ERR"):
                raise OSError(line.decode())

    def _close(self):
        if self._socket:
            self._reader.close()
            self._socket.close()
        self._socket = self._reader = None


# What the pair keeps in JetStream: the alerts, the feed, the lease and the pair's origin;
# with the feed's durable consumers, each a group of three replicas with its leader.
PAIR_STREAMS = ("KEW_ALERTS", "KEW_FEED", "KV_KEW_LEASE", "KV_KEW_PAIR")
PAIR_GROUPS = PAIR_STREAMS + (("KEW_FEED", "kewd_a"), ("KEW_FEED", "kewd_b"))


class HotStandbyOnCluster(ClusterCase):
    def test_a_pair_on_the_cluster_survives_losing_the_alert_stream_leader_then_the_lease_leader(self):
        """A active, B standby on three nodes, every stream on three replicas. Mid-conflict
        the node leading the alert stream is killed, restarted with its store and caught
        up; then the node leading the lease's stream is killed. Each time publication
        resumes within RESUME_AFTER_ELECTION_S of the survivors electing leaders, the lease
        has one holder (the standby takes over only a lease the active lost, in step), and
        at the end the stream read through the survivors is the run without failure."""
        recording = self.path("tma-long.ndjson")
        generate(recording, "tma", aircraft=150, duration=300, seed=5)
        self.cluster = cluster = NatsCluster(self.workdir)
        # Everything on three replicas, the feed read through any node.
        config = {name: SERVICE + pair_member(name, cluster.urls, replicas=3) for name in "ab"}
        kewd = {"a": self.start(config["a"])}
        kewd["a"].wait_log("a holds the lease active: active", timeout_s=30)
        kewd["b"] = self.start(config["b"])
        kewd["b"].wait_log("b: in step with the active", timeout_s=30)
        expected = offline_alerts(kewd["a"].config_path, recording)
        self.assertGreater(len(expected), 200, "the scenario must keep alerts open through both failures")

        def caught_up(what):
            """Waits until every stream and feed consumer of the pair has three current
            replicas; a failure names those that have not."""
            try:
                wait_until(lambda: all(cluster.current_replicas(group) == 3 for group in PAIR_GROUPS), 60, what)
            except AssertionError as e:
                behind = {group: cluster.current_replicas(group) for group in PAIR_GROUPS}
                raise AssertionError(f"{e}; current replicas: {behind}") from None

        caught_up("every stream and feed consumer of the pair on three current replicas")
        subscribers = {name: Subscriber(kewd[name].alert_port) for name in "ab"}
        feeder = AcknowledgedFeed(cluster, "kew.feed.tma", recording, speed=4)
        feeder.start()

        def published():
            return sum(k.stats()["nats"]["published"] for k in kewd.values())

        def received():
            return sum(len(s.alert_lines()) for s in subscribers.values())

        def kept():
            return ((cluster.stream_info("KEW_ALERTS") or {}).get("state") or {}).get("messages", 0)

        def lose(stream):
            """Kills the node leading `stream` mid-conflict; returns the node, what it led
            of the pair's, and when (after the kill) the survivors had a leader for each,
            kewd published again and a subscriber received an alert again."""
            wait_until(lambda: active_at_end(subscribers["a"].alert_lines() + subscribers["b"].alert_lines()), 60,
                       "alerts open")
            led = wait_until(lambda: stream in (leaders := cluster.leaders()) and leaders, 30, f"{stream}'s leader")
            node = led[stream]
            groups = [group for group, leader in led.items() if leader == node and group in PAIR_GROUPS]
            at_kill = published(), received()
            cluster.kill(node)
            killed = time.monotonic()
            elected = resumed = delivered = None
            while elected is None or resumed is None or delivered is None:
                now = time.monotonic()
                self.assertLess(now - killed, 60, f"within 60 s: leaders for {groups} ({elected is not None}), a "
                                f"publication ({resumed is not None}), an alert ({delivered is not None})")
                if elected is None and all(group in cluster.leaders() for group in groups):
                    elected = now
                if resumed is None and published() > at_kill[0] + 1:
                    resumed = now
                if delivered is None and received() > at_kill[1]:
                    delivered = now
                time.sleep(0.1)
            return node, groups, elected - killed, resumed - killed, delivered - killed

        wait_until(lambda: published() >= len(expected) // 5, 120, "a fifth of the events published")
        first = lose("KEW_ALERTS")
        cluster.restart(first[0])
        caught_up(f"node{first[0]} back: every stream and feed consumer of the pair on three current replicas")
        wait_until(lambda: published() >= len(expected) // 2, 120, "half the events published")
        second = lose("KV_KEW_LEASE")
        for (node, groups, elected, resumed, delivered), what in ((first, "the alert stream's"),
                                                                  (second, "the lease's")):
            print(f"\nnode{node} ({what} leader; it led {', '.join(map(str, groups))}) killed: leaders elected after "
                  f"{elected:.1f} s, kewd publishing again after {resumed:.1f} s, a subscriber receiving again after "
                  f"{delivered:.1f} s")
            self.assertLess(resumed - elected, RESUME_AFTER_ELECTION_S, "publication resumes once leaders are elected")

        feeder.join()
        print(f"feed messages sent again until acknowledged: {feeder.sent_again}")
        for k in kewd.values():
            k.wait_records(count_lines(recording))
        wait_until(lambda: kept() >= len(expected) and all(k.stats()["nats"]["queued"] == 0 for k in kewd.values()),
                   60, "every event in the stream, the outboxes emptied")
        stream = watch(",".join(cluster.url(i) for i in range(cluster.SIZE)), "--since", "0", "-n", str(len(expected)))
        check_alert_lifecycles(self, stream)
        self.assertEqual(stream, expected, "JetStream holds the run without failure, event for event")
        self.assertEqual(active_at_end(stream), active_at_end(expected), "every alert ends as in the run without failure")

        # One holder at a time: every holding but the last ended by its holder's own loss.
        logs = {name: k.log() for name, k in kewd.items()}
        took = {name: logs[name].count(f"active now (hot standby {name})") for name in kewd}
        lost = {name: logs[name].count("could not renew the lease") for name in kewd}
        print("lease: " + "; ".join(f"{name} took it {took[name]}x, lost it {lost[name]}x" for name in kewd))
        for name in kewd:
            self.assertIn(took[name] - lost[name], (0, 1), f"{name}: {took[name]} holdings, {lost[name]} losses")
        self.assertEqual(sum(took.values()) - sum(lost.values()), 1, "one instance holds the lease at the end")
        for name in kewd:
            self.assertNotIn("unsynced", logs[name], "every takeover by an instance in step")
            self.assertNotIn("they are lost", logs[name])
        # One numbering on the subscribers' streams too: a seq is the run's event, wherever received.
        run = {json.loads(line)["seq"]: line for line in expected}
        for name, subscriber in subscribers.items():
            for line in subscriber.alert_lines():
                self.assertEqual(line, run.get(json.loads(line)["seq"]), f"{name}'s stream: the run's event")


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
