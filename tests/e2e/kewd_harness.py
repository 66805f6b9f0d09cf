"""Test harness for end-to-end tests of the real kewd binary (design §6).

Starts kewd in the foreground on loopback on free ports, learns the ports from its log,
and talks to it as subscribers, feeds and operators do. kewd refuses port 0 (a listener
on it would be unreachable at an unknown port), so the harness replaces every
"127.0.0.1:0" of a configuration with a port that is free at that moment. Binaries come from the
environment (set by ctest): KEWD, KEW_REPLAY, KEW_GEN, KEW_WATCH.
"""

import json
import os
import random
import re
import shutil
import signal
import socket
import struct
import subprocess
import tempfile
import threading
import time
import unittest

KEWD = os.environ.get("KEWD", "kewd")
KEW_REPLAY = os.environ.get("KEW_REPLAY", "kew-replay")
KEW_GEN = os.environ.get("KEW_GEN", "kew-gen")
KEW_WATCH = os.environ.get("KEW_WATCH", "kew-watch")

STARTUP_TIMEOUT_S = 20.0


def wait_until(predicate, timeout_s, what):
    """Polls `predicate` until it returns a true value; fails with `what` on timeout."""
    deadline = time.monotonic() + timeout_s
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout_s} s waiting for {what}")
        time.sleep(0.05)


def free_port():
    """A loopback port free for both TCP and UDP a moment ago, below the kernel's range of
    ephemeral ports: a server a test stops and starts again on its port (a NATS outage)
    finds it free, as no outgoing connection and no bind to port 0 is given it meanwhile."""
    low, _ = (int(x) for x in open("/proc/sys/net/ipv4/ip_local_port_range").read().split())
    for _ in range(1000):
        port = random.randrange(10000, max(low, 10001))
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as t, \
                socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as u:
            try:
                t.bind(("127.0.0.1", port))
                u.bind(("127.0.0.1", port))
            except OSError:
                continue
        return port
    raise AssertionError("no free loopback port")


def with_free_ports(config_text):
    """The configuration with each "127.0.0.1:0" replaced by its own free port: distinct,
    since a port found free is not held, and the next search may find it again."""
    taken = set()

    def distinct(_):
        while True:
            port = free_port()
            if port not in taken:
                taken.add(port)
                return f'"127.0.0.1:{port}"'
    return re.sub(r'"127\.0\.0\.1:0"', distinct, config_text)


class Kewd:
    """One kewd process with its configuration in a temporary directory."""

    def __init__(self, config_text, workdir, extra_args=(), cwd=None, env=None, preexec_fn=None):
        """`config_text` None: no -c (kewd --replay's built-in configuration); `cwd`: the
        directory kewd runs in; `env`: variables added to the environment; `preexec_fn`:
        run in the child before kewd (resource limits)."""
        self.workdir = workdir
        self.config_path = os.path.join(workdir, "kew.toml")
        config_args = []
        if config_text is not None:
            if not re.search(r"^\[http\]", config_text, re.M):
                # The HTTP server is on by default: a free port, not 8747, for every kewd
                # here. First, so that a test appending keys to the file's last table still does.
                config_text = '[http]\nlisten = "127.0.0.1:0"\n\n' + config_text
            with open(self.config_path, "w") as f:
                f.write(with_free_ports(config_text))
            config_args = ["-c", self.config_path]
        self.log_lines = []
        self._log_lock = threading.Lock()
        self.process = subprocess.Popen(
            [KEWD, "-N", *config_args, *extra_args],
            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True, cwd=cwd,
            env={**os.environ, **env} if env else None, preexec_fn=preexec_fn)
        self._reader = threading.Thread(target=self._read_log, daemon=True)
        self._reader.start()
        self.alert_port = int(wait_until(lambda: self._find_log("alerts on port "), STARTUP_TIMEOUT_S,
                                         "kewd to listen").split("alerts on port ")[1].split()[0])
        http_line = self._find_log("HTTP (map, API, metrics) on port ")
        self.http_port = int(http_line.split("on port ")[1].split(",")[0]) if http_line else None

    def _read_log(self):
        for line in self.process.stderr:
            with self._log_lock:
                self.log_lines.append(line.rstrip("\n"))

    def _find_log(self, text):
        with self._log_lock:
            for line in self.log_lines:
                if text in line:
                    return line
        if self.process.poll() is not None:
            raise AssertionError("kewd exited with %s:\n%s" % (self.process.returncode, "\n".join(self.log_lines)))
        return None

    def log(self):
        with self._log_lock:
            return "\n".join(self.log_lines)

    def wait_log(self, text, timeout_s=10.0):
        return wait_until(lambda: self._find_log(text), timeout_s, f"'{text}' in kewd's log")

    def input_port(self, name):
        """The port an input bound, from its start-up line in the log."""
        line = self.wait_log(f"input {name}: ")
        return int(line.split("(port ")[1].rstrip(")"))

    def stats(self):
        """The daemon's STATS object (the answer to ?STATS)."""
        try:
            s = socket.create_connection(("127.0.0.1", self.alert_port), timeout=10)
        except ConnectionRefusedError:
            if self.process.poll() is not None:
                raise AssertionError("kewd exited with %s; the end of its log:\n%s"
                                     % (self.process.returncode, "\n".join(self.log().splitlines()[-40:])))
            raise
        with s:
            s.sendall(b"?STATS\n")
            reader = s.makefile("r")
            for line in reader:
                obj = json.loads(line)
                if obj["class"] == "STATS":
                    return obj
        raise AssertionError("no STATS object")

    def wait_records(self, n, timeout_s=60.0):
        return wait_until(lambda: self.stats()["records"] >= n, timeout_s, f"{n} records processed")

    def running(self):
        return self.process.poll() is None

    def terminate(self, timeout_s=20.0):
        """SIGTERM, then the exit status."""
        self.process.send_signal(signal.SIGTERM)
        return self.process.wait(timeout=timeout_s)

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        self._reader.join(timeout=5)
        self.process.stderr.close()


class Subscriber:
    """A client of the alert stream: connects, reads VERSION, sends ?WATCH."""

    opened = []  # closed by the tests' tearDown

    def __init__(self, port, min_severity="caution", tracks=False, receive_buffer=None, read=True):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        if receive_buffer:
            self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, receive_buffer)
        self.sock.connect(("127.0.0.1", port))
        Subscriber.opened.append(self)
        self.file = self.sock.makefile("rb")
        self.version = json.loads(self.file.readline())
        request = {"enable": True, "min_severity": min_severity, "tracks": tracks}
        self.sock.sendall(b"?WATCH=" + json.dumps(request).encode() + b"\n")
        self.lines = []
        self.closed = False
        self._thread = None
        if read:
            self.start_reading()

    def start_reading(self):
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self):
        for raw in self.file:
            self.lines.append(raw.decode())
        self.closed = True

    def objects(self, cls=None):
        out = [json.loads(line) for line in list(self.lines)]
        return [o for o in out if cls is None or o["class"] == cls]

    def alert_lines(self):
        return [line for line in list(self.lines) if line.startswith('{"class":"ALERT",')]

    def wait_closed(self, timeout_s=15.0):
        wait_until(lambda: self.closed, timeout_s, "the server to close the subscriber")

    def close(self):
        try:
            self.sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        if self._thread:
            self._thread.join(timeout=5)
        self.file.close()
        self.sock.close()


def generate(path, scenario="airways", aircraft=300, duration=300, seed=5):
    subprocess.run([KEW_GEN, "--scenario", scenario, "--aircraft", str(aircraft), "--duration", str(duration),
                    "--seed", str(seed), "-o", path], check=True)


def offline_alerts(config_path, recording):
    """kew-replay's offline ALERT lines for `recording` under the same configuration."""
    result = subprocess.run([KEW_REPLAY, "--config", config_path, recording], check=True,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    return result.stdout.splitlines(keepends=True)


def replay_to(target, recording, *pace):
    subprocess.run([KEW_REPLAY, "--to", target, *pace, recording], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def active_at_end(alert_lines):
    """id → last event of every alert not ended, from ALERT lines."""
    last = {}
    for line in alert_lines:
        event = json.loads(line)
        last[event["id"]] = event
    return {i: e for i, e in last.items() if e["state"] != "end"}


def count_lines(path):
    with open(path) as f:
        return sum(1 for line in f if line.strip() and not line.startswith("#"))


def write_pcap(path, datagrams, udp_port=8600):
    """Classic pcap (Ethernet/IPv4/UDP) of `datagrams`, for tshark; port 8600 is the
    port Wireshark decodes as ASTERIX by default."""
    with open(path, "wb") as f:
        f.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
        for i, payload in enumerate(datagrams):
            udp = struct.pack("!HHHH", 40000, udp_port, 8 + len(payload), 0) + payload
            ip = struct.pack("!BBHHHBBH4s4s", 0x45, 0, 20 + len(udp), i & 0xFFFF, 0, 64, 17, 0,
                             bytes([127, 0, 0, 1]), bytes([127, 0, 0, 1])) + udp
            frame = b"\x00" * 12 + b"\x08\x00" + ip
            f.write(struct.pack("<IIII", 1700000000 + i, 0, len(frame), len(frame)) + frame)


def temporary_directory():
    return tempfile.TemporaryDirectory(prefix="kew-e2e-")


# The live tick never fires during a test (a feed silent for a whole tick would move the
# clock on and make the stream differ from the offline run, as it should live).
SERVICE = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 60
subscriber_queue = {queue}
alert_log = "{workdir}/alerts.jsonl"
"""

TCP_INPUT = """
[[input]]
name = "{name}"
format = "{format}"
transport = "tcp-server"
address = "127.0.0.1:0"
"""

UDP_INPUT = """
[[input]]
name = "{name}"
format = "{format}"
transport = "udp"
address = "127.0.0.1:0"
"""


class E2eCase(unittest.TestCase):
    def setUp(self):
        self._dir = temporary_directory()
        self.workdir = self._dir.name
        self.daemons = []

    def tearDown(self):
        for d in self.daemons:
            d.kill()
        while Subscriber.opened:
            Subscriber.opened.pop().close()
        self._dir.cleanup()

    def start(self, config, *args, env=None, preexec_fn=None):
        daemon = Kewd(config, self.workdir, args, env=env, preexec_fn=preexec_fn)
        self.daemons.append(daemon)
        return daemon

    def path(self, name):
        return os.path.join(self.workdir, name)


MODBUS_CLIENT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "daemon",
                             "modbus_client.py")


def pymodbus_python():
    """Debian's python3 (pymodbus is a Debian package), else the one on PATH if it has it."""
    for python in ("/usr/bin/python3", shutil.which("python3")):
        if python and subprocess.run([python, "-c", "import pymodbus"], stderr=subprocess.DEVNULL).returncode == 0:
            return python
    return None



NATS_SERVER = os.environ.get("NATS_SERVER", "nats-server")


class NatsServer:
    """A real nats-server (Debian's) on loopback with JetStream (its store in `workdir`,
    kept across restart()) and its MQTT listener, on free ports."""

    def __init__(self, workdir):
        self.port = free_port()
        self.mqtt_port = free_port()
        self.store = os.path.join(workdir, "jetstream")
        self.config_path = os.path.join(workdir, "nats.conf")
        with open(self.config_path, "w") as f:
            # MQTT needs JetStream and a server name.
            f.write(f'server_name: kew_e2e\nlisten: 127.0.0.1:{self.port}\n'
                    f'jetstream {{ store_dir: "{self.store}" }}\nmqtt {{ listen: 127.0.0.1:{self.mqtt_port} }}\n')
        self.log_path = os.path.join(workdir, "nats.log")
        self.process = None
        self.start()

    @property
    def url(self):
        return f"nats://127.0.0.1:{self.port}"

    def start(self):
        self._log = open(self.log_path, "a")
        self.process = subprocess.Popen([NATS_SERVER, "-c", self.config_path], stdout=self._log,
                                        stderr=subprocess.STDOUT)
        wait_until(self._ready, STARTUP_TIMEOUT_S, "nats-server to be ready")

    def _ready(self):
        if self.process.poll() is not None:
            with open(self.log_path) as f:
                raise AssertionError("nats-server exited:\n" + f.read())
        try:
            with socket.create_connection(("127.0.0.1", self.port), timeout=1) as s:
                return s.makefile("rb").readline().startswith(b"INFO ")
        except OSError:
            return False

    def stop(self):
        if self.process and self.process.poll() is None:
            self.process.terminate()
            self.process.wait(timeout=20)
        if self.process:
            self._log.close()
        self.process = None


def _nats_client(port, timeout_s):
    """(socket, reader) of a connection that has read the server's INFO and sent CONNECT
    (NATS's text protocol)."""
    s = socket.create_connection(("127.0.0.1", port), timeout=timeout_s)
    reader = s.makefile("rb")
    assert reader.readline().startswith(b"INFO ")
    s.sendall(b'CONNECT {"verbose":false,"pedantic":false,"headers":true,"no_responders":true,"name":"kew-e2e"}\r\n')
    return s, reader


def _nats_next(s, reader, subject):
    """(reply subject or None, payload bytes with headers left out) of the next message the
    connection receives."""
    while True:
        line = reader.readline()
        if not line:
            raise AssertionError(f"the server closed before a message on {subject}")
        if line.startswith(b"PING"):
            s.sendall(b"PONG\r\n")
        elif line.startswith(b"MSG "):
            fields = line.split()
            size = int(fields[-1])
            return (fields[3].decode() if len(fields) == 5 else None), reader.read(size + 2)[:size]
        elif line.startswith(b"HMSG "):
            fields = line.split()
            header_size, size = (int(n) for n in fields[-2:])
            return (fields[3].decode() if len(fields) == 6 else None), reader.read(size + 2)[header_size:size]


def _nats_next_payload(s, reader, subject):
    """The payload (bytes, headers left out) of the next message the connection receives."""
    return _nats_next(s, reader, subject)[1]


def nats_publish(port, subject, payloads, reply=None):
    """Publishes each of `payloads` (bytes) as one message through NATS's text protocol
    (with `reply` as its reply subject when given), then waits for the server's PONG:
    every message has reached it."""
    s, reader = _nats_client(port, 10)
    with s:
        out = []
        head = subject if reply is None else f"{subject} {reply}"
        for payload in payloads:
            out.append(b"PUB %s %d\r\n%s\r\n" % (head.encode(), len(payload), payload))
        out.append(b"PING\r\n")
        s.sendall(b"".join(out))
        while True:
            line = reader.readline()
            if not line or line.startswith(b"PONG"):
                break
            if line.startswith(b"-ERR"):
                raise AssertionError(line.decode())


def nats_next_message(port, subject, timeout_s=10.0):
    """Subscribes to `subject` through NATS's text protocol and returns the payload (bytes)
    of the first message published to it, headers left out."""
    s, reader = _nats_client(port, timeout_s)
    with s:
        s.sendall(b"SUB %s 1\r\nPING\r\n" % subject.encode())
        return _nats_next_payload(s, reader, subject)


def nats_next_reply_subject(port, subject, timeout_s=10.0):
    """Subscribes to `subject` and returns the reply subject of the first message published
    to it with one (where its sender waits for the answer)."""
    s, reader = _nats_client(port, timeout_s)
    with s:
        s.sendall(b"SUB %s 1\r\nPING\r\n" % subject.encode())
        while True:
            reply, _ = _nats_next(s, reader, subject)
            if reply is not None:
                return reply


def nats_request(port, subject, payload=b"", timeout_s=10.0):
    """Sends one request (e.g. to JetStream's API, $JS.API.…) and returns the reply's payload."""
    s, reader = _nats_client(port, timeout_s)
    with s:
        inbox = "_INBOX.kew_e2e"
        s.sendall(b"SUB %s 1\r\nPUB %s %s %d\r\n%s\r\n" % (inbox.encode(), subject.encode(), inbox.encode(),
                                                            len(payload), payload))
        return _nats_next_payload(s, reader, inbox)
