"""A hot-standby pair of kewd on one real NATS server (design §5.9, reliability.md "Hot
standby"): a killed active replaced with no event lost or repeated, acknowledgements and
subscribers carried across the takeover, notifications delivered once across it, a chain
of failures and restarts, stalls of one instance and of the whole host, and the bus away
for 10 s.

Run by ctest with a real `nats-server` (Debian's, with JetStream); by hand:
KEWD=... KEW_REPLAY=... KEW_GEN=... KEW_WATCH=... python3 -m unittest test_hot_standby -v
"""

import json
import shutil
import signal
import subprocess
import threading
import time
import urllib.request

from kewd_harness import (KEW_WATCH, Subscriber, count_lines, generate, nats_publish, offline_alerts, replay_to,
                          wait_until)
from test_http import WebSocket
from test_notify import Endpoint, passing
from test_nats import (SERVICE, UDP_INPUT, NatsCase, check_alert_lifecycles, stream_first_seq, stream_messages,
                       watch)


def pair_member(name, servers, replicas=1, nats_keys="", input_keys=""):
    """The [nats] table and NATS feed of hot-standby pair member `name` on `servers` (URLs of
    one server or of a cluster's nodes), each stream with `replicas` replicas: it reads the
    feed through its own durable consumer of the stream KEW_FEED, through any server.
    `nats_keys`, `input_keys`: more lines for the [nats] table and the input."""
    listed = ", ".join(f'"{url}"' for url in servers)
    return f"""
[nats]
servers = [{listed}]
replicas = {replicas}
hot_standby = true
instance = "{name}"
{nats_keys}

[[input]]
name = "bus"
format = "ndjson"
transport = "nats"
address = "kew.feed.tma"
nats_servers = [{listed}]
durable = "kewd_{name}"
stream = "KEW_FEED"
{input_keys}
"""

# Hot standby fed by UDP on each instance (radar delivered to both hosts): the lease and
# the alert stream are on the bus, the feed is not.
BUS_AWAY = """
[nats]
url = "{url}"
hot_standby = true
instance = "{name}"
""" + UDP_INPUT


class HotStandby(NatsCase):
    def test_the_standby_takes_over_a_killed_active_and_no_event_is_lost_or_repeated(self):
        first, second = self.start_pair()
        # The run without failure: every event once, in order (as the other tests show the
        # stream, JetStream and the file give).
        expected = offline_alerts(first.config_path, self.recording)
        on_first = Subscriber(first.alert_port)
        on_second = Subscriber(second.alert_port)
        # A standby says so: a display connected to it must not take silence for a quiet sky.
        wait_until(lambda: on_second.objects("ALIVE"), 10, "the standby's ALIVE")
        self.assertEqual(on_second.objects("ALIVE")[-1]["health"], "standby")
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "4"))
        feeder.start()
        # Mid-conflict: alerts are open when the active dies.
        wait_until(lambda: len(on_first.alert_lines()) >= len(expected) // 4, 60, "alerts from the active")
        first.process.kill()
        killed = time.monotonic()
        line = second.wait_log("active now (hot standby b)", timeout_s=30)
        print(f"\nthe standby took over {time.monotonic() - killed:.2f} s after SIGKILL: {line}")
        feeder.join()
        second.wait_records(count_lines(self.recording))
        wait_until(lambda: second.stats()["nats"]["published"] > 0 and second.stats()["nats"]["queued"] == 0, 30,
                   "the new active's outbox emptied")
        time.sleep(1.0)
        self.assertTrue(second.stats()["nats"]["active"])
        self.assertNotEqual(on_second.objects("ALIVE")[-1]["health"], "standby", "active now")
        with urllib.request.urlopen(f"http://127.0.0.1:{second.http_port}/metrics", timeout=10) as reply:
            metrics = reply.read()
        self.assertIn(b"kew_standby_active 1\n", metrics)
        # Every NATS metric in Prometheus' own checker (Debian's prometheus package).
        if shutil.which("promtool") is None:
            self.skipTest("promtool is not installed (Debian prometheus): the NATS metrics were NOT checked")
        result = subprocess.run(["promtool", "check", "metrics"], input=metrics, capture_output=True)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)

        kept = watch(self.nats.url, "--since", "0", "-n", str(len(expected)))
        self.assertEqual(kept, expected, "JetStream holds the run without failure, event for event")
        with self.assertRaises(subprocess.TimeoutExpired):
            watch(self.nats.url, "--since", str(json.loads(expected[-1])["seq"]), "-n", "1", timeout=3)
        self.assertFalse(any('"reason":"restart"' in event for event in kept), "no alert ended by the failover")

        seen_first = on_first.alert_lines()
        self.assertEqual(seen_first, expected[:len(seen_first)], "the active's stream until it died")
        published = int(line.split("published up to seq ")[1].split(";")[0])
        wait_until(lambda: len(on_second.alert_lines()) >= len(expected) - published, 20, "the new active's stream")
        # Its stream continues with the next seq: nothing the dead active had sent, nothing missing.
        self.assertEqual(on_second.alert_lines(), expected[published:])

    def start_pair(self, config=None, standby_ready="hot standby as b"):
        """The active a, then the standby b once its log says `standby_ready`; `config`:
        each one's configuration (by default each reads the feed through its own consumer)."""
        feed_on_the_bus = config is None
        config = config or {name: SERVICE + pair_member(name, [self.nats.url]) for name in "ab"}
        first = self.start(config["a"])
        first.wait_log("a holds the lease active: active")
        second = self.start(config["b"])
        second.wait_log(standby_ready)
        if feed_on_the_bus:
            for kewd in (first, second):
                kewd.wait_log("reading kew.feed.tma through the JetStream consumer")
        return first, second

    def publish(self, lines):
        """Feed lines on the bus, 20 a message."""
        nats_publish(self.nats.port, "kew.feed.tma", [b"".join(lines[i:i + 20]) for i in range(0, len(lines), 20)])

    def test_an_acknowledgement_on_the_active_stays_after_the_takeover(self):
        first, second = self.start_pair()
        lines = self.feed_lines()
        half = lines[:len(lines) // 2]
        self.publish(half)
        for kewd in (first, second):
            kewd.wait_records(len(half))
        self.assertGreater(len(active_alerts(first)), 0, "alerts are open")
        acknowledged = ack_all(first)
        self.assertTrue(acknowledged)
        second.wait_log(f"standby: {len(acknowledged)} alerts acknowledged on the active")
        first.process.kill()
        second.wait_log("active now (hot standby b)", timeout_s=30)
        after = {a["id"]: a for a in active_alerts(second)}
        for alert_id in acknowledged:
            self.assertTrue(after[alert_id]["ack"], f"{alert_id} acknowledged on the active stays so")

    def test_a_subscriber_of_the_standby_gets_every_open_alert_at_the_takeover(self):
        first, second = self.start_pair()
        # A display on the standby's stream and one on its map, connected before any alert.
        on_second = Subscriber(second.alert_port)
        wait_until(lambda: on_second.objects("ALERTS"), 10, "the standby's snapshot")
        map_client = WebSocket(second.http_port)
        self.assertEqual(map_client.status, 101)
        map_client.sock.settimeout(None)
        map_messages = []  # read as they come (pings answered); batches once a tick, 60 s here

        def read_map():
            try:
                while True:
                    map_messages.append(map_client.message())
            except (ConnectionError, OSError):
                pass
        threading.Thread(target=read_map, daemon=True).start()
        self.addCleanup(map_client.close)
        lines = self.feed_lines()
        half = lines[:len(lines) // 2]
        self.publish(half)
        for kewd in (first, second):
            kewd.wait_records(len(half))
        open_alerts = {a["id"]: a["seq"] for a in active_alerts(second)}
        self.assertGreater(len(open_alerts), 0, "alerts are open")
        self.assertEqual(open_alerts, {a["id"]: a["seq"] for a in active_alerts(first)})
        first.process.kill()
        second.wait_log("active now (hot standby b)", timeout_s=30)

        snapshots = wait_until(lambda: len(on_second.objects("ALERTS")) >= 2 and on_second.objects("ALERTS"), 10,
                               "an ALERTS snapshot at the takeover")
        self.assertEqual(len(snapshots), 2)
        self.assertEqual({a["id"]: a["seq"] for a in snapshots[1]["alerts"]}, open_alerts,
                         "every open alert, as its latest event")
        # Before the events that follow: the rest of the feed's.
        rest = lines[len(half):]
        self.publish(rest)
        second.wait_records(len(lines))
        wait_until(lambda: [o for o in on_second.objects("ALERT") if o["seq"] > snapshots[1]["seq"]], 20,
                   "alert events after the takeover")
        stream = on_second.objects()
        at = [i for i, o in enumerate(stream) if o["class"] == "ALERTS"][1]
        self.assertEqual([o for o in stream[:at] if o["class"] == "ALERT" and o["seq"] > snapshots[1]["seq"]], [])
        # The map gets the same snapshot in its next batch (the first holds every track and alert).
        in_batches = wait_until(lambda: [o for m in map_messages[1:] for o in m if o.get("class") == "ALERTS"], 130,
                                "an ALERTS object on the map's WebSocket")
        self.assertEqual({a["id"]: a["seq"] for a in in_batches[0]["alerts"]}, open_alerts)


    def test_a_chain_of_failures_and_restarts_keeps_the_stream_of_the_run_without_failure(self):
        """A active, B standby; SIGKILL A, restart A; SIGKILL B, restart B; SIGKILL A: each
        restarted instance catches up with the pair before it may take over, and JetStream
        holds the run without failure event for event."""
        recording = self.path("tma-long.ndjson")
        generate(recording, "tma", aircraft=150, duration=300, seed=5)
        config = {name: SERVICE + pair_member(name, [self.nats.url]) for name in "ab"}
        kewd = {"a": self.start(config["a"])}
        kewd["a"].wait_log("a holds the lease active: active")
        kewd["b"] = self.start(config["b"])
        for name in "ab":
            kewd[name].wait_log("reading kew.feed.tma through the JetStream consumer")
        expected = offline_alerts(kewd["a"].config_path, recording)
        self.assertGreater(len(expected), 200, "the scenario must keep alerts open through every failure")
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", recording, "--speed", "5"))
        feeder.start()
        takeovers = []

        def fail_over(dead, heir, share):
            # Mid-conflict: a share of the run's events is in the stream when the active dies.
            wait_until(lambda: stream_messages(self.nats.port) >= len(expected) * share, 120, "alerts in the stream")
            kewd[dead].process.kill()
            kewd[dead].process.wait()
            killed = time.monotonic()
            kewd[heir].wait_log(f"active now (hot standby {heir})", timeout_s=30)
            takeovers.append(time.monotonic() - killed)
            kewd[dead] = self.start(config[dead])
            # Back as a standby in step with the pair: only then may it take over.
            kewd[dead].wait_log(f"{dead}: in step with the active", timeout_s=60)

        fail_over("a", "b", 1 / 6)
        fail_over("b", "a", 2 / 6)
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected) * 3 / 6, 120, "alerts in the stream")
        kewd["a"].process.kill()
        killed = time.monotonic()
        kewd["b"].wait_log("active now (hot standby b)", timeout_s=30)
        takeovers.append(time.monotonic() - killed)
        print("\ntakeovers after SIGKILL: " + ", ".join(f"{t:.2f} s" for t in takeovers))
        feeder.join()
        kewd["b"].wait_records(count_lines(recording))
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected), 60, "every event in the stream")
        time.sleep(1.0)
        kept = [line for line in watch(self.nats.url, "--since", "0", "-n", str(stream_messages(self.nats.port)))
                if json.loads(line)["class"] == "ALERT"]
        check_alert_lifecycles(self, kept)
        self.assertEqual(kept, expected, "JetStream holds the run without failure, event for event")


    def test_a_standby_restarted_after_the_feed_dropped_the_origin_continues_the_latest_checkpoint(self):
        """The feed stream keeps 12 s of records and the active writes a checkpoint (of 330
        aircraft: more than one message) every 3 s: the standby, killed early and restarted once the stream no longer holds the
        pair's origin, loads the latest checkpoint, is in step, and takes over when the
        active dies; JetStream holds the run without failure event for event. (Without
        checkpoints, checkpoint_interval_s = 0, the restarted standby is never in step.)"""
        recording = self.path("tma-long.ndjson")
        generate(recording, "tma", aircraft=330, duration=300, seed=5)  # a checkpoint of two parts
        member = {name: SERVICE + pair_member(name, [self.nats.url], nats_keys="checkpoint_interval_s = 3",
                                              input_keys="stream_max_age_s = 12") for name in "ab"}
        first, second = self.start_pair(member)
        for kewd in (first, second):
            kewd.wait_log("reading kew.feed.tma through the JetStream consumer")
        expected = offline_alerts(first.config_path, recording)
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", recording, "--speed", "5"))
        feeder.start()
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected) / 10, 60, "alerts in the stream")
        second.process.kill()
        second.process.wait()
        # The stream has dropped the pair's first records: judging the feed again from the
        # origin is impossible now.
        wait_until(lambda: stream_first_seq(self.nats.port, "KEW_FEED") > 1, 60, "the feed's first records dropped")
        first.wait_log("[nats] checkpoint written to KEW_CHECKPOINTS.active", timeout_s=30)
        second = self.start(member["b"])
        loaded = second.wait_log("the pair's latest checkpoint (written by a)", timeout_s=30)
        state_bytes = int(loaded.split(" bytes of state")[0].rsplit(" ", 1)[1])
        self.assertGreater(state_bytes, 256 * 1024, "a checkpoint of more than one message (256 KiB each)")
        second.wait_log("hot standby: the pipeline continues the checkpoint of a", timeout_s=30)
        second.wait_log("b: in step with the active", timeout_s=60)
        self.assertTrue(second.stats()["nats"]["began_from_checkpoint"])
        self.assertGreater(first.stats()["nats"]["checkpoints_written"], 0)
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected) / 2, 120, "alerts in the stream")
        first.process.kill()
        second.wait_log("active now (hot standby b)", timeout_s=30)
        feeder.join()
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected), 60, "every event in the stream")
        time.sleep(1.0)
        kept = [line for line in watch(self.nats.url, "--since", "0", "-n", str(stream_messages(self.nats.port)))
                if json.loads(line)["class"] == "ALERT"]
        check_alert_lifecycles(self, kept)
        self.assertEqual(kept, expected, "JetStream holds the run without failure, event for event")

    def test_a_host_wide_stall_past_the_lease_leaves_one_speaker(self):
        """A paused virtual machine stops everything at once, nats-server included, and
        resumes everything together: SIGSTOP the server, the active and the standby
        mid-conflict for three lease TTLs, then SIGCONT all three, the server first.
        Whoever holds the lease afterwards speaks (the pair is not left silent), no event
        reaches the subscribers of both instances after the stall, and JetStream holds the
        run without failure."""
        first, second = self.start_pair(standby_ready="b: in step with the active")
        expected = offline_alerts(first.config_path, self.recording)
        subscribers = {"a": Subscriber(first.alert_port), "b": Subscriber(second.alert_port)}
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "4"))
        feeder.start()
        wait_until(lambda: len(subscribers["a"].alert_lines()) >= len(expected) // 4, 60, "alerts from the active")
        host = (self.nats.process, first.process, second.process)
        for process in host:
            process.send_signal(signal.SIGSTOP)
        # Three TTLs (1.5 s each); what was written before the stall is read by now.
        time.sleep(4.5)
        before = {name: len(subscriber.alert_lines()) for name, subscriber in subscribers.items()}
        for process in host:
            process.send_signal(signal.SIGCONT)
        # The holder of the lease speaks again: the stream grows past what the active had
        # sent before the stall (its stream runs ahead of its publications).
        wait_until(lambda: stream_messages(self.nats.port) > before["a"], 30, "publication after the stall")
        feeder.join()
        for kewd in (first, second):
            kewd.wait_records(count_lines(self.recording))
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected), 60, "every event in the stream")
        time.sleep(1.0)  # the last alerts reach the subscribers
        after = {name: [json.loads(line)["seq"] for line in subscriber.alert_lines()[before[name]:]]
                 for name, subscriber in subscribers.items()}
        holders = [kewd for kewd in (first, second) if kewd.stats()["nats"]["active"]]
        print(f"\nafter the stall: {len(after['a'])} alert events from a, {len(after['b'])} from b")
        for name, kewd in (("a", first), ("b", second)):
            for line in kewd.log().splitlines():
                if any(word in line for word in ("renew the lease", "the lease again", "now", "fenced")):
                    print(f"{name}: {line}")
        self.assertEqual(len(holders), 1, "one instance holds the lease")
        self.assertEqual(sorted(set(after["a"]) & set(after["b"])), [], "no event sent by both after the stall")
        result = subprocess.run([KEW_WATCH, "--nats", self.nats.url, "--json", "--since", "0", "-n",
                                 str(len(expected))], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("no longer held the lease", result.stderr, "no message of a stalled holding after another")
        self.assertEqual(result.stdout.splitlines(keepends=True), expected,
                         "JetStream holds the run without failure, event for event")

    def test_an_active_stalled_past_its_lease_sends_nothing_after_the_takeover(self):
        """SIGSTOP the active for three lease TTLs, then SIGCONT: nothing it computes after
        the standby took over reaches its subscribers, the stream or kew-watch."""
        first, second = self.start_pair(standby_ready="b: in step with the active")
        expected = offline_alerts(first.config_path, self.recording)
        on_first = Subscriber(first.alert_port)
        on_second = Subscriber(second.alert_port)
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "4"))
        feeder.start()
        wait_until(lambda: len(on_first.alert_lines()) >= len(expected) // 4, 60, "alerts from the active")
        first.process.send_signal(signal.SIGSTOP)
        stopped = time.monotonic()
        second.wait_log("active now (hot standby b)", timeout_s=30)
        # Three TTLs (1.5 s each) in all; what the stopped active had written is read by now.
        time.sleep(max(0.0, 4.5 - (time.monotonic() - stopped)))
        seen_by_first = len(on_first.alert_lines())
        first.process.send_signal(signal.SIGCONT)
        first.wait_log("standby now", timeout_s=30)
        feeder.join()
        second.wait_records(count_lines(self.recording))
        first.wait_records(count_lines(self.recording))
        wait_until(lambda: stream_messages(self.nats.port) >= len(expected), 60, "every event in the stream")
        time.sleep(1.0)
        self.assertEqual(len(on_first.alert_lines()), seen_by_first, "the stalled active sent nothing after waking")
        self.assertEqual(on_first.objects("ALIVE")[-1]["health"], "standby")
        result = subprocess.run([KEW_WATCH, "--nats", self.nats.url, "--json", "--since", "0", "-n",
                                 str(len(expected))], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("no longer held the lease", result.stderr, "no message of the stalled holding after the takeover")
        kept = result.stdout.splitlines(keepends=True)
        self.assertEqual(kept, expected, "JetStream holds the run without failure, event for event")
        published = int(second.wait_log("active now (hot standby b)").split("published up to seq ")[1].split(";")[0])
        self.assertEqual(on_second.alert_lines(), expected[published:])


    def test_the_bus_away_for_10_s_leaves_the_active_serving_its_other_outputs(self):
        """Every NATS server down for 10 s mid-conflict: the active's TCP stream goes on
        with every event (a lost bus is not a lost lease: nobody can take the key while
        no server answers), the standby stays silent, and when the server is back the
        active keeps the lease and JetStream receives every event once."""
        first, second = self.start_pair({name: SERVICE + BUS_AWAY.format(url=self.nats.url, name=name) for name in "ab"})
        expected = offline_alerts(first.config_path, self.recording)
        on_first = Subscriber(first.alert_port)
        on_second = Subscriber(second.alert_port)
        # Radar delivered to both hosts (multicast in a real centre): each instance is fed.
        feeders = [threading.Thread(target=replay_to, args=(
            f"udp://127.0.0.1:{kewd.input_port('udp')}", self.recording, "--speed", "4")) for kewd in (first, second)]
        for feeder in feeders:
            feeder.start()
        wait_until(lambda: len(on_first.alert_lines()) >= len(expected) // 4, 60, "alerts from the active")
        self.nats.stop()
        stopped = time.monotonic()
        # Past two lease TTLs (1.5 s each) the lease has expired on the server.
        time.sleep(3.0)
        late = len(on_first.alert_lines())
        time.sleep(max(0.0, 10.0 - (time.monotonic() - stopped)))
        during = len(on_first.alert_lines()) - late
        print(f"\n{during} alert events on the active's stream from 3 to 10 s into the outage")
        self.assertGreater(during, 0, "the active's stream went on while the bus was away")
        stats = first.stats()["nats"]
        self.assertTrue(stats["active"] and stats["bus_away"] and not stats["connected"], stats)
        self.assertNotEqual(on_first.objects("ALIVE")[-1]["health"], "standby")
        self.nats.start()
        for feeder in feeders:
            feeder.join()
        first.wait_records(count_lines(self.recording))
        wait_until(lambda: len(on_first.alert_lines()) >= len(expected), 30, "every alert on the active's stream")
        self.assertEqual(on_first.alert_lines(), expected, "the active's stream is the run without failure")
        wait_until(lambda: first.stats()["nats"]["published"] >= len(expected) and first.stats()["nats"]["queued"] == 0,
                   60, "the outbox emptied once the lease was renewed")
        stats = first.stats()["nats"]
        self.assertTrue(stats["active"] and not stats["bus_away"], stats)
        self.assertEqual(stats["dropped"], 0)
        self.assertFalse(second.stats()["nats"]["active"])
        self.assertEqual(on_second.alert_lines(), [], "the standby said nothing")
        self.assertEqual(on_second.objects("ALIVE")[-1]["health"], "standby")
        self.assertNotIn("active now", second.log())
        self.assertIn("still active for the outputs that need no bus", first.log())
        kept = watch(self.nats.url, "--since", "0", "-n", str(len(expected)))
        self.assertEqual(kept, expected, "JetStream holds every event once, in order")

    def test_a_takeover_delivers_each_notification_once(self):
        endpoint = Endpoint()
        self.addCleanup(endpoint.close)
        notify = f"""
[[notify]]
name = "hook"
url = "{endpoint.url}/kew"
backoff_max_s = 1
"""
        first, second = self.start_pair({name: SERVICE + notify + pair_member(name, [self.nats.url]) for name in "ab"})
        expected = offline_alerts(first.config_path, self.recording)
        owed = [e["seq"] for _, e in passing([json.loads(line) for line in expected])]
        on_first = Subscriber(first.alert_port)
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "4"))
        feeder.start()
        # Killed with messages delivered and messages owed, the endpoint refusing the rest.
        wait_until(lambda: len(endpoint.requests()) >= len(owed) // 3, 60, "a third of the messages")
        endpoint.fail_until = time.monotonic() + 3.0
        time.sleep(1.0)
        first.process.kill()
        second.wait_log("active now (hot standby b)", timeout_s=30)
        feeder.join()
        second.wait_records(count_lines(self.recording))
        wait_until(lambda: len(endpoint.requests()) >= len(owed), 60, "every message")
        time.sleep(2.0)
        delivered = [int(r["headers"]["Kew-Seq"]) for r in endpoint.requests()]
        self.assertEqual(delivered, owed, "each event once, in order, across the takeover")
        self.assertEqual([r["body"] for r in endpoint.requests()],
                         [line for line in expected if json.loads(line)["seq"] in set(owed)])
        self.assertTrue(on_first.alert_lines(), "the active spoke before it died")
        self.assertEqual(second.stats()["notify"][0]["queued"], 0)


def active_alerts(kewd):
    with urllib.request.urlopen(f"http://127.0.0.1:{kewd.http_port}/api/alerts", timeout=10) as reply:
        return json.load(reply)["alerts"]


def ack_all(kewd):
    """POST /api/ack {"all": true} as the map does; the ids acknowledged."""
    request = urllib.request.Request(f"http://127.0.0.1:{kewd.http_port}/api/ack", data=b'{"all":true}', headers={
        "Content-Type": "application/json", "X-Kew-Ack": "1", "Origin": f"http://127.0.0.1:{kewd.http_port}"})
    with urllib.request.urlopen(request, timeout=10) as reply:
        return json.load(reply)["acknowledged"]
