"""kewd on a real NATS server (design §5.9): the NATS input, the alerts kept in JetStream
for a subscriber that was away, MQTT through nats-server's own listener, bad input on a
subject, a durable consumer across a restart, late answers to its pull requests and its
deletion, a server that goes away and comes back (for the alert publisher, and for two
instances reading a live feed through their durable consumers: the backlog judged at its
own times, design §4.1) and zones across machines (three instances, each serving a band of
longitudes, together equal to one). Hot standby has its own module, test_hot_standby.

Run by ctest with a real `nats-server` (Debian's, with JetStream) and `mosquitto_sub`;
by hand: KEWD=... KEW_REPLAY=... KEW_GEN=... KEW_WATCH=... python3 -m unittest test_nats -v
"""

import json
import shutil
import signal
import subprocess
import threading
import time
import unittest
import urllib.request

from kewd_harness import (KEW_WATCH, NATS_SERVER, E2eCase, NatsServer, Subscriber, active_at_end, count_lines, generate,
                          nats_next_message, nats_next_reply_subject, nats_publish, nats_request, offline_alerts,
                          replay_to, wait_until)

# The live tick never fires during a test (as in the harness's SERVICE): the stream equals the offline run.
SERVICE = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 60
subscriber_queue = 20000
"""

NATS_OUTPUT = """
[nats]
url = "{url}"
"""

NATS_INPUT = """
[[input]]
name = "bus"
format = "ndjson"
transport = "nats"
address = "kew.feed.tma"
"""

DURABLE = """durable = "kewd_e2e"
stream = "KEW_FEED"
"""

UDP_INPUT = """
[[input]]
name = "udp"
format = "ndjson"
transport = "udp"
address = "127.0.0.1:0"
"""


def watch(url, *args, timeout=60):
    """kew-watch --nats URL --json ARGS: its JSON lines."""
    result = subprocess.run([KEW_WATCH, "--nats", url, "--json", *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, timeout=timeout)
    assert result.returncode == 0, result.stderr
    return result.stdout.splitlines(keepends=True)


class NatsCase(E2eCase):
    """The harness's E2eCase (a work directory, kewd processes) with a NATS server and helper
    processes of its own."""

    def setUp(self):
        if shutil.which(NATS_SERVER) is None:
            self.skipTest(f"{NATS_SERVER} is not installed (Debian nats-server): NATS NOT checked")
        super().setUp()
        self.nats = NatsServer(self.workdir)
        self.processes = []
        self.recording = self.path("tma.ndjson")
        generate(self.recording, "tma", aircraft=150, duration=120, seed=3)

    def tearDown(self):
        for p in self.processes:
            if p.poll() is None:
                p.kill()
                p.wait()
            if p.stdout:
                p.stdout.close()
        self.nats.stop()
        super().tearDown()

    def feed_lines(self):
        with open(self.recording, "rb") as f:
            return [line for line in f if line.strip() and not line.startswith(b"#")]


class NatsInputAndOutput(NatsCase):
    def test_nats_input_gives_the_file_alerts_on_the_stream_jetstream_and_mqtt(self):
        kewd = self.start(SERVICE + NATS_OUTPUT.format(url=self.nats.url) + "tracks_interval_s = 1\n"
                          + NATS_INPUT + DURABLE)
        expected = offline_alerts(kewd.config_path, self.recording)
        self.assertGreater(len(expected), 100)
        # Status and track snapshots, published and not kept.
        self.assertEqual(json.loads(nats_next_message(self.nats.port, "kew.status"))["class"], "ALIVE")
        self.assertEqual(json.loads(nats_next_message(self.nats.port, "kew.tracks"))["class"], "TRACKS")
        kewd.wait_log("reading kew.feed.tma through the JetStream consumer kewd_e2e")
        reader = Subscriber(kewd.alert_port)
        if shutil.which("mosquitto_sub") is None:
            self.skipTest("mosquitto_sub is not installed (Debian mosquitto-clients): MQTT NOT checked")
        mqtt = subprocess.Popen(["mosquitto_sub", "-h", "127.0.0.1", "-p", str(self.nats.mqtt_port), "-v",
                                 "-t", "kew/alerts/#", "-t", "kew/probe"], stdout=subprocess.PIPE, text=True)
        self.processes.append(mqtt)
        received = []
        threading.Thread(target=lambda: received.extend(mqtt.stdout), daemon=True).start()
        # mosquitto_sub says nothing once subscribed: a probe published on NATS until it
        # arrives over MQTT says it is.
        wait_until(lambda: nats_publish(self.nats.port, "kew.probe", [b"probe"]) or time.sleep(0.2)
                   or received, 20, "the MQTT subscriber")
        replay_to(f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "40")
        kewd.wait_records(count_lines(self.recording))
        wait_until(lambda: len(reader.alert_lines()) >= len(expected), 30, "every alert")
        self.assertEqual(reader.alert_lines(), expected, "the NATS input gives the file's alerts")

        kept = watch(self.nats.url, "--since", "0", "-n", str(len(expected)))
        self.assertEqual(kept, expected, "JetStream keeps every alert event, in order")

        wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected), 20, "every event published")
        wait_until(lambda: len(received) >= len(expected) + 1, 20, "every event over MQTT")
        time.sleep(0.5)
        mqtt.terminate()
        mqtt.wait(timeout=10)
        received = [line.rstrip("\n") for line in received if not line.startswith("kew/probe ")]
        self.assertEqual(len(received), len(expected), "MQTT subscribers receive every alert event")
        for line, alert in zip(received, expected):
            topic, _, payload = line.partition(" ")
            self.assertRegex(topic, r"^kew/alerts/[NS]\d\d_\dE\d\d\d_\d$")  # kew.alerts.<zone>
            self.assertEqual(payload + "\n", alert)
        stats = kewd.stats()
        self.assertEqual(stats["nats"]["dropped"], 0)
        with urllib.request.urlopen(f"http://127.0.0.1:{kewd.http_port}/metrics", timeout=10) as reply:
            metrics = reply.read().decode()
        self.assertIn(f"kew_nats_published_total {stats['nats']['published']}\n", metrics)
        self.assertIn("kew_nats_connected 1\n", metrics)
        self.assertTrue(stats["nats"]["connected"])
        self.assertEqual(stats["inputs"][0]["reports"], count_lines(self.recording))
        self.assertEqual(kewd.terminate(), 0)

    def test_a_subscriber_away_for_30_s_reads_every_alert_it_missed(self):
        # A plain subscription (no durable) feeds kewd here.
        kewd = self.start(SERVICE + NATS_OUTPUT.format(url=self.nats.url) + NATS_INPUT)
        expected = offline_alerts(kewd.config_path, self.recording)
        kewd.wait_log("input bus: subscribed to kew.feed.tma")
        first = subprocess.Popen([KEW_WATCH, "--nats", self.nats.url, "--json"], stdout=subprocess.PIPE, text=True)
        self.processes.append(first)
        time.sleep(1.0)  # subscribed before the first alert
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "2.5"))
        feeder.start()
        lines = []
        wait_until(lambda: lines.append(first.stdout.readline()) or len(lines) >= 20, 30, "the first alerts")
        first.kill()
        first.wait()
        seen = [json.loads(line) for line in lines]
        last_seq = seen[-1]["seq"]
        time.sleep(30)  # away
        feeder.join()
        kewd.wait_records(count_lines(self.recording))
        wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected), 20, "every event published")
        missed = watch(self.nats.url, "--since", str(last_seq), "-n", str(len(expected) - len(seen)))
        self.assertEqual(lines + missed, expected, "what it saw and what it missed are every event, once")

    def test_since_shows_the_end_of_an_alert_opened_before_it(self):
        kewd = self.start(SERVICE + NATS_OUTPUT.format(url=self.nats.url) + NATS_INPUT + DURABLE)
        expected = offline_alerts(kewd.config_path, self.recording)
        kewd.wait_log("reading kew.feed.tma through the JetStream consumer kewd_e2e")
        replay_to(f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", self.recording, "--speed", "40")
        kewd.wait_records(count_lines(self.recording))
        wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected), 20, "every event published")
        # The reader saw every event up to the one before the first End: alerts are open
        # across it, and one of them ends right after it.
        events = [json.loads(line) for line in expected]
        middle = [e["state"] for e in events].index("end") - 1
        opened = {e["id"] for e in events[:middle + 1] if e["state"] == "new"}
        ended = {e["id"] for e in events[:middle + 1] if e["state"] == "end"}
        open_across = opened - ended
        later = [e for e in events[middle + 1:] if e["id"] in open_across]
        self.assertTrue([e for e in later if e["state"] == "end"], "alerts open at the seq end after it")
        self.assertTrue([e for e in later if e["state"] == "update"], "alerts open at the seq change after it")
        try:
            missed = watch(self.nats.url, "--since", str(events[middle]["seq"]), "-n", str(len(events) - middle - 1),
                           timeout=30)
        except subprocess.TimeoutExpired as e:  # fewer events shown than kept: which ones, below
            output = e.stdout or ""
            missed = (output.decode() if isinstance(output, bytes) else output).splitlines(keepends=True)
        self.assertEqual(missed, expected[middle + 1:], "every event after the seq, ends and updates included")


class NatsFaults(NatsCase):
    def test_garbage_on_the_subject_is_counted_and_refused(self):
        # No [nats] table: the input names its server.
        kewd = self.start(SERVICE + NATS_INPUT + f'nats_url = "{self.nats.url}"\n')
        kewd.wait_log("input bus: subscribed to kew.feed.tma")
        good = self.feed_lines()[:200]
        nats_publish(self.nats.port, "kew.feed.tma",
                     [b"\x00\xff garbage", b'{"t":1714400000,"id":', bytes(range(256)) * 4]
                     + [b"".join(good[i:i + 10]) for i in range(0, len(good), 10)])
        kewd.wait_records(len(good))
        stats = kewd.stats()
        bus = stats["inputs"][0]
        self.assertEqual(bus["reports"], len(good), "every good record after the garbage is taken")
        self.assertGreaterEqual(sum(bus["rejected"].values()), 3, bus)
        self.assertTrue(kewd.running())
        self.assertIn("rejected", kewd.log())

    def test_a_durable_consumer_resumes_where_kewd_stopped(self):
        config = SERVICE + NATS_INPUT + f'nats_url = "{self.nats.url}"\n' + DURABLE
        kewd = self.start(config)
        kewd.wait_log("reading kew.feed.tma through the JetStream consumer kewd_e2e")
        lines = self.feed_lines()
        half = len(lines) // 2
        nats_publish(self.nats.port, "kew.feed.tma", [b"".join(lines[i:i + 20]) for i in range(0, half, 20)])
        kewd.wait_records(half)
        self.assertEqual(kewd.terminate(), 0)
        # Published while kewd is down: kept by JetStream, read by the next run.
        nats_publish(self.nats.port, "kew.feed.tma", [b"".join(lines[i:i + 20]) for i in range(half, len(lines), 20)])
        again = self.start(config)
        again.wait_records(len(lines) - half)
        time.sleep(1.0)
        self.assertEqual(again.stats()["records"], len(lines) - half, "each message read once, by one run")

    def test_pull_answers_arriving_late_are_taken_once_each_in_order(self):
        """Answers to pull requests kewd no longer waits for (sent before an outage and
        flushed at reconnection, or expired on its clock before the server's) arrive in
        its inbox before and during its next read, any number at a time: each message is
        taken once, in the stream's order, and kewd lives on. Here kewd is paused while
        its own requests expire, 200 messages (more than half of one read's) are answered
        into its inbox, and a second late request keeps answering while it reads."""
        config = SERVICE + NATS_INPUT + f'nats_url = "{self.nats.url}"\n' + DURABLE
        kewd = self.start(config)
        kewd.wait_log("reading kew.feed.tma through the JetStream consumer kewd_e2e")
        expected = offline_alerts(kewd.config_path, self.recording)
        next_subject = "$JS.API.CONSUMER.MSG.NEXT.KEW_FEED.kewd_e2e"
        inbox = nats_next_reply_subject(self.nats.port, next_subject)
        reader = Subscriber(kewd.alert_port)
        lines = self.feed_lines()
        kewd.process.send_signal(signal.SIGSTOP)
        try:
            time.sleep(0.6)  # its waiting requests expire on the server
            nats_publish(self.nats.port, "kew.feed.tma", lines[:200])
            nats_publish(self.nats.port, next_subject, [b'{"batch":200,"expires":5000000000}'], reply=inbox)
            nats_publish(self.nats.port, next_subject, [b'{"batch":100000,"expires":30000000000}'], reply=inbox)
            time.sleep(0.3)
        finally:
            kewd.process.send_signal(signal.SIGCONT)
        # Bursts of 200 answered at once into the inbox: a read that takes a whole batch
        # leaves the rest of a burst waiting for the next.
        for i in range(200, len(lines), 200):
            nats_publish(self.nats.port, "kew.feed.tma", lines[i:i + 200])
            time.sleep(0.05)
        wait_until(lambda: not kewd.running() or consumer_done(self.nats.port, "kewd_e2e"), 120,
                   "kewd to read the stream")
        self.assertTrue(kewd.running(), kewd.log())
        wait_until(lambda: len(reader.alert_lines()) >= len(expected), 30, "every alert on the stream")
        stats = kewd.stats()
        self.assertEqual(stats["records"], len(lines), "each message taken once")
        self.assertEqual(stats["accepted"], len(lines), stats["rejected"])
        self.assertEqual(reader.alert_lines(), expected, "in the stream's order: the alerts of the file")
        self.assertEqual(kewd.terminate(), 0)

    def test_a_deleted_consumer_is_made_again_after_the_last_message_taken(self):
        config = SERVICE + NATS_INPUT + f'nats_url = "{self.nats.url}"\n' + DURABLE
        kewd = self.start(config)
        kewd.wait_log("reading kew.feed.tma through the JetStream consumer kewd_e2e")
        lines = self.feed_lines()
        half = len(lines) // 40 * 20
        nats_publish(self.nats.port, "kew.feed.tma", [b"".join(lines[i:i + 20]) for i in range(0, half, 20)])
        kewd.wait_records(half)
        # nats-server 2.9 refuses to delete a consumer while it writes an acknowledgement
        # to its files ("unlinkat ...: directory not empty", JetStream error 10051): the
        # operator deletes it once kewd has acknowledged what it read, and tries again
        # while the server still answers that.
        wait_until(lambda: consumer_done(self.nats.port, "kewd_e2e"), 10, "the first half acknowledged")
        # An operator deletes the consumer while kewd runs (nats consumer rm KEW_FEED kewd_e2e).
        def delete_consumer():
            reply = json.loads(nats_request(self.nats.port, "$JS.API.CONSUMER.DELETE.KEW_FEED.kewd_e2e"))
            busy = reply.get("error", {}).get("err_code") == 10051
            return None if busy else reply
        reply = wait_until(delete_consumer, 10, "the server's files of the consumer written")
        self.assertTrue(reply.get("success"), reply)
        nats_publish(self.nats.port, "kew.feed.tma", [b"".join(lines[i:i + 20]) for i in range(half, len(lines), 20)])
        kewd.wait_records(len(lines))
        time.sleep(1.0)
        self.assertEqual(kewd.stats()["records"], len(lines), "each message read once")
        self.assertIn("is gone: making it again from message", kewd.log())

    def test_a_server_away_and_back_loses_no_alert(self):
        kewd = self.start(SERVICE + NATS_OUTPUT.format(url=self.nats.url) + UDP_INPUT)
        expected = offline_alerts(kewd.config_path, self.recording)
        wait_until(lambda: kewd.stats()["nats"]["connected"], 10, "kewd connected to NATS")
        feeder = threading.Thread(target=replay_to, args=(
            f"udp://127.0.0.1:{kewd.input_port('udp')}", self.recording, "--speed", "10"))
        feeder.start()
        time.sleep(3)
        self.nats.stop()
        wait_until(lambda: not kewd.stats()["nats"]["connected"], 10, "kewd to see the server gone")
        time.sleep(3)
        self.nats.start()
        feeder.join()
        kewd.wait_records(count_lines(self.recording))
        wait_until(lambda: kewd.stats()["nats"]["published"] >= len(expected) and kewd.stats()["nats"]["queued"] == 0,
                   60, "the outbox emptied")
        stats = kewd.stats()["nats"]
        self.assertGreaterEqual(stats["disconnects"], 1)
        self.assertEqual(stats["dropped"], 0)
        kept = watch(self.nats.url, "--since", "0", "-n", str(len(expected)))
        self.assertEqual(kept, expected, "every alert event in JetStream once, in order")
        # Nothing after the last event: a retried publication kept twice would be there.
        with self.assertRaises(subprocess.TimeoutExpired):
            watch(self.nats.url, "--since", str(json.loads(expected[-1])["seq"]), "-n", "1", timeout=3)

    def test_a_deleted_stream_is_created_again_and_keeps_every_later_alert(self):
        kewd = self.start(SERVICE + NATS_OUTPUT.format(url=self.nats.url) + UDP_INPUT)
        expected = offline_alerts(kewd.config_path, self.recording)
        reader = Subscriber(kewd.alert_port)
        wait_until(lambda: kewd.stats()["nats"]["connected"], 10, "kewd connected to NATS")
        feeder = threading.Thread(target=replay_to, args=(
            f"udp://127.0.0.1:{kewd.input_port('udp')}", self.recording, "--speed", "10"))
        feeder.start()
        wait_until(lambda: kewd.stats()["nats"]["published"] >= 10, 30, "the first events published")
        # An operator deletes the stream while kewd runs (nats stream rm KEW_ALERTS).
        reply = json.loads(nats_request(self.nats.port, "$JS.API.STREAM.DELETE.KEW_ALERTS"))
        self.assertTrue(reply.get("success"), reply)
        deleted_after = len(reader.alert_lines())
        feeder.join()
        kewd.wait_records(count_lines(self.recording))
        wait_until(lambda: len(reader.alert_lines()) >= len(expected), 30, "every alert on the stream")
        wait_until(lambda: kewd.stats()["nats"]["queued"] == 0, 30, "the outbox emptied")
        self.assertEqual(kewd.stats()["nats"]["dropped"], 0)
        # The stream again, holding every event from (at the latest) the deletion on, in order.
        info = json.loads(nats_request(self.nats.port, "$JS.API.STREAM.INFO.KEW_ALERTS"))
        kept = info["state"]["messages"]
        self.assertGreaterEqual(kept, len(expected) - deleted_after, info)
        self.assertLessEqual(kept, len(expected))
        again = watch(self.nats.url, "--since", "0", "-n", str(kept))
        self.assertEqual(again, expected[len(expected) - kept:])
        self.assertIn("no stream takes it: creating the stream again", kewd.log())


# The live tick at its work (every 3 s; kew-replay's records at speed 1 come every few
# tens of ms, so it never moves the clock while the feed flows), and a lateness bound of
# 5 s, half the outage, so that a clock moved on by the outage's wall time makes the
# backlog too late whatever the tick's phase.
LIVE_FEED = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 3
subscriber_queue = 20000
record_file = "{record_file}"

[tracks]
max_lateness_s = 5.0
max_time_jump_s = 5.0
""" + NATS_INPUT + """nats_url = "{url}"
durable = "kewd_{name}"
stream = "KEW_FEED"
"""


class FeedOutage(NatsCase):
    def test_two_instances_judge_the_backlog_of_a_10_s_outage_at_its_own_times_and_stay_identical(self):
        recording = self.path("tma60.ndjson")
        generate(recording, "tma", aircraft=150, duration=60, seed=3)
        instances = {}
        for name in ("a", "b"):
            kewd = self.start(LIVE_FEED.format(url=self.nats.url, name=name,
                                               record_file=self.path(f"records_{name}.ndjson")))
            kewd.wait_log("reading kew.feed.tma through the JetStream consumer")
            instances[name] = (kewd, Subscriber(kewd.alert_port))
        a, on_a = instances["a"]
        # A real-time feed; kew-replay's NATS client keeps what it publishes while the
        # server is away and sends it once it reconnects (a producer that buffers).
        feeder = threading.Thread(target=replay_to, args=(
            f"nats://127.0.0.1:{self.nats.port}/kew.feed.tma", recording, "--speed", "1"))
        feeder.start()
        wait_until(lambda: len(active_at_end(on_a.alert_lines())) >= 3, 40, "conflicts open")
        before_outage = on_a.alert_lines()
        open_at_outage = set(active_at_end(before_outage))
        self.nats.stop()
        time.sleep(10)
        self.nats.start()
        feeder.join()
        for name, (kewd, _) in instances.items():
            wait_until(lambda: consumer_done(self.nats.port, f"kewd_{name}"), 180, f"kewd {name} to read the stream")
        time.sleep(1.0)  # the last alerts reach the subscribers
        stats = {name: kewd.stats() for name, (kewd, _) in instances.items()}
        for name, (kewd, _) in instances.items():
            self.assertEqual(kewd.terminate(), 0)
        for name, (_, subscriber) in instances.items():
            subscriber.wait_closed()

        for name in instances:
            self.assertGreaterEqual(stats[name]["inputs"][0]["connections"], 2, "the server did go away")
            self.assertNotIn("too_late", stats[name]["rejected"], f"kewd {name}: the backlog is not too late")
            self.assertEqual(stats[name]["accepted"], stats[name]["records"], f"kewd {name}: {stats[name]['rejected']}")
        # What reached the stream (a message in flight when the server stopped may not
        # have), as each instance took it: the same records in the same order.
        with open(self.path("records_a.ndjson")) as f:
            records_a = f.read()
        with open(self.path("records_b.ndjson")) as f:
            self.assertEqual(f.read(), records_a, "both instances read the same records")
        with open(self.path("pipeline.toml"), "w") as f:
            f.write("[tracks]\nmax_lateness_s = 5.0\nmax_time_jump_s = 5.0\n")
        expected = offline_alerts(self.path("pipeline.toml"), self.path("records_a.ndjson"))
        self.assertGreater(len(expected), 100)
        last_t = max(json.loads(line)["t"] for line in records_a.splitlines() if line.startswith("{"))

        def judged_from_records(lines):
            """The events of the records: after the last one, the live tick moves the clock."""
            return [line for line in lines if json.loads(line)["t"] <= last_t]
        alerts_a = judged_from_records(on_a.alert_lines())
        alerts_b = judged_from_records(instances["b"][1].alert_lines())
        self.assertEqual(alerts_a, alerts_b, "two instances fed by one stream send the same events")
        self.assertEqual(alerts_a, expected, "the run without an outage, event for event")
        dropped = [e for e in map(json.loads, alerts_a) if e.get("reason") == "track_dropped"]
        self.assertEqual(dropped, [], "no track dropped by the outage")
        after_outage = {json.loads(line)["id"] for line in alerts_a[len(before_outage):]}
        self.assertTrue(open_at_outage & after_outage, "a conflict open across the outage goes on after it")
        for name, (_, subscriber) in instances.items():
            healths = [alive["health"] for alive in subscriber.objects("ALIVE")]
            self.assertIn("feed_unreachable", healths, f"kewd {name} said its feed was unreachable")
            self.assertEqual(healths[-1], "healthy", f"kewd {name} is healthy again")


def consumer_done(port, durable):
    """The JetStream consumer `durable` of KEW_FEED has delivered every message and has
    every one acknowledged (kewd acknowledges a batch once decoded)."""
    try:
        info = json.loads(nats_request(port, f"$JS.API.CONSUMER.INFO.KEW_FEED.{durable}"))
    except (OSError, AssertionError):
        return False
    return info.get("num_pending") == 0 and info.get("num_ack_pending") == 0


def stream_messages(port, stream="KEW_ALERTS"):
    """Messages held by a JetStream stream (0 before it exists)."""
    info = json.loads(nats_request(port, f"$JS.API.STREAM.INFO.{stream}"))
    return info.get("state", {}).get("messages", 0)


def stream_first_seq(port, stream):
    """The sequence of the first message a JetStream stream holds (0 before it exists)."""
    info = json.loads(nats_request(port, f"$JS.API.STREAM.INFO.{stream}"))
    return info.get("state", {}).get("first_seq", 0)


def check_alert_lifecycles(case, alert_lines):
    """Every id begins with its "new" and has no event after its "end"; no pair of
    aircraft has two alerts open at once; seq grows by one."""
    open_by_pair = {}
    state_by_id = {}
    previous_seq = None
    for line in alert_lines:
        event = json.loads(line)
        if previous_seq is not None:
            case.assertEqual(event["seq"], previous_seq + 1, line)
        previous_seq = event["seq"]
        pair = tuple(sorted((event["a"]["id"], event["b"]["id"])))
        known = state_by_id.get(event["id"])
        if event["state"] == "new":
            case.assertIsNone(known, f"a second new: {line}")
            case.assertNotIn(pair, open_by_pair, f"the pair has two open alerts: {line}")
            open_by_pair[pair] = event["id"]
        else:
            case.assertEqual(known, "open", f"an {event['state']} of an alert not open: {line}")
        if event["state"] == "end":
            del open_by_pair[pair]
            state_by_id[event["id"]] = "ended"
        else:
            state_by_id[event["id"]] = "open"


ZONE_SHARE = """
[projection]
serve_west_deg = {west}
serve_east_deg = {east}

[nats]
url = "{url}"

[[input]]
name = "bus"
format = "ndjson"
transport = "nats"
address = "kew.feed.world"
durable = "kewd_{name}"
stream = "KEW_WORLD"
"""


def without_stream_numbers(line):
    """An ALERT line as every instance writes it: seq and alert numbers are each stream's own."""
    event = json.loads(line)
    event.pop("seq")
    event.pop("number")
    return json.dumps(event, sort_keys=True)


class ZonesAcrossMachines(NatsCase):
    def test_three_instances_owning_different_zones_give_the_single_process_alerts(self):
        world = self.path("global.ndjson")
        generate(world, "global", aircraft=3000, duration=300, seed=4)
        bands = {"west": (-180, -60), "middle": (-60, 60), "east": (60, 180)}
        instances = []
        for name, (west, east) in bands.items():
            kewd = self.start(SERVICE + ZONE_SHARE.format(west=west, east=east, url=self.nats.url, name=name))
            kewd.wait_log("reading kew.feed.world through the JetStream consumer")
            instances.append(kewd)
        with open(self.path("single.toml"), "w") as f:
            f.write("")  # the same pipeline tables, every zone
        whole = offline_alerts(self.path("single.toml"), world)
        self.assertGreater(len(whole), 100)
        # The feed is published once; every instance reads it all.
        replay_to(f"nats://127.0.0.1:{self.nats.port}/kew.feed.world", world, "--max-speed")
        records = count_lines(world)
        published = 0
        for kewd in instances:
            kewd.wait_records(records, timeout_s=120)
        wait_until(lambda: sum(k.stats()["nats"]["published"] for k in instances) >= len(whole), 30,
                   "every instance's events published")
        for kewd in instances:
            stats = kewd.stats()
            self.assertEqual(stats["nats"]["queued"], 0)
            published += stats["nats"]["published"]
        self.assertEqual(published, len(whole), "no pair twice, none missing")
        union = watch(self.nats.url, "--since", "0", "-n", str(len(whole)), timeout=120)
        self.assertEqual(sorted(map(without_stream_numbers, union)), sorted(map(without_stream_numbers, whole)),
                         "together the single process's alerts, ids and all")


if __name__ == "__main__":
    unittest.main()
