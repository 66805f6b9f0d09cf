"""kewd polling an HTTP(S) server for aircraft.json (design §5.7, `transport = "http"`): a
loopback server serving changing snapshots as tar1090 serves /data/aircraft.json (ETag,
Last-Modified, gzip), over plain HTTP and over TLS with a test certificate; the server
going away and coming back; an answer too large; API keys and OAuth2 tokens from files.

Run by ctest; by hand: KEWD=... KEW_REPLAY=... python3 -m unittest test_http_poll -v
"""

import gzip
import http.server
import json
import os
import socket
import ssl
import subprocess
import threading
import time
import urllib.request

from kewd_harness import KEWD, KEW_REPLAY, E2eCase, Subscriber, wait_until

HISTORY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "text",
                       "aircraft_json_history.json")

# The live tick and ALIVE at their defaults (1 s); a feed silent for 3 s is stale.
SERVICE = """
[service]
alert_listen = "127.0.0.1:0"
alert_log = "{workdir}/alerts.jsonl"

[tracks]
timeout_s = 3

[http]
listen = "127.0.0.1:0"
"""

POLL = """
[[input]]
name = "receiver"
format = "{format}"
transport = "http"
address = "{url}"
poll_interval_s = 0.1
reconnect_min_s = 0.2
reconnect_max_s = 0.5
"""


def snapshots():
    return [line.encode() for line in open(HISTORY, encoding="utf-8") if line.strip()]


def opensky_states(document):
    """An aircraft.json snapshot as OpenSky's /api/states/all answers it: state vectors,
    SI units, the position's time in whole seconds."""
    snapshot = json.loads(document)
    states = []
    for a in snapshot["aircraft"]:
        t = int(snapshot["now"] - a["seen_pos"])
        states.append([a["hex"], a["flight"], "United States", t, int(snapshot["now"]), a["lon"], a["lat"],
                       round(a["alt_baro"] * 0.3048, 2), False, round((a["gs"] or 0) * 1852 / 3600, 2),
                       a["track"], 0.0, None, None, "1200", False, 0])
    return json.dumps({"time": int(snapshot["now"]), "states": states}).encode()


class SnapshotServer:
    """One document at every path, replaced by set(); answers as a web server serves a
    static file: ETag and Last-Modified, 304 to a matching If-None-Match, gzip when the
    client accepts it. Counts what it served; may demand a header, serve a token
    endpoint (POST /token) and insist on the bearer tokens it gave."""

    def __init__(self, port=0, tls=None, require=None, tokens=False):
        self.lock = threading.Lock()
        self.body = b"{}"
        self.version = 0
        self.served = {}          # version -> 200 answers
        self.not_modified = 0
        self.gzipped = 0
        self.requests = []        # the headers of each GET, lower-case names
        self.require = require or {}
        self.tokens = tokens
        self.issued = []          # bearer tokens given out
        self.revoked = set()
        self.token_requests = []  # the form bodies POSTed to /token
        self.raw = None           # (headers, body) served instead of the document
        self.refuse_for_s = None  # the next GET refused 429, asking to wait this long
        self.get_times = []       # time.monotonic() of each GET
        server = self

        self.connections = set()

        class Handler(http.server.BaseHTTPRequestHandler):
            protocol_version = "HTTP/1.1"

            def setup(self):
                super().setup()
                with server.lock:
                    server.connections.add(self.connection)

            def log_message(self, *args):
                pass

            def do_POST(self):
                length = int(self.headers.get("Content-Length", "0"))
                form = self.rfile.read(length).decode()
                with server.lock:
                    server.token_requests.append(form)
                    token = f"token-{len(server.issued) + 1}"
                    server.issued.append(token)
                body = json.dumps({"access_token": token, "expires_in": 1800, "token_type": "Bearer"}).encode()
                self.send_response(200)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def do_GET(self):
                headers = {k.lower(): v for k, v in self.headers.items()}
                with server.lock:
                    server.requests.append(headers)
                    server.get_times.append(time.monotonic())
                    body, version, raw = server.body, server.version, server.raw
                    refuse_for_s, server.refuse_for_s = server.refuse_for_s, None
                if refuse_for_s is not None:
                    # As OpenSky answers once a day's credits are spent.
                    return self.answer(429, b"Too many requests",
                                       {"X-Rate-Limit-Retry-After-Seconds": str(refuse_for_s)})
                for name, value in server.require.items():
                    if headers.get(name) != value:
                        return self.answer(403, b"forbidden")
                if server.tokens:
                    token = headers.get("authorization", "").removeprefix("Bearer ")
                    if token not in server.issued or token in server.revoked:
                        return self.answer(401, b"unauthorised")
                if raw:
                    return self.raw_answer(*raw)
                etag = f'"v{version}"'
                if headers.get("if-none-match") == etag:
                    with server.lock:
                        server.not_modified += 1
                    self.send_response(304)
                    self.send_header("ETag", etag)
                    self.end_headers()
                    return
                extra = {"ETag": etag, "Last-Modified": self.date_time_string(time.time())}
                if "gzip" in headers.get("accept-encoding", ""):
                    body = gzip.compress(body)
                    extra["Content-Encoding"] = "gzip"
                    with server.lock:
                        server.gzipped += 1
                with server.lock:
                    server.served[version] = server.served.get(version, 0) + 1
                self.answer(200, body, extra)

            def answer(self, status, body, extra=None):
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(body)))
                for name, value in (extra or {}).items():
                    self.send_header(name, value)
                self.end_headers()
                self.wfile.write(body)

            def raw_answer(self, headers, chunks):
                self.send_response(200)
                for name, value in headers.items():
                    self.send_header(name, value)
                self.end_headers()
                try:
                    for chunk in chunks():
                        self.wfile.write(chunk)
                except (BrokenPipeError, ConnectionResetError, ssl.SSLError):
                    pass
                self.close_connection = True

        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", port), Handler)
        self.httpd.daemon_threads = True
        if tls:
            context = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
            context.load_cert_chain(*tls)
            self.httpd.socket = context.wrap_socket(self.httpd.socket, server_side=True)
        self.port = self.httpd.server_address[1]
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)
        self.thread.start()

    def set(self, body):
        with self.lock:
            self.body = body
            self.version += 1
            return self.version

    def served_version(self, version):
        with self.lock:
            return self.served.get(version, 0)

    def stop(self):
        """Gone: the listening socket closed, and the connections kept alive cut."""
        self.httpd.shutdown()
        self.httpd.server_close()
        with self.lock:
            for connection in self.connections:
                try:
                    connection.shutdown(socket.SHUT_RDWR)
                except OSError:
                    pass


def test_certificate(directory):
    """A self-signed certificate for 127.0.0.1 and localhost (openssl), and its key."""
    cert, key = os.path.join(directory, "cert.pem"), os.path.join(directory, "key.pem")
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", key, "-out", cert,
                    "-days", "2", "-subj", "/CN=localhost", "-addext", "subjectAltName=IP:127.0.0.1,DNS:localhost"],
                   check=True, capture_output=True)
    return cert, key


class HttpPoll(E2eCase):
    def setUp(self):
        super().setUp()
        self.servers = []

    def tearDown(self):
        for s in self.servers:
            s.stop()
        super().tearDown()

    def serve(self, first=None, **kwargs):
        """A server, serving `first` (the first snapshot unless given) before kewd asks."""
        server = SnapshotServer(**kwargs)
        self.servers.append(server)
        server.set(first if first is not None else snapshots()[0])
        return server

    def replayed_records(self, documents):
        """What kew-replay reads from the same snapshots as a directory of history files."""
        history = self.path("history")
        os.makedirs(history, exist_ok=True)
        for i, document in enumerate(documents):
            with open(os.path.join(history, f"history_{i}.json"), "wb") as f:
                f.write(document)
        subprocess.run([KEW_REPLAY, "--stats-json", self.path("replay.json"), history], capture_output=True,
                       check=True)
        with open(self.path("replay.json"), encoding="utf-8") as f:
            return json.load(f)["records"]

    def play(self, kewd, server, documents):
        """Serves each document until kewd has fetched it once."""
        for document in documents:
            version = server.set(document)
            wait_until(lambda: server.served_version(version) > 0, 10, f"version {version} fetched")

    def test_snapshots_polled_over_http_and_https_give_each_position_once(self):
        """120 snapshots (real readsb positions, tests/data/text) served one after another
        from a loopback server, plainly and over TLS with a test certificate named by
        ca_file: kewd takes each position once, as kew-replay reads the same snapshots, the
        answers come gzipped, and a snapshot not yet replaced costs a 304."""
        documents = snapshots()
        expected = self.replayed_records(documents)
        self.assertGreater(expected, 90)
        cert, key = test_certificate(self.workdir)
        for scheme in ("http", "https"):
            with self.subTest(scheme=scheme):
                server = self.serve(tls=(cert, key) if scheme == "https" else None)
                url = f"{scheme}://127.0.0.1:{server.port}/data/aircraft.json"
                config = SERVICE.format(workdir=self.workdir) + POLL.format(format="aircraft-json", url=url)
                if scheme == "https":
                    config += f'ca_file = "{cert}"\n'
                kewd = self.start(config)
                kewd.wait_log(f"input receiver: aircraft-json http {url}")
                self.play(kewd, server, documents)
                wait_until(lambda: kewd.stats()["records"] >= expected, 10, "every position taken")
                wait_until(lambda: server.not_modified > 0, 10, "a conditional request answered 304")
                stats = kewd.stats()
                self.assertEqual(stats["records"], expected, "each position once, as kew-replay reads the snapshots")
                self.assertEqual(stats["rejected_total"], 0, stats["rejected"])
                receiver = stats["inputs"][0]
                self.assertGreaterEqual(receiver["polls"], len(documents))
                self.assertGreater(receiver["polls_unchanged"], 0)
                self.assertEqual(receiver["poll_failures"], 0, kewd.log())
                self.assertEqual(server.gzipped, sum(server.served.values()), "every answer asked for gzip")
                with urllib.request.urlopen(f"http://127.0.0.1:{kewd.http_port}/metrics", timeout=5) as response:
                    metrics = response.read().decode()
                self.assertRegex(metrics, r'kew_input_polls_total{input="receiver",result="unchanged"} [1-9]')
                self.assertRegex(metrics, r'kew_input_polls_total{input="receiver",result="failed"} 0\n')
                kewd.terminate()

    def test_opensky_rest_answers_polled_with_a_token(self):
        """OpenSky's REST API as a loopback server: state-vector answers (the 120
        snapshots as /api/states/all gives them), an OAuth2 token for OpenSky's JSON
        credentials: kewd takes each position once, as kew-replay reads the same answers
        from a directory."""
        documents = [opensky_states(d) for d in snapshots()]
        expected = self.replayed_records(documents)
        self.assertGreater(expected, 90)
        credentials = self.path("credentials.json")
        with open(credentials, "w", encoding="utf-8") as f:
            json.dump({"clientId": "kew-api-client", "clientSecret": "s"}, f)
        server = self.serve(first=documents[0], tokens=True)
        base = f"http://127.0.0.1:{server.port}"
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="opensky-rest", url=f"{base}/api/states/all?lamin=40.5&lomin=-119.5&lamax=41&lomax=-118.9")
            + f'credentials_file = "{credentials}"\ntoken_url = "{base}/token"\n')
        self.play(kewd, server, documents)
        wait_until(lambda: kewd.stats()["records"] >= expected, 10, "every position taken")
        stats = kewd.stats()
        self.assertEqual(stats["records"], expected)
        self.assertEqual(stats["rejected_total"], 0, stats["rejected"])
        self.assertEqual(len(server.issued), 1)

    def test_a_certificate_nobody_vouches_for_is_refused(self):
        """The same TLS server without ca_file: libcurl checks the certificate against the
        system's authorities; every request fails, counted, and nothing is read."""
        cert, key = test_certificate(self.workdir)
        server = self.serve(tls=(cert, key))
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="aircraft-json", url=f"https://127.0.0.1:{server.port}/data/aircraft.json"))
        wait_until(lambda: kewd.stats()["inputs"][0]["poll_failures"] >= 2, 10, "failed requests counted")
        self.assertEqual(kewd.stats()["records"], 0)
        self.assertIn("certificate", kewd.log().lower())

    def test_the_server_away_and_back(self):
        """The server stops mid-history: kewd keeps running, counts the failed requests,
        logs them (not one line per request), says feed_stale; the server back on its
        port, kewd reads the rest of the history and says healthy again."""
        documents = snapshots()
        server = self.serve()
        port = server.port
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="aircraft-json", url=f"http://127.0.0.1:{port}/data/aircraft.json"))
        watcher = Subscriber(kewd.alert_port)

        def health():
            alive = watcher.objects("ALIVE")
            return alive[-1]["health"] if alive else None

        self.play(kewd, server, documents[:60])
        wait_until(lambda: health() == "healthy", 10, "ALIVE to say healthy")
        before = kewd.stats()["records"]
        self.assertGreater(before, 0)
        server.stop()
        self.servers.remove(server)
        wait_until(lambda: health() == "feed_stale", 15, "ALIVE to say feed_stale")
        failures = kewd.stats()["inputs"][0]["poll_failures"]
        self.assertGreaterEqual(failures, 3)
        self.assertLess(kewd.log().count("Connection refused") + kewd.log().count("Couldn't connect"), failures,
                        "repeated failures are summarised, not logged one by one")

        server = self.serve(port=port)
        self.play(kewd, server, documents[60:])
        wait_until(lambda: kewd.stats()["records"] > before, 10, "records after the server came back")
        wait_until(lambda: health() == "healthy", 10, "ALIVE to say healthy again")
        self.assertIn("answering again", kewd.log())
        self.assertTrue(kewd.running())

    def test_a_server_that_asks_to_wait_is_not_asked_sooner(self):
        """A 429 naming X-Rate-Limit-Retry-After-Seconds (OpenSky's header once the day's
        credits are spent): the next request waits that long, beyond reconnect_max_s,
        and the poll goes on at its interval afterwards."""
        server = self.serve()
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="aircraft-json", url=f"http://127.0.0.1:{server.port}/data/aircraft.json"))
        wait_until(lambda: kewd.stats()["records"] > 0, 10, "the first snapshot read")
        with server.lock:
            server.refuse_for_s = 3
        wait_until(lambda: kewd.stats()["inputs"][0]["poll_failures"] == 1, 10, "the refusal counted")
        with server.lock:
            refused_at = len(server.get_times)
        wait_until(lambda: len(server.get_times) > refused_at, 10, "the next request")
        with server.lock:
            waited = server.get_times[refused_at] - server.get_times[refused_at - 1]
        self.assertGreaterEqual(waited, 2.9, "asked again before the server's time")
        wait_until(lambda: len(server.get_times) > refused_at + 5, 10, "polling at the interval again")

    def test_an_answer_larger_than_the_limit_is_refused(self):
        """A 50 MB answer with its length announced, and a gzip answer of a few kilobytes
        that unpacks to 50 MB: each refused by the size limit (32 MiB by default, counted
        after decompression), counted and logged; the next good snapshot is read."""
        documents = snapshots()
        server = self.serve()
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="aircraft-json", url=f"http://127.0.0.1:{server.port}/data/aircraft.json"))
        fifty_mb = 50 * 1000 * 1000
        filler = b" " * (1 << 20)

        def announced():
            yield b'{"now":1,"aircraft":['
            for _ in range(fifty_mb // len(filler)):
                yield filler

        bomb = gzip.compress(b'{"now":1,"aircraft":[' + b" " * fifty_mb + b"]}")
        self.assertLess(len(bomb), 1 << 20)
        cases = [("announced", {"Content-Length": str(fifty_mb + 21)}, announced),
                 ("gzip bomb", {"Content-Length": str(len(bomb)), "Content-Encoding": "gzip"}, lambda: [bomb])]
        for name, headers, chunks in cases:
            with self.subTest(answer=name):
                failures = kewd.stats()["inputs"][0]["poll_failures"]
                with server.lock:
                    server.raw = (headers, chunks)
                wait_until(lambda: kewd.stats()["inputs"][0]["poll_failures"] > failures, 20, "the answer refused")
                with server.lock:
                    server.raw = None
                version = server.set(documents[0])
                wait_until(lambda: server.served_version(version) > 0, 10, "the next snapshot fetched")
                wait_until(lambda: kewd.stats()["records"] > 0, 10, "its records read")
        self.assertIn("larger than", kewd.log())
        self.assertTrue(kewd.running())

    def test_an_api_key_from_a_file_and_a_token_for_credentials(self):
        """secret_header and secret_file: the key is sent with every request and appears in
        neither the configuration nor the log. credentials_file with OpenSky's JSON
        credentials: kewd fetches a bearer token from token_url (OAuth2 client
        credentials), sends it, and fetches another when the server refuses it (401)."""
        documents = snapshots()
        key_file = self.path("api-key")
        with open(key_file, "w", encoding="utf-8") as f:
            f.write("s3cret-key-123\n")
        os.chmod(key_file, 0o600)
        server = self.serve(require={"api-auth": "s3cret-key-123"})
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="aircraft-json", url=f"http://127.0.0.1:{server.port}/api/v2/lat/29.9/lon/-95.3/dist/250")
            + f'secret_header = "api-auth"\nsecret_file = "{key_file}"\n')
        self.play(kewd, server, documents[:5])
        wait_until(lambda: kewd.stats()["records"] > 0, 10, "records through the keyed server")
        self.assertEqual(kewd.stats()["inputs"][0]["poll_failures"], 0)
        self.assertNotIn("s3cret", kewd.log())
        with open(kewd.config_path, encoding="utf-8") as f:
            self.assertNotIn("s3cret", f.read())
        kewd.terminate()

        credentials = self.path("credentials.json")
        with open(credentials, "w", encoding="utf-8") as f:
            json.dump({"clientId": "kew-test-api-client", "clientSecret": "x&y=z"}, f)
        os.chmod(credentials, 0o600)
        server = self.serve(tokens=True)
        base = f"http://127.0.0.1:{server.port}"
        kewd = self.start(SERVICE.format(workdir=self.workdir) + POLL.format(
            format="aircraft-json", url=f"{base}/data/aircraft.json")
            + f'credentials_file = "{credentials}"\ntoken_url = "{base}/token"\n')
        self.play(kewd, server, documents[5:10])
        self.assertEqual(len(server.issued), 1, "one token for many requests")
        self.assertIn("grant_type=client_credentials", server.token_requests[0])
        self.assertIn("client_secret=x%26y%3Dz", server.token_requests[0], "the form's values escaped")
        with server.lock:
            server.revoked.add(server.issued[0])
        self.play(kewd, server, documents[10:15])
        self.assertEqual(len(server.issued), 2, "a new token after a 401")
        self.assertGreater(kewd.stats()["records"], 0)

    def test_configuration_mistakes_are_refused_at_their_line(self):
        """An OpenSky URL polled faster than OpenSky allows, a secret file that is not
        there, a header key on a socket input: kewd --check-config names each."""
        cases = [
            (POLL.format(format="aircraft-json", url="https://opensky-network.org/api/states/all"),
             "OpenSky's API allows one request every 10 s without credentials"),
            (POLL.format(format="aircraft-json", url="http://127.0.0.1:1/a.json")
             + f'secret_header = "api-auth"\nsecret_file = "{self.path("missing")}"\n',
             "secret_file"),
            (POLL.format(format="aircraft-json", url="ftp://127.0.0.1/a.json"), "http:// or https:// URL"),
            ('[[input]]\ntransport = "udp"\naddress = "127.0.0.1:30998"\npoll_interval_s = 1\n',
             "poll_interval_s is for transport http only"),
        ]
        for text, message in cases:
            with self.subTest(message=message):
                path = self.path("mistake.toml")
                with open(path, "w", encoding="utf-8") as f:
                    f.write('[service]\nalert_listen = "127.0.0.1:30999"\n' + text)
                checked = subprocess.run([KEWD, "--check-config", "-c", path], capture_output=True, text=True)
                self.assertNotEqual(checked.returncode, 0)
                self.assertIn(message, checked.stderr + checked.stdout)


if __name__ == "__main__":
    import unittest
    unittest.main()
