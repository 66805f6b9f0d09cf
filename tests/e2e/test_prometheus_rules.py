"""The shipped alerting rules (deploy/prometheus/kew-rules.yml) name only metrics kewd
exports: every kew_* name in the file (expressions and the annotations that tell the
operator what to check) is a family of a real kewd's /metrics, and every health reason
the rules select is a kew_health sample. kewd runs with each optional family on: an alert
log, and hot standby on a real nats-server (kew_nats_*, kew_standby_*).

Run by ctest with a real `nats-server` (Debian's, with JetStream); by hand:
KEWD=... python3 -m unittest test_prometheus_rules -v
"""

import os
import re
import shutil
import unittest
import urllib.request

from kewd_harness import NATS_SERVER, Kewd, NatsServer, temporary_directory

RULES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "deploy", "prometheus", "kew-rules.yml")

# The notification families exist only while a [[notify]] endpoint is configured, which
# this kewd has none of: the rules may name them without their showing here.
NOTIFY_METRICS = {
    "kew_notify_delivered_total",
    "kew_notify_failures_total",
    "kew_notify_dropped_total",
    "kew_notify_queued",
    "kew_notify_failing",
}

CONFIG = """
[service]
alert_listen = "127.0.0.1:0"
tick_interval_s = 0.5
alert_log = "{workdir}/alerts.jsonl"

[http]
listen = "127.0.0.1:0"

[nats]
url = "{url}"
hot_standby = true
instance = "rules"

[[input]]
name = "feed"
format = "ndjson"
transport = "tcp-server"
address = "127.0.0.1:0"
"""


def rule_metric_names(text):
    """Every kew_* metric name in the rules file; recorded series (kew:…) are not metrics."""
    return set(re.findall(r"(?<![\w:])kew_[a-z0-9_]+", text))


class RulesUseExportedMetrics(unittest.TestCase):
    def setUp(self):
        if shutil.which(NATS_SERVER) is None:
            self.skipTest(f"SKIPPED LOUDLY: {NATS_SERVER} absent (Debian nats-server): the standby families "
                          "cannot be shown, the rules NOT checked")
        self._dir = temporary_directory()
        self.workdir = self._dir.name
        self.nats = NatsServer(self.workdir)
        self.kewd = None

    def tearDown(self):
        if self.kewd:
            self.kewd.kill()
        self.nats.stop()
        self._dir.cleanup()

    def test_rules_name_only_exported_metrics(self):
        with open(RULES) as f:
            rules = f.read()
        self.kewd = Kewd(CONFIG.format(workdir=self.workdir, url=self.nats.url), self.workdir)
        self.kewd.wait_log("active now", timeout_s=30)
        with urllib.request.urlopen(f"http://127.0.0.1:{self.kewd.http_port}/metrics", timeout=10) as response:
            exposition = response.read().decode()
        # A family is exported once its TYPE line is, samples or not (an input's refusals
        # by reason appear with the first refusal).
        families = set(re.findall(r"^# TYPE (\S+) ", exposition, re.M))
        named = rule_metric_names(rules)
        self.assertIn("kew_health", named)
        self.assertIn("kew_standby_active", named)
        self.assertTrue(NOTIFY_METRICS & named, "the rules watch the notifications")
        missing = sorted(named - families - NOTIFY_METRICS)
        self.assertEqual(missing, [], "named by kew-rules.yml, absent from /metrics")

        reasons = set(re.findall(r'^kew_health\{reason="([a-z_]+)"\} [01]$', exposition, re.M))
        self.assertIn("healthy", reasons)
        selected = set(re.findall(r'kew_health\{reason="([a-z_]+)"\}', rules))
        self.assertTrue(selected)
        self.assertEqual(sorted(selected - reasons), [], "health reasons of kew-rules.yml kewd does not report")
        # One reason at a time.
        self.assertEqual(len(re.findall(r'^kew_health\{reason="[a-z_]+"\} 1$', exposition, re.M)), 1, exposition)


if __name__ == "__main__":
    unittest.main()
