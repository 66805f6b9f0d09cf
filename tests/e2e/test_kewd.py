"""End-to-end tests of the real kewd binary on loopback (design §5.3–5.7, §6).

Run by ctest (tests/CMakeLists.txt) with the binaries in the environment; by hand:
  KEWD=build/daemon/kewd KEW_REPLAY=build/replay/kew-replay KEW_GEN=build/replay/kew-gen \
  KEW_WATCH=build/daemon/kew-watch python3 -m unittest tests/e2e/test_kewd.py -v
"""

import json
import os
import random
import resource
import shutil
import signal
import socket
import subprocess
import unittest

from kewd_harness import (KEWD, KEW_REPLAY, KEW_WATCH, SERVICE, TCP_INPUT, UDP_INPUT, E2eCase, Subscriber, active_at_end,
                          count_lines, generate, offline_alerts, replay_to, wait_until, with_free_ports)

class AlertStream(E2eCase):
    """The stream over TCP equals the offline replay; slow and reconnecting subscribers."""

    def test_tcp_feed_two_subscribers_snapshot_and_clean_shutdown(self):
        recording = self.path("airways.ndjson")
        generate(recording, "airways", aircraft=1000, duration=300, seed=11)
        # A queue longer than the whole alert stream: the reader is never cut off however
        # busy the machine, while the stalled client (every TRACK too, ~90k objects) is.
        kewd = self.start(SERVICE.format(queue=20000, workdir=self.workdir)
                          + TCP_INPUT.format(name="feed", format="ndjson"))
        expected = offline_alerts(kewd.config_path, recording)
        self.assertGreater(len(expected), 1000, "the scenario must have conflicts")
        self.assertLess(len(expected), 20000)

        reader = Subscriber(kewd.alert_port)
        # Asks for every TRACK object and never reads: its queue overflows.
        stalled = Subscriber(kewd.alert_port, tracks=True, receive_buffer=4096, read=False)
        wait_until(lambda: kewd.stats()["subscribers"]["now"] >= 3 or reader.objects("ALERTS"), 10,
                   "both subscribers watching")
        records = count_lines(recording)
        replay_to(f"127.0.0.1:{kewd.input_port('feed')}", recording, "--max-speed")
        kewd.wait_records(records)

        stats = kewd.stats()
        self.assertEqual(stats["subscribers"]["cut_off"], 1, "the stalled subscriber is disconnected\n" + kewd.log())
        self.assertEqual(stats["accepted"], records)
        # The resident set in bytes (pages times the page size): a daemon with its
        # libraries and thousands of tracks holds more than 4 MB.
        self.assertGreater(stats["resident_bytes"], 4 << 20)
        wait_until(lambda: len(reader.alert_lines()) >= len(expected), 30, "the reader to receive every alert")
        self.assertEqual(reader.alert_lines(), expected, "the live stream equals kew-replay's offline output")
        for obj in reader.objects():
            self.assertIn("seq", obj)

        # The stalled client finally reads: what the kernel held, then the ERROR.
        stalled.start_reading()
        stalled.wait_closed()
        self.assertEqual(stalled.objects()[-1]["class"], "ERROR")

        # A client connecting now gets the active alerts as its snapshot.
        late = Subscriber(kewd.alert_port)
        wait_until(lambda: late.objects("ALERTS"), 10, "the snapshot")
        snapshot = late.objects("ALERTS")[0]["alerts"]
        active = active_at_end(expected)
        self.assertGreater(len(active), 0)
        self.assertEqual({a["id"]: a for a in snapshot}, active)
        # ... and so does kew-watch.
        watch = subprocess.run(["timeout", "2", KEW_WATCH, f"127.0.0.1:{kewd.alert_port}"], stdout=subprocess.PIPE,
                               text=True, check=False)
        self.assertIn(f"{len(active)} active alerts", watch.stdout)

        self.assertEqual(kewd.terminate(), 0)
        reader.wait_closed()
        late.wait_closed()
        with open(self.path("alerts.jsonl")) as f:
            logged = f.readlines()
        self.assertTrue(logged[0].startswith('{"class":"START",'), logged[0])  # the run's START first
        self.assertEqual(logged[1:], expected, "the alert log holds every alert")
        self.assertIn("SIGTERM received", kewd.log())

    def test_file_input_reads_like_kew_replay_and_reports_the_same_statistics(self):
        """kewd's file input goes through kew-replay's recording reader: the same alerts,
        and ?STATS gives every figure of kew-replay's --stats-json under the same key."""
        recording = self.path("mixed.ndjson")
        generate(recording, "mixed", aircraft=300, duration=120, seed=3)
        with open(recording, "a") as f:
            f.write('{"t":"late","id":"X"}\n')  # one decoder rejection, counted by both
        unreadable = self.path("a-directory")
        os.mkdir(unreadable)
        kewd = self.start(SERVICE.format(queue=100000, workdir=self.workdir)
                          + f'[[input]]\nname = "file"\nformat = "ndjson"\ntransport = "file"\naddress = "{recording}"\n'
                          + f'[[input]]\nname = "dir"\ntransport = "file"\naddress = "{unreadable}"\n')
        kewd.wait_log("input file: " + recording + " read to the end", 60)
        live = kewd.stats()
        stats_path = self.path("replay-stats.json")
        offline = subprocess.run([KEW_REPLAY, "--config", kewd.config_path, "--stats-json", stats_path, recording],
                                 check=True, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
        with open(stats_path) as f:
            replay = json.load(f)
        kewd.terminate()
        with open(self.path("alerts.jsonl")) as f:
            start, _, logged = f.read().partition("\n")
        self.assertTrue(start.startswith('{"class":"START",'), start)  # the run's START first
        self.assertEqual(logged, offline, "the file input gives kew-replay's alerts")
        self.assertGreater(replay["alerts_new"], 0, "the scenario must have conflicts")
        only_replay = {"audits", "audit_violations_found", "audit_violations_unrepaired", "wall_s"}
        for key, value in replay.items():
            if key in only_replay:
                continue
            self.assertIn(key, live, "kewd's STATS lacks kew-replay's key " + key)
            if key == "zones":  # each zone's busy_s is wall time, like wall_s
                for zones in (live[key], value):
                    for z in zones["list"]:
                        z.pop("busy_s")
            if key not in ("rejected", "rejected_total"):
                self.assertEqual(live[key], value, key)
        # kewd's total adds the empty directory (a directory is the recording of its files:
        # this one names none) to the recording's one bad line.
        self.assertEqual(replay["rejected"], {"wrong_type": 1})
        self.assertEqual(live["rejected"], {"no_files": 1, "wrong_type": 1})
        self.assertEqual((replay["rejected_total"], live["rejected_total"]), (1, 2))
        by_name = {i["name"]: i for i in live["inputs"]}
        self.assertEqual(by_name["dir"]["rejected"], {"no_files": 1}, "an input that reads nothing is counted")
        self.assertEqual(by_name["file"]["rejected"], {"wrong_type": 1})
        self.assertEqual(by_name["file"]["reports"], live["records"])

    def test_udp_feed_equals_offline(self):
        recording = self.path("tma.ndjson")
        generate(recording, "tma", aircraft=150, duration=120, seed=3)
        kewd = self.start(SERVICE.format(queue=5000, workdir=self.workdir)
                          + UDP_INPUT.format(name="udp", format="ndjson"))
        expected = offline_alerts(kewd.config_path, recording)
        self.assertGreater(len(expected), 10)
        reader = Subscriber(kewd.alert_port)
        records = count_lines(recording)
        # Paced: a UDP receiver that falls behind loses datagrams, as it would live.
        replay_to(f"udp://127.0.0.1:{kewd.input_port('udp')}", recording, "--speed", "40")
        kewd.wait_records(records)
        wait_until(lambda: len(reader.alert_lines()) >= len(expected), 20, "every alert")
        self.assertEqual(reader.alert_lines(), expected)
        self.assertEqual(kewd.terminate(), 0)


class BadInput(E2eCase):
    """Malformed input on every transport: counted, and the daemon carries on."""

    def test_malformed_input_on_every_transport(self):
        good = self.path("good.ndjson")
        generate(good, "random", aircraft=20, duration=20, seed=2)
        with open(good) as f:
            good_lines = [line for line in f if not line.startswith("#")]
        garbage = bytes(random.Random(7).getrandbits(8) for _ in range(3000))
        bad_text = (b'{"t":1714400000,"id":"ABC"\n'           # truncated object
                    + b'MSG,3,1,1,4CA123,1,2024/04/29,12:00:00.000,,,,35000,,,51.5,-0.4,,,0,0,0,0\n'  # SBS
                    + b'{"t":"x","id":"A","lat":1,"lon":2,"alt_ft":3}\n'  # wrong type
                    + b'{"t":1e999,"id":"B","lat":91,"lon":2,"alt_ft":3}\n'  # out of range
                    + b"x" * 10000 + b"\n"                     # over max_line_bytes
                    + garbage + b"\n")
        bad_file = self.path("bad.ndjson")
        with open(bad_file, "wb") as f:
            f.write(bad_text + "".join(good_lines).encode())

        # The daemon connects to this server (tcp-client input).
        server = socket.socket()
        server.bind(("127.0.0.1", 0))
        server.listen(1)
        config = (SERVICE.format(queue=1000, workdir=self.workdir)
                  + TCP_INPUT.format(name="tcp", format="ndjson")
                  + UDP_INPUT.format(name="udp", format="ndjson")
                  + UDP_INPUT.format(name="asterix", format="asterix-datagram")
                  + f"""
[[input]]
name = "client"
format = "ndjson"
transport = "tcp-client"
address = "127.0.0.1:{server.getsockname()[1]}"
reconnect_min_s = 0.1

[[input]]
name = "file"
format = "ndjson"
transport = "file"
address = "{bad_file}"
""")
        kewd = self.start(config)
        # tcp-server: garbage, then a connection cut in the middle of a line.
        with socket.create_connection(("127.0.0.1", kewd.input_port("tcp"))) as s:  # noqa
            s.sendall(bad_text + b'{"t":17144')
        # udp: every bad line as its own datagram, an oversized datagram, then garbage.
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as u:
            for line in bad_text.split(b"\n"):
                u.sendto(line[:60000] + b"\n", ("127.0.0.1", kewd.input_port("udp")))
            for chunk in range(0, len(garbage), 500):
                u.sendto(garbage[chunk:chunk + 500], ("127.0.0.1", kewd.input_port("asterix")))
        # tcp-client: garbage and a cut, then the daemon reconnects.
        connection, _ = server.accept()
        connection.sendall(bad_text + b'{"t":1714400000.5,"id":')
        connection.close()
        connection, _ = server.accept()
        connection.sendall("".join(good_lines).encode())

        # The file and the tcp-client input carry the same good records: the second copy
        # is refused by the track table as a repetition, so count records offered.
        try:
            wait_until(lambda: kewd.stats()["records"] >= 2 * len(good_lines), 20, "the good records")
        except AssertionError:
            print(json.dumps(kewd.stats(), indent=1), len(good_lines), kewd.log()[-3000:])
            raise
        stats = kewd.stats()
        by_name = {i["name"]: i for i in stats["inputs"]}
        for name in ("tcp", "udp", "asterix", "client", "file"):
            self.assertGreater(sum(by_name[name]["rejected"].values()), 0, f"{name}: rejections counted")
        for name in ("tcp", "udp", "client", "file"):
            self.assertIn("line_too_long", by_name[name]["rejected"], name)
        self.assertGreaterEqual(by_name["tcp"]["rejected"].get("truncated", 0), 1)
        self.assertGreaterEqual(by_name["client"]["connections"], 2, "the client input reconnected")
        self.assertEqual(by_name["file"]["reports"], len(good_lines), "records after garbage are decoded")
        self.assertTrue(kewd.running())
        self.assertIn("rejected", kewd.log())
        connection.close()
        self.assertEqual(kewd.terminate(), 0)
        server.close()


def limited_memory():
    """preexec_fn: a child that would read without bound fails instead of filling the machine."""
    resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))


class InputFraming(E2eCase):
    """Datagrams, noise, configurations that never end and the recording (docs/reliability.md
    "Input framing")."""

    def test_udp_datagrams_never_contaminate_each_other(self):
        good = self.path("good.ndjson")
        generate(good, "random", aircraft=20, duration=20, seed=2)
        with open(good, "rb") as f:
            lines = [line for line in f if not line.startswith(b"#")]
        kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir)
                          + UDP_INPUT.format(name="udp", format="ndjson"))
        target = ("127.0.0.1", kewd.input_port("udp"))
        sent = 0

        def send(sender, payload):
            nonlocal sent
            sender.sendto(payload, target)
            sent += len(payload)
            # Nothing may be lost to a full receive buffer: wait until kewd has read it.
            wait_until(lambda: by_name(kewd)["udp"]["bytes"] >= sent, 20, "kewd to read the datagram")

        # Sender A sends a record per datagram with its newline, sender B one without it
        # (still whole), a record cut short, random bytes, and 1.2 MB of one over-long line
        # in datagrams without a newline, between each of A's.
        rng = random.Random(5)
        garbage = bytes(rng.getrandbits(8) for _ in range(600)).replace(b"\n", b" ")
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as a, \
                socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as b:
            for i, line in enumerate(lines):
                if i % 2:
                    send(b, line.rstrip(b"\n"))
                else:
                    send(a, line)
                send(b, (b'{"t":1714400000,"id":"CUT"', garbage, b"x" * 40000)[i % 3])
        stats = by_name(kewd)["udp"]
        self.assertEqual(stats["reports"], len(lines), "every valid record decoded\n" + json.dumps(stats))
        self.assertNotIn("truncated", stats["rejected"], "a datagram is whole: nothing in it is cut")
        for reason in ("bad_json", "line_too_long"):
            self.assertIn(reason, stats["rejected"])
        self.assertEqual(kewd.terminate(), 0)

    def test_auto_detection_finds_ndjson_after_noise(self):
        good = self.path("good.ndjson")
        generate(good, "random", aircraft=20, duration=20, seed=2)
        with open(good, "rb") as f:
            text = f.read()
        kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir)
                          + TCP_INPUT.format(name="tcp", format="auto"))
        rng = random.Random(9)  # binary noise: text noise was always skipped as a bad line
        noise = bytes(rng.getrandbits(8) for _ in range(4096)) + b"\n"
        with socket.create_connection(("127.0.0.1", kewd.input_port("tcp"))) as s:
            s.sendall(noise + text)
        records = count_lines(good)
        wait_until(lambda: by_name(kewd)["tcp"]["reports"] >= records, 20, "the records after the noise")
        stats = by_name(kewd)["tcp"]
        self.assertEqual(stats["reports"], records)
        self.assertEqual(stats["rejected"].get("unknown_format"), 1, "the noise is counted once")
        self.assertEqual(kewd.terminate(), 0)

    def test_config_that_never_ends_is_refused(self):
        fifo = self.path("fifo.toml")
        os.mkfifo(fifo)
        for path, why in (("/dev/zero", "not a regular file"), (fifo, "not a regular file")):
            # The timeout and the memory limit only guard against a hang: kewd answers at once.
            result = subprocess.run([KEWD, "--check-config", "-c", path], stderr=subprocess.PIPE, text=True,
                                    timeout=30, preexec_fn=limited_memory)
            self.assertEqual(result.returncode, 64, result.stderr)
            self.assertIn(f"{path}: {why}", result.stderr)
        # SIGHUP re-reads the path kewd was started with: made a link to the pipe, it is refused.
        kewd = self.start(SERVICE.format(queue=100, workdir=self.workdir))
        os.remove(kewd.config_path)
        os.symlink(fifo, kewd.config_path)
        kewd.process.send_signal(signal.SIGHUP)
        self.assertIn("not a regular file", kewd.wait_log("configuration kept"))
        self.assertTrue(kewd.running())
        self.assertEqual(kewd.terminate(), 0)

    def test_record_file_replays_to_the_same_alerts(self):
        recording = self.path("airways.ndjson")
        generate(recording, "airways", aircraft=300, duration=120, seed=6)
        recorded = self.path("recorded.ndjson")
        kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir) + f'record_file = "{recorded}"\n'
                          + f'[[input]]\nname = "file"\nformat = "ndjson"\ntransport = "file"\naddress = "{recording}"\n')
        kewd.wait_log("input file: " + recording + " read to the end", 60)
        self.assertEqual(kewd.terminate(), 0)
        self.assertEqual(count_lines(recorded), count_lines(recording), "one line per record")
        expected = offline_alerts(kewd.config_path, recording)
        self.assertGreater(len(expected), 10, "the scenario must have conflicts")
        self.assertEqual(offline_alerts(kewd.config_path, recorded), expected)


def by_name(kewd):
    """The STATS figures of each input, by its name."""
    return {i["name"]: i for i in kewd.stats()["inputs"]}


class Operations(E2eCase):
    def test_check_config_and_version(self):
        good = self.path("good.toml")
        with open(good, "w") as f:
            f.write(with_free_ports(SERVICE.format(queue=100, workdir=self.workdir)))
        self.assertEqual(subprocess.run([KEWD, "--check-config", "-c", good], stdout=subprocess.DEVNULL).returncode, 0)
        # One HOST:PORT rule for every tool: port 0 and bare IPv6 are refused, naming the text.
        zero = self.path("zero.toml")
        with open(zero, "w") as f:
            f.write(SERVICE.format(queue=100, workdir=self.workdir))
        result = subprocess.run([KEWD, "--check-config", "-c", zero], stderr=subprocess.PIPE, text=True)
        self.assertEqual(result.returncode, 64)
        self.assertIn('alert_listen = "127.0.0.1:0" is not HOST:PORT: port 0', result.stderr)
        for tool in ([KEW_REPLAY, "--to", "::1:4747"], [KEW_WATCH, "::1:4747"]):
            result = subprocess.run(tool + ([self.path("zero.toml")] if tool[0] == KEW_REPLAY else []),
                                    stderr=subprocess.PIPE, text=True, timeout=20)
            self.assertEqual(result.returncode, 64, tool)
            self.assertIn('"::1:4747" is not HOST:PORT: an IPv6 address goes in brackets', result.stderr)
        bad = self.path("bad.toml")
        with open(bad, "w") as f:
            f.write("[service]\nalert_listen = \"127.0.0.1:4747\"\nalert_lisen = 3\n")
        result = subprocess.run([KEWD, "--check-config", "-c", bad], stderr=subprocess.PIPE, text=True)
        self.assertEqual(result.returncode, 64)
        self.assertIn("bad.toml:3", result.stderr)
        version = subprocess.run([KEWD, "--version"], stdout=subprocess.PIPE, text=True, check=True).stdout
        self.assertTrue(version.startswith("kewd "))

    def test_sighup_reloads_log_level_and_limits(self):
        kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir))
        with open(kewd.config_path) as f:
            text = f.read().replace("subscriber_queue = 1000", "subscriber_queue = 77")
        with open(kewd.config_path, "w") as f:
            f.write(text + 'log_level = "debug"\n')
        kewd.process.send_signal(signal.SIGHUP)
        kewd.wait_log("SIGHUP: reloaded")
        self.assertIn("77 queued objects", kewd.log())
        # A broken file is refused and the service keeps its configuration.
        with open(kewd.config_path, "a") as f:
            f.write("no_such_key = 1\n")
        kewd.process.send_signal(signal.SIGHUP)
        kewd.wait_log("configuration kept")
        self.assertTrue(kewd.running())
        self.assertEqual(kewd.terminate(), 0)

    def test_sighup_keeps_the_log_level_given_on_the_command_line(self):
        # -l overrides the file's log_level (design §5.6), on a reload too.
        kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir) + 'log_level = "warn"\n', "-l", "info")
        kewd.process.send_signal(signal.SIGHUP)
        line = kewd.wait_log("SIGHUP: reloaded")
        self.assertIn("log level info", line)
        self.assertEqual(kewd.terminate(), 0)

    def test_background_start_reports_failure_and_success(self):
        busy = socket.socket()
        busy.bind(("127.0.0.1", 0))
        busy.listen(1)
        config = self.path("busy.toml")
        with open(config, "w") as f:
            f.write(f'[service]\nalert_listen = "127.0.0.1:{busy.getsockname()[1]}"\n')
        # Without -N kewd forks; the command fails when the daemon cannot start.
        self.assertEqual(subprocess.run([KEWD, "-c", config], timeout=20, stderr=subprocess.DEVNULL).returncode, 1)
        busy.close()
        pidfile_config = self.path("ok.toml")
        with open(pidfile_config, "w") as f:
            f.write(with_free_ports('[service]\nalert_listen = "127.0.0.1:0"\n[http]\nlisten = "127.0.0.1:0"\n'))
        self.assertEqual(subprocess.run([KEWD, "-c", pidfile_config], timeout=20).returncode, 0)
        # The daemon is running in the background: find it by its command line and stop it.
        pids = subprocess.run(["pgrep", "-f", f"{KEWD} -c {pidfile_config}"], stdout=subprocess.PIPE,
                              text=True).stdout.split()
        self.assertEqual(len(pids), 1)
        os.kill(int(pids[0]), signal.SIGTERM)
        wait_until(lambda: subprocess.run(["pgrep", "-f", f"{KEWD} -c {pidfile_config}"],
                                          stdout=subprocess.DEVNULL).returncode != 0, 10, "the daemon to stop")


class ListenAddresses(E2eCase):
    """Listeners bind loopback unless allowed; --check-config catches what start would not survive."""

    def check(self, config_text, *args):
        path = self.path("check.toml")
        with open(path, "w") as f:
            f.write(with_free_ports(config_text))
        return subprocess.run([KEWD, "--check-config", "-c", path, *args], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, timeout=20, cwd=self.workdir)

    def test_wildcard_refused_without_listen_any_or_allow_remote(self):
        wildcard = '[service]\nalert_listen = "0.0.0.0:4747"\n'
        result = self.check(wildcard)
        self.assertEqual(result.returncode, 64)
        self.assertIn('[service] alert_listen = "0.0.0.0:4747" listens on every interface', result.stderr)
        self.assertEqual(self.check(wildcard, "--listen-any").returncode, 0)
        self.assertEqual(self.check(wildcard + "allow_remote = true\n").returncode, 0)
        udp = UDP_INPUT.format(name="radar", format="asterix-datagram").replace("127.0.0.1:0", "0.0.0.0:8600")
        result = self.check(udp)
        self.assertEqual(result.returncode, 64)
        self.assertIn('[input 1] address = "0.0.0.0:8600" listens on every interface', result.stderr)
        self.assertEqual(self.check(udp + "allow_remote = true\n").returncode, 0, result.stderr)
        # Refused at start as well, before anything binds.
        path = self.path("start.toml")
        with open(path, "w") as f:
            f.write('[service]\nalert_listen = "[::]:4747"\n')
        started = subprocess.run([KEWD, "-N", "-c", path], stderr=subprocess.PIPE, text=True, timeout=20)
        self.assertEqual(started.returncode, 64)
        self.assertIn('alert_listen = "[::]:4747" listens on every interface', started.stderr)

    def test_ports_and_paths_checked_before_start(self):
        two = (TCP_INPUT.format(name="a", format="ndjson").replace("127.0.0.1:0", "127.0.0.1:4748")
               + TCP_INPUT.format(name="b", format="ndjson").replace("127.0.0.1:0", "127.0.0.1:4748"))
        result = self.check(two)
        self.assertEqual(result.returncode, 64)
        self.assertIn('[input 2] address = "127.0.0.1:4748" uses TCP port 4748 (IPv4), as [input 1]', result.stderr)
        os.mkdir(self.path("logs"))
        result = self.check('[service]\nalert_log = "logs"\n')
        self.assertEqual(result.returncode, 64)
        self.assertIn(f'alert_log = "{self.path("logs")}" is a directory', result.stderr)
        # Relative paths: resolved against the working directory, reported resolved.
        result = self.check('[service]\nalert_log = "logs/../logs/alerts.jsonl"\n')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn(f"alert log: {self.path('logs/alerts.jsonl')}", result.stdout)


class Install(E2eCase):
    def test_install_tree_unit_and_configuration(self):
        build = os.environ.get("KEW_BUILD_DIR")
        if not build:
            self.skipTest("KEW_BUILD_DIR is not set (ctest sets it)")
        prefix = self.path("prefix")
        subprocess.run(["cmake", "--install", build, "--prefix", prefix], check=True, stdout=subprocess.DEVNULL)
        for binary in ("kewd", "kew-watch", "kew-replay", "kew-gen"):
            self.assertTrue(os.access(os.path.join(prefix, "bin", binary), os.X_OK), binary)
        config = os.path.join(prefix, "etc", "kew", "kew.toml")
        result = subprocess.run([os.path.join(prefix, "bin", "kewd"), "--check-config", "-c", config],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        # --check-config checks that the alert log can be written: /var/log/kew and
        # /var/lib/kew are the unit's LogsDirectory and StateDirectory, which systemd
        # creates at the first start; before it, the check passes and says so.
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        with open(config) as f:
            text = f.read()
        if not os.path.exists("/var/log/kew"):
            self.assertIn('note: [service] alert_log = "/var/log/kew/alerts.jsonl": /var/log/kew does not exist yet; '
                          "systemd creates it when kewd.service starts", result.stdout)
            # kewd itself, about to start, trusts nothing: outside systemd the directory is missing.
            started = subprocess.run([os.path.join(prefix, "bin", "kewd"), "-N", "-c", config], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, timeout=20)
            self.assertEqual(started.returncode, 64, started.stdout)
            self.assertIn("its directory /var/log/kew does not exist", started.stderr)
        # A directory systemd does not create still fails the check.
        below = self.path("below.toml")
        with open(below, "w") as f:
            f.write(text.replace("/var/log/kew/alerts.jsonl", "/var/log/kew/more/alerts.jsonl"))
        result = subprocess.run([os.path.join(prefix, "bin", "kewd"), "--check-config", "-c", below],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.assertEqual(result.returncode, 64, result.stdout)
        self.assertIn("its directory /var/log/kew/more does not exist", result.stderr)
        self.assertIn('alert_log = "/var/log/kew/alerts.jsonl"', text)
        self.assertIn('state_directory = "/var/lib/kew"', text)
        elsewhere = self.path("installed.toml")
        with open(elsewhere, "w") as f:
            f.write(text.replace("/var/log/kew/alerts.jsonl", self.path("alerts.jsonl"))
                    .replace("/var/lib/kew", self.path("state")))
        result = subprocess.run([os.path.join(prefix, "bin", "kewd"), "--check-config", "-c", elsewhere],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        # The installed programs read the aerodrome table installed beside them, wherever
        # the tree was staged: the lower limit's, and kew-gen's global scenario's.
        table = os.path.join(prefix, "share", "kew", "aerodromes.csv")
        self.assertTrue(os.path.isfile(table), table)
        # The Prometheus alerting rules, as the package ships them.
        rules = os.path.join(prefix, "share", "kew", "prometheus", "kew-rules.yml")
        self.assertTrue(os.path.isfile(rules), rules)
        self.assertIn(f"aerodromes file: {table} (", result.stdout)
        generated = subprocess.run([os.path.join(prefix, "bin", "kew-gen"), "--scenario", "global", "--aircraft", "3",
                                    "--duration", "8", "--no-header"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True)
        self.assertEqual(generated.returncode, 0, generated.stderr)
        self.assertTrue(generated.stdout.strip(), "kew-gen wrote no record")
        unit = os.path.join(prefix, "lib", "systemd", "system", "kewd.service")
        with open(unit) as f:
            text = f.read()
        for setting in ("Type=notify", "DynamicUser=yes", "StateDirectory=kew", "NoNewPrivileges=yes", "ProtectSystem=strict",
                        "RestrictAddressFamilies=AF_INET AF_INET6 AF_UNIX", "WatchdogSec="):
            self.assertIn(setting, text)
        if shutil.which("systemd-analyze") is None:
            self.skipTest("systemd-analyze is not installed: the unit was NOT verified")
        # The unit names the configured prefix; point it at the staged tree to verify it.
        staged = os.path.join(self.workdir, "kewd.service")
        installed_prefix = text.split("ExecStart=")[1].split("/bin/kewd")[0]
        with open(staged, "w") as f:
            f.write(text.replace(installed_prefix + "/", prefix + "/"))
        verify = subprocess.run(["systemd-analyze", "verify", staged], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        self.assertEqual(verify.returncode, 0, verify.stdout)
        self.assertNotIn("kewd.service", verify.stdout, verify.stdout)


if __name__ == "__main__":
    unittest.main()
