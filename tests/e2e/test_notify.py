"""Notifications (design §5.10) from a real kewd to HTTP endpoints on loopback: small
servers in the test that record every request. Every alert event that passes a
notifier's filter arrives once, in order, with its template's body and headers; an
endpoint that fails for 30 s loses and repeats nothing; one that never answers delays
neither the other endpoint nor the stream; events waiting when kewd is killed are
delivered once by the next start. Hot standby's takeover: test_hot_standby.py.

Run by ctest with test_kewd; by hand as test_kewd.py says.
"""

import json
import os
import statistics
import threading
import time
import unittest
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

from kewd_harness import E2eCase, Subscriber, active_at_end, generate, replay_to, wait_until

RANK = {"none": 0, "caution": 1, "warning": 2, "loss": 3}
EVERY_STATE = ("new", "escalated", "updated", "ended")
PEOPLE_STATES = ("new", "escalated", "ended")

SERVICE = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 60
alert_log = "{workdir}/alerts.jsonl"

[[input]]
name = "feed"
format = "ndjson"
transport = "tcp-server"
address = "127.0.0.1:0"
"""

JSON_NOTIFIER = """
[[notify]]
name = "hook"
url = "{url}/kew"
token_file = "{workdir}/hook.token"
backoff_max_s = 2
failing_after_s = 5
"""

NTFY_NOTIFIER = """
[[notify]]
name = "phone"
url = "{url}/kew-alerts"
template = "ntfy"
token_file = "{workdir}/ntfy.token"
min_severity = "warning"
coalesce_s = 0
max_per_minute = 0
"""


class Endpoint:
    """An HTTP server that takes POSTs and records each it took: path, headers, body and
    when it came (time.monotonic). It can refuse with 503 until a moment, or never
    answer at all."""

    def __init__(self):
        self.taken = []
        self.refused = 0
        self.fail_until = 0.0
        self.take_at_most = None  # then 503 for every request
        self.hang = False
        self.lock = threading.Lock()
        self.closing = threading.Event()
        endpoint = self

        class Handler(BaseHTTPRequestHandler):
            protocol_version = "HTTP/1.1"

            def log_message(self, *args):
                pass

            def do_POST(self):
                body = self.rfile.read(int(self.headers.get("Content-Length", "0")))
                if endpoint.hang:
                    endpoint.closing.wait()
                    return
                with endpoint.lock:
                    full = endpoint.take_at_most is not None and len(endpoint.taken) >= endpoint.take_at_most
                if full or time.monotonic() < endpoint.fail_until:
                    with endpoint.lock:
                        endpoint.refused += 1
                    self.send_response(503)
                    self.send_header("Retry-After", "1")
                    self.send_header("Content-Length", "0")
                    self.end_headers()
                    return
                with endpoint.lock:
                    endpoint.taken.append({"path": self.path, "headers": dict(self.headers.items()),
                                           "body": body.decode(), "at": time.monotonic()})
                self.send_response(200)
                self.send_header("Content-Length", "0")
                self.end_headers()

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.server.daemon_threads = True
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    @property
    def url(self):
        return f"http://127.0.0.1:{self.server.server_address[1]}"

    def requests(self):
        with self.lock:
            return list(self.taken)

    def close(self):
        self.closing.set()
        self.server.shutdown()
        self.server.server_close()


def passing(events, min_severity="caution", states=EVERY_STATE):
    """(state, event) for each event a notifier sends, by the rules of design §5.10: an
    alert's events at or above min_severity; escalated when its severity rises above any
    it had or first reaches min_severity; its end when it was announced."""
    followed, out = {}, []
    for e in events:
        serious = RANK[e["severity"]] >= RANK[min_severity]
        if e["state"] == "end":
            f = followed.pop(e["id"], None)
            if (serious if f is None else f["announced"]) and "ended" in states:
                out.append(("ended", e))
            continue
        f = followed.setdefault(e["id"], {"highest": 0, "reached": False, "announced": False})
        before, reached_before = f["highest"], f["reached"]
        f["highest"] = max(before, RANK[e["severity"]])
        if not serious:
            continue
        f["reached"] = True
        if e["state"] == "new":
            state = "new"
        elif not reached_before or RANK[e["severity"]] > before:
            state = "escalated"
        else:
            state = "updated"
        if state in states:
            f["announced"] = True
            out.append((state, e))
    return out


def identity(event):
    """What names an alert event whatever its seq."""
    return event["id"], event["state"], event["t"]


def alert_log_lines(path):
    with open(path) as f:
        return [line for line in f if line.startswith('{"class":"ALERT",')]


class Notify(E2eCase):
    def setUp(self):
        super().setUp()
        self.endpoints = []
        for name, token in (("hook.token", "hook-secret"), ("ntfy.token", "tk_phone")):
            with open(self.path(name), "w") as f:
                f.write(token + "\n")
            os.chmod(self.path(name), 0o600)
        self.recording = self.path("airways.ndjson")
        generate(self.recording, "airways", aircraft=150, duration=240, seed=21)

    def tearDown(self):
        for e in self.endpoints:
            e.close()
        super().tearDown()

    def endpoint(self):
        e = Endpoint()
        self.endpoints.append(e)
        return e

    def config(self, *notifiers):
        return SERVICE.format(workdir=self.workdir) + "".join(
            template.format(url=endpoint.url, workdir=self.workdir) for template, endpoint in notifiers)

    def feed(self, kewd, speed="20"):
        replay_to(f"127.0.0.1:{kewd.input_port('feed')}", self.recording, "--speed", speed)

    def wait_delivered(self, endpoint, n, timeout_s=60.0):
        wait_until(lambda: len(endpoint.requests()) >= n, timeout_s, f"{n} messages at {endpoint.url}")
        time.sleep(1.0)  # anything more would be a message too many
        return endpoint.requests()

    def check_json(self, requests, lines):
        expected = passing([json.loads(line) for line in lines])
        self.assertGreater(len(expected), 10, "the scenario gives too few alert events to test")
        self.assertEqual([r["body"] for r in requests], [line for line in lines
                                                          if any(json.loads(line)["seq"] == e["seq"]
                                                                 for _, e in expected)])
        for r, (_, e) in zip(requests, expected):
            self.assertEqual(r["path"], "/kew")
            self.assertEqual(r["headers"]["Content-Type"], "application/json")
            self.assertEqual(r["headers"]["Authorization"], "Bearer hook-secret")
            self.assertEqual(int(r["headers"]["Kew-Seq"]), e["seq"])
            self.assertEqual(r["headers"]["Kew-Alert"], e["id"])

    def test_every_event_that_passes_arrives_once_in_order_with_its_template(self):
        hook, phone = self.endpoint(), self.endpoint()
        kewd = self.start(self.config((JSON_NOTIFIER, hook), (NTFY_NOTIFIER, phone)))
        self.feed(kewd)
        lines = alert_log_lines(self.path("alerts.jsonl"))
        events = [json.loads(line) for line in lines]
        self.check_json(self.wait_delivered(hook, len(passing(events))), lines)
        expected_phone = passing(events, "warning", PEOPLE_STATES)
        self.assertGreater(len(expected_phone), 3)
        received = self.wait_delivered(phone, len(expected_phone))
        self.assertEqual(len(received), len(expected_phone))
        for r, (state, e) in zip(received, expected_phone):
            h = r["headers"]
            self.assertEqual(int(h["Kew-Seq"]), e["seq"], "in order, each once")
            self.assertEqual(h["Authorization"], "Bearer tk_phone")
            self.assertTrue(h["Content-Type"].startswith("text/plain"))
            names = [p.get("cs") or p["id"] for p in (e["a"], e["b"])]
            word = "ended" if state == "ended" else e["severity"].upper()
            self.assertEqual(h["Title"], f"kew: {word} {names[0]} / {names[1]}")
            expected_priority = 2 if state == "ended" else {"loss": 5, "warning": 4}[e["severity"]]
            self.assertEqual(int(h["Priority"]), expected_priority)
            self.assertIn(h["Tags"], ("rotating_light", "warning", "white_check_mark"))
            self.assertIn(f"Alert {e['number']} opened", r["body"])
        stats = kewd.stats()["notify"]
        self.assertEqual([(n["name"], n["delivered"], n["queued"], n["dropped"]) for n in stats],
                         [("hook", len(passing(events)), 0, 0), ("phone", len(expected_phone), 0, 0)])

    def test_an_endpoint_down_for_30_s_loses_nothing_and_repeats_nothing(self):
        hook = self.endpoint()
        hook.fail_until = time.monotonic() + 30.0
        kewd = self.start(self.config((JSON_NOTIFIER, hook)))
        watcher = Subscriber(kewd.alert_port)
        self.feed(kewd)
        # Failing for longer than failing_after_s: the health says so, the counters too.
        wait_until(lambda: any(a.get("health") == "notify_failing" for a in watcher.objects("ALIVE")), 30,
                   "health notify_failing")
        during = kewd.stats()["notify"][0]
        self.assertTrue(during["failing"])
        self.assertGreater(during["failures"], 0)
        self.assertGreater(during["queued"], 0)
        self.assertEqual(hook.requests(), [])
        lines = alert_log_lines(self.path("alerts.jsonl"))
        self.check_json(self.wait_delivered(hook, len(passing([json.loads(l) for l in lines])), 90), lines)
        self.assertGreater(hook.refused, 3)
        after = kewd.stats()["notify"][0]
        self.assertFalse(after["failing"])
        self.assertEqual(after["queued"], 0)
        wait_until(lambda: watcher.objects("ALIVE")[-1]["health"] != "notify_failing", 10, "healthy again")

    def timed_run(self, with_dead_endpoint):
        """Per event: when the stream sent it and when the live endpoint took it."""
        hook = self.endpoint()
        notifiers = [(JSON_NOTIFIER, hook)]
        if with_dead_endpoint:
            dead = self.endpoint()
            dead.hang = True
            notifiers.append((JSON_NOTIFIER.replace('name = "hook"', 'name = "dead"').replace(
                "backoff_max_s = 2", "timeout_s = 600"), dead))
        kewd = self.start(self.config(*notifiers))
        stream_at = {}

        def read_stream(sub):
            for raw in sub.file:
                line = raw.decode()
                if line.startswith('{"class":"ALERT",'):
                    event = json.loads(line)
                    stream_at.setdefault(event["seq"], (identity(event), time.monotonic()))
        sub = Subscriber(kewd.alert_port, read=False)
        threading.Thread(target=read_stream, args=(sub,), daemon=True).start()
        started = time.monotonic()
        self.feed(kewd)
        lines = alert_log_lines(self.path("alerts.jsonl"))
        requests = self.wait_delivered(hook, len(passing([json.loads(l) for l in lines])))
        self.check_json(requests, lines)
        delays = [r["at"] - stream_at[int(r["headers"]["Kew-Seq"])][1] for r in requests]
        # By identity: the second run's seq continues the first's (the state directory).
        offsets = {key: at - started for key, at in stream_at.values()}
        kewd.kill()
        os.remove(self.path("alerts.jsonl"))
        return delays, offsets

    def test_an_endpoint_that_never_answers_delays_neither_the_other_nor_the_stream(self):
        alone, stream_alone = self.timed_run(False)
        beside, stream_beside = self.timed_run(True)
        print(f"\ndelivery after the stream, median / max: {statistics.median(alone):.3f} / {max(alone):.3f} s alone, "
              f"{statistics.median(beside):.3f} / {max(beside):.3f} s beside an endpoint that never answers")
        # Delivery after the stream: the same with a dead endpoint beside it.
        self.assertLess(statistics.median(beside), statistics.median(alone) + 0.25, (alone, beside))
        self.assertLess(max(beside), 1.0, beside)
        # The stream: each event when the feed's pace brings it, with or without.
        common = sorted(set(stream_alone) & set(stream_beside))
        self.assertGreater(len(common), 10)
        lag = [stream_beside[s] - stream_alone[s] for s in common]
        self.assertLess(max(abs(x) for x in lag), 1.0, lag)

    def test_events_waiting_when_kewd_is_killed_are_delivered_once_by_the_next_start(self):
        hook = self.endpoint()
        config = self.config((JSON_NOTIFIER, hook))
        kewd = self.start(config)
        # Half the events are taken, then the endpoint refuses the rest.
        hook.take_at_most = 40
        self.feed(kewd)
        lines = alert_log_lines(self.path("alerts.jsonl"))
        expected = passing([json.loads(l) for l in lines])
        self.assertGreater(len(expected), 60)
        wait_until(lambda: hook.refused > 0, 30, "the endpoint to refuse")
        self.assertEqual(len(hook.requests()), 40)
        kewd.kill()  # SIGKILL: nothing flushed, nothing said
        outbox = self.path("notify-hook.outbox")
        self.assertTrue(os.path.exists(outbox))
        hook.take_at_most = None
        again = self.start(config)
        again.wait_log("notify hook")
        # The restart ends the alerts the killed run left open: more events, delivered too.
        self.assertTrue(active_at_end(lines), "the scenario leaves alerts open at the kill")
        wait_until(lambda: not active_at_end(alert_log_lines(self.path("alerts.jsonl"))), 10, "the restart's end events")
        lines = alert_log_lines(self.path("alerts.jsonl"))
        self.check_json(self.wait_delivered(hook, len(passing([json.loads(l) for l in lines]))), lines)
        seqs = [int(r["headers"]["Kew-Seq"]) for r in hook.requests()]
        self.assertEqual(len(seqs), len(set(seqs)), "each event once")


if __name__ == "__main__":
    unittest.main()
