"""End-to-end tests of kewd's plant outputs (design §5.4–5.5): CAT004 datagrams decoded
by tshark, and the Modbus TCP alarm map read by real clients (mbpoll and pymodbus).

Run by ctest with the e2e tests; by hand as test_kewd.py says.
"""

import json
import shutil
import socket
import subprocess
import threading
import time
import unittest

from kewd_harness import (MODBUS_CLIENT, SERVICE, TCP_INPUT, E2eCase, Subscriber, count_lines, generate,
                          offline_alerts, pymodbus_python, replay_to, wait_until, write_pcap)


class Cat004(E2eCase):
    def test_cat004_datagrams_decoded_by_tshark(self):
        if shutil.which("tshark") is None:
            self.skipTest("tshark is not installed (apt-get install tshark): CAT004 NOT checked")
        receiver = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        receiver.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
        receiver.bind(("127.0.0.1", 0))
        receiver.settimeout(0.2)
        datagrams = []
        receiving = True

        def receive():
            while receiving:
                try:
                    datagrams.append(receiver.recv(65536))
                except socket.timeout:
                    pass
        thread = threading.Thread(target=receive, daemon=True)
        recording = self.path("stacks.ndjson")
        generate(recording, "airways", aircraft=300, duration=200, seed=4)
        kewd = self.start(SERVICE.format(queue=1000, workdir=self.workdir)
                          + TCP_INPUT.format(name="feed", format="ndjson")
                          + f"""
[cat004]
enabled = true
destination = "127.0.0.1:{receiver.getsockname()[1]}"
sac = 25
sic = 7
""")
        expected = [json.loads(line) for line in offline_alerts(kewd.config_path, recording)]
        records = count_lines(recording)
        thread.start()
        replay_to(f"127.0.0.1:{kewd.input_port('feed')}", recording, "--speed", "100")
        kewd.wait_records(records)
        time.sleep(2.5)  # at least two Alive messages
        self.assertEqual(kewd.terminate(), 0)
        receiving = False
        thread.join()
        receiver.close()
        pcap = self.path("cat004.pcap")
        write_pcap(pcap, datagrams)
        out = subprocess.run(["tshark", "-n", "-r", pcap, "-T", "fields", "-E", "occurrence=a", "-E",
                              "aggregator=;", "-e", "asterix.category", "-e", "asterix.004_010_SAC", "-e",
                              "asterix.004_010_SIC", "-e", "asterix.004_000_VALUE"],
                             stdout=subprocess.PIPE, text=True, check=True).stdout
        types = []
        for row in out.splitlines():
            category, sac, sic, message_types = row.split("\t")
            self.assertEqual(set(category.split(";")), {"4"})
            self.assertEqual({int(v, 0) for v in sac.split(";")}, {25})
            self.assertEqual({int(v, 0) for v in sic.split(";")}, {7})
            types += [int(t) for t in message_types.split(";")]
        self.assertEqual(types.count(7), sum(1 for e in expected if e["state"] != "end"), "an STCA per new/update")
        self.assertEqual(types.count(17), sum(1 for e in expected if e["state"] == "end"), "an End per end")
        self.assertGreaterEqual(types.count(1), 2, "Alive once a second")


SEVERITY_CODE = {"caution": 1, "warning": 2, "loss": 3}




class ModbusMap(E2eCase):
    """kewd's Modbus TCP alarm map read by real clients (design §5.5)."""

    def setUp(self):
        super().setUp()
        self.python = pymodbus_python()
        if self.python is None or shutil.which("mbpoll") is None:
            self.skipTest("python3-pymodbus or mbpoll is not installed: the Modbus map was NOT checked")

    def modbus(self, port, *command):
        result = subprocess.run([self.python, MODBUS_CLIENT, "--port", str(port), *command],
                                stdout=subprocess.PIPE, text=True, timeout=20)
        return json.loads(result.stdout)

    def start_with_modbus(self, extra=""):
        kewd = self.start(SERVICE.format(queue=20000, workdir=self.workdir)
                          + TCP_INPUT.format(name="feed", format="ndjson")
                          + '\n[modbus]\nenabled = true\nlisten = "127.0.0.1:0"\ntable_entries = 16\n' + extra)
        port = int(kewd.wait_log("Modbus TCP alarm map on port").split("on port ")[1].split()[0])
        return kewd, port

    def test_map_matches_the_alert_stream_and_acknowledges(self):
        recording = self.path("airways.ndjson")
        generate(recording, "airways", aircraft=300, duration=150, seed=8)
        kewd, port = self.start_with_modbus()
        # Clients that connect and never send, or send garbage, must not disturb anything.
        silent = socket.create_connection(("127.0.0.1", port))
        noisy = socket.create_connection(("127.0.0.1", port))
        noisy.sendall(bytes(range(256)) * 4)
        replay_to(f"127.0.0.1:{kewd.input_port('feed')}", recording, "--max-speed")
        kewd.wait_records(count_lines(recording))
        watcher = Subscriber(kewd.alert_port)
        wait_until(lambda: watcher.objects("ALERTS"), 10, "the snapshot")
        active = watcher.objects("ALERTS")[0]["alerts"]
        self.assertGreater(len(active), 3, "the scenario must leave alerts active")
        time.sleep(0.5)  # the map is republished within 200 ms of a change

        decoded = self.modbus(port, "read-map", "--entries", "16")
        self.assertTrue(decoded["ok"], decoded)
        m = decoded["map"]
        severities = {a["severity"] for a in active}
        self.assertEqual(m["registers"]["map_version"], 1)
        self.assertEqual(m["registers"]["active_alerts"], len(active))
        self.assertEqual(m["registers"]["highest_severity"], max(SEVERITY_CODE[s] for s in severities))
        self.assertEqual(m["registers"]["unacknowledged"], len(active))
        self.assertEqual(m["registers"]["live_tracks"], kewd.stats()["tracks"])
        self.assertEqual(m["discrete_inputs"]["any_alert"], 1)
        for name in ("caution", "warning", "loss"):
            self.assertEqual(m["discrete_inputs"][name], int(name in severities), name)
        self.assertEqual(m["discrete_inputs"]["feed_healthy"], 1)
        # The table: the most severe alerts, then the soonest, as in the stream's snapshot.
        ranked = sorted(active, key=lambda a: (-SEVERITY_CODE[a["severity"]], a["t_los_s"], a["number"]))
        self.assertEqual(len(m["table"]), min(16, len(active)))
        for row, alert in zip(m["table"], ranked):
            self.assertEqual(row["alert_number"], alert["number"])
            self.assertEqual(row["severity"], SEVERITY_CODE[alert["severity"]])
            self.assertEqual((row["track_a"], row["track_b"]), (alert["a"]["tn"], alert["b"]["tn"]))
            self.assertLessEqual(abs(row["t_los_s"] - alert["t_los_s"]), 0.5)
            self.assertLessEqual(abs(row["cpa_h_10m"] - alert["cpa_h_m"] / 10), 0.5)
            self.assertLessEqual(abs(row["cpa_v_10ft"] - alert["cpa_v_ft"] / 10), 0.5)
            self.assertEqual(row["state"], 1 if alert["state"] == "new" else 2)
            self.assertEqual(row["kind"], 1 if alert.get("kind") == "apw" else 0)

        # A second, different client reads the same discrete inputs.
        polled = subprocess.run(["mbpoll", "-m", "tcp", "-a", "1", "-t", "1", "-r", "1", "-c", "6", "-1",
                                 "-p", str(port), "127.0.0.1"], stdout=subprocess.PIPE, text=True, timeout=20)
        bits = [int(line.split(":")[1]) for line in polled.stdout.splitlines() if line.startswith("[")]
        names = ["any_alert", "caution", "warning", "loss", "feed_healthy", "degraded"]  # PDU addresses 0–5
        self.assertEqual(bits, [m["discrete_inputs"][name] for name in names])

        # The heartbeat moves once a second.
        first = self.modbus(port, "read-input-registers", "5", "1")["values"][0]
        time.sleep(1.3)
        self.assertGreater(self.modbus(port, "read-input-registers", "5", "1")["values"][0], first)

        # Coil 0 acknowledges every active alert: an ACK object in the stream, the count
        # of unacknowledged alerts drops to 0, the coil reads back 0.
        written = self.modbus(port, "write-coil", "0", "1")
        self.assertTrue(written["ok"])
        wait_until(lambda: watcher.objects("ACK"), 10, "the ACK object")
        ack = watcher.objects("ACK")[0]
        self.assertEqual(set(ack["ids"]), {a["id"] for a in active})
        self.assertEqual(ack["by"], "modbus")
        # The ACK names the client: its address and port, as the client sees its socket.
        self.assertTrue(written["client"].startswith("127.0.0.1:"), written)
        self.assertEqual(ack["client"], written["client"])
        wait_until(lambda: self.modbus(port, "read-input-registers", "8", "1")["values"] == [0], 5,
                   "no unacknowledged alert")
        self.assertEqual(self.modbus(port, "read-coils", "0", "1")["values"], [0])
        late = Subscriber(kewd.alert_port)
        wait_until(lambda: late.objects("ALERTS"), 10, "a new snapshot")
        self.assertTrue(all(a["ack"] for a in late.objects("ALERTS")[0]["alerts"]))

        # Refusals with the right exception codes.
        self.assertEqual(self.modbus(port, "write-coil", "1", "1")["exception_code"], 2)   # ILLEGAL DATA ADDRESS
        self.assertEqual(self.modbus(port, "write-register", "0", "7")["exception_code"], 2)
        self.assertEqual(self.modbus(port, "read-input-registers", str(16 + 16 * 8), "1")["exception_code"], 2)
        self.assertEqual(self.modbus(port, "read-input-registers", "0", "200")["exception_code"], 3)  # > 125

        # The silent and noisy clients changed nothing; the pipeline still runs.
        self.assertTrue(kewd.running())
        stats = kewd.stats()
        self.assertEqual(stats["modbus"]["acknowledgements"], 1)
        silent.close()
        noisy.close()
        self.assertEqual(kewd.terminate(), 0)
        with open(self.path("alerts.jsonl")) as f:
            logged = [json.loads(line) for line in f if '"class":"ACK"' in line]
        self.assertEqual(len(logged), 1, "the acknowledgement is in the alert log")
        self.assertEqual(logged[0]["client"], written["client"])

    def test_read_only_map_refuses_writes(self):
        kewd, port = self.start_with_modbus("read_only = true\n")
        self.assertEqual(self.modbus(port, "write-coil", "0", "1")["exception_code"], 1)  # ILLEGAL FUNCTION
        self.assertEqual(self.modbus(port, "write-register", "0", "1")["exception_code"], 1)
        self.assertTrue(self.modbus(port, "read-discrete-inputs", "0", "6")["ok"])
        self.assertEqual(kewd.stats()["modbus"]["acknowledgements"], 0)
        self.assertEqual(kewd.terminate(), 0)


    def test_acknowledge_from_refuses_other_clients(self):
        kewd, port = self.start_with_modbus('acknowledge_from = ["192.0.2.7"]\n')
        self.assertEqual(self.modbus(port, "write-coil", "0", "1")["exception_code"], 1)  # ILLEGAL FUNCTION
        self.assertTrue(self.modbus(port, "read-discrete-inputs", "0", "6")["ok"])
        modbus = kewd.stats()["modbus"]
        self.assertEqual(modbus["acknowledgements"], 0)
        self.assertEqual(modbus["rejected"]["modbus_write_not_permitted"], 1)
        kewd.wait_log("modbus: refused a request (modbus_write_not_permitted): a write from 127.0.0.1:")
        self.assertEqual(kewd.terminate(), 0)


if __name__ == "__main__":
    unittest.main()
